/* ref_trace.c — the double-precision CPU reference tracer (snell_ref.h):
 * scene intersection (mesh BVH or analytic sphere), the MATCHED chain and
 * the FULL Whitted tree, camera rays, the pthread image loop and light paths.
 * Optics are the shared kernel of optics.h (Unger 2.1: Snell with TIR, mirror
 * reflection, Schlick, Beer-Lambert); the chain follows Unger 4.1 with exact
 * ray casts in place of the cubemap binary search. */
#define _POSIX_C_SOURCE 200809L
#include "ref/ref_trace.h"
#include "render/env.h"
#include "mesh/mesh.h"
#include "core/optics.h"
#include "ref/ref_bvh.h"

#include <math.h>
#include <pthread.h>
#include <string.h>
#include <unistd.h>

/* FULL mode: a branch whose throughput (largest channel) falls below this ends
 * with an env lookup in its direction instead of being traced further. The
 * error is below MIN_WEIGHT * (difference of two radiances <= 1) per pruned
 * branch, far under half an 8-bit step (1/510). */
#define MIN_WEIGHT 1e-5

struct snell_ref {
    snell_ctx *ctx;
    snell_alloc alloc;
    snell__bvh *bvh;          /* NULL for the analytic sphere */
    double *normals;          /* 3 * vertex_count: inverse-transpose(model) * n, not renormalised (glass.vert) */
    uint32_t *indices;        /* 3 * triangle_count, copy of the mesh's */
    int analytic;             /* 1: exact sphere sph_c, sph_r */
    double sph_c[3], sph_r;
    double bs_c[3], bs_r;     /* bounding sphere of the GPU single method */
    double eps;               /* tmin of every ray cast, world units */
};

/* Parameters with defaults resolved. */
typedef struct optics {
    snell_ref_mode mode;
    int max_if;
    snell_ref_absorption absorb;
    double ior, sigma[3], tint[3];
    int has_sigma;
    const snell_env *env;
    snell_ref_env_fn env_fn;
    void *env_user;
} optics;

typedef struct surf {
    double t, p[3], n[3]; /* n: unit smooth normal, not yet flipped */
    uint32_t prim;
} surf;

/* ------------------------------------------------------------ vectors */

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static int normalize3(double v[3])
{
    double l = sqrt(dot3(v, v));
    if (!(l > 0.0) || !isfinite(l)) return 0;
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
    return 1;
}

static void env_rgb(const optics *op, const double d[3], double rgb[3])
{
    if (op->env_fn)
        op->env_fn(d, rgb, op->env_user);
    else
        snell_env_sample_d(op->env, d, rgb);
}

/* ------------------------------------------------------------ geometry */

static int sphere_hit(const snell_ref *r, const double o[3], const double d[3], surf *s)
{
    double oc[3] = {o[0] - r->sph_c[0], o[1] - r->sph_c[1], o[2] - r->sph_c[2]};
    double a = dot3(d, d), b = dot3(oc, d), c = dot3(oc, oc) - r->sph_r * r->sph_r, disc = b * b - a * c, q, t0,
           t1, t;
    int k;
    if (disc < 0.0) return 0;
    /* Stable roots: q = -(b + sign(b) sqrt(disc)); t = q / a and c / q. */
    q = -(b + (b >= 0.0 ? sqrt(disc) : -sqrt(disc)));
    if (q == 0.0) return 0;
    t0 = q / a;
    t1 = c / q;
    if (t0 > t1) {
        t = t0;
        t0 = t1;
        t1 = t;
    }
    t = t0 > r->eps ? t0 : t1;
    if (!(t > r->eps)) return 0;
    s->t = t;
    for (k = 0; k < 3; k++) s->n[k] = o[k] + t * d[k] - r->sph_c[k];
    if (!normalize3(s->n)) return 0;
    /* Put the point exactly on the sphere (its radius error would otherwise
     * accumulate along a chain). */
    for (k = 0; k < 3; k++) s->p[k] = r->sph_c[k] + r->sph_r * s->n[k];
    s->prim = 0;
    return 1;
}

