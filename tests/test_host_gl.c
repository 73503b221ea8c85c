/* SPDX-License-Identifier: MIT */
/* The host's GL untouched and every framebuffer an app binds (issue 48),
 * EXTERNAL in a host's own EGL context: its pending GL errors kept (each
 * kind), its transform feedback paused, its KHR_debug callback given back,
 * its packed depth given back exactly (NO_WRITE); framebuffers snell cannot
 * draw into refused by name, with no GL error left behind; MRT (draw buffer
 * 0 alone written, COPY_BOUND's source), sRGB (encoded once) and two eyes
 * side by side (the host's viewport). */
#include "test_util.h"
#include "snell/snell_2d.h"
#include "snell/snell_water.h"
#include "snell_components.h"

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 64
#define H 48

static snell_ctx *g_ctx;
static snell_mesh *g_mesh;
static snell_env *g_env;

/* A host framebuffer of colour (0: none) and depth (0: none) renderbuffers. */
typedef struct host_fb {
    GLuint fbo, rb[3];
} host_fb;

static void fb_make(host_fb *f, GLenum color, GLenum depth, int w, int h)
{
    memset(f, 0, sizeof *f);
    glGenFramebuffers(1, &f->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, f->fbo);
    glGenRenderbuffers(3, f->rb);
    if (color) {
        glBindRenderbuffer(GL_RENDERBUFFER, f->rb[0]);
        glRenderbufferStorage(GL_RENDERBUFFER, color, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, f->rb[0]);
    }
    if (depth) {
        glBindRenderbuffer(GL_RENDERBUFFER, f->rb[1]);
        glRenderbufferStorage(GL_RENDERBUFFER, depth, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER,
                                  depth == GL_DEPTH24_STENCIL8 || depth == GL_DEPTH32F_STENCIL8 ? GL_DEPTH_STENCIL_ATTACHMENT
                                                                                               : GL_DEPTH_ATTACHMENT,
                                  GL_RENDERBUFFER, f->rb[1]);
    }
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glViewport(0, 0, w, h);
}

static void fb_free(host_fb *f)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &f->fbo);
    glDeleteRenderbuffers(3, f->rb);
}

static snell_renderer *renderer(int w, int h, int premultiplied)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.width = w, rd.height = h, rd.target = SNELL_TARGET_BOUND_FRAMEBUFFER, rd.premultiplied_alpha = premultiplied;
    CHECK_OK_CTX(g_ctx, snell_renderer_create(g_ctx, &rd, &r));
    return r;
}

static snell_status frame(snell_renderer *r, snell_depth_mode depth, snell_backdrop *bd)
{
    snell_frame_desc fd;
    snell_glass g;
    memset(&fd, 0, sizeof fd);
    memset(&g, 0, sizeof g);
    g.mesh = g_mesh;
    fd.glass = &g, fd.glass_count = 1, fd.env = g_env;
    fd.depth = depth;
    fd.backdrop = bd;
    return snell_render(r, &fd, NULL);
}

static GLuint program(const char *vs, const char *fs, const char *varying)
{
    const char *src[2] = {vs, fs};
    GLuint p = glCreateProgram();
    GLint ok = 0;
    int i;
    for (i = 0; i < 2; i++) {
        GLuint s = glCreateShader(i ? GL_FRAGMENT_SHADER : GL_VERTEX_SHADER);
        glShaderSource(s, 1, &src[i], NULL);
        glCompileShader(s);
        glAttachShader(p, s);
        glDeleteShader(s);
    }
    if (varying) glTransformFeedbackVaryings(p, 1, &varying, GL_INTERLEAVED_ATTRIBS);
    glLinkProgram(p);
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    CHECK(ok, "host program links");
    return p;
}

/* ------------------------------------------------ pending errors, each kind */
static void raise_error(GLenum e, GLuint incomplete)
{
    switch (e) {
    case GL_INVALID_ENUM: glEnable(0x1234); break;
    case GL_INVALID_VALUE: glLineWidth(-1.0f); break;
    case GL_INVALID_OPERATION: glEndTransformFeedback(); break;
    default:
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, incomplete);
        glClear(GL_COLOR_BUFFER_BIT);
        break;
    }
}

