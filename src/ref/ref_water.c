/* SPDX-License-Identifier: MIT */
/* ref_water.c — the reference for the water scene (snell_ref_water_render):
 * the height field intersected exactly, in double, as the triangles the GPU draws,
 * found by walking the cells the ray crosses (Amanatides-Woo); the container's
 * faces as exact planes; water_surface.frag's optics; the objects traced by
 * ref_trace.c's MATCHED model within the two media (snell__ref_medium). More:
 * docs/ARCHITECTURE.md, "Design notes by file". */
#include "frame/lighting.h"
#include "core/optics.h"
#include "ref/ref_scene.h"
#include "ref/ref_trace.h"
#include "frame/env.h"
#include "snell/snell_water.h"
#include "water/water.h"

#include <pthread.h>
#include <string.h>
#include <unistd.h>

typedef struct water_scene {
    const snell_water *w;
    const snell_ref *objects;   /* the objects standing in (or above) the water, or NULL */
    snell__ref_medium air, air_above, water; /* air_above: the mirror rays, which leave the surface out */
    const float *h;             /* heights, n * n */
    double half, dx, hmin, hmax;
    int n;
    const snell_ref_params *p;
    const camera_rays *cr;
    const snell_ref_output *out;
    int samples;
    pthread_mutex_t lock;
    int next_row;
    snell__ref_progress progress;
} water_scene;

static void env(const water_scene *s, const double d[3], double rgb[3])
{
    if (s->p->env_fn) s->p->env_fn(d, rgb, s->p->env_user);
    else snell_env_sample_d(s->p->env, d, rgb);
}

/* Node (i, j): world position and the vertex shader's unnormalised normal. */
static void node(const water_scene *s, int i, int j, double p[3], double nrm[3])
{
    int n = s->n, il = i > 0 ? i - 1 : 0, ir = i + 1 < n ? i + 1 : n - 1, jd = j > 0 ? j - 1 : 0, ju = j + 1 < n ? j + 1 : n - 1;
    const float *h = s->h;
    p[0] = -s->half + i * s->dx;
    p[1] = h[(size_t)j * n + i];
    p[2] = -s->half + j * s->dx;
    nrm[0] = -((double)h[(size_t)j * n + ir] - h[(size_t)j * n + il]) / ((ir - il) * s->dx);
    nrm[1] = 1.0;
    nrm[2] = -((double)h[(size_t)ju * n + i] - h[(size_t)jd * n + i]) / ((ju - jd) * s->dx);
}

/* Moeller-Trumbore: t and barycentrics (b1 for v1, b2 for v2) if o + t d hits triangle v0 v1 v2. */
static int triangle(const double o[3], const double d[3], const double v0[3], const double v1[3], const double v2[3],
                    double *t, double *b1, double *b2)
{
    double e1[3], e2[3], pv[3], tv[3], qv[3], det, inv, u, v;
    int k;
    for (k = 0; k < 3; k++) {
        e1[k] = v1[k] - v0[k];
        e2[k] = v2[k] - v0[k];
        tv[k] = o[k] - v0[k];
    }
    pv[0] = d[1] * e2[2] - d[2] * e2[1];
    pv[1] = d[2] * e2[0] - d[0] * e2[2];
    pv[2] = d[0] * e2[1] - d[1] * e2[0];
    det = snell__ref_dot3(e1, pv);
    if (fabs(det) < 1e-300) return 0;
    inv = 1.0 / det;
    u = snell__ref_dot3(tv, pv) * inv;
    if (u < 0.0 || u > 1.0) return 0;
    qv[0] = tv[1] * e1[2] - tv[2] * e1[1];
    qv[1] = tv[2] * e1[0] - tv[0] * e1[2];
    qv[2] = tv[0] * e1[1] - tv[1] * e1[0];
    v = snell__ref_dot3(d, qv) * inv;
    if (v < 0.0 || u + v > 1.0) return 0;
    *t = snell__ref_dot3(e2, qv) * inv;
    *b1 = u;
    *b2 = v;
    return *t > 1e-9; /* not the triangle a mirror ray leaves */
}

