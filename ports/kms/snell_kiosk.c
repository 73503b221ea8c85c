/* SPDX-License-Identifier: MIT */
/* snell-kiosk — refractive glass full screen on a DRM/KMS display (issue 16).
 *
 * kmscube's pipeline: open the display (card, connector, mode, CRTC), make a
 * GBM surface and an EGL context on it, then per frame: snell_render into the
 * bound (window) framebuffer through the EXTERNAL backend, eglSwapBuffers,
 * lock the new front buffer and show it (a modeset for the first, a legacy
 * page flip after; the next frame renders while the flip waits for vblank).
 * SIGINT/SIGTERM end the loop; teardown waits for the queued flip, puts the
 * CRTC back as it was and checks it took. --bench times snell-bench
 * configurations on the display and writes snell-bench's JSON. kiosk.h lists
 * the files; main reads as the pipeline. */
#define _POSIX_C_SOURCE 200809L
#include "bench.h"
#include "cli_input.h"
#include "cli_scene.h"
#include "cli_system.h"
#include "cli_time.h"
#include "kiosk.h"
#include "kms_flip.h"
#include "kms_gpu.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PI 3.14159265358979323846
#define FLIP_TIMEOUT_MS 2000 /* a flip event later than this means the display is stuck */
#define MAX_INTERVALS 4096 /* show mode keeps the last this many frame intervals for the median */

static volatile sig_atomic_t g_stop;

static void on_signal(int sig)
{
    (void)sig;
    g_stop = 1;
}

/* The kiosk's state: the display, the GPU side, the flip machine and the
 * times at which frames reached the screen. */
typedef struct kiosk {
    kms_display disp;
    kms_gpu gpu;
    kms_flip flip;
    double last_shown_ms; /* when the last frame reached the screen (0: none yet), CLOCK_MONOTONIC */
    int record; /* intervals are being recorded */
    double intervals[MAX_INTERVALS]; /* ms between frames reaching the screen (ring) */
    long interval_count; /* recorded, in all */
    int display_failed; /* showing a frame failed on the display's side (then err: that call's -errno) */
    int err;
    char msg[1024];
} kiosk;

static void log_cb(snell_log_level level, const char *msg, void *user)
{
    (void)user;
    /* Errors come back as a status whose message (snell_last_error) the kiosk
     * prints where it fails: printing them here too said each one twice. */
    if (level == SNELL_LOG_WARN) fprintf(stderr, "snell-kiosk: snell: %s\n", msg);
}

/* A frame reached the screen at t_ms (CLOCK_MONOTONIC, as cli_now_ms). */
static void frame_shown(kiosk *k, double t_ms)
{
    if (k->record && k->last_shown_ms > 0) k->intervals[k->interval_count++ % MAX_INTERVALS] = t_ms - k->last_shown_ms;
    k->last_shown_ms = t_ms;
}

/* t_s: the kernel's time stamp of the vblank at which the flip took effect
 * (when the event is read is later: after the next frame's rendering). */
static void on_flip(void *user, double t_s)
{
    kiosk *k = (kiosk *)user;
    int ok;
    void *old = kms_flip_complete(&k->flip, &ok);
    if (!ok) return; /* not ours (no flip queued): nothing changed */
    kms_gpu_release(&k->gpu, (struct gbm_bo *)old);
    frame_shown(k, k->disp.monotonic_events ? t_s * 1000.0 : cli_now_ms());
}

/* Waits until no flip is queued (signals do not cut it short: the buffers
 * must not go while the display may still read one). */
static int wait_for_flip(kiosk *k)
{
    while (kms_flip_pending(&k->flip)) {
        int r = kms_display_wait(&k->disp, FLIP_TIMEOUT_MS, on_flip, k);
        k->display_failed = r == 0 || r == -1;
        k->err = r == -1 ? -errno : 0;
        if (r == 0) return snprintf(k->msg, sizeof k->msg, "no page-flip event within %d ms", FLIP_TIMEOUT_MS), 0;
        if (r == -1) return snprintf(k->msg, sizeof k->msg, "reading DRM events failed: %s", strerror(-k->err)), 0;
    }
    return 1;
}

