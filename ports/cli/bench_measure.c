/* SPDX-License-Identifier: MIT */
/* bench_measure.c — one configuration's error against the CPU reference: its
 * colour frame and exit directions (SNELL_OUTPUT_EXIT_DIRECTION) compared with
 * the reference of the same scene in the MATCHED model (the method's own,
 * with its interface cap) and the FULL model (Whitted tree). The reference
 * models what the frame drew: where the renderer drew each glass object over
 * its own environment (scene layers off) it runs with isolate_glass = 1
 * (light that has left a glass object sees the environment and the opaque
 * objects but no other glass object), where the frame drew the scene layers
 * with isolate_glass = 0, so the error measured is the method's own. Colour is
 * compared over the glass pixels as PSNR and SSIM, on area-averaged images
 * with --aa S (the GPU frame supersampled S x S, the references with S x S
 * rays a pixel): pixel-centre colours of a bumpy scan alias. The exit
 * directions are always the pixel centres'.
 *
 * Then the whole scene (issue 13): the same frame against the FULL reference
 * with isolate_glass = 0 (light that leaves one glass object may enter
 * another), per object class of the reference's first hit (bench_classes.c),
 * beside two baselines: the scene drawn by the method one glass object at a
 * time over the environment and the opaque objects, composed back to front
 * (what drawing each object alone gives, whatever the renderer does with
 * several), and the isolated FULL reference (each object alone, exactly). */
#include "bench.h"
#include "bench_ref.h"
#include "cli_progress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void bench_fail(bench_config *c, const char *what, snell_ctx *ctx)
{
    const char *msg = snell_last_error(ctx);
    if (!msg || !*msg) msg = snell_last_error(NULL);
    snprintf(c->error, sizeof c->error, "%s: %s", what, msg && *msg ? msg : "failed");
    c->ok = 0;
}

/* Error map for --images: grey background, glass pixels coloured by the
 * log of the angle, 0.01 degrees (black) .. 10 degrees (white), red = NaN. */
int bench_image_failures;

/* --images: a file that cannot be written is reported and fails the run. */
static void write_png(const char *path, int w, int h, const uint8_t *px)
{
    if (snell_write_png(path, w, h, px) == SNELL_OK) return;
    fprintf(stderr, "snell-bench: %s\n", snell_last_error(NULL));
    bench_image_failures++;
}

static void write_error_map(const char *path, const float *err, const uint8_t *mask, const float *dirs, int w,
                            int h)
{
    uint8_t *px = (uint8_t *)malloc((size_t)w * h * 4);
    long i;
    if (!px) return;
    for (i = 0; i < (long)w * h; i++) {
        uint8_t *p = px + 4 * i;
        p[3] = 255;
        if (!isfinite(dirs[3 * i]) || !isfinite(dirs[3 * i + 1]) || !isfinite(dirs[3 * i + 2])) {
            p[0] = 255, p[1] = p[2] = 0;
        } else if (!mask[i] || isnan(err[i])) {
            p[0] = p[1] = p[2] = 64;
        } else {
            double t = (log10(err[i] > 1e-4f ? err[i] : 1e-4f) + 2.0) / 3.0;
            t = t < 0 ? 0 : t > 1 ? 1 : t;
            p[0] = (uint8_t)(255 * t);
            p[1] = (uint8_t)(255 * t * t);
            p[2] = (uint8_t)(255 * 2 * t * (1 - t));
        }
    }
    write_png(path, w, h, px);
    free(px);
}

static void sanitize(char *s)
{
    for (; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') || *s == '.' ||
              *s == '-' || *s == '='))
            *s = '_';
}

/* Buffers of one measurement, c->width * c->height pixels each. The
 * alone_* images are the glass objects drawn one at a time and composed;
 * one_* and bg_rgba the frames they are composed from. */