/* The two triangles of cell (i, j): nearest hit, its point and normal. */
static int cell_hit(const water_scene *s, int i, int j, const double o[3], const double d[3], double *t, double nrm[3])
{
    double p[4][3], q[4][3], tt, b1, b2, best = HUGE_VAL;
    int k, hit = 0;
    node(s, i, j, p[0], q[0]);
    node(s, i + 1, j, p[1], q[1]);
    node(s, i + 1, j + 1, p[2], q[2]);
    node(s, i, j + 1, p[3], q[3]);
    if (triangle(o, d, p[0], p[1], p[2], &tt, &b1, &b2) && tt < best) {
        best = tt;
        for (k = 0; k < 3; k++) nrm[k] = (1.0 - b1 - b2) * q[0][k] + b1 * q[1][k] + b2 * q[2][k];
        hit = 1;
    }
    if (triangle(o, d, p[0], p[2], p[3], &tt, &b1, &b2) && tt < best) {
        best = tt;
        for (k = 0; k < 3; k++) nrm[k] = (1.0 - b1 - b2) * q[0][k] + b1 * q[2][k] + b2 * q[3][k];
        hit = 1;
    }
    *t = best;
    return hit;
}

/* Nearest hit of the surface: the ray clipped to the box |x|, |z| <= half,
 * hmin <= y <= hmax, then the cells its xz projection crosses, in order. */
static int surface_hit(const water_scene *s, const double o[3], const double d[3], double *t_out, double nrm[3])
{
    double lo[3] = {-s->half, s->hmin, -s->half}, hi[3] = {s->half, s->hmax, s->half}, t0 = 0.0, t1 = HUGE_VAL;
    double tnx, tnz, tdx, tdz;
    int k, ci, cj, si, sj, last = s->n - 2;
    for (k = 0; k < 3; k++) {
        if (d[k] == 0.0) {
            if (o[k] < lo[k] || o[k] > hi[k]) return 0;
            continue;
        }
        {
            double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
            if (a > b) {
                double c = a;
                a = b;
                b = c;
            }
            if (a > t0) t0 = a;
            if (b < t1) t1 = b;
        }
    }
    if (t0 > t1) return 0;
    {
        double x = o[0] + t0 * d[0], z = o[2] + t0 * d[2];
        ci = (int)floor((x + s->half) / s->dx);
        cj = (int)floor((z + s->half) / s->dx);
    }
    ci = ci < 0 ? 0 : ci > last ? last : ci;
    cj = cj < 0 ? 0 : cj > last ? last : cj;
    si = d[0] > 0.0 ? 1 : -1;
    sj = d[2] > 0.0 ? 1 : -1;
    tnx = d[0] != 0.0 ? (-s->half + (ci + (si > 0)) * s->dx - o[0]) / d[0] : HUGE_VAL;
    tnz = d[2] != 0.0 ? (-s->half + (cj + (sj > 0)) * s->dx - o[2]) / d[2] : HUGE_VAL;
    tdx = d[0] != 0.0 ? s->dx / fabs(d[0]) : HUGE_VAL;
    tdz = d[2] != 0.0 ? s->dx / fabs(d[2]) : HUGE_VAL;
    for (;;) {
        if (cell_hit(s, ci, cj, o, d, t_out, nrm)) return 1;
        if (tnx > t1 && tnz > t1) return 0;
        if (tnx < tnz) {
            ci += si;
            tnx += tdx;
        } else {
            cj += sj;
            tnz += tdz;
        }
        if (ci < 0 || cj < 0 || ci > last || cj > last) return 0;
    }
}

/* Nearest face of the container (0 floor, 1..4 walls as snell_water_tile_color), seen from anywhere. */
static int container_hit(const water_scene *s, const double o[3], const double d[3], double *t_out)
{
    const snell_water_desc *wd = &s->w->d;
    double best = HUGE_VAL;
    int face = -1, f;
    for (f = 0; f < 5; f++) {
        int axis = f == 0 ? 1 : f <= 2 ? 0 : 2;
        double plane = f == 0 ? -wd->depth : (f == 1 || f == 3) ? -s->half : s->half, t, p[3];
        int k, inside = 1;
        if (d[axis] == 0.0) continue;
        t = (plane - o[axis]) / d[axis];
        if (!(t > 1e-9) || t >= best) continue;
        for (k = 0; k < 3; k++) p[k] = o[k] + t * d[k];
        for (k = 0; k < 3; k++) {
            if (k == axis) continue;
            if (k == 1 ? (p[1] < -wd->depth || p[1] > wd->rim) : fabs(p[k]) > s->half) inside = 0;
        }
        if (inside) {
            best = t;
            face = f;
        }
    }
    *t_out = best;
    return face;
}