/* Puts the frame just rendered on screen: swap, wait for the previous flip,
 * lock the new front buffer, modeset or queue its flip. */
static int present(kiosk *k)
{
    struct gbm_bo *bo;
    uint32_t fb;
    int r;
    if (!eglSwapBuffers(k->gpu.dpy, k->gpu.surf)) {
        k->display_failed = 1;
        return snprintf(k->msg, sizeof k->msg, "eglSwapBuffers failed (EGL error 0x%x)", eglGetError()), 0;
    }
    if (!wait_for_flip(k)) return 0;
    if (!(bo = kms_gpu_lock_front(&k->gpu, &k->disp, &fb, k->msg, sizeof k->msg))) return 0;
    if (kms_flip_next(&k->flip) == KMS_STEP_MODESET) {
        if ((r = kms_display_modeset(&k->disp, fb)) != 0) {
            kms_gpu_release(&k->gpu, bo);
            k->display_failed = 1;
            k->err = r;
            snprintf(k->msg, sizeof k->msg, "modeset of %dx%d on CRTC %u failed: %s%s", k->gpu.width, k->gpu.height,
                     k->disp.crtc_id, strerror(-r),
                     r == -EACCES || r == -EPERM ? " (another program, e.g. a desktop, is DRM master of this card)"
                                                 : "");
            return 0;
        }
        kms_flip_modeset_done(&k->flip, bo);
        frame_shown(k, cli_now_ms());
        return 1;
    }
    if ((r = kms_display_page_flip(&k->disp, fb)) != 0) {
        kms_gpu_release(&k->gpu, bo);
        k->display_failed = 1;
        k->err = r;
        return snprintf(k->msg, sizeof k->msg, "page flip failed: %s", strerror(-r)), 0;
    }
    if (!kms_flip_queued(&k->flip, bo)) /* GBM handed back the buffer on screen: cannot happen */
        return snprintf(k->msg, sizeof k->msg, "page flip to the buffer already on screen"), 0;
    return 1;
}

/* Renders one frame of fd into the window surface and shows it. */
static int frame(kiosk *k, snell_ctx *ctx, snell_renderer *r, const snell_frame_desc *fd, snell_frame_stats *stats)
{
    if (snell_render(r, fd, stats) != SNELL_OK)
        return snprintf(k->msg, sizeof k->msg, "snell_render: %s", snell_last_error(ctx)), 0;
    return present(k);
}

/* Median of the recorded intervals (the last MAX_INTERVALS), ms; NAN if none. */
static double interval_median(kiosk *k, double *min, double *max)
{
    long n = k->interval_count < MAX_INTERVALS ? k->interval_count : MAX_INTERVALS;
    double med;
    if (n == 0) return *min = *max = NAN;
    med = cli_median(k->intervals, (int)n); /* sorts: the ring's order no longer matters */
    *min = k->intervals[0];
    *max = k->intervals[n - 1];
    return med;
}

/* The configuration's renderer (width x height into target: the display's
 * bound framebuffer, or offscreen for --preview) and frame. */
static int scene_open(snell_ctx *ctx, const snell_env *env, const bench_config *c, int width, int height,
                      snell_target target, snell_renderer **r, snell_glass *glass, snell_frame_desc *fd, char *msg,
                      size_t n)
{
    snell_renderer_desc rd;
    const bench_scene *s;
    memset(&rd, 0, sizeof rd);
    rd.width = width;
    rd.height = height;
    rd.target = target;
    rd.shading = c->shading;
    if (bench_scene_get(ctx, c->scene, &s) != SNELL_OK)
        return snprintf(msg, n, "scene %s: %s", c->scene, snell_last_error(ctx)), 0;
    bench_scene_frame(c, s, env, glass, fd);
    fd->depth = SNELL_DEPTH_CLEAR; /* the kiosk's frame is all snell's: nothing drawn before it to keep */
    if (bench_scene_lod(ctx, c, glass, s->glass_count) != SNELL_OK)
        return snprintf(msg, n, "lod: %s", snell_last_error(ctx)), 0;
    if (snell_renderer_create(ctx, &rd, r) != SNELL_OK)
        return snprintf(msg, n, "renderer: %s", snell_last_error(ctx)), 0;
    return 1;
}