static void check_pending_errors(void)
{
    static const GLenum kinds[4] = {GL_INVALID_ENUM, GL_INVALID_VALUE, GL_INVALID_OPERATION,
                                    GL_INVALID_FRAMEBUFFER_OPERATION};
    host_fb f;
    GLuint incomplete;
    snell_renderer *r;
    snell_backdrop bd;
    int k;
    glGenFramebuffers(1, &incomplete);
    fb_make(&f, GL_RGBA8, GL_DEPTH_COMPONENT24, W, H);
    for (k = 0; k < 4; k++) {
        GLenum got, then;
        snell_status st;
        raise_error(kinds[k], incomplete);
        glBindFramebuffer(GL_FRAMEBUFFER, f.fbo);
        r = renderer(W, H, 0);
        got = glGetError();
        CHECK(got == kinds[k] && glGetError() == GL_NO_ERROR, "renderer_create: host error 0x%x came back as 0x%x",
              kinds[k], got);
        raise_error(kinds[k], incomplete);
        glBindFramebuffer(GL_FRAMEBUFFER, f.fbo);
        memset(&bd, 0, sizeof bd);
        bd.source = SNELL_BACKDROP_COPY_BOUND;
        st = frame(r, SNELL_DEPTH_TEST, &bd);
        CHECK(st == SNELL_OK, "a frame with host error 0x%x pending: %s", kinds[k], snell_last_error(g_ctx));
        got = glGetError();
        then = glGetError();
        CHECK(got == kinds[k] && then == GL_NO_ERROR, "snell_render: host error 0x%x came back as 0x%x, then 0x%x",
              kinds[k], got, then);
        snell_renderer_destroy(r);
    }
    fb_free(&f);
    glDeleteFramebuffers(1, &incomplete);
}

/* A call that touches GL with each kind of host error pending: the call
 * succeeds and the error comes back, once. */
#define KEEPS(what, call)                                                                                          \
    do {                                                                                                           \
        int k_;                                                                                                    \
        for (k_ = 0; k_ < 4; k_++) {                                                                               \
            GLenum got_, then_;                                                                                    \
            snell_status st_;                                                                                      \
            raise_error(g_kinds[k_], g_incomplete);                                                                \
            glBindFramebuffer(GL_FRAMEBUFFER, 0);                                                                  \
            st_ = (call);                                                                                          \
            CHECK(st_ == SNELL_OK, "%s with host error 0x%x pending: %s", what, g_kinds[k_],                       \
                  snell_last_error(g_ctx));                                                                        \
            got_ = glGetError();                                                                                   \
            then_ = glGetError();                                                                                  \
            CHECK(got_ == g_kinds[k_] && then_ == GL_NO_ERROR, "%s: host error 0x%x came back as 0x%x, then 0x%x", \
                  what, g_kinds[k_], got_, then_);                                                                 \
        }                                                                                                          \
    } while (0)

static const GLenum g_kinds[4] = {GL_INVALID_ENUM, GL_INVALID_VALUE, GL_INVALID_OPERATION,
                                  GL_INVALID_FRAMEBUFFER_OPERATION};
static GLuint g_incomplete;

static snell_status env_made(void)
{
    snell_env_desc ed;
    snell_env *e = NULL;
    snell_status st;
    memset(&ed, 0, sizeof ed);
    ed.face_size = 8;
    st = snell_env_create(g_ctx, &ed, &e);
    snell_env_destroy(e);
    return st;
}

#ifdef SNELL_WITH_WATER
static snell_status water_run(void)
{
    snell_water_desc wd;
    snell_water *w = NULL;
    static float h[64 * 64];
    snell_status st;
    memset(&wd, 0, sizeof wd);
    wd.grid = 64, wd.sim = SNELL_WATER_SIM_GPU;
    st = snell_water_create(g_ctx, &wd, &w);
    if (st == SNELL_OK) st = snell_water_drop(w, 0.0f, 0.0f, 0.3f, 0.01f);
    if (st == SNELL_OK) st = snell_water_step(w, 0.0f, 2, NULL);
    if (st == SNELL_OK) st = snell_water_read_heights(w, h);
    snell_water_destroy(w);
    return st;
}
#endif

