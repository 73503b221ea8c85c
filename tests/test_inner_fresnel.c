/* SPDX-License-Identifier: MIT */
/* test_inner_fresnel — inner-surface Fresnel in the cubemap kernel
 * (material.cubemap.inner_fresnel, cubemap.frag SNELL_INNER_FRESNEL) and in
 * oliveira's image-space search (material.oliveira.inner_fresnel), each:
 *  - energy: in a uniform grey environment (128) every glass pixel stays 128
 *    with it on (F + (1-F) [(1-Fe) + Fe ((1-F') + F')] = 1 when the weights
 *    sum right; grey, not white, so that too much light is not clamped
 *    away), with both Fresnel models;
 *  - it moves the sphere towards the FULL reference: glass-pixel PSNR against
 *    FULL at least 2 dB above the same kernel without it for the cubemap
 *    (measured at 128x128: +2.8 dB, 29.7 -> 32.5, the exit's 1 - F and the
 *    first internal reflection being what the two-interface model leaves
 *    out); for oliveira at least 0.2 dB: here, point-sampled at 128x128, its
 *    own error dominates (20.6 dB: exit normals from a per-pixel map on a
 *    sphere 90 px across), measured +0.34 dB; +1.6 dB at 256x256
 *    area-averaged (bench/BENCHMARKS.md);
 *  - AUTO is on for the (convex) sphere and off for the torus: images equal
 *    to ON and OFF respectively;
 *  - the same for the depth-peeling kernel (material.peel.inner_fresnel):
 *    grey-world energy on the sphere, torus and goblet; PSNR against FULL up
 *    on each (bounds and measured gains in peel_checks); AUTO on for all
 *    three. */
#include "test_util.h"
#include "snell/snell_metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 128
#define H 128

static uint8_t *frame(snell_ctx *ctx, snell_frame_desc *fd, snell_glass *g, snell_method method,
                      snell_inner_fresnel inner, snell_fresnel_model model)
{
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    uint8_t *px = (uint8_t *)malloc((size_t)W * H * 4);
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.shading = test_shading();
    g->material.method = method;
    g->material.cubemap.inner_fresnel = g->material.oliveira.inner_fresnel = g->material.peel.inner_fresnel = inner;
    g->material.cubemap.fresnel = g->material.oliveira.fresnel = g->material.peel.fresnel = model;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (r) {
        CHECK_OK_CTX(ctx, snell_render(r, fd, NULL));
        CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, px));
    }
    snell_renderer_destroy(r);
    return px;
}

static snell_env *grey_env(snell_ctx *ctx)
{
    static uint8_t face[8 * 8 * 4];
    char paths[6][256];
    snell_env_desc ed;
    snell_env *env = NULL;
    int f;
    memset(face, 128, sizeof face);
    memset(&ed, 0, sizeof ed);
    ed.source = SNELL_ENV_FACES;
    for (f = 0; f < 6; f++) {
        char name[32];
        snprintf(name, sizeof name, "inner_grey%d.png", f);
        snprintf(paths[f], sizeof paths[f], "%s", test_out(name));
        CHECK_OK(snell_write_png(paths[f], 8, 8, face));
        ed.face_paths[f] = paths[f];
    }
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &env));
    return env;
}

/* Channels of glass and background alike more than 1 off the grey 128. */
static long off_grey(const uint8_t *px)
{
    long i, off = 0;
    for (i = 0; i < (long)W * H * 4; i++) off += i % 4 != 3 && abs(px[i] - 128) > 1;
    return off;
}

