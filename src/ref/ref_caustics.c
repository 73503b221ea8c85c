/* ref_caustics.c — the reference of the caustics stage (issue 27): the
 * receiver plane's irradiance traced from the light in double precision:
 * shadow rays for the direct light, and photons refracted through each glass
 * object (the stage's optics: Schlick and Snell in and out, tint,
 * Beer-Lambert) splatted onto the plane's texels with the stage's tent, flux-correct. */
#include "ref/ref_scene.h"
#include "core/ctx.h"
#include "core/optics.h"

#include <math.h>
#include <string.h>

typedef struct plane_map {
    double cx, cz, h, ext, texel;
    int size;
    double *acc; /* 3 per texel */
} plane_map;

/* Adds flux (irradiance per texel area) about plane point (x, z) as the
 * stage splats it: a tent of half-width 2 texels along each axis, weights
 * (1 - |dx| / 2) / 2 at the texel centres within 2 texels (they sum to 1). */
static void splat(plane_map *m, double x, double z, const double e[3])
{
    double tx = (x - (m->cx - m->ext)) / m->texel - 0.5, tz = (z - (m->cz - m->ext)) / m->texel - 0.5;
    int ix, iz, c;
    if (!(tx > -2.0 && tz > -2.0 && tx < m->size + 1.0 && tz < m->size + 1.0)) return;
    for (iz = (int)floor(tz) - 1; iz <= (int)floor(tz) + 2; iz++)
        for (ix = (int)floor(tx) - 1; ix <= (int)floor(tx) + 2; ix++) {
            double wx = 1.0 - fabs(tx - ix) / 2.0, wz = 1.0 - fabs(tz - iz) / 2.0, w;
            if (wx <= 0.0 || wz <= 0.0 || ix < 0 || iz < 0 || ix >= m->size || iz >= m->size) continue;
            w = wx * wz / 4.0;
            for (c = 0; c < 3; c++) m->acc[3 * ((size_t)iz * (size_t)m->size + (size_t)ix) + c] += w * e[c];
        }
}

static void basis(const double d[3], double u[3], double v[3])
{
    double a[3] = {0.0, 1.0, 0.0};
    if (fabs(d[1]) > 0.99) a[0] = 1.0, a[1] = 0.0;
    u[0] = a[1] * d[2] - a[2] * d[1], u[1] = a[2] * d[0] - a[0] * d[2], u[2] = a[0] * d[1] - a[1] * d[0];
    snell__ref_normalize3(u);
    v[0] = d[1] * u[2] - d[2] * u[1], v[1] = d[2] * u[0] - d[0] * u[2], v[2] = d[0] * u[1] - d[1] * u[0];
}

/* One photon along d from o through glass object g; adds it to m if it lands. */
static void photon(const snell_ref *ref, int g, const double o[3], const double d[3], const double flux[3],
                   plane_map *m)
{
    const ref_glass *gl = &ref->glass[g];
    ref_view air = {-1, REF_SEE_ALL, -1}, in = {g, REF_SEE_ALL, -1};
    ref_surf s1, s2, s3;
    double n[3], t[3], t2[3], ci, f1, f2, len, e[3], p[3];
    int k;
    if (!snell__ref_hit(ref, o, d, SNELL__BVH_NONE, &air, &s1) || s1.object != g) return;
    memcpy(n, s1.n, sizeof n);
    if (snell__ref_dot3(n, d) > 0.0) n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
    ci = -snell__ref_dot3(n, d);
    f1 = snell_optd_fresnel_schlick(ci, 1.0, gl->ior);
    if (!snell_optd_refract(d, n, 1.0 / gl->ior, t)) return;
    snell__ref_normalize3(t);
    if (!snell__ref_hit(ref, s1.p, t, s1.prim, &in, &s2) || s2.object != g) return;
    memcpy(n, s2.n, sizeof n);
    if (snell__ref_dot3(n, t) < 0.0) n[0] = -n[0], n[1] = -n[1], n[2] = -n[2]; /* outward, along the ray */
    f2 = snell_optd_fresnel_schlick(snell__ref_dot3(n, t), gl->ior, 1.0);
    n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
    if (!snell_optd_refract(t, n, gl->ior, t2)) return; /* TIR: dropped, as the stage drops it */
    snell__ref_normalize3(t2);
    if (!(t2[1] < 0.0)) return;
    len = s2.t;
    {
        double sp = (m->h - s2.p[1]) / t2[1];
        if (sp < 0.0) return;
        /* anything between the exit and the plane stops it */
        if (snell__ref_hit(ref, s2.p, t2, s2.prim, &air, &s3) && s3.t < sp) return;
        for (k = 0; k < 3; k++) p[k] = s2.p[k] + t2[k] * sp;
    }
    for (k = 0; k < 3; k++) e[k] = flux[k] * gl->tint[k] * (1.0 - f1) * (1.0 - f2) * exp(-gl->sigma[k] * len);
    splat(m, p[0], p[2], e);
}

