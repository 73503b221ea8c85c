/* SPDX-License-Identifier: MIT */
/* test_env_paraboloid — dual-paraboloid environment maps (render/env_paraboloid.h,
 * common/env.glsl). (1) The C twin of the parameterisation inverts itself and
 * gives a rim direction the same texel in both maps. (2) The GPU look-up
 * (snell_renderer_env_probe) against the procedural environment's exact
 * radiance, for random directions and for directions within 1 degree of the
 * rim, against bounds stated below; directions where the exact radiance is not
 * smooth (checker and sun edges within 0.01 rad, the floor's checkers near the
 * horizon) are left out, since there both look-ups report the faces' 3x3 box
 * filter and the texel grid's aliasing, not their parameterisation.
 * (3) A frame through the paraboloid path against the cube path, by PSNR:
 * every kernel with the static environment, the water, the scene layers, and a dynamic
 * environment with an opaque object (its maps made from the cube or
 * rendered directly). */
#include "test_util.h"
#include "render/env_paraboloid.h"
#include "snell/snell_metrics.h"
#include "snell/snell_water.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define N_RANDOM 20000
#define N_RIM 8000
#define SMOOTH_ANGLE 0.01   /* rad: a direction is smooth if the exact radiance varies by */
#define SMOOTH_SPREAD 0.02  /* at most this within SMOOTH_ANGLE of it (5 x 5 samples), */
#define FLOOR_MIN_DOWN 0.15 /* and it is sky or floor at least this far down (checkers >= 0.02 rad) */

/* Bounds, in 1/255, on the smooth directions (measured: see the printout and
 * bench/BENCHMARKS.md "Environment look-up"): the paraboloid look-up's largest
 * error, random and at the rim, and its mean against the cube's. */
#define MAX_ERR_255 2.0
#define RIM_MAX_ERR_255 2.0
#define MEAN_ERR_RATIO 1.5
#define PSNR_STATIC_DB 36.0
#define PSNR_DYNAMIC_DB 36.0
#define PSNR_DIRECT_DB 34.0

static unsigned long rng = 12345;
static double urand(void)
{
    rng = rng * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(rng >> 11) / 9007199254740992.0;
}

static void twin_checks(void)
{
    int i, worst_layer = 0;
    double worst = 0.0, worst_rim = 0.0;
    for (i = 0; i < 10000; i++) {
        double z = 2.0 * urand() - 1.0, phi = 2.0 * SNELL_PI * urand(), r = sqrt(1.0 - z * z);
        double d[3] = {r * cos(phi), r * sin(phi), z}, back[3], u, v, u2, v2;
        int layer, k;
        snell__dp_coords(d, 1024, &u, &v, &layer);
        snell__dp_dir(u, v, layer, 1024, back);
        for (k = 0; k < 3; k++) worst = fmax(worst, fabs(back[k] - d[k]));
        worst_layer |= layer != (z < 0.0);
        /* on the rim both maps: the same texture coordinate */
        d[0] = cos(phi); d[1] = sin(phi); d[2] = 0.0;
        snell__dp_coords(d, 1024, &u, &v, &layer);
        d[2] = -0.0;
        snell__dp_dir(u, v, 1, 1024, back);
        snell__dp_coords(back, 1024, &u2, &v2, &layer);
        worst_rim = fmax(worst_rim, fmax(fabs(u - u2), fabs(v - v2)));
        /* the rim lies SNELL__DP_MARGIN texels inside the edge */
        worst_rim = fmax(worst_rim, fabs(hypot(u - 0.5, v - 0.5) - (0.5 - SNELL__DP_MARGIN / 1024.0)));
    }
    CHECK(worst < 1e-12, "direction -> texel -> direction off by %g", worst);
    CHECK(!worst_layer, "a direction went to the other hemisphere's map");
    CHECK(worst_rim < 1e-12, "rim directions: maps disagree or rim not at the margin, by %g", worst_rim);
}

typedef struct err_stats {
    double sum, max;
    long n;
} err_stats;

