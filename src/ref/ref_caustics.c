/* SPDX-License-Identifier: MIT */
/* ref_caustics.c — the reference of the caustics stage: the receiver plane's
 * irradiance traced from the light in double precision: shadow rays for the
 * direct light, and photons refracted through each glass object along their
 * whole path by the tracer's BVH (through()), on through up to
 * SNELL__CAUSTICS_CHAIN objects (chain()), splatted with the stage's tent,
 * flux-correct. The optics and how the GPU matches them: docs/ARCHITECTURE.md,
 * "Design notes by file". */
#include "frame/lighting.h"
#include "ref/ref_trace.h"
#include "core/ctx.h"
#include "core/optics.h"
#include "frame/frame.h"

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

/* The surfaces a photon's path through glass object g may meet: the exact
 * method's interface cap (its material.exact.max_interfaces: the MATCHED
 * model's), or that parameter's default in a build without the method. */
static int interfaces_of(const ref_glass *gl)
{
    return gl->res.material.exact.max_interfaces > 0 ? gl->res.material.exact.max_interfaces : 8;
}

/* One photon along d from o through glass object g (the stage's optics): in
 * where the light first meets g (Schlick, Snell, the tint), inside
 * (snell__ref_inside: the next surface ahead, total internal reflection
 * followed, Beer-Lambert over the way) and out (Schlick, Snell), and in
 * again wherever its way out meets g once more (a torus's hole, a goblet's
 * bowl), the entry counted as an interface too, up to g's cap
 * (interfaces_of): there it leaves through the next surface in its
 * direction, as the MATCHED model's rays do, and sees g no more. A thin
 * wall bends nothing: every surface of g on the photon's line, up to the
 * cap, is a slab it crosses straight on. *prim: the triangle o lies on (or
 * SNELL__BVH_NONE), from: its object, neither seen by the way in. 1 if it
 * leaves, at x along t2 (prim: the triangle it leaves from), carrying e. */
static int through(const snell_ref *ref, int g, int from, const double o[3], const double d[3], const double flux[3],
                   double x[3], double t2[3], uint32_t *prim, double e[3])
{
    const ref_glass *gl = &ref->glass[g];
    const int max_if = interfaces_of(gl);
    ref_surf s;
    double pos[3], dir[3], n[3], t[3], len, cos_out;
    int k, depth = 0, end;
    memcpy(pos, o, sizeof pos);
    memcpy(dir, d, sizeof dir);
    for (k = 0; k < 3; k++) e[k] = flux[k];
    for (;;) {
        ref_view air = {-1, depth < max_if ? REF_SEE_ALL : REF_SEE_NONE, depth == 0 ? from : -1};
        double ci;
        if (!snell__ref_hit(ref, pos, dir, *prim, &air, &s) || s.object != g) {
            if (depth == 0) return 0; /* the light meets something else first */
            break;                    /* out for good: the caller looks at what it meets */
        }
        memcpy(n, s.n, sizeof n);
        if (snell__ref_dot3(n, dir) > 0.0) n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
        ci = -snell__ref_dot3(n, dir);
        if (gl->thin) { /* a wall: the slab (the kernels' thin wall), straight on, the tint at each */
            double rs[3], ts[3];
            snell_optd_thin_slab(ci, gl->ior, gl->sigma, gl->thickness, rs, ts);
            for (k = 0; k < 3; k++) e[k] *= gl->tint[k] * ts[k];
            depth++;
            memcpy(pos, s.p, sizeof pos);
            *prim = s.prim;
            continue;
        }
        if (!snell_optd_refract(dir, n, 1.0 / gl->ior, t)) return 0;
        snell__ref_normalize3(t);
        for (k = 0; k < 3; k++) e[k] *= gl->tint[k] * (1.0 - snell_optd_fresnel_schlick(ci, 1.0, gl->ior));
        depth++;
        memcpy(pos, s.p, sizeof pos);
        memcpy(dir, t, sizeof dir);
        *prim = s.prim;
        len = 0.0;
        end = snell__ref_inside(ref, g, gl->ior, NULL, max_if, pos, dir, prim, &depth, &len, &s, &cos_out, NULL, NULL);
        if (end == SNELL__REF_OPAQUE) return 0; /* an opaque object in the glass stops it */
        for (k = 0; k < 3; k++) {
            e[k] *= exp(-gl->sigma[k] * len);
            if (end == SNELL__REF_OUT) e[k] *= 1.0 - snell_optd_fresnel_schlick(cos_out, gl->ior, 1.0);
        }
    }
    memcpy(x, pos, 3 * sizeof(double));
    memcpy(t2, dir, 3 * sizeof(double));
    return 1;
}