typedef struct measure_buf {
    size_t n;
    uint8_t *rgba, *mask, *either;
    float *dirs, *bgdirs, *err;
    int draw_order[SNELL_MAX_GLASS]; /* the colour frame's (snell_object_stats.draw_order) */
    uint8_t *alone_rgba, *alone_mask, *one_rgba, *bg_rgba, *through;
    float *alone_dirs, *one_dirs;
} measure_buf;

static int buf_alloc(measure_buf *b, const bench_config *c)
{
    b->n = (size_t)c->width * (size_t)c->height;
    b->rgba = (uint8_t *)malloc(b->n * 4);
    b->mask = (uint8_t *)malloc(b->n);
    b->either = (uint8_t *)malloc(b->n);
    b->dirs = (float *)malloc(b->n * 3 * sizeof(float));
    b->bgdirs = (float *)malloc(b->n * 3 * sizeof(float));
    b->err = (float *)malloc(b->n * sizeof(float));
    b->alone_rgba = (uint8_t *)malloc(b->n * 4);
    b->alone_mask = (uint8_t *)malloc(b->n);
    b->one_rgba = (uint8_t *)malloc(b->n * 4);
    b->bg_rgba = (uint8_t *)malloc(b->n * 4);
    b->alone_dirs = (float *)malloc(b->n * 3 * sizeof(float));
    b->one_dirs = (float *)malloc(b->n * 3 * sizeof(float));
    b->through = (uint8_t *)malloc(b->n);
    return b->through && b->rgba && b->mask && b->either && b->dirs && b->bgdirs && b->err && b->alone_rgba && b->alone_mask &&
           b->one_rgba && b->bg_rgba && b->alone_dirs && b->one_dirs;
}

static void buf_free(measure_buf *b)
{
    free(b->rgba);
    free(b->mask);
    free(b->either);
    free(b->dirs);
    free(b->bgdirs);
    free(b->err);
    free(b->alone_rgba);
    free(b->alone_mask);
    free(b->one_rgba);
    free(b->bg_rgba);
    free(b->alone_dirs);
    free(b->one_dirs);
    free(b->through);
}

/* The frame of fd, refine times where the configuration refines (its mean of
 * that many still frames), else once. */
static snell_status render_still(snell_renderer *r, const snell_frame_desc *fd, int refine, snell_frame_stats *fs)
{
    snell_status st;
    int k = 0;
    do st = snell_render(r, fd, fs);
    while (st == SNELL_OK && ++k < refine);
    return st;
}

/* The colour frame (timing was done before, in bench_time_all), with the
 * per-object statistics: how many glass objects warn. aa > 1: supersampled
 * (snell_renderer_desc.ssaa), the area-averaged image the reference's
 * samples = aa is compared with. */
static int colour_frame(snell_ctx *ctx, const snell_frame_desc *fd, int aa, bench_config *c, measure_buf *b)
{
    snell_renderer *r = NULL;
    snell_renderer_desc desc;
    snell_frame_stats fs;
    int i, ok = 0;
    memset(&desc, 0, sizeof desc);
    desc.width = c->width;
    desc.height = c->height;
    desc.shading = c->shading;
    /* The configuration's own antialiasing if it has one, else --aa's. */
    desc.ssaa = c->ssaa || c->msaa || c->refine ? c->ssaa : aa;
    desc.msaa = c->msaa;
    desc.refine = c->refine;
    if (snell_renderer_create(ctx, &desc, &r) != SNELL_OK) bench_fail(c, "renderer", ctx);
    else if (render_still(r, fd, c->refine, &fs) != SNELL_OK) bench_fail(c, "render", ctx);
    else if (snell_renderer_read_rgba(r, b->rgba) != SNELL_OK) bench_fail(c, "readback", ctx);
    else ok = 1;
    if (ok) {
        c->warnings = 0;
        for (i = 0; i < fs.glass_count; i++) {
            c->warnings += fs.glass[i].warning != 0;
            b->draw_order[i] = fs.glass[i].draw_order;
            c->methods_used[i] = fs.glass[i].method_used;
        }
        c->layers_drawn = fs.scene_layer_passes > 0;
    }
    snell_renderer_destroy(r);
    return ok;
}