/* The three checks of the header for one method, against the FULL image refpx. */
static void check_method(snell_ctx *ctx, snell_method method, double min_gain_db, snell_mesh *sphere,
                         snell_mesh *torus, snell_env *env, snell_env *grey, const uint8_t *refpx, const uint8_t *hit)
{
    snell_frame_desc fd;
    snell_glass g;
    snell_image_error e_off, e_on;
    const char *name = snell_method_str(method);
    int m;
    test_frame_one(&fd, &g, sphere, grey);
    for (m = SNELL_FRESNEL_SCHLICK; m <= SNELL_FRESNEL_EXACT; m++) {
        uint8_t *px = frame(ctx, &fd, &g, method, SNELL_INNER_FRESNEL_ON, (snell_fresnel_model)m);
        long off = off_grey(px);
        CHECK(off == 0, "%s: grey environment, inner Fresnel, model %d: %ld channels off 128 by more than 1", name, m,
              off);
        free(px);
    }
    test_frame_one(&fd, &g, sphere, env);
    {
        uint8_t *off = frame(ctx, &fd, &g, method, SNELL_INNER_FRESNEL_OFF, SNELL_FRESNEL_EXACT);
        uint8_t *on = frame(ctx, &fd, &g, method, SNELL_INNER_FRESNEL_ON, SNELL_FRESNEL_EXACT);
        uint8_t *aut = frame(ctx, &fd, &g, method, SNELL_INNER_FRESNEL_AUTO, SNELL_FRESNEL_EXACT);
        CHECK_OK(snell_metrics_image_error(off, refpx, W, H, hit, &e_off));
        CHECK_OK(snell_metrics_image_error(on, refpx, W, H, hit, &e_on));
        printf("%s: sphere %dx%d vs FULL over %ld glass pixels: inner Fresnel off %.2f dB, on %.2f dB\n", name, W, H,
               e_on.pixels, e_off.psnr_db, e_on.psnr_db);
        CHECK(e_on.psnr_db >= e_off.psnr_db + min_gain_db, "%s inner Fresnel: %.2f dB, not %.1f dB above %.2f dB",
              name, e_on.psnr_db, min_gain_db, e_off.psnr_db);
        CHECK(!memcmp(aut, on, (size_t)W * H * 4), "%s: AUTO is on for the convex sphere", name);
        free(off);
        free(on);
        free(aut);
    }
    test_frame_one(&fd, &g, torus, env);
    {
        uint8_t *off = frame(ctx, &fd, &g, method, SNELL_INNER_FRESNEL_OFF, SNELL_FRESNEL_SCHLICK);
        uint8_t *aut = frame(ctx, &fd, &g, method, SNELL_INNER_FRESNEL_AUTO, SNELL_FRESNEL_SCHLICK);
        uint8_t *on = frame(ctx, &fd, &g, method, SNELL_INNER_FRESNEL_ON, SNELL_FRESNEL_SCHLICK);
        CHECK(!memcmp(aut, off, (size_t)W * H * 4), "%s: AUTO is off for the torus (not convex)", name);
        CHECK(memcmp(on, off, (size_t)W * H * 4) != 0, "%s: ON changes the torus", name);
        free(off);
        free(aut);
        free(on);
    }
}

/* The FULL reference of fd's glass in env at pixel centres: rgba8, and the glass pixels. */
static void full_reference(snell_ctx *ctx, const snell_frame_desc *fd, const snell_glass *g, const snell_env *env,
                           float *rgb, uint8_t *hit, uint8_t *refpx)
{
    snell_ref_desc rdsc;
    snell_ref_output o;
    snell_ref_params p;
    snell_ref *ref = NULL;
    memset(&rdsc, 0, sizeof rdsc);
    rdsc.glass = g;
    rdsc.glass_count = 1;
    CHECK_OK(snell_ref_create(ctx, &rdsc, &ref));
    memset(&p, 0, sizeof p);
    p.mode = SNELL_REF_FULL;
    p.isolate_glass = 1;
    p.env = env;
    p.camera = fd->camera;
    p.width = W;
    p.height = H;
    memset(&o, 0, sizeof o);
    o.rgb = rgb;
    o.hit = hit;
    memset(rgb, 0, sizeof(float) * 3 * W * H);
    memset(hit, 0, W * H);
    if (ref) CHECK_OK(snell_ref_render(ref, &p, &o));
    snell_ref_rgb_to_rgba8(rgb, W, H, refpx);
    snell_ref_destroy(ref);
}

/* The same option in the depth-peeling kernel (material.peel.inner_fresnel,
 * peel.frag SNELL_INNER_FRESNEL), at the last exit into air, on the sphere,
 * the torus and the goblet: energy in the grey world, the gain against FULL,
 * and AUTO = ON on all three (peel's default, BENCHMARKS.md). */
