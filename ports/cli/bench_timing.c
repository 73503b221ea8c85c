/* SPDX-License-Identifier: MIT */
/* bench_timing.c — timing of snell-bench's configurations. Those of one scene
 * and size take turns frame by frame (each with its own renderer, so nothing
 * is re-baked between turns), so a shared machine's drift hits all of them
 * alike; ratios to the single-surface configuration are taken per round. Each
 * frame is snell_render + glFinish on the CPU wall clock, plus a GL timer
 * query where the context has one. */
#include "bench.h"
#include "bench_timer.h"
#include "cli_time.h"

#include <stdlib.h>
#include <string.h>

#define MAX_INTERLEAVED 48 /* renderers alive at once while timing (memory) */

/* One configuration while it is being timed. */
typedef struct timing_slot {
    bench_config *c;
    snell_renderer *r;
    snell_glass glass[SNELL_MAX_GLASS];
    snell_frame_desc fd;
    double *times, *gpu, *ratio;
    int gpu_n;
} timing_slot;

int bench_same_group(const bench_config *a, const bench_config *b)
{
    return !strcmp(a->scene, b->scene) && a->width == b->width && a->height == b->height;
}

/* One frame of t; recorded as round `round` if record, else warm-up. A
 * failure marks the configuration failed (c->ok = 0). */
/* spin=: the camera turns about its target before every frame. */
static void turn_camera(timing_slot *t)
{
    t->fd.camera.azimuth += (float)(t->c->spin * 3.14159265358979323846 / 180.0);
}

static void time_frame(snell_ctx *ctx, timing_slot *t, int record, int round)
{
    double t0, g;
    snell_status st;
    turn_camera(t);
    t0 = cli_now_ms();
    bench_timer_begin();
    st = snell_render(t->r, &t->fd, NULL);
    bench_timer_end();
    snell_renderer_finish(t->r);
    if (st != SNELL_OK) {
        bench_fail(t->c, "render", ctx);
        return;
    }
    if (!record) {
        bench_timer_read();
        return;
    }
    t->times[round] = cli_now_ms() - t0;
    g = bench_timer_read();
    if (g >= 0.0) t->gpu[t->gpu_n++] = g;
}

/* Renderer, frame and buffers of one slot, then its warm-up frames. */
static void open_slot(snell_ctx *ctx, const snell_env *env, const bench_options *o, timing_slot *t)
{
    snell_renderer_desc desc;
    const bench_scene *s = NULL;
    int k;
    t->c->ok = 1;
    t->c->frames = o->frames;
    t->c->vs_single = -1.0;
    t->c->vs_scene = -1.0;
    t->times = (double *)malloc(sizeof(double) * (size_t)o->frames);
    t->gpu = (double *)malloc(sizeof(double) * (size_t)o->frames);
    t->ratio = (double *)malloc(sizeof(double) * (size_t)o->frames);
    if (!t->times || !t->gpu || !t->ratio) {
        snprintf(t->c->error, sizeof t->c->error, "out of memory");
        t->c->ok = 0;
        return;
    }
    if (bench_scene_get(ctx, t->c->scene, &s) != SNELL_OK) {
        bench_fail(t->c, "scene", ctx);
        return;
    }
    memset(&desc, 0, sizeof desc);
    desc.width = t->c->width;
    desc.height = t->c->height;
    desc.shading = t->c->shading;
    desc.ssaa = t->c->ssaa;
    desc.msaa = t->c->msaa;
    desc.refine = t->c->refine;
    if (snell_renderer_create(ctx, &desc, &t->r) != SNELL_OK) {
        bench_fail(t->c, "renderer", ctx);
        return;
    }
    bench_scene_frame(t->c, s, env, t->glass, &t->fd);
    if (bench_scene_lod(ctx, t->c, t->glass, t->fd.glass_count) != SNELL_OK) {
        bench_fail(t->c, "lod", ctx);
        return;
    }
    for (k = 0; k < o->warmup && t->c->ok; k++) time_frame(ctx, t, 0, 0);
    if (t->c->ok) {
        /* the passes of a frame after warm-up (the first frame's also bake and prepare), untimed */
        snell_frame_stats fs;
        turn_camera(t);
        if (snell_render(t->r, &t->fd, &fs) != SNELL_OK) {
            bench_fail(t->c, "render", ctx);
            return;
        }
        snell_renderer_finish(t->r);
        t->c->passes = fs.passes;
        t->c->layer_passes = fs.scene_layer_passes;
        t->c->layers_used = fs.scene_layers;
    }
}