static int open_config(kiosk *k, snell_ctx *ctx, const snell_env *env, const bench_config *c, snell_renderer **r,
                       snell_glass *glass, snell_frame_desc *fd)
{
    return scene_open(ctx, env, c, k->gpu.width, k->gpu.height, SNELL_TARGET_BOUND_FRAMEBUFFER, r, glass, fd, k->msg,
                      sizeof k->msg);
}

/* Blocks until SIGINT or SIGTERM (sigsuspend: no signal is lost between the
 * check and the wait). */
static void wait_for_signal(void)
{
    sigset_t block, old;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigprocmask(SIG_BLOCK, &block, &old);
    while (!g_stop) sigsuspend(&old);
    sigprocmask(SIG_SETMASK, &old, NULL);
}

/* AUTO by budget: every configuration it may pick built and timed before the
 * first frame that counts (show mode and --preview). */
static int warm_for_budget(snell_ctx *ctx, snell_renderer *r, snell_frame_desc *fd)
{
    snell_warm_stats ws;
    if (snell_renderer_warm(r, fd, &ws) != SNELL_OK) {
        fprintf(stderr, "snell-kiosk: warming for the budget: %s\n", snell_last_error(ctx));
        return 0;
    }
    printf("snell-kiosk: warmed for the budget: %d frames in %.0f ms, %d configurations timed\n", ws.frames, ws.ms,
           ws.rungs);
    return 1;
}

/* Show mode: frames of configuration c, the camera turning spin_deg a frame. */
static int show(kiosk *k, snell_ctx *ctx, const snell_env *env, const bench_config *c, const kiosk_options *o)
{
    snell_renderer *r = NULL;
    snell_glass glass[SNELL_MAX_GLASS];
    snell_frame_desc fd, shown;
    snell_frame_stats stats;
    kiosk_panels kp;
    double t_start = cli_now_ms(), t_report = t_start, lo, hi;
    long i, frames_at_report = 0;
    int ok = open_config(k, ctx, env, c, &r, glass, &fd);
    kiosk_panels_open(&kp, o);
    k->record = 1;
    fd.budget_ms = o->budget_ms;
    if (ok && o->budget_ms > 0.0f) {
        fd.camera.azimuth = (float)(c->cam[0] * PI / 180.0);
        ok = warm_for_budget(ctx, r, &fd);
    }
    printf("snell-kiosk: showing %s at %dx%d\n", c->spec, k->gpu.width, k->gpu.height);
    for (i = 0; ok && !g_stop && (!o->frames || i < o->frames); i++) {
        fd.camera.azimuth = (float)((c->cam[0] + (double)i * o->spin_deg) * PI / 180.0);
        shown = fd;
        ok = kiosk_panels_frame(&kp, (cli_now_ms() - t_start) / 1000.0, &shown, k->msg, sizeof k->msg) &&
             frame(k, ctx, r, &shown, &stats);
        if (ok && o->report_s > 0 && cli_now_ms() - t_report >= o->report_s * 1000.0) {
            double now = cli_now_ms();
            printf("snell-kiosk: %ld frames, %.1f FPS over the last %.1f s\n", k->flip.frames,
                   (double)(k->flip.frames - frames_at_report) * 1000.0 / (now - t_report), (now - t_report) / 1000.0);
            if (o->budget_ms > 0.0f && stats.glass_count > 0)
                printf("snell-kiosk: budget %.1f ms: last frame %.2f ms; glass 0 %s\n", (double)o->budget_ms,
                       stats.budget_measured_ms, stats.glass[0].reason);
            fflush(stdout);
            t_report = now;
            frames_at_report = k->flip.frames;
        }
    }
    ok = ok && wait_for_flip(k);
    if (ok) {
        double med = interval_median(k, &lo, &hi), secs = (cli_now_ms() - t_start) / 1000.0;
        printf("snell-kiosk: %ld frames shown (%ld modeset + %ld page flips) in %.2f s; frame interval median %.3f ms "
               "(min %.3f, max %.3f) = %.2f FPS; last camera azimuth %.3f deg\n",
               k->flip.frames, k->flip.frames - k->flip.flips, k->flip.flips, secs, med, lo, hi, 1000.0 / med,
               c->cam[0] + (double)(i - 1) * o->spin_deg);
        if (o->hold && !g_stop) {
            printf("snell-kiosk: holding frame %ld on screen until SIGINT/SIGTERM\n", k->flip.frames);
            fflush(stdout);
            wait_for_signal();
        }
    }
    kiosk_panels_close(&kp);
    snell_renderer_destroy(r);
    return ok;
}