static int smooth(const double d[3])
{
    double lo[3] = {1, 1, 1}, hi[3] = {0, 0, 0}, t1[3], t2[3], len;
    int i, k;
    /* two tangents */
    if (fabs(d[0]) < 0.9) { t1[0] = 0; t1[1] = -d[2]; t1[2] = d[1]; }
    else { t1[0] = -d[2]; t1[1] = 0; t1[2] = d[0]; }
    len = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (k = 0; k < 3; k++) t1[k] /= len;
    t2[0] = d[1] * t1[2] - d[2] * t1[1]; t2[1] = d[2] * t1[0] - d[0] * t1[2]; t2[2] = d[0] * t1[1] - d[1] * t1[0];
    /* Near the horizon the floor's checkers shrink below any fixed angle. */
    if (d[1] < 0.0 && d[1] > -FLOOR_MIN_DOWN) return 0;
    for (i = 0; i < 25; i++) {
        double a = SMOOTH_ANGLE * ((i % 5) - 2) / 2, b = SMOOTH_ANGLE * ((i / 5) - 2) / 2, p[3], c[3];
        for (k = 0; k < 3; k++) p[k] = d[k] + a * t1[k] + b * t2[k];
        snell_env_procedural_radiance(p, c);
        for (k = 0; k < 3; k++) { lo[k] = fmin(lo[k], c[k]); hi[k] = fmax(hi[k], c[k]); }
    }
    return hi[0] - lo[0] <= SMOOTH_SPREAD && hi[1] - lo[1] <= SMOOTH_SPREAD && hi[2] - lo[2] <= SMOOTH_SPREAD;
}

/* dirs: n directions; the look-up's errors against exact radiance on the smooth ones. */
static void lookup_errors(snell_renderer *r, const snell_env *env, snell_env_lookup lookup, const float *dirs,
                          const unsigned char *is_smooth, int n, err_stats *e)
{
    float *rgb = (float *)malloc(sizeof(float) * 3 * (size_t)n);
    int i, k;
    memset(e, 0, sizeof *e);
    CHECK_OK(snell_renderer_env_probe(r, env, lookup, dirs, n, rgb));
    for (i = 0; i < n; i++) {
        double d[3] = {dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]}, c[3];
        if (!is_smooth[i]) continue;
        snell_env_procedural_radiance(d, c);
        for (k = 0; k < 3; k++) {
            double err = fabs(rgb[3 * i + k] - c[k]) * 255.0;
            e->sum += err;
            e->max = fmax(e->max, err);
        }
        e->n++;
    }
    free(rgb);
}

static void make_dirs(float *dirs, unsigned char *is_smooth, int n, double z_max)
{
    int i;
    for (i = 0; i < n; i++) {
        double z = z_max * (2.0 * urand() - 1.0), phi = 2.0 * SNELL_PI * urand(), r = sqrt(1.0 - z * z);
        double d[3] = {r * cos(phi), r * sin(phi), z};
        if (i < 6) { /* where the rim meets the texture's axes, and the poles */
            d[0] = i == 0 ? 1 : i == 1 ? -1 : 0;
            d[1] = i == 2 ? 1 : i == 3 ? -1 : 0;
            d[2] = z_max < 1.0 ? 0.0 : i == 4 ? 1 : i == 5 ? -1 : 0;
            if (z_max < 1.0 && i >= 4) { d[0] = 0.70710678118654752; d[1] = i == 4 ? 0.70710678118654752 : -0.70710678118654752; }
        }
        dirs[3 * i] = (float)d[0]; dirs[3 * i + 1] = (float)d[1]; dirs[3 * i + 2] = (float)d[2];
        is_smooth[i] = (unsigned char)smooth(d);
    }
}