int bench_frame_times(bench_config *c, const double *ms, int n)
{
    double *sorted = (double *)malloc(sizeof(double) * (size_t)(n > 0 ? n : 1)), sum = 0.0;
    int i, tail = (n + 99) / 100; /* the slowest 1%, at least one frame */
    free(c->frame_ms);
    c->frame_ms = (double *)malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
    if (!sorted || !c->frame_ms || n < 1) {
        free(sorted);
        free(c->frame_ms);
        c->frame_ms = NULL;
        return 0;
    }
    memcpy(c->frame_ms, ms, sizeof(double) * (size_t)n);
    memcpy(sorted, ms, sizeof(double) * (size_t)n);
    c->frames = n;
    c->t_p95 = cli_percentile(sorted, n, 0.95); /* sorts */
    c->t_p99 = cli_percentile(sorted, n, 0.99);
    c->t_median = cli_median(sorted, n);
    c->t_min = sorted[0];
    c->t_max = sorted[n - 1];
    for (i = n - tail; i < n; i++) sum += sorted[i];
    c->t_low1 = sum / tail;
    free(sorted);
    return 1;
}

void bench_configs_free(bench_config *cs, int n)
{
    int i;
    for (i = 0; cs && i < n; i++) {
        free(cs[i].frame_ms);
        cs[i].frame_ms = NULL;
    }
}

/* The slot's time summary, then its resources freed. */
static void close_slot(const bench_options *o, timing_slot *t)
{
    if (t->c->ok) {
        if (!bench_frame_times(t->c, t->times, o->frames)) {
            t->c->ok = 0;
            snprintf(t->c->error, sizeof t->c->error, "out of memory");
        }
        t->c->gpu_median = t->gpu_n == o->frames ? cli_median(t->gpu, t->gpu_n) : -1.0;
    }
    snell_renderer_destroy(t->r);
    free(t->times);
    free(t->gpu);
    free(t->ratio);
}

/* The spec after its scene (scene= leads the canonical spec: bench_spec.c). */
static const char *spec_after_scene(const bench_config *c)
{
    size_t skip = strlen(c->method->name) + strlen(":scene=") + strlen(c->scene);
    return strlen(c->spec) >= skip ? c->spec + skip : "";
}

/* The same configuration on another scene. */
static int same_spec(const bench_config *a, const bench_config *b)
{
    return a->method == b->method && !strcmp(spec_after_scene(a), spec_after_scene(b));
}

/* Median over rounds of t's time over base's (each round's frames side by side). */
static double round_ratio(const bench_options *o, const timing_slot *t, const timing_slot *base)
{
    int r;
    for (r = 0; r < o->frames; r++) t->ratio[r] = t->times[r] / base->times[r];
    return cli_median(t->ratio, o->frames);
}

/* Times the m configurations cs[idx[0..m)] (one size; one scene unless
 * --baseline-scene): each gets its warm-up frames, then o->frames rounds in
 * which every configuration renders one frame, the order rotating from round
 * to round. vs_single: against the single-surface configuration of the same
 * scene; vs_scene: against the same spec on the baseline scene. */