/* Light through glass objects in sequence: a photon of g's grid counts only
 * if the light meets g first (through; else that light is another object's
 * grid's), and leaving g it goes on through the next glass object it meets,
 * by that object's optics (through from the surface it left), and so on up
 * to SNELL__CAUSTICS_CHAIN objects: each ray of light counted once,
 * refracted by every glass it crosses (the stage's chain path,
 * render/caustics_photons.c). A photon that would meet one more is the caller's to
 * stop (the landing's cast meets it). 1 if it leaves the last, *last, at x
 * along t2 (prim: the triangle it leaves from), carrying e. */
static int chain(const snell_ref *ref, int g, const double o[3], const double d[3], const double flux[3],
                 double x[3], double t2[3], uint32_t *prim, double e[3], int *last)
{
    double p[3], dir[3], f[3];
    int n;
    *prim = SNELL__BVH_NONE;
    *last = g;
    if (!through(ref, g, -1, o, d, flux, x, t2, prim, e)) return 0;
    for (n = 1; n < SNELL__CAUSTICS_CHAIN; n++) {
        ref_view air = {-1, REF_SEE_ALL, *last}; /* the last is done with it (through) */
        ref_surf s;
        if (!snell__ref_hit(ref, x, t2, *prim, &air, &s) || s.object < 0) break; /* nothing, or opaque: it lands */
        memcpy(p, x, sizeof p), memcpy(dir, t2, sizeof dir), memcpy(f, e, sizeof f);
        if (!through(ref, s.object, *last, p, dir, f, x, t2, prim, e)) return 0;
        *last = s.object;
    }
    return 1;
}

/* How far back from g's bounding sphere's centre along the directional
 * light d its photons start: before every glass object (so that the light
 * meeting another one first is seen), 1 past g's sphere alone. */
static double start_back(const snell_ref *ref, int g, const double d[3])
{
    double back = ref->glass[g].bs_r;
    int h, k;
    for (h = 0; h < ref->glass_count; h++) {
        double w = ref->glass[h].bs_r;
        for (k = 0; k < 3; k++) w -= (ref->glass[h].bs_c[k] - ref->glass[g].bs_c[k]) * d[k];
        back = fmax(back, w);
    }
    return back + 1.0;
}

/* One photon along d from o of glass object g's grid; adds it to m if it
 * lands (an opaque object on its way stops it, as one more glass object
 * past the chain's cap does). */
static void photon(const snell_ref *ref, int g, const double o[3], const double d[3], const double flux[3],
                   plane_map *m)
{
    ref_surf s3;
    double x[3], t2[3], e[3], p[3], sp;
    uint32_t prim;
    int k, last;
    if (!chain(ref, g, o, d, flux, x, t2, &prim, e, &last) || !(t2[1] < 0.0)) return;
    sp = (m->h - x[1]) / t2[1];
    if (sp < 0.0) return;
    {
        /* anything between the exit and the plane stops it */
        ref_view air = {-1, REF_SEE_ALL, last};
        if (snell__ref_hit(ref, x, t2, prim, &air, &s3) && s3.t < sp) return;
    }
    for (k = 0; k < 3; k++) p[k] = x[k] + t2[k] * sp;
    splat(m, p[0], p[2], e);
}

