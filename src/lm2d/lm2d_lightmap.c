/* SPDX-License-Identifier: MIT */
/* lm2d_lightmap.c — the public lightmap object: decides per frame what must be
 * traced (changed lights, lights whose paths a moved object can touch, or one
 * more progressive pass), runs the tracer on the pool and rasterises (GL lines,
 * or the exact CPU rasteriser on the same pool, chosen once at creation). */
#define _POSIX_C_SOURCE 200809L
#include "lm2d/lm2d_raster.h"

#include "core/ctx.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

typedef struct light_state {
    lm2d_path *paths;
    size_t n, cap;
    unsigned version;         /* scene light version these paths belong to; 0 = none */
    int rays;
    lm2d_energy e;            /* bookkeeping of the last trace */
} light_state;

typedef struct slice {
    size_t n;
    lm2d_energy e;
} slice;

struct snell_lightmap2d {
    snell_ctx *ctx;
    const snell_alloc *al;
    snell_lightmap2d_desc d;
    lm2d_raster_view view;
    lm2d_raster_view cpu_view; /* the same with y flipped: the CPU image is stored bottom row first, as GL */
    lm2d_gl *gl;              /* GL target (texture); NULL without GL */
    snell_raster2d raster;    /* resolved: GL or CPU */
    char raster_reason[SNELL_REASON_SIZE];
    lm2d_pool *pool;
    light_state *ls;
    int n_ls;
    unsigned geom_version;
    int traced_once;
    int passes;
    uint32_t pass;
    float *cpu;               /* CPU accumulation (sum, or product for SCREEN; LM2D_RASTER_PX floats a
                                 pixel, bottom row first: the GL texture's layout); exact scratch for GL */
    /* job for the pool */
    const snell_scene2d *scene;
    int *todo;
    int n_todo;
    slice *slices;            /* n_ls * threads */
    lm2d_raster_src *src;     /* n_ls: the CPU rasteriser's segment lists */
    lm2d_raster_bins *bins;   /* its scratch */
    lm2d_energy frame_e;      /* bookkeeping of the last traced frame, all lights */
    size_t image_bytes;       /* the CPU image and, with GL, the texture and its readback */
};


static void energy_reset(lm2d_energy *e)
{
    memset(e, 0, sizeof *e);
    e->lo[0] = e->lo[1] = FLT_MAX;
    e->hi[0] = e->hi[1] = -FLT_MAX;
}

static void energy_add(lm2d_energy *a, const lm2d_energy *b)
{
    a->emitted += b->emitted;
    a->absorbed += b->absorbed;
    a->escaped += b->escaped;
    a->capped += b->capped;
    a->rr_killed += b->rr_killed;
    a->rr_gained += b->rr_gained;
    if (b->lo[0] < a->lo[0]) a->lo[0] = b->lo[0];
    if (b->lo[1] < a->lo[1]) a->lo[1] = b->lo[1];
    if (b->hi[0] > a->hi[0]) a->hi[0] = b->hi[0];
    if (b->hi[1] > a->hi[1]) a->hi[1] = b->hi[1];
    a->unbounded |= b->unbounded;
}

/* GL lines draw the lightmap (else the CPU rasteriser does; lm->gl may still
 * hold the texture it is uploaded to). */
static int use_gl(const snell_lightmap2d *lm) { return lm->raster == SNELL_RASTER2D_GL; }

snell_raster2d lm2d_raster_pick(snell_raster2d want, int have_gl, const char *renderer, char *reason,
                                size_t reason_size)
{
    const char *soft;
    if (want == SNELL_RASTER2D_GL || want == SNELL_RASTER2D_CPU) {
        snprintf(reason, reason_size, "%s requested", want == SNELL_RASTER2D_GL ? "GL lines" : "CPU rasteriser");
        return want;
    }
    if (!have_gl) {
        snprintf(reason, reason_size, "auto: no GL (ctx NULL or cpu_only): CPU rasteriser");
        return SNELL_RASTER2D_CPU;
    }
    if ((soft = snell__software_rasteriser(renderer)) != NULL) {
        snprintf(reason, reason_size,
                 "auto: renderer '%.60s' is software GL (%s: lines set up serially): CPU rasteriser", renderer, soft);
        return SNELL_RASTER2D_CPU;
    }
    snprintf(reason, reason_size, "auto: renderer '%.80s' is not a software rasteriser: GL lines",
             renderer ? renderer : "?");
    return SNELL_RASTER2D_GL;
}