#ifdef SNELL_WITH_LM2D
static snell_status lightmap_run(void)
{
    snell_lightmap2d_desc d;
    snell_light2d_desc l;
    snell_lightmap2d *lm = NULL;
    snell_scene2d *s = NULL;
    float rgb[16 * 16 * 3];
    snell_status st;
    memset(&d, 0, sizeof d);
    memset(&l, 0, sizeof l);
    d.width = d.height = 16, d.threads = 1;
    l.type = SNELL_LIGHT2D_POINT, l.position[0] = l.position[1] = 8.0f, l.power = 1.0f, l.rays = 500;
    st = snell_scene2d_create(g_ctx, &s);
    if (st == SNELL_OK) st = snell_scene2d_add_light(s, &l, NULL);
    if (st == SNELL_OK) st = snell_lightmap2d_create(g_ctx, &d, &lm);
    if (st == SNELL_OK) st = snell_lightmap2d_frame(lm, s, NULL);
    if (st == SNELL_OK) st = snell_lightmap2d_read_rgb(lm, rgb);
    snell_lightmap2d_destroy(lm);
    snell_scene2d_destroy(s);
    return st;
}
#endif

/* The other calls that touch GL keep the host's errors as snell_render does. */
static void check_pending_errors_elsewhere(void)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    static uint8_t rgba[W * H * 4];
    static const float dir[3] = {0.0f, 0.0f, -1.0f};
    float rgb[3];
    glGenFramebuffers(1, &g_incomplete);
    memset(&rd, 0, sizeof rd);
    rd.width = W, rd.height = H;
    CHECK_OK_CTX(g_ctx, snell_renderer_create(g_ctx, &rd, &r));
    CHECK_OK_CTX(g_ctx, frame(r, SNELL_DEPTH_CLEAR, NULL));
    KEEPS("snell_env_create", env_made());
    KEEPS("snell_renderer_read_rgba", snell_renderer_read_rgba(r, rgba));
    KEEPS("snell_renderer_env_probe",
          snell_renderer_env_probe(r, g_env, SNELL_ENV_LOOKUP_CUBE, dir, 1, rgb));
#ifdef SNELL_WITH_WATER
    KEEPS("the water's calls", water_run());
#endif
#ifdef SNELL_WITH_LM2D
    KEEPS("the 2D lightmap's calls", lightmap_run());
#endif
    snell_renderer_destroy(r);
    glDeleteFramebuffers(1, &g_incomplete);
}

/* ------------------------------------------------ transform feedback */
static void check_transform_feedback(void)
{
    static const char vs[] = "#version 300 es\nout float v_id;\n"
                             "void main() { v_id = float(gl_VertexID); gl_Position = vec4(0.0, 0.0, 0.0, 1.0); "
                             "gl_PointSize = 1.0; }\n";
    static const char fs[] = "#version 300 es\nprecision mediump float;\nin float v_id;\nout vec4 o;\n"
                             "void main() { o = vec4(v_id); }\n";
    GLuint prog = program(vs, fs, "v_id"), buf, vao, q;
    GLuint written = 0;
    GLboolean active = GL_FALSE, paused = GL_TRUE;
    float got[8];
    host_fb f;
    snell_renderer *r;
    void *map;
    fb_make(&f, GL_RGBA8, GL_DEPTH_COMPONENT24, W, H);
    r = renderer(W, H, 0);
    glGenBuffers(1, &buf);
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, buf);
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, 4096 * sizeof(float), NULL, GL_STATIC_READ);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buf);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenQueries(1, &q);
    glUseProgram(prog);
    glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, q);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, 3);
    CHECK(frame(r, SNELL_DEPTH_TEST, NULL) == SNELL_OK, "a frame inside the host's transform feedback: %s",
          snell_last_error(g_ctx));
    glGetBooleanv(GL_TRANSFORM_FEEDBACK_ACTIVE, &active);
    glGetBooleanv(GL_TRANSFORM_FEEDBACK_PAUSED, &paused);
    CHECK(active && !paused, "the host's transform feedback active %d paused %d after the frame", active, paused);
    glDrawArrays(GL_POINTS, 3, 5);
    glEndTransformFeedback();
    glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
    glGetQueryObjectuiv(q, GL_QUERY_RESULT, &written);
    CHECK(written == 8, "transform feedback wrote %u primitives; the host drew 8", written);
    map = glMapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, sizeof got, GL_MAP_READ_BIT);
    if (map) {
        memcpy(got, map, sizeof got);
        glUnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER);
        CHECK(got[2] == 2.0f && got[3] == 3.0f && got[7] == 7.0f, "captured %g %g %g: the host's vertices in order",
              (double)got[2], (double)got[3], (double)got[7]);
    }
    CHECK(glGetError() == GL_NO_ERROR, "GL error around transform feedback");
    glUseProgram(0);
    glDeleteProgram(prog);
    glDeleteBuffers(1, &buf);
    glDeleteVertexArrays(1, &vao);
    glDeleteQueries(1, &q);
    snell_renderer_destroy(r);
    fb_free(&f);
}

