/* test_inner_fresnel — the cubemap kernel's inner-surface Fresnel
 * (material.cubemap.inner_fresnel, cubemap.frag SNELL_INNER_FRESNEL):
 *  - energy: in a uniform grey environment (128) every glass pixel stays 128
 *    with it on (F + (1-F) [(1-Fe) + Fe ((1-F') + F')] = 1 when the weights
 *    sum right; grey, not white, so that too much light is not clamped
 *    away), with both Fresnel models;
 *  - it moves the sphere towards the FULL reference: glass-pixel PSNR against
 *    FULL at least 2 dB above the same kernel without it (measured at 128x128:
 *    +2.8 dB, 29.7 -> 32.5, the exit's 1 - F and the first internal reflection being
 *    what the two-interface model leaves out);
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

static uint8_t *frame_with(snell_ctx *ctx, snell_frame_desc *fd, snell_glass *g, snell_method method,
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
    g->material.cubemap.inner_fresnel = inner;
    g->material.cubemap.fresnel = model;
    g->material.peel.inner_fresnel = inner;
    g->material.peel.fresnel = model;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (r) {
        CHECK_OK_CTX(ctx, snell_render(r, fd, NULL));
        CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, px));
    }
    snell_renderer_destroy(r);
    return px;
}

static uint8_t *frame(snell_ctx *ctx, snell_frame_desc *fd, snell_glass *g, snell_inner_fresnel inner,
                      snell_fresnel_model model)
{
    return frame_with(ctx, fd, g, SNELL_METHOD_CUBEMAP, inner, model);
}

/* Channels of glass and background alike more than 1 off the grey 128. */
static long off_grey(const uint8_t *px)
{
    long i, off = 0;
    for (i = 0; i < (long)W * H * 4; i++) off += i % 4 != 3 && abs(px[i] - 128) > 1;
    return off;
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
            uint8_t *px = frame_with(ctx, &fd, &g, SNELL_METHOD_PEEL, SNELL_INNER_FRESNEL_ON, (snell_fresnel_model)m);
            long off = off_grey(px);
            CHECK(off == 0, "peel, grey environment, inner Fresnel, mesh %d, model %d: %ld channels off 128 by more "
                            "than 1", k, m, off);
            free(px);
        }
    }
    for (k = 0; k < 3; k++) {
        uint8_t *off, *on, *aut;
        test_frame_one(&fd, &g, meshes[k], env);
        full_reference(ctx, &fd, &g, env, rgb, hit, refpx);
        off = frame_with(ctx, &fd, &g, SNELL_METHOD_PEEL, SNELL_INNER_FRESNEL_OFF, SNELL_FRESNEL_EXACT);
        on = frame_with(ctx, &fd, &g, SNELL_METHOD_PEEL, SNELL_INNER_FRESNEL_ON, SNELL_FRESNEL_EXACT);
        aut = frame_with(ctx, &fd, &g, SNELL_METHOD_PEEL, SNELL_INNER_FRESNEL_AUTO, SNELL_FRESNEL_EXACT);
        CHECK_OK(snell_metrics_image_error(off, refpx, W, H, hit, &e_off));
        CHECK_OK(snell_metrics_image_error(on, refpx, W, H, hit, &e_on));
        printf("peel, mesh %d, %dx%d vs FULL over %ld glass pixels: inner Fresnel off %.2f dB, on %.2f dB\n", k, W,
               H, e_on.pixels, e_off.psnr_db, e_on.psnr_db);
        CHECK(e_on.psnr_db >= e_off.psnr_db + min_gain[k], "peel, mesh %d, inner Fresnel: %.2f dB, not %.1f dB above "
              "%.2f dB", k, e_on.psnr_db, min_gain[k], e_off.psnr_db);
        CHECK(!memcmp(aut, on, (size_t)W * H * 4), "peel, mesh %d: AUTO is on (convex or not)", k);
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
    snell_image_error e_off, e_on;
    int m;
    if (!ctx) SKIP("no GL context");
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_SPHERE, 96, 48}, &sphere));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_TORUS, 64, 32}, &torus));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_GOBLET, 64, 32}, &goblet));
    memset(&ed, 0, sizeof ed);
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &env));
    grey = grey_env(ctx);
    if (!sphere || !torus || !goblet || !env || !grey) return test_finish();

    test_frame_one(&fd, &g, sphere, grey);
    for (m = SNELL_FRESNEL_SCHLICK; m <= SNELL_FRESNEL_EXACT; m++) {
        uint8_t *px = frame(ctx, &fd, &g, SNELL_INNER_FRESNEL_ON, (snell_fresnel_model)m);
        long off = off_grey(px);
        CHECK(off == 0, "grey environment, inner Fresnel, model %d: %ld channels off 128 by more than 1", m, off);
        free(px);
    }

    test_frame_one(&fd, &g, sphere, env);
    full_reference(ctx, &fd, &g, env, rgb, hit, refpx);
    {
        uint8_t *off = frame(ctx, &fd, &g, SNELL_INNER_FRESNEL_OFF, SNELL_FRESNEL_EXACT);
        uint8_t *on = frame(ctx, &fd, &g, SNELL_INNER_FRESNEL_ON, SNELL_FRESNEL_EXACT);
        uint8_t *aut = frame(ctx, &fd, &g, SNELL_INNER_FRESNEL_AUTO, SNELL_FRESNEL_EXACT);
        CHECK_OK(snell_metrics_image_error(off, refpx, W, H, hit, &e_off));
        CHECK_OK(snell_metrics_image_error(on, refpx, W, H, hit, &e_on));
        printf("sphere %dx%d vs FULL over %ld glass pixels: inner Fresnel off %.2f dB, on %.2f dB\n", W, H,
               e_on.pixels, e_off.psnr_db, e_on.psnr_db);
        CHECK(e_on.psnr_db >= e_off.psnr_db + 2.0, "inner Fresnel: %.2f dB, not 2 dB above %.2f dB", e_on.psnr_db,
              e_off.psnr_db);
        CHECK(!memcmp(aut, on, (size_t)W * H * 4), "AUTO is on for the convex sphere");
        free(off);
        free(on);
        free(aut);
    }
    test_frame_one(&fd, &g, torus, env);
    {
        uint8_t *off = frame(ctx, &fd, &g, SNELL_INNER_FRESNEL_OFF, SNELL_FRESNEL_SCHLICK);
        uint8_t *aut = frame(ctx, &fd, &g, SNELL_INNER_FRESNEL_AUTO, SNELL_FRESNEL_SCHLICK);
        uint8_t *on = frame(ctx, &fd, &g, SNELL_INNER_FRESNEL_ON, SNELL_FRESNEL_SCHLICK);
        CHECK(!memcmp(aut, off, (size_t)W * H * 4), "AUTO is off for the torus (not convex)");
        CHECK(memcmp(on, off, (size_t)W * H * 4) != 0, "ON changes the torus");
        free(off);
        free(aut);
        free(on);
    }
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