/* Linear accumulation (progressive passes averaged) only for plain sums in
 * float; SCREEN is nonlinear and the fixed-point fallback is pre-exposed. */
static int linear_accum(const snell_lightmap2d *lm)
{
    if (lm->d.blend != SNELL_BLEND2D_ADD) return 0;
    if (use_gl(lm)) {
        snell_format2d f = lm2d_gl_format(lm->gl);
        return f == SNELL_FORMAT2D_RGBA32F || f == SNELL_FORMAT2D_RGBA16F;
    }
    return 1;
}

snell_status snell_lightmap2d_create(snell_ctx *ctx, const snell_lightmap2d_desc *desc, snell_lightmap2d **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    snell_lightmap2d *lm;
    snell_lightmap2d_desc d;
    snell_status st;
    int threads;
    size_t px;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_lightmap2d_create: out is NULL");
    *out = NULL;
    memset(&d, 0, sizeof d);
    if (desc) d = *desc;
    if (d.width == 0) d.width = 512;
    if (d.height == 0) d.height = 512;
    if (d.width < 1 || d.height < 1 || d.width > 16384 || d.height > 16384)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_lightmap2d_create: size %dx%d outside [1,16384]", d.width,
                           d.height);
    if (d.view_min[0] == 0.0f && d.view_min[1] == 0.0f && d.view_max[0] == 0.0f && d.view_max[1] == 0.0f) {
        d.view_max[0] = (float)d.width;
        d.view_max[1] = (float)d.height;
    }
    if (!(d.view_max[0] > d.view_min[0]) || !(d.view_max[1] > d.view_min[1]) || !isfinite(d.view_min[0]) ||
        !isfinite(d.view_min[1]) || !isfinite(d.view_max[0]) || !isfinite(d.view_max[1]))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_lightmap2d_create: empty or non-finite view rectangle");
    if (d.max_bounces == 0) d.max_bounces = 8;
    if (d.max_bounces < 0) d.max_bounces = 0;
    if (d.max_bounces > 1000)
        return snell__fail(ctx, SNELL_E_LIMIT, "snell_lightmap2d_create: max_bounces %d > 1000", d.max_bounces);
    if (d.exposure == 0.0f) d.exposure = 1.0f;
    if (!(d.exposure > 0.0f) || !isfinite(d.exposure))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_lightmap2d_create: exposure must be > 0");
    if ((unsigned)d.blend > SNELL_BLEND2D_SCREEN || (unsigned)d.format > SNELL_FORMAT2D_RGBA8 ||
        (unsigned)d.raster > SNELL_RASTER2D_CPU)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_lightmap2d_create: unknown blend, format or raster");
    if (d.raster == SNELL_RASTER2D_GL && (!ctx || d.cpu_only))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_lightmap2d_create: raster GL needs a ctx and cpu_only = 0");
    threads = d.threads;
    if (threads <= 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        threads = n > 0 ? (int)n : 1;
    }
    if (threads > 256) threads = 256;
    lm = (snell_lightmap2d *)snell__calloc(al, 1, sizeof *lm);
    if (!lm) return snell__fail(ctx, SNELL_E_NOMEM, "snell_lightmap2d_create: out of memory");
    lm->ctx = ctx;
    lm->al = al;
    lm->d = d;
    lm->view.width = d.width;
    lm->view.height = d.height;
    lm->view.lo[0] = d.view_min[0];
    lm->view.lo[1] = d.view_min[1];
    lm->view.hi[0] = d.view_max[0];
    lm->view.hi[1] = d.view_max[1];
    lm->cpu_view = lm->view;
    lm->cpu_view.lo[1] = d.view_max[1];
    lm->cpu_view.hi[1] = d.view_min[1];
    px = (size_t)d.width * (size_t)d.height;
    /* 16 bytes a pixel each: the CPU image, and with GL the texture (at most
     * RGBA32F) and the readback the first read allocates */
    lm->image_bytes = px * LM2D_RASTER_PX * sizeof(float) * (ctx && !d.cpu_only ? 3 : 1);
    {
        char what[96];
        snprintf(what, sizeof what, "lightmap2d: a %dx%d lightmap", d.width, d.height);
        if ((st = snell__budget_check(ctx, lm->image_bytes, what)) != SNELL_OK) {
            snell__free(al, lm);
            return st;
        }
    }
    lm->cpu = (float *)snell__calloc(al, px, LM2D_RASTER_PX * sizeof(float));
    if (!lm->cpu) {
        snell__free(al, lm);
        return snell__fail(ctx, SNELL_E_NOMEM, "snell_lightmap2d_create: out of memory for %dx%d", d.width, d.height);
    }
    snell__ctx_retain(ctx); /* released by snell_lightmap2d_destroy (lm->al lives in ctx) */
    if ((st = lm2d_raster_bins_create(ctx, al, &lm->bins)) != SNELL_OK ||
        (st = lm2d_pool_create(ctx, al, threads, &lm->pool)) != SNELL_OK) {
        snell_lightmap2d_destroy(lm);
        return st;
    }
    if (ctx && !d.cpu_only) {
        if ((st = lm2d_gl_create(ctx, d.width, d.height, d.format, d.blend, &lm->gl)) != SNELL_OK) {
            snell_lightmap2d_destroy(lm);
            return st;
        }
    }
    lm->raster = lm2d_raster_pick(d.raster, lm->gl != NULL, ctx ? snell_ctx_gl_renderer(ctx) : NULL,
                                  lm->raster_reason, sizeof lm->raster_reason);
    *out = lm;
    return SNELL_OK;
}

