/* SPDX-License-Identifier: MIT */
/* test_peel_layer0 — peel's first layer converted from the screen-space
 * G-buffer (methods/peel.c, shaders_es/peel_layer0.frag; material.peel.layer0,
 * counter layer0_gbuffer) against the same layer peeled (layer0 = peel).
 * Shading forced to screen space (the route exists only there).
 *
 * 1. The layer itself: after a frame the layer array is left bound on the
 *    kernel's unit (1); layer 0's two slices are read back for each route.
 *    The same texels must be non-empty (the G-buffer's front surface is the
 *    culled peel's: same triangles, same rasteriser, depth LESS), the normal
 *    bytes equal (the G-buffer's texel copied; both are
 *    snell_pack_dir_rgba8 of the same normal), and the depth within a few
 *    quanta of the 24-bit range: the G-buffer's depth is the 24-bit window
 *    depth, which at the torus's distance (3.5, near plane about 0.1) is
 *    coarser than the layer's 2r / 2^24, and its reconstruction through the
 *    inverse view-projection loses some more bits in float. Measured: mean
 *    97, worst 664 quanta; required: every texel within 1024 quanta (6e-5
 *    of the range; the search's binary steps resolve 1/16/2^6 = 1e-3) and
 *    the mean below 150.
 * 2. The image: exit directions and colour of the torus and the goblet, the
 *    G-buffer route against the peeled one. Required: 99.5% of the glass
 *    pixels' exit directions within 1e-3 rad and the colour image's PSNR
 *    above 40 dB. (A layer 0 left empty instead: most pixels change.)
 * 3. The rule (render/stages.c, snell__object.front_whole): the route is
 *    taken alone on screen; not with layer0 = peel, shaded forward, with
 *    the eye within the bounding sphere (every face peeled), at a resolution
 *    scale, on large triangles (a torus of 256: the conversion costs more
 *    there than peeling the mesh; methods/peel.c), in a frame with an
 *    opaque object, nor for two glass objects whose rectangles overlap (the
 *    G-buffer holds only the nearer one's surface there); it is for two
 *    apart. With an opaque cube in front of the torus the image is bitwise
 *    the peeled one's (where the cube covers the torus the G-buffer holds
 *    none of it, a peel does). */
#include "test_util.h"

#include <GLES3/gl3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 160
#define H 160

static snell_mesh *shape(snell_ctx *ctx, snell_shape s)
{
    snell_shape_desc sd;
    snell_mesh *mesh = NULL;
    memset(&sd, 0, sizeof sd);
    sd.shape = s;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    if (mesh && s != SNELL_SHAPE_SPHERE) CHECK_OK(snell_mesh_normalize(mesh, 1.0f));
    return mesh;
}

/* Two frames of fd (the second's peels follow the first's queries) with
 * glass 0's layer0 set to l0 on a new renderer of this shading; its colour or
 * exit directions (whichever is given), layer 0's slices (if slices: W*H*4
 * bytes of normals, then as many of depths) and glass i's layer0_gbuffer
 * counter in route[i]. */
static void render(snell_ctx *ctx, snell_frame_desc *fd, snell_glass *g, snell_peel_layer0 l0, snell_shading shading,
                   uint8_t *rgba, float *dirs, uint8_t *slices, int route[2])
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_stats st;
    int i;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = rgba ? SNELL_OUTPUT_COLOR : SNELL_OUTPUT_EXIT_DIRECTION;
    rd.shading = shading;
    route[0] = route[1] = -1;
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r) return;
    g->material.peel.layer0 = l0;
    CHECK_OK_CTX(ctx, snell_render(r, fd, &st));
    CHECK_OK_CTX(ctx, snell_render(r, fd, &st));
    for (i = 0; i < fd->glass_count && i < 2; i++) route[i] = snell_object_counter(&st.glass[i], "layer0_gbuffer");
    if (slices) {
        GLint tex = 0;
        GLuint fbo = 0;
        glActiveTexture(GL_TEXTURE1);
        glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &tex);
        glActiveTexture(GL_TEXTURE0);
        CHECK(tex != 0, "no texture array on unit 1 after the frame");
        glGenFramebuffers(1, &fbo);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        for (i = 0; i < 2 && tex; i++) {
            glFramebufferTextureLayer(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, (GLuint)tex, 0, i);
            glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, slices + (size_t)i * W * H * 4);
        }
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        glDeleteFramebuffers(1, &fbo);
        CHECK(glGetError() == GL_NO_ERROR, "GL error reading the layers back");
    }
    if (rgba) CHECK_OK(snell_renderer_read_rgba(r, rgba));
    if (dirs) CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
    snell_renderer_destroy(r);
}

