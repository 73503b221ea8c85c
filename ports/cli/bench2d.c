/* SPDX-License-Identifier: MIT */
/* bench2d.c — `snell-bench --2d`: the 2D lightmap benchmarks of Brückner ch. 7
 * on the public API: tracer rays/s per core on a 2263-edge polygon set (7.3.1),
 * BVH leaf-size sweep (7.3.2), GL line rasterisation in paths/ms (7.4), and the
 * frame time of a 1920x1080 lightmap with one point light of 2.5e4 rays and 3
 * specular bounces (7.6) for each rasteriser, taking turns frame by frame
 * (`--frame`: only that). Prints a table, writes JSON and CSV. */
#define _POSIX_C_SOURCE 200809L
#include "snell/snell.h"
#include "snell/snell_2d.h"
#include "cli_opts.h"
#include "cli_time.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

int snell_bench2d_main(int argc, char **argv);

#define PI_F 3.14159265358979323846f
#define VIEW_W 1920
#define VIEW_H 1080


/* Thesis Abb. A.17 stand-in: 8 irregular blobs on a ring around the screen
 * centre, 2263 edges in all, so most rays from the centre hit an edge. */
static snell_status bvh_scene(snell_ctx *ctx, int edges, float mirror, snell_scene2d **out)
{
    snell_scene2d *s;
    snell_status st;
    int k;
    float *pts = (float *)malloc(sizeof(float) * 2 * (size_t)edges);
    if (!pts) return SNELL_E_NOMEM;
    if ((st = snell_scene2d_create(ctx, &s)) != SNELL_OK) {
        free(pts);
        return st;
    }
    for (k = 0; k < 8 && st == SNELL_OK; k++) {
        int n = edges / 8 + (k < edges % 8), i;
        float ca = 2.0f * PI_F * (float)k / 8.0f, cx = VIEW_W / 2 + 400.0f * cosf(ca), cy = VIEW_H / 2 + 400.0f * sinf(ca);
        snell_object2d_desc d;
        for (i = 0; i < n; i++) {
            float th = 2.0f * PI_F * (float)i / (float)n, ph = (float)k;
            float r = 140.0f * (1.0f + 0.25f * sinf(3 * th + ph) + 0.1f * sinf(7 * th + 2 * ph) + 0.05f * sinf(23 * th));
            pts[2 * i] = cx + r * cosf(th);
            pts[2 * i + 1] = cy + r * sinf(th);
        }
        memset(&d, 0, sizeof d);
        d.points = pts;
        d.point_count = n;
        d.material.absorption = mirror > 0.0f ? 1.0f - mirror : 0.5f;
        d.material.diffuse = mirror > 0.0f ? 0.0f : 0.3f;
        st = snell_scene2d_add_object(s, &d, NULL);
    }
    free(pts);
    if (st != SNELL_OK) {
        snell_scene2d_destroy(s);
        return st;
    }
    *out = s;
    return SNELL_OK;
}

static snell_light2d_desc point_light(int rays, float x, float y)
{
    snell_light2d_desc L;
    memset(&L, 0, sizeof L);
    L.type = SNELL_LIGHT2D_POINT;
    L.position[0] = x;
    L.position[1] = y;
    L.power = 100.0f;
    L.rays = rays;
    return L;
}

static snell_light2d_desc bench2d_light0; /* light 0 of the scene being timed */

#define MAX_REPEAT 64

/* CPU time of the whole process (all threads, llvmpipe's included): what a
 * frame costs the machine, robust to other processes sharing it. */
static double process_cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

typedef struct result {
    double ms, trace_ms, raster_ms, trace_cpu_ms, upload_ms, cpu_ms;
    unsigned long long rays, paths;
    snell_raster2d raster;
    int raster_threads;
    char reason[SNELL_REASON_SIZE];
} result;

/* n configurations on one scene, taking turns frame by frame (the first of
 * each round rotates), medians over `repeat` rounds; the light moves by a hair
 * every round so every frame really re-traces (a static scene is reused). */