/* Closest surface along o + t d, t > eps; skip: the mesh triangle the ray
 * starts on (a planar triangle cannot be hit again by a ray leaving it). */
static int scene_hit(const snell_ref *r, const double o[3], const double d[3], uint32_t skip, surf *s)
{
    snell__bvh_hit h;
    const uint32_t *tri;
    int k;
    if (r->analytic) return sphere_hit(r, o, d, s);
    if (!snell__bvh_closest(r->bvh, o, d, r->eps, HUGE_VAL, skip, &h)) return 0;
    tri = r->indices + 3 * (size_t)h.tri;
    s->t = h.t;
    s->prim = h.tri;
    for (k = 0; k < 3; k++) {
        s->p[k] = h.p[k];
        /* Barycentric interpolation of the world vertex normals, as the GPU
         * interpolates v_world_normal (perspective-correct = barycentric). */
        s->n[k] = h.b[0] * r->normals[3 * (size_t)tri[0] + k] + h.b[1] * r->normals[3 * (size_t)tri[1] + k] +
                  h.b[2] * r->normals[3 * (size_t)tri[2] + k];
    }
    if (!normalize3(s->n)) {
        /* Opposite vertex normals cancelled: fall back to the face normal. */
        const double *v = NULL;
        uint32_t i;
        for (i = 0; i < r->bvh->triangle_count; i++)
            if (r->bvh->tri_ids[i] == h.tri) {
                v = r->bvh->tri_verts + 9 * (size_t)i;
                break;
            }
        if (v) {
            double e1[3] = {v[3] - v[0], v[4] - v[1], v[5] - v[2]}, e2[3] = {v[6] - v[0], v[7] - v[1], v[8] - v[2]};
            s->n[0] = e1[1] * e2[2] - e1[2] * e2[1];
            s->n[1] = e1[2] * e2[0] - e1[0] * e2[2];
            s->n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        }
        if (!normalize3(s->n)) {
            s->n[0] = -d[0];
            s->n[1] = -d[1];
            s->n[2] = -d[2];
            normalize3(s->n);
        }
    }
    return 1;
}

/* ------------------------------------------------------------ the optics */

static void path_point(snell_ref_path *path, const double p[3], snell_ref_event ev)
{
    int i = path->interfaces;
    if (i >= SNELL_REF_MAX_INTERFACES) return; /* cannot happen: max_if <= SNELL_REF_MAX_INTERFACES */
    path->interfaces = i + 1;
    memcpy(path->points[i + 1], p, 3 * sizeof(double));
    path->events[i + 1] = ev;
}

/* Walks one path: MATCHED = always refract unless TIR and stop once out of the
 * glass; FULL = the branch of larger Fresnel weight at every interface. Fills
 * path (points, events, exit_dir, ended_inside, inside_length, fresnel) and the
 * first-surface reflection r1 and refraction t1 (for the MATCHED colour). */
static void walk(const snell_ref *r, const optics *op, const double o[3], const double d[3], snell_ref_path *path,
                 double r1[3], double t1[3])
{
    double pos[3], dir[3];
    uint32_t prim = SNELL__BVH_NONE;
    int inside = 0, k;
    surf s;
    memcpy(pos, o, sizeof pos);
    memcpy(dir, d, sizeof dir);
    for (;;) {
        double n[3], nd, n1, n2, F, out_dir[3];
        snell_ref_event ev;
        if (op->mode == SNELL_REF_MATCHED && path->interfaces > 0 && !inside) break; /* out: env lookup */
        if (!scene_hit(r, pos, dir, prim, &s)) break;
        if (path->interfaces == 0) path->hit = 1;
        if (inside) path->inside_length += s.t;
        if (path->interfaces >= op->max_if) break; /* cap: leaves in its current direction */
        memcpy(n, s.n, sizeof n);
        nd = dot3(n, dir);
        if (nd > 0.0) { /* face the incoming ray */
            n[0] = -n[0];
            n[1] = -n[1];
            n[2] = -n[2];
            nd = -nd;
        }
        n1 = inside ? op->ior : 1.0;
        n2 = inside ? 1.0 : op->ior;
        F = snell_optd_fresnel_schlick(-nd, n1, n2);
        if (!snell_optd_refract(dir, n, n1 / n2, out_dir)) {
            ev = SNELL_REF_EVENT_TIR;
        } else if (op->mode == SNELL_REF_FULL && F > 1.0 - F) {
            snell_optd_reflect(dir, n, out_dir);
            ev = SNELL_REF_EVENT_REFLECT;
        } else {
            ev = SNELL_REF_EVENT_REFRACT;
            inside = !inside;
        }
        if (path->interfaces == 0) {
            path->fresnel = F;
            snell_optd_reflect(dir, n, r1);
            normalize3(r1);
            if (!snell_optd_refract(dir, n, n1 / n2, t1)) memcpy(t1, r1, 3 * sizeof(double));
            normalize3(t1);
        }
        normalize3(out_dir);
        path_point(path, s.p, ev);
        memcpy(pos, s.p, sizeof pos);
        memcpy(dir, out_dir, sizeof dir);
        prim = s.prim;
    }
    for (k = 0; k < 3; k++) path->exit_dir[k] = dir[k];
    path->ended_inside = inside;
}