static void peel_checks(snell_ctx *ctx, const snell_mesh *sphere, const snell_mesh *torus, const snell_mesh *goblet,
                        const snell_env *env, const snell_env *grey, float *rgb, uint8_t *hit, uint8_t *refpx)
{
    const snell_mesh *const meshes[3] = {sphere, torus, goblet};
    static const char *const names[3] = {"sphere", "torus", "goblet"};
    snell_frame_desc fd;
    snell_glass g;
    /* the least gain against FULL (128x128, pixel centres, exact Fresnel).
     * Measured on llvmpipe, forward and screen alike within 0.03 dB: sphere
     * +3.32 dB, torus +0.43, goblet +0.59; with the exit's F halved (a
     * mutation) +2.80, +0.34, +0.37. The sphere's and goblet's bounds lie
     * between the two, so that mutation fails them; the torus' only
     * asserts a clear gain. */
    static const double min_gain[3] = {3.0, 0.3, 0.48};
    snell_image_error e_off, e_on;
    int k, m;
    for (k = 0; k < 3; k++) {
        test_frame_one(&fd, &g, meshes[k], grey);
        for (m = SNELL_FRESNEL_SCHLICK; m <= SNELL_FRESNEL_EXACT; m++) {
            uint8_t *px = frame(ctx, &fd, &g, SNELL_METHOD_PEEL, SNELL_INNER_FRESNEL_ON, (snell_fresnel_model)m);
            long off = off_grey(px);
            CHECK(off == 0, "peel: %s, grey environment, inner Fresnel, model %d: %ld channels off 128 by more "
                            "than 1", names[k], m, off);
            free(px);
        }
    }
    for (k = 0; k < 3; k++) {
        uint8_t *off, *on, *aut;
        test_frame_one(&fd, &g, meshes[k], env);
        full_reference(ctx, &fd, &g, env, rgb, hit, refpx);
        off = frame(ctx, &fd, &g, SNELL_METHOD_PEEL, SNELL_INNER_FRESNEL_OFF, SNELL_FRESNEL_EXACT);
        on = frame(ctx, &fd, &g, SNELL_METHOD_PEEL, SNELL_INNER_FRESNEL_ON, SNELL_FRESNEL_EXACT);
        aut = frame(ctx, &fd, &g, SNELL_METHOD_PEEL, SNELL_INNER_FRESNEL_AUTO, SNELL_FRESNEL_EXACT);
        CHECK_OK(snell_metrics_image_error(off, refpx, W, H, hit, &e_off));
        CHECK_OK(snell_metrics_image_error(on, refpx, W, H, hit, &e_on));
        printf("peel: %s %dx%d vs FULL over %ld glass pixels: inner Fresnel off %.2f dB, on %.2f dB\n", names[k], W,
               H, e_on.pixels, e_off.psnr_db, e_on.psnr_db);
        CHECK(e_on.psnr_db >= e_off.psnr_db + min_gain[k], "peel: %s, inner Fresnel: %.2f dB, not %.2f dB above "
              "%.2f dB", names[k], e_on.psnr_db, min_gain[k], e_off.psnr_db);
        CHECK(!memcmp(aut, on, (size_t)W * H * 4), "peel: %s, AUTO is on (convex or not)", names[k]);
        free(off);
        free(on);
        free(aut);
    }
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL, *grey;
    snell_env_desc ed;
    snell_mesh *sphere = NULL, *torus = NULL, *goblet = NULL;
    snell_frame_desc fd;
    snell_glass g;
    float *rgb = (float *)malloc(sizeof(float) * 3 * W * H);
    uint8_t *hit = (uint8_t *)malloc(W * H), *refpx = (uint8_t *)malloc(W * H * 4);
    if (!ctx) SKIP("no GL context");
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_SPHERE, 96, 48}, &sphere));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_TORUS, 64, 32}, &torus));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_GOBLET, 64, 32}, &goblet));
    memset(&ed, 0, sizeof ed);
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &env));
    grey = grey_env(ctx);
    if (!sphere || !torus || !goblet || !env || !grey) return test_finish();

    test_frame_one(&fd, &g, sphere, env);
    full_reference(ctx, &fd, &g, env, rgb, hit, refpx);
    check_method(ctx, SNELL_METHOD_CUBEMAP, 2.0, sphere, torus, env, grey, refpx, hit);
    check_method(ctx, SNELL_METHOD_OLIVEIRA, 0.2, sphere, torus, env, grey, refpx, hit);
    peel_checks(ctx, sphere, torus, goblet, env, grey, rgb, hit, refpx);
    free(rgb);
    free(hit);
    free(refpx);
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(torus);
    snell_mesh_destroy(goblet);
    snell_env_destroy(env);
    snell_env_destroy(grey);
    snell_ctx_destroy(ctx);
    return test_finish();
}