/* The media around the objects (ref_trace.h): a trace walks through them
 * with its recursion depth (the water's shading traces its own two rays). */
typedef struct water_walk {
    const water_scene *s;
    int depth;
} water_walk;

#define WATER_MAX_DEPTH 3 /* deeper, the surface is shaded without objects */

static void trace_in(const water_scene *s, int depth, const snell__ref_medium *m, const double o[3], const double d[3],
                     double rgb[3]);

/* In the water: the seed's five wall distances (a rising ray meets the
 * walls, not the surface from below), Beer-Lambert over the distance; an
 * object nearer than them is the trace's. */
static int meet_water(const void *user, const double o[3], const double d[3], double t_limit, double rgb[3])
{
    const water_scene *s = ((const water_walk *)user)->s;
    double t = HUGE_VAL, q[3];
    int face = 0, k;
    if (d[1] < 0.0) t = (-s->w->d.depth - o[1]) / d[1];
    if (d[0] != 0.0) {
        double e = ((d[0] > 0.0 ? s->half : -s->half) - o[0]) / d[0];
        if (e < t) {
            t = e;
            face = d[0] > 0.0 ? 2 : 1;
        }
    }
    if (d[2] != 0.0) {
        double e = ((d[2] > 0.0 ? s->half : -s->half) - o[2]) / d[2];
        if (e < t) {
            t = e;
            face = d[2] > 0.0 ? 4 : 3;
        }
    }
    if (t < 0.0) t = 0.0;
    if (t >= t_limit) return 0;
    for (k = 0; k < 3; k++) q[k] = o[k] + t * d[k];
    snell__water_tile(&s->w->d, face, q, rgb);
    for (k = 0; k < 3; k++) rgb[k] *= exp(-s->water.sigma[k] * t);
    return 1;
}

/* The water surface met at p by the ray d from the air, normal nrm
 * (unnormalised): Schlick's Fresnel between the mirror ray (in the air,
 * leaving the surface out) and the refracted one (in the water). */
static void shade_surface(const water_scene *s, int depth, const double p[3], const double d[3], double nrm[3],
                          double rgb[3])
{
    double r[3], t[3], f, seen[3], sky[3];
    int k;
    snell__ref_normalize3(nrm);
    if (snell__ref_dot3(nrm, d) > 0.0)
        for (k = 0; k < 3; k++) nrm[k] = -nrm[k];
    snell_optd_reflect(d, nrm, r);
    snell__ref_normalize3(r);
    snell_optd_refract(d, nrm, 1.0 / s->water.ior, t);
    snell__ref_normalize3(t);
    f = snell_optd_fresnel_schlick(-snell__ref_dot3(d, nrm), 1.0, s->water.ior);
    trace_in(s, depth + 1, &s->water, p, t, seen);
    trace_in(s, depth + 1, &s->air_above, p, r, sky);
    for (k = 0; k < 3; k++) rgb[k] = (1.0 - f) * seen[k] + f * sky[k];
}

/* In the air: the water surface (with_surface) or a face of the container
 * (either side, walls up to the rim), whichever comes first before t_limit. */
static int meet_air_or_above(const water_walk *wk, const double o[3], const double d[3], double t_limit, int with_surface,
                             double rgb[3])
{
    const water_scene *s = wk->s;
    double tw = HUGE_VAL, tc, nrm[3] = {0.0, 1.0, 0.0}, p[3];
    int water = with_surface && surface_hit(s, o, d, &tw, nrm), face = container_hit(s, o, d, &tc), k;
    if (water && tw < t_limit && (face < 0 || tw <= tc)) {
        for (k = 0; k < 3; k++) p[k] = o[k] + tw * d[k];
        shade_surface(s, wk->depth, p, d, nrm, rgb);
        return 1;
    }
    if (face >= 0 && tc < t_limit) {
        for (k = 0; k < 3; k++) p[k] = o[k] + tc * d[k];
        snell__water_tile(&s->w->d, face, p, rgb);
        return 1;
    }
    return 0;
}

static int meet_air(const void *user, const double o[3], const double d[3], double t_limit, double rgb[3])
{
    return meet_air_or_above((const water_walk *)user, o, d, t_limit, 1, rgb);
}

static int meet_above(const void *user, const double o[3], const double d[3], double t_limit, double rgb[3])
{
    return meet_air_or_above((const water_walk *)user, o, d, t_limit, 0, rgb);
}

