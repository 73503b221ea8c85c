/* SPDX-License-Identifier: MIT */
/* test_backdrop_sky — the host's sky behind the glass (issue 48, item 5).
 * The host's frame as textures: ground (green, depth 0.98) below, its sky
 * (magenta, at its far plane) above. Glass rays that meet nothing take the
 * host's colour where their direction vanishes over its sky: every method's
 * magenta pixels against the reference's with the same backdrop (SINGLE's
 * through one surface): textures under a standard and a reversed-Z camera
 * (depth 1 - d), and COPY_BOUND. `test_backdrop_sky PATH` also draws
 * docs/host_sky.png: the app's sky cube as the environment, its frame copied. */
#include "test_util.h"
#include "snell/snell_ref.h"

#include <GLES3/gl3.h>
#include <cglm/cglm.h>
#include <math.h>
#include <string.h>

#define N 64
#define GROUND 26 /* rows 0..GROUND-1 (from the bottom) are the host's ground */

static const uint8_t k_sky[3] = {230, 20, 230}, k_ground[3] = {40, 160, 60};

static void camera(snell_camera *c, int reversed)
{
    vec3 eye = {0.0f, 0.25f, 3.0f}, at = {0.0f, 0.1f, 0.0f}, up = {0.0f, 1.0f, 0.0f};
    mat4 view, proj;
    int k;
    glm_lookat(eye, at, up, view);
    glm_perspective(0.9f, 1.0f, 0.1f, 50.0f, proj);
    for (k = 0; reversed && k < 4; k++) proj[k][2] = -proj[k][2]; /* window depth 1 - d */
    memset(c, 0, sizeof *c);
    c->kind = SNELL_CAMERA_MATRICES;
    memcpy(c->view, view, sizeof c->view);
    memcpy(c->projection, proj, sizeof c->projection);
}

/* The host's frame at w x h into colour and depth textures (made first if
 * alloc): ground below, sky above. */
static void host_frame(GLuint fbo, GLuint color, GLuint depth, int w, int h, int reversed, int alloc)
{
    int k;
    glBindTexture(GL_TEXTURE_2D, color);
    if (alloc) glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, w, h);
    glBindTexture(GL_TEXTURE_2D, depth);
    if (alloc) glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT24, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth, 0);
    glEnable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    for (k = 0; k < 2; k++) {
        const uint8_t *c = k ? k_sky : k_ground;
        int y0 = k ? GROUND * h / N : 0, y1 = k ? h : GROUND * h / N;
        float d = k ? 1.0f : 0.98f;
        glScissor(0, y0, w, y1 - y0);
        glClearColor(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, 1.0f);
        glClearDepthf(reversed ? 1.0f - d : d);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    glDisable(GL_SCISSOR_TEST);
    glClearDepthf(1.0f);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static int magenta(const uint8_t *p) { return p[0] > p[1] + 80 && p[2] > p[1] + 80; }

/* The reference's glass pixels (hit) and its magenta ones, top row first,
 * through at most `interfaces` surfaces. */
static int reference(snell_ctx *ctx, snell_frame_desc *fd, int interfaces, uint8_t *hit, uint8_t *sky)
{
    static uint8_t rgba[N * N * 4], img[N * N * 4];
    static float depth[N * N], rgb[N * N * 3];
    snell_ref *ref = NULL;
    snell_ref_backdrop rb;
    snell_ref_params p;
    int i, n = 0;
    for (i = 0; i < N * N; i++) {
        int ground = i / N < GROUND;
        memcpy(rgba + 4 * i, ground ? k_ground : k_sky, 3), rgba[4 * i + 3] = 255;
        depth[i] = ground ? 0.98f : 1.0f;
    }
    memset(&rb, 0, sizeof rb);
    rb.rgba = rgba, rb.depth = depth, rb.width = N, rb.height = N, rb.camera = fd->camera;
    CHECK_OK_CTX(ctx, test_ref_create(ctx, fd, &ref));
    if (!ref) return 0;
    CHECK_OK_CTX(ctx, snell_ref_set_backdrop(ref, &rb));
    test_ref_params(fd, N, N, interfaces, &p);
    CHECK_OK_CTX(ctx, test_ref_render(ref, &p, rgb, NULL, hit));
    snell_ref_rgb_to_rgba8(rgb, N, N, img);
    for (i = 0; i < N * N; i++) n += (sky[i] = hit[i] && magenta(img + 4 * i));
    snell_ref_destroy(ref);
    return n;
}

/* The app's own sky cube: a blue zenith over a warm horizon, its ground below. */
static GLuint app_sky_cube(int size)
{
    static uint8_t px[64 * 64 * 4];
    GLuint tex;
    int f, x, y;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_CUBE_MAP, tex);
    glTexStorage2D(GL_TEXTURE_CUBE_MAP, 1, GL_RGBA8, size, size);
    for (f = 0; f < 6; f++) {
        for (y = 0; y < size; y++)
            for (x = 0; x < size; x++) {
                /* the face's direction (GL's cube map conventions): its y component */
                float s = 2.0f * (x + 0.5f) / size - 1.0f, t = 2.0f * (y + 0.5f) / size - 1.0f, d[3], up;
                uint8_t *q = px + 4 * (y * size + x);
                const float *m = (const float[6][3]){{1, -t, -s}, {-1, -t, s}, {s, 1, t},
                                                     {s, -1, -t}, {s, -t, 1}, {-s, -t, -1}}[f];
                memcpy(d, m, sizeof d);
                up = d[1] / sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                q[0] = (uint8_t)(up > 0 ? 250 - 200 * up : k_ground[0]);
                q[1] = (uint8_t)(up > 0 ? 170 - 40 * up : k_ground[1]);
                q[2] = (uint8_t)(up > 0 ? 90 + 160 * up : k_ground[2]);
                q[3] = 255;
            }
        glTexSubImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f, 0, 0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, px);
    }
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return tex;
}

