/* SPDX-License-Identifier: MIT */
/* test_ctx — context creation on every backend available here, failure paths,
 * and the EXTERNAL backend inside a context the test made itself: the host's
 * GL state must be untouched by a snell frame. */
#define _POSIX_C_SOURCE 200112L /* setenv */
#include "test_util.h"

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

static int log_count;
static void count_log(snell_log_level level, const char *msg, void *user)
{
    (void)level; (void)msg;
    (*(int *)user)++;
}

static void check_backend(snell_backend b, const char *name)
{
    snell_ctx *ctx = NULL;
    snell_ctx_desc d;
    memset(&d, 0, sizeof d);
    d.backend = b;
    d.log = count_log;
    d.log_user = &log_count;
    d.gl_debug = 1;
    CHECK_OK(snell_ctx_create(&d, &ctx));
    if (!ctx) return;
    printf("%s -> %s on %s\n", name, snell_backend_str(snell_ctx_backend(ctx)), snell_ctx_gl_renderer(ctx));
    CHECK(eglGetCurrentContext() != EGL_NO_CONTEXT, "%s: no current context", name);
    CHECK(snell_ctx_has_gl_extension(ctx, "GL_KHR_debu") == 0, "extension lookup must be exact-token");
    /* GL debug output reaches the log callback: provoke a GL error. */
    if (snell_ctx_has_gl_extension(ctx, "GL_KHR_debug")) {
        int before = log_count;
        glEnable(0x7fff); /* not a capability: GL_INVALID_ENUM */
        glFinish();
        CHECK(glGetError() == GL_INVALID_ENUM, "%s: expected GL_INVALID_ENUM", name);
        CHECK(log_count > before, "%s: KHR_debug message not forwarded to the log callback", name);
    } else {
        printf("%s: no GL_KHR_debug; debug forwarding not checked\n", name);
    }
    CHECK(snell_ctx_has_gl_extension(ctx, "") == 0, "empty name");
    snell_ctx_destroy(ctx);
    CHECK(eglGetCurrentContext() == EGL_NO_CONTEXT, "%s: context still current after destroy", name);
}


static void check_external(void)
{
    EGLDisplay dpy;
    EGLContext host;
    snell_ctx *ctx = NULL;
    snell_ctx_desc d;
    snell_env *env = NULL;
    snell_mesh *mesh = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_glass g;
    snell_shape_desc sd;
    GLuint host_fbo, host_rb, host_prog_dummy;
    GLint v[4], i1;
    GLboolean b;
    GLfloat cc[4];

    if (!test_host_context(&dpy, &host)) {
        printf("cannot make a host context here; EXTERNAL checked only for the failure path\n");
        return;
    }
    /* Host state that snell must not disturb. */
    glGenFramebuffers(1, &host_fbo);
    glGenRenderbuffers(1, &host_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, host_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 64, 64);
    glBindFramebuffer(GL_FRAMEBUFFER, host_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, host_rb);
    host_prog_dummy = glCreateProgram();
    glViewport(3, 5, 17, 19);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glDepthFunc(GL_GEQUAL);
    glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
    glActiveTexture(GL_TEXTURE2);

    memset(&d, 0, sizeof d);
    d.backend = SNELL_BACKEND_EXTERNAL;
    CHECK_OK(snell_ctx_create(&d, &ctx));
    if (!ctx) return;
    memset(&sd, 0, sizeof sd);
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = 64;
    env = test_sky(ctx, 32);
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    test_frame_one(&fd, &g, mesh, env);
    if (r && env && mesh) CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));

    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &i1);
    CHECK(i1 == (GLint)host_fbo, "framebuffer binding changed to %d", i1);
    glGetIntegerv(GL_VIEWPORT, v);
    CHECK(v[0] == 3 && v[1] == 5 && v[2] == 17 && v[3] == 19, "viewport changed");
    CHECK(glIsEnabled(GL_BLEND) && glIsEnabled(GL_CULL_FACE) && !glIsEnabled(GL_DEPTH_TEST), "enables changed");
    glGetIntegerv(GL_BLEND_DST_RGB, &i1);
    CHECK(i1 == GL_ONE, "blend func changed");
    glGetIntegerv(GL_CULL_FACE_MODE, &i1);
    CHECK(i1 == GL_FRONT, "cull mode changed");
    glGetIntegerv(GL_DEPTH_FUNC, &i1);
    CHECK(i1 == GL_GEQUAL, "depth func changed");
    glGetIntegerv(GL_CURRENT_PROGRAM, &i1);
    CHECK(i1 == 0, "program changed");
    glGetIntegerv(GL_ACTIVE_TEXTURE, &i1);
    CHECK(i1 == GL_TEXTURE2, "active texture changed");
    glGetFloatv(GL_COLOR_CLEAR_VALUE, cc);
    CHECK(cc[0] == 0.25f && cc[2] == 0.75f, "clear colour changed");
    glGetBooleanv(GL_DEPTH_WRITEMASK, &b);
    CHECK(b == GL_TRUE, "depth mask changed");

    snell_renderer_destroy(r);
    snell_mesh_destroy(mesh);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    CHECK(eglGetCurrentContext() == host, "EXTERNAL destroy must leave the host's context current");
    glDeleteProgram(host_prog_dummy);
    glDeleteRenderbuffers(1, &host_rb);
    glDeleteFramebuffers(1, &host_fbo);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, host);
    eglTerminate(dpy);
}