void snell_lightmap2d_destroy(snell_lightmap2d *lm)
{
    snell_ctx *ctx;
    int i;
    if (!lm) return;
    for (i = 0; i < lm->n_ls; i++) snell__free(lm->al, lm->ls[i].paths);
    snell__free(lm->al, lm->ls);
    snell__free(lm->al, lm->todo);
    snell__free(lm->al, lm->slices);
    snell__free(lm->al, lm->src);
    lm2d_raster_bins_destroy(lm->bins);
    snell__free(lm->al, lm->cpu);
    lm2d_pool_destroy(lm->pool);
    if (lm->gl) {
        /* In its context; after snell_ctx_destroy its GL objects are gone with it. */
        snell__gl_scope sc;
        snell__gl_scope_enter(lm->ctx, &sc);
        lm2d_gl_destroy(lm->gl);
        snell__gl_scope_leave(&sc);
    }
    ctx = lm->ctx;
    snell__free(lm->al, lm);
    snell__ctx_release(ctx);
}

void snell_lightmap2d_finish(snell_lightmap2d *lm)
{
    if (lm && lm->gl) lm2d_gl_finish(lm->gl);
}

unsigned snell_lightmap2d_texture(const snell_lightmap2d *lm) { return lm ? lm2d_gl_texture(lm->gl) : 0; }

/* Everything the lightmap holds for this scene, checked against the memory
 * budget before any of it is allocated (a scene file of a few hundred bytes
 * may ask for gigabytes): the images, per-light state, every light's path
 * buffer (rays x (max_bounces + 1) segments, or what it holds already) and,
 * rasterising on the CPU, the bins over all those segments. The bins get
 * what is left as their limit. */