static void time_group(snell_ctx *ctx, const snell_env *env, const bench_options *o, bench_config *cs, const int *idx,
                       int m)
{
    timing_slot *ts = (timing_slot *)calloc((size_t)m, sizeof *ts);
    int i, r, k;
    if (!ts) {
        for (i = 0; i < m; i++) {
            cs[idx[i]].ok = 0;
            snprintf(cs[idx[i]].error, sizeof cs[idx[i]].error, "out of memory");
        }
        return;
    }
    for (i = 0; i < m; i++) {
        ts[i].c = &cs[idx[i]];
        open_slot(ctx, env, o, &ts[i]);
    }
    for (r = 0; r < o->frames; r++)
        for (k = 0; k < m; k++) {
            timing_slot *t = &ts[(k + r) % m];
            if (t->c->ok) time_frame(ctx, t, 1, r);
        }
    for (i = 0; i < m; i++) {
        timing_slot *t = &ts[i];
        if (!t->c->ok) continue;
        for (k = 0; k < m; k++) {
            const bench_config *b = ts[k].c;
            if (!b->ok) continue;
            if (t->c->vs_single < 0 && b->method->method == SNELL_METHOD_SINGLE && bench_same_group(b, t->c))
                t->c->vs_single = round_ratio(o, t, &ts[k]);
            if (t->c->vs_scene < 0 && o->baseline_scene && !strcmp(b->scene, o->baseline_scene) && same_spec(b, t->c))
                t->c->vs_scene = round_ratio(o, t, &ts[k]);
        }
    }
    for (i = 0; i < m; i++) close_slot(o, &ts[i]);
    free(ts);
}

/* --baseline-scene: every configuration of one size takes turns with every
 * other, so that ratios across scenes are taken side by side; at most
 * MAX_INTERLEAVED of them. */
static void time_across_scenes(snell_ctx *ctx, const snell_env *env, const bench_options *o, bench_config *cs, int n,
                               int *done)
{
    int idx[MAX_INTERLEAVED], i, j, m;
    for (i = 0; i < n; i++) {
        if (done[i]) continue;
        for (j = i, m = 0; j < n; j++) {
            if (done[j] || cs[j].width != cs[i].width || cs[j].height != cs[i].height) continue;
            done[j] = 1;
            if (m < MAX_INTERLEAVED) idx[m] = j;
            m++;
        }
        if (m > MAX_INTERLEAVED) {
            for (j = i; j < n; j++)
                if (cs[j].width == cs[i].width && cs[j].height == cs[i].height) {
                    cs[j].ok = 0;
                    snprintf(cs[j].error, sizeof cs[j].error,
                             "--baseline-scene: %d configurations at %dx%d, at most %d take turns", m, cs[i].width,
                             cs[i].height, MAX_INTERLEAVED);
                }
            continue;
        }
        if (!o->quiet)
            fprintf(stderr, "timing %d configuration(s) at %dx%d across scenes, taking turns frame by frame\n", m,
                    cs[i].width, cs[i].height);
        time_group(ctx, env, o, cs, idx, m);
    }
}

/* At most MAX_INTERLEAVED configurations at once; a larger group is timed in
 * parts, each with the group's single-surface configuration, if any, so every
 * ratio is taken within one part. */
void bench_time_all(snell_ctx *ctx, const snell_env *env, const bench_options *o, bench_config *cs, int n)
{
    int *done = (int *)calloc((size_t)(n > 0 ? n : 1), sizeof(int));
    int idx[MAX_INTERLEAVED], i, j, k, m, single, part;
    if (!done) {
        for (i = 0; i < n; i++) {
            cs[i].ok = 0;
            snprintf(cs[i].error, sizeof cs[i].error, "out of memory");
        }
        return;
    }
    if (o->baseline_scene) {
        time_across_scenes(ctx, env, o, cs, n, done);
        free(done);
        return;
    }
    for (i = 0; i < n; i++) {
        if (done[i]) continue;
        single = -1;
        for (j = i; j < n && single < 0; j++)
            if (!done[j] && cs[j].method->method == SNELL_METHOD_SINGLE && bench_same_group(&cs[j], &cs[i])) single = j;
        j = i;
        for (part = 0;; part++) {
            m = 0;
            if (single >= 0) idx[m++] = single;
            for (; j < n && m < MAX_INTERLEAVED; j++)
                if (!done[j] && j != single && bench_same_group(&cs[j], &cs[i])) idx[m++] = j;
            if (part > 0 && m == (single >= 0)) break; /* nothing left but the baseline */
            if (!o->quiet)
                fprintf(stderr, "timing %d configuration(s) of %s at %dx%d, taking turns frame by frame\n", m,
                        cs[i].scene, cs[i].width, cs[i].height);
            time_group(ctx, env, o, cs, idx, m);
            for (k = 0; k < m; k++) done[idx[k]] = 1;
            if (j >= n) break;
        }
    }
    free(done);
}
