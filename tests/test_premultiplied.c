/* SPDX-License-Identifier: MIT */
/* test_premultiplied — premultiplied alpha output
 * (snell_renderer_desc.premultiplied_alpha), over a transparent target: a
 * grey-tinted glass sphere with an opaque cube beside it drawn with
 * draw_background = -1 into a framebuffer cleared to (0, 0, 0, 0), for every
 * method. Where nothing is drawn the target stays 0 (alpha 0); the cube's
 * pixels have alpha 255; composited over a colour b (rgb + (1 - a) b), the
 * glass's pixels are what the same frame draws, without alpha, in a uniform
 * environment of colour b (the environment's weight in a grey glass is
 * grey, so the composite is exact up to 8-bit rounding: within 3 of 255);
 * its alpha is the glass's absorption, well inside 0..255. Refused with
 * exit-direction output. */
#include "test_util.h"

#include <GLES3/gl3.h>
#include <string.h>

#define N 64

static const uint8_t k_b[3] = {70, 150, 210};
static const float k_cube[16] = {0.3f, 0, 0, 0, 0, 0.3f, 0, 0, 0, 0, 0.3f, 0, 1.0f, 0.0f, 0.0f, 1};
static const float k_left[16] = {0.8f, 0, 0, 0, 0, 0.8f, 0, 0, 0, 0, 0.8f, 0, -0.3f, 0, 0, 1};

int main(void)
{
    static uint8_t premul[N * N * 4], plain[N * N * 4], sky[8 * 4 * 4];
    snell_ctx *ctx = test_ctx();
    snell_renderer *rp = NULL, *r = NULL;
    snell_renderer_desc rd = {.width = N, .height = N, .target = SNELL_TARGET_BOUND_FRAMEBUFFER,
                              .premultiplied_alpha = 1};
    snell_env *env = NULL;
    snell_env_desc ed;
    snell_mesh *sphere = NULL, *cube = NULL;
    snell_glass g;
    snell_opaque op;
    snell_frame_desc fd;
    GLuint fbo, rb[2];
    int i, m;
    if (!ctx) SKIP("no GL context");
    for (i = 0; i < 8 * 4; i++) memcpy(sky + 4 * i, k_b, 3), sky[4 * i + 3] = 255;
    memset(&ed, 0, sizeof ed);
    ed.source = SNELL_ENV_EQUIRECT;
    ed.equirect_rgba = sky, ed.equirect_width = 8, ed.equirect_height = 4, ed.face_size = 8;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &env));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE}, &sphere));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_CUBE}, &cube));
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &rp));
    rd.premultiplied_alpha = 0;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (!env || !sphere || !cube || !rp || !r) return test_finish();
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(2, rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, N, N);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, N, N);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    test_frame_one(&fd, &g, sphere, env);
    g.model = k_left;
    g.material.ior = 1.5f;
    g.material.tint[0] = g.material.tint[1] = g.material.tint[2] = 0.6f;
    memset(&op, 0, sizeof op);
    op.mesh = cube;
    op.model = k_cube;
    fd.opaque = &op;
    fd.opaque_count = 1;
    fd.draw_background = -1;
    fd.depth = SNELL_DEPTH_CLEAR;
    for (m = 0; m < snell_method_count(); m++) {
        int glass = 0, near = 0, outside = 0, clear = 0, cube_px = 0, cube_opaque = 0, partial = 0;
        g.material.method = snell_method_info_at(m)->method;
        for (i = 0; i < 2; i++) {
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glViewport(0, 0, N, N);
            glClearColor(i ? k_b[0] / 255.0f : 0.0f, i ? k_b[1] / 255.0f : 0.0f, i ? k_b[2] / 255.0f : 0.0f,
                         i ? 1.0f : 0.0f);
            glClear(GL_COLOR_BUFFER_BIT);
            CHECK_OK_CTX(ctx, snell_render(i ? r : rp, &fd, NULL));
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glReadPixels(0, 0, N, N, GL_RGBA, GL_UNSIGNED_BYTE, i ? plain : premul);
        }
        for (i = 0; i < N * N; i++) {
            const uint8_t *p = premul + 4 * i, *q = plain + 4 * i;
            int drawn = memcmp(q, k_b, 3) != 0, k, ok = 1;
            int is_cube = p[3] == 255 && q[0] == p[0] && q[1] == p[1] && q[2] == p[2] && drawn;
            if (!drawn && p[3] == 0) { /* nothing of the frame here, or glass that shows only the sky */
                outside++;
                clear += p[0] == 0 && p[1] == 0 && p[2] == 0;
                continue;
            }
            if (is_cube) {
                cube_px++;
                cube_opaque++;
                continue;
            }
            glass++;
            partial += p[3] > 20 && p[3] < 235;
            for (k = 0; k < 3; k++) {
                int c = p[k] + (255 - p[3]) * k_b[k] / 255;
                ok &= c - q[k] <= 3 && q[k] - c <= 3;
            }
            near += ok;
        }
        printf("%s: %d glass pixels (%d composite within 3, %d of partial alpha), %d cube, %d clear (%d zero)\n",
               snell_method_info_at(m)->name, glass, near, partial, cube_px, outside, clear);
        CHECK(outside > N * N / 4 && clear == outside, "%s: %d of %d empty pixels not zero",
              snell_method_info_at(m)->name, outside - clear, outside);
        CHECK(cube_px > 50 && cube_opaque == cube_px, "%s: cube pixels %d", snell_method_info_at(m)->name, cube_px);
        CHECK(glass > 400 && near >= glass * 99 / 100 && partial > glass / 2,
              "%s: the composite within 3 on %d of %d glass pixels (%d of partial alpha)",
              snell_method_info_at(m)->name, near, glass, partial);
    }
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    rd.target = SNELL_TARGET_OFFSCREEN;
    rd.premultiplied_alpha = 1;
    {
        snell_renderer *bad = NULL;
        CHECK(snell_renderer_create(ctx, &rd, &bad) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "premultiplied"),
              "premultiplied exit directions: %s", snell_last_error(ctx));
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(2, rb);
    snell_renderer_destroy(rp);
    snell_renderer_destroy(r);
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(cube);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