static snell_status check_budget(snell_lightmap2d *lm, const snell_scene2d *s)
{
    size_t budget = snell__ctx_budget(lm->ctx), segs, per_light, total, bins = 0;
    int i, T = lm2d_pool_size(lm->pool);
    double sum, segs_d = 0.0; /* summed in double: no wrap, however many lights */
    char what[160];
    per_light = sizeof(light_state) + sizeof(int) + sizeof(lm2d_raster_src) + (size_t)T * sizeof(slice);
    for (i = 0; i < s->n_lights; i++) {
        const snell_light2d_desc *L = &s->lights[i].d;
        size_t n = L->power > 0.0f && L->rays > 0 ? (size_t)L->rays * (size_t)(lm->d.max_bounces + 1) : 0;
        if (i < lm->n_ls && lm->ls[i].cap > n) n = lm->ls[i].cap;
        segs_d += (double)n;
    }
    segs = segs_d >= 1.8e19 ? (size_t)-1 : (size_t)segs_d;
    if (!use_gl(lm)) bins = lm2d_raster_bins_bytes(segs);
    sum = (double)lm->image_bytes + (double)s->n_lights * (double)per_light + segs_d * sizeof(lm2d_path) +
          (double)bins;
    total = sum >= 1.8e19 ? (size_t)-1 : (size_t)sum;
    if (total > budget) {
        snprintf(what, sizeof what, "lightmap2d: a %dx%d lightmap, %d lights and their %zu path segments",
                 lm->d.width, lm->d.height, s->n_lights, segs);
        return snell__budget_check(lm->ctx, total, what);
    }
    lm2d_raster_bins_limit(lm->bins, budget - (total - bins));
    return SNELL_OK;
}

/* Per-light state follows the scene's light count (grows only when lights are added). */
static snell_status sync_lights(snell_lightmap2d *lm, const snell_scene2d *s)
{
    int T = lm2d_pool_size(lm->pool), i;
    if (s->n_lights > lm->n_ls) {
        light_state *ls = (light_state *)snell__realloc(lm->al, lm->ls, (size_t)s->n_lights * sizeof *ls);
        int *todo;
        slice *sl;
        lm2d_raster_src *src;
        if (!ls) return snell__fail(lm->ctx, SNELL_E_NOMEM, "lightmap2d: out of memory");
        lm->ls = ls;
        for (i = lm->n_ls; i < s->n_lights; i++) memset(&ls[i], 0, sizeof ls[i]);
        lm->n_ls = s->n_lights;
        todo = (int *)snell__realloc(lm->al, lm->todo, (size_t)s->n_lights * sizeof *todo);
        if (!todo) return snell__fail(lm->ctx, SNELL_E_NOMEM, "lightmap2d: out of memory");
        lm->todo = todo;
        sl = (slice *)snell__realloc(lm->al, lm->slices, (size_t)s->n_lights * (size_t)T * sizeof *sl);
        if (!sl) return snell__fail(lm->ctx, SNELL_E_NOMEM, "lightmap2d: out of memory");
        lm->slices = sl;
        src = (lm2d_raster_src *)snell__realloc(lm->al, lm->src, (size_t)s->n_lights * sizeof *src);
        if (!src) return snell__fail(lm->ctx, SNELL_E_NOMEM, "lightmap2d: out of memory");
        lm->src = src;
    }
    return SNELL_OK;
}

