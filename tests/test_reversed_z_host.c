/* SPDX-License-Identifier: MIT */
/* test_reversed_z_host — glass drawn into a host framebuffer whose depth is
 * reversed-Z (issue 48 item 2): the host clears its depth to 0, draws an
 * occluder with GREATER, snell tests against that depth (SNELL_DEPTH_TEST,
 * mapped into its own convention and back), then the host draws a probe
 * behind the glass with GREATER. Every method's picture must equal the same
 * scene drawn with the standard projection, to a few edge pixels: the
 * occluder hides the glass, and the glass's depth, given back, hides the probe.
 * D24, D24S8 and D32F depth; NO_WRITE gives the host's depth back unchanged. Without host framebuffer support the camera is
 * refused by name. */
#include "test_util.h"
#include "snell_components.h"

#include <GLES3/gl3.h>
#include <cglm/cglm.h>
#include <stdlib.h>
#include <string.h>

#define N 64
#define EDGE 12

static GLuint g_prog, g_vbo, g_vao;

static void host_program(void)
{
    static const char *vs = "#version 300 es\nin vec3 a_pos;\nuniform mat4 u_pv;\n"
                            "void main() { gl_Position = u_pv * vec4(a_pos, 1.0); }\n";
    static const char *fs = "#version 300 es\nprecision mediump float;\nuniform vec4 u_color;\nout vec4 o;\n"
                            "void main() { o = u_color; }\n";
    const char *src[2] = {vs, fs};
    GLint ok = 0;
    int i;
    g_prog = glCreateProgram();
    for (i = 0; i < 2; i++) {
        GLuint s = glCreateShader(i ? GL_FRAGMENT_SHADER : GL_VERTEX_SHADER);
        glShaderSource(s, 1, &src[i], NULL);
        glCompileShader(s);
        glAttachShader(g_prog, s);
        glDeleteShader(s);
    }
    glBindAttribLocation(g_prog, 0, "a_pos");
    glLinkProgram(g_prog);
    glGetProgramiv(g_prog, GL_LINK_STATUS, &ok);
    CHECK(ok, "host program links");
    glGenBuffers(1, &g_vbo);
    glGenVertexArrays(1, &g_vao);
}

/* The host's quad x0..x1 by -3..3 at world z, drawn with its depth test. */
static void host_quad(const float pv[16], float x0, float x1, float z, const float color[4])
{
    const float v[18] = {x0, -3, z, x1, -3, z, x1, 3, z, x0, -3, z, x1, 3, z, x0, 3, z};
    glUseProgram(g_prog);
    glBindVertexArray(g_vao);
    glBindBuffer(GL_ARRAY_BUFFER, g_vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof v, v, GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    glUniformMatrix4fv(glGetUniformLocation(g_prog, "u_pv"), 1, GL_FALSE, pv);
    glUniform4fv(glGetUniformLocation(g_prog, "u_color"), 1, color);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glBindVertexArray(0);
    glUseProgram(0);
}

/* The scene into fbo through the standard (rev 0) or reversed-Z camera; the
 * picture read back top row first. */
static snell_status scene(snell_renderer *r, snell_frame_desc *fd, GLuint fbo, int rev, uint8_t *img)
{
    static const float green[4] = {0.1f, 0.8f, 0.2f, 1.0f}, magenta[4] = {0.9f, 0.1f, 0.9f, 1.0f};
    static const float flip_z[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1};
    vec3 eye = {0.0f, 0.3f, 3.2f}, at = {0.0f, 0.0f, 0.0f}, up = {0.0f, 1.0f, 0.0f};
    mat4 view, proj, rz, pv;
    snell_status st;
    uint8_t px[N * N * 4];
    int y;
    glm_lookat(eye, at, up, view);
    glm_perspective(0.8f, 1.0f, 0.1f, 50.0f, proj);
    if (rev) {
        memcpy(rz, flip_z, sizeof rz);
        glm_mat4_mul(rz, proj, proj);
    }
    glm_mat4_mul(proj, view, pv);
    memset(&fd->camera, 0, sizeof fd->camera);
    fd->camera.kind = SNELL_CAMERA_MATRICES;
    memcpy(fd->camera.view, view, sizeof fd->camera.view);
    memcpy(fd->camera.projection, proj, sizeof fd->camera.projection);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, N, N);
    glClearColor(0.2f, 0.2f, 0.25f, 1.0f);
    glClearDepthf(rev ? 0.0f : 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(rev ? GL_GREATER : GL_LESS);
    host_quad((const float *)pv, -3.0f, -0.25f, 1.4f, green); /* in front of the glass, on the left */
    st = snell_render(r, fd, NULL);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, N, N);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(rev ? GL_GREATER : GL_LESS);
    host_quad((const float *)pv, -3.0f, 3.0f, 0.3f, magenta); /* behind the glass's front */
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepthf(1.0f);
    glReadPixels(0, 0, N, N, GL_RGBA, GL_UNSIGNED_BYTE, px);
    for (y = 0; y < N; y++) memcpy(img + 4 * N * y, px + 4 * N * (N - 1 - y), 4 * N);
    return st;
}