/* Under a profile each answer it could change goes, with the driver's own, to
 * the file SNELL_PROFILE_TRACE names (core/profile.h): .ci/run picks the tests
 * of its profile legs by them (tests/scripts/profile_tests.py). */
static void check_profile_trace(void)
{
    char path[1024], *kept = getenv("SNELL_PROFILE_TRACE"), want[256], text[4096] = "";
    unsigned char *bytes;
    snell_ctx *ctx = NULL;
    snell_ctx_desc d;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_device_limits lim;
    GLint i, n = 0, debug = 0, texture = 0;
    size_t len = 0;
    snprintf(path, sizeof path, "%s", test_out("profile_trace.txt"));
    remove(path);
    setenv("SNELL_PROFILE_TRACE", path, 1);
    memset(&d, 0, sizeof d);
    d.device_profile = "gles30-min";
    CHECK_OK(snell_ctx_create(&d, &ctx));
    if (kept) setenv("SNELL_PROFILE_TRACE", kept, 1);
    else unsetenv("SNELL_PROFILE_TRACE");
    if (!ctx) return;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (i = 0; i < n; i++) debug |= strcmp((const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i), "GL_KHR_debug") == 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
    CHECK(!snell_ctx_has_gl_extension(ctx, "GL_KHR_debug"), "gles30-min has no KHR_debug");
    snell_ctx_limits(ctx, &lim);
    memset(&rd, 0, sizeof rd);
    rd.width = 3000; /* over gles30-min's 2048 */
    rd.height = 8;
    CHECK(snell_renderer_create(ctx, &rd, &r) == SNELL_E_UNSUPPORTED, "3000 wide under gles30-min");
    snell_ctx_destroy(ctx);
    bytes = test_read_file(path, &len);
    CHECK(bytes != NULL, "no trace in %s", path);
    if (!bytes) return;
    memcpy(text, bytes, len < sizeof text - 1 ? len : sizeof text - 1);
    free(bytes);
    snprintf(want, sizeof want, "ext %d GL_KHR_debug\n", debug ? 1 : 0);
    CHECK(strstr(text, want) != NULL, "trace lacks \"%s\": %s", want, text);
    snprintf(want, sizeof want, "limits %d ", texture);
    CHECK(strstr(text, want) != NULL, "trace lacks \"%s\": %s", want, text);
    /* light maps' format and KHR_debug are asked only by what uses them */
    CHECK(strstr(text, "GL_EXT_float_blend") == NULL, "no light map, yet float blending asked: %s", text);
    snprintf(want, sizeof want, "check 0 3000 %d\n", texture);
    CHECK(strstr(text, want) != NULL, "trace lacks \"%s\": %s", want, text);
}

int main(void)
{
    snell_ctx *ctx = (snell_ctx *)0x1;
    snell_ctx_desc d;

    check_backend(SNELL_BACKEND_DEFAULT, "default");
    check_backend(SNELL_BACKEND_SURFACELESS, "surfaceless");
    check_backend(SNELL_BACKEND_PBUFFER, "pbuffer");

    /* Two contexts at once share the EGL display; destroying one keeps the other usable. */
    {
        snell_ctx *a = NULL, *b = NULL;
        CHECK_OK(snell_ctx_create(NULL, &a));
        CHECK_OK(snell_ctx_create(NULL, &b));
        snell_ctx_destroy(a);
        if (b) {
            snell_env *env = NULL;
            snell_env_desc ed;
            memset(&ed, 0, sizeof ed);
            ed.face_size = 8;
            CHECK_OK(snell_env_create(b, &ed, &env));
            snell_env_destroy(env);
        }
        snell_ctx_destroy(b);
    }

    /* Failure paths: a status and a message, never a crash. */
    memset(&d, 0, sizeof d);
    d.backend = SNELL_BACKEND_EXTERNAL;
    CHECK(snell_ctx_create(&d, &ctx) == SNELL_E_EGL, "EXTERNAL without a current context must fail");
    CHECK(ctx == NULL, "out must be NULL on failure");
    CHECK(strstr(snell_last_error(NULL), "no GL context is current") != NULL, "message: %s", snell_last_error(NULL));
    d.backend = (snell_backend)42;
    CHECK(snell_ctx_create(&d, &ctx) == SNELL_E_INVALID_ARG, "unknown backend");
    CHECK(snell_ctx_create(NULL, NULL) == SNELL_E_INVALID_ARG, "NULL out");
    snell_ctx_destroy(NULL);

    check_external();
    check_profile_trace();
    return test_finish();
}