/* ------------------------------------------------ KHR_debug callback */
static void GL_APIENTRY host_debug(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                   const GLchar *message, const void *user)
{
    (void)source, (void)type, (void)id, (void)severity, (void)length, (void)message, (void)user;
}

static void quiet_log(snell_log_level level, const char *msg, void *user) { (void)level, (void)msg, (void)user; }

static void check_debug_callback(void)
{
    PFNGLDEBUGMESSAGECALLBACKKHRPROC set =
        (PFNGLDEBUGMESSAGECALLBACKKHRPROC)eglGetProcAddress("glDebugMessageCallbackKHR");
    PFNGLGETPOINTERVKHRPROC get = (PFNGLGETPOINTERVKHRPROC)eglGetProcAddress("glGetPointervKHR");
    static int tag;
    void *fn = NULL, *user = NULL, *want;
    GLDEBUGPROCKHR mine = host_debug;
    snell_ctx *c = NULL;
    snell_ctx_desc d;
    if (!set || !get) {
        printf("no KHR_debug: the host's callback not checked\n");
        return;
    }
    set(host_debug, &tag);
    memset(&d, 0, sizeof d);
    d.backend = SNELL_BACKEND_EXTERNAL, d.gl_debug = 1, d.log = quiet_log;
    CHECK_OK(snell_ctx_create(&d, &c));
    get(GL_DEBUG_CALLBACK_FUNCTION_KHR, &fn);
    CHECK(fn != NULL, "snell's callback installed");
    snell_ctx_destroy(c);
    get(GL_DEBUG_CALLBACK_FUNCTION_KHR, &fn);
    get(GL_DEBUG_CALLBACK_USER_PARAM_KHR, &user);
    memcpy(&want, &mine, sizeof want);
    CHECK(fn == want && user == &tag, "after snell_ctx_destroy the host's callback %p (user %p) is %p (user %p)", want,
          (void *)&tag, fn, user);
    set(NULL, NULL);
}

/* ------------------------------------------------ NO_WRITE, every depth format */
/* A slope of depths over the whole framebuffer; EQUAL passes only where the
 * depth is what this drew. */
static GLuint g_slope;
static void slope(GLenum func, int white)
{
    glUseProgram(g_slope);
    glUniform1f(glGetUniformLocation(g_slope, "u_white"), white ? 1.0f : 0.0f);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(func);
    glDepthMask(func == GL_ALWAYS);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(0);
}

static int count_white(int w, int h)
{
    uint8_t *px = (uint8_t *)malloc((size_t)w * h * 4);
    int i, n = 0;
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    for (i = 0; i < w * h; i++) n += px[4 * i] == 255;
    free(px);
    return n;
}

