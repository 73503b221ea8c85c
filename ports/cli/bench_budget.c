/* SPDX-License-Identifier: MIT */
/* bench_budget.c — snell-bench --budget: AUTO by frame budget against every
 * fixed configuration of its rung table (issue 25 item 3), on a moving
 * camera. Per scene: AUTO with the budget and each rung (every glass object
 * on it) get a renderer each and take turns frame by frame over the same
 * camera path (the camera turns --spin degrees a frame), so load drift hits
 * all alike; each frame is snell_render + snell_renderer_finish on the CPU
 * clock. At --samples frames spread over the run every configuration's
 * image is kept and measured against the FULL reference of that camera
 * (glass pixels, pixel centres). The table: median, 95th percentile and
 * worst frame, frames over 110% of the budget, mean glass PSNR; and the
 * best fixed configuration whose 95th percentile meets the budget, beside
 * AUTO. The rung table itself is printed first: the frontier AUTO chooses
 * from. */
#include "bench.h"
#include "bench_ref.h"
#include "cli_opts.h"
#include "cli_progress.h"
#include "cli_system.h"
#include "cli_time.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_CONFIGS 16
#define MAX_SAMPLES 8

typedef struct budget_opts {
    const char *scene;
    int width, height, frames, samples, threads, warmup, every;
    float spin, budget_ms, budget_x; /* budget_x > 0: the budget is that many times single's median */
    float ior;                      /* of every glass object of a mesh scene (0: 1.5) */
    int exact_auto;                 /* AUTO's objects let exact on their ladders (material.exact.auto_pick) */
    int no_warm;                    /* --warm off: AUTO starts cold (the table's costs, first uses in the run) */
    const char *cache;
    const char *out_prefix;         /* -o: PREFIX.json, PREFIX.csv */
    int quiet;                      /* -q: no rung table, no progress */
} budget_opts;

typedef struct budget_config {
    char name[112];
    int rung;                       /* -1: AUTO with the budget */
    snell_renderer *r;
    snell_glass glass[SNELL_MAX_GLASS];
    snell_frame_desc fd;
    double *ms;
    uint8_t *img[MAX_SAMPLES];
    double psnr[MAX_SAMPLES];
    char drawn[MAX_SAMPLES][160];   /* AUTO: what drew each object at the sample */
    int changes, over, over_steady, first_use, n_ms; /* n_ms: frames drawn (fixed: every K-th) */
    unsigned char *first; /* AUTO: frames that drew a configuration for the first time */
    int n_slow;                     /* AUTO: frames over 110% of the budget noted in slow[] */
    char slow[8][200];
} budget_config;

static void usage(void)
{
    printf("usage: snell-bench --budget MS|Nx [--scene S] [--sizes WxH] [--frames F] [--spin DEG] [--samples K]\n"
           "                   [--fixed-every K] [--ior N] [--exact-auto allow|never] [--threads T]\n"
           "                   [--warm on|off] [--cache DIR] [-o PREFIX] [-q]\n"
           "AUTO by frame budget (snell_frame_desc.budget_ms) against every fixed configuration of its rung\n"
           "table, frame by frame on a moving camera. MS: the budget in ms; Nx: N times single's median frame\n"
           "(measured first). AUTO draws every frame, the fixed configurations every K-th (and at the\n"
           "samples). AUTO's renderer is first warmed (snell_renderer_warm: every rung of its ladders built\n"
           "and timed on this device) unless --warm off. Writes PREFIX.json and PREFIX.csv as snell-bench\n"
           "does (every frame's time, p50/p95/p99/1%% low, the glass PSNR vs FULL as vs_full.psnr_glass_db).\n"
           "Defaults: --scene bunny --sizes 256x256 --frames 300 --spin 1.2 --samples 4 --fixed-every 5\n"
           "--warm on -o snell-bench-budget.\n");
}

/* An integer option in lo..hi. */
static int int_opt(const char *name, const char *v, int lo, int hi, int *out)
{
    char key[48];
    snprintf(key, sizeof key, "--budget: %s", name);
    return bench_parse_int(key, v, lo, hi, out);
}

/* A number option in lo..hi. */
static int float_opt(const char *name, const char *v, float lo, float hi, float *out)
{
    char *end;
    double x = strtod(v, &end);
    if (end == v || *end || !isfinite(x) || x < lo || x > hi) {
        fprintf(stderr, "snell-bench --budget: %s %s: want a number in %g..%g\n", name, v, (double)lo, (double)hi);
        return 0;
    }
    *out = (float)x;
    return 1;
}