static void test_layer(snell_ctx *ctx, snell_env *env)
{
    static uint8_t a[2 * W * H * 4], b[2 * W * H * 4];
    snell_mesh *mesh = shape(ctx, SNELL_SHAPE_TORUS);
    snell_frame_desc fd;
    snell_glass g;
    int i, route[2], full = 0, occupancy = 0, normals = 0;
    long worst = 0;
    double sum = 0.0;
    if (!mesh) return;
    test_frame_one(&fd, &g, mesh, env);
    g.material.method = SNELL_METHOD_PEEL;
    fd.camera.elevation = 0.5f;
    render(ctx, &fd, &g, SNELL_PEEL_LAYER0_GBUFFER, SNELL_SHADING_SCREEN, NULL, NULL, a, route);
    CHECK(route[0] == 1, "layer0_gbuffer %d alone on screen (want 1)", route[0]);
    render(ctx, &fd, &g, SNELL_PEEL_LAYER0_PEEL, SNELL_SHADING_SCREEN, NULL, NULL, b, route);
    CHECK(route[0] == 0, "layer0_gbuffer %d with layer0 = peel", route[0]);
    for (i = 0; i < W * H; i++) {
        const uint8_t *da = a + 4 * (W * H + i), *db = b + 4 * (W * H + i);
        long qa = (long)da[0] << 16 | da[1] << 8 | da[2], qb = (long)db[0] << 16 | db[1] << 8 | db[2];
        if ((da[3] != 0) != (db[3] != 0)) {
            occupancy++;
            continue;
        }
        if (!db[3]) continue;
        full++;
        normals += memcmp(a + 4 * i, b + 4 * i, 4) != 0;
        sum += labs(qa - qb);
        if (labs(qa - qb) > worst) worst = labs(qa - qb);
    }
    printf("layer 0: %d texels, %d occupied in one route only, %d normals differ; depth |G-buffer - peel| mean %.1f, "
           "worst %ld quanta of 2^24\n", full, occupancy, normals, sum / (full ? full : 1), worst);
    CHECK(full > W * H / 10, "the torus's layer 0 holds %d texels", full);
    CHECK(occupancy == 0, "%d texels are empty in one route and not in the other", occupancy);
    CHECK(normals == 0, "%d normal texels differ", normals);
    CHECK(worst <= 1024 && sum < 150.0 * full, "depth off by %ld quanta at worst, %.1f on average", worst,
          sum / (full ? full : 1));
    snell_mesh_destroy(mesh);
}

static double psnr(const uint8_t *a, const uint8_t *b)
{
    double se = 0.0;
    int i;
    for (i = 0; i < W * H * 4; i++)
        if (i % 4 != 3) se += (double)(a[i] - b[i]) * (a[i] - b[i]);
    return se > 0.0 ? 10.0 * log10(255.0 * 255.0 * 3 * W * H / se) : INFINITY;
}