static void check_no_write_exact(void)
{
    static const char vs[] = "#version 300 es\nvoid main() {\n"
                             "  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n"
                             "  gl_Position = vec4(p, 0.13 * p.x + 0.61 * p.y - 0.2, 1.0);\n}\n";
    static const char fs[] = "#version 300 es\nprecision mediump float;\nuniform float u_white;\nout vec4 o;\n"
                             "void main() { o = vec4(u_white); }\n";
    static const GLenum formats[5] = {GL_DEPTH24_STENCIL8, GL_DEPTH32F_STENCIL8, GL_DEPTH_COMPONENT16,
                                      GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT32F};
    const int w = 128, h = 96;
    GLuint vao;
    int k;
    g_slope = program(vs, fs, NULL);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    for (k = 0; k < 5; k++) {
        host_fb f;
        snell_renderer *r;
        int all, kept;
        snell_status st;
        fb_make(&f, GL_RGBA8, formats[k], w, h);
        r = renderer(w, h, 0);
        glClearColor(0, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        slope(GL_ALWAYS, 0);
        slope(GL_EQUAL, 1);
        all = count_white(w, h);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        slope(GL_ALWAYS, 0);
        glBindVertexArray(0);
        st = frame(r, SNELL_DEPTH_TEST_NO_WRITE, NULL);
        CHECK(st == SNELL_OK, "NO_WRITE on 0x%x: %s", formats[k], snell_last_error(g_ctx));
        glBindVertexArray(vao);
        glClear(GL_COLOR_BUFFER_BIT);
        slope(GL_EQUAL, 1);
        kept = count_white(w, h);
        CHECK(all == w * h && kept == all, "NO_WRITE on 0x%x: %d of %d depths given back exactly", formats[k], kept,
              all);
        snell_renderer_destroy(r);
        fb_free(&f);
    }
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(g_slope);
    CHECK(glGetError() == GL_NO_ERROR, "GL error in the NO_WRITE cases");
}


#ifdef SNELL_WITH_HOST_FRAMEBUFFERS
/* ------------------------------------------------ framebuffers snell cannot draw into */
static void expect_refusal(snell_renderer *r, const char *what, const char *part, snell_backdrop *bd)
{
    snell_status st = frame(r, SNELL_DEPTH_TEST, bd);
    GLenum e = glGetError();
    CHECK(st != SNELL_OK && strstr(snell_last_error(g_ctx), part) != NULL, "%s: %s (%s), wanted a refusal naming "
          "\"%s\"", what, snell_status_str(st), snell_last_error(g_ctx), part);
    CHECK(e == GL_NO_ERROR, "%s: the refusal left GL error 0x%x", what, e);
}

/* A framebuffer smaller than the frame is named (renderbuffers; textures
 * where the context is GLES 3.1, which can ask a level's size); a larger
 * one is drawn into, its corner. */
static void check_sizes(snell_renderer *r)
{
    host_fb f;
    GLuint tex, small_depth;
    GLint minor = 0;
    fb_make(&f, GL_RGBA8, GL_DEPTH_COMPONENT24, W / 2, H / 2);
    glViewport(0, 0, W, H);
    expect_refusal(r, "a colour renderbuffer smaller than the renderer", "colour buffer is 32x24", NULL);
    fb_free(&f);
    fb_make(&f, GL_RGBA8, 0, W, H);
    glGenRenderbuffers(1, &small_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, small_depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, W / 2, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, small_depth);
    expect_refusal(r, "a depth renderbuffer narrower than the renderer", "depth buffer is 32x48", NULL);
    glDeleteRenderbuffers(1, &small_depth);
    fb_free(&f);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    fb_make(&f, 0, GL_DEPTH_COMPONENT24, W, H / 2);
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, W, H / 2);
    glBindTexture(GL_TEXTURE_2D, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glViewport(0, 0, W, H);
    if (minor >= 1) expect_refusal(r, "a colour texture shorter than the renderer", "colour buffer is 64x24", NULL);
    else printf("a GLES 3.0 context: a texture's size cannot be asked (not checked)\n");
    glDeleteTextures(1, &tex);
    fb_free(&f);
    fb_make(&f, GL_RGBA8, GL_DEPTH_COMPONENT24, 2 * W, 2 * H);
    CHECK(frame(r, SNELL_DEPTH_TEST, NULL) == SNELL_OK, "a framebuffer larger than the renderer: %s",
          snell_last_error(g_ctx));
    CHECK(glGetError() == GL_NO_ERROR, "a larger framebuffer: GL error");
    fb_free(&f);
}

static void check_refusals(void)
{
    host_fb f;
    snell_renderer *r = renderer(W, H, 0), *pre = renderer(W, H, 1);
    snell_backdrop bd;
    GLuint cube;
    fb_make(&f, 0, 0, W, H);
    expect_refusal(r, "a framebuffer with no attachment", "not complete", NULL);
    fb_free(&f);
    fb_make(&f, GL_RGBA8, 0, W, H);
    expect_refusal(r, "a framebuffer without depth", "no depth buffer", NULL);
    fb_free(&f);
    fb_make(&f, GL_RGBA8UI, GL_DEPTH_COMPONENT24, W, H);
    expect_refusal(r, "an integer colour buffer", "has an integer colour buffer", NULL);
    fb_free(&f);
    fb_make(&f, GL_RGB8, GL_DEPTH_COMPONENT24, W, H);
    expect_refusal(pre, "premultiplied alpha into RGB8", "lacks alpha (premultiplied_alpha)", NULL);
    fb_free(&f);
    fb_make(&f, GL_RGBA8, GL_DEPTH_COMPONENT24, W, H);
    glGenTextures(1, &cube);
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
    glTexStorage2D(GL_TEXTURE_CUBE_MAP, 1, GL_RGBA8, W, W);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    memset(&bd, 0, sizeof bd);
    bd.source = SNELL_BACKDROP_TEXTURES, bd.color_texture = cube, bd.width = W, bd.height = H;
    expect_refusal(r, "a cube map as the backdrop's colour", "backdrop.color_texture", &bd);
    CHECK(strstr(snell_last_error(g_ctx), "not a GL_TEXTURE_2D") != NULL, "the message names the target: %s",
          snell_last_error(g_ctx));
    glDeleteTextures(1, &cube);
    fb_free(&f);
    check_sizes(r);
    snell_renderer_destroy(r);
    snell_renderer_destroy(pre);
}

/* ------------------------------------------------ MRT: only draw buffer 0 written; COPY_BOUND from it */
static void pixel_of(GLenum buffer, int x, int y, uint8_t out[4])
{
    GLint prev = 0;
    glGetIntegerv(GL_READ_BUFFER, &prev);
    glReadBuffer(buffer);
    glReadPixels(x, y, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, out);
    glReadBuffer((GLenum)prev);
}

static void check_mrt(void)
{
    static const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    static const float red[4] = {0.9f, 0.05f, 0.05f, 1.0f}, green[4] = {0.05f, 0.9f, 0.05f, 1.0f};
    host_fb f;
    GLuint rb1;
    GLint db1 = GL_NONE, read = GL_NONE;
    snell_renderer *r = renderer(W, H, 0);
    snell_backdrop bd;
    snell_frame_desc fd;
    snell_glass g;
    uint8_t c0[4], c1[4];
    int x, y, changed1 = 0;
    fb_make(&f, GL_RGBA8, GL_DEPTH_COMPONENT24, W, H);
    glGenRenderbuffers(1, &rb1);
    glBindRenderbuffer(GL_RENDERBUFFER, rb1);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, rb1);
    glDrawBuffers(2, both);
    glClearBufferfv(GL_COLOR, 0, red);
    glClearBufferfv(GL_COLOR, 1, green);
    glClear(GL_DEPTH_BUFFER_BIT);
    CHECK(frame(r, SNELL_DEPTH_TEST, NULL) == SNELL_OK, "MRT frame: %s", snell_last_error(g_ctx));
    for (y = 0; y < H; y += 4)
        for (x = 0; x < W; x += 4) {
            pixel_of(GL_COLOR_ATTACHMENT1, x, y, c1);
            changed1 += c1[0] != 13 || c1[1] != 230 || c1[2] != 13;
        }
    pixel_of(GL_COLOR_ATTACHMENT0, W / 2, H / 2, c0);
    glGetIntegerv(GL_DRAW_BUFFER1, &db1);
    CHECK(changed1 == 0, "attachment 1 (not drawn to) changed at %d sampled pixels", changed1);
    CHECK(c0[0] != 230 || c0[1] != 13, "attachment 0 got no glass");
    CHECK(db1 == GL_COLOR_ATTACHMENT1, "the host's draw buffer 1 back: 0x%x", db1);

    /* COPY_BOUND reads draw buffer 0 (red), not the host's read buffer (green). */
    glDrawBuffers(1, both);
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glClearBufferfv(GL_COLOR, 0, red);
    glDrawBuffers(2, both);
    glClearBufferfv(GL_COLOR, 1, green);
    glDrawBuffers(1, both);
    glClearDepthf(0.999f); /* a wall far behind the glass (depth 1 is the sky: the environment) */
    glClear(GL_DEPTH_BUFFER_BIT);
    glClearDepthf(1.0f);
    memset(&fd, 0, sizeof fd);
    memset(&g, 0, sizeof g);
    memset(&bd, 0, sizeof bd);
    g.mesh = g_mesh;
    fd.glass = &g, fd.glass_count = 1, fd.env = g_env, fd.draw_background = -1;
    bd.source = SNELL_BACKDROP_COPY_BOUND;
    fd.backdrop = &bd;
    CHECK(snell_render(r, &fd, NULL) == SNELL_OK, "COPY_BOUND frame: %s", snell_last_error(g_ctx));
    pixel_of(GL_COLOR_ATTACHMENT0, W / 2, H / 2, c0);
    glGetIntegerv(GL_READ_BUFFER, &read);
    CHECK(c0[0] > 2 * c0[1], "the glass refracts %d,%d,%d: the drawn-into buffer is red, the read buffer green",
          c0[0], c0[1], c0[2]);
    CHECK(read == GL_COLOR_ATTACHMENT1, "the host's read buffer back: 0x%x", read);
    CHECK(glGetError() == GL_NO_ERROR, "GL error in the MRT cases");
    glDeleteRenderbuffers(1, &rb1);
    fb_free(&f);
    snell_renderer_destroy(r);
}