/* Exit directions, and a frame without the glass (opaque objects and
 * background only) for the coverage mask. */
static int exit_dir_frames(snell_ctx *ctx, const snell_frame_desc *fd, bench_config *c, measure_buf *b)
{
    snell_renderer *r = NULL;
    snell_renderer_desc desc;
    snell_frame_desc bg = *fd;
    snell_frame_stats fs;
    size_t i;
    int ok = 0, g, k;
    memset(&desc, 0, sizeof desc);
    desc.width = c->width;
    desc.height = c->height;
    desc.shading = c->shading;
    desc.output = SNELL_OUTPUT_EXIT_DIRECTION;
    bg.glass = NULL;
    bg.glass_count = 0;
    if (snell_renderer_create(ctx, &desc, &r) != SNELL_OK) {
        bench_fail(c, "exit-direction renderer", ctx);
        return 0;
    }
    c->encoding = snell_renderer_exit_dir_encoding(r);
    for (k = 0; k < SNELL_MAX_METHOD_COUNTERS; k++) c->counters[k] = -1;
    if (snell_render(r, &bg, NULL) != SNELL_OK || snell_renderer_read_exit_dirs(r, b->bgdirs) != SNELL_OK ||
        snell_render(r, fd, &fs) != SNELL_OK || snell_renderer_read_exit_dirs(r, b->dirs) != SNELL_OK) {
        bench_fail(c, "exit-direction frame", ctx);
    } else {
        ok = 1;
        for (g = 0; g < fs.glass_count; g++)
            for (k = 0; k < SNELL_MAX_METHOD_COUNTERS; k++)
                if (fs.glass[g].method_used == c->method->method && fs.glass[g].counters[k] >= 0)
                    c->counters[k] = (c->counters[k] < 0 ? 0 : c->counters[k]) + fs.glass[g].counters[k];
        snell_metrics_coverage_mask(b->dirs, b->bgdirs, (long)b->n, b->mask);
        c->nan_inf = 0;
        for (i = 0; i < b->n; i++)
            c->nan_inf += !isfinite(b->dirs[3 * i]) || !isfinite(b->dirs[3 * i + 1]) || !isfinite(b->dirs[3 * i + 2]);
    }
    snell_renderer_destroy(r);
    return ok;
}

static void write_images(const bench_options *o, const bench_config *c, int mode, const measure_buf *b,
                         const bench_ref_image *ref)
{
    char path[1400], name[600];
    snprintf(name, sizeof name, "%s", c->spec);
    sanitize(name);
    if (mode == 0) {
        snprintf(path, sizeof path, "%s/%s.png", o->images_dir, name);
        write_png(path, c->width, c->height, b->rgba);
    }
    snprintf(path, sizeof path, "%s/%s.ref-%s.png", o->images_dir, name, mode ? "full" : "matched");
    write_png(path, c->width, c->height, ref->rgba);
    snprintf(path, sizeof path, "%s/%s.err-%s.png", o->images_dir, name, mode ? "full" : "matched");
    write_error_map(path, b->err, b->mask, b->dirs, c->width, c->height);
}

/* The reference of fd's scene with its objects ref_glass (fd's objects with
 * their original meshes, lod= or not); mode 0: MATCHED, 1: FULL; isolate:
 * isolate_glass. *cached tells whether it came from the cache. */