static snell_status run_interleaved(snell_ctx *ctx, snell_scene2d *s, const snell_lightmap2d_desc *d, int n,
                                    int repeat, result *r)
{
    snell_lightmap2d *lm[8];
    snell_lightmap2d_stats st;
    snell_status rc = SNELL_OK;
    static double t[8][MAX_REPEAT], tr[8][MAX_REPEAT], ra[8][MAX_REPEAT], tc[8][MAX_REPEAT], up[8][MAX_REPEAT],
        pc[8][MAX_REPEAT];
    int i, c, k;
    snell_light2d_desc L;
    if (repeat > MAX_REPEAT) repeat = MAX_REPEAT;
    if (n > 8) n = 8;
    memset(lm, 0, sizeof lm);
    for (c = 0; c < n && rc == SNELL_OK; c++) rc = snell_lightmap2d_create(ctx, &d[c], &lm[c]);
    for (i = -1; i < repeat && rc == SNELL_OK; i++) { /* round -1 warms up (allocation, shader, BVH) */
        L = bench2d_light0;
        L.position[0] += (i & 1) ? 1e-3f : -1e-3f;
        if ((rc = snell_scene2d_set_light(s, 0, &L)) != SNELL_OK) break;
        for (k = 0; k < n && rc == SNELL_OK; k++) {
            double t0, c0;
            c = (k + (i < 0 ? 0 : i)) % n;
            c0 = process_cpu_ms();
            t0 = cli_now_ms();
            if ((rc = snell_lightmap2d_frame(lm[c], s, &st)) != SNELL_OK) break;
            snell_lightmap2d_finish(lm[c]);
            if (i < 0) continue;
            t[c][i] = cli_now_ms() - t0;
            pc[c][i] = process_cpu_ms() - c0;
            tr[c][i] = st.trace_ms;
            tc[c][i] = st.trace_cpu_ms;
            up[c][i] = st.upload_ms;
            ra[c][i] = t[c][i] - st.trace_ms;
            r[c].rays = st.rays;
            r[c].paths = st.paths;
            r[c].raster = st.raster;
            r[c].raster_threads = st.raster_threads;
            memcpy(r[c].reason, st.raster_reason, sizeof r[c].reason);
        }
    }
    for (c = 0; c < n; c++) snell_lightmap2d_destroy(lm[c]);
    if (rc != SNELL_OK) return rc;
    for (c = 0; c < n; c++) {
        r[c].ms = cli_median(t[c], repeat);
        r[c].trace_ms = cli_median(tr[c], repeat);
        r[c].trace_cpu_ms = cli_median(tc[c], repeat);
        r[c].raster_ms = cli_median(ra[c], repeat);
        r[c].upload_ms = cli_median(up[c], repeat);
        r[c].cpu_ms = cli_median(pc[c], repeat);
    }
    return SNELL_OK;
}

static snell_status run_frames(snell_ctx *ctx, snell_scene2d *s, const snell_lightmap2d_desc *d, int repeat, result *r)
{
    memset(r, 0, sizeof *r);
    return run_interleaved(ctx, s, d, 1, repeat, r);
}

static const char *raster_name(snell_raster2d r)
{
    return r == SNELL_RASTER2D_GL ? "GL lines" : r == SNELL_RASTER2D_CPU ? "CPU exact" : "auto";
}

static void usage(FILE *out)
{
    fprintf(out,
            "usage: snell-bench --2d [--rays N] [--repeat R] [--threads T] [--no-gpu] [--quick] [--frame]\n"
            "                        [--json FILE] [--csv FILE]\n"
            "  rays/s per core (1 thread, 2263 edges, 0 bounces), leaf sweep, GL paths/ms,\n"
            "  1920x1080 frame (2.5e4 rays, 3 specular bounces): auto, CPU rasteriser on T threads and\n"
            "  on 1, GL lines, taking turns frame by frame. --frame: only the 1080p frame.\n");
}

