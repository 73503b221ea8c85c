/* SPDX-License-Identifier: MIT */
/* test_cubemap_env — opaque objects and the dynamic environment (Unger 4.1):
 *  - the cubemap is rendered in the first frame, skipped while nothing moves
 *    (also when only kernel parameters change), re-rendered when an object
 *    moves, changes colour, or the glass moves;
 *  - a red cube placed behind a glass sphere is seen through it (refracted
 *    into the glass pixels), and not without the dynamic environment;
 *  - frames after the first allocate nothing (checked in test_alloc for the
 *    kernel; here the skip path is exercised);
 *  - bad opaque lists give SNELL_E_INVALID_ARG with a message. */
#include "test_util.h"

#include <math.h>
#include <string.h>

#define W 128
#define H 128

static int red_pixels(const uint8_t *px)
{
    int i, n = 0;
    for (i = 0; i < W * H; i++) n += px[4 * i] > 150 && px[4 * i + 1] < 90 && px[4 * i + 2] < 90;
    return n;
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_mesh *sphere = NULL, *cube = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_shape_desc sd;
    snell_frame_desc fd;
    snell_frame_stats fs;
    snell_glass g;
    snell_opaque ob[2];
    float m0[16], m1[16];
    static uint8_t px[W * H * 4], px_no[W * H * 4];
    int red_with, red_without, f;
    if (!ctx) SKIP("no GL context");
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &sphere));
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &cube));
    env = test_sky(ctx, 128);
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!sphere || !cube || !env || !r) return test_finish();

    /* Camera on +Z looking at the sphere; a red cube (scale 0.6) behind it
     * at z = -3, and a green one off to the side. */
    memset(m0, 0, sizeof m0);
    m0[0] = m0[5] = m0[10] = 0.6f;
    m0[14] = -3.0f;
    m0[15] = 1.0f;
    memcpy(m1, m0, sizeof m1);
    m1[12] = 3.0f;
    m1[14] = 0.0f;
    memset(ob, 0, sizeof ob);
    ob[0].mesh = cube;
    ob[0].model = m0;
    ob[0].color[0] = 1.0f;
    ob[1].mesh = cube;
    ob[1].model = m1;
    ob[1].color[1] = 1.0f;
    test_frame_one(&fd, &g, sphere, env);
    g.material.method = SNELL_METHOD_CUBEMAP;
    g.material.cubemap.max_interfaces = 2;
    fd.camera.distance = 3.0f;
    fd.camera.fov_y = 0.6f; /* the sphere fills the view: the cube is only seen through it */

    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK_OK(snell_renderer_read_rgba(r, px_no));
    red_without = red_pixels(px_no);
    CHECK(fs.glass[0].env_updated == 0 && !(fs.glass[0].skipped & SNELL_SKIP_ENV_UPDATE) && fs.opaque_drawn == 0,
          "no opaque objects: no dynamic environment");

    fd.opaque = ob;
    fd.opaque_count = 2;
    /* this test is the dynamic environment's: the scene layers (the default
     * with opaque objects, test_scene_layers) off */
    fd.scene_layers = -1;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(fs.glass[0].env_updated == 1 && !(fs.glass[0].skipped & SNELL_SKIP_ENV_UPDATE) && fs.opaque_drawn == 2,
          "first frame with objects renders the environment");
    CHECK_OK(snell_renderer_read_rgba(r, px));
    red_with = red_pixels(px);
    printf("red pixels through the sphere: %d with the dynamic environment, %d without\n", red_with, red_without);
    /* (the procedural sky has a few red texels of its own) */
    CHECK(red_with > 10 * (red_without + 10), "the red cube behind the glass must be seen through it");
    snell_write_png(test_out("cubemap_env.png"), W, H, px);

    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(fs.glass[0].env_updated == 0 && (fs.glass[0].skipped & SNELL_SKIP_ENV_UPDATE), "nothing moved: skipped");
    g.material.cubemap.iterations = 12;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(fs.glass[0].env_updated == 0 && (fs.glass[0].skipped & SNELL_SKIP_ENV_UPDATE),
          "kernel parameters do not touch the environment");

    /* Moving objects: every frame that moves one re-renders. */
    for (f = 0; f < 3; f++) {
        m1[13] = 0.2f * (f + 1);
        CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
        CHECK(fs.glass[0].env_updated == 1, "frame %d: a moved object re-renders", f);
        snell_renderer_read_rgba(r, px);
    }
    ob[1].color[2] = 0.5f;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(fs.glass[0].env_updated == 1, "a colour change re-renders");
    {
        float gm[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.1f, 0, 0, 1};
        g.model = gm;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
        CHECK(fs.glass[0].env_updated == 1, "a moved glass re-renders (new centre)");
        CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
        CHECK(fs.glass[0].env_updated == 0 && (fs.glass[0].skipped & SNELL_SKIP_ENV_UPDATE), "then skips again");
        g.model = NULL;
    }

    /* Bad input. */
    fd.opaque_count = SNELL_MAX_OPAQUE + 1;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "too many opaque objects");
    fd.opaque_count = 1;
    fd.opaque = NULL;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "NULL opaque list");
    fd.opaque = ob;
    ob[0].mesh = NULL;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "object without mesh");
    CHECK(strstr(snell_last_error(ctx), "no mesh") != NULL, "message: %s", snell_last_error(ctx));
    ob[0].mesh = cube;
    fd.dynamic_env_size = 8;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "dynamic_env_size 8");
    fd.dynamic_env_size = 0;
    ob[0].color[1] = NAN;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "NaN colour");
    ob[0].color[1] = 0.0f;
    g.material.cubemap.iterations = 33;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "iterations 33");
    g.material.cubemap.iterations = 0;
    g.material.cubemap.max_interfaces = 9;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "interfaces 9");
    g.material.cubemap.max_interfaces = 0;
    g.material.cubemap.face_size = 15;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "face 15");
    g.material.cubemap.face_size = 0;
    g.material.cubemap.encoding = (snell_ndcube_encoding)7;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "encoding 7");
    g.material.cubemap.encoding = SNELL_NDCUBE_DEFAULT;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));

    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(cube);
    snell_mesh_destroy(sphere);
    snell_ctx_destroy(ctx);
    return test_finish();
}