static int parse(int argc, char **argv, budget_opts *o)
{
    static const struct option longopts[] = {
        {"budget", required_argument, NULL, 'B'}, {"scene", required_argument, NULL, 's'},
        {"sizes", required_argument, NULL, 'S'},  {"frames", required_argument, NULL, 'f'},
        {"samples", required_argument, NULL, 'k'}, {"fixed-every", required_argument, NULL, 'e'},
        {"threads", required_argument, NULL, 't'}, {"spin", required_argument, NULL, 'p'},
        {"cache", required_argument, NULL, 'c'},  {"ior", required_argument, NULL, 'i'},
        {"exact-auto", required_argument, NULL, 'x'}, {"warm", required_argument, NULL, 'w'},
        {"help", no_argument, NULL, 'h'},          {NULL, 0, NULL, 0}};
    int c;
    char tail;
    memset(o, 0, sizeof *o);
    o->scene = "bunny";
    o->width = o->height = 256;
    o->frames = 300;
    o->samples = 4;
    o->spin = 1.2f;
    o->warmup = 3;
    o->every = 5;
    o->cache = "snell-bench-cache";
    o->out_prefix = "snell-bench-budget";
    if (cli_wants_help(argc, argv)) { /* wherever it is */
        usage();
        return -1;
    }
    cli_opts_reset();
    while ((c = cli_getopt("snell-bench --budget", "--budget --help", argc, argv, "o:qh", longopts)) != -1) {
        const char *v = optarg;
        char *end = NULL;
        switch (c) {
        case 'B': {
            double x = strtod(v, &end);
            o->budget_ms = o->budget_x = 0.0f;
            if (x > 0.0 && isfinite(x) && end && (*end == 'x' || *end == 'X') && end[1] == 0) o->budget_x = (float)x;
            else if (x > 0.0 && isfinite(x) && end && *end == 0) o->budget_ms = (float)x;
            else {
                fprintf(stderr, "snell-bench --budget %s: want a budget in ms (e.g. 40) or times single's frame "
                                "(e.g. 4x)\n", v);
                return 0;
            }
            break;
        }
        case 's': o->scene = v; break;
        case 'S':
            if (sscanf(v, "%dx%d%c", &o->width, &o->height, &tail) != 2 || o->width < 16 || o->height < 16 ||
                o->width > 2048 || o->height > 2048) {
                fprintf(stderr, "snell-bench --budget: --sizes %s: want one size WxH within 16..2048\n", v);
                return 0;
            }
            break;
        case 'f': if (!int_opt("--frames", v, 10, 100000, &o->frames)) return 0; break;
        case 'k': if (!int_opt("--samples", v, 1, MAX_SAMPLES, &o->samples)) return 0; break;
        case 'e': if (!int_opt("--fixed-every", v, 1, 100000, &o->every)) return 0; break;
        case 't': if (!int_opt("--threads", v, 0, SNELL_REF_MAX_THREADS, &o->threads)) return 0; break;
        case 'p': if (!float_opt("--spin", v, -360.0f, 360.0f, &o->spin)) return 0; break;
        case 'c': o->cache = v; break;
        case 'i': if (!float_opt("--ior", v, 1.0f, 4.0f, &o->ior)) return 0; break;
        case 'x':
            if (strcmp(v, "allow") && strcmp(v, "never")) {
                fprintf(stderr, "snell-bench --budget: --exact-auto %s: allow or never\n", v);
                return 0;
            }
            o->exact_auto = !strcmp(v, "allow");
            break;
        case 'w':
            if (strcmp(v, "on") && strcmp(v, "off")) {
                fprintf(stderr, "snell-bench --budget: --warm %s: on or off\n", v);
                return 0;
            }
            o->no_warm = !strcmp(v, "off");
            break;
        case 'o': o->out_prefix = v; break;
        case 'q': o->quiet = 1; break;
        default: return 0; /* '?': the message is printed */
        }
    }
    if (optind < argc) {
        fprintf(stderr, "snell-bench --budget: unexpected argument '%s'; see --budget --help\n", argv[optind]);
        return 0;
    }
    if (!(o->budget_ms > 0.0f) && !(o->budget_x > 0.0f)) {
        fprintf(stderr, "snell-bench --budget: needs a budget in ms (e.g. 40) or times single's frame (e.g. 4x)\n");
        return 0;
    }
    if (o->every > o->frames) {
        fprintf(stderr, "snell-bench --budget: --fixed-every %d: at most --frames (%d)\n", o->every, o->frames);
        return 0;
    }
    return 1;
}

