/* SPDX-License-Identifier: MIT */
/* bench_env.c — snell-bench --env-lookup: the cube against the dual-paraboloid
 * environment look-up (snell_renderer_desc.env_lookup: dynamic maps made from
 * the cube, or rendered directly), all in one run. Time: frames that take
 * turns round by round (skybox alone, full-screen kernels, a dynamic
 * environment re-rendered every frame), medians and the median of per-round
 * ratios, and each case's frame against the cube's (PSNR). Error: each look-up on the GPU
 * (snell_renderer_env_probe) against the procedural environment's exact
 * radiance (snell_env_procedural_radiance), for uniformly random directions
 * and for directions within 1 degree of the paraboloids' rim (z = 0). */
#include "snell/snell.h"
#include "cli_opts.h"
#include "cli_time.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>

#define N_CASES 6
#define N_DIRS 200000
#define N_LOOKUPS 3 /* cube, dual paraboloid, dual paraboloid with dynamic maps rendered directly */

typedef struct env_case {
    const char *name;
    snell_method method;      /* glass drawn; SNELL_METHOD_COUNT_ = no glass (skybox alone) */
    float distance;           /* camera distance (a sphere of radius 1 at the origin) */
    int opaque;               /* an opaque object moving every frame, so the dynamic environment re-renders:
                               * 1 a cube (12 triangles), 2 a dense sphere (65,536 triangles) */
} env_case;

static const env_case k_cases[N_CASES] = {
    {"skybox", SNELL_METHOD_COUNT_, 3.5f, 0},
    {"single full-screen", SNELL_METHOD_SINGLE, 1.05f, 0},
    {"cubemap full-screen", SNELL_METHOD_CUBEMAP, 1.05f, 0},
    {"single, dynamic env", SNELL_METHOD_SINGLE, 3.5f, 1},
    {"cubemap, dynamic env", SNELL_METHOD_CUBEMAP, 3.5f, 1},
    {"single, dynamic env, dense opaque", SNELL_METHOD_SINGLE, 3.5f, 2},
};

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static unsigned long g_rng = 2002;
static double urand(void)
{
    g_rng = g_rng * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(g_rng >> 11) / 9007199254740992.0;
}

/* One timed frame of case c, ended by glFinish, its opaque object (if any) at
 * orbit position frame. */
static int render_case_at(snell_renderer *r, const snell_env *env, const env_case *c, const snell_mesh *sphere,
                          const snell_mesh *const *opaque, int frame, double *ms)
{
    snell_frame_desc fd;
    snell_glass g;
    snell_opaque op;
    float model[16] = {0.4f, 0, 0, 0, 0, 0.4f, 0, 0, 0, 0, 0.4f, 0, 0, 0, 0, 1};
    double t0;
    memset(&fd, 0, sizeof fd);
    memset(&g, 0, sizeof g);
    fd.env = env;
    fd.camera.distance = c->distance;
    fd.camera.fov_y = 1.0472f; /* 60 degrees: at distance 1.05 the sphere covers the frame */
    if (c->method != SNELL_METHOD_COUNT_) {
        g.mesh = sphere;
        g.material.ior = 1.5f;
        g.material.method = c->method;
        fd.glass = &g;
        fd.glass_count = 1;
    }
    if (c->opaque) {
        /* moves every frame, so every frame re-renders the dynamic environment */
        memset(&op, 0, sizeof op);
        model[12] = 1.6f * cosf(0.1f * (float)frame);
        model[14] = 1.6f * sinf(0.1f * (float)frame);
        op.mesh = opaque[c->opaque - 1];
        op.model = model;
        op.color[0] = 0.9f; op.color[1] = 0.4f; op.color[2] = 0.2f;
        fd.opaque = &op;
        fd.opaque_count = 1;
        fd.scene_layers = -1; /* seen through the dynamic environment, not the scene layers */
    }
    t0 = cli_now_ms();
    if (snell_render(r, &fd, NULL) != SNELL_OK) return 0;
    snell_renderer_finish(r);
    *ms = cli_now_ms() - t0;
    return 1;
}

/* PSNR (RGB, 8 bits) of one frame of case c through each look-up against
 * the cube's (psnr[0] unused). */