static snell_status ensure_capacity(snell_lightmap2d *lm, light_state *ls, int rays)
{
    size_t cap = (size_t)rays * (size_t)(lm->d.max_bounces + 1);
    if (cap > ls->cap) {
        lm2d_path *p;
        int ok = 1;
        snell__mul_size(cap, sizeof(lm2d_path), &ok);
        if (!ok) return snell__fail(lm->ctx, SNELL_E_NOMEM, "lightmap2d: path buffer size overflows");
        {
            /* rays * (max_bounces + 1) segments: a 40-byte scene line
             * ("rays 100000000") would otherwise ask for 36 GB */
            char what[96];
            snell_status st;
            snprintf(what, sizeof what, "lightmap2d: the path buffer of %d rays x %d segments", rays,
                     lm->d.max_bounces + 1);
            if ((st = snell__budget_check(lm->ctx, cap * sizeof(lm2d_path), what)) != SNELL_OK) return st;
        }
        p = (lm2d_path *)snell__realloc(lm->al, ls->paths, cap * sizeof(lm2d_path));
        if (!p)
            return snell__fail(lm->ctx, SNELL_E_NOMEM, "lightmap2d: out of memory for %zu path segments", cap);
        ls->paths = p;
        ls->cap = cap;
    }
    return SNELL_OK;
}

static void trace_job(int t, int T, void *arg)
{
    snell_lightmap2d *lm = (snell_lightmap2d *)arg;
    lm2d_trace_params p;
    int j;
    memset(&p, 0, sizeof p);
    p.scene = lm->scene;
    p.view_lo[0] = lm->view.lo[0];
    p.view_lo[1] = lm->view.lo[1];
    p.view_hi[0] = lm->view.hi[0];
    p.view_hi[1] = lm->view.hi[1];
    p.max_bounces = lm->d.max_bounces;
    p.seed = lm->d.seed;
    p.pass = lm->pass;
    for (j = 0; j < lm->n_todo; j++) {
        int li = lm->todo[j];
        light_state *ls = &lm->ls[li];
        int N = lm->scene->lights[li].d.rays;
        int r0 = (int)((int64_t)N * t / T), r1 = (int)((int64_t)N * (t + 1) / T);
        size_t base = (size_t)r0 * (size_t)(p.max_bounces + 1);
        slice *sl = &lm->slices[(size_t)li * (size_t)T + (size_t)t];
        energy_reset(&sl->e);
        sl->n = lm2d_trace_rays(&p, li, r0, r1, ls->paths + base, (size_t)(r1 - r0) * (size_t)(p.max_bounces + 1),
                                &sl->e);
    }
}

static int boxes_overlap(const float alo[2], const float ahi[2], const float blo[2], const float bhi[2])
{
    return alo[0] <= bhi[0] && blo[0] <= ahi[0] && alo[1] <= bhi[1] && blo[1] <= ahi[1];
}

/* Every light's paths (all = 1) or this frame's (the progressive pass), in
 * light order, into lm->cpu on the pool's threads. SCREEN applies the exposure
 * inside the blend (6.5.3); ADD keeps the raw sum. */
static void raster_cpu(snell_lightmap2d *lm, int all, int clear)
{
    int screen = lm->d.blend == SNELL_BLEND2D_SCREEN, n = 0, i;
    for (i = 0; i < (all ? lm->n_ls : lm->n_todo); i++) {
        const light_state *ls = &lm->ls[all ? i : lm->todo[i]];
        lm->src[n].paths = ls->paths;
        lm->src[n++].n = ls->n;
    }
    lm2d_raster_exact(lm->bins, lm->pool, lm->src, n, &lm->cpu_view, screen ? lm->d.exposure : 1.0f,
                      screen ? LM2D_RASTER_SCREEN : LM2D_RASTER_ADD, clear, lm->cpu);
}

/* CPU rasteriser with a GL target: the texture gets what the GL lines would
 * have left there (raw sum for float ADD; display values otherwise). */
static snell_status upload_cpu(snell_lightmap2d *lm)
{
    snell_format2d f = lm2d_gl_format(lm->gl);
    int fixed = f == SNELL_FORMAT2D_RGB10A2 || f == SNELL_FORMAT2D_RGBA8;
    if (lm->d.blend == SNELL_BLEND2D_SCREEN) return lm2d_gl_upload(lm->gl, lm->cpu, 1.0f, 1);
    return lm2d_gl_upload(lm->gl, lm->cpu, fixed ? lm->d.exposure / (float)(lm->passes ? lm->passes : 1) : 1.0f, 0);
}