static int bench_done(bench_config *c, int ok, const char *msg, const snell_frame_stats *stats, int opaque_count);

/* One benchmark configuration: warm-up, then timed frames; c gets the
 * times and a glmark2-style line is printed. */
static int bench_one(kiosk *k, snell_ctx *ctx, const snell_env *env, bench_config *c, const kiosk_options *o)
{
    snell_renderer *r = NULL;
    snell_glass glass[SNELL_MAX_GLASS];
    snell_frame_desc fd;
    snell_frame_stats stats;
    long i;
    int ok = open_config(k, ctx, env, c, &r, glass, &fd);
    memset(&stats, 0, sizeof stats);
    k->record = 0;
    for (i = 0; ok && !g_stop && i < o->warmup + o->frames; i++) {
        if (i == o->warmup) k->record = 1, k->interval_count = 0;
        fd.camera.azimuth = (float)((c->cam[0] + (double)i * o->spin_deg) * PI / 180.0);
        ok = frame(k, ctx, r, &fd, &stats);
    }
    ok = ok && wait_for_flip(k) && !g_stop;
    k->record = 0;
    snell_renderer_destroy(r);
    if (ok && (k->interval_count < 1 || k->interval_count > MAX_INTERVALS ||
               !bench_frame_times(c, k->intervals, (int)k->interval_count)))
        ok = 0, snprintf(k->msg, sizeof k->msg, "%ld frame intervals recorded: want 1..%d", k->interval_count,
                         MAX_INTERVALS);
    return bench_done(c, ok, k->msg, &stats, fd.opaque_count);
}

/* --vsync off: one benchmark configuration drawn offscreen at the display's
 * size, each frame snell_render + snell_renderer_finish (glFinish) on the CPU
 * clock, as snell-bench times: what the GPU does when no refresh caps it.
 * Nothing reaches the screen. */
static int bench_offscreen(kiosk *k, snell_ctx *ctx, const snell_env *env, bench_config *c, const kiosk_options *o)
{
    snell_renderer *r = NULL;
    snell_glass glass[SNELL_MAX_GLASS];
    snell_frame_desc fd;
    snell_frame_stats stats;
    double *ms = (double *)malloc(sizeof(double) * (size_t)o->frames);
    long i;
    int ok = ms && scene_open(ctx, env, c, k->gpu.width, k->gpu.height, SNELL_TARGET_OFFSCREEN, &r, glass, &fd,
                              k->msg, sizeof k->msg);
    if (!ms) snprintf(k->msg, sizeof k->msg, "out of memory for %ld frame times", o->frames);
    memset(&stats, 0, sizeof stats);
    for (i = 0; ok && !g_stop && i < o->warmup + o->frames; i++) {
        double t0 = cli_now_ms();
        fd.camera.azimuth = (float)((c->cam[0] + (double)i * o->spin_deg) * PI / 180.0);
        if (snell_render(r, &fd, &stats) != SNELL_OK)
            ok = 0, snprintf(k->msg, sizeof k->msg, "snell_render: %s", snell_last_error(ctx));
        snell_renderer_finish(r);
        if (i >= o->warmup) ms[i - o->warmup] = cli_now_ms() - t0;
    }
    snell_renderer_destroy(r);
    ok = ok && !g_stop && bench_frame_times(c, ms, (int)o->frames);
    free(ms);
    return bench_done(c, ok, k->msg, &stats, fd.opaque_count);
}