/* ------------------------------------------------ sRGB: snell's colour encoded once */
static float linear_of(float c) { return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f); }

/* The frame into a fresh W x H target of the colour format, the host's
 * scene stored as the bytes 51, 102, 153 (cleared in linear values on sRGB). */
static int srgb_frame(GLenum format, int copy_bound, uint8_t *px)
{
    host_fb f;
    snell_renderer *r = renderer(W, H, 0);
    snell_backdrop bd;
    snell_frame_desc fd;
    snell_glass g;
    snell_status st;
    float c[3] = {0.2f, 0.4f, 0.6f};
    int k;
    if (format == GL_SRGB8_ALPHA8)
        for (k = 0; k < 3; k++) c[k] = linear_of(c[k]);
    fb_make(&f, format, GL_DEPTH_COMPONENT24, W, H);
    glClearColor(c[0], c[1], c[2], 1.0f);
    glClearDepthf(0.999f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glClearColor(0, 0, 0, 0);
    glClearDepthf(1.0f);
    memset(&fd, 0, sizeof fd);
    memset(&g, 0, sizeof g);
    memset(&bd, 0, sizeof bd);
    g.mesh = g_mesh;
    fd.glass = &g, fd.glass_count = 1, fd.env = g_env, fd.draw_background = SNELL_BACKGROUND_NONE;
    bd.source = SNELL_BACKDROP_COPY_BOUND;
    fd.backdrop = copy_bound ? &bd : NULL;
    st = snell_render(r, &fd, NULL);
    CHECK(st == SNELL_OK, "frame into format 0x%x: %s", format, snell_last_error(g_ctx));
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
    snell_renderer_destroy(r);
    fb_free(&f);
    return st == SNELL_OK;
}

static void check_srgb(void)
{
    static uint8_t a[W * H * 4], b[W * H * 4];
    int copy;
    GLint enc = 0;
    if (!snell_ctx_has_gl_extension(g_ctx, "GL_EXT_sRGB_write_control")) { /* the GL's or a device profile's */
        host_fb f;
        snell_renderer *r = renderer(W, H, 0);
        fb_make(&f, GL_SRGB8_ALPHA8, GL_DEPTH_COMPONENT24, W, H);
        expect_refusal(r, "an sRGB target without GL_EXT_sRGB_write_control", "no GL_EXT_sRGB_write_control", NULL);
        snell_renderer_destroy(r);
        fb_free(&f);
        return;
    }
    for (copy = 0; copy < 2; copy++) {
        int i, worst = 0, glass = 0;
        if (!srgb_frame(GL_RGBA8, copy, a) || !srgb_frame(GL_SRGB8_ALPHA8, copy, b)) continue;
        for (i = 0; i < W * H * 4; i++) {
            int d = abs((int)a[i] - (int)b[i]);
            worst = d > worst ? d : worst;
        }
        for (i = 0; i < W * H; i++) glass += a[4 * i] != 51 || a[4 * i + 1] != 102;
        CHECK(glass > W * H / 20 && worst <= 2, "%s: the sRGB target's bytes differ from RGBA8's by up to %d (%d glass "
              "pixels): snell's colour must be encoded once", copy ? "COPY_BOUND" : "no backdrop", worst, glass);
    }
    glGetIntegerv(GL_FRAMEBUFFER_SRGB_EXT, &enc);
    CHECK(enc == 1, "the host's GL_FRAMEBUFFER_SRGB_EXT back on: %d", enc);
}

/* ------------------------------------------------ the host's viewport: two eyes side by side */
static int eye(int x, int w, uint8_t *px, int read_w)
{
    snell_renderer *r = renderer(W, H, 0);
    snell_status st;
    glViewport(x, 0, W, H);
    st = frame(r, SNELL_DEPTH_TEST, NULL);
    snell_renderer_destroy(r);
    CHECK(st == SNELL_OK, "an eye at x %d: %s", x, snell_last_error(g_ctx));
    glReadPixels(0, 0, read_w, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
    (void)w;
    return st == SNELL_OK;
}

static void check_viewport(void)
{
    static uint8_t alone[W * H * 4], both[2 * W * H * 4];
    host_fb f;
    snell_renderer *r = renderer(W, H, 0);
    GLint vp[4];
    int x, y, worst = 0, touched = 0;
    fb_make(&f, GL_RGBA8, GL_DEPTH_COMPONENT24, W, H);
    glClearColor(0.2f, 0.4f, 0.6f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (!eye(0, W, alone, W)) goto done;
    fb_free(&f);
    fb_make(&f, GL_RGBA8, GL_DEPTH_COMPONENT24, 2 * W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (!eye(0, W, both, 2 * W)) goto done;
    for (y = 0; y < H; y++)
        for (x = W; x < 2 * W; x++) touched += both[4 * (y * 2 * W + x)] != 51;
    CHECK(touched == 0, "the left eye drew %d pixels into the right one", touched);
    if (!eye(W, W, both, 2 * W)) goto done;
    glGetIntegerv(GL_VIEWPORT, vp);
    CHECK(vp[0] == W && vp[2] == W, "the host's viewport back: %d,%d %dx%d", vp[0], vp[1], vp[2], vp[3]);
    for (y = 0; y < H; y++)
        for (x = 0; x < 2 * W; x++) {
            int k, d;
            for (k = 0; k < 4; k++) {
                d = abs((int)both[4 * (y * 2 * W + x) + k] - (int)alone[4 * (y * W + x % W) + k]);
                worst = d > worst ? d : worst;
            }
        }
    CHECK(worst <= 1, "each eye of the side-by-side frame differs from the frame alone by up to %d", worst);
    glViewport(1, 0, W + 1, H);
    CHECK(frame(r, SNELL_DEPTH_TEST, NULL) != SNELL_OK && strstr(snell_last_error(g_ctx), "the viewport is 65x48"),
          "a viewport of another size than the renderer: %s", snell_last_error(g_ctx));
    CHECK(glGetError() == GL_NO_ERROR, "GL error in the viewport cases");
done:
    glViewport(0, 0, W, H);
    glClearColor(0, 0, 0, 0);
    snell_renderer_destroy(r);
    fb_free(&f);
}
#endif

int main(void)
{
    EGLDisplay dpy;
    EGLContext host;
    snell_ctx_desc d;
    snell_shape_desc sd;
    snell_env_desc ed;
    if (!test_host_context(&dpy, &host)) {
        printf("SKIP: cannot make a host context here\n");
        return 77;
    }
    memset(&d, 0, sizeof d);
    memset(&sd, 0, sizeof sd);
    memset(&ed, 0, sizeof ed);
    d.backend = SNELL_BACKEND_EXTERNAL;
    ed.face_size = 16;
    CHECK_OK(snell_ctx_create(&d, &g_ctx));
    CHECK_OK_CTX(g_ctx, snell_mesh_create_shape(g_ctx, &sd, &g_mesh));
    CHECK_OK_CTX(g_ctx, snell_env_create(g_ctx, &ed, &g_env));
    if (!g_ctx || !g_mesh || !g_env) return test_finish();
    check_pending_errors();
    check_pending_errors_elsewhere();
    check_transform_feedback();
    check_no_write_exact();
#ifdef SNELL_WITH_HOST_FRAMEBUFFERS
    check_refusals();
    check_mrt();
    check_srgb();
    check_viewport();
#else
    printf("a build without SNELL_WITH_HOST_FRAMEBUFFERS: the bound framebuffer is not checked\n");
#endif
    snell_env_destroy(g_env);
    snell_mesh_destroy(g_mesh);
    snell_ctx_destroy(g_ctx);
    check_debug_callback();
    CHECK(glGetError() == GL_NO_ERROR, "GL error at the end");
    return test_finish();
}