/* The height of the drawn surface (its triangles) at world (x, z) inside the container. */
static double surface_height(const water_scene *s, double x, double z)
{
    double gx = (x + s->half) / s->dx, gz = (z + s->half) / s->dx, u, v;
    int i = (int)floor(gx), j = (int)floor(gz), n = s->n;
    const float *h = s->h;
    i = i < 0 ? 0 : i > n - 2 ? n - 2 : i;
    j = j < 0 ? 0 : j > n - 2 ? n - 2 : j;
    u = gx - i;
    v = gz - j;
    {
        double h00 = h[(size_t)j * n + i], h10 = h[(size_t)j * n + i + 1], h11 = h[(size_t)(j + 1) * n + i + 1],
               h01 = h[(size_t)(j + 1) * n + i];
        /* split along (i, j)-(i+1, j+1): below it (u >= v) the triangle 00-10-11, else 00-11-01 */
        return u >= v ? h00 + u * (h10 - h00) + v * (h11 - h10) : h00 + v * (h01 - h00) + u * (h11 - h01);
    }
}

/* The medium at a point on an object's surface: the water inside the box below the surface, else the air. */
static const snell__ref_medium *medium_at(const void *user, const double p[3])
{
    const water_scene *s = ((const water_walk *)user)->s;
    if (fabs(p[0]) <= s->half && fabs(p[2]) <= s->half && p[1] >= -s->w->d.depth &&
        p[1] < surface_height(s, p[0], p[2]))
        return &s->water;
    return &s->air;
}

/* The radiance along o + t d starting in medium m: through the objects (a
 * MATCHED trace within the media) or, without objects, straight to what the
 * medium meets. */
static void trace_in(const water_scene *s, int depth, const snell__ref_medium *m, const double o[3], const double d[3],
                     double rgb[3])
{
    water_walk wk;
    snell__ref_surroundings sur;
    wk.s = s;
    wk.depth = depth;
    if (depth > WATER_MAX_DEPTH) { /* a path bounced between the surface and the glass: end it plainly */
        if (m == &s->water) meet_water(&wk, o, d, HUGE_VAL, rgb);
        else env(s, d, rgb);
        return;
    }
    if (!s->objects) {
        if (!m->meet(&wk, o, d, HUGE_VAL, rgb)) env(s, d, rgb);
        return;
    }
    sur.user = &wk;
    sur.at = medium_at;
    snell__ref_trace_matched(s->objects, s->p, &sur, m, o, d, rgb);
}

/* What a view ray meets first, for the outputs other than rgb: 1 if the
 * water surface (exit_dir the refracted direction), else 0 (exit_dir d). */
static int view_hit(const water_scene *s, const double o[3], const double d[3], double exit_dir[3])
{
    const ref_view view = {-1, REF_SEE_ALL, -1};
    double tw = HUGE_VAL, tc, nrm[3] = {0.0, 1.0, 0.0};
    ref_surf os;
    int water = surface_hit(s, o, d, &tw, nrm), face = container_hit(s, o, d, &tc), k;
    memcpy(exit_dir, d, 3 * sizeof(double));
    if (s->objects && snell__ref_hit(s->objects, o, d, SNELL__BVH_NONE, &view, &os) && (!water || os.t < tw)) return 0;
    if (!water || (face >= 0 && tc < tw)) return 0;
    snell__ref_normalize3(nrm);
    if (snell__ref_dot3(nrm, d) > 0.0)
        for (k = 0; k < 3; k++) nrm[k] = -nrm[k];
    snell_optd_refract(d, nrm, 1.0 / s->water.ior, exit_dir);
    snell__ref_normalize3(exit_dir);
    return 1;
}