/* Distance from p along unit t to the exit of the bounding sphere (single.frag). */
static double bsphere_path(const snell_ref *r, const double p[3], const double t[3])
{
    double oc[3] = {p[0] - r->bs_c[0], p[1] - r->bs_c[1], p[2] - r->bs_c[2]};
    double b = dot3(oc, t), c = dot3(oc, oc) - r->bs_r * r->bs_r, disc = b * b - c, d;
    d = -b + sqrt(disc > 0.0 ? disc : 0.0);
    return d > 0.0 ? d : 0.0;
}

static void matched_colour(const snell_ref *r, const optics *op, const snell_ref_path *path, const double r1[3],
                           const double t1[3], double rgb[3])
{
    double refl[3], trans[3], dist, F = path->fresnel;
    int k;
    env_rgb(op, path->exit_dir, trans);
    if (!path->hit) {
        memcpy(rgb, trans, 3 * sizeof(double));
        return;
    }
    env_rgb(op, r1, refl);
    dist = op->absorb == SNELL_REF_ABSORB_BOUNDING_SPHERE ? bsphere_path(r, path->points[1], t1)
                                                          : path->inside_length;
    for (k = 0; k < 3; k++) {
        double T = op->has_sigma ? exp(-op->sigma[k] * dist) : 1.0;
        rgb[k] = F * refl[k] + (1.0 - F) * op->tint[k] * T * trans[k];
    }
}

/* FULL: Whitted recursion. w = throughput of this ray; adds its radiance
 * contribution to acc. depth = interfaces already processed on this branch. */
static void whitted(const snell_ref *r, const optics *op, const double o[3], const double d[3], uint32_t prim,
                    int inside, int depth, const double w_in[3], double acc[3])
{
    double w[3] = {w_in[0], w_in[1], w_in[2]}, n[3], nd, n1, n2, F, dir_r[3], dir_t[3], wmax, c[3];
    int k, tir;
    surf s;
    wmax = w[0] > w[1] ? (w[0] > w[2] ? w[0] : w[2]) : (w[1] > w[2] ? w[1] : w[2]);
    if (wmax < MIN_WEIGHT || !scene_hit(r, o, d, prim, &s)) {
        env_rgb(op, d, c);
        for (k = 0; k < 3; k++) acc[k] += w[k] * c[k];
        return;
    }
    if (inside && op->has_sigma)
        for (k = 0; k < 3; k++) w[k] *= exp(-op->sigma[k] * s.t);
    if (depth >= op->max_if) { /* cap: leaves in its current direction */
        env_rgb(op, d, c);
        for (k = 0; k < 3; k++) acc[k] += w[k] * c[k];
        return;
    }
    memcpy(n, s.n, sizeof n);
    nd = dot3(n, d);
    if (nd > 0.0) {
        n[0] = -n[0];
        n[1] = -n[1];
        n[2] = -n[2];
        nd = -nd;
    }
    n1 = inside ? op->ior : 1.0;
    n2 = inside ? 1.0 : op->ior;
    F = snell_optd_fresnel_schlick(-nd, n1, n2);
    tir = !snell_optd_refract(d, n, n1 / n2, dir_t);
    if (tir) F = 1.0;
    snell_optd_reflect(d, n, dir_r);
    normalize3(dir_r);
    if (F > 0.0) {
        double wr[3] = {w[0] * F, w[1] * F, w[2] * F};
        whitted(r, op, s.p, dir_r, s.prim, inside, depth + 1, wr, acc);
    }
    if (!tir && F < 1.0) {
        double wt[3];
        for (k = 0; k < 3; k++) wt[k] = w[k] * (1.0 - F) * (inside ? 1.0 : op->tint[k]);
        normalize3(dir_t);
        whitted(r, op, s.p, dir_t, s.prim, !inside, depth + 1, wt, acc);
    }
}