static int reference(const snell_frame_desc *fd, const snell_glass *ref_glass, const char *env_name,
                     const bench_options *o, bench_config *c, int mode, int isolate, bench_ref_image *ref, int *cached)
{
    snell_ref_params p;
    snell_ref_desc scene;
    cli_progress bar;
    memset(&scene, 0, sizeof scene);
    scene.glass = ref_glass;
    scene.glass_count = fd->glass_count;
    scene.opaque = fd->opaque;
    scene.opaque_count = fd->opaque_count;
    memset(&p, 0, sizeof p);
    p.mode = mode ? SNELL_REF_FULL : SNELL_REF_MATCHED;
    p.max_interfaces = mode ? o->full_interfaces : c->ref_interfaces;
    p.absorption_model = mode ? SNELL_REF_ABSORB_PATH : c->ref_absorb;
    p.isolate_glass = isolate;
    p.terms = mode ? 0u : c->ref_terms;
    p.env = fd->env;
    p.camera = fd->camera;
    p.width = c->width;
    p.height = c->height;
    p.threads = o->threads;
    p.samples = o->aa;
    if (!o->quiet)
        fprintf(stderr, "    reference %s (%d interfaces, %s)...\n", mode ? "FULL" : "MATCHED", p.max_interfaces,
                isolate ? "glass objects isolated" : "the whole scene");
    if (cli_progress_wanted(o->quiet)) { /* a trace (not a cache hit) shows its progress on a terminal */
        cli_progress_start(&bar, mode ? "reference FULL" : "reference MATCHED");
        p.progress = cli_progress_report;
        p.progress_user = &bar;
    }
    if (bench_ref_get(&scene, &p, env_name, o->cache_dir, ref, cached) != SNELL_OK) {
        bench_fail(c, mode ? (isolate ? "isolated FULL reference" : "whole-scene FULL reference") : "MATCHED reference",
                   NULL);
        return 0;
    }
    return 1;
}

static void dir_error(const float *test, const uint8_t *test_mask, const bench_ref_image *ref, float *err,
                      snell_dir_error *out)
{
    snell_dir_error_desc dd;
    memset(&dd, 0, sizeof dd);
    dd.test = test;
    dd.ref = ref->exit_dir;
    dd.ref_mask = ref->hit;
    dd.test_mask = test_mask;
    dd.width = ref->width;
    dd.height = ref->height;
    dd.error_deg = err;
    snell_metrics_dir_error(&dd, out);
}

/* mode 0: MATCHED, 1: FULL, both with isolate_glass = 1 unless the frame drew
 * the scene layers (then glass seen through glass is the renderer's to draw
 * too). keep: the reference is handed back there (the caller frees it)
 * instead of freed. */
static int compare(const snell_frame_desc *fd, const snell_glass *ref_glass, const char *env_name,
                   const bench_options *o, bench_config *c, int mode, measure_buf *b, bench_ref_image *keep)
{
    bench_ref_image ref;
    size_t j;
    if (!reference(fd, ref_glass, env_name, o, c, mode, !c->layers_drawn, &ref, &c->ref_cached[mode])) return 0;
    dir_error(b->dirs, b->mask, &ref, b->err, &c->dir[mode]);
    snell_metrics_image_error(b->rgba, ref.rgba, c->width, c->height, NULL, &c->img[mode]);
    for (j = 0; j < b->n; j++) b->either[j] = (uint8_t)(b->mask[j] || ref.hit[j]);
    snell_metrics_image_error(b->rgba, ref.rgba, c->width, c->height, b->either, &c->img_glass[mode]);
    snell_metrics_ssim(b->rgba, ref.rgba, c->width, c->height, b->either, &c->ssim_glass[mode]);
    if (o->images_dir) write_images(o, c, mode, b, &ref);
    if (keep) *keep = ref;
    else bench_ref_free(&ref);
    return 1;
}

/* b->alone_*: the glass objects of fd drawn one at a time (each frame: that
 * object, every opaque object, the background), composed back to front in
 * the colour frame's draw order: where an object's frame covers a pixel
 * (its exit direction differs from the glass-free frame's, or its colour
 * does: a supersampled edge) it replaces what the farther ones left. */