static void row(water_scene *s, int y)
{
    const camera_rays *cr = s->cr;
    const snell_ref_output *out = s->out;
    int x, a, b, k, S = s->samples;
    for (x = 0; x < cr->w; x++) {
        size_t i = (size_t)y * (size_t)cr->w + (size_t)x;
        double dir[3], org[3], rgb[3], ex[3], sum[3] = {0, 0, 0};
        int hit;
        for (b = 0; b < S; b++)
            for (a = 0; a < S; a++) {
                snell__ref_camera_ray(cr, x, y, (a + 0.5) / S, (b + 0.5) / S, org, dir);
                trace_in(s, 0, &s->air, org, dir, rgb);
                for (k = 0; k < 3; k++) sum[k] += rgb[k];
            }
        for (k = 0; k < 3; k++) out->rgb[3 * i + k] = (float)(sum[k] / (S * S));
        snell__ref_camera_ray(cr, x, y, 0.5, 0.5, org, dir);
        hit = view_hit(s, org, dir, ex);
        if (out->exit_dir)
            for (k = 0; k < 3; k++) out->exit_dir[3 * i + k] = (float)ex[k];
        if (out->hit) out->hit[i] = (uint8_t)hit;
    }
}

static void *worker(void *arg)
{
    water_scene *s = (water_scene *)arg;
    int y = -1;
    for (;;) {
        pthread_mutex_lock(&s->lock);
        if (y >= 0) snell__ref_progress_row(&s->progress); /* row y is done */
        y = s->next_row++;
        pthread_mutex_unlock(&s->lock);
        if (y >= s->cr->h) break;
        row(s, y);
    }
    return NULL;
}

snell_status snell_ref_water_render(snell_water *w, const snell_ref *objects, const snell_ref_params *params,
                                    const snell_ref_output *out)
{
    water_scene s;
    camera_rays cr;
    pthread_t tids[SNELL_REF_MAX_THREADS];
    snell_status st;
    size_t i, nodes;
    float *h;
    int k, nthreads, started = 0;
    if (!w || !params || !out || !out->rgb)
        return snell__fail(w ? w->ctx : NULL, SNELL_E_INVALID_ARG,
                           "snell_ref_water_render: water, params, out and out->rgb are required");
    if (!params->env && !params->env_fn)
        return snell__fail(w->ctx, SNELL_E_INVALID_ARG, "snell_ref_water_render: params need env or env_fn");
    if (!params->env_fn && !params->env->faces[0])
        return snell__fail(w->ctx, params->env->borrowed ? SNELL_E_UNSUPPORTED : SNELL_E_INVALID_ARG,
                           "snell_ref_water_render: the environment has no CPU faces%s",
                           params->env->borrowed ? " (SNELL_ENV_GL_TEXTURE: the host's texture, GPU only)" : "");
    if (params->max_interfaces < 0 || params->max_interfaces > SNELL_REF_MAX_INTERFACES)
        return snell__fail(w->ctx, SNELL_E_INVALID_ARG, "snell_ref_water_render: max_interfaces %d outside 0..%d",
                           params->max_interfaces, SNELL_REF_MAX_INTERFACES);
    if (params->samples < 0 || params->samples > SNELL_REF_MAX_SAMPLES || params->threads < 0)
        return snell__fail(w->ctx, SNELL_E_INVALID_ARG, "snell_ref_water_render: samples %d outside 0..%d or threads %d < 0",
                           params->samples, SNELL_REF_MAX_SAMPLES, params->threads);
    if ((st = snell__ref_camera_setup(w->ctx, params, &cr)) != SNELL_OK) return st;
    nodes = (size_t)w->n * (size_t)w->n;
    h = (float *)snell__calloc(&w->alloc, nodes, sizeof(float));
    if (!h) return snell__fail(w->ctx, SNELL_E_NOMEM, "snell_ref_water_render: out of memory for the heights");
    if ((st = snell_water_read_heights(w, h)) != SNELL_OK) {
        snell__free(&w->alloc, h);
        return st;
    }
    memset(&s, 0, sizeof s);
    s.w = w;
    s.objects = objects;
    s.h = h;
    s.n = w->n;
    s.half = 0.5 * (double)w->d.width;
    s.dx = w->dx;
    for (k = 0; k < 3; k++) s.water.sigma[k] = w->sigma[k];
    s.air.meet = meet_air;
    s.air_above.meet = meet_above;
    s.water.meet = meet_water;
    s.air.ior = s.air_above.ior = 1.0;
    s.water.ior = w->d.ior;
    s.hmin = s.hmax = h[0];
    for (i = 1; i < nodes; i++) {
        if (h[i] < s.hmin) s.hmin = h[i];
        if (h[i] > s.hmax) s.hmax = h[i];
    }
    s.p = params;
    s.cr = &cr;
    s.out = out;
    s.samples = params->samples > 1 ? params->samples : 1;
    nthreads = params->threads;
    if (nthreads == 0) {
        long c = sysconf(_SC_NPROCESSORS_ONLN);
        nthreads = c > 0 ? (int)(c < SNELL_REF_MAX_THREADS ? c : SNELL_REF_MAX_THREADS) : 1;
    }
    if (nthreads > SNELL_REF_MAX_THREADS) nthreads = SNELL_REF_MAX_THREADS;
    snell__ref_progress_init(&s.progress, params, cr.h);
    if (pthread_mutex_init(&s.lock, NULL) != 0) {
        snell__free(&w->alloc, h);
        return snell__fail(w->ctx, SNELL_E_NOMEM, "snell_ref_water_render: cannot create a mutex");
    }
    for (k = 1; k < nthreads; k++) {
        if (pthread_create(&tids[started], NULL, worker, &s) != 0) break;
        started++;
    }
    worker(&s);
    for (k = 0; k < started; k++) pthread_join(tids[k], NULL);
    pthread_mutex_destroy(&s.lock);
    snell__free(&w->alloc, h);
    snell__ref_progress_end(&s.progress);
    return SNELL_OK;
}

