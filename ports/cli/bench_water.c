/* SPDX-License-Identifier: MIT */
/* bench_water.c — snell-bench --water: the water scene's costs measured
 * apart (issue 17): one simulation step on the CPU and on the GPU (each
 * timed over a batch of steps, the GPU's finished with glFinish), a frame's
 * rendering with the surface fixed, and the frame's error against
 * snell_ref_water_render for the still and the rippled surface. The CPU and
 * GPU batches and the frames take turns round by round; times are medians
 * over the rounds. One line per figure, and the load average. */
#include "cli_opts.h"
#include "cli_progress.h"
#include "cli_time.h"
#include "snell/snell_metrics.h"
#include "snell/snell_ref.h"
#include "snell/snell_water.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ROUNDS 200

typedef struct water_bench {
    int grid, size, rounds, steps;
} water_bench;

static void usage(FILE *f)
{
    fprintf(f, "usage: snell-bench --water [--grid N] [--sizes SxS] [--rounds R] [--steps K]\n"
               "The water scene's costs apart: a simulation step on the CPU and the GPU, a frame, and its\n"
               "error against the reference tracer.\n"
               "  --grid N     height-field nodes per side (default 256)\n"
               "  --sizes SxS  image size (square), 16..4096 (default 512x512)\n"
               "  --rounds R   rounds, 1..%d (default 15); times are medians over them\n"
               "  --steps K    simulation steps per timed batch (default 10)\n"
               "  -h, --help   this text\n", MAX_ROUNDS);
}

/* A positive integer option value; else one message naming it. */
static int parse_count(const char *a, const char *v, int *out)
{
    char *end;
    long x = strtol(v, &end, 10);
    if (end == v || *end || x < 1 || x > 1000000) {
        fprintf(stderr, "snell-bench --water: %s wants a positive integer, got '%s'\n", a, v);
        return 0;
    }
    *out = (int)x;
    return 1;
}