/* docs/host_sky.png, the recipe of docs/integrating.md "Your sky": the app
 * draws its sky cube (here with snell, no glass) and its ground into its
 * framebuffer, hands the cube over as the environment and its frame as the
 * backdrop (COPY_BOUND), and snell draws the glass into that framebuffer. */
static void picture(snell_ctx *ctx, const snell_mesh *sphere, const char *path)
{
    enum { W = 192, H = 128 };
    static uint8_t px[W * H * 4], flip[W * H * 4];
    snell_renderer *r = NULL;
    snell_renderer_desc rd = {.width = W, .height = H, .target = SNELL_TARGET_BOUND_FRAMEBUFFER};
    snell_env *env = NULL;
    snell_env_desc ed;
    snell_backdrop bd = {.source = SNELL_BACKDROP_COPY_BOUND};
    snell_glass g;
    snell_frame_desc fd;
    GLuint fbo, tex[2], cube = app_sky_cube(64);
    mat4 view, proj;
    vec3 eye = {0.0f, 0.25f, 3.0f}, at = {0.0f, 0.1f, 0.0f}, up = {0.0f, 1.0f, 0.0f};
    int y;
    glGenFramebuffers(1, &fbo);
    glGenTextures(2, tex);
    host_frame(fbo, tex[0], tex[1], W, H, 0, 1);
    memset(&ed, 0, sizeof ed);
    ed.source = SNELL_ENV_GL_TEXTURE, ed.gl_texture = cube, ed.face_size = 64;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &env));
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (env && r) {
        test_frame_one(&fd, &g, sphere, env);
        g.material.ior = 1.5f;
        glm_lookat(eye, at, up, view);
        glm_perspective(0.9f, (float)W / H, 0.1f, 50.0f, proj);
        fd.camera.kind = SNELL_CAMERA_MATRICES;
        memcpy(fd.camera.view, view, sizeof view), memcpy(fd.camera.projection, proj, sizeof proj);
        fd.glass_count = 0, fd.depth = SNELL_DEPTH_CLEAR; /* the app's sky pass */
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glEnable(GL_SCISSOR_TEST); /* the app's ground */
        glScissor(0, 0, W, GROUND * H / N);
        glClearColor(k_ground[0] / 255.0f, k_ground[1] / 255.0f, k_ground[2] / 255.0f, 1.0f);
        glClearDepthf(0.98f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glDisable(GL_SCISSOR_TEST);
        glClearDepthf(1.0f);
        fd.glass_count = 1, fd.depth = SNELL_DEPTH_TEST, fd.draw_background = -1, fd.backdrop = &bd;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
        for (y = 0; y < H; y++) memcpy(flip + 4 * W * y, px + 4 * W * (H - 1 - y), 4 * W);
        CHECK_OK_CTX(ctx, snell_write_png(path, W, H, flip));
        printf("wrote %s\n", path);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    glDeleteTextures(1, &cube);
    glDeleteTextures(2, tex);
    glDeleteFramebuffers(1, &fbo);
}

/* img's magenta glass pixels (hit) against the reference's (sky, n_ref of them). */
static void check_sky(const char *name, const char *how, const uint8_t *img, const uint8_t *hit, const uint8_t *sky,
                      int n_ref)
{
    int i, both = 0, extra = 0;
    for (i = 0; i < N * N; i++) {
        int s = hit[i] && magenta(img + 4 * i);
        both += s && sky[i];
        extra += s && !sky[i];
    }
    printf("%s%s: %d of the reference's %d host-sky pixels, %d more\n", name, how, both, n_ref, extra);
    CHECK(both > 100 && both >= n_ref * 85 / 100 && extra <= n_ref / 10, "%s%s: the host's sky on %d of %d pixels, "
          "%d more", name, how, both, n_ref, extra);
}

int main(int argc, char **argv)
{
    static uint8_t img[N * N * 4], px[N * N * 4], hit[N * N], sky[2][N * N];
    snell_renderer *rb = NULL;
    snell_renderer_desc rd = {.width = N, .height = N, .target = SNELL_TARGET_BOUND_FRAMEBUFFER};
    snell_ctx *ctx = test_ctx();
    snell_renderer *r;
    snell_env *env;
    snell_mesh *sphere = NULL;
    snell_glass g;
    snell_frame_desc fd;
    snell_backdrop bd;
    GLuint fbo[3], tex[6];
    int m, rev, i, n_refs[2];
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 32);
    r = test_renderer(ctx, N, N);
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE}, &sphere));
    if (!env || !r || !sphere) return test_finish();
    if (argc > 1) picture(ctx, sphere, argv[1]);
    glGenFramebuffers(3, fbo);
    glGenTextures(6, tex);
    for (rev = 0; rev < 3; rev++) host_frame(fbo[rev], tex[2 * rev], tex[2 * rev + 1], N, N, rev == 1, 1);
    test_frame_one(&fd, &g, sphere, env);
    g.material.ior = 1.5f;
    camera(&fd.camera, 0);
    for (i = 0; i < 2; i++) {
        n_refs[i] = reference(ctx, &fd, i ? 1 : 6, hit, sky[i]);
        printf("reference, %d interfaces: %d of its glass pixels show the host's sky\n", i ? 1 : 6, n_refs[i]);
        CHECK(n_refs[i] > 100, "the reference's glass shows the host's sky on %d pixels", n_refs[i]);
    }
    memset(&bd, 0, sizeof bd);
    bd.source = SNELL_BACKDROP_TEXTURES, bd.width = N, bd.height = N;
    fd.backdrop = &bd;
    for (rev = 0; rev < 2; rev++) {
        camera(&fd.camera, rev);
        bd.color_texture = tex[2 * rev], bd.depth_texture = tex[2 * rev + 1];
        for (m = 0; m < snell_method_count(); m++) {
            const char *name = snell_method_info_at(m)->name;
            int one = snell_method_info_at(m)->method == SNELL_METHOD_SINGLE;
            g.material.method = snell_method_info_at(m)->method;
            CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
            CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, img));
            check_sky(name, rev ? ", reversed-Z" : "", img, hit, sky[one], n_refs[one]);
        }
    }
    /* COPY_BOUND: snell copies the bound framebuffer's colour and depth itself */
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &rb));
    camera(&fd.camera, 0);
    memset(&bd, 0, sizeof bd);
    bd.source = SNELL_BACKDROP_COPY_BOUND;
    for (m = 0; rb && m < snell_method_count(); m++) {
        int one = snell_method_info_at(m)->method == SNELL_METHOD_SINGLE, y;
        g.material.method = snell_method_info_at(m)->method;
        host_frame(fbo[2], tex[4], tex[5], N, N, 0, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo[2]);
        glViewport(0, 0, N, N);
        CHECK_OK_CTX(ctx, snell_render(rb, &fd, NULL));
        glBindFramebuffer(GL_FRAMEBUFFER, fbo[2]);
        glReadPixels(0, 0, N, N, GL_RGBA, GL_UNSIGNED_BYTE, px);
        for (y = 0; y < N; y++) memcpy(img + 4 * N * y, px + 4 * N * (N - 1 - y), 4 * N); /* top row first */
        check_sky(snell_method_info_at(m)->name, ", COPY_BOUND", img, hit, sky[one], n_refs[one]);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    snell_renderer_destroy(rb);
    glDeleteTextures(6, tex);
    glDeleteFramebuffers(3, fbo);
    snell_mesh_destroy(sphere);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
