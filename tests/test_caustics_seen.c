/* SPDX-License-Identifier: MIT */
/* test_caustics_seen — the glass sees the lit receiver plane (issue 27;
 * common/receiver.glsl, the caustics stage's kernel hook SNELL_RECEIVER):
 * along their exit and reflected rays every method's kernel meets the plane
 * before the environment, lit by the same light map as the view draws it.
 * Derived without a reference: a sphere of IOR 1.001 bends no ray by more
 * than its 8-bit normals times 0.001 and reflects under 1% (Schlick, F0 =
 * 2.5e-7) within 80% of its radius, so there its pixels must show what the
 * same pixels show without it. The light (along
 * (1, -0.15, 0)) puts the sphere's shadow and caustic from x = 6.6 on, off
 * the plane's square (|x| <= 2.5, y = -2), so the plane's light map is the
 * same with and without it. The
 * plane fills most of the sphere's pixels (checked: without the plane they
 * show the environment), and those are compared (where the sphere shows
 * the environment, its cube map look-ups and the background's differ at
 * the checkers' edges, which is not this test's); without the hook they
 * show the environment too, and fail
 * (checked by leaving the hook's variant bit unset: every method then
 * differs on all 2516 pixels compared). For every method in the registry,
 * forward and screen-space shading (SHADINGS).
 * Then the same for an opaque object seen through the glass (the scene
 * layers, on by default with opaque objects; common/opaque_lit.glsl): a cube
 * behind the sphere, lit by a light whose sphere shadow and caustic fall
 * beside it, no plane. Inside 80% of the sphere's radius, where the view
 * ray meets the cube (1 pixel in from its outline), the pixels must be the
 * frame's without the sphere, lit by the light as the view draws the cube;
 * with the cube shaded as opaque.frag shades it without a light (the hook
 * off) they differ. */
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 160
#define H 120

static void render(snell_ctx *ctx, const snell_frame_desc *fd, snell_method m, uint8_t *rgba, float *dirs)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc f = *fd;
    snell_glass g;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = dirs ? SNELL_OUTPUT_EXIT_DIRECTION : SNELL_OUTPUT_COLOR;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r) return;
    if (f.glass_count) {
        g = f.glass[0];
        g.material.method = m;
        f.glass = &g;
    }
    CHECK_OK_CTX(ctx, snell_render(r, &f, NULL));
    if (dirs) CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
    else CHECK_OK(snell_renderer_read_rgba(r, rgba));
    snell_renderer_destroy(r);
}

/* Whether the view ray (a background pixel's exit direction) meets the
 * plane's square 0.1 inside its edges. */
static int on_plane(const snell_frame_desc *fd, const float *d)
{
    float eye[3], view[16], proj[16];
    double t, x, z;
    snell_camera_matrices(&fd->camera, (float)W / H, eye, view, proj);
    if (!(d[1] < 0.0f)) return 0;
    t = (fd->receiver.height - eye[1]) / d[1];
    x = eye[0] + t * d[0] - fd->receiver.center[0], z = eye[2] + t * d[2] - fd->receiver.center[1];
    return fabs(x) < fd->receiver.extent - 0.1 && fabs(z) < fd->receiver.extent - 0.1;
}

/* Whether pixel k of mask lies at least e pixels inside it (its disc of
 * radius e all in the mask). */
static int inside(const uint8_t *mask, int k, int e)
{
    int x = k % W, y = k / W, i, j;
    for (j = -e; j <= e; j++)
        for (i = -e; i <= e; i++)
            if (i * i + j * j <= e * e &&
                (x + i < 0 || y + j < 0 || x + i >= W || y + j >= H || !mask[(y + j) * W + x + i]))
                return 0;
    return 1;
}

static int differs(const uint8_t *a, const uint8_t *b, int tol)
{
    int c;
    for (c = 0; c < 3; c++)
        if (abs(a[c] - b[c]) > tol) return 1;
    return 0;
}