snell_status snell_lightmap2d_frame(snell_lightmap2d *lm, snell_scene2d *s, snell_lightmap2d_stats *stats)
{
    snell_lightmap2d_stats stl;
    snell_status st;
    int i, T, all = 0, progressive_pass = 0, changed = 0;
    double t0;
    uint64_t rays = 0, paths = 0;
    if (!stats) stats = &stl;
    memset(stats, 0, sizeof *stats);
    if (!lm || !s) return snell__fail(lm ? lm->ctx : NULL, SNELL_E_INVALID_ARG, "snell_lightmap2d_frame: NULL argument");
    stats->raster = lm->raster;
    stats->raster_threads = use_gl(lm) ? 0 : lm2d_pool_size(lm->pool);
    memcpy(stats->raster_reason, lm->raster_reason, sizeof stats->raster_reason);
    if ((st = lm2d_scene_prepare(s)) != SNELL_OK) return st;
    if ((st = check_budget(lm, s)) != SNELL_OK) return st;
    if ((st = sync_lights(lm, s)) != SNELL_OK) return st;
    T = lm2d_pool_size(lm->pool);
    stats->format = lm->gl ? lm2d_gl_format(lm->gl) : SNELL_FORMAT2D_AUTO;
    /* --- what must be traced */
    if (!lm->traced_once || lm->geom_version != s->geom_version) {
        /* objects changed: a light keeps its paths only if the change region is
         * known relative to our last trace, its rays all ended on geometry, and
         * their bounds miss the region */
        int region = lm->traced_once && s->changed_any && s->changed_base == lm->geom_version;
        for (i = 0; i < s->n_lights; i++) {
            light_state *ls = &lm->ls[i];
            if (ls->version == 0) continue;
            if (!region || ls->e.unbounded || boxes_overlap(ls->e.lo, ls->e.hi, s->changed_min, s->changed_max))
                ls->version = 0;
        }
        all = 1;
        s->changed_any = 0; /* consumed (a second lightmap on this scene sees a base mismatch and re-traces all) */
        lm->geom_version = s->geom_version;
    }
    lm->n_todo = 0;
    for (i = 0; i < s->n_lights; i++) {
        const snell_light2d_desc *L = &s->lights[i].d;
        light_state *ls = &lm->ls[i];
        if (L->power <= 0.0f || L->rays == 0) {
            /* off: costs nothing; its old paths (if any) vanish */
            if (ls->n) changed = 1;
            ls->n = 0;
            ls->version = s->lights[i].version;
            energy_reset(&ls->e);
            stats->lights_skipped++;
            continue;
        }
        if (ls->version != s->lights[i].version) lm->todo[lm->n_todo++] = i;
        else stats->lights_skipped++;
    }
    if (lm->n_todo == 0 && !changed && !all) {
        if (!lm->d.progressive || !linear_accum(lm) || !lm->traced_once) {
            stats->passes = lm->passes;
            return SNELL_OK; /* static scene: the cached lightmap stands */
        }
        /* one more pass of every active light, added onto the accumulation */
        for (i = 0; i < s->n_lights; i++)
            if (s->lights[i].d.power > 0.0f && s->lights[i].d.rays > 0) lm->todo[lm->n_todo++] = i;
        stats->lights_skipped = s->n_lights - lm->n_todo;
        progressive_pass = 1;
        lm->pass++;
    } else {
        lm->pass = 0;
    }
    /* --- trace */
    t0 = snell__now_ms();
    for (i = 0; i < lm->n_todo; i++) {
        int li = lm->todo[i];
        if ((st = ensure_capacity(lm, &lm->ls[li], s->lights[li].d.rays)) != SNELL_OK) return st;
    }
    lm->scene = s;
    if (lm->n_todo) {
        struct timespec c0, c1;
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
        lm2d_pool_run(lm->pool, trace_job, lm);
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
        stats->trace_cpu_ms = (double)(c1.tv_sec - c0.tv_sec) * 1e3 + (double)(c1.tv_nsec - c0.tv_nsec) * 1e-6;
    }
    energy_reset(&lm->frame_e);
    for (i = 0; i < lm->n_todo; i++) {
        int li = lm->todo[i], t;
        light_state *ls = &lm->ls[li];
        int N = s->lights[li].d.rays;
        size_t w = 0;
        energy_reset(&ls->e);
        /* join the thread slices in ray order: the buffer is the same for any thread count */
        for (t = 0; t < T; t++) {
            const slice *sl = &lm->slices[(size_t)li * (size_t)T + (size_t)t];
            int r0 = (int)((int64_t)N * t / T);
            size_t base = (size_t)r0 * (size_t)(lm->d.max_bounces + 1);
            if (base != w && sl->n) memmove(ls->paths + w, ls->paths + base, sl->n * sizeof(lm2d_path));
            w += sl->n;
            energy_add(&ls->e, &sl->e);
        }
        energy_add(&lm->frame_e, &ls->e);
        ls->n = w;
        ls->version = s->lights[li].version;
        ls->rays = N;
        rays += (uint64_t)N;
    }
    stats->trace_ms = snell__now_ms() - t0;
    stats->lights_traced = lm->n_todo;
    stats->rays = rays;
    stats->traced = 1;
    lm->traced_once = 1;
    /* --- rasterise */
    t0 = snell__now_ms();
    if (progressive_pass) {
        for (i = 0; i < lm->n_todo; i++) paths += lm->ls[lm->todo[i]].n;
        if (use_gl(lm)) {
            for (i = 0; i < lm->n_todo; i++) {
                light_state *ls = &lm->ls[lm->todo[i]];
                if ((st = lm2d_gl_draw(lm->gl, ls->paths, ls->n, &lm->view, 1.0f)) != SNELL_OK) return st;
            }
        } else {
            raster_cpu(lm, 0, 0);
        }
        lm->passes++;
    } else {
        float scale = linear_accum(lm) ? 1.0f : lm->d.exposure;
        for (i = 0; i < lm->n_ls; i++) paths += lm->ls[i].n;
        if (use_gl(lm)) {
            lm2d_gl_clear(lm->gl);
            for (i = 0; i < lm->n_ls; i++)
                if ((st = lm2d_gl_draw(lm->gl, lm->ls[i].paths, lm->ls[i].n, &lm->view, scale)) != SNELL_OK) return st;
        } else {
            raster_cpu(lm, 1, 1);
        }
        lm->passes = 1;
    }
    if (!use_gl(lm) && lm->gl) {
        double t1 = snell__now_ms();
        if ((st = upload_cpu(lm)) != SNELL_OK) return st;
        stats->upload_ms = snell__now_ms() - t1;
    }
    stats->raster_ms = snell__now_ms() - t0;
    stats->paths = paths;
    stats->passes = lm->passes;
    return SNELL_OK;
}