static void test_image(snell_ctx *ctx, snell_env *env, snell_shape s, const char *name)
{
    static float da[W * H * 3], db[W * H * 3], none[W * H * 3];
    static uint8_t ca[W * H * 4], cb[W * H * 4];
    snell_mesh *mesh = shape(ctx, s);
    snell_frame_desc fd;
    snell_glass g;
    int i, route[2], glass = 0, close = 0;
    double p;
    if (!mesh) return;
    test_frame_one(&fd, &g, mesh, env);
    g.material.method = SNELL_METHOD_PEEL;
    fd.camera.elevation = 0.3f;
    render(ctx, &fd, &g, SNELL_PEEL_LAYER0_GBUFFER, SNELL_SHADING_SCREEN, NULL, da, NULL, route);
    CHECK(route[0] == 1, "%s: layer0_gbuffer %d", name, route[0]);
    render(ctx, &fd, &g, SNELL_PEEL_LAYER0_PEEL, SNELL_SHADING_SCREEN, NULL, db, NULL, route);
    fd.glass_count = 0; /* the background's directions: where the object is not */
    render(ctx, &fd, &g, SNELL_PEEL_LAYER0_PEEL, SNELL_SHADING_SCREEN, NULL, none, NULL, route);
    fd.glass_count = 1;
    for (i = 0; i < W * H; i++) {
        if (!memcmp(db + 3 * i, none + 3 * i, 3 * sizeof(float))) continue;
        glass++;
        close += test_dir_angle(da + 3 * i, db + 3 * i) < 1e-3;
    }
    render(ctx, &fd, &g, SNELL_PEEL_LAYER0_GBUFFER, SNELL_SHADING_SCREEN, ca, NULL, NULL, route);
    render(ctx, &fd, &g, SNELL_PEEL_LAYER0_PEEL, SNELL_SHADING_SCREEN, cb, NULL, NULL, route);
    p = psnr(ca, cb);
    printf("%s: layer 0 from the G-buffer against peeled: %d of %d glass px within 1e-3 rad; colour PSNR %.2f dB\n",
           name, close, glass, p);
    CHECK(glass > W * H / 10, "%s covers %d px", name, glass);
    CHECK(close >= 0.995 * glass, "%s: %d of %d px within 1e-3 rad", name, close, glass);
    CHECK(p > 40.0, "%s: PSNR %.2f dB", name, p);
    snell_mesh_destroy(mesh);
}