/* --- the floor's light (snell_ref_water_floor_render) --------------------- */

typedef struct floor_trace {
    water_scene s;
    int spot, photons, size, next_row;
    double d[3], u[3], v[3], pos[3], col[3], centre[3], extent, back, cos_cone, cell, texel;
    double *acc[SNELL_REF_MAX_THREADS];
    int nacc;
    pthread_mutex_t lock;
} floor_trace;

/* Adds e about floor point (x, z) as the caustics stage splats (caustics_splat.frag): a tent of
 * half-width 2 texels along each axis, (1 - |dx| / 2)(1 - |dz| / 2) / 4 at the texel centres. */
static void floor_splat(const floor_trace *ft, double *acc, double x, double z, const double e[3])
{
    double tx = (x + ft->s.half) / ft->texel - 0.5, tz = (z + ft->s.half) / ft->texel - 0.5;
    int ix, iz, c, m = ft->size;
    if (!(tx > -2.0 && tz > -2.0 && tx < m + 1.0 && tz < m + 1.0)) return;
    for (iz = (int)floor(tz) - 1; iz <= (int)floor(tz) + 2; iz++)
        for (ix = (int)floor(tx) - 1; ix <= (int)floor(tx) + 2; ix++) {
            double wx = 1.0 - fabs(tx - ix) / 2.0, wz = 1.0 - fabs(tz - iz) / 2.0, w;
            if (wx <= 0.0 || wz <= 0.0 || ix < 0 || iz < 0 || ix >= m || iz >= m) continue;
            w = wx * wz / 4.0;
            for (c = 0; c < 3; c++) acc[3 * ((size_t)iz * (size_t)m + (size_t)ix) + c] += w * e[c];
        }
}

/* Whether an opaque object of s->objects lies on o + t d, 0 < t < far. */
static int opaque_on(const water_scene *s, const double o[3], const double d[3], double far_)
{
    ref_view opaque_only = {-1, REF_SEE_NONE, -1};
    ref_surf os;
    return s->objects && snell__ref_hit(s->objects, o, d, SNELL__BVH_NONE, &opaque_only, &os) && os.t < far_;
}

/* One photon from o along unit dir carrying flux (per texel area): through
 * the surface onto the floor, unless a wall or an opaque object is in the way. */
static void floor_photon(const floor_trace *ft, double *acc, const double o[3], const double dir[3], const double flux[3])
{
    const water_scene *s = &ft->s;
    double tw, tc, nrm[3], p[3], t[3], f, tf, e[3];
    int k;
    if (!(dir[1] < 0.0) || !surface_hit(s, o, dir, &tw, nrm)) return; /* light from below: none (as the stage) */
    if (container_hit(s, o, dir, &tc) >= 0 && tc < tw) return; /* a wall (the rim) hides the surface there */
    if (opaque_on(s, o, dir, tw)) return;
    for (k = 0; k < 3; k++) p[k] = o[k] + tw * dir[k];
    snell__ref_normalize3(nrm);
    if (snell__ref_dot3(nrm, dir) > 0.0)
        for (k = 0; k < 3; k++) nrm[k] = -nrm[k];
    f = snell_optd_fresnel_schlick(-snell__ref_dot3(dir, nrm), 1.0, s->water.ior);
    if (!snell_optd_refract(dir, nrm, 1.0 / s->water.ior, t)) return;
    snell__ref_normalize3(t);
    if (!(t[1] < 0.0)) return;
    tf = (-s->w->d.depth - p[1]) / t[1];
    for (k = 0; k < 3; k += 2) /* a wall before the floor takes it */
        if (t[k] != 0.0 && ((t[k] > 0.0 ? s->half : -s->half) - p[k]) / t[k] < tf) return;
    if (opaque_on(s, p, t, tf)) return;
    for (k = 0; k < 3; k++) e[k] = flux[k] * (1.0 - f) * exp(-s->water.sigma[k] * tf);
    floor_splat(ft, acc, p[0] + tf * t[0], p[2] + tf * t[2], e);
}