/* Rung g written into m as the library's budget stage writes it: method, scale, param=value and each
 * further "name=value" of g->more. */
static void apply_rung(const snell_budget_rung *g, snell_glass_material *m)
{
    char v[16], more[160], *p, *eq;
    m->method = g->method;
    m->scale = g->scale > 1 ? (float)g->scale : 1.0f;
    snprintf(v, sizeof v, "%d", g->value);
    if (g->param) snell_glass_set_param(m, g->method, g->param, v);
    snprintf(more, sizeof more, "%s", g->param && g->more ? g->more : "");
    for (p = strtok(more, ":"); p; p = strtok(NULL, ":"))
        if ((eq = strchr(p, '=')) != NULL) {
            *eq = '\0';
            snell_glass_set_param(m, g->method, p, eq + 1);
        }
}

/* "peel layers=2 scale=2", "exact max_interfaces=10:fresnel=exact:...", as the library's reasons name a rung. */
static void rung_name(const snell_budget_rung *g, char *buf, size_t n)
{
    char param[40] = "", scale[24] = "";
    if (g->param) snprintf(param, sizeof param, " %s=%d", g->param, g->value);
    if (g->scale > 1) snprintf(scale, sizeof scale, " scale=%d", g->scale);
    snprintf(buf, n, "%s%s%s%s%s", snell_method_str(g->method), param, g->param && g->more ? ":" : "",
             g->param && g->more ? g->more : "", scale);
}

static void print_table(void)
{
    int i, c;
    printf("the rung table (snell_budget_rung_at): frame time x single / glass PSNR vs FULL per mesh class\n");
    printf("  %-22s %18s %18s %18s %18s\n", "configuration", "convex", "cubemap-served", "deep concave",
           "open");
    for (i = 0; i < snell_budget_rung_count(); i++) {
        const snell_budget_rung *g = snell_budget_rung_at(i);
        char name[112];
        rung_name(g, name, sizeof name);
        printf("  %-22s", name);
        for (c = 0; c < 4; c++) {
            if (g->db[c] > 0.0f) printf("     %5.2fx %5.2f dB", (double)g->cost[c], (double)g->db[c]);
            else printf("     %18s", "-");
        }
        printf("\n");
    }
}

/* Configuration k's frame: the scene's objects with its material. */
static void frame_of(const bench_scene *s, const snell_env *env, budget_config *k, const float cam[3],
                     const budget_opts *o)
{
    int i;
    memset(&k->fd, 0, sizeof k->fd);
    for (i = 0; i < s->glass_count; i++) {
        k->glass[i] = s->glass[i];
        if (!s->file) {
            memset(&k->glass[i].material, 0, sizeof k->glass[i].material);
            k->glass[i].material.ior = o->ior > 0.0f ? o->ior : 1.5f;
        }
        if (k->rung >= 0) {
            const snell_budget_rung *g = snell_budget_rung_at(k->rung);
            apply_rung(g, &k->glass[i].material);
        } else {
            k->glass[i].material.method = SNELL_METHOD_AUTO;
            if (o->exact_auto) k->glass[i].material.exact.auto_pick = SNELL_EXACT_AUTO_ALLOW;
        }
    }
    k->fd.env = env;
    k->fd.glass = k->glass;
    k->fd.glass_count = s->glass_count;
    k->fd.opaque = s->opaque;
    k->fd.opaque_count = s->opaque_count;
    k->fd.camera = s->has_camera ? s->camera : (snell_camera){0};
    if (!s->has_camera) {
        k->fd.camera.azimuth = cam[0] * 3.14159265f / 180.0f;
        k->fd.camera.elevation = cam[1] * 3.14159265f / 180.0f;
        k->fd.camera.distance = cam[2];
    }
}

/* cli_percentile of a copy: v keeps its frame order. */
static double percentile(const double *v, int n, double p)
{
    double *t = (double *)malloc(sizeof(double) * (size_t)n), r;
    if (!t) return -1.0;
    memcpy(t, v, sizeof(double) * (size_t)n);
    r = cli_percentile(t, n, p);
    free(t);
    return r;
}