snell_status snell_ref_receiver_render(const snell_ref *ref, const snell_light *light, const snell_receiver *rc,
                                       int photons, int samples, float *rgb, float *caustic)
{
    plane_map m;
    snell_light lt;
    snell_receiver rr;
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
    snell__light_defaults(light, &lt);
    snell__receiver_defaults(rc, &rr);
    light = &lt, rc = &rr;
    for (k = 0; k < 3; k++) d[k] = light->direction[k];
    len = sqrt(snell__ref_dot3(d, d));
    if (!(len > 0.0) || !isfinite(len))
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_receiver_render: light.direction zero or not finite");
    for (k = 0; k < 3; k++) d[k] /= len, pos[k] = light->position[k];
    cos_cone = cos((double)light->spot_angle);
    for (k = 0; k < 3; k++) col[k] = light->color[k];
    size = rc->map_size;
    n = (size_t)size * (size_t)size;
    m.cx = rc->center[0], m.cz = rc->center[1], m.h = rc->height, m.ext = rc->extent;
    m.size = size, m.texel = 2.0 * rc->extent / size;
    m.acc = (double *)snell__calloc(&ref->alloc, n, 3 * sizeof(double));
    if (!m.acc) return snell__fail(ref->ctx, SNELL_E_NOMEM, "snell_ref_receiver_render: out of memory");
    /* light through glass */
    for (g = 0; g < ref->glass_count; g++) {
        const ref_glass *gl = &ref->glass[g];
        double r = gl->bs_r, cell = 2.0 * r / photons, flux[3], w[3], tan_half = 0.0, dist = 0.0;
        double back = start_back(ref, g, d);
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
                    for (k = 0; k < 3; k++) o[k] = gl->bs_c[k] + u[k] * x + v[k] * y - d[k] * back;
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

/* ------------------------------------------------ the opaque objects lit */
/* The caustics stage's light frame (render/caustics_maps.c make_frame), in
 * double: directional, an orthographic view along d (x = s.(p - c), y =
 * u.(p - c), depth = d.(p - c)); spot, a perspective view from the light
 * looking straight down (x/depth, y/depth, depth = light y - p.y); its
 * window holds the receiver square's corners and the opaque objects'
 * bounding spheres; size x size texels, twice the receiver's map_size (at
 * most 2048). acc: the light through glass on the opaque objects the light
 * sees first, flux per texel area facing the light; depth: that surface's
 * depth per texel centre (HUGE_VAL: none). */
struct ref_lit {
    int spot, size;
    double d[3], pos[3], col[3], cos_cone;
    double c[3], s[3], u[3], f[3];  /* the frame's origin and axes */
    double lo[2], hi[2], texel, area;
    int plane;
    double plane_h;
    double *acc, *depth;
};

static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
}

/* p in the frame: x, y (spot: over depth) and depth; 0 if behind a spot light. */
static int frame_xy(const struct ref_lit *L, const double p[3], double *x, double *y, double *z)
{
    double q[3] = {p[0] - L->c[0], p[1] - L->c[1], p[2] - L->c[2]};
    *x = snell__ref_dot3(L->s, q), *y = snell__ref_dot3(L->u, q), *z = snell__ref_dot3(L->f, q);
    if (!L->spot) return 1;
    if (!(*z > 1e-9)) return 0;
    *x /= *z, *y /= *z;
    return 1;
}

static void grow2(double lo[2], double hi[2], double x, double y)
{
    lo[0] = fmin(lo[0], x), hi[0] = fmax(hi[0], x), lo[1] = fmin(lo[1], y), hi[1] = fmax(hi[1], y);
}

static void lit_frame(const snell_ref *ref, const snell_receiver *rc, struct ref_lit *L)
{
    double up[3] = {0.0, 0.0, 1.0};
    int i, k, plane = rc->extent > 0.0f;
    L->lo[0] = L->lo[1] = 1e300, L->hi[0] = L->hi[1] = -1e300;
    if (L->spot) {
        memcpy(L->c, L->pos, sizeof L->c);
        L->f[0] = 0.0, L->f[1] = -1.0, L->f[2] = 0.0;
    } else {
        if (plane) L->c[0] = rc->center[0], L->c[1] = rc->height, L->c[2] = rc->center[1];
        else
            for (k = 0; k < 3; k++) {
                L->c[k] = 0.0;
                for (i = 0; i < ref->opaque_count; i++) L->c[k] += ref->opaque_bs[i][k] / ref->opaque_count;
            }
        memcpy(L->f, L->d, sizeof L->f);
        up[0] = 0.0, up[1] = 1.0, up[2] = 0.0;
        if (fabs(L->d[1]) > 0.99) up[0] = 1.0, up[1] = 0.0;
    }
    cross3(L->f, up, L->s);
    snell__ref_normalize3(L->s);
    cross3(L->s, L->f, L->u);
    for (k = 0; k < 4 && plane; k++) {
        double p[3] = {rc->center[0] + ((k & 1) ? rc->extent : -rc->extent), rc->height,
                       rc->center[1] + ((k & 2) ? rc->extent : -rc->extent)}, x, y, z;
        double q[3] = {p[0] - L->c[0], p[1] - L->c[1], p[2] - L->c[2]};
        x = snell__ref_dot3(L->s, q), y = snell__ref_dot3(L->u, q), z = snell__ref_dot3(L->f, q);
        if (L->spot) z = z > 1e-3 ? z : 1e-3, x /= z, y /= z;
        grow2(L->lo, L->hi, x, y);
    }
    for (i = 0; i < ref->opaque_count; i++) {
        const double *b = ref->opaque_bs[i];
        double q[3] = {b[0] - L->c[0], b[1] - L->c[1], b[2] - L->c[2]}, x, y, z;
        x = snell__ref_dot3(L->s, q), y = snell__ref_dot3(L->u, q), z = snell__ref_dot3(L->f, q);
        if (!L->spot) {
            grow2(L->lo, L->hi, x - b[3], y - b[3]);
            grow2(L->lo, L->hi, x + b[3], y + b[3]);
        } else {
            for (k = 0; k < 8; k++) {
                double xk = x + ((k & 1) ? b[3] : -b[3]), yk = y + ((k & 2) ? b[3] : -b[3]);
                double zk = z + ((k & 4) ? b[3] : -b[3]);
                if (zk > 1e-3) grow2(L->lo, L->hi, xk / zk, yk / zk);
                else grow2(L->lo, L->hi, xk < 0.0 ? -1e3 : 1e3, yk < 0.0 ? -1e3 : 1e3);
            }
        }
    }
    if (L->spot)
        for (i = 0; i < 2; i++) L->lo[i] = fmax(L->lo[i], -12.0), L->hi[i] = fmin(L->hi[i], 12.0);
    L->size = rc->map_size ? rc->map_size : SNELL_DEFAULT_RECEIVER_MAP;
    L->size = L->size * 2 > 2048 ? 2048 : L->size * 2;
    L->texel = fmax(L->hi[0] - L->lo[0], L->hi[1] - L->lo[1]) / L->size;
    L->area = (L->hi[0] - L->lo[0]) * (L->hi[1] - L->lo[1]) / ((double)L->size * L->size);
    L->plane = plane, L->plane_h = rc->height;
}

/* The tent splat of the stage (caustics_splat.frag) at frame texel
 * coordinates (tx, ty) (texel centres at integers). */
static void splat_frame(struct ref_lit *L, double tx, double ty, const double e[3])
{
    int ix, iy, c, n = L->size;
    if (!(tx > -2.0 && ty > -2.0 && tx < n + 1.0 && ty < n + 1.0)) return;
    for (iy = (int)floor(ty) - 1; iy <= (int)floor(ty) + 2; iy++)
        for (ix = (int)floor(tx) - 1; ix <= (int)floor(tx) + 2; ix++) {
            double wx = 1.0 - fabs(tx - ix) / 2.0, wy = 1.0 - fabs(ty - iy) / 2.0, w;
            if (wx <= 0.0 || wy <= 0.0 || ix < 0 || iy < 0 || ix >= n || iy >= n) continue;
            w = wx * wy / 4.0;
            for (c = 0; c < 3; c++) L->acc[3 * ((size_t)iy * (size_t)n + (size_t)ix) + c] += w * e[c];
        }
}

/* The ray from the light through frame point (x, y): origin and unit direction. */
static void frame_ray(const struct ref_lit *L, double x, double y, double o[3], double dir[3])
{
    int k;
    for (k = 0; k < 3; k++) {
        if (L->spot) o[k] = L->pos[k], dir[k] = L->f[k] + L->s[k] * x + L->u[k] * y;
        else o[k] = L->c[k] + L->s[k] * x + L->u[k] * y - L->f[k] * 1e4, dir[k] = L->f[k];
    }
    snell__ref_normalize3(dir);
}

/* The nearest opaque surface the light sees at p's frame point: its depth (HUGE_VAL: none). */
static double first_opaque(const snell_ref *ref, const struct ref_lit *L, double x, double y)
{
    ref_view opq = {-1, REF_SEE_NONE, -1};
    ref_surf s;
    double o[3], dir[3], px, py, z;
    frame_ray(L, x, y, o, dir);
    if (!snell__ref_hit(ref, o, dir, SNELL__BVH_NONE, &opq, &s)) return HUGE_VAL;
    frame_xy(L, s.p, &px, &py, &z);
    return z;
}

/* A photon that left glass g, the last of its chain, at x along t2
 * carrying e: where it first meets an opaque object (before the plane; one
 * more glass object, past the chain's cap, stops it; g is done with it), if
 * the light sees that surface there, its flux per texel area facing the
 * light is splatted. */
static void land_opaque(const snell_ref *ref, struct ref_lit *L, int g, const double x[3], const double t2[3],
                        uint32_t prim, const double e[3])
{
    ref_view air = {-1, REF_SEE_ALL, g}; /* g is done with it (through) */
    ref_surf s;
    double fx, fy, fz, w[3], zs;
    int k;
    if (!snell__ref_hit(ref, x, t2, prim, &air, &s) || s.object >= 0) return; /* nothing, or glass past the cap */
    if (L->plane && t2[1] < 0.0 && (L->plane_h - x[1]) / t2[1] >= 0.0 && (L->plane_h - x[1]) / t2[1] < s.t) return;
    if (!frame_xy(L, s.p, &fx, &fy, &fz)) return;
    zs = first_opaque(ref, L, fx, fy);
    if (!(fabs(zs - fz) <= 1e-6 * (1.0 + fabs(fz)) + 1e2 * ref->eps)) return; /* a face the light does not see */
    for (k = 0; k < 3; k++) w[k] = e[k];
    if (L->spot) { /* the texel's solid angle: cos^3 off the frame's axis */
        double v[3] = {s.p[0] - L->pos[0], s.p[1] - L->pos[1], s.p[2] - L->pos[2]}, cl;
        cl = (L->pos[1] - s.p[1]) / sqrt(snell__ref_dot3(v, v));
        for (k = 0; k < 3; k++) w[k] /= cl * cl * cl;
    }
    splat_frame(L, (fx - L->lo[0]) / (L->hi[0] - L->lo[0]) * L->size - 0.5,
                (fy - L->lo[1]) / (L->hi[1] - L->lo[1]) * L->size - 0.5, w);
}

void snell__ref_lit_free(snell_ref *r)
{
    if (!r->lit) return;
    snell__free(&r->alloc, r->lit->acc);
    snell__free(&r->alloc, r->lit->depth);
    snell__free(&r->alloc, r->lit);
    r->lit = NULL;
}

snell_status snell_ref_set_light(snell_ref *ref, const snell_light *light, const snell_receiver *rc, int photons)
{
    struct ref_lit *L;
    snell_light lt;
    double len;
    int g, i, j, k;
    size_t n;
    if (!ref) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ref_set_light: NULL reference");
    if (!light || light->type == SNELL_LIGHT_NONE) {
        snell__ref_lit_free(ref);
        return SNELL_OK;
    }
    if (light->type != SNELL_LIGHT_DIRECTIONAL && light->type != SNELL_LIGHT_SPOT)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_set_light: light.type %d", (int)light->type);
    if (!rc || !isfinite(rc->extent) || rc->extent < 0.0f || rc->map_size < 0 || rc->map_size > 2048 ||
        photons < 1 || photons > 4096)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_set_light: receiver extent >= 0, map_size "
                           "0..2048, photons %d 1..4096", photons);
    if (rc->extent == 0.0f && ref->opaque_count == 0)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_set_light: neither a receiver nor opaque objects");
    len = sqrt((double)light->direction[0] * light->direction[0] + (double)light->direction[1] * light->direction[1] +
               (double)light->direction[2] * light->direction[2]);
    if (!(len > 0.0) || !isfinite(len))
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_set_light: light.direction zero or not finite");
    snell__ref_lit_free(ref);
    L = (struct ref_lit *)snell__calloc(&ref->alloc, 1, sizeof *L);
    if (!L) return snell__fail(ref->ctx, SNELL_E_NOMEM, "snell_ref_set_light: out of memory");
    ref->lit = L;
    snell__light_defaults(light, &lt);
    L->spot = light->type == SNELL_LIGHT_SPOT;
    for (k = 0; k < 3; k++) {
        L->d[k] = light->direction[k] / len, L->pos[k] = light->position[k];
        L->col[k] = lt.color[k];
    }
    L->cos_cone = cos((double)lt.spot_angle);
    lit_frame(ref, rc, L);
    n = (size_t)L->size * (size_t)L->size;
    L->acc = (double *)snell__calloc(&ref->alloc, 3 * n, sizeof(double));
    L->depth = (double *)snell__calloc(&ref->alloc, n, sizeof(double));
    if (!L->acc || !L->depth) {
        snell__ref_lit_free(ref);
        return snell__fail(ref->ctx, SNELL_E_NOMEM, "snell_ref_set_light: out of memory");
    }
    for (j = 0; j < L->size; j++)
        for (i = 0; i < L->size; i++)
            L->depth[(size_t)j * L->size + i] = first_opaque(ref, L, L->lo[0] + (i + 0.5) * (L->hi[0] - L->lo[0]) / L->size,
                                                             L->lo[1] + (j + 0.5) * (L->hi[1] - L->lo[1]) / L->size);
    /* photons: the grid of snell_ref_receiver_render */
    for (g = 0; g < ref->glass_count; g++) {
        const ref_glass *gl = &ref->glass[g];
        double r = gl->bs_r, cell = 2.0 * r / photons, flux[3], w[3], u[3], v[3], tan_half = 0.0, dist;
        double back = start_back(ref, g, L->d);
        if (L->spot) {
            for (k = 0; k < 3; k++) w[k] = gl->bs_c[k] - L->pos[k];
            dist = sqrt(snell__ref_dot3(w, w));
            if (dist <= r * 1.001) continue;
            for (k = 0; k < 3; k++) w[k] /= dist;
            tan_half = r / sqrt(dist * dist - r * r);
            cell = 2.0 * tan_half / photons;
            basis(w, u, v);
        } else {
            basis(L->d, u, v);
        }
        for (k = 0; k < 3; k++) flux[k] = L->col[k] * cell * cell / L->area;
        for (j = 0; j < photons; j++)
            for (i = 0; i < photons; i++) {
                double o[3], dir[3], f[3], x[3], t2[3], e[3];
                uint32_t prim;
                int last;
                if (L->spot) {
                    double px = -tan_half + (i + 0.5) * cell, py = -tan_half + (j + 0.5) * cell, c;
                    for (k = 0; k < 3; k++) dir[k] = w[k] + u[k] * px + v[k] * py;
                    snell__ref_normalize3(dir);
                    c = 1.0 / sqrt(1.0 + px * px + py * py);
                    if (snell__ref_dot3(dir, L->d) < L->cos_cone) continue;
                    for (k = 0; k < 3; k++) o[k] = L->pos[k], f[k] = flux[k] * c * c * c;
                } else {
                    double px = -r + (i + 0.5) * cell, py = -r + (j + 0.5) * cell;
                    if (px * px + py * py > r * r) continue;
                    for (k = 0; k < 3; k++) o[k] = gl->bs_c[k] + u[k] * px + v[k] * py - L->d[k] * back;
                    memcpy(dir, L->d, sizeof dir);
                    memcpy(f, flux, sizeof f);
                }
                if (chain(ref, g, o, dir, f, x, t2, &prim, e, &last)) land_opaque(ref, L, last, x, t2, prim, e);
            }
    }
    return SNELL_OK;
}