static void lookup_checks(snell_ctx *ctx, snell_renderer *r, const snell_env *env)
{
    static float dirs[3 * N_RANDOM], rim[3 * N_RIM];
    static unsigned char ok[N_RANDOM], ok_rim[N_RIM];
    err_stats cube, dp, cube_rim, dp_rim;
    float one[3] = {0, 0, 1}, out[3];
    make_dirs(dirs, ok, N_RANDOM, 1.0);
    make_dirs(rim, ok_rim, N_RIM, sin(SNELL_PI / 180.0));
    lookup_errors(r, env, SNELL_ENV_LOOKUP_CUBE, dirs, ok, N_RANDOM, &cube);
    lookup_errors(r, env, SNELL_ENV_LOOKUP_DUAL_PARABOLOID, dirs, ok, N_RANDOM, &dp);
    lookup_errors(r, env, SNELL_ENV_LOOKUP_CUBE, rim, ok_rim, N_RIM, &cube_rim);
    lookup_errors(r, env, SNELL_ENV_LOOKUP_DUAL_PARABOLOID, rim, ok_rim, N_RIM, &dp_rim);
    printf("smooth directions %ld of %d: cube mean %.3f max %.2f /255, paraboloid mean %.3f max %.2f\n", cube.n,
           N_RANDOM, cube.sum / (3.0 * cube.n), cube.max, dp.sum / (3.0 * dp.n), dp.max);
    printf("within 1 deg of the rim, %ld of %d: cube mean %.3f max %.2f /255, paraboloid mean %.3f max %.2f\n",
           cube_rim.n, N_RIM, cube_rim.sum / (3.0 * cube_rim.n), cube_rim.max, dp_rim.sum / (3.0 * dp_rim.n),
           dp_rim.max);
    CHECK(cube.n > N_RANDOM / 2 && cube_rim.n > N_RIM / 2, "too few smooth directions: %ld, %ld", cube.n, cube_rim.n);
    CHECK(dp.max <= MAX_ERR_255, "paraboloid look-up off by %.2f/255 > %.1f", dp.max, MAX_ERR_255);
    CHECK(dp_rim.max <= RIM_MAX_ERR_255, "paraboloid look-up at the rim off by %.2f/255 > %.1f", dp_rim.max,
          RIM_MAX_ERR_255);
    CHECK(dp.sum <= MEAN_ERR_RATIO * cube.sum && dp_rim.sum <= MEAN_ERR_RATIO * cube_rim.sum,
          "paraboloid mean error %.3f (rim %.3f) above %.1f x the cube's %.3f (%.3f)", dp.sum / (3.0 * dp.n),
          dp_rim.sum / (3.0 * dp_rim.n), MEAN_ERR_RATIO, cube.sum / (3.0 * cube.n), cube_rim.sum / (3.0 * cube_rim.n));
    CHECK(snell_renderer_env_probe(r, env, SNELL_ENV_LOOKUP_CUBE, one, 0, out) == SNELL_E_INVALID_ARG,
          "n = 0 accepted");
    CHECK(snell_renderer_env_probe(r, env, (snell_env_lookup)7, one, 1, out) == SNELL_E_INVALID_ARG,
          "unknown look-up accepted");
    (void)ctx;
}

static snell_status frame_rgba(snell_ctx *ctx, snell_env_lookup lookup, const snell_frame_desc *fd, int w, int h,
                               uint8_t *px, snell_frame_stats *fs)
{
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    snell_status st;
    memset(&rd, 0, sizeof rd);
    rd.width = w;
    rd.height = h;
    rd.env_lookup = lookup;
    rd.shading = test_shading();
    if ((st = snell_renderer_create(ctx, &rd, &r)) != SNELL_OK) return st;
    st = snell_render(r, fd, fs);
    if (st == SNELL_OK) st = snell_renderer_read_rgba(r, px);
    snell_renderer_destroy(r);
    return st;
}

/* Exit-direction output does not read the environment: the paraboloid
 * variant's programs (built with both defines) give the cube's directions. */
static void exit_dir_check(snell_ctx *ctx, const snell_frame_desc *fd)
{
    enum { W = 64, H = 48 };
    static float dirs[2][W * H * 3];
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    int l, same = 1, i;
    for (l = 0; l < 2; l++) {
        memset(&rd, 0, sizeof rd);
        rd.width = W;
        rd.height = H;
        rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
        rd.env_lookup = l ? SNELL_ENV_LOOKUP_DUAL_PARABOLOID : SNELL_ENV_LOOKUP_CUBE;
        CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
        if (!r) return;
        CHECK_OK_CTX(ctx, snell_render(r, fd, NULL));
        CHECK_OK_CTX(ctx, snell_renderer_read_exit_dirs(r, dirs[l]));
        snell_renderer_destroy(r);
        r = NULL;
    }
    for (i = 0; i < W * H * 3; i++) same &= dirs[0][i] == dirs[1][i];
    CHECK(same, "exit directions differ between the look-ups");
}