static int alone_frames(snell_ctx *ctx, const snell_frame_desc *fd, int aa, bench_config *c, measure_buf *b)
{
    snell_renderer *rc = NULL, *rd = NULL;
    snell_renderer_desc desc;
    snell_frame_desc one = *fd;
    int order, i, ok = 1;
    size_t j;
    memset(&desc, 0, sizeof desc);
    desc.width = c->width;
    desc.height = c->height;
    desc.shading = c->shading;
    desc.ssaa = c->ssaa || c->msaa || c->refine ? c->ssaa : aa;
    desc.msaa = c->msaa;
    desc.refine = c->refine;
    if (snell_renderer_create(ctx, &desc, &rc) != SNELL_OK) ok = 0;
    desc.ssaa = desc.msaa = desc.refine = 0;
    desc.output = SNELL_OUTPUT_EXIT_DIRECTION;
    if (ok && snell_renderer_create(ctx, &desc, &rd) != SNELL_OK) ok = 0;
    one.glass_count = 0;
    if (ok && (render_still(rc, &one, c->refine, NULL) != SNELL_OK || snell_renderer_read_rgba(rc, b->bg_rgba) != SNELL_OK))
        ok = 0;
    if (ok) {
        memcpy(b->alone_rgba, b->bg_rgba, b->n * 4);
        memcpy(b->alone_dirs, b->bgdirs, b->n * 3 * sizeof(float));
        memset(b->alone_mask, 0, b->n);
    }
    one.glass_count = 1;
    for (order = 0; ok && order < fd->glass_count; order++)
        for (i = 0; ok && i < fd->glass_count; i++) {
            if (b->draw_order[i] != order) continue;
            one.glass = &fd->glass[i];
            if (render_still(rc, &one, c->refine, NULL) != SNELL_OK || snell_renderer_read_rgba(rc, b->one_rgba) != SNELL_OK ||
                snell_render(rd, &one, NULL) != SNELL_OK || snell_renderer_read_exit_dirs(rd, b->one_dirs) != SNELL_OK) {
                ok = 0;
                break;
            }
            for (j = 0; j < b->n; j++) {
                if (!memcmp(b->one_dirs + 3 * j, b->bgdirs + 3 * j, 3 * sizeof(float)) &&
                    !memcmp(b->one_rgba + 4 * j, b->bg_rgba + 4 * j, 3))
                    continue;
                memcpy(b->alone_rgba + 4 * j, b->one_rgba + 4 * j, 4);
                memcpy(b->alone_dirs + 3 * j, b->one_dirs + 3 * j, 3 * sizeof(float));
                b->alone_mask[j] = 1;
            }
        }
    if (!ok) bench_fail(c, "glass objects drawn alone", ctx);
    snell_renderer_destroy(rc);
    snell_renderer_destroy(rd);
    return ok;
}

/* c->whole[]: the method's frame, the objects drawn alone and the isolated
 * FULL reference against the FULL reference of the whole scene. full: the
 * FULL reference compare() used (isolated unless the frame drew the scene
 * layers); the other one is rendered here. With one glass object both are
 * the same: nothing else to see through. */
static void whole_scene(snell_ctx *ctx, const snell_frame_desc *fd, const snell_glass *ref_glass, const char *env_name,
                        const bench_options *o, bench_config *c, measure_buf *b, const bench_ref_image *full)
{
    bench_ref_image other;
    const bench_ref_image *ref = full, *iso = full;
    const uint8_t *rgba[3];
    const float *dirs[3];
    const uint8_t *masks[3];
    int cached, k;
    size_t j;
    memset(&other, 0, sizeof other);
    if (fd->glass_count > 1) {
        if (!reference(fd, ref_glass, env_name, o, c, 1, c->layers_drawn, &other, &cached)) return;
        if (c->layers_drawn) iso = &other;
        else ref = &other;
        if (!alone_frames(ctx, fd, o->aa, c, b)) {
            bench_ref_free(&other);
            return;
        }
    } else {
        memcpy(b->alone_rgba, b->rgba, b->n * 4);
        memcpy(b->alone_dirs, b->dirs, b->n * 3 * sizeof(float));
        memcpy(b->alone_mask, b->mask, b->n);
    }
    rgba[0] = b->rgba, rgba[1] = b->alone_rgba, rgba[2] = iso->rgba;
    dirs[0] = b->dirs, dirs[1] = b->alone_dirs, dirs[2] = iso->exit_dir;
    masks[0] = b->mask, masks[1] = b->alone_mask, masks[2] = iso->hit;
    /* where other glass shows: the whole scene's colour is not the isolated one's */
    for (j = 0; j < b->n; j++) b->through[j] = (uint8_t)(memcmp(ref->rgba + 4 * j, iso->rgba + 4 * j, 3) != 0);
    for (k = 0; k < 3; k++) {
        if (bench_class_errors(rgba[k], ref->rgba, ref->object, b->through, c->width, c->height, b->either,
                               c->whole[k].cls) != SNELL_OK) {
            bench_fail(c, "class errors", NULL);
            break;
        }
        dir_error(dirs[k], masks[k], ref, b->err, &c->whole[k].dir);
    }
    c->whole_measured = k == 3;
    if (o->images_dir && c->whole_measured) {
        char path[1400], name[600];
        snprintf(name, sizeof name, "%s", c->spec);
        sanitize(name);
        snprintf(path, sizeof path, "%s/%s.alone.png", o->images_dir, name);
        write_png(path, c->width, c->height, b->alone_rgba);
        snprintf(path, sizeof path, "%s/%s.ref-scene.png", o->images_dir, name);
        write_png(path, c->width, c->height, ref->rgba);
    }
    bench_ref_free(&other);
}