static int differ(const uint8_t *a, const uint8_t *b)
{
    int i, k, n = 0;
    for (i = 0; i < N * N; i++) {
        int d = 0;
        for (k = 0; k < 3; k++) d |= abs(a[4 * i + k] - b[4 * i + k]) > 8;
        n += d;
    }
    return n;
}

static int count(const uint8_t *img, int r, int g, int b)
{
    int i, n = 0;
    for (i = 0; i < N * N; i++)
        n += abs(img[4 * i] - r) < 20 && abs(img[4 * i + 1] - g) < 20 && abs(img[4 * i + 2] - b) < 20;
    return n;
}

int main(void)
{
    static const GLenum formats[3] = {GL_DEPTH_COMPONENT24, GL_DEPTH24_STENCIL8, GL_DEPTH_COMPONENT32F};
    static uint8_t std_img[N * N * 4], rev_img[N * N * 4];
    snell_ctx *ctx = test_ctx();
    snell_renderer *r = NULL;
    snell_renderer_desc rd = {.width = N, .height = N, .target = SNELL_TARGET_BOUND_FRAMEBUFFER};
    snell_env *env;
    snell_mesh *sphere = NULL;
    snell_glass g;
    snell_frame_desc fd;
    GLuint fbo, rb[2];
    int f, m;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 32);
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE}, &sphere));
    if (!env || !r || !sphere) return test_finish();
    host_program();
    test_frame_one(&fd, &g, sphere, env);
    g.material.ior = 1.5f;
    fd.depth = SNELL_DEPTH_TEST;
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(2, rb);
    for (f = 0; f < 3; f++) {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, N, N);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
        glDeleteRenderbuffers(1, &rb[1]);
        glGenRenderbuffers(1, &rb[1]);
        glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
        glRenderbufferStorage(GL_RENDERBUFFER, formats[f], N, N);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER,
                                  formats[f] == GL_DEPTH24_STENCIL8 ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
                                  GL_RENDERBUFFER, rb[1]);
        for (m = 0; m < snell_method_count(); m++) {
            const char *name = snell_method_info_at(m)->name;
            snell_status st;
            int d, glass, probe;
            g.material.method = snell_method_info_at(m)->method;
            CHECK_OK_CTX(ctx, scene(r, &fd, fbo, 0, std_img));
            st = scene(r, &fd, fbo, 1, rev_img);
#ifndef SNELL_WITH_HOST_FRAMEBUFFERS
            CHECK(st == SNELL_E_UNSUPPORTED && strstr(snell_last_error(ctx), "reversed-Z"),
                  "%s: reversed-Z refused by name without host framebuffer support: %s", name, snell_last_error(ctx));
            continue;
#endif
            CHECK(st == SNELL_OK, "%s, depth 0x%x: reversed-Z, depth tested: %s", name, formats[f],
                  snell_last_error(ctx));
            probe = count(std_img, 230, 25, 230);
            glass = N * N - probe - count(std_img, 25, 204, 51);
            d = differ(std_img, rev_img);
            printf("%s, depth 0x%x: %d glass pixels, occluder %d, probe %d; reversed-Z differs on %d\n", name,
                   formats[f], glass, count(std_img, 25, 204, 51), count(std_img, 230, 25, 230), d);
            CHECK(glass > 300 && count(std_img, 25, 204, 51) > 300 && count(std_img, 230, 25, 230) > 300,
                  "%s: the standard scene shows glass, occluder and probe", name);
            CHECK(d <= EDGE, "%s, depth 0x%x: the reversed-Z picture differs from the standard one on %d pixels",
                  name, formats[f], d);
            if (formats[f] != GL_DEPTH24_STENCIL8) continue;
            /* NO_WRITE: the host's depth comes back as it was, so the probe shows through the glass */
            fd.depth = SNELL_DEPTH_TEST_NO_WRITE;
            CHECK_OK_CTX(ctx, scene(r, &fd, fbo, 0, std_img));
            CHECK_OK_CTX(ctx, scene(r, &fd, fbo, 1, rev_img));
            fd.depth = SNELL_DEPTH_TEST;
            d = differ(std_img, rev_img);
            CHECK(d <= EDGE && count(std_img, 230, 25, 230) > probe + glass / 2,
                  "%s, NO_WRITE: reversed-Z differs on %d pixels; the probe on %d (%d where the glass wrote depth)",
                  name, d, count(std_img, 230, 25, 230), probe);
        }
    }
    CHECK(glGetError() == GL_NO_ERROR, "GL error at the end");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(2, rb);
    snell_mesh_destroy(sphere);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