/* lm->cpu as display RGB, top row first: 1 - product for SCREEN, else sum x scale. */
static void cpu_to_rgb(const snell_lightmap2d *lm, float *rgb, float scale)
{
    int w = lm->d.width, h = lm->d.height, x, y, k, screen = lm->d.blend == SNELL_BLEND2D_SCREEN;
    for (y = 0; y < h; y++) {
        const float *src = lm->cpu + LM2D_RASTER_PX * (size_t)(h - 1 - y) * (size_t)w;
        float *dst = rgb + 3 * (size_t)y * (size_t)w;
        for (x = 0; x < w; x++, src += LM2D_RASTER_PX, dst += 3)
            for (k = 0; k < 3; k++) dst[k] = screen ? 1.0f - src[k] : src[k] * scale;
    }
}

snell_status snell_lightmap2d_read_rgb(snell_lightmap2d *lm, float *rgb)
{
    if (!lm || !rgb) return snell__fail(lm ? lm->ctx : NULL, SNELL_E_INVALID_ARG, "snell_lightmap2d_read_rgb: NULL argument");
    if (use_gl(lm)) {
        float scale = linear_accum(lm) ? lm->d.exposure / (float)(lm->passes ? lm->passes : 1) : 1.0f;
        return lm2d_gl_read(lm->gl, rgb, scale);
    }
    if (!lm->passes) {
        memset(rgb, 0, 3 * sizeof(float) * (size_t)lm->d.width * (size_t)lm->d.height);
        return SNELL_OK;
    }
    cpu_to_rgb(lm, rgb, lm->d.exposure / (float)lm->passes);
    return SNELL_OK;
}