/* 1: run; 0: bad usage (message printed); -1: --help printed. */
static int parse(int argc, char **argv, water_bench *b)
{
    static const struct option longopts[] = {
        {"water", no_argument, NULL, 'W'},       {"grid", required_argument, NULL, 'g'},
        {"sizes", required_argument, NULL, 's'}, {"rounds", required_argument, NULL, 'r'},
        {"steps", required_argument, NULL, 'k'}, {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    int c, h;
    char tail;
    if (cli_wants_help(argc, argv)) {
        usage(stdout);
        return -1;
    }
    b->grid = 256;
    b->size = 512;
    b->rounds = 15;
    b->steps = 10;
    cli_opts_reset();
    while ((c = cli_getopt("snell-bench --water", "--water --help", argc, argv, "h", longopts)) != -1) {
        if (c == '?') return 0;
        if (c == 'g' && !parse_count("--grid", optarg, &b->grid)) return 0;
        if (c == 'r' && !parse_count("--rounds", optarg, &b->rounds)) return 0;
        if (c == 'k' && !parse_count("--steps", optarg, &b->steps)) return 0;
        if (c == 's' && (sscanf(optarg, "%dx%d%c", &b->size, &h, &tail) != 2 || h != b->size)) {
            fprintf(stderr, "snell-bench --water: --sizes %s: want a square size SxS\n", optarg);
            return 0;
        }
    }
    if (optind < argc) {
        fprintf(stderr, "snell-bench --water: unexpected argument '%s'; see --water --help\n", argv[optind]);
        return 0;
    }
    if (b->rounds < 1 || b->rounds > MAX_ROUNDS || b->steps < 1 || b->size < 16 || b->size > 4096) {
        fprintf(stderr, "snell-bench --water: want --rounds 1..%d and --sizes 16x16..4096x4096, got %d and %dx%d\n",
                MAX_ROUNDS, b->rounds, b->size, b->size);
        return 0;
    }
    return 1;
}

/* The frame of fd against the reference (with fd's glass and opaque objects
 * in it): PSNR over the water pixels and over the whole frame,
 * exit-direction error. */
static int error_line(snell_ctx *ctx, snell_water *w, const snell_frame_desc *fd, int size, const char *what)
{
    snell_ref *objects = NULL;
    snell_image_error all;
    size_t n = (size_t)size * size;
    float *rgb = (float *)malloc(n * 3 * sizeof(float)), *rdir = (float *)malloc(n * 3 * sizeof(float));
    float *gdir = (float *)malloc(n * 3 * sizeof(float));
    uint8_t *hit = (uint8_t *)malloc(n), *gpu = (uint8_t *)malloc(n * 4), *ref = (uint8_t *)malloc(n * 4);
    snell_renderer *rc = NULL, *rd = NULL;
    snell_ref_params p;
    snell_ref_output out;
    snell_image_error ie;
    snell_dir_error de;
    cli_progress bar;
    int ok = rgb && rdir && gdir && hit && gpu && ref;
    double t0;
    memset(&p, 0, sizeof p);
    p.env = fd->env;
    p.camera = fd->camera;
    p.width = p.height = size;
    memset(&out, 0, sizeof out);
    out.rgb = rgb;
    out.exit_dir = rdir;
    out.hit = hit;
    ok = ok && snell_renderer_create(ctx, &(snell_renderer_desc){.width = size, .height = size}, &rc) == SNELL_OK;
    ok = ok && snell_renderer_create(ctx, &(snell_renderer_desc){.width = size, .height = size,
                                                                 .output = SNELL_OUTPUT_EXIT_DIRECTION}, &rd) == SNELL_OK;
    ok = ok && snell_render(rc, fd, NULL) == SNELL_OK && snell_renderer_read_rgba(rc, gpu) == SNELL_OK;
    ok = ok && snell_render(rd, fd, NULL) == SNELL_OK && snell_renderer_read_exit_dirs(rd, gdir) == SNELL_OK;
    if (ok && fd->glass_count + fd->opaque_count > 0)
        ok = snell_ref_create(ctx, &(snell_ref_desc){.glass = fd->glass, .glass_count = fd->glass_count,
                                                      .opaque = fd->opaque, .opaque_count = fd->opaque_count},
                              &objects) == SNELL_OK;
    if (cli_progress_wanted(0)) { /* on a terminal: the trace's progress */
        cli_progress_start(&bar, "water reference");
        p.progress = cli_progress_report;
        p.progress_user = &bar;
    }
    t0 = cli_now_ms();
    ok = ok && snell_ref_water_render(w, objects, &p, &out) == SNELL_OK;
    if (ok) {
        double ref_ms = cli_now_ms() - t0;
        snell_ref_rgb_to_rgba8(rgb, size, size, ref);
        snell_metrics_image_error(gpu, ref, size, size, hit, &ie);
        snell_metrics_image_error(gpu, ref, size, size, NULL, &all);
        snell_metrics_dir_error(&(snell_dir_error_desc){.test = gdir, .ref = rdir, .ref_mask = hit, .test_mask = hit,
                                                        .width = size, .height = size}, &de);
        printf("error %-14s %ld water pixels: PSNR %.2f dB (rmse %.3f/255, max %d/255), whole frame %.2f dB; exit "
               "direction mean %.2e deg, p99 %.2e, max %.2e (reference %.0f ms)\n", what, ie.pixels, ie.psnr_db,
               ie.rmse, ie.max_abs, all.psnr_db, de.mean_deg, de.p99_deg, de.max_deg, ref_ms);
    } else {
        fprintf(stderr, "snell-bench --water: error measurement: %s\n", snell_last_error(ctx));
    }
    snell_ref_destroy(objects);
    snell_renderer_destroy(rc);
    snell_renderer_destroy(rd);
    free(rgb);
    free(rdir);
    free(gdir);
    free(hit);
    free(gpu);
    free(ref);
    return ok;
}

static void drops(snell_water *w)
{
    snell_water_drop(w, 0.3f, -0.2f, 0.15f, -0.03f);
    snell_water_drop(w, -0.5f, 0.4f, 0.1f, 0.02f);
    snell_water_drop(w, 0.6f, 0.6f, 0.08f, -0.02f);
}

static double frame_ms(snell_renderer *r, const snell_frame_desc *fd)
{
    double t0 = cli_now_ms();
    snell_render(r, fd, NULL);
    snell_renderer_finish(r);
    return cli_now_ms() - t0;
}

int snell_bench_water_main(int argc, char **argv)
{
    water_bench b;
    snell_ctx *ctx = NULL;
    snell_env *env = NULL;
    snell_water *cpu = NULL, *gpu = NULL;
    snell_renderer *r = NULL;
    snell_frame_desc fd;
    double t_cpu[MAX_ROUNDS], t_gpu[MAX_ROUNDS], t_frame_cpu[MAX_ROUNDS], t_frame_gpu[MAX_ROUNDS];
    double t_obj[MAX_ROUNDS], t_glass[MAX_ROUNDS], t_glass_off[MAX_ROUNDS];
    snell_mesh *sphere = NULL;
    snell_opaque objects[2];
    snell_glass glass[2];
    /* two opaque spheres, one through the surface; then two glass spheres (one through it) and the second
     * opaque one (test_water_glass's kind of scene) */
    static const float m0[16] = {0.35f, 0, 0, 0, 0, 0.35f, 0, 0, 0, 0, 0.35f, 0, 0.35f, -0.2f, 0.1f, 1};
    static const float m1[16] = {0.2f, 0, 0, 0, 0, 0.2f, 0, 0, 0, 0, 0.2f, 0, -0.45f, -0.5f, -0.3f, 1};
    static const float g0[16] = {0.35f, 0, 0, 0, 0, 0.35f, 0, 0, 0, 0, 0.35f, 0, -0.1f, -0.2f, 0.05f, 1};
    static const float g1[16] = {0.2f, 0, 0, 0, 0, 0.2f, 0, 0, 0, 0, 0.2f, 0, 0.5f, -0.5f, -0.35f, 1};
    char load[64], threads_why[96];
    int k, rc = 1, threads;
    if ((k = parse(argc, argv, &b)) <= 0) return k < 0 ? 0 : 2;
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-bench --water: no GL context: %s\n", snell_last_error(NULL));
        return 1;
    }
    if (snell_env_create(ctx, &(snell_env_desc){0}, &env) != SNELL_OK ||
        snell_water_create(ctx, &(snell_water_desc){.grid = b.grid, .sim = SNELL_WATER_SIM_CPU}, &cpu) != SNELL_OK ||
        snell_water_create(ctx, &(snell_water_desc){.grid = b.grid, .sim = SNELL_WATER_SIM_GPU}, &gpu) != SNELL_OK ||
        snell_renderer_create(ctx, &(snell_renderer_desc){.width = b.size, .height = b.size}, &r) != SNELL_OK ||
        snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE}, &sphere) != SNELL_OK) {
        fprintf(stderr, "snell-bench --water: %s\n", snell_last_error(ctx));
        goto done;
    }
    memset(objects, 0, sizeof objects);
    objects[0].mesh = objects[1].mesh = sphere;
    objects[0].model = m0;
    objects[1].model = m1;
    objects[0].color[0] = objects[1].color[2] = 0.9f;
    objects[0].color[1] = objects[0].color[2] = objects[1].color[0] = objects[1].color[1] = 0.3f;
    memset(glass, 0, sizeof glass);
    glass[0].mesh = glass[1].mesh = sphere;
    glass[0].model = g0;
    glass[1].model = g1;
    glass[0].material.ior = glass[1].material.ior = 1.5f;
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.camera.azimuth = 0.5f;
    fd.camera.elevation = 0.6f;
    fd.camera.distance = 3.6f;
    fd.camera.target[1] = -0.2f;
    fd.water = cpu;
    if (!error_line(ctx, cpu, &fd, b.size, "still")) goto done;
    drops(cpu);
    drops(gpu);
    /* a warm-up batch each (programs, first uploads) */
    snell_water_step(cpu, 0.0f, b.steps, NULL);
    snell_water_step(gpu, 0.0f, b.steps, NULL);
    snell_render(r, &fd, NULL);
    snell_renderer_finish(r);
    for (k = 0; k < b.rounds; k++) {
        double t0 = cli_now_ms();
        snell_water_step(cpu, 0.0f, b.steps, NULL);
        t_cpu[k] = (cli_now_ms() - t0) / b.steps;
        t0 = cli_now_ms();
        snell_water_step(gpu, 0.0f, b.steps, NULL);
        snell_renderer_finish(r); /* the passes finished, the settle check's read-back too */
        t_gpu[k] = (cli_now_ms() - t0) / b.steps;
        fd.water = cpu; /* its new heights are uploaded in this frame */
        t0 = cli_now_ms();
        snell_render(r, &fd, NULL);
        snell_renderer_finish(r);
        t_frame_cpu[k] = cli_now_ms() - t0;
        fd.water = gpu; /* read from its state texture */
        t0 = cli_now_ms();
        snell_render(r, &fd, NULL);
        snell_renderer_finish(r);
        t_frame_gpu[k] = cli_now_ms() - t0;
        fd.opaque = objects; /* two spheres in the water: their pass, the copy and the search */
        fd.opaque_count = 2;
        t_obj[k] = frame_ms(r, &fd);
        fd.scene_layers = -1; /* the glass drawn, but not seen by the water */
        fd.opaque = objects + 1;
        fd.opaque_count = 1;
        fd.glass = glass;
        fd.glass_count = 2;
        t_glass_off[k] = frame_ms(r, &fd);
        fd.scene_layers = 0;
        t_glass[k] = frame_ms(r, &fd);
        fd.glass = NULL;
        fd.glass_count = 0;
        fd.opaque = NULL;
        fd.opaque_count = 0;
    }
    cli_loadavg(load, sizeof load);
    threads = cli_llvmpipe_threads(snell_ctx_gl_renderer(ctx), threads_why, sizeof threads_why);
    printf("water %dx%d grid, %dx%d frame, %d rounds of %d steps; %s, llvmpipe threads %d; load %s\n", b.grid, b.grid,
           b.size, b.size, b.rounds, b.steps, snell_ctx_gl_renderer(ctx), threads, load);
    printf("simulation step: CPU %.3f ms, GPU %.3f ms (median per step; a GPU batch includes its settle reduction, finished)\n",
           cli_median(t_cpu, b.rounds), cli_median(t_gpu, b.rounds));
    printf("render frame: %.2f ms with the CPU simulation's heights uploaded, %.2f ms from the GPU state (medians, "
           "finished)\n", cli_median(t_frame_cpu, b.rounds), cli_median(t_frame_gpu, b.rounds));
    printf("render frame with two opaque spheres in the water (GPU heights): %.2f ms\n", cli_median(t_obj, b.rounds));
    printf("render frame with two glass spheres and an opaque one in the water (GPU heights, glass AUTO): %.2f ms, "
           "%.2f ms with the water not seeing the glass (scene_layers -1)\n", cli_median(t_glass, b.rounds),
           cli_median(t_glass_off, b.rounds));
    fd.water = gpu;
    if (!error_line(ctx, gpu, &fd, b.size, "rippled")) goto done;
    fd.opaque = objects;
    fd.opaque_count = 2;
    if (!error_line(ctx, gpu, &fd, b.size, "opaque")) goto done;
    fd.scene_layers = -1;
    fd.opaque = objects + 1;
    fd.opaque_count = 1;
    fd.glass = glass;
    fd.glass_count = 2;
    if (!error_line(ctx, gpu, &fd, b.size, "glass/off")) goto done;
    fd.scene_layers = 0;
    if (!error_line(ctx, gpu, &fd, b.size, "glass")) goto done;
    rc = 0;
done:
    snell_renderer_destroy(r);
    snell_mesh_destroy(sphere);
    snell_water_destroy(cpu);
    snell_water_destroy(gpu);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return rc;
}