/* The camera's azimuth at frame index f of the path (turning --spin degrees a frame from az0). */
static float azimuth_at(const budget_opts *o, float az0, int f) { return az0 + (float)f * o->spin * 3.14159265f / 180.0f; }

/* One frame of k at frame index f (camera turned f * spin from the start); its ms. */
static double frame(snell_ctx *ctx, budget_config *k, const budget_opts *o, float az0, int f, snell_frame_stats *st,
                    int *ok)
{
    double t0;
    k->fd.camera.azimuth = azimuth_at(o, az0, f);
    t0 = cli_now_ms();
    if (snell_render(k->r, &k->fd, st) != SNELL_OK) {
        fprintf(stderr, "snell-bench --budget: %s: %s\n", k->name, snell_last_error(ctx));
        *ok = 0;
    }
    snell_renderer_finish(k->r);
    return cli_now_ms() - t0;
}

/* The glass PSNR of img against the FULL reference of k's frame at frame f. */
static int measure(const budget_opts *o, const bench_scene *s, budget_config *ks, int n, int f, int j, float az0)
{
    snell_ref_desc scene;
    snell_ref_params p;
    bench_ref_image ref;
    bench_class_error cls[BENCH_CLASS_COUNT];
    uint8_t *mask = (uint8_t *)malloc((size_t)o->width * o->height);
    snell_glass ref_glass[SNELL_MAX_GLASS];
    int cached = 0, k, i;
    cli_progress bar;
    if (!mask) return 0;
    /* the reference's materials: the scene's optics (AUTO's configuration carries no method parameters) */
    memcpy(ref_glass, ks[0].glass, sizeof ref_glass);
    for (i = 0; i < s->glass_count; i++) ref_glass[i].material.method = SNELL_METHOD_AUTO;
    memset(&scene, 0, sizeof scene);
    scene.glass = ref_glass;
    scene.glass_count = s->glass_count;
    scene.opaque = s->opaque;
    scene.opaque_count = s->opaque_count;
    memset(&p, 0, sizeof p);
    p.mode = SNELL_REF_FULL;
    p.max_interfaces = 10;
    p.absorption_model = SNELL_REF_ABSORB_PATH;
    p.env = ks[0].fd.env;
    p.camera = ks[0].fd.camera;
    p.camera.azimuth = azimuth_at(o, az0, f);
    p.width = o->width;
    p.height = o->height;
    p.threads = o->threads;
    p.samples = 1;
    if (!o->quiet && cli_progress_wanted(0)) { /* a trace (not a cache hit) shows its progress on a terminal */
        cli_progress_start(&bar, "reference FULL");
        p.progress = cli_progress_report;
        p.progress_user = &bar;
    }
    if (bench_ref_get(&scene, &p, "procedural", o->cache, &ref, &cached) != SNELL_OK) {
        fprintf(stderr, "snell-bench --budget: FULL reference: %s\n", snell_last_error(NULL));
        free(mask);
        return 0;
    }
    for (k = 0; k < n; k++) {
        ks[k].psnr[j] = -1.0;
        if (bench_class_errors(ks[k].img[j], ref.rgba, ref.object, NULL, o->width, o->height, mask, cls) == SNELL_OK)
            ks[k].psnr[j] = cls[BENCH_CLASS_GLASS].img.psnr_db;
    }
    bench_ref_free(&ref);
    free(mask);
    return 1;
}

/* PREFIX.json and PREFIX.csv in snell-bench's form: one result per
 * configuration (AUTO first), spec "METHOD:scene=S:size=WxH" plus the rung's
 * parameter and scale or AUTO's budget, its frame times, and the mean glass
 * PSNR of its samples as vs_full.psnr_glass_db. 1 if both were written. */