int snell_bench2d_main(int argc, char **argv)
{
    int rays = 200000, repeat = 9, threads = 0, gpu = 1, frame_only = 0, li, c, nf = 0, edges = 2263, write_failed = 0;
    const char *json = "bench2d.json", *csv = "bench2d.csv";
    static const int leaves[] = {1, 2, 3, 4, 6, 8, 12, 16};
    double leaf_rps[8] = {0}, leaf_cpu[8] = {0};
    snell_ctx *ctx = NULL;
    snell_scene2d *s = NULL;
    snell_lightmap2d_desc d, fd[4];
    snell_status st;
    result r1, rT, rg, rf[4];
    char lpwhy[64];
    int lp;
    FILE *f;
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    static const struct option longopts[] = {
        {"2d", no_argument, NULL, '2'},          {"rays", required_argument, NULL, 'r'},
        {"repeat", required_argument, NULL, 'R'}, {"threads", required_argument, NULL, 't'},
        {"json", required_argument, NULL, 'j'},  {"csv", required_argument, NULL, 'c'},
        {"no-gpu", no_argument, NULL, 'n'},      {"frame", no_argument, NULL, 'f'},
        {"quick", no_argument, NULL, 'q'},       {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    if (cli_wants_help(argc, argv)) {
        usage(stdout);
        return 0;
    }
    cli_opts_reset();
    while ((c = cli_getopt("snell-bench --2d", "--2d --help", argc, argv, "h", longopts)) != -1) {
        if (c == '?') return 2;
        if (c == 'r') rays = atoi(optarg);
        else if (c == 'R') repeat = atoi(optarg);
        else if (c == 't') threads = atoi(optarg);
        else if (c == 'j') json = optarg;
        else if (c == 'c') csv = optarg;
        else if (c == 'n') gpu = 0;
        else if (c == 'f') frame_only = 1;
        else if (c == 'q') {
            rays = 50000;
            repeat = 3;
        }
    }
    if (optind < argc) {
        fprintf(stderr, "snell-bench --2d: unexpected argument '%s'; see --2d --help\n", argv[optind]);
        return 2;
    }
    if (rays < 1000 || repeat < 1 || repeat > MAX_REPEAT || threads < 0) {
        fprintf(stderr, "snell-bench --2d: want --rays >= 1000, --repeat 1..%d and --threads >= 0, got %d, %d, %d\n",
                MAX_REPEAT, rays, repeat, threads);
        return 2;
    }
    if (threads == 0) threads = ncpu > 0 ? (int)ncpu : 1;
    if (gpu && snell_ctx_create(NULL, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-bench --2d: no GL context (%s); GPU entries skipped\n", snell_last_error(NULL));
        ctx = NULL;
    }
    lp = cli_llvmpipe_threads(ctx ? snell_ctx_gl_renderer(ctx) : NULL, lpwhy, sizeof lpwhy);
    memset(&r1, 0, sizeof r1);
    memset(&rT, 0, sizeof rT);
    memset(&rg, 0, sizeof rg);
    memset(rf, 0, sizeof rf);
    memset(&d, 0, sizeof d);
    d.width = VIEW_W;
    d.height = VIEW_H;
    if (!frame_only) {
        if ((st = bvh_scene(ctx, edges, 0.0f, &s)) != SNELL_OK) goto fail;
        bench2d_light0 = point_light(rays, VIEW_W / 2, VIEW_H / 2);
        if ((st = snell_scene2d_add_light(s, &bench2d_light0, NULL)) != SNELL_OK) goto fail;
        /* 1. tracer throughput, 0 bounces (thesis 7.3.1), CPU only so raster is the exact CPU one */
        d.max_bounces = -1;
        d.threads = 1;
        d.cpu_only = 1;
        if ((st = run_frames(NULL, s, &d, repeat, &r1)) != SNELL_OK) goto fail;
        d.threads = threads;
        if ((st = run_frames(NULL, s, &d, repeat, &rT)) != SNELL_OK) goto fail;
        /* 2. leaf sweep (7.3.2), 1 thread */
        d.threads = 1;
        for (li = 0; li < 8; li++) {
            result r;
            snell_scene2d_set_bvh_leaf_size(s, leaves[li]);
            if ((st = run_frames(NULL, s, &d, repeat, &r)) != SNELL_OK) goto fail;
            leaf_rps[li] = (double)r.rays / (r.trace_ms * 1e-3);
            leaf_cpu[li] = (double)r.rays / (r.trace_cpu_ms * 1e-3);
        }
        snell_scene2d_set_bvh_leaf_size(s, 0);
        if (ctx) {
            /* 3. GL rasterisation of the same 2e5 paths into a 1080p RGBA32F target (7.4) */
            d.cpu_only = 0;
            d.threads = threads;
            d.raster = SNELL_RASTER2D_GL;
            if ((st = run_frames(ctx, s, &d, repeat, &rg)) != SNELL_OK) goto fail;
        }
        snell_scene2d_destroy(s);
        s = NULL;
    }
    /* 4. 1080p frame: mirror blobs, 2.5e4 rays, 3 specular bounces (7.6); every
     * rasteriser on the same frames, taking turns */
    if ((st = bvh_scene(ctx, edges, 0.9f, &s)) != SNELL_OK) goto fail;
    bench2d_light0 = point_light(25000, VIEW_W / 2, VIEW_H / 2);
    if ((st = snell_scene2d_add_light(s, &bench2d_light0, NULL)) != SNELL_OK) goto fail;
    memset(&d, 0, sizeof d);
    d.width = VIEW_W;
    d.height = VIEW_H;
    d.max_bounces = 3;
    d.threads = threads;
    d.cpu_only = ctx == NULL;
    fd[nf++] = d; /* AUTO */
    d.raster = SNELL_RASTER2D_CPU;
    fd[nf++] = d;
    d.threads = 1;
    fd[nf++] = d;
    if (ctx) {
        d.threads = threads;
        d.raster = SNELL_RASTER2D_GL;
        fd[nf++] = d;
    }
    if ((st = run_interleaved(ctx, s, fd, nf, repeat, rf)) != SNELL_OK) goto fail;

    printf("snell-bench --2d  (%s, %d thread(s) where not 1, median of %d)\n", ctx ? snell_ctx_gl_renderer(ctx) : "no GL",
           threads, repeat);
    if (lp >= 0) printf("llvmpipe threads: %d (%s)\n", lp, lpwhy);
    printf("%-44s %14s\n", "measure", "value");
    if (!frame_only) {
        printf("%-44s %14.3g\n", "trace rays/s per core (1 thread, 2263 edges)", (double)r1.rays / (r1.trace_ms * 1e-3));
        printf("%-44s %14.3g\n", "  same, by thread CPU time (load-robust)", (double)r1.rays / (r1.trace_cpu_ms * 1e-3));
        printf("%-44s %14.3f\n", "  trace ms for 2e5 rays (thesis: 389 ms/4c)", r1.trace_ms * 200000.0 / (double)r1.rays);
        printf("%-44s %14.3g\n", "trace rays/s, all threads", (double)rT.rays / (rT.trace_ms * 1e-3));
        for (li = 0; li < 8; li++) {
            char name[64];
            snprintf(name, sizeof name, "  leaf size %2d: rays/s per core (wall, cpu)", leaves[li]);
            printf("%-44s %14.3g %10.3g\n", name, leaf_rps[li], leaf_cpu[li]);
        }
        if (ctx) {
            printf("%-44s %14.1f\n", "GL paths/ms (1080p RGBA32F, incl. upload)", (double)rg.paths / rg.raster_ms);
            printf("%-44s %14llu\n", "  paths per frame", rg.paths);
        }
    }
    printf("1080p frame (2.5e4 rays, 3 bounces, %llu paths), ms:\n", rf[0].paths);
    printf("  %-24s %9s %9s %9s %9s %7s %9s\n", "rasteriser", "frame", "trace", "raster", "upload", "FPS",
           "CPU ms");
    for (c = 0; c < nf; c++) {
        char name[64];
        snprintf(name, sizeof name, "%s%s, %d thr", c == 0 ? "auto -> " : "", raster_name(rf[c].raster),
                 fd[c].threads);
        printf("  %-24s %9.2f %9.2f %9.2f %9.2f %7.1f %9.1f\n", name, rf[c].ms, rf[c].trace_ms, rf[c].raster_ms,
               rf[c].upload_ms, 1000.0 / rf[c].ms, rf[c].cpu_ms);
    }
    printf("  (frame = trace + raster incl. upload and glFinish; CPU ms: all threads of the process)\n");
    printf("  rasteriser of the first row: %s\n", rf[0].reason);

    f = fopen(json, "w");
    if (!f) fprintf(stderr, "snell-bench --2d: cannot write '%s': %s\n", json, strerror(errno)), write_failed = 1;
    if (f) {
        fprintf(f, "{\n  \"renderer\": \"%s\",\n", ctx ? snell_ctx_gl_renderer(ctx) : "none");
        if (lp >= 0) fprintf(f, "  \"llvmpipe_threads\": %d,\n", lp);
        else fprintf(f, "  \"llvmpipe_threads\": null,\n");
        fprintf(f, "  \"llvmpipe_threads_from\": \"%s\",\n  \"threads\": %d,\n  \"repeat\": %d,\n", lpwhy, threads,
                repeat);
        if (!frame_only) {
            fprintf(f, "  \"edges\": %d,\n  \"rays\": %d,\n", edges, rays);
            fprintf(f, "  \"trace_rays_per_s_per_core\": %.1f,\n", (double)r1.rays / (r1.trace_ms * 1e-3));
            fprintf(f, "  \"trace_rays_per_cpu_s\": %.1f,\n", (double)r1.rays / (r1.trace_cpu_ms * 1e-3));
            fprintf(f, "  \"trace_rays_per_s_all_threads\": %.1f,\n", (double)rT.rays / (rT.trace_ms * 1e-3));
            fprintf(f, "  \"leaf_sweep\": [");
            for (li = 0; li < 8; li++)
                fprintf(f, "%s{\"leaf\": %d, \"rays_per_s\": %.1f, \"rays_per_cpu_s\": %.1f}", li ? ", " : "",
                        leaves[li], leaf_rps[li], leaf_cpu[li]);
            fprintf(f, "],\n  \"gl_paths_per_ms\": %.1f,\n", ctx ? (double)rg.paths / rg.raster_ms : 0.0);
        }
        fprintf(f, "  \"frame_1080p_paths\": %llu,\n  \"frame_1080p_auto\": \"%s\",\n  \"frame_1080p\": [", rf[0].paths,
                rf[0].reason);
        for (c = 0; c < nf; c++)
            fprintf(f,
                    "%s{\"config\": \"%s\", \"raster\": \"%s\", \"threads\": %d, \"ms\": %.3f, \"trace_ms\": %.3f, "
                    "\"raster_ms\": %.3f, \"upload_ms\": %.3f, \"cpu_ms\": %.3f}",
                    c ? ", " : "", c == 0 ? "auto" : raster_name(fd[c].raster), raster_name(rf[c].raster),
                    fd[c].threads, rf[c].ms, rf[c].trace_ms, rf[c].raster_ms, rf[c].upload_ms, rf[c].cpu_ms);
        fprintf(f, "],\n  \"frame_1080p_ms\": %.3f,\n  \"frame_1080p_trace_ms\": %.3f,\n  \"frame_1080p_raster_ms\": %.3f\n}\n",
                rf[0].ms, rf[0].trace_ms, rf[0].raster_ms);
        fclose(f);
    }
    f = fopen(csv, "w");
    if (!f) fprintf(stderr, "snell-bench --2d: cannot write '%s': %s\n", csv, strerror(errno)), write_failed = 1;
    if (f) {
        fprintf(f, "measure,value\n");
        fprintf(f, "renderer,\"%s\"\n", ctx ? snell_ctx_gl_renderer(ctx) : "none");
        if (lp >= 0) fprintf(f, "llvmpipe_threads,%d\n", lp);
        if (!frame_only) {
            fprintf(f, "trace_rays_per_s_per_core,%.1f\n", (double)r1.rays / (r1.trace_ms * 1e-3));
            fprintf(f, "trace_rays_per_cpu_s,%.1f\n", (double)r1.rays / (r1.trace_cpu_ms * 1e-3));
            fprintf(f, "trace_rays_per_s_all_threads,%.1f\n", (double)rT.rays / (rT.trace_ms * 1e-3));
            for (li = 0; li < 8; li++)
                fprintf(f, "leaf_%d_rays_per_s,%.1f\nleaf_%d_rays_per_cpu_s,%.1f\n", leaves[li], leaf_rps[li],
                        leaves[li], leaf_cpu[li]);
            fprintf(f, "gl_paths_per_ms,%.1f\n", ctx ? (double)rg.paths / rg.raster_ms : 0.0);
        }
        fprintf(f, "frame_1080p_ms,%.3f\nframe_1080p_trace_ms,%.3f\nframe_1080p_raster_ms,%.3f\n", rf[0].ms,
                rf[0].trace_ms, rf[0].raster_ms);
        for (c = 1; c < nf; c++)
            fprintf(f, "frame_1080p_%s_%dthr_ms,%.3f\n", fd[c].raster == SNELL_RASTER2D_GL ? "gl" : "cpu",
                    fd[c].threads, rf[c].ms);
        fclose(f);
    }
    if (!write_failed) printf("wrote %s and %s\n", json, csv);
    snell_scene2d_destroy(s);
    snell_ctx_destroy(ctx);
    return write_failed;
fail:
    fprintf(stderr, "snell-bench --2d: %s: %s\n", snell_status_str(st), snell_last_error(ctx));
    snell_scene2d_destroy(s);
    snell_ctx_destroy(ctx);
    return 1;
}