/* The end of one benchmark configuration: c's fields, and the glmark2-style line. */
static int bench_done(bench_config *c, int ok, const char *msg, const snell_frame_stats *stats, int opaque_count)
{
    int g;
    if (!ok) {
        snprintf(c->error, sizeof c->error, "%.200s", g_stop ? "interrupted" : msg);
        c->ok = 0;
        return 0;
    }
    c->ok = 1;
    c->gpu_median = c->vs_single = -1.0;
    c->encoding = "none"; /* no exit directions: times only */
    c->glass_objects = stats->glass_count;
    c->opaque_objects = opaque_count;
    for (g = 0; g < stats->glass_count; g++) c->warnings += stats->glass[g].warning;
    /* glmark2: "[scene] options: FPS: n FrameTime: t ms" */
    printf("[%s] %s: FPS: %.0f FrameTime: %.3f ms\n", c->method->name, c->spec + strlen(c->method->name) + 1,
           1000.0 / c->t_median, c->t_median);
    fflush(stdout);
    return 1;
}

/* Configurations from -b (or the defaults) at the display's size. */
static int expand_configs(const kiosk_options *o, snell_ctx *ctx, const snell_env *env, bench_options *bo,
                          bench_config *cs, int *n, int width, int height)
{
    int i;
    memset(bo, 0, sizeof *bo);
    snprintf(bo->scenes, sizeof bo->scenes, "%s", o->bench ? "bunny" : "sphere");
    snprintf(bo->sizes, sizeof bo->sizes, "%dx%d", width, height);
    bo->frames = (int)o->frames;
    bo->warmup = o->warmup;
    bo->plot_y = "full-mean";
    for (i = 0; i < o->spec_count; i++)
        if (!bench_expand_spec(o->specs[i], bo, cs, n)) return 0;
    if (!o->spec_count) {
        if (!o->bench) return bench_expand_spec("cubemap", bo, cs, n);
        for (i = 0; i < snell_method_count(); i++)
            if (bench_method_works(ctx, env, snell_method_info_at(i)) &&
                !bench_expand_spec(snell_method_info_at(i)->name, bo, cs, n))
                return 0;
    }
    for (i = 0; i < *n; i++)
        if (cs[i].width != width || cs[i].height != height) {
            fprintf(stderr, "snell-kiosk: %s: the kiosk renders full screen, %dx%d (leave out size=)\n", cs[i].spec,
                    width, height);
            return 0;
        }
    if (!o->bench && *n != 1) {
        fprintf(stderr, "snell-kiosk: -b %s is %d configurations; show one, or time them with --bench\n", o->specs[0],
                *n);
        return 0;
    }
    return 1;
}

