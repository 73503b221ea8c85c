/* SPDX-License-Identifier: MIT */
/* lm2d_trace.c — light tracing through the 2D scene (Brückner 6.4, 6.2.1.2)
 * with per-ray deterministic RNG, Russian roulette and energy bookkeeping. */
#define _POSIX_C_SOURCE 200809L
#include "lm2d/lm2d_trace.h"

#include "core/optics.h"

#include <math.h>
#include <pthread.h>
#include <string.h>

#define PI_F 3.14159265358979323846f
#define RR_MIN_WEIGHT 1e-3f /* below this fraction of the emitted flux, roulette on weight */

/* ------------------------------------------------------------------- RNG */
/* splitmix64 hashes (seed, pass, light, ray) into a per-ray PCG32 state, so a
 * ray's random numbers do not depend on which thread traces it. */
static uint64_t splitmix(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

typedef struct rng {
    uint64_t s;
} rng;

static inline float rng_next(rng *r)
{
    uint64_t old = r->s;
    uint32_t xs, rot, v;
    r->s = old * 6364136223846793005ull + 1442695040888963407ull;
    xs = (uint32_t)(((old >> 18) ^ old) >> 27);
    rot = (uint32_t)(old >> 59);
    v = (xs >> rot) | (xs << ((32u - rot) & 31u));
    return (float)(v >> 8) * (1.0f / 16777216.0f); /* [0,1) */
}

/* ---------------------------------------------------------------- helpers */
int lm2d_clip(const float lo[2], const float hi[2], const float o[2], const float d[2], float t_end, float *ta,
              float *tb)
{
    float a = 0.0f, b = t_end;
    int k;
    for (k = 0; k < 2; k++) {
        if (d[k] == 0.0f) {
            if (o[k] < lo[k] || o[k] > hi[k]) return 0;
        } else {
            float inv = 1.0f / d[k], t0 = (lo[k] - o[k]) * inv, t1 = (hi[k] - o[k]) * inv;
            if (t0 > t1) {
                float t = t0;
                t0 = t1;
                t1 = t;
            }
            if (t0 > a) a = t0;
            if (t1 < b) b = t1;
        }
    }
    if (!(a < b)) return 0;
    *ta = a;
    *tb = b;
    return 1;
}

static inline float sum3(const float w[3]) { return w[0] + w[1] + w[2]; }
static inline float max3(const float w[3])
{
    float m = w[0] > w[1] ? w[0] : w[1];
    return m > w[2] ? m : w[2];
}

typedef struct tracer {
    const lm2d_trace_params *p;
    lm2d_path *out;
    size_t n, cap;
    lm2d_energy *e;
} tracer;

/* Stores the part of o..o+t_end*d inside the view, flux w0 at t=0 and w1 at t_end. */
static void emit(tracer *tr, const float o[2], const float d[2], float t_end, const float w0[3], const float w1[3])
{
    float ta, tb;
    lm2d_path *q;
    int k;
    if (!lm2d_clip(tr->p->view_lo, tr->p->view_hi, o, d, t_end, &ta, &tb)) return;
    if (tr->n >= tr->cap) return; /* cannot happen with the documented capacity */
    q = &tr->out[tr->n++];
    q->x0 = o[0] + ta * d[0];
    q->y0 = o[1] + ta * d[1];
    q->x1 = o[0] + tb * d[0];
    q->y1 = o[1] + tb * d[1];
    if (isinf(t_end)) {
        for (k = 0; k < 3; k++) q->c0[k] = q->c1[k] = w0[k];
    } else {
        float fa = ta / t_end, fb = tb / t_end;
        for (k = 0; k < 3; k++) {
            q->c0[k] = w0[k] + (w1[k] - w0[k]) * fa;
            q->c1[k] = w0[k] + (w1[k] - w0[k]) * fb;
        }
    }
}

/* Russian roulette on a throughput factor f (rgb, each <= 1 after scaling):
 * survive with p = max(f); survivors carry w * f / p, so no component ever grows.
 * Returns 0 if the ray dies. */
static int roulette(tracer *tr, rng *r, float w[3], const float f[3])
{
    float before[3], p = max3(f);
    int k;
    for (k = 0; k < 3; k++) before[k] = w[k];
    for (k = 0; k < 3; k++) w[k] *= f[k];
    tr->e->absorbed += (double)(sum3(before) - sum3(w));
    if (p >= 1.0f) return 1;
    if (p <= 0.0f || rng_next(r) >= p) {
        tr->e->rr_killed += (double)sum3(w);
        return 0;
    }
    before[0] = sum3(w);
    for (k = 0; k < 3; k++) w[k] /= p;
    tr->e->rr_gained += (double)(sum3(w) - before[0]);
    return 1;
}

static inline void v2_from_angle(float a, float v[2])
{
    v[0] = cosf(a);
    v[1] = sinf(a);
}

/* z = 0 wrappers so 2D uses the one optics kernel (src/core/optics.h). */
static inline void reflect2(const float i[2], const float n[2], float r[2])
{
    float i3[3] = {i[0], i[1], 0.0f}, n3[3] = {n[0], n[1], 0.0f}, r3[3];
    snell_opt_reflect(i3, n3, r3);
    r[0] = r3[0];
    r[1] = r3[1];
}

static inline int refract2(const float i[2], const float n[2], float eta, float t[2])
{
    float i3[3] = {i[0], i[1], 0.0f}, n3[3] = {n[0], n[1], 0.0f}, t3[3];
    int ok = snell_opt_refract(i3, n3, eta, t3);
    float l = sqrtf(t3[0] * t3[0] + t3[1] * t3[1]);
    t[0] = t3[0] / l;
    t[1] = t3[1] / l;
    return ok;
}

static inline float dot2(const float a[2], const float b[2]) { return a[0] * b[0] + a[1] * b[1]; }

/* BRDF sample (eq. 6.1): uniform angle within +-d*pi/2 of the mirror direction
 * r about the facing shading normal nf; the lobe is turned so it stays within
 * +-pi/2 of nf (Abb. 6.6). */
static void sample_brdf(rng *r, const float dir[2], const float nf[2], float diffuse, float out[2])
{
    float m[2], phi, dh = diffuse * 0.5f * PI_F, lim = 0.5f * PI_F - dh, a;
    reflect2(dir, nf, m);
    if (diffuse <= 0.0f) {
        out[0] = m[0];
        out[1] = m[1];
        return;
    }
    phi = atan2f(nf[0] * m[1] - nf[1] * m[0], dot2(nf, m)); /* angle of m from nf */
    if (phi > lim) phi = lim;
    if (phi < -lim) phi = -lim;
    phi += (2.0f * rng_next(r) - 1.0f) * dh;
    a = atan2f(nf[1], nf[0]) + phi;
    v2_from_angle(a, out);
}

static inline void grow(lm2d_energy *e, const float p[2])
{
    if (p[0] < e->lo[0]) e->lo[0] = p[0];
    if (p[1] < e->lo[1]) e->lo[1] = p[1];
    if (p[0] > e->hi[0]) e->hi[0] = p[0];
    if (p[1] > e->hi[1]) e->hi[1] = p[1];
}

static void trace_one(tracer *tr, rng *r, float o[2], float d[2], float w[3])
{
    const lm2d_trace_params *p = tr->p;
    const snell_scene2d *sc = p->scene;
    const lm2d_bvh *bvh = &sc->bvh;
    /* New rays start a hair off the surface on the side they leave to (and skip
     * the edge they left): a fixed t_min instead would miss a neighbouring edge
     * met within t_min, e.g. near a corner, and leak light through it. */
    float lift = 1e-6f * ((bvh->hi[0] - bvh->lo[0]) + (bvh->hi[1] - bvh->lo[1])), t_min = 0.0f;
    float w_floor = RR_MIN_WEIGHT * max3(w);
    int skip = -1, medium = -1, bounce = 0;
    tr->e->emitted += (double)sum3(w);
    grow(tr->e, o);
    for (;;) {
        float t = INFINITY, pt[2], w1[3], ng[2], ns[2], nf[2], ngf[2], nd[2], s, ex, ey, l2, cosi;
        int hit = -1, k, front;
        const lm2d_edge *ed;
        const snell_material2d *m;
        float tb_a, tb_b;
        /* the ray can reach neither geometry nor display: stop without traversal */
        if (bvh->n_prims > 0 && lm2d_clip(bvh->lo, bvh->hi, o, d, INFINITY, &tb_a, &tb_b))
            hit = lm2d_bvh_intersect(bvh, o, d, t_min, &t, skip);
        if (hit < 0) {
            emit(tr, o, d, INFINITY, w, w);
            tr->e->escaped += (double)sum3(w);
            tr->e->unbounded = 1;
            return;
        }
        pt[0] = o[0] + t * d[0];
        pt[1] = o[1] + t * d[1];
        grow(tr->e, pt);
        for (k = 0; k < 3; k++) w1[k] = w[k];
        if (medium >= 0 && sc->objs[medium].mat.opaqueness > 0.0f) {
            /* Beer-Lambert inside the object (shared kernel) */
            float sig = sc->objs[medium].mat.opaqueness, sig3[3] = {sig, sig, sig}, att[3];
            snell_opt_beer_lambert(sig3, t, att);
            for (k = 0; k < 3; k++) w1[k] = w[k] * att[k];
            tr->e->absorbed += (double)(sum3(w) - sum3(w1));
        }
        emit(tr, o, d, t, w, w1);
        for (k = 0; k < 3; k++) w[k] = w1[k];
        if (bounce >= p->max_bounces) {
            tr->e->capped += (double)sum3(w);
            return;
        }
        bounce++;
        ed = &sc->edges[hit];
        m = &sc->objs[ed->obj].mat;
        ng[0] = ed->ng[0];
        ng[1] = ed->ng[1];
        /* interpolated point normal at the hit (6.2.1.1, Abb. 6.3) */
        ex = ed->p2[0] - ed->p1[0];
        ey = ed->p2[1] - ed->p1[1];
        l2 = ex * ex + ey * ey;
        s = ((pt[0] - ed->p1[0]) * ex + (pt[1] - ed->p1[1]) * ey) / l2;
        s = s < 0.0f ? 0.0f : (s > 1.0f ? 1.0f : s);
        ns[0] = ed->n1[0] + (ed->n2[0] - ed->n1[0]) * s;
        ns[1] = ed->n1[1] + (ed->n2[1] - ed->n1[1]) * s;
        {
            float l = sqrtf(dot2(ns, ns));
            ns[0] /= l;
            ns[1] /= l;
        }
        front = dot2(d, ng) < 0.0f; /* arriving from outside the object */
        for (k = 0; k < 2; k++) {
            ngf[k] = front ? ng[k] : -ng[k];
            nf[k] = front ? ns[k] : -ns[k];
        }
        if (dot2(d, nf) >= 0.0f) { /* shading normal faces away from the ray: use the edge normal */
            nf[0] = ngf[0];
            nf[1] = ngf[1];
        }
        cosi = -dot2(d, nf);
        /* from outside, t splits BTDF/BRDF; from inside a transmissive object the
         * ray can only leave or reflect internally; an opaque object reflects on
         * both sides (a light placed inside one stays inside) */
        if (front ? rng_next(r) < m->transmission : m->transmission > 0.0f) {
            /* BTDF (6.4.2.2 with refraction): Fresnel decides reflect / transmit */
            float n1 = front ? 1.0f : m->ior, n2 = front ? m->ior : 1.0f;
            float F = m->ior != 1.0f ? snell_opt_fresnel_schlick(cosi, n1, n2) : 0.0f;
            if (F > 0.0f && rng_next(r) < F) {
                reflect2(d, nf, nd);
                if (dot2(nd, ngf) <= 0.0f) reflect2(d, ngf, nd);
            } else {
                if (m->ior != 1.0f) {
                    if (!refract2(d, nf, n1 / n2, nd) || dot2(nd, ngf) >= 0.0f) {
                        if (!refract2(d, ngf, n1 / n2, nd)) reflect2(d, ngf, nd);
                    }
                } else {
                    nd[0] = d[0];
                    nd[1] = d[1];
                }
                if (dot2(nd, ngf) < 0.0f) medium = front ? ed->obj : -1;
                if (front && !roulette(tr, r, w, m->color)) return; /* tint once, on entry */
            }
        } else {
            /* BRDF (eq. 6.1): absorb a, tint, scatter within the lobe */
            float f[3];
            for (k = 0; k < 3; k++) f[k] = (1.0f - m->absorption) * m->color[k];
            if (!roulette(tr, r, w, f)) return;
            sample_brdf(r, d, nf, m->diffuse, nd);
            if (dot2(nd, ngf) <= 0.0f) { /* 6.4.1.4.2: never scatter into the object */
                float c = 2.0f * dot2(nd, ngf);
                nd[0] -= c * ngf[0];
                nd[1] -= c * ngf[1];
            }
        }
        /* weight roulette keeps faint rays from running to the bounce cap */
        if (max3(w) < w_floor) {
            float q = max3(w) / w_floor, f[3] = {q, q, q}, keep[3];
            for (k = 0; k < 3; k++) keep[k] = w[k];
            if (rng_next(r) >= q) {
                tr->e->rr_killed += (double)sum3(w);
                return;
            }
            for (k = 0; k < 3; k++) w[k] = keep[k] / f[k];
            tr->e->rr_gained += (double)(sum3(w) - sum3(keep));
        }
        {
            float side = dot2(nd, ng) > 0.0f ? lift : -lift;
            o[0] = pt[0] + side * ng[0];
            o[1] = pt[1] + side * ng[1];
        }
        d[0] = nd[0];
        d[1] = nd[1];
        skip = hit;
    }
}

size_t lm2d_trace_rays(const lm2d_trace_params *p, int li, int r0, int r1, lm2d_path *out, size_t cap,
                       lm2d_energy *e)
{
    const snell_light2d_desc *L = &p->scene->lights[li].d;
    tracer tr;
    int i;
    float flux[3], ex = L->end[0] - L->position[0], ey = L->end[1] - L->position[1];
    float inv_n = 1.0f / (float)L->rays;
    float bar_n = 0.0f, sin_half = sinf(0.5f * L->spread);
    tr.p = p;
    tr.out = out;
    tr.n = 0;
    tr.cap = cap;
    tr.e = e;
    for (i = 0; i < 3; i++) flux[i] = L->power * L->color[i] * inv_n;
    if (L->type == SNELL_LIGHT2D_BAR) bar_n = atan2f(-ex, ey); /* angle of (ey, -ex) */
    for (i = r0; i < r1; i++) {
        rng r;
        float o[2], d[2], w[3], u;
        r.s = splitmix(splitmix(splitmix(p->seed) ^ ((uint64_t)p->pass << 32 | (uint32_t)li)) ^ (uint64_t)i);
        u = ((float)i + rng_next(&r)) * inv_n; /* stratified position in [0,1) */
        switch (L->type) {
        case SNELL_LIGHT2D_POINT:
            o[0] = L->position[0];
            o[1] = L->position[1];
            v2_from_angle(L->direction - 0.5f * L->spread + u * L->spread, d);
            break;
        case SNELL_LIGHT2D_BAR: {
            /* Lambertian emitter: sin(angle) uniform gives intensity ~ cos (2D) */
            float a = bar_n + asinf((2.0f * rng_next(&r) - 1.0f) * sin_half);
            if (L->two_sided && rng_next(&r) < 0.5f) a += PI_F;
            o[0] = L->position[0] + u * ex;
            o[1] = L->position[1] + u * ey;
            v2_from_angle(a, d);
            break;
        }
        default:
            o[0] = L->position[0] + u * ex;
            o[1] = L->position[1] + u * ey;
            v2_from_angle(L->direction, d);
            break;
        }
        w[0] = flux[0];
        w[1] = flux[1];
        w[2] = flux[2];
        trace_one(&tr, &r, o, d, w);
    }
    return tr.n;
}

/* ------------------------------------------------------------------ pool */
struct lm2d_pool {
    const snell_alloc *al;
    pthread_t *threads;
    int n;               /* total including the caller */
    pthread_mutex_t mu;
    pthread_cond_t go, done;
    unsigned gen;
    int pending, quit;
    lm2d_pool_fn fn;
    void *arg;
};

typedef struct worker_arg {
    lm2d_pool *pool;
    int index;
} worker_arg;

static void *worker(void *a)
{
    worker_arg *wa = (worker_arg *)a;
    lm2d_pool *pool = wa->pool;
    int index = wa->index;
    unsigned seen = 0;
    for (;;) {
        lm2d_pool_fn fn;
        void *arg;
        pthread_mutex_lock(&pool->mu);
        while (pool->gen == seen && !pool->quit) pthread_cond_wait(&pool->go, &pool->mu);
        if (pool->quit) {
            pthread_mutex_unlock(&pool->mu);
            return NULL;
        }
        seen = pool->gen;
        fn = pool->fn;
        arg = pool->arg;
        pthread_mutex_unlock(&pool->mu);
        fn(index, pool->n, arg);
        pthread_mutex_lock(&pool->mu);
        if (--pool->pending == 0) pthread_cond_signal(&pool->done);
        pthread_mutex_unlock(&pool->mu);
    }
}

snell_status lm2d_pool_create(const snell_ctx *ctx, const snell_alloc *al, int threads, lm2d_pool **out)
{
    lm2d_pool *pool;
    worker_arg *args;
    int i;
    *out = NULL;
    if (threads < 1) threads = 1;
    if (threads > 256) threads = 256;
    pool = (lm2d_pool *)snell__calloc(al, 1, sizeof *pool + (size_t)threads * sizeof(worker_arg));
    if (!pool) return snell__fail(ctx, SNELL_E_NOMEM, "lightmap2d: out of memory for the thread pool");
    pool->al = al;
    pool->n = threads;
    args = (worker_arg *)(pool + 1);
    pool->threads = (pthread_t *)snell__calloc(al, (size_t)threads, sizeof(pthread_t));
    if (!pool->threads) {
        snell__free(al, pool);
        return snell__fail(ctx, SNELL_E_NOMEM, "lightmap2d: out of memory for the thread pool");
    }
    pthread_mutex_init(&pool->mu, NULL);
    pthread_cond_init(&pool->go, NULL);
    pthread_cond_init(&pool->done, NULL);
    for (i = 1; i < threads; i++) {
        args[i].pool = pool;
        args[i].index = i;
        if (pthread_create(&pool->threads[i], NULL, worker, &args[i]) != 0) {
            pool->n = i; /* run with the threads we have */
            break;
        }
    }
    *out = pool;
    return SNELL_OK;
}

int lm2d_pool_size(const lm2d_pool *pool) { return pool ? pool->n : 1; }

void lm2d_pool_run(lm2d_pool *pool, lm2d_pool_fn fn, void *arg)
{
    if (pool->n == 1) {
        fn(0, 1, arg);
        return;
    }
    pthread_mutex_lock(&pool->mu);
    pool->fn = fn;
    pool->arg = arg;
    pool->pending = pool->n - 1;
    pool->gen++;
    pthread_cond_broadcast(&pool->go);
    pthread_mutex_unlock(&pool->mu);
    fn(0, pool->n, arg);
    pthread_mutex_lock(&pool->mu);
    while (pool->pending > 0) pthread_cond_wait(&pool->done, &pool->mu);
    pthread_mutex_unlock(&pool->mu);
}

void lm2d_pool_destroy(lm2d_pool *pool)
{
    int i;
    if (!pool) return;
    pthread_mutex_lock(&pool->mu);
    pool->quit = 1;
    pthread_cond_broadcast(&pool->go);
    pthread_mutex_unlock(&pool->mu);
    for (i = 1; i < pool->n; i++) pthread_join(pool->threads[i], NULL);
    pthread_mutex_destroy(&pool->mu);
    pthread_cond_destroy(&pool->go);
    pthread_cond_destroy(&pool->done);
    snell__free(pool->al, pool->threads);
    snell__free(pool->al, pool);
}