snell_status snell_lightmap2d_read_rgb_exact(snell_lightmap2d *lm, float *rgb)
{
    if (!lm || !rgb)
        return snell__fail(lm ? lm->ctx : NULL, SNELL_E_INVALID_ARG, "snell_lightmap2d_read_rgb_exact: NULL argument");
    if (!use_gl(lm)) return snell_lightmap2d_read_rgb(lm, rgb);
    /* the paths kept are each light's latest pass: equal to the GPU image when passes == 1 */
    raster_cpu(lm, 1, 1);
    cpu_to_rgb(lm, rgb, lm->d.exposure);
    return SNELL_OK;
}

static uint8_t to8(float v) { return (uint8_t)(v <= 0.0f ? 0 : v >= 1.0f ? 255 : (int)(v * 255.0f + 0.5f)); }

snell_status snell_lightmap2d_read_rgba(snell_lightmap2d *lm, uint8_t *rgba)
{
    size_t px, i;
    snell_status st;
    if (!lm || !rgba) return snell__fail(lm ? lm->ctx : NULL, SNELL_E_INVALID_ARG, "snell_lightmap2d_read_rgba: NULL argument");
    px = (size_t)lm->d.width * (size_t)lm->d.height;
    if (use_gl(lm)) {
        /* the CPU image is scratch in GL mode (4 floats a pixel: room for the RGB) */
        float *tmp = lm->cpu;
        if ((st = snell_lightmap2d_read_rgb(lm, tmp)) != SNELL_OK) return st;
        for (i = 0; i < px; i++) {
            rgba[4 * i] = to8(tmp[3 * i]);
            rgba[4 * i + 1] = to8(tmp[3 * i + 1]);
            rgba[4 * i + 2] = to8(tmp[3 * i + 2]);
            rgba[4 * i + 3] = 255;
        }
        return SNELL_OK;
    }
    {
        int w = lm->d.width, h = lm->d.height, x, y, k, screen = lm->d.blend == SNELL_BLEND2D_SCREEN;
        float scale = lm->d.exposure / (float)(lm->passes ? lm->passes : 1);
        for (y = 0; y < h; y++) {
            const float *src = lm->cpu + LM2D_RASTER_PX * (size_t)(h - 1 - y) * (size_t)w;
            uint8_t *dst = rgba + 4 * (size_t)y * (size_t)w;
            for (x = 0; x < w; x++, src += LM2D_RASTER_PX, dst += 4) {
                for (k = 0; k < 3; k++)
                    dst[k] = !lm->passes ? 0 : to8(screen ? 1.0f - src[k] : src[k] * scale);
                dst[3] = 255;
            }
        }
    }
    return SNELL_OK;
}

void snell_lightmap2d_energy(const snell_lightmap2d *lm, snell_energy2d *out)
{
    if (!out) return;
    memset(out, 0, sizeof *out);
    if (!lm) return;
    out->emitted = lm->frame_e.emitted;
    out->absorbed = lm->frame_e.absorbed;
    out->escaped = lm->frame_e.escaped;
    out->capped = lm->frame_e.capped;
    out->rr_killed = lm->frame_e.rr_killed;
    out->rr_gained = lm->frame_e.rr_gained;
}