static void test_rule(snell_ctx *ctx, snell_env *env)
{
    static uint8_t ca[W * H * 4], cb[W * H * 4];
    snell_mesh *torus = shape(ctx, SNELL_SHAPE_TORUS), *goblet = shape(ctx, SNELL_SHAPE_GOBLET);
    snell_mesh *cube = shape(ctx, SNELL_SHAPE_CUBE);
    float over[16] = {0.45f, 0, 0, 0, 0, 0.45f, 0, 0, 0, 0, 0.45f, 0, 0.3f, 0, 0, 1};
    float left[16] = {0.45f, 0, 0, 0, 0, 0.45f, 0, 0, 0, 0, 0.45f, 0, -1.0f, 0, 0, 1};
    float right[16] = {0.45f, 0, 0, 0, 0, 0.45f, 0, 0, 0, 0, 0.45f, 0, 1.0f, 0, 0, 1};
    float box[16] = {0.3f, 0, 0, 0, 0, 0.3f, 0, 0, 0, 0, 0.3f, 0, 0.4f, 0.2f, 1.5f, 1};
    snell_frame_desc fd;
    snell_glass g[2];
    snell_opaque op;
    int route[2];
    if (!torus || !goblet || !cube) goto out;
    memset(g, 0, sizeof g);
    test_frame_one(&fd, &g[0], torus, env);
    g[0].material.method = SNELL_METHOD_PEEL;
    fd.camera.azimuth = 0.0f;
    fd.camera.elevation = 0.3f;
    render(ctx, &fd, &g[0], SNELL_PEEL_LAYER0_GBUFFER, SNELL_SHADING_FORWARD, NULL, NULL, NULL, route);
    CHECK(route[0] == 0, "layer0_gbuffer %d shaded forward", route[0]);
    fd.camera.distance = 0.9f; /* above the hole, within the bounding sphere: every face peeled */
    fd.camera.elevation = 1.5f;
    render(ctx, &fd, &g[0], SNELL_PEEL_LAYER0_GBUFFER, SNELL_SHADING_SCREEN, NULL, NULL, NULL, route);
    CHECK(route[0] == 0, "layer0_gbuffer %d from within the bounding sphere", route[0]);
    fd.camera.distance = 0.0f;
    fd.camera.elevation = 0.3f;
    g[0].material.scale = 2.0f; /* colour output: the scale is a colour target's */
    render(ctx, &fd, &g[0], SNELL_PEEL_LAYER0_GBUFFER, SNELL_SHADING_SCREEN, ca, NULL, NULL, route);
    CHECK(route[0] == 0, "layer0_gbuffer %d at a resolution scale", route[0]);
    g[0].material.scale = 0.0f;
    {
        /* large triangles: peeling the mesh costs less than the conversion */
        snell_shape_desc sd;
        snell_mesh *coarse = NULL;
        memset(&sd, 0, sizeof sd);
        sd.shape = SNELL_SHAPE_TORUS;
        sd.segments = 16;
        sd.rings = 8;
        CHECK_OK(snell_mesh_create_shape(ctx, &sd, &coarse));
        if (coarse) CHECK_OK(snell_mesh_normalize(coarse, 1.0f));
        g[0].mesh = coarse;
        render(ctx, &fd, &g[0], SNELL_PEEL_LAYER0_GBUFFER, SNELL_SHADING_SCREEN, NULL, NULL, NULL, route);
        CHECK(route[0] == 0, "layer0_gbuffer %d on large triangles (256 of them)", route[0]);
        g[0].mesh = torus;
        snell_mesh_destroy(coarse);
    }

    /* an opaque cube in front of part of the torus */
    memset(&op, 0, sizeof op);
    op.mesh = cube;
    op.model = box;
    fd.opaque = &op;
    fd.opaque_count = 1;
    render(ctx, &fd, &g[0], SNELL_PEEL_LAYER0_GBUFFER, SNELL_SHADING_SCREEN, ca, NULL, NULL, route);
    CHECK(route[0] == 0, "layer0_gbuffer %d with an opaque object", route[0]);
    render(ctx, &fd, &g[0], SNELL_PEEL_LAYER0_PEEL, SNELL_SHADING_SCREEN, cb, NULL, NULL, route);
    CHECK(!memcmp(ca, cb, sizeof ca), "with an opaque cube in front, the image differs from the peeled layer 0's");
    fd.opaque_count = 0;

    /* two glass objects: the goblet within the torus's rectangle, then the two apart */
    g[1].mesh = goblet;
    g[1].model = over;
    g[1].material.method = SNELL_METHOD_PEEL;
    g[1].material.peel.layer0 = SNELL_PEEL_LAYER0_GBUFFER;
    fd.glass = g;
    fd.glass_count = 2;
    fd.scene_layers = -1;
    render(ctx, &fd, &g[0], SNELL_PEEL_LAYER0_GBUFFER, SNELL_SHADING_SCREEN, NULL, NULL, NULL, route);
    CHECK(route[0] == 0 && route[1] == 0, "overlapping rectangles: layer0_gbuffer %d %d", route[0], route[1]);
    g[0].model = left;
    g[1].model = right;
    render(ctx, &fd, &g[0], SNELL_PEEL_LAYER0_GBUFFER, SNELL_SHADING_SCREEN, NULL, NULL, NULL, route);
    CHECK(route[0] == 1 && route[1] == 1, "apart: layer0_gbuffer %d %d", route[0], route[1]);
out:
    snell_mesh_destroy(torus);
    snell_mesh_destroy(goblet);
    snell_mesh_destroy(cube);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 128);
    if (!env) return test_finish();
    test_layer(ctx, env);
    test_image(ctx, env, SNELL_SHAPE_TORUS, "torus");
    test_image(ctx, env, SNELL_SHAPE_GOBLET, "goblet");
    test_rule(ctx, env);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