static void floor_row(const floor_trace *ft, double *acc, int j)
{
    int i, k, n = ft->photons;
    for (i = 0; i < n; i++) {
        double x = -ft->extent + (i + 0.5) * ft->cell, y = -ft->extent + (j + 0.5) * ft->cell, o[3], dir[3], flux[3];
        double base = ft->cell * ft->cell / (ft->texel * ft->texel);
        if (ft->spot) {
            double c = 1.0 / sqrt(1.0 + x * x + y * y); /* its solid angle: cell^2 cos^3 */
            if (c < ft->cos_cone) continue;
            for (k = 0; k < 3; k++) dir[k] = ft->d[k] + ft->u[k] * x + ft->v[k] * y, o[k] = ft->pos[k];
            snell__ref_normalize3(dir);
            base *= c * c * c;
        } else {
            for (k = 0; k < 3; k++) {
                o[k] = ft->centre[k] + ft->u[k] * x + ft->v[k] * y - ft->d[k] * ft->back;
                dir[k] = ft->d[k];
            }
        }
        for (k = 0; k < 3; k++) flux[k] = ft->col[k] * base;
        floor_photon(ft, acc, o, dir, flux);
    }
}

static void *floor_worker(void *arg)
{
    floor_trace *ft = (floor_trace *)arg;
    double *acc;
    int j;
    pthread_mutex_lock(&ft->lock);
    acc = ft->acc[ft->nacc++];
    pthread_mutex_unlock(&ft->lock);
    for (;;) {
        pthread_mutex_lock(&ft->lock);
        j = ft->next_row++;
        pthread_mutex_unlock(&ft->lock);
        if (j >= ft->photons) break;
        floor_row(ft, acc, j);
    }
    return NULL;
}