static int frame_psnr(snell_renderer *const *r, const snell_env *env, const env_case *c, const snell_mesh *sphere,
                      const snell_mesh *const *opaque, int size, double psnr[N_LOOKUPS])
{
    size_t n = (size_t)size * size * 4, i;
    uint8_t *px[N_LOOKUPS];
    int l, ok = 1;
    double ms;
    for (l = 0; l < N_LOOKUPS; l++) px[l] = (uint8_t *)malloc(n);
    for (l = 0; l < N_LOOKUPS && ok; l++) /* the opaque object at one position for all */
        ok = px[l] && render_case_at(r[l], env, c, sphere, opaque, 7, &ms) && snell_renderer_read_rgba(r[l], px[l]) == SNELL_OK;
    for (l = 1; l < N_LOOKUPS && ok; l++) {
        double se = 0.0;
        for (i = 0; i < n; i++)
            if (i % 4 != 3) se += ((double)px[l][i] - px[0][i]) * ((double)px[l][i] - px[0][i]);
        se /= (double)(n / 4 * 3);
        psnr[l] = se > 0.0 ? 20.0 * log10(255.0 / sqrt(se)) : INFINITY;
    }
    for (l = 0; l < N_LOOKUPS; l++) free(px[l]);
    return ok;
}

/* The same, the opaque object moved at every call: no renderer's dynamic
 * environment is ever reused. */
static int render_case(snell_renderer *r, const snell_env *env, const env_case *c, const snell_mesh *sphere,
                       const snell_mesh *const *opaque, double *ms)
{
    static int frame;
    return render_case_at(r, env, c, sphere, opaque, ++frame, ms);
}

typedef struct err_acc {
    double sum, max;
    long n;
} err_acc;

/* Is the exact radiance smooth about d: within 0.01 rad (5 x 5 samples) it
 * varies by at most 0.02, and d is sky or floor at least 0.15 down (nearer the
 * horizon the checkers shrink below any fixed angle)? Elsewhere both look-ups
 * report the faces' 3x3 box filter and aliasing, not their parameterisation
 * (tests/test_env_paraboloid.c uses the same rule). */
static int smooth(const double d[3])
{
    double lo[3] = {1, 1, 1}, hi[3] = {0, 0, 0}, t1[3], t2[3], len;
    int i, k;
    if (d[1] < 0.0 && d[1] > -0.15) return 0;
    if (fabs(d[0]) < 0.9) { t1[0] = 0; t1[1] = -d[2]; t1[2] = d[1]; }
    else { t1[0] = -d[2]; t1[1] = 0; t1[2] = d[0]; }
    len = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (k = 0; k < 3; k++) t1[k] /= len;
    t2[0] = d[1] * t1[2] - d[2] * t1[1]; t2[1] = d[2] * t1[0] - d[0] * t1[2]; t2[2] = d[0] * t1[1] - d[1] * t1[0];
    for (i = 0; i < 25; i++) {
        double a = 0.005 * ((i % 5) - 2), b = 0.005 * ((i / 5) - 2), p[3], c[3];
        for (k = 0; k < 3; k++) p[k] = d[k] + a * t1[k] + b * t2[k];
        snell_env_procedural_radiance(p, c);
        for (k = 0; k < 3; k++) { lo[k] = fmin(lo[k], c[k]); hi[k] = fmax(hi[k], c[k]); }
    }
    return hi[0] - lo[0] <= 0.02 && hi[1] - lo[1] <= 0.02 && hi[2] - lo[2] <= 0.02;
}

/* e[0]: every direction, e[1]: the smooth ones. */
static void errors(snell_renderer *r, const snell_env *env, snell_env_lookup lookup, const float *dirs, int n,
                   err_acc e[2])
{
    float *rgb = (float *)malloc(sizeof(float) * 3 * (size_t)n);
    int i, k, j;
    memset(e, 0, 2 * sizeof *e);
    if (!rgb || snell_renderer_env_probe(r, env, lookup, dirs, n, rgb) != SNELL_OK) {
        e[0].n = -1;
        free(rgb);
        return;
    }
    for (i = 0; i < n; i++) {
        double d[3] = {dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]}, c[3];
        int sm = smooth(d);
        snell_env_procedural_radiance(d, c);
        for (j = 0; j <= sm; j++) {
            for (k = 0; k < 3; k++) {
                double err = fabs(rgb[3 * i + k] - c[k]) * 255.0;
                e[j].sum += err * err;
                e[j].max = fmax(e[j].max, err);
            }
            e[j].n++;
        }
    }
    free(rgb);
}