/* The frames both parts compare: fd with the sphere at IOR 1.001 (with) and
 * without it (without), and the sphere's pixels (mask: where its exit
 * directions at IOR 1.5 differ from the empty frame's, none). Returns their count. */
static int sphere_frames(snell_ctx *ctx, const snell_frame_desc *fd, snell_glass *g, snell_method m, uint8_t *with,
                         uint8_t *without, uint8_t *mask, float *none)
{
    static float dirs[W * H * 3];
    snell_frame_desc bare = *fd;
    int k, glass = 0;
    bare.glass_count = 0;
    g->material.ior = 1.5f;
    render(ctx, fd, m, NULL, dirs);
    render(ctx, &bare, m, NULL, none);
    g->material.ior = 1.001f;
    render(ctx, fd, m, with, NULL);
    render(ctx, &bare, m, without, NULL);
    for (k = 0; k < W * H; k++) glass += mask[k] = memcmp(dirs + 3 * k, none + 3 * k, 3 * sizeof(float)) != 0;
    return glass;
}

/* The lit cube behind the IOR 1.001 sphere (above); the sphere mask from
 * its exit directions at IOR 1.5 as for the plane. */
static void opaque_seen(snell_ctx *ctx, snell_env *env, snell_mesh *sphere, snell_mesh *cube)
{
    static uint8_t with[W * H * 4], without[W * H * 4], empty[W * H * 4], dark[W * H * 4], mask[W * H], cube_px[W * H];
    static float none[W * H * 3];
    static const float place[16] = {1.2f, 0, 0, 0, 0, 1.2f, 0, 0, 0, 0, 1.2f, 0, 0, 0, -3.0f, 1};
    snell_frame_desc fd, bare;
    snell_glass g;
    snell_opaque op;
    int i, k;
    test_frame_one(&fd, &g, sphere, env);
    memset(&op, 0, sizeof op);
    op.mesh = cube, op.model = place, op.color[0] = 0.9f, op.color[1] = 0.6f, op.color[2] = 0.3f;
    fd.opaque = &op, fd.opaque_count = 1;
    fd.camera.azimuth = 0.0f, fd.camera.elevation = 0.15f, fd.camera.distance = 5.0f;
    /* along (-0.9, -0.2, -0.4): onto the cube's face towards the camera (z =
     * -1.8) at cosine 0.4; the sphere's shadow reaches that plane at x = -4.05
     * (its radius 1), beside the cube (|x| <= 1.2) */
    fd.light.type = SNELL_LIGHT_DIRECTIONAL;
    fd.light.direction[0] = -0.9f, fd.light.direction[1] = -0.2f, fd.light.direction[2] = -0.4f;
    fd.light.color[0] = fd.light.color[1] = fd.light.color[2] = 2.5f;
    for (i = 0; i < snell_method_count(); i++) {
        const snell_method_info *mi = snell_method_info_at(i);
        int glass, inner, seen = 0, off = 0, unlit = 0;
        glass = sphere_frames(ctx, &fd, &g, mi->method, with, without, mask, none);
        inner = (int)ceil(0.2 * sqrt(glass / 3.14159));
        bare = fd;
        bare.glass_count = bare.opaque_count = 0;
        render(ctx, &bare, mi->method, empty, NULL);
        /* what the sphere showed before: the cube shaded without the light */
        bare = fd;
        bare.light.type = SNELL_LIGHT_NONE;
        render(ctx, &bare, mi->method, dark, NULL);
        for (k = 0; k < W * H; k++) cube_px[k] = differs(without + 4 * k, empty + 4 * k, 0);
        for (k = 0; k < W * H; k++) {
            if (!mask[k] || !inside(mask, k, inner) || !inside(cube_px, k, 1)) continue;
            seen++;
            off += differs(with + 4 * k, without + 4 * k, 3);
            unlit += differs(dark + 4 * k, without + 4 * k, 8);
        }
        if (mi->method == SNELL_METHOD_PEEL) {
            snell_write_png(test_out("caustics_seen_opaque_with.png"), W, H, with);
            snell_write_png(test_out("caustics_seen_opaque_without.png"), W, H, without);
        }
        printf("%s, opaque: of %d sphere pixels %d show the cube (%d of them unlike the unlit cube), %d of them differ "
               "from the frame without the sphere\n", mi->name, glass, seen, unlit, off);
        CHECK(seen > 300 && unlit * 10 > seen * 8, "%s: %d pixels show the cube, %d unlike the unlit one", mi->name,
              seen, unlit);
        CHECK(off * 50 <= seen, "%s: %d of %d pixels on the cube differ", mi->name, off, seen);
    }
}