snell_status snell_ref_receiver_render(const snell_ref *ref, const snell_light *light, const snell_receiver *rc,
                                       int photons, int samples, float *rgb, float *caustic)
{
    plane_map m;
    double d[3], u[3], v[3], col[3], pos[3], cos_cone, len;
    int spot = light->type == SNELL_LIGHT_SPOT;
    int size, i, j, k, g, a, b;
    size_t n;
    if (!ref || !light || !rc || !rgb) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ref_receiver_render: NULL argument");
    if (light->type != SNELL_LIGHT_DIRECTIONAL && light->type != SNELL_LIGHT_SPOT)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_receiver_render: no light");
    if (!(rc->extent > 0.0f) || !isfinite(rc->extent) || (rc->map_size != 0 && (rc->map_size < 1 || rc->map_size > 4096)))
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_receiver_render: receiver extent %g > 0, "
                           "map_size %d 0..4096", rc->extent, rc->map_size);
    if (photons < 1 || photons > 4096 || samples < 1 || samples > 16)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_receiver_render: photons %d (1..4096), "
                           "samples %d (1..16)", photons, samples);
    for (k = 0; k < 3; k++) d[k] = light->direction[k];
    len = sqrt(snell__ref_dot3(d, d));
    if (!(len > 0.0) || !isfinite(len))
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_receiver_render: light.direction zero or not finite");
    for (k = 0; k < 3; k++) d[k] /= len, pos[k] = light->position[k];
    cos_cone = cos(light->spot_angle > 0.0f ? (double)light->spot_angle : 0.5);
    for (k = 0; k < 3; k++)
        col[k] = light->color[0] == 0.0f && light->color[1] == 0.0f && light->color[2] == 0.0f ? 1.0 : light->color[k];
    size = rc->map_size ? rc->map_size : 256;
    n = (size_t)size * (size_t)size;
    m.cx = rc->center[0], m.cz = rc->center[1], m.h = rc->height, m.ext = rc->extent;
    m.size = size, m.texel = 2.0 * rc->extent / size;
    m.acc = (double *)snell__calloc(&ref->alloc, n, 3 * sizeof(double));
    if (!m.acc) return snell__fail(ref->ctx, SNELL_E_NOMEM, "snell_ref_receiver_render: out of memory");
    /* light through glass */
    for (g = 0; g < ref->glass_count; g++) {
        const ref_glass *gl = &ref->glass[g];
        double r = gl->bs_r, cell = 2.0 * r / photons, flux[3], w[3], tan_half = 0.0, dist = 0.0;
        if (gl->thin) continue; /* the stage passes thin walls */
        if (spot) {
            /* a square of directions from the light just holding the bounding
             * sphere; a photon's cell is cell^2 on the plane at distance 1 */
            for (k = 0; k < 3; k++) w[k] = gl->bs_c[k] - pos[k];
            dist = sqrt(snell__ref_dot3(w, w));
            if (dist <= r * 1.001) continue; /* the light inside: as the stage, no photons */
            for (k = 0; k < 3; k++) w[k] /= dist;
            tan_half = r / sqrt(dist * dist - r * r);
            cell = 2.0 * tan_half / photons;
            basis(w, u, v);
        } else {
            basis(d, u, v);
        }
        for (k = 0; k < 3; k++) flux[k] = col[k] * cell * cell / (m.texel * m.texel);
        for (j = 0; j < photons; j++)
            for (i = 0; i < photons; i++) {
                double o[3], dir[3], f[3];
                if (spot) {
                    double x = -tan_half + (i + 0.5) * cell, y = -tan_half + (j + 0.5) * cell, c;
                    for (k = 0; k < 3; k++) dir[k] = w[k] + u[k] * x + v[k] * y;
                    snell__ref_normalize3(dir);
                    c = 1.0 / sqrt(1.0 + x * x + y * y); /* its solid angle: cell^2 cos^3 */
                    if (snell__ref_dot3(dir, d) < cos_cone) continue;
                    for (k = 0; k < 3; k++) o[k] = pos[k], f[k] = flux[k] * c * c * c;
                } else {
                    double x = -r + (i + 0.5) * cell, y = -r + (j + 0.5) * cell;
                    if (x * x + y * y > r * r) continue;
                    for (k = 0; k < 3; k++) o[k] = gl->bs_c[k] + u[k] * x + v[k] * y - d[k] * (r + 1.0);
                    memcpy(dir, d, sizeof dir);
                    memcpy(f, flux, sizeof f);
                }
                photon(ref, g, o, dir, f, &m);
            }
    }
    if (caustic)
        for (i = 0; i < (int)(3 * n); i++) caustic[i] = (float)m.acc[i];
    /* direct light */
    for (j = 0; j < size; j++)
        for (i = 0; i < size; i++) {
            double e = 0.0;
            ref_view air = {-1, REF_SEE_ALL, -1};
            ref_surf s;
            for (b = 0; b < samples; b++)
                for (a = 0; a < samples; a++) {
                    double q[3] = {m.cx - m.ext + (i + (a + 0.5) / samples) * m.texel, m.h,
                                   m.cz - m.ext + (j + (b + 0.5) / samples) * m.texel};
                    double back[3] = {-d[0], -d[1], -d[2]}, ek = -d[1] > 0.0 ? -d[1] : 0.0, far_ = HUGE_VAL;
                    if (spot) { /* towards the light, up to it; inside its cone, cosine / distance^2 */
                        double d2;
                        for (k = 0; k < 3; k++) back[k] = pos[k] - q[k];
                        d2 = snell__ref_dot3(back, back);
                        far_ = sqrt(d2);
                        snell__ref_normalize3(back);
                        ek = -snell__ref_dot3(back, d) >= cos_cone && back[1] > 0.0 ? back[1] / d2 : 0.0;
                    }
                    if (ek > 0.0 && !(snell__ref_hit(ref, q, back, SNELL__BVH_NONE, &air, &s) && s.t < far_)) e += ek;
                }
            for (k = 0; k < 3; k++) {
                size_t t = 3 * ((size_t)j * (size_t)size + (size_t)i) + (size_t)k;
                rgb[t] = (float)(m.acc[t] + col[k] * e / (double)(samples * samples));
            }
        }
    snell__free(&ref->alloc, m.acc);
    return SNELL_OK;
}