snell_status snell_ref_water_floor_render(snell_water *w, const snell_ref *objects, const snell_light *light, int size,
                                          int photons, int threads, float *rgb)
{
    floor_trace *ft;
    pthread_t tids[SNELL_REF_MAX_THREADS];
    float *h;
    size_t nodes, texels, i;
    snell_light lt;
    double len, r;
    int k, t, started = 0;
    snell_status st = SNELL_OK;
    if (!w || !light || !rgb)
        return snell__fail(w ? w->ctx : NULL, SNELL_E_INVALID_ARG, "snell_ref_water_floor_render: NULL argument");
    if (light->type != SNELL_LIGHT_DIRECTIONAL && light->type != SNELL_LIGHT_SPOT)
        return snell__fail(w->ctx, SNELL_E_INVALID_ARG, "snell_ref_water_floor_render: no light");
    len = sqrt((double)light->direction[0] * light->direction[0] + (double)light->direction[1] * light->direction[1] +
               (double)light->direction[2] * light->direction[2]);
    if (!(len > 0.0) || !isfinite(len) || (light->type == SNELL_LIGHT_SPOT && !(light->spot_angle >= 0.0f &&
                                                                              light->spot_angle <= 1.5f)))
        return snell__fail(w->ctx, SNELL_E_INVALID_ARG, "snell_ref_water_floor_render: light.direction zero or not "
                           "finite, or spot_angle outside 0..1.5");
    if (size == 0) size = w->d.light_map ? w->d.light_map : 256;
    if (size < 1 || size > 4096 || photons < 1 || photons > 16384 || threads < 0)
        return snell__fail(w->ctx, SNELL_E_INVALID_ARG, "snell_ref_water_floor_render: size %d (0..4096), photons %d "
                           "(1..16384), threads %d (>= 0)", size, photons, threads);
    if (threads == 0) {
        long c = sysconf(_SC_NPROCESSORS_ONLN);
        threads = c > 0 ? (int)c : 1;
    }
    if (threads > 16) threads = 16; /* each keeps a map of its own */
    nodes = (size_t)w->n * (size_t)w->n;
    texels = (size_t)size * (size_t)size;
    ft = (floor_trace *)snell__calloc(&w->alloc, 1, sizeof *ft);
    h = (float *)snell__calloc(&w->alloc, nodes, sizeof(float));
    for (t = 0; ft && t < threads; t++)
        if (!(ft->acc[t] = (double *)snell__calloc(&w->alloc, texels, 3 * sizeof(double)))) st = SNELL_E_NOMEM;
    if (!ft || !h || st != SNELL_OK) {
        st = snell__fail(w->ctx, SNELL_E_NOMEM, "snell_ref_water_floor_render: out of memory");
        goto done;
    }
    if ((st = snell_water_read_heights(w, h)) != SNELL_OK) goto done;
    ft->s.w = w;
    ft->s.objects = objects;
    ft->s.h = h;
    ft->s.n = w->n;
    ft->s.half = 0.5 * (double)w->d.width;
    ft->s.dx = w->dx;
    ft->s.water.ior = w->d.ior;
    for (k = 0; k < 3; k++) ft->s.water.sigma[k] = w->sigma[k];
    ft->s.hmin = ft->s.hmax = h[0];
    for (i = 1; i < nodes; i++) {
        if (h[i] < ft->s.hmin) ft->s.hmin = h[i];
        if (h[i] > ft->s.hmax) ft->s.hmax = h[i];
    }
    snell__light_defaults(light, &lt);
    ft->spot = light->type == SNELL_LIGHT_SPOT;
    ft->photons = photons;
    ft->size = size;
    ft->texel = (double)w->d.width / size;
    for (k = 0; k < 3; k++) {
        ft->d[k] = light->direction[k] / len;
        ft->pos[k] = light->position[k];
        ft->col[k] = lt.color[k];
    }
    {
        double a[3] = {0.0, 1.0, 0.0};
        if (fabs(ft->d[1]) > 0.99) a[0] = 1.0, a[1] = 0.0;
        ft->u[0] = a[1] * ft->d[2] - a[2] * ft->d[1];
        ft->u[1] = a[2] * ft->d[0] - a[0] * ft->d[2];
        ft->u[2] = a[0] * ft->d[1] - a[1] * ft->d[0];
        snell__ref_normalize3(ft->u);
        ft->v[0] = ft->d[1] * ft->u[2] - ft->d[2] * ft->u[1];
        ft->v[1] = ft->d[2] * ft->u[0] - ft->d[0] * ft->u[2];
        ft->v[2] = ft->d[0] * ft->u[1] - ft->d[1] * ft->u[0];
    }
    if (ft->spot) {
        ft->cos_cone = cos((double)lt.spot_angle);
        ft->extent = tan(acos(ft->cos_cone));
    } else {
        /* a sphere about the water's top holds every point a ray can meet it at */
        ft->centre[1] = 0.5 * (ft->s.hmin + ft->s.hmax);
        r = sqrt(2.0 * ft->s.half * ft->s.half + 0.25 * (ft->s.hmax - ft->s.hmin) * (ft->s.hmax - ft->s.hmin));
        ft->extent = r * 1.001;
        ft->back = r + w->d.rim + w->d.depth + 1.0; /* starts outside the container */
    }
    ft->cell = 2.0 * ft->extent / photons;
    if (pthread_mutex_init(&ft->lock, NULL) != 0) {
        st = snell__fail(w->ctx, SNELL_E_NOMEM, "snell_ref_water_floor_render: cannot create a mutex");
        goto done;
    }
    for (t = 1; t < threads; t++) {
        if (pthread_create(&tids[started], NULL, floor_worker, ft) != 0) break;
        started++;
    }
    floor_worker(ft);
    for (t = 0; t < started; t++) pthread_join(tids[t], NULL);
    pthread_mutex_destroy(&ft->lock);
    for (i = 0; i < 3 * texels; i++) {
        double e = 0.0;
        for (t = 0; t < threads; t++) e += ft->acc[t][i];
        rgb[i] = (float)e;
    }
done:
    if (ft)
        for (t = 0; t < threads; t++) snell__free(&w->alloc, ft->acc[t]);
    snell__free(&w->alloc, ft);
    snell__free(&w->alloc, h);
    return st;
}