static void render_checks(snell_ctx *ctx, const snell_env *env)
{
    enum { W = 160, H = 120 };
    static uint8_t a[W * H * 4], b[W * H * 4];
    snell_shape_desc sd = {SNELL_SHAPE_SPHERE, 48, 24};
    snell_shape_desc cd = {SNELL_SHAPE_CUBE, 0, 0};
    snell_mesh *sphere = NULL, *cube = NULL;
    snell_frame_desc fd;
    snell_glass g;
    snell_opaque op;
    snell_frame_stats fs;
    snell_image_error e;
    int passes_from_cube, m;
    float model[16] = {0.4f, 0, 0, 0, 0, 0.4f, 0, 0, 0, 0, 0.4f, 0, 1.2f, -0.3f, -0.8f, 1};
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &sphere));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &cd, &cube));
    if (!sphere || !cube) return;
    test_frame_one(&fd, &g, sphere, env);
    /* every kernel's paraboloid variant: each method of the registry */
    for (m = 0; m < snell_method_count(); m++) {
        snell_method id = snell_method_info_at(m)->method;
        g.material.method = id;
        CHECK_OK_CTX(ctx, frame_rgba(ctx, SNELL_ENV_LOOKUP_CUBE, &fd, W, H, a, &fs));
        CHECK(!fs.glass[0].env_paraboloid && !fs.background_paraboloid, "cube look-up asked for, paraboloid used");
        CHECK_OK_CTX(ctx, frame_rgba(ctx, SNELL_ENV_LOOKUP_DUAL_PARABOLOID, &fd, W, H, b, &fs));
        CHECK(fs.glass[0].env_paraboloid && fs.background_paraboloid && fs.glass[0].method_used == id,
              "paraboloid look-up asked for, not used");
        CHECK_OK(snell_metrics_image_error(b, a, W, H, NULL, &e));
        printf("static environment, %s: paraboloid vs cube PSNR %.2f dB, max %d/255\n",
               snell_method_str(fs.glass[0].method_used), e.psnr_db, e.max_abs);
        CHECK(e.psnr_db >= PSNR_STATIC_DB, "%s: paraboloid frame %.2f dB from the cube frame < %.0f",
              snell_method_str(id), e.psnr_db, PSNR_STATIC_DB);
    }
    g.material.method = SNELL_METHOD_AUTO;
    exit_dir_check(ctx, &fd);
    /* a dynamic environment: an opaque cube beside the glass */
    memset(&op, 0, sizeof op);
    op.mesh = cube;
    op.model = model;
    op.color[0] = 0.9f; op.color[1] = 0.3f; op.color[2] = 0.2f;
    fd.opaque = &op;
    fd.opaque_count = 1;
    /* seen through the scene layers (the default with opaque objects): exit
     * rays march them, then look the static environment up */
    CHECK_OK_CTX(ctx, frame_rgba(ctx, SNELL_ENV_LOOKUP_CUBE, &fd, W, H, a, &fs));
    CHECK_OK_CTX(ctx, frame_rgba(ctx, SNELL_ENV_LOOKUP_DUAL_PARABOLOID, &fd, W, H, b, &fs));
    CHECK(fs.glass[0].env_paraboloid && fs.scene_layer_passes > 0, "scene layers with paraboloid maps not used");
    CHECK_OK(snell_metrics_image_error(b, a, W, H, NULL, &e));
    printf("scene layers: paraboloid vs cube PSNR %.2f dB, max %d/255\n", e.psnr_db, e.max_abs);
    CHECK(e.psnr_db >= PSNR_STATIC_DB, "paraboloid frame %.2f dB from the cube frame < %.0f", e.psnr_db, PSNR_STATIC_DB);
    /* through a dynamic environment */
    fd.scene_layers = -1;
    CHECK_OK_CTX(ctx, frame_rgba(ctx, SNELL_ENV_LOOKUP_CUBE, &fd, W, H, a, &fs));
    CHECK_OK_CTX(ctx, frame_rgba(ctx, SNELL_ENV_LOOKUP_DUAL_PARABOLOID, &fd, W, H, b, &fs));
    CHECK(fs.glass[0].env_paraboloid && fs.glass[0].env_updated, "dynamic paraboloid maps not made");
    CHECK_OK(snell_metrics_image_error(b, a, W, H, NULL, &e));
    printf("dynamic environment: paraboloid vs cube PSNR %.2f dB, max %d/255\n", e.psnr_db, e.max_abs);
    CHECK(e.psnr_db >= PSNR_DYNAMIC_DB, "paraboloid frame %.2f dB from the cube frame < %.0f", e.psnr_db,
          PSNR_DYNAMIC_DB);
    passes_from_cube = fs.glass[0].passes;
    /* its maps rendered straight: 2 views instead of 6 faces and 2 resamplings */
    CHECK_OK_CTX(ctx, frame_rgba(ctx, SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT, &fd, W, H, b, &fs));
    CHECK(fs.glass[0].env_paraboloid && fs.glass[0].env_updated, "direct paraboloid maps not made");
    CHECK(fs.glass[0].passes == passes_from_cube - 10, "direct maps: %d passes, want %d - 10 (2 x 2 instead of "
          "6 x 2 + 2)", fs.glass[0].passes, passes_from_cube);
    CHECK_OK(snell_metrics_image_error(b, a, W, H, NULL, &e));
    printf("dynamic environment, maps rendered directly: paraboloid vs cube PSNR %.2f dB, max %d/255\n", e.psnr_db,
           e.max_abs);
    CHECK(e.psnr_db >= PSNR_DIRECT_DB, "direct paraboloid frame %.2f dB from the cube frame < %.0f", e.psnr_db,
          PSNR_DIRECT_DB);
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(cube);
}