/* --floor-aa: the FULL reference at floor_aa x floor_aa rays against full
 * (at --aa's), over the glass pixels of either: how far FULL itself is from
 * converged at the coarser sampling. */
static void full_floor(const snell_frame_desc *fd, const snell_glass *ref_glass, const char *env_name,
                       const bench_options *o, bench_config *c, measure_buf *b, const bench_ref_image *full)
{
    bench_options fo = *o;
    bench_ref_image coarse;
    int cached;
    size_t j;
    fo.aa = o->floor_aa;
    if (!reference(fd, ref_glass, env_name, &fo, c, 1, !c->layers_drawn, &coarse, &cached)) return;
    for (j = 0; j < b->n; j++) b->either[j] = (uint8_t)(coarse.hit[j] || full->hit[j]);
    snell_metrics_image_error(coarse.rgba, full->rgba, c->width, c->height, b->either, &c->floor_glass);
    bench_ref_free(&coarse);
}

void bench_measure(snell_ctx *ctx, const snell_env *env, const char *env_name, const bench_options *o,
                   bench_config *c)
{
    const bench_scene *s = NULL;
    snell_glass glass[SNELL_MAX_GLASS], ref_glass[SNELL_MAX_GLASS];
    snell_frame_desc fd;
    measure_buf b;
    memset(&b, 0, sizeof b);
    if (!c->ok) return; /* timing failed */
    if (!buf_alloc(&b, c)) {
        snprintf(c->error, sizeof c->error, "out of memory");
        c->ok = 0;
    } else if (bench_scene_get(ctx, c->scene, &s) != SNELL_OK) {
        bench_fail(c, "scene", ctx);
    } else {
        bench_scene_frame(c, s, env, glass, &fd);
        memcpy(ref_glass, glass, sizeof(snell_glass) * (size_t)fd.glass_count);
        c->glass_objects = fd.glass_count;
        c->angles_meaningful = s->analytic;
        c->opaque_objects = fd.opaque_count;
        if (bench_scene_lod(ctx, c, glass, fd.glass_count) != SNELL_OK) bench_fail(c, "lod", ctx);
        else if (colour_frame(ctx, &fd, o->aa, c, &b) && exit_dir_frames(ctx, &fd, c, &b) &&
                 compare(&fd, ref_glass, env_name, o, c, 0, &b, NULL)) {
            bench_ref_image full;
            if (compare(&fd, ref_glass, env_name, o, c, 1, &b, &full)) {
                whole_scene(ctx, &fd, ref_glass, env_name, o, c, &b, &full);
                if (o->floor_aa) full_floor(&fd, ref_glass, env_name, o, c, &b, &full);
                bench_ref_free(&full);
            }
        }
    }
    buf_free(&b);
}