int main(void)
{
    static float none[W * H * 3];
    static uint8_t with[W * H * 4], without[W * H * 4], env_only[W * H * 4], mask[W * H];
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL;
    snell_shape_desc sd;
    snell_mesh *mesh = NULL;
    snell_frame_desc fd, bare;
    snell_glass g;
    int i, k;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 128);
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    if (!env || !mesh) return test_finish();
    test_frame_one(&fd, &g, mesh, env);
    fd.camera.azimuth = 0.4f;
    fd.camera.elevation = 1.0f;
    fd.camera.distance = 4.0f;
    fd.light.type = SNELL_LIGHT_DIRECTIONAL;
    fd.light.direction[0] = 1.0f, fd.light.direction[1] = -0.15f;
    fd.light.color[0] = fd.light.color[1] = fd.light.color[2] = 5.0f;
    fd.receiver.height = -2.0f;
    fd.receiver.extent = 2.5f;
    fd.receiver.albedo[0] = 0.9f, fd.receiver.albedo[1] = 0.7f, fd.receiver.albedo[2] = 0.5f;
    fd.receiver.map_size = 128;
    for (i = 0; i < snell_method_count(); i++) {
        const snell_method_info *mi = snell_method_info_at(i);
        int glass, off = 0, plane = 0, distinct = 0;
        glass = sphere_frames(ctx, &fd, &g, mi->method, with, without, mask, none);
        bare = fd;
        bare.light.type = SNELL_LIGHT_NONE;
        memset(&bare.receiver, 0, sizeof bare.receiver);
        render(ctx, &bare, mi->method, env_only, NULL);
        for (k = 0; k < W * H; k++) {
            /* the inner 80% of its radius: nearer the rim even Fresnel at IOR 1.001 reflects percents */
            if (!mask[k] || !inside(mask, k, (int)ceil(0.2 * sqrt(glass / 3.14159)))) continue;
            if (!on_plane(&fd, none + 3 * k)) continue; /* the environment there */
            plane++;
            off += differs(with + 4 * k, without + 4 * k, 3);
            distinct += differs(env_only + 4 * k, without + 4 * k, 8); /* what the sphere shows without the hook */
        }
        printf("%s: of %d sphere pixels %d show the plane (%d of them unlike the environment), %d of them differ from "
               "the frame without the sphere\n", mi->name, glass, plane, distinct, off);
        CHECK(glass > W * H / 10 && plane * 3 > glass && distinct * 10 > plane * 8,
              "%s: %d sphere pixels, %d on the plane, %d unlike the environment", mi->name, glass, plane, distinct);
        CHECK(off * 50 <= plane, "%s: %d of %d pixels on the plane differ", mi->name, off, plane);
    }
    {
        snell_mesh *cube = NULL;
        sd.shape = SNELL_SHAPE_CUBE;
        CHECK_OK(snell_mesh_create_shape(ctx, &sd, &cube));
        if (cube) opaque_seen(ctx, env, mesh, cube);
        snell_mesh_destroy(cube);
    }
    snell_mesh_destroy(mesh);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