/* Traces one ray (unit d). want_path: the walk is needed (path outputs) even
 * in FULL mode, where the colour comes from the tree. */
static void trace(const snell_ref *r, const optics *op, const double o[3], const double d[3], int want_path,
                  snell_ref_path *path)
{
    double r1[3] = {0, 0, 0}, t1[3] = {0, 0, 0};
    path->hit = 0;
    path->interfaces = 0;
    memcpy(path->points[0], o, 3 * sizeof(double));
    path->events[0] = SNELL_REF_EVENT_EYE;
    path->ended_inside = 0;
    path->fresnel = 0.0;
    path->inside_length = 0.0;
    if (op->mode == SNELL_REF_MATCHED) {
        walk(r, op, o, d, path, r1, t1);
        matched_colour(r, op, path, r1, t1, path->rgb);
    } else {
        static const double one[3] = {1.0, 1.0, 1.0};
        path->rgb[0] = path->rgb[1] = path->rgb[2] = 0.0;
        whitted(r, op, o, d, SNELL__BVH_NONE, 0, 0, one, path->rgb);
        if (want_path) {
            walk(r, op, o, d, path, r1, t1);
        } else {
            memcpy(path->exit_dir, d, 3 * sizeof(double));
        }
    }
}

/* ------------------------------------------------------------ parameters */

static snell_status resolve(const snell_ref *ref, const snell_ref_params *p, optics *op)
{
    const snell_ctx *ctx = ref->ctx;
    const snell_glass_desc *g = &p->glass;
    int k;
    if (p->mode != SNELL_REF_MATCHED && p->mode != SNELL_REF_FULL)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: unknown mode %d", (int)p->mode);
    if (p->absorption_model != SNELL_REF_ABSORB_PATH && p->absorption_model != SNELL_REF_ABSORB_BOUNDING_SPHERE)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: unknown absorption model %d",
                           (int)p->absorption_model);
    if (p->max_interfaces < 0 || p->max_interfaces > SNELL_REF_MAX_INTERFACES)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: max_interfaces %d outside 0..%d",
                           p->max_interfaces, SNELL_REF_MAX_INTERFACES);
    if (!p->env && !p->env_fn)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: an environment (env or env_fn) is required");
    if (!p->env_fn && !p->env->faces[0])
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: the environment has no CPU faces");
    if (!(g->ior >= 0.0f) || !isfinite(g->ior))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: ior %g is not a positive number", (double)g->ior);
    memset(op, 0, sizeof *op);
    op->mode = p->mode;
    op->max_if = p->max_interfaces ? p->max_interfaces : 10;
    op->absorb = p->absorption_model;
    op->ior = g->ior > 0.0f ? (double)g->ior : 1.5;
    for (k = 0; k < 3; k++) {
        if (!(g->absorption[k] >= 0.0f) || !isfinite(g->absorption[k]) || !isfinite(g->tint[k]) || g->tint[k] < 0.0f)
            return snell__fail(ctx, SNELL_E_INVALID_ARG,
                               "reference: absorption and tint must be finite and non-negative");
        op->sigma[k] = g->absorption[k];
        if (op->sigma[k] > 0.0) op->has_sigma = 1;
    }
    if (g->tint[0] != 0.0f || g->tint[1] != 0.0f || g->tint[2] != 0.0f)
        for (k = 0; k < 3; k++) op->tint[k] = g->tint[k];
    else
        op->tint[0] = op->tint[1] = op->tint[2] = 1.0;
    op->env = p->env;
    op->env_fn = p->env_fn;
    op->env_user = p->env_user;
    return SNELL_OK;
}