static int write_files(const budget_opts *o, const budget_config *ks, int n, const char *load0, const char *load1,
                       snell_ctx *ctx, double psnr_mean[MAX_CONFIGS])
{
    bench_config *cs = (bench_config *)calloc((size_t)n, sizeof *cs);
    bench_options bo;
    bench_run_info run;
    cli_system sys;
    char path[1200], date[64], timing[256];
    time_t now = time(NULL);
    int k, m, ok = 1;
    if (!cs) return 0;
    memset(&bo, 0, sizeof bo);
    bo.frames = o->frames;
    bo.warmup = o->warmup;
    bo.full_interfaces = 10;
    bo.aa = 1;
    for (k = 0; k < n; k++) {
        bench_config *c = &cs[k];
        const snell_budget_rung *g = ks[k].rung >= 0 ? snell_budget_rung_at(ks[k].rung) : NULL;
        char extra[160] = "";
        c->method = bench_method_info(g ? g->method : SNELL_METHOD_AUTO);
        if (!g) snprintf(extra, sizeof extra, ":budget_ms=%.2f", (double)o->budget_ms);
        else if (g->param) snprintf(extra, sizeof extra, ":%s=%d", g->param, g->value);
        if (g && g->more) snprintf(extra + strlen(extra), sizeof extra - strlen(extra), ":%s", g->more);
        if (g && g->scale > 1) snprintf(extra + strlen(extra), sizeof extra - strlen(extra), ":scale=%d", g->scale);
        snprintf(c->spec, sizeof c->spec, "%s:scene=%s:size=%dx%d%s", c->method->name, o->scene, o->width, o->height,
                 extra);
        snprintf(c->scene, sizeof c->scene, "%s", o->scene);
        c->width = o->width;
        c->height = o->height;
        c->glass = ks[k].glass[0].material;
        c->ok = bench_frame_times(c, ks[k].ms, ks[k].n_ms);
        if (!c->ok) snprintf(c->error, sizeof c->error, "out of memory");
        c->gpu_median = c->vs_single = c->vs_scene = -1.0;
        c->encoding = "none";
        c->glass_objects = ks[k].fd.glass_count;
        c->opaque_objects = ks[k].fd.opaque_count;
        for (m = 0; m < 2; m++) {
            snell_dir_error *d = &c->dir[m];
            d->mean_deg = d->rms_deg = d->median_deg = d->p99_deg = d->max_deg = NAN;
            d->frac_above_1deg = d->frac_above_5deg = NAN;
            c->img[m].rmse = c->img[m].psnr_db = c->img_glass[m].rmse = c->ssim_glass[m] = NAN;
            c->img_glass[m].psnr_db = m ? psnr_mean[k] : NAN;
        }
    }
    cli_system_read(&sys);
    strftime(date, sizeof date, "%Y-%m-%d %H:%M", localtime(&now));
    snprintf(timing, sizeof timing, "snell-bench --budget: frames on a camera turning %.2f deg a frame; AUTO every "
             "frame, the fixed rungs every %d-th; each frame = snell_render + glFinish (CPU wall clock); "
             "vs_full.psnr_glass_db: the mean over %d samples", (double)o->spin, o->every, o->samples);
    memset(&run, 0, sizeof run);
    run.system = &sys;
    run.renderer = snell_ctx_gl_renderer(ctx);
    run.date = date;
    run.load_before = load0;
    run.load_after = load1;
    run.timing = timing;
    run.no_errors = 1;
    snprintf(path, sizeof path, "%s.json", o->out_prefix);
    errno = 0;
    if (!bench_write_json(path, cs, n, &bo, &run)) ok = 0;
    snprintf(path + strlen(path) - 5, 6, ".csv");
    if (ok && !bench_write_csv(path, cs, n)) ok = 0;
    if (!ok) fprintf(stderr, "snell-bench --budget: cannot write '%s': %s\n", path, errno ? strerror(errno) : "write failed");
    else printf("wrote %s.json, %s.csv\n", o->out_prefix, o->out_prefix);
    bench_configs_free(cs, n);
    free(cs);
    return ok;
}