/* --bench: every configuration, the score, the JSON. */
static int bench(kiosk *k, snell_ctx *ctx, const snell_env *env, bench_config *cs, int n, const bench_options *bo,
                 const kiosk_options *o)
{
    char load_before[64], load_after[64], date[64];
    time_t now = time(NULL);
    bench_run_info run;
    cli_system sys;
    double fps_sum = 0.0;
    int i, done = 0, ok = 1;
    cli_loadavg(load_before, sizeof load_before);
    strftime(date, sizeof date, "%Y-%m-%d %H:%M", localtime(&now));
    printf("snell-kiosk: %d configuration(s) on %s at %dx%d, %d warm-up + %ld timed frames each, vsync %s; load %s\n",
           n, snell_ctx_gl_renderer(ctx), k->gpu.width, k->gpu.height, o->warmup, o->frames,
           o->vsync_off ? "off (offscreen)" : "on (page flips)", load_before);
    for (i = 0; i < n && !g_stop; i++) {
        if (o->vsync_off ? bench_offscreen(k, ctx, env, &cs[i], o) : bench_one(k, ctx, env, &cs[i], o))
            fps_sum += 1000.0 / cs[i].t_median, done++;
        else
            fprintf(stderr, "snell-kiosk: %s FAILED: %s\n", cs[i].spec, cs[i].error), ok = 0;
    }
    cli_loadavg(load_after, sizeof load_after);
    memset(&run, 0, sizeof run);
    run.tool = "snell-kiosk";
    run.no_errors = 1;
    run.timing = o->vsync_off
                     ? "frames after warm-up drawn offscreen at the display's size, each = snell_render + glFinish "
                       "(CPU wall clock), nothing shown; no error measurement (the vs_* fields are null)"
                     : "frame intervals after warm-up: time between successive frames reaching the screen (the "
                       "kernel's vblank time stamps of the page-flip events); each frame = snell_render into the "
                       "window surface + eglSwapBuffers + a page flip at vblank, the next frame rendered while the "
                       "flip waits; no error measurement (the vs_* fields are null)";
    run.vsync = o->vsync_off ? "off: offscreen frames at the display's size, each ended by glFinish"
                             : "on: page-flipped at vblank, capped at the refresh rate";
    cli_system_read(&sys);
    run.system = &sys;
    run.renderer = snell_ctx_gl_renderer(ctx);
    run.date = date;
    run.load_before = load_before;
    run.load_after = load_after;
    for (i = 0; i < n; i++)
        if (!cs[i].ok && !cs[i].error[0]) snprintf(cs[i].error, sizeof cs[i].error, "not run (interrupted)");
    if (done) printf("snell-kiosk Score: %.0f\n", fps_sum / done);
    errno = 0;
    if (!bench_write_json(o->json, cs, n, bo, &run)) {
        fprintf(stderr, "snell-kiosk: cannot write '%s': %s\n", o->json, errno ? strerror(errno) : "write failed");
        ok = 0;
    } else {
        printf("wrote %s\n", o->json);
    }
    return ok && !g_stop;
}

/* No error measurement in the kiosk: every error field is "not measured". */
static void no_errors(bench_config *cs, int n)
{
    int i, m;
    for (i = 0; i < n; i++)
        for (m = 0; m < 2; m++) {
            snell_dir_error *d = &cs[i].dir[m];
            d->mean_deg = d->rms_deg = d->median_deg = d->p99_deg = d->max_deg = NAN;
            d->frac_above_1deg = d->frac_above_5deg = NAN;
            cs[i].img[m].rmse = cs[i].img[m].psnr_db = cs[i].img_glass[m].rmse = cs[i].img_glass[m].psnr_db = NAN;
        }
}

/* After a failure on the display's side: 1 if the display went away
 * (unplugged, its card gone), which the kiosk reports with its own exit
 * status for a supervisor to restart it on (docs/kiosk.md "As a service"). */
static int display_lost(kiosk *k)
{
    kms_connector_info now;
    if (!k->display_failed) return 0;
    memset(&now, 0, sizeof now);
    now.id = k->disp.connector_id;
    if (!kms_display_recheck(&k->disp, &now.connection, &now.mode_count)) return kms_display_gone(k->err, NULL);
    return kms_display_gone(k->err, &now);
}

/* Teardown in reverse: the queued flip lands, the CRTC gets its old
 * framebuffer back (checked), then the buffers and the display go. */
static int close_display(kiosk *k, int display_shown, int lost)
{
    int ok = 1;
    if (display_shown && !lost) { /* a display that went away has nothing to wait for or restore */
        if (!wait_for_flip(k)) fprintf(stderr, "snell-kiosk: %s\n", k->msg), ok = 0;
        ok = kms_display_restore(&k->disp, k->msg, sizeof k->msg) && ok;
        fprintf(ok ? stdout : stderr, "snell-kiosk: %s\n", k->msg);
    }
    if (display_shown) {
        kms_gpu_release(&k->gpu, (struct gbm_bo *)k->flip.shown);
        kms_gpu_release(&k->gpu, (struct gbm_bo *)k->flip.queued);
    }
    kms_gpu_close(&k->gpu);
    kms_display_close(&k->disp);
    return ok;
}