/* ------------------------------------------------------------ camera rays */

typedef struct camera_rays {
    double eye[3], inv[16]; /* inverse of proj * view, column-major */
    int w, h;
} camera_rays;

/* Gauss-Jordan with partial pivoting; column-major in and out. */
static int invert4(const double m[16], double out[16])
{
    double a[4][8];
    int i, j, k;
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            a[i][j] = m[4 * j + i]; /* row i, column j */
            a[i][4 + j] = i == j ? 1.0 : 0.0;
        }
    for (k = 0; k < 4; k++) {
        int piv = k;
        double f;
        for (i = k + 1; i < 4; i++)
            if (fabs(a[i][k]) > fabs(a[piv][k])) piv = i;
        if (!(fabs(a[piv][k]) > 0.0) || !isfinite(a[piv][k])) return 0;
        if (piv != k)
            for (j = 0; j < 8; j++) {
                double t = a[k][j];
                a[k][j] = a[piv][j];
                a[piv][j] = t;
            }
        f = 1.0 / a[k][k];
        for (j = 0; j < 8; j++) a[k][j] *= f;
        for (i = 0; i < 4; i++)
            if (i != k) {
                double g = a[i][k];
                for (j = 0; j < 8; j++) a[i][j] -= g * a[k][j];
            }
    }
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) out[4 * j + i] = a[i][4 + j];
    for (i = 0; i < 16; i++)
        if (!isfinite(out[i])) return 0;
    return 1;
}

static snell_status camera_setup(const snell_ref *ref, const snell_ref_params *p, camera_rays *cr)
{
    float eye[3], view[16], proj[16];
    double vp[16];
    int i, j, k;
    if (p->width < 0 || p->height < 0)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "reference: negative image size %dx%d", p->width,
                           p->height);
    cr->w = p->width ? p->width : 512;
    cr->h = p->height ? p->height : 512;
    if (cr->w > SNELL_REF_MAX_SIZE || cr->h > SNELL_REF_MAX_SIZE)
        return snell__fail(ref->ctx, SNELL_E_LIMIT, "reference: image %dx%d exceeds %d pixels a side", cr->w, cr->h,
                           SNELL_REF_MAX_SIZE);
    snell_camera_matrices(&p->camera, (float)cr->w / (float)cr->h, eye, view, proj);
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            double s = 0.0;
            for (k = 0; k < 4; k++) s += (double)proj[4 * k + i] * (double)view[4 * j + k];
            vp[4 * j + i] = s;
        }
    for (k = 0; k < 3; k++) cr->eye[k] = eye[k];
    if (!invert4(vp, cr->inv) || !isfinite(cr->eye[0]) || !isfinite(cr->eye[1]) || !isfinite(cr->eye[2]))
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "reference: camera matrices are singular or not finite");
    return SNELL_OK;
}

static void unproject(const double inv[16], double x, double y, double z, double out[3])
{
    double v[4];
    int i;
    for (i = 0; i < 4; i++) v[i] = inv[i] * x + inv[4 + i] * y + inv[8 + i] * z + inv[12 + i];
    for (i = 0; i < 3; i++) out[i] = v[i] / v[3];
}

/* Ray through the centre of pixel (x, y), y = 0 the top row (GL's window row
 * h - 1 - y): direction from the near-plane point to the far-plane point. */
static void camera_ray(const camera_rays *cr, int x, int y, double dir[3])
{
    double nx = 2.0 * ((double)x + 0.5) / (double)cr->w - 1.0;
    double ny = 1.0 - 2.0 * ((double)y + 0.5) / (double)cr->h;
    double pn[3], pf[3];
    unproject(cr->inv, nx, ny, -1.0, pn);
    unproject(cr->inv, nx, ny, 1.0, pf);
    dir[0] = pf[0] - pn[0];
    dir[1] = pf[1] - pn[1];
    dir[2] = pf[2] - pn[2];
    normalize3(dir);
}