static void random_dirs(float *dirs, int n, double z_max)
{
    int i;
    for (i = 0; i < n; i++) {
        double z = z_max * (2.0 * urand() - 1.0), phi = 2.0 * 3.14159265358979323846 * urand(), s = sqrt(1.0 - z * z);
        dirs[3 * i] = (float)(s * cos(phi));
        dirs[3 * i + 1] = (float)(s * sin(phi));
        dirs[3 * i + 2] = (float)z;
    }
}

int snell_bench_env_main(int argc, char **argv)
{
    int frames = 21, size = 512, face = 512, i, c, l, rc = 0;
    snell_env_desc ed;
    snell_ctx *ctx = NULL;
    snell_env *env = NULL;
    snell_mesh *sphere = NULL, *opaque[2] = {NULL, NULL};
    static const snell_env_lookup lookups[N_LOOKUPS] = {SNELL_ENV_LOOKUP_CUBE, SNELL_ENV_LOOKUP_DUAL_PARABOLOID,
                                                        SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT};
    snell_renderer *r[N_LOOKUPS] = {NULL, NULL, NULL};
    snell_shape_desc sd = {SNELL_SHAPE_SPHERE, 64, 32}, cd = {SNELL_SHAPE_CUBE, 0, 0};
    snell_shape_desc dd = {SNELL_SHAPE_SPHERE, 256, 128};
    static double t[N_CASES][N_LOOKUPS][256], ratio[N_CASES][256];
    float *dirs = (float *)malloc(sizeof(float) * 3 * N_DIRS);
    static const struct option longopts[] = {
        {"env-lookup", no_argument, NULL, 'E'}, {"frames", required_argument, NULL, 'f'},
        {"sizes", required_argument, NULL, 's'}, {"face", required_argument, NULL, 'F'},
        {"help", no_argument, NULL, 'h'},       {NULL, 0, NULL, 0}};
    if (cli_wants_help(argc, argv)) {
        printf("usage: snell-bench --env-lookup [--frames N] [--sizes SxS] [--face N]\n"
               "The cube against the dual-paraboloid environment look-up: frame times side by side.\n"
               "  --frames N   timed frames, 3..256 (default 21)\n"
               "  --sizes SxS  image size (square), 16..4096 (default 512x512)\n"
               "  --face N     environment face size, 16..4096 (default 512)\n"
               "  -h, --help   this text\n");
        free(dirs);
        return 0;
    }
    cli_opts_reset();
    while ((c = cli_getopt("snell-bench --env-lookup", "--env-lookup --help", argc, argv, "h", longopts)) != -1) {
        char *end, tail;
        long v;
        int h = 0;
        if (c == '?') return free(dirs), 2;
        if (c == 's') {
            if (sscanf(optarg, "%dx%d%c", &size, &h, &tail) != 2 || h != size || size < 16 || size > 4096) {
                fprintf(stderr, "snell-bench --env-lookup: --sizes %s: want a square size SxS, 16..4096\n", optarg);
                return free(dirs), 2;
            }
            continue;
        }
        if (c != 'f' && c != 'F') continue; /* --env-lookup itself */
        v = strtol(optarg, &end, 10);
        if (end == optarg || *end || v < (c == 'f' ? 3 : 16) || v > (c == 'f' ? 256 : 4096)) {
            fprintf(stderr, "snell-bench --env-lookup: %s wants %s, got '%s'\n", c == 'f' ? "--frames" : "--face",
                    c == 'f' ? "3..256" : "16..4096", optarg);
            return free(dirs), 2;
        }
        *(c == 'f' ? &frames : &face) = (int)v;
    }
    if (optind < argc) {
        fprintf(stderr, "snell-bench --env-lookup: unexpected argument '%s'; see --env-lookup --help\n", argv[optind]);
        return free(dirs), 2;
    }
    if (!dirs) {
        fprintf(stderr, "snell-bench --env-lookup: out of memory\n");
        return 1;
    }
    memset(&ed, 0, sizeof ed);
    ed.face_size = face;
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK || snell_env_create(ctx, &ed, &env) != SNELL_OK ||
        snell_mesh_create_shape(ctx, &sd, &sphere) != SNELL_OK || snell_mesh_create_shape(ctx, &cd, &opaque[0]) != SNELL_OK ||
        snell_mesh_create_shape(ctx, &dd, &opaque[1]) != SNELL_OK) {
        fprintf(stderr, "snell-bench --env-lookup: %s\n", snell_last_error(ctx));
        rc = 1;
        goto done;
    }
    for (l = 0; l < N_LOOKUPS; l++) {
        snell_renderer_desc rd;
        memset(&rd, 0, sizeof rd);
        rd.width = rd.height = size;
        rd.env_lookup = lookups[l];
        if (snell_renderer_create(ctx, &rd, &r[l]) != SNELL_OK) {
            fprintf(stderr, "snell-bench --env-lookup: %s\n", snell_last_error(ctx));
            rc = 1;
            goto done;
        }
    }
    printf("renderer: %s\nframe %dx%d, environment face %d (paraboloid maps 2 x %d^2), %d rounds after 2 of warm-up\n",
           snell_ctx_gl_renderer(ctx), size, size, face, 2 * face, frames);
    /* Round by round, every case with every look-up, the order rotating. */
    for (i = -2; i < frames; i++)
        for (c = 0; c < N_CASES; c++)
            for (l = 0; l < N_LOOKUPS; l++) {
                int which = (l + i + 2) % N_LOOKUPS;
                double ms;
                if (!render_case(r[which], env, &k_cases[c], sphere, (const snell_mesh *const *)opaque, &ms)) {
                    fprintf(stderr, "snell-bench --env-lookup: %s: %s\n", k_cases[c].name, snell_last_error(ctx));
                    rc = 1;
                    goto done;
                }
                if (i >= 0) t[c][which][i] = ms;
            }
    printf("\n| case | cube ms | paraboloid ms | direct ms | paraboloid / cube | direct / cube | paraboloid PSNR | direct PSNR |\n"
           "| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (c = 0; c < N_CASES; c++) {
        double q[N_LOOKUPS], psnr[N_LOOKUPS];
        if (!frame_psnr(r, env, &k_cases[c], sphere, (const snell_mesh *const *)opaque, size, psnr)) {
            fprintf(stderr, "snell-bench --env-lookup: %s: %s\n", k_cases[c].name, snell_last_error(ctx));
            rc = 1;
            goto done;
        }
        for (l = 1; l < N_LOOKUPS; l++) {
            for (i = 0; i < frames; i++) ratio[c][i] = t[c][l][i] / t[c][0][i];
            q[l] = median(ratio[c], frames);
        }
        printf("| %s | %.2f | %.2f | %.2f | %.3f | %.3f | %.2f | %.2f |\n", k_cases[c].name, median(t[c][0], frames),
               median(t[c][1], frames), median(t[c][2], frames), q[1], q[2], psnr[1], psnr[2]);
    }
    printf("\n| directions | cube RMS /255 | cube max | paraboloid RMS /255 | paraboloid max |\n| --- | --- | --- | --- | --- |\n");
    for (c = 0; c < 2; c++) {
        err_acc cube_e[2], dp_e[2];
        random_dirs(dirs, N_DIRS, c ? sin(3.14159265358979323846 / 180.0) : 1.0);
        errors(r[0], env, SNELL_ENV_LOOKUP_CUBE, dirs, N_DIRS, cube_e);
        errors(r[0], env, SNELL_ENV_LOOKUP_DUAL_PARABOLOID, dirs, N_DIRS, dp_e);
        if (cube_e[0].n <= 0 || dp_e[0].n <= 0) {
            fprintf(stderr, "snell-bench --env-lookup: probe: %s\n", snell_last_error(ctx));
            rc = 1;
            goto done;
        }
        for (l = 0; l < 2; l++)
            printf("| %ld %s%s | %.3f | %.2f | %.3f | %.2f |\n", cube_e[l].n, c ? "within 1 deg of the rim" : "uniform",
                   l ? ", smooth" : "", sqrt(cube_e[l].sum / (3.0 * cube_e[l].n)), cube_e[l].max,
                   sqrt(dp_e[l].sum / (3.0 * dp_e[l].n)), dp_e[l].max);
    }
done:
    for (l = 0; l < N_LOOKUPS; l++) snell_renderer_destroy(r[l]);
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(opaque[0]);
    snell_mesh_destroy(opaque[1]);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    free(dirs);
    return rc;
}