int snell_bench_budget_main(int argc, char **argv)
{
    budget_opts o;
    snell_ctx *ctx = NULL;
    snell_env *env = NULL;
    const bench_scene *s = NULL;
    budget_config ks[MAX_CONFIGS];
    int n = 0, i, f, k, ok = 1, rc = 0, sample_at[MAX_SAMPLES], best = -1;
    float cam[3], az0;
    double psnr_mean[MAX_CONFIGS];
    char load0[64], load1[64];
    size_t px;
    int r = parse(argc, argv, &o);
    if (r <= 0) return r < 0 ? 0 : 2;
    memset(ks, 0, sizeof ks);
    px = (size_t)o.width * o.height * 4;
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-bench --budget: cannot create a GL context: %s\n", snell_last_error(NULL));
        return 1;
    }
    if (snell_env_create(ctx, &(snell_env_desc){0}, &env) != SNELL_OK || bench_scene_get(ctx, o.scene, &s) != SNELL_OK) {
        fprintf(stderr, "snell-bench --budget: %s\n", snell_last_error(ctx));
        rc = 1;
        goto done;
    }
    if (!o.quiet) print_table();
    bench_scene_camera(o.scene, cam);
    /* AUTO, then every rung the build has */
    for (i = -1; i < snell_budget_rung_count() && n < MAX_CONFIGS; i++) {
        budget_config *c = &ks[n];
        c->rung = i;
        if (i >= 0) {
            rung_name(snell_budget_rung_at(i), c->name, sizeof c->name);
        } else
            snprintf(c->name, sizeof c->name, "auto, budget");
        frame_of(s, env, c, cam, &o);
        c->ms = (double *)calloc((size_t)o.frames, sizeof(double));
        c->first = (unsigned char *)calloc((size_t)o.frames, 1);
        for (k = 0; k < o.samples; k++) c->img[k] = (uint8_t *)malloc(px);
        if (!c->ms || !c->first || snell_renderer_create(ctx, &(snell_renderer_desc){.width = o.width, .height = o.height}, &c->r) !=
                          SNELL_OK) {
            fprintf(stderr, "snell-bench --budget: %s\n", snell_last_error(ctx));
            rc = 1;
            n++;
            goto done;
        }
        n++;
    }
    az0 = ks[0].fd.camera.azimuth;
    /* warm-up (bakes, programs), and single's median for a budget given as Nx */
    {
        double single_ms[9];
        int single = -1;
        for (k = 1; k < n; k++)
            if (snell_budget_rung_at(ks[k].rung)->method == SNELL_METHOD_SINGLE) single = k;
        for (k = 1; k < n && ok; k++)
            for (f = 0; f < o.warmup; f++) frame(ctx, &ks[k], &o, az0, 0, NULL, &ok);
        /* single along the first frames of the camera path, after its own warm-up */
        for (f = 0; f < 9 && ok && single >= 0; f++) single_ms[f] = frame(ctx, &ks[single], &o, az0, f, NULL, &ok);
        if (o.budget_x > 0.0f) {
            if (single < 0) {
                fprintf(stderr, "snell-bench --budget: Nx needs the single method\n");
                rc = 2;
                goto done;
            }
            o.budget_ms = (float)(o.budget_x * cli_median(single_ms, 9));
        }
    }
    ks[0].fd.budget_ms = o.budget_ms;
    if (!o.no_warm) {
        snell_warm_stats ws;
        if (snell_renderer_warm(ks[0].r, &ks[0].fd, &ws) != SNELL_OK) {
            fprintf(stderr, "snell-bench --budget: warming AUTO: %s\n", snell_last_error(ctx));
            rc = 1;
            goto done;
        }
        printf("AUTO warmed (snell_renderer_warm): %d frames in %.0f ms, %d rungs timed on this device, the frame "
               "without glass %.2f ms\n", ws.frames, ws.ms, ws.rungs, ws.base_ms);
    } else
        printf("AUTO not warmed (--warm off): it starts from the rung table's costs\n");
    for (k = 0; k < o.samples; k++) sample_at[k] = (int)((long)o.frames * (k + 1) / (o.samples + 1));
    cli_loadavg(load0, sizeof load0);
    printf("scene %s, %dx%d, %d frames turning %.2f deg each, budget %.2f ms%s; load %s\n", o.scene, o.width, o.height,
           o.frames, (double)o.spin, (double)o.budget_ms, o.budget_x > 0.0f ? " (Nx single's median)" : "", load0);
    fflush(stdout);
    for (f = 0; f < o.frames && ok; f++) {
        int sample = 0, j;
        for (j = 0; j < o.samples; j++) sample |= sample_at[j] == f;
        for (i = 0; i < n && ok; i++) {
            budget_config *c = &ks[(i + f) % n]; /* the order turns with the frames */
            snell_frame_stats st;
            if (c->rung >= 0 && f % o.every && !sample) continue;
            c->ms[c->n_ms++] = frame(ctx, c, &o, az0, f, &st, &ok);
            if (c->rung < 0) {
                c->changes += st.budget_changed;
                c->first[c->n_ms - 1] = (unsigned char)st.budget_first_use;
                c->first_use += st.budget_first_use;
                if (c->ms[c->n_ms - 1] > 1.1 * o.budget_ms && c->n_slow < 8 && st.glass_count > 0)
                    snprintf(c->slow[c->n_slow++], sizeof c->slow[0], "frame %d: %.2f ms, %s drew glass 0; the plan: %.80s",
                             f, c->ms[c->n_ms - 1], snell_method_str(st.glass[0].method_used), st.budget_reason);
            }
            for (j = 0; j < o.samples; j++)
                if (sample_at[j] == f) {
                    snell_renderer_read_rgba(c->r, c->img[j]);
                    if (c->rung < 0) {
                        size_t used = 0;
                        int g;
                        c->drawn[j][0] = 0;
                        for (g = 0; g < st.glass_count && used < sizeof c->drawn[j]; g++)
                            used += (size_t)snprintf(c->drawn[j] + used, sizeof c->drawn[j] - used, "%s%s",
                                                     g ? "; " : "", st.glass[g].reason + (strncmp(st.glass[g].reason,
                                                     "auto by budget: ", 16) ? 0 : 16));
                    }
                }
        }
    }
    cli_loadavg(load1, sizeof load1);
    if (!ok) {
        rc = 1;
        goto done;
    }
    for (k = 0; k < o.samples; k++)
        if (!measure(&o, s, ks, n, sample_at[k], k, az0)) {
            rc = 1;
            goto done;
        }
    printf("\n| configuration | median ms | p95 ms | worst ms | frames > 110%% budget | of them not first uses "
           "| glass PSNR vs FULL [dB] |\n");
    printf("|---|---:|---:|---:|---:|---:|---:|\n");
    for (k = 0; k < n; k++) {
        int m = ks[k].n_ms;
        double q = 0.0, med = percentile(ks[k].ms, m, 0.5), p95 = percentile(ks[k].ms, m, 0.95);
        double worst = percentile(ks[k].ms, m, 1.0);
        for (f = 0; f < m; f++) {
            ks[k].over += ks[k].ms[f] > 1.1 * o.budget_ms;
            ks[k].over_steady += ks[k].ms[f] > 1.1 * o.budget_ms && !ks[k].first[f];
        }
        for (i = 0; i < o.samples; i++) q += ks[k].psnr[i] / o.samples;
        psnr_mean[k] = q;
        printf("| %s | %.2f | %.2f | %.2f | %d of %d | %d | %.2f |\n", ks[k].name, med, p95, worst, ks[k].over, m,
               ks[k].over_steady, q);
        if (k > 0 && p95 <= o.budget_ms) {
            double bq = 0.0;
            if (best >= 0)
                for (i = 0; i < o.samples; i++) bq += ks[best].psnr[i] / o.samples;
            if (best < 0 || q > bq) best = k;
        }
    }
    printf("\nAUTO: %d plan changes in %d frames, %d of them drawing a configuration for the first time (its programs "
           "and bakes built in that frame); at the samples it drew:\n", ks[0].changes, o.frames, ks[0].first_use);
    for (i = 0; i < o.samples; i++) printf("  frame %d: %s\n", sample_at[i], ks[0].drawn[i]);
    if (ks[0].n_slow) printf("AUTO's frames over 110%% of the budget (the first 8):\n");
    for (i = 0; i < ks[0].n_slow; i++) printf("  %s\n", ks[0].slow[i]);
    {
        double aq = 0.0, bq = 0.0;
        for (i = 0; i < o.samples; i++) aq += ks[0].psnr[i] / o.samples;
        if (best >= 0) {
            for (i = 0; i < o.samples; i++) bq += ks[best].psnr[i] / o.samples;
            printf("best fixed configuration within the budget (p95): %s, %.2f dB; AUTO %.2f dB (%+.2f dB)\n",
                   ks[best].name, bq, aq, aq - bq);
        } else
            printf("no fixed configuration holds the budget at the 95th percentile; AUTO %.2f dB\n", aq);
    }
    printf("load %s before, %s after\n", load0, load1);
    if (!write_files(&o, ks, n, load0, load1, ctx, psnr_mean)) rc = 1;
done:
    for (k = 0; k < n; k++) {
        if (ks[k].r) snell_renderer_destroy(ks[k].r);
        free(ks[k].ms);
        free(ks[k].first);
        for (i = 0; i < o.samples; i++) free(ks[k].img[i]);
    }
    bench_scene_release_all();
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return rc;
}