/* ------------------------------------------------------------ image loop */

typedef struct job {
    const snell_ref *ref;
    const optics *op;
    const camera_rays *cr;
    const snell_ref_output *out;
    pthread_mutex_t lock;
    int next_row;
} job;

static void render_row(job *jb, int y)
{
    const camera_rays *cr = jb->cr;
    const snell_ref_output *out = jb->out;
    int want_path = out->exit_dir || out->interfaces || out->hit;
    snell_ref_path path;
    int x, k;
    for (x = 0; x < cr->w; x++) {
        size_t i = (size_t)y * (size_t)cr->w + (size_t)x;
        double dir[3];
        camera_ray(cr, x, y, dir);
        trace(jb->ref, jb->op, cr->eye, dir, want_path, &path);
        for (k = 0; k < 3; k++) out->rgb[3 * i + k] = (float)path.rgb[k];
        if (out->exit_dir)
            for (k = 0; k < 3; k++) out->exit_dir[3 * i + k] = (float)path.exit_dir[k];
        if (out->interfaces) out->interfaces[i] = (uint8_t)path.interfaces;
        if (out->hit) out->hit[i] = (uint8_t)path.hit;
    }
}

/* Rows are handed out one at a time through a counter: the pixels do not
 * depend on which thread computes them, so the image is bitwise the same for
 * any thread count. */
static void *worker(void *arg)
{
    job *jb = (job *)arg;
    for (;;) {
        int y;
        pthread_mutex_lock(&jb->lock);
        y = jb->next_row++;
        pthread_mutex_unlock(&jb->lock);
        if (y >= jb->cr->h) break;
        render_row(jb, y);
    }
    return NULL;
}

snell_status snell_ref_render(const snell_ref *ref, const snell_ref_params *params, const snell_ref_output *out)
{
    optics op;
    camera_rays cr;
    job jb;
    pthread_t tids[SNELL_REF_MAX_THREADS];
    int nthreads, started = 0, i;
    snell_status st;
    if (!ref || !params || !out || !out->rgb)
        return snell__fail(ref ? ref->ctx : NULL, SNELL_E_INVALID_ARG,
                           "snell_ref_render: ref, params, out and out->rgb are required");
    if ((st = resolve(ref, params, &op)) != SNELL_OK) return st;
    if ((st = camera_setup(ref, params, &cr)) != SNELL_OK) return st;
    if (params->threads < 0)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_render: threads %d is negative",
                           params->threads);
    nthreads = params->threads;
    if (nthreads == 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        nthreads = n > 0 ? (int)(n < SNELL_REF_MAX_THREADS ? n : SNELL_REF_MAX_THREADS) : 1;
    }
    if (nthreads > SNELL_REF_MAX_THREADS) nthreads = SNELL_REF_MAX_THREADS;
    if (nthreads > cr.h) nthreads = cr.h;
    jb.ref = ref;
    jb.op = &op;
    jb.cr = &cr;
    jb.out = out;
    jb.next_row = 0;
    if (pthread_mutex_init(&jb.lock, NULL) != 0)
        return snell__fail(ref->ctx, SNELL_E_NOMEM, "snell_ref_render: cannot create a mutex");
    /* The calling thread is worker 0; if a thread cannot be started the others
     * (at least this one) simply take more rows. */
    for (i = 1; i < nthreads; i++) {
        if (pthread_create(&tids[started], NULL, worker, &jb) != 0) break;
        started++;
    }
    worker(&jb);
    for (i = 0; i < started; i++) pthread_join(tids[i], NULL);
    pthread_mutex_destroy(&jb.lock);
    return SNELL_OK;
}