/* --preview: no display, no DRM. The options and the scene go through the
 * checks a run on the device makes, then the first frame it would show is
 * drawn offscreen at the --mode size and written as PNG. Exit status as the
 * kiosk's: 2 for bad usage (a -b that does not parse included), 1 on failure. */
static int preview(const kiosk_options *o)
{
    static bench_options bo;
    snell_ctx *ctx = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_glass glass[SNELL_MAX_GLASS];
    snell_frame_desc fd;
    snell_frame_stats stats;
    kiosk_panels kp;
    bench_config *cs = (bench_config *)calloc(BENCH_MAX_CONFIGS, sizeof *cs);
    uint8_t *rgba = NULL;
    int w = o->display.mode.width ? o->display.mode.width : 1920;
    int h = o->display.mode.height ? o->display.mode.height : 1080;
    int n = 0, status = 1;
    char msg[1024];
    if (!cs) return fprintf(stderr, "snell-kiosk: out of memory\n"), 1;
    kiosk_panels_open(&kp, o);
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-kiosk: --preview: %s\n", snell_last_error(NULL));
        goto done;
    }
    if (cli_env_open(ctx, NULL, &env) != SNELL_OK) {
        fprintf(stderr, "snell-kiosk: environment: %s\n", snell_last_error(ctx));
        goto done;
    }
    if (!expand_configs(o, ctx, env, &bo, cs, &n, w, h)) {
        status = 2;
        goto done;
    }
    if (!scene_open(ctx, env, &cs[0], w, h, SNELL_TARGET_OFFSCREEN, &r, glass, &fd, msg, sizeof msg)) {
        fprintf(stderr, "snell-kiosk: %s\n", msg);
        goto done;
    }
    fd.camera.azimuth = (float)(cs[0].cam[0] * PI / 180.0);
    fd.budget_ms = o->budget_ms;
    if (o->budget_ms > 0.0f && !warm_for_budget(ctx, r, &fd)) goto done;
    if (!(rgba = (uint8_t *)malloc((size_t)w * (size_t)h * 4))) {
        fprintf(stderr, "snell-kiosk: out of memory for a %dx%d preview\n", w, h);
        goto done;
    }
    if (!kiosk_panels_frame(&kp, 0.0, &fd, msg, sizeof msg)) {
        fprintf(stderr, "snell-kiosk: %s\n", msg);
        goto done;
    }
    if (snell_render(r, &fd, &stats) != SNELL_OK || snell_renderer_read_rgba(r, rgba) != SNELL_OK) {
        char where[300];
        fprintf(stderr, "snell-kiosk: --preview %s: %s%s\n", o->preview, snell_last_error(ctx),
                cli_panels_where(&o->panels, o->panels_file ? o->panels_file : "", snell_last_error(ctx), where,
                                 sizeof where));
        goto done;
    }
    if (snell_write_png(o->preview, w, h, rgba) != SNELL_OK) { /* a call without a context: its message is the thread's */
        fprintf(stderr, "snell-kiosk: --preview: %s\n", snell_last_error(NULL));
        goto done;
    }
    printf("snell-kiosk: preview of %s at %dx%d (%s) written to %s\n",
           o->slide_count ? "the first slide" : cs[0].spec, w, h, snell_ctx_gl_renderer(ctx), o->preview);
    if (o->panels.count)
        printf("snell-kiosk: %d panels from %s: %d drawn, %d captures; %s\n", o->panels.count, o->panels_file,
               stats.panels_drawn, stats.panels_captures, stats.panels_reason);
    status = 0;
done:
    free(rgba);
    kiosk_panels_close(&kp);
    snell_renderer_destroy(r);
    bench_scene_release_all();
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    free(cs);
    return status;
}

/* The -b specs parse (sizes aside, which are the display's): a typo is bad
 * usage, exit 2, on a machine without a display as on one with it. */