/* caustics_opaque.frag in double: the direct light where a ray towards the
 * light meets nothing, plus the caustic map read bilinearly over the texels
 * whose nearest surface is this one (depth within 3 texels), both times the
 * cosine (spot: over distance^2; the direct light inside its cone). */
void snell__ref_lit_irradiance(const snell_ref *r, const ref_surf *s, double e[3])
{
    const struct ref_lit *L = r->lit;
    ref_view air = {-1, REF_SEE_ALL, -1};
    ref_surf h;
    double l[3], fall = 1.0, cone = 1.0, far_ = HUGE_VAL, cosl, fx, fy, fz, tw, tx, ty, acc[3] = {0, 0, 0}, wsum = 0.0;
    double back[3];
    int k, q;
    e[0] = e[1] = e[2] = 0.0;
    memcpy(l, L->d, sizeof l);
    if (L->spot) {
        for (k = 0; k < 3; k++) l[k] = s->p[k] - L->pos[k];
        fall = 1.0 / snell__ref_dot3(l, l);
        far_ = sqrt(1.0 / fall);
        snell__ref_normalize3(l);
        cone = snell__ref_dot3(l, L->d) >= L->cos_cone ? 1.0 : 0.0;
    }
    cosl = -snell__ref_dot3(s->n, l);
    if (!(cosl > 0.0)) return;
    for (k = 0; k < 3; k++) back[k] = -l[k];
    if (cone > 0.0 && !(snell__ref_hit(r, s->p, back, s->prim, &air, &h) && h.t < far_))
        for (k = 0; k < 3; k++) e[k] = L->col[k] * fall * cosl;
    if (!frame_xy(L, s->p, &fx, &fy, &fz)) return; /* above a spot light: outside its frame, no caustic */
    tw = L->texel * (L->spot ? fz : 1.0);
    tx = (fx - L->lo[0]) / (L->hi[0] - L->lo[0]) * L->size - 0.5;
    ty = (fy - L->lo[1]) / (L->hi[1] - L->lo[1]) * L->size - 0.5;
    for (q = 0; q < 4; q++) {
        int ix = (int)floor(tx) + (q & 1), iy = (int)floor(ty) + (q >> 1);
        double wk = (q & 1 ? tx - floor(tx) : 1.0 - (tx - floor(tx))) * (q >> 1 ? ty - floor(ty) : 1.0 - (ty - floor(ty)));
        size_t t;
        ix = ix < 0 ? 0 : ix >= L->size ? L->size - 1 : ix;
        iy = iy < 0 ? 0 : iy >= L->size ? L->size - 1 : iy;
        t = (size_t)iy * (size_t)L->size + (size_t)ix;
        if (!(fabs(L->depth[t] - fz) < 3.0 * tw)) continue;
        for (k = 0; k < 3; k++) acc[k] += wk * L->acc[3 * t + k];
        wsum += wk;
    }
    if (wsum > 0.0)
        for (k = 0; k < 3; k++) e[k] += acc[k] / wsum * fall * cosl;
}

const double *snell__ref_lit_map(const snell_ref *r, int *size, double *area)
{
    if (!r->lit) return NULL;
    *size = r->lit->size;
    *area = r->lit->area;
    return r->lit->acc;
}