void snell_ref_rgb_to_rgba8(const float *rgb, int width, int height, uint8_t *rgba)
{
    size_t i, n;
    if (!rgb || !rgba || width <= 0 || height <= 0) return;
    n = (size_t)width * (size_t)height;
    for (i = 0; i < n; i++) {
        int k;
        for (k = 0; k < 3; k++) {
            float v = rgb[3 * i + k];
            v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* also maps NaN to 0 */
            rgba[4 * i + k] = (uint8_t)(v * 255.0f + 0.5f);
        }
        rgba[4 * i + 3] = 255;
    }
}

/* ------------------------------------------------------------ light paths */

snell_status snell_ref_trace_ray(const snell_ref *ref, const snell_ref_params *params, const double org[3],
                                 const double dir[3], snell_ref_path *path)
{
    optics op;
    double d[3];
    snell_status st;
    int k;
    if (!ref || !params || !org || !dir || !path)
        return snell__fail(ref ? ref->ctx : NULL, SNELL_E_INVALID_ARG,
                           "snell_ref_trace_ray: ref, params, org, dir and path are required");
    if ((st = resolve(ref, params, &op)) != SNELL_OK) return st;
    for (k = 0; k < 3; k++) {
        if (!isfinite(org[k]) || !isfinite(dir[k]))
            return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_trace_ray: ray is not finite");
        d[k] = dir[k];
    }
    if (!normalize3(d)) return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_trace_ray: dir is zero");
    trace(ref, &op, org, d, 1, path);
    return SNELL_OK;
}

snell_status snell_ref_trace_pixel(const snell_ref *ref, const snell_ref_params *params, int x, int y,
                                   snell_ref_path *path)
{
    optics op;
    camera_rays cr;
    double d[3];
    snell_status st;
    if (!ref || !params || !path)
        return snell__fail(ref ? ref->ctx : NULL, SNELL_E_INVALID_ARG,
                           "snell_ref_trace_pixel: ref, params and path are required");
    if ((st = resolve(ref, params, &op)) != SNELL_OK) return st;
    if ((st = camera_setup(ref, params, &cr)) != SNELL_OK) return st;
    if (x < 0 || y < 0 || x >= cr.w || y >= cr.h)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_trace_pixel: pixel (%d, %d) outside %dx%d", x,
                           y, cr.w, cr.h);
    camera_ray(&cr, x, y, d);
    trace(ref, &op, cr.eye, d, 1, path);
    return SNELL_OK;
}

/* ------------------------------------------------------------ creation */

static snell_status ref_alloc(snell_ctx *ctx, snell_ref **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    snell_ref *r = (snell_ref *)snell__calloc(al, 1, sizeof *r);
    if (!r) return snell__fail(ctx, SNELL_E_NOMEM, "reference: out of memory");
    r->ctx = ctx;
    r->alloc = *al;
    *out = r;
    return SNELL_OK;
}