static int specs_parse(const kiosk_options *o)
{
    static bench_options bo;
    bench_config *cs;
    int i, n = 0, ok = 1;
    if (!o->spec_count) return 1;
    if (!(cs = (bench_config *)calloc(BENCH_MAX_CONFIGS, sizeof *cs))) return 1; /* checked again later */
    memset(&bo, 0, sizeof bo);
    snprintf(bo.scenes, sizeof bo.scenes, "sphere");
    snprintf(bo.sizes, sizeof bo.sizes, "64x64");
    bo.frames = 1;
    bo.plot_y = "full-mean";
    for (i = 0; i < o->spec_count && ok; i++) ok = bench_expand_spec(o->specs[i], &bo, cs, &n);
    free(cs);
    return ok;
}

int main(int argc, char **argv)
{
    static kiosk_options o;
    static kiosk k;
    static bench_options bo;
    bench_config *cs = NULL;
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_env *env = NULL;
    struct sigaction sa;
    int n = 0, ok = 0, usage_ok = 1, lost = 0, r;

    bench_prog = "snell-kiosk"; /* the shared spec parser's messages */
    if (!cli_args_clean("snell-kiosk", argc, argv)) return 2;
    if ((r = kiosk_parse_options(argc, argv, &o)) <= 0) return r < 0 ? 0 : 2;
    if (!specs_parse(&o)) return 2;
    if (o.preview) return preview(&o);
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal; /* no SA_RESTART: a blocked poll returns at once */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    switch (kms_display_open(&k.disp, &o.display, k.msg, sizeof k.msg)) {
    case KMS_OPEN_NO_DISPLAY:
        fprintf(stderr, "snell-kiosk: %s; nothing to show on (exit %d)\n", k.msg, KIOSK_EXIT_NO_DISPLAY);
        return KIOSK_EXIT_NO_DISPLAY;
    case KMS_OPEN_FAILED:
        fprintf(stderr, "snell-kiosk: %s\n", k.msg);
        kms_display_close(&k.disp);
        return 1;
    case KMS_OPEN_OK: printf("snell-kiosk: %s\n", k.msg); break;
    }
    kms_flip_init(&k.flip);
    if (!kms_gpu_open(&k.gpu, &k.disp, k.msg, sizeof k.msg)) {
        fprintf(stderr, "snell-kiosk: %s\n", k.msg);
        goto done;
    }
    printf("snell-kiosk: %s\n", k.msg);
    memset(&cd, 0, sizeof cd);
    cd.backend = SNELL_BACKEND_EXTERNAL; /* the kiosk's context; snell restores the GL state it changes */
    cd.log = log_cb;
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-kiosk: snell on the kiosk's context: %s\n", snell_last_error(NULL));
        goto done;
    }
    printf("snell-kiosk: %s, precision %s\n", snell_ctx_gl_renderer(ctx), snell_ctx_precision(ctx));
    if (cli_env_open(ctx, NULL, &env) != SNELL_OK) {
        fprintf(stderr, "snell-kiosk: environment: %s\n", snell_last_error(ctx));
        goto done;
    }
    if (!(cs = (bench_config *)calloc(BENCH_MAX_CONFIGS, sizeof *cs))) {
        fprintf(stderr, "snell-kiosk: out of memory\n");
        goto done;
    }
    /* A -b that does not parse is bad usage, found only now: sizes are the mode's. */
    if (!(usage_ok = expand_configs(&o, ctx, env, &bo, cs, &n, k.gpu.width, k.gpu.height))) goto done;
    no_errors(cs, n);
    fflush(stdout);
    ok = o.bench ? bench(&k, ctx, env, cs, n, &bo, &o) : show(&k, ctx, env, cs, &o);
    if (!ok && k.msg[0] && !o.bench) fprintf(stderr, "snell-kiosk: %s\n", k.msg);
    if (!ok && (lost = display_lost(&k)))
        fprintf(stderr, "snell-kiosk: the display went away (connector %u on %s); exit %d for a restart\n",
                k.disp.connector_id, k.disp.path, KIOSK_EXIT_DISPLAY_LOST);
done:
    bench_configs_free(cs, n);
    bench_scene_release_all();
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    free(cs);
    ok = close_display(&k, k.flip.shown != NULL, lost) && ok;
    return !usage_ok ? 2 : lost ? KIOSK_EXIT_DISPLAY_LOST : ok ? 0 : 1;
}