/* The water (src/water/) reflects the static environment through the same look-up. */
static void water_check(snell_ctx *ctx, const snell_env *env)
{
    enum { W = 128, H = 96 };
    static uint8_t a[W * H * 4], b[W * H * 4];
    snell_water *w = NULL;
    snell_frame_desc fd;
    snell_frame_stats fs;
    snell_image_error e;
    CHECK_OK_CTX(ctx, snell_water_create(ctx, &(snell_water_desc){.grid = 64, .sim = SNELL_WATER_SIM_CPU}, &w));
    if (!w) return;
    CHECK_OK(snell_water_drop(w, 0.3f, -0.2f, 0.15f, -0.03f));
    CHECK_OK_CTX(ctx, snell_water_step(w, 0.0f, 20, NULL));
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.water = w;
    fd.camera.elevation = 0.6f;
    fd.camera.distance = 3.6f;
    CHECK_OK_CTX(ctx, frame_rgba(ctx, SNELL_ENV_LOOKUP_CUBE, &fd, W, H, a, &fs));
    CHECK_OK_CTX(ctx, frame_rgba(ctx, SNELL_ENV_LOOKUP_DUAL_PARABOLOID, &fd, W, H, b, &fs));
    CHECK(fs.water_drawn, "no water drawn");
    CHECK_OK(snell_metrics_image_error(b, a, W, H, NULL, &e));
    printf("water: paraboloid vs cube PSNR %.2f dB, max %d/255\n", e.psnr_db, e.max_abs);
    CHECK(e.psnr_db >= PSNR_STATIC_DB, "water: paraboloid frame %.2f dB from the cube frame < %.0f", e.psnr_db,
          PSNR_STATIC_DB);
    snell_water_destroy(w);
}

int main(void)
{
    snell_ctx *ctx;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    twin_checks();
    if (!(ctx = test_ctx())) SKIP("no GL context");
    CHECK_OK_CTX(ctx, snell_env_create(ctx, NULL, &env));
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = 16;
    rd.env_lookup = (snell_env_lookup)7;
    CHECK(snell_renderer_create(ctx, &rd, &r) == SNELL_E_INVALID_ARG && !r, "unknown env_lookup accepted");
    rd.env_lookup = SNELL_ENV_LOOKUP_AUTO;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (env && r) {
        lookup_checks(ctx, r, env);
        render_checks(ctx, env);
        water_check(ctx, env);
    }
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