snell_status snell_ref_create(snell_ctx *ctx, const snell_ref_desc *desc, snell_ref **out)
{
    const snell_mesh *m;
    snell_ref *r = NULL;
    snell_status st;
    double M[16], N[9], c[3], s = 0.0;
    uint32_t i;
    int k;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: out is NULL");
    *out = NULL;
    if (!desc || !desc->mesh) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: desc->mesh is required");
    m = desc->mesh;
    if (!m->triangle_count || !m->positions || !m->normals || !m->indices)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: mesh has no triangles");
    if ((st = ref_alloc(ctx, &r)) != SNELL_OK) return st;
    if ((st = snell__bvh_build_mesh(ctx, m, desc->model, &r->bvh)) != SNELL_OK) { /* validates model */
        snell_ref_destroy(r);
        return st;
    }
    for (k = 0; k < 16; k++) M[k] = desc->model ? (double)desc->model[k] : (k % 5 == 0 ? 1.0 : 0.0);
    {
        /* N = inverse-transpose of the 3x3 = cofactor matrix / det (column-major). */
        double a = M[0], b = M[4], cc = M[8], d = M[1], e = M[5], f = M[9], g = M[2], h = M[6], ii = M[10];
        double det = a * (e * ii - f * h) - b * (d * ii - f * g) + cc * (d * h - e * g);
        /* N[col*3+row] = cof(row, col) / det, where cof is of the row-major A. */
        N[0] = (e * ii - f * h) / det;
        N[3] = -(d * ii - f * g) / det;
        N[6] = (d * h - e * g) / det;
        N[1] = -(b * ii - cc * h) / det;
        N[4] = (a * ii - cc * g) / det;
        N[7] = -(a * h - b * g) / det;
        N[2] = (b * f - cc * e) / det;
        N[5] = -(a * f - cc * d) / det;
        N[8] = (a * e - b * d) / det;
    }
    r->normals = (double *)snell__calloc(&r->alloc, 3 * (size_t)m->vertex_count, sizeof(double));
    r->indices = (uint32_t *)snell__calloc(&r->alloc, 3 * (size_t)m->triangle_count, sizeof(uint32_t));
    if (!r->normals || !r->indices) {
        snell_ref_destroy(r);
        return snell__fail(ctx, SNELL_E_NOMEM, "snell_ref_create: out of memory");
    }
    memcpy(r->indices, m->indices, 3 * (size_t)m->triangle_count * sizeof(uint32_t));
    for (i = 0; i < m->vertex_count; i++) {
        const float *n = m->normals + 3 * (size_t)i;
        for (k = 0; k < 3; k++) r->normals[3 * (size_t)i + k] = N[k] * n[0] + N[3 + k] * n[1] + N[6 + k] * n[2];
    }
    /* Bounding sphere as renderer.c uses it for single.frag: the mesh's own radius. */
    for (k = 0; k < 3; k++) c[k] = 0.5 * ((double)m->bmin[k] + (double)m->bmax[k]);
    for (k = 0; k < 3; k++) {
        double len = sqrt(M[4 * k] * M[4 * k] + M[4 * k + 1] * M[4 * k + 1] + M[4 * k + 2] * M[4 * k + 2]);
        if (len > s) s = len;
    }
    for (k = 0; k < 3; k++) r->bs_c[k] = M[k] * c[0] + M[4 + k] * c[1] + M[8 + k] * c[2] + M[12 + k];
    r->bs_r = (double)m->bradius * s;
    {
        /* Ray epsilon: far above the rounding of hit points (~1e-16 of the
         * coordinates), far below any feature of a sane mesh. */
        double ext = 0.0;
        for (k = 0; k < 3; k++) {
            double e = fabs(r->bvh->bmin[k]) > fabs(r->bvh->bmax[k]) ? fabs(r->bvh->bmin[k]) : fabs(r->bvh->bmax[k]);
            if (e > ext) ext = e;
        }
        r->eps = 1e-9 * (ext > 0.0 ? ext : 1.0);
    }
    *out = r;
    return SNELL_OK;
}

snell_status snell__ref_create_sphere(snell_ctx *ctx, const double centre[3], double radius, snell_ref **out)
{
    snell_ref *r = NULL;
    snell_status st;
    int k;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference sphere: out is NULL");
    *out = NULL;
    if (!centre || !(radius > 0.0) || !isfinite(radius) || !isfinite(centre[0]) || !isfinite(centre[1]) ||
        !isfinite(centre[2]))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference sphere: centre and positive radius required");
    if ((st = ref_alloc(ctx, &r)) != SNELL_OK) return st;
    r->analytic = 1;
    for (k = 0; k < 3; k++) r->sph_c[k] = r->bs_c[k] = centre[k];
    r->sph_r = r->bs_r = radius;
    r->eps = 1e-9 * (radius + fabs(centre[0]) + fabs(centre[1]) + fabs(centre[2]));
    *out = r;
    return SNELL_OK;
}

void snell_ref_bounding_sphere(const snell_ref *ref, double centre[3], double *radius)
{
    int k;
    for (k = 0; k < 3; k++)
        if (centre) centre[k] = ref ? ref->bs_c[k] : 0.0;
    if (radius) *radius = ref ? ref->bs_r : 0.0;
}

void snell_ref_destroy(snell_ref *ref)
{
    snell_alloc al;
    if (!ref) return;
    al = ref->alloc;
    snell__bvh_destroy(ref->bvh);
    snell__free(&al, ref->normals);
    snell__free(&al, ref->indices);
    snell__free(&al, ref);
}
