/* SPDX-License-Identifier: MIT */
/* test_host — the library in the hands of a careless host (issue 14): objects
 * of one context used in another (3), host GL state that must not change the
 * output of an EXTERNAL frame and must come back as it was (4), host pixel
 * buffers bound around uploads and read-backs (5), objects destroyed after
 * their context (8), NULL and non-finite environment lookups (9), camera and
 * model values (10), and a second owned context on the same thread. */
#include "test_util.h"
#include "gl_count.h"
#include "snell/snell_2d.h"
#include "snell/snell_water.h"

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

#define W 48
#define H 48

/* ------------------------------------------------------------------ helpers */

static snell_mesh *shape(snell_ctx *ctx, snell_shape s)
{
    snell_mesh *m = NULL;
    snell_shape_desc sd;
    memset(&sd, 0, sizeof sd);
    sd.shape = s;
    sd.segments = 24;
    sd.rings = 12;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &m));
    return m;
}

static snell_env *env16(snell_ctx *ctx)
{
    snell_env *e = NULL;
    snell_env_desc ed;
    memset(&ed, 0, sizeof ed);
    ed.face_size = 16;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &e));
    return e;
}

static snell_renderer *renderer(snell_ctx *ctx, snell_shading shading)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.shading = shading;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    return r;
}

static int has(const char *msg, const char *part)
{
    return msg && strstr(msg, part) != NULL;
}

/* Expects status st from call and a message containing part. */
#define CHECK_FAILS(ctx, call, want, part)                                                                    \
    do {                                                                                                      \
        snell_status s_ = (call);                                                                             \
        CHECK(s_ == (want) && has(snell_last_error(ctx), part), "%s: got %s \"%s\", want %s with \"%s\"",     \
              #call, snell_status_str(s_), snell_last_error(ctx), snell_status_str(want), part);              \
    } while (0)

/* A counting allocator: live blocks of a context and what it made. */
static long g_live;
static void *count_alloc(size_t n, void *u) { (void)u; g_live++; return malloc(n); }
static void *count_realloc(void *p, size_t n, void *u)
{
    (void)u;
    if (!p) g_live++;
    return realloc(p, n);
}
static void count_free(void *p, void *u) { (void)u; if (p) g_live--; free(p); }

static snell_ctx *owned_ctx(int counting)
{
    snell_ctx *ctx = NULL;
    snell_ctx_desc d;
    memset(&d, 0, sizeof d);
    if (counting) {
        d.allocator.alloc = count_alloc;
        d.allocator.realloc = count_realloc;
        d.allocator.free = count_free;
    }
    CHECK_OK(snell_ctx_create(&d, &ctx));
    return ctx;
}

/* ------------------------------------------------------- 9: env_sample */

static void check_env_sample(void)
{
    snell_env *env = NULL;
    snell_env_desc ed;
    float rgb[3] = {1, 1, 1}, dir[3] = {0, 1, 0};
    double rgbd[3] = {1, 1, 1}, dird[3] = {0, 1, 0};
    const float nan = (float)NAN, inf = (float)INFINITY;
    const float bad[4][3] = {{nan, 0, 0}, {0, nan, 1}, {inf, 0, 0}, {0, 0, -inf}};
    int i;
    memset(&ed, 0, sizeof ed);
    ed.face_size = 8;
    CHECK_OK(snell_env_create(NULL, &ed, &env));
    snell_env_sample(NULL, dir, rgb);
    CHECK(rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0, "env_sample(NULL) gives %g %g %g, want black", rgb[0], rgb[1],
          rgb[2]);
    snell_env_sample_d(NULL, dird, rgbd);
    CHECK(rgbd[0] == 0 && rgbd[1] == 0 && rgbd[2] == 0, "env_sample_d(NULL) not black");
    snell_env_sample(env, NULL, rgb);
    CHECK(rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0, "env_sample(env, NULL dir) not black");
    snell_env_sample(env, dir, NULL); /* nothing to write: no crash */
    snell_env_sample(env, dir, rgb);
    CHECK(rgb[0] + rgb[1] + rgb[2] > 0.0f, "a real direction must see the sky");
    for (i = 0; i < 4; i++) {
        double bd[3] = {bad[i][0], bad[i][1], bad[i][2]};
        rgb[0] = rgb[1] = rgb[2] = 0.5f;
        snell_env_sample(env, bad[i], rgb);
        CHECK(rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0, "non-finite direction %d gives %g %g %g, want black", i,
              rgb[0], rgb[1], rgb[2]);
        rgbd[0] = rgbd[1] = rgbd[2] = 0.5;
        snell_env_sample_d(env, bd, rgbd);
        CHECK(rgbd[0] == 0 && rgbd[1] == 0 && rgbd[2] == 0, "double: non-finite direction %d not black", i);
    }
    snell_env_destroy(env);
}

/* ------------------------------------- 3 + "Also": two contexts, one thread */

static void frame_of(snell_frame_desc *fd, snell_glass *g, const snell_mesh *m, const snell_env *e)
{
    test_frame_one(fd, g, m, e);
    g->material.method = SNELL_METHOD_SINGLE;
}

static void check_two_contexts(void)
{
    snell_ctx *a, *b;
    snell_env *env_a, *env_b, *env_x = NULL;
    snell_mesh *mesh_a, *mesh_b, *cpu;
    snell_renderer *r_a, *r_b, *r_x = NULL;
    snell_frame_desc fd;
    snell_glass g;
    snell_opaque op;
    snell_env_desc ed;

    a = owned_ctx(0);
    if (!a) return;
    env_a = env16(a);
    mesh_a = shape(a, SNELL_SHAPE_SPHERE);
    r_a = renderer(a, SNELL_SHADING_AUTO);
    cpu = shape(NULL, SNELL_SHAPE_CUBE);
    b = owned_ctx(0); /* now current: a is not */
    if (!b) return;

    /* "Also": a's calls say that a is not current, not a misleading GL error. */
    frame_of(&fd, &g, mesh_a, env_a);
    CHECK_FAILS(a, snell_render(r_a, &fd, NULL), SNELL_E_INVALID_ARG, "snell_ctx_make_current");
    memset(&ed, 0, sizeof ed);
    ed.face_size = 8;
    CHECK_FAILS(a, snell_env_create(a, &ed, &env_x), SNELL_E_INVALID_ARG, "not current");
    CHECK(env_x == NULL, "no environment on failure");
    CHECK_FAILS(a, snell_renderer_create(a, NULL, &r_x), SNELL_E_INVALID_ARG, "not current");
    CHECK(r_x == NULL, "no renderer on failure");
    CHECK_FAILS(NULL, snell_ctx_make_current(NULL), SNELL_E_INVALID_ARG, "NULL");

    env_b = env16(b);
    mesh_b = shape(b, SNELL_SHAPE_SPHERE);
    r_b = renderer(b, SNELL_SHADING_AUTO);

    /* 3: objects of a in a frame of b. */
    frame_of(&fd, &g, mesh_a, env_b);
    CHECK_FAILS(b, snell_render(r_b, &fd, NULL), SNELL_E_INVALID_ARG, "another context");
    frame_of(&fd, &g, mesh_b, env_a);
    CHECK_FAILS(b, snell_render(r_b, &fd, NULL), SNELL_E_INVALID_ARG, "another context");
    memset(&op, 0, sizeof op);
    op.mesh = mesh_a;
    frame_of(&fd, &g, mesh_b, env_b);
    fd.opaque = &op;
    fd.opaque_count = 1;
    CHECK_FAILS(b, snell_render(r_b, &fd, NULL), SNELL_E_INVALID_ARG, "another context");

    /* A CPU-only mesh is drawn in b first: its GPU buffers live in b. */
    frame_of(&fd, &g, cpu, env_b);
    CHECK_OK_CTX(b, snell_render(r_b, &fd, NULL));
    op.mesh = cpu;
    frame_of(&fd, &g, mesh_b, env_b);
    fd.opaque = &op;
    fd.opaque_count = 1;
    CHECK_OK_CTX(b, snell_render(r_b, &fd, NULL));

    /* ... so a must refuse it, as glass and as an opaque object. */
    CHECK_OK_CTX(a, snell_ctx_make_current(a));
    frame_of(&fd, &g, cpu, env_a);
    CHECK_FAILS(a, snell_render(r_a, &fd, NULL), SNELL_E_INVALID_ARG, "another context");
    frame_of(&fd, &g, mesh_a, env_a);
    fd.opaque = &op;
    fd.opaque_count = 1;
    CHECK_FAILS(a, snell_render(r_a, &fd, NULL), SNELL_E_INVALID_ARG, "another context");
    /* a's own objects still draw after the refusals. */
    frame_of(&fd, &g, mesh_a, env_a);
    CHECK_OK_CTX(a, snell_render(r_a, &fd, NULL));

    /* Destroyed while a is current: deleted in b (made current for it), and a stays current. */
    snell_mesh_destroy(cpu);
    CHECK_OK_CTX(a, snell_render(r_a, &fd, NULL));
    snell_renderer_destroy(r_a);
    snell_mesh_destroy(mesh_a);
    snell_env_destroy(env_a);
    snell_ctx_destroy(a);
    CHECK_OK_CTX(b, snell_ctx_make_current(b));
    frame_of(&fd, &g, mesh_b, env_b);
    CHECK_OK_CTX(b, snell_render(r_b, &fd, NULL));
    snell_renderer_destroy(r_b);
    snell_mesh_destroy(mesh_b);
    snell_env_destroy(env_b);
    snell_ctx_destroy(b);
}

/* --------------------------------------------------------- 8: destroy order */

static int render_read(snell_ctx *ctx, snell_renderer *r, const snell_frame_desc *fd, uint8_t *px)
{
    snell_status s = snell_render(r, fd, NULL);
    CHECK(s == SNELL_OK, "render: %s %s", snell_status_str(s), snell_last_error(ctx));
    if (s != SNELL_OK) return 0;
    s = snell_renderer_read_rgba(r, px);
    CHECK(s == SNELL_OK, "read: %s %s", snell_status_str(s), snell_last_error(ctx));
    return s == SNELL_OK;
}

static void check_destroy_order(void)
{
    snell_ctx *ctx, *a, *b;
    snell_env *env, *env_a, *env_b;
    snell_mesh *mesh, *mesh_a, *mesh_b, *cpu;
    snell_renderer *r, *r_a, *r_b;
    snell_ref *ref = NULL;
    snell_ref_desc rdesc;
    snell_scene2d *s2 = NULL;
    snell_lightmap2d *lm = NULL;
    snell_lightmap2d_desc ld;
    snell_frame_desc fd;
    snell_glass g;
    gl_counts before, after;
    static uint8_t img1[W * H * 4], img2[W * H * 4], px[W * H * 4];

    /* Every kind of object outlives its context. */
    g_live = 0;
    ctx = owned_ctx(1);
    if (!ctx) return;
    env = env16(ctx);
    mesh = shape(ctx, SNELL_SHAPE_SPHERE);
    cpu = shape(NULL, SNELL_SHAPE_CUBE);
    r = renderer(ctx, SNELL_SHADING_AUTO);
    test_frame_one(&fd, &g, mesh, env);
    memset(&rdesc, 0, sizeof rdesc);
    rdesc.glass = &g;
    rdesc.glass_count = 1;
    CHECK_OK_CTX(ctx, snell_ref_create(ctx, &rdesc, &ref));
    CHECK_OK_CTX(ctx, snell_scene2d_create(ctx, &s2));
    memset(&ld, 0, sizeof ld);
    ld.width = ld.height = 16;
    ld.view_min[0] = ld.view_min[1] = -1.0f;
    ld.view_max[0] = ld.view_max[1] = 1.0f;
    ld.threads = 1;
    CHECK_OK_CTX(ctx, snell_lightmap2d_create(ctx, &ld, &lm));
    render_read(ctx, r, &fd, px);
    test_frame_one(&fd, &g, cpu, env); /* cpu bound to ctx, buffers uploaded there */
    render_read(ctx, r, &fd, px);
    snell_ctx_destroy(ctx);
    CHECK(eglGetCurrentContext() == EGL_NO_CONTEXT, "an owned context released on destroy");
    CHECK(g_live > 0, "the context's memory lives while its objects do");
    /* Use after the context: a clear error, no GL, no crash (ASan). */
    CHECK_FAILS(ctx, snell_render(r, &fd, NULL), SNELL_E_INVALID_ARG, "destroyed");
    CHECK_FAILS(ctx, snell_renderer_read_rgba(r, px), SNELL_E_INVALID_ARG, "destroyed");
    snell_renderer_destroy(r);
    snell_mesh_destroy(cpu);
    snell_lightmap2d_destroy(lm);
    snell_ref_destroy(ref);
    snell_mesh_destroy(mesh);
    snell_scene2d_destroy(s2);
    CHECK(g_live > 0, "one object (env) still alive");
    snell_env_destroy(env);
    CHECK(g_live == 0, "%ld blocks of the context's allocator still live after its last object", g_live);

    /* a's renderer destroyed after a, with b current: b's GL objects (the same
     * names: each context counts from 1) must survive, b stays current. */
    a = owned_ctx(0);
    if (!a) return;
    env_a = env16(a);
    mesh_a = shape(a, SNELL_SHAPE_SPHERE);
    r_a = renderer(a, SNELL_SHADING_AUTO);
    test_frame_one(&fd, &g, mesh_a, env_a);
    g.material.method = SNELL_METHOD_CUBEMAP;
    render_read(a, r_a, &fd, px);
    b = owned_ctx(0);
    if (!b) return;
    env_b = env16(b);
    mesh_b = shape(b, SNELL_SHAPE_SPHERE);
    r_b = renderer(b, SNELL_SHADING_AUTO);
    test_frame_one(&fd, &g, mesh_b, env_b);
    g.material.method = SNELL_METHOD_CUBEMAP;
    render_read(b, r_b, &fd, img1);
    before = gl_count_objects();
    snell_ctx_destroy(a);
    snell_renderer_destroy(r_a);
    snell_mesh_destroy(mesh_a);
    snell_env_destroy(env_a);
    after = gl_count_objects();
    gl_counts_print(stdout, "b before a's objects went", &before);
    CHECK(gl_counts_equal(&before, &after), "destroying a's objects after a changed b's GL objects");
    if (render_read(b, r_b, &fd, img2))
        CHECK(memcmp(img1, img2, sizeof img1) == 0, "b's frame changed after a's objects were destroyed");

    /* a alive but not current: its objects are deleted in a, b stays current. */
    a = owned_ctx(0);
    if (!a) return;
    env_a = env16(a);
    mesh_a = shape(a, SNELL_SHAPE_SPHERE);
    r_a = renderer(a, SNELL_SHADING_AUTO);
    test_frame_one(&fd, &g, mesh_a, env_a);
    g.material.method = SNELL_METHOD_CUBEMAP;
    render_read(a, r_a, &fd, px);
    CHECK_OK_CTX(b, snell_ctx_make_current(b));
    before = gl_count_objects();
    snell_renderer_destroy(r_a);
    snell_mesh_destroy(mesh_a);
    snell_env_destroy(env_a);
    after = gl_count_objects();
    CHECK(gl_counts_equal(&before, &after), "destroying a's objects while b is current changed b's GL objects");
    test_frame_one(&fd, &g, mesh_b, env_b);
    g.material.method = SNELL_METHOD_CUBEMAP;
    if (render_read(b, r_b, &fd, img2))
        CHECK(memcmp(img1, img2, sizeof img1) == 0, "b's frame changed after a's objects were destroyed");
    CHECK_OK_CTX(a, snell_ctx_make_current(a));
    after = gl_count_objects();
    CHECK(after.textures == 0 && after.buffers == 0 && after.programs == 0 && after.framebuffers == 0,
          "a's objects were not deleted in a: %d textures, %d buffers, %d programs, %d framebuffers left",
          after.textures, after.buffers, after.programs, after.framebuffers);
    snell_ctx_destroy(a);
    snell_renderer_destroy(r_b);
    snell_mesh_destroy(mesh_b);
    snell_env_destroy(env_b);
    snell_ctx_destroy(b);
}

/* ----------------------------------------------------- 10: camera, models */

static void check_camera(void)
{
    snell_ctx *ctx = owned_ctx(0);
    snell_env *env;
    snell_mesh *mesh;
    snell_renderer *r;
    snell_frame_desc fd;
    snell_glass g;
    snell_opaque op;
    snell_ref *ref = NULL;
    snell_ref_params rp;
    static float rgb[4 * 4 * 3];
    const float nan = (float)NAN, inf = (float)INFINITY;
    float zero_scale[16] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
    float tiny[16] = {1e-15f, 0, 0, 0, 0, 1e-15f, 0, 0, 0, 0, 1e-15f, 0, 0, 0, 0, 1};
    struct {
        const char *field;
        snell_camera cam;
    } bad[16];
    int n = 0, i;
    if (!ctx) return;
    memset(bad, 0, sizeof bad);
    bad[n].field = "camera.distance", bad[n++].cam.distance = inf;
    bad[n].field = "camera.distance", bad[n++].cam.distance = nan;
    bad[n].field = "camera.distance", bad[n++].cam.distance = -2.0f;
    bad[n].field = "camera.distance", bad[n++].cam.distance = 1e37f; /* far plane 1e39 overflows */
    bad[n].field = "camera.target", bad[n++].cam.target[1] = nan;
    bad[n].field = "camera.elevation", bad[n++].cam.elevation = nan;
    bad[n].field = "camera.azimuth", bad[n++].cam.azimuth = inf;
    bad[n].field = "camera.z_far", bad[n++].cam.z_far = inf;
    bad[n].field = "camera.fov_y", bad[n++].cam.fov_y = 3.14159274f; /* (float)pi */
    bad[n].field = "camera.fov_y", bad[n++].cam.fov_y = 4.0f;
    bad[n].field = "camera.fov_y", bad[n++].cam.fov_y = -0.5f;
    bad[n].field = "camera.z_near", bad[n].cam.z_near = 2.0f, bad[n++].cam.z_far = 1.0f;
    bad[n].field = "camera.z_near", bad[n].cam.z_near = 2.0f, bad[n++].cam.z_far = 2.0f;
    bad[n].field = "camera.z_near", bad[n++].cam.z_near = 1000.0f; /* beyond the derived far plane 350 */
    bad[n].field = "camera.z_near", bad[n++].cam.z_near = nan;
    env = env16(ctx);
    mesh = shape(ctx, SNELL_SHAPE_SPHERE);
    r = renderer(ctx, SNELL_SHADING_AUTO);
    test_frame_one(&fd, &g, mesh, env);
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK_CTX(ctx, test_ref_create(ctx, &fd, &ref));
    for (i = 0; i < n; i++) {
        fd.camera = bad[i].cam;
        CHECK_FAILS(ctx, snell_render(r, &fd, NULL), SNELL_E_INVALID_ARG, bad[i].field);
        if (ref) {
            test_ref_params(&fd, 4, 4, 2, &rp);
            CHECK_FAILS(ctx, test_ref_render(ref, &rp, rgb, NULL, NULL), SNELL_E_INVALID_ARG, bad[i].field);
        }
    }
    /* Values at the edges of the valid ranges still render. */
    memset(&fd.camera, 0, sizeof fd.camera);
    fd.camera.fov_y = 3.0f;
    fd.camera.z_near = 0.5f;
    fd.camera.z_far = 0.6f;
    fd.camera.elevation = 1.5707964f;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    memset(&fd.camera, 0, sizeof fd.camera);
    g.model = zero_scale;
    CHECK_FAILS(ctx, snell_render(r, &fd, NULL), SNELL_E_INVALID_ARG, "glass 0: model matrix is singular");
    g.model = tiny;
    CHECK_FAILS(ctx, snell_render(r, &fd, NULL), SNELL_E_INVALID_ARG, "glass 0: model matrix is singular");
    g.model = NULL;
    memset(&op, 0, sizeof op);
    op.mesh = mesh;
    op.model = zero_scale;
    fd.opaque = &op;
    fd.opaque_count = 1;
    CHECK_FAILS(ctx, snell_render(r, &fd, NULL), SNELL_E_INVALID_ARG, "opaque object 0: model matrix is singular");
    op.model = NULL;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    snell_ref_destroy(ref);
    snell_renderer_destroy(r);
    snell_mesh_destroy(mesh);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
}

/* -------------------------------------------------- 4 + 5: EXTERNAL state */


#define UNITS 16 /* texture units the library uses: SNELL_GLSTATE_UNITS (core/glstate.h) */

typedef struct host_objects {
    GLuint sampler, pack_pbo, unpack_pbo, fbo_draw, fbo_read, rb, tex[UNITS];
} host_objects;

/* One piece of host state: set to an odd value, and checked to be that value still. */
typedef struct piece {
    const char *name;
    void (*set)(const host_objects *h);
    int (*kept)(const host_objects *h);
    int fresh_env;          /* create the environment under this state (uploads) */
} piece;

static GLint geti(GLenum e) { GLint v = 0; glGetIntegerv(e, &v); return v; }

static void set_samplers(const host_objects *h)
{
    int u;
    for (u = 0; u < UNITS; u++) glBindSampler((GLuint)u, h->sampler);
}
static int kept_samplers(const host_objects *h)
{
    int u, ok = 1;
    for (u = 0; u < UNITS; u++) {
        glActiveTexture((GLenum)(GL_TEXTURE0 + u));
        ok &= geti(GL_SAMPLER_BINDING) == (GLint)h->sampler;
    }
    glActiveTexture(GL_TEXTURE3);
    return ok;
}
static void set_depth_range(const host_objects *h) { (void)h; glDepthRangef(0.5f, 0.5f); }
static int kept_depth_range(const host_objects *h)
{
    GLfloat r[2];
    (void)h;
    glGetFloatv(GL_DEPTH_RANGE, r);
    return r[0] == 0.5f && r[1] == 0.5f;
}
static void set_stencil(const host_objects *h)
{
    (void)h;
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_NEVER, 1, 0xff);
    glStencilOp(GL_ZERO, GL_ZERO, GL_ZERO);
}
static int kept_stencil(const host_objects *h)
{
    (void)h;
    return glIsEnabled(GL_STENCIL_TEST) && geti(GL_STENCIL_FUNC) == GL_NEVER && geti(GL_STENCIL_FAIL) == GL_ZERO;
}
static void set_polygon_offset(const host_objects *h)
{
    (void)h;
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(4.0f, 1000.0f);
}
static int kept_polygon_offset(const host_objects *h)
{
    GLfloat f = 0, u = 0;
    (void)h;
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &f);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &u);
    return glIsEnabled(GL_POLYGON_OFFSET_FILL) && f == 4.0f && u == 1000.0f;
}
static void set_color_mask(const host_objects *h) { (void)h; glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE); }
static int kept_color_mask(const host_objects *h)
{
    GLboolean m[4];
    (void)h;
    glGetBooleanv(GL_COLOR_WRITEMASK, m);
    return m[0] && !m[1] && m[2] && !m[3];
}
static void set_blend(const host_objects *h)
{
    (void)h;
    glEnable(GL_BLEND);
    glBlendFunc(GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
    glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
    glBlendColor(0.1f, 0.2f, 0.3f, 0.4f);
}
static int kept_blend(const host_objects *h)
{
    (void)h;
    return glIsEnabled(GL_BLEND) && geti(GL_BLEND_SRC_RGB) == GL_ZERO &&
           geti(GL_BLEND_DST_ALPHA) == GL_ONE_MINUS_SRC_COLOR &&
           geti(GL_BLEND_EQUATION_RGB) == GL_FUNC_REVERSE_SUBTRACT;
}
static void set_scissor(const host_objects *h)
{
    (void)h;
    glEnable(GL_SCISSOR_TEST);
    glScissor(1, 2, 3, 4);
}
static int kept_scissor(const host_objects *h)
{
    GLint b[4];
    (void)h;
    glGetIntegerv(GL_SCISSOR_BOX, b);
    return glIsEnabled(GL_SCISSOR_TEST) && b[0] == 1 && b[1] == 2 && b[2] == 3 && b[3] == 4;
}
static void set_cull(const host_objects *h)
{
    (void)h;
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT_AND_BACK);
    glFrontFace(GL_CW);
}
static int kept_cull(const host_objects *h)
{
    (void)h;
    return glIsEnabled(GL_CULL_FACE) && geti(GL_CULL_FACE_MODE) == GL_FRONT_AND_BACK && geti(GL_FRONT_FACE) == GL_CW;
}
static void set_front_face(const host_objects *h) { (void)h; glFrontFace(GL_CW); glCullFace(GL_FRONT); }
static int kept_front_face(const host_objects *h)
{
    (void)h;
    return !glIsEnabled(GL_CULL_FACE) && geti(GL_FRONT_FACE) == GL_CW && geti(GL_CULL_FACE_MODE) == GL_FRONT;
}
static void set_discard(const host_objects *h) { (void)h; glEnable(GL_RASTERIZER_DISCARD); }
static int kept_discard(const host_objects *h) { (void)h; return glIsEnabled(GL_RASTERIZER_DISCARD); }
static void set_coverage(const host_objects *h)
{
    (void)h;
    glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    glEnable(GL_SAMPLE_COVERAGE);
    glSampleCoverage(0.0f, GL_TRUE);
}
static int kept_coverage(const host_objects *h)
{
    (void)h;
    return glIsEnabled(GL_SAMPLE_ALPHA_TO_COVERAGE) && glIsEnabled(GL_SAMPLE_COVERAGE);
}
static void set_restart(const host_objects *h) { (void)h; glEnable(GL_PRIMITIVE_RESTART_FIXED_INDEX); }
static int kept_restart(const host_objects *h) { (void)h; return glIsEnabled(GL_PRIMITIVE_RESTART_FIXED_INDEX); }
static void set_dither(const host_objects *h) { (void)h; glDisable(GL_DITHER); }
static int kept_dither(const host_objects *h) { (void)h; return !glIsEnabled(GL_DITHER); }
static void set_depth(const host_objects *h)
{
    (void)h;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_NEVER);
    glDepthMask(GL_FALSE);
    glClearDepthf(0.0f);
}
static int kept_depth(const host_objects *h)
{
    GLboolean m = GL_TRUE;
    GLfloat c = 1;
    (void)h;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &m);
    glGetFloatv(GL_DEPTH_CLEAR_VALUE, &c);
    return glIsEnabled(GL_DEPTH_TEST) && geti(GL_DEPTH_FUNC) == GL_NEVER && !m && c == 0.0f;
}
static void set_bindings(const host_objects *h)
{
    int u;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, h->fbo_draw);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, h->fbo_read);
    glBindRenderbuffer(GL_RENDERBUFFER, h->rb);
    for (u = 0; u < UNITS; u++) {
        glActiveTexture((GLenum)(GL_TEXTURE0 + u));
        glBindTexture(u & 1 ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D, h->tex[u]);
    }
    glActiveTexture(GL_TEXTURE3);
    glViewport(3, 5, 7, 9);
    glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
}
static int kept_bindings(const host_objects *h)
{
    int u, ok;
    GLint v[4];
    GLfloat c[4];
    ok = geti(GL_DRAW_FRAMEBUFFER_BINDING) == (GLint)h->fbo_draw &&
         geti(GL_READ_FRAMEBUFFER_BINDING) == (GLint)h->fbo_read &&
         geti(GL_RENDERBUFFER_BINDING) == (GLint)h->rb && geti(GL_ACTIVE_TEXTURE) == GL_TEXTURE3;
    for (u = 0; u < UNITS; u++) { /* the host's binding of its kind, and none of the other kind */
        glActiveTexture((GLenum)(GL_TEXTURE0 + u));
        ok &= geti(u & 1 ? GL_TEXTURE_BINDING_CUBE_MAP : GL_TEXTURE_BINDING_2D) == (GLint)h->tex[u];
        ok &= geti(u & 1 ? GL_TEXTURE_BINDING_2D : GL_TEXTURE_BINDING_CUBE_MAP) == 0;
    }
    glActiveTexture(GL_TEXTURE3);
    glGetIntegerv(GL_VIEWPORT, v);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, c);
    return ok && v[0] == 3 && v[1] == 5 && v[2] == 7 && v[3] == 9 && c[0] == 0.25f && c[2] == 0.75f;
}
static void set_pack(const host_objects *h)
{
    (void)h;
    glPixelStorei(GL_PACK_ALIGNMENT, 8);
    glPixelStorei(GL_PACK_ROW_LENGTH, W + 13);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 3);
    glPixelStorei(GL_PACK_SKIP_ROWS, 2);
}
static int kept_pack(const host_objects *h)
{
    (void)h;
    return geti(GL_PACK_ALIGNMENT) == 8 && geti(GL_PACK_ROW_LENGTH) == W + 13 && geti(GL_PACK_SKIP_PIXELS) == 3 &&
           geti(GL_PACK_SKIP_ROWS) == 2;
}
static void set_unpack(const host_objects *h)
{
    (void)h;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 21);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 3);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 2);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 5);
    glPixelStorei(GL_UNPACK_SKIP_IMAGES, 1);
}
static int kept_unpack(const host_objects *h)
{
    (void)h;
    return geti(GL_UNPACK_ALIGNMENT) == 8 && geti(GL_UNPACK_ROW_LENGTH) == 21 && geti(GL_UNPACK_SKIP_PIXELS) == 3 &&
           geti(GL_UNPACK_SKIP_ROWS) == 2 && geti(GL_UNPACK_IMAGE_HEIGHT) == 5 && geti(GL_UNPACK_SKIP_IMAGES) == 1;
}
/* 5: host pixel buffers, small (a read-back or upload through them fails)
 * and filled with a pattern that must survive. */
static void set_pack_pbo(const host_objects *h) { glBindBuffer(GL_PIXEL_PACK_BUFFER, h->pack_pbo); }
static void set_unpack_pbo(const host_objects *h) { glBindBuffer(GL_PIXEL_UNPACK_BUFFER, h->unpack_pbo); }
static int pbo_intact(GLenum target, GLuint pbo)
{
    const uint8_t *p;
    int i, ok;
    GLenum binding = target == GL_PIXEL_PACK_BUFFER ? GL_PIXEL_PACK_BUFFER_BINDING : GL_PIXEL_UNPACK_BUFFER_BINDING;
    if (geti(binding) != (GLint)pbo)
        return 0;
    p = (const uint8_t *)glMapBufferRange(target, 0, 64, GL_MAP_READ_BIT);
    ok = p != NULL;
    for (i = 0; ok && i < 64; i++) ok = p[i] == (uint8_t)(i * 7 + 1);
    glUnmapBuffer(target);
    return ok;
}
static int kept_pack_pbo(const host_objects *h) { return pbo_intact(GL_PIXEL_PACK_BUFFER, h->pack_pbo); }
static int kept_unpack_pbo(const host_objects *h) { return pbo_intact(GL_PIXEL_UNPACK_BUFFER, h->unpack_pbo); }

static const piece g_pieces[] = {
    {"sampler objects on units 0-4", set_samplers, kept_samplers, 0},
    {"depth range 0.5..0.5", set_depth_range, kept_depth_range, 0},
    {"stencil test NEVER", set_stencil, kept_stencil, 0},
    {"polygon offset fill", set_polygon_offset, kept_polygon_offset, 0},
    {"colour mask", set_color_mask, kept_color_mask, 0},
    {"blend", set_blend, kept_blend, 0},
    {"scissor", set_scissor, kept_scissor, 0},
    {"culling front and back", set_cull, kept_cull, 0},
    {"front face CW, cull mode FRONT", set_front_face, kept_front_face, 0},
    {"rasterizer discard", set_discard, kept_discard, 0},
    {"alpha-to-coverage, sample coverage 0", set_coverage, kept_coverage, 0},
    {"primitive restart", set_restart, kept_restart, 0},
    {"dither off", set_dither, kept_dither, 0},
    {"depth test NEVER, no depth writes, clear depth 0", set_depth, kept_depth, 0},
    {"framebuffer, texture and renderbuffer bindings, viewport", set_bindings, kept_bindings, 0},
    {"pixel pack state", set_pack, kept_pack, 0},
    {"pixel unpack state", set_unpack, kept_unpack, 1},
    {"GL_PIXEL_PACK_BUFFER bound", set_pack_pbo, kept_pack_pbo, 0},
    {"GL_PIXEL_UNPACK_BUFFER bound", set_unpack_pbo, kept_unpack_pbo, 1},
};
#define N_PIECES ((int)(sizeof g_pieces / sizeof *g_pieces))

/* The host's GL state back to the defaults of a new context. */
static void host_defaults(void)
{
    int u;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    for (u = 0; u < UNITS; u++) {
        glActiveTexture((GLenum)(GL_TEXTURE0 + u));
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
        glBindSampler((GLuint)u, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    glViewport(0, 0, 1, 1);
    glClearColor(0, 0, 0, 0);
    glDepthRangef(0.0f, 1.0f);
    glDisable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 0, 0xffffffffu);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0, 0);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_ADD);
    glBlendColor(0, 0, 0, 0);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glDisable(GL_RASTERIZER_DISCARD);
    glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    glDisable(GL_SAMPLE_COVERAGE);
    glSampleCoverage(1.0f, GL_FALSE);
    glDisable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
    glEnable(GL_DITHER);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearDepthf(1.0f);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
    glPixelStorei(GL_UNPACK_SKIP_IMAGES, 0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

static void host_objects_make(host_objects *h)
{
    uint8_t pattern[64];
    int i;
    for (i = 0; i < 64; i++) pattern[i] = (uint8_t)(i * 7 + 1);
    glGenSamplers(1, &h->sampler);
    /* No mipmaps in snell's textures: with this filter they are incomplete (black). */
    glSamplerParameteri(h->sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glSamplerParameteri(h->sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(h->sampler, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glGenBuffers(1, &h->pack_pbo);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, h->pack_pbo);
    glBufferData(GL_PIXEL_PACK_BUFFER, 64, pattern, GL_STATIC_READ);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glGenBuffers(1, &h->unpack_pbo);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, h->unpack_pbo);
    glBufferData(GL_PIXEL_UNPACK_BUFFER, 64, pattern, GL_STATIC_DRAW);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glGenRenderbuffers(1, &h->rb);
    glBindRenderbuffer(GL_RENDERBUFFER, h->rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 8, 8);
    glGenFramebuffers(1, &h->fbo_draw);
    glBindFramebuffer(GL_FRAMEBUFFER, h->fbo_draw);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, h->rb);
    glGenFramebuffers(1, &h->fbo_read);
    glBindFramebuffer(GL_FRAMEBUFFER, h->fbo_read);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, h->rb);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glGenTextures(UNITS, h->tex);
    for (i = 0; i < UNITS; i++) {
        glBindTexture(i & 1 ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D, h->tex[i]);
        glBindTexture(i & 1 ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D, 0);
    }
}

/* The scene: a CUBEMAP sphere (baked ndcube) and a PEEL torus seeing an
 * opaque cube and each other through the scene layers, standing in rippled
 * water (its grid, heights texture and programs made under the host's
 * state; the water's rays march the layers, the kernels see the water), the
 * background last. */
typedef struct host_scene {
    snell_mesh *sphere, *torus, *cube;
    snell_water *water;
    snell_backdrop bd;              /* the host's frame behind the glass: a colour and a depth texture */
    GLuint bd_tex[2];
    snell_glass g[2];
    snell_opaque op;
    float m_sphere[16], m_torus[16], m_cube[16];
} host_scene;

static void place(float m[16], float x, float y, float z, float s)
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = s;
    m[12] = x;
    m[13] = y;
    m[14] = z;
    m[15] = 1.0f;
}

static void scene_frame(host_scene *s, const snell_env *env, snell_frame_desc *fd)
{
    memset(fd, 0, sizeof *fd);
    memset(s->g, 0, sizeof s->g);
    place(s->m_sphere, -0.6f, 0.0f, 0.0f, 0.6f);
    place(s->m_torus, 0.7f, 0.1f, 0.0f, 0.5f);
    place(s->m_cube, 0.0f, -0.3f, -1.5f, 0.4f);
    s->g[0].mesh = s->sphere;
    s->g[0].model = s->m_sphere;
    s->g[0].material.method = SNELL_METHOD_CUBEMAP;
    s->g[0].material.cubemap.face_size = 32;
    s->g[0].material.attenuation_distance = 2.0f;
    s->g[0].material.attenuation_color[0] = 0.9f;
    s->g[0].material.attenuation_color[1] = 0.6f;
    s->g[0].material.attenuation_color[2] = 0.3f;
    s->g[1].mesh = s->torus;
    s->g[1].model = s->m_torus;
    /* peel: its layer passes (own framebuffer, texture array, occlusion query) under the host's state */
    s->g[1].material.method = SNELL_METHOD_PEEL;
    s->g[1].material.ior = 1.33f;
    memset(&s->op, 0, sizeof s->op);
    s->op.mesh = s->cube;
    s->op.model = s->m_cube;
    s->op.color[0] = 0.9f;
    s->op.color[1] = 0.2f;
    s->op.color[2] = 0.1f;
    fd->env = env;
    fd->glass = s->g;
    fd->glass_count = 2;
    fd->opaque = &s->op;
    fd->opaque_count = 1;
    fd->water = s->water;
    fd->camera.azimuth = 0.4f;
    fd->camera.elevation = 0.3f;
    fd->camera.distance = 3.2f;
    fd->dynamic_env_size = 16;
    /* caustics: its shadow map, glass maps, photons and light map under the host's state */
    fd->light.type = SNELL_LIGHT_DIRECTIONAL;
    fd->light.direction[0] = 0.3f, fd->light.direction[1] = -1.0f, fd->light.direction[2] = 0.2f;
    fd->light.photons = 32;
    fd->receiver.height = -0.9f, fd->receiver.extent = 2.5f, fd->receiver.map_size = 64;
    /* the host's frame behind the glass: its samplers (own sampler objects) under the host's */
    fd->backdrop = &s->bd;
}

/* The backdrop's textures: stripes of colour, the right half at depth 0.99, the left empty (1). */
static void backdrop_make(host_scene *s)
{
    static uint8_t rgba[16 * 16 * 4];
    static GLuint depth[16 * 16];
    int i;
    for (i = 0; i < 16 * 16; i++) {
        rgba[4 * i] = (uint8_t)(i * 37), rgba[4 * i + 1] = (uint8_t)(i * 11), rgba[4 * i + 2] = 200, rgba[4 * i + 3] = 255;
        depth[i] = i % 16 < 8 ? 0xffffffffu : (GLuint)(0.99 * 4294967295.0);
    }
    glGenTextures(2, s->bd_tex);
    glBindTexture(GL_TEXTURE_2D, s->bd_tex[0]);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 16, 16, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindTexture(GL_TEXTURE_2D, s->bd_tex[1]);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, 16, 16, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, depth);
    glBindTexture(GL_TEXTURE_2D, 0);
    memset(&s->bd, 0, sizeof s->bd);
    s->bd.color_texture = s->bd_tex[0], s->bd.depth_texture = s->bd_tex[1];
    s->bd.width = s->bd.height = 16;
}

/* A frame with a new renderer (so bakes, dynamic environments, G-buffers and
 * programs are all made under the host's state) read into px; NULL env: a new
 * one (uploads under the host's state). */
static int host_render(snell_ctx *ctx, host_scene *s, snell_env *env, snell_shading shading, uint8_t *px)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_env *own = NULL;
    snell_status st;
    if (!env) {
        snell_env_desc ed;
        memset(&ed, 0, sizeof ed);
        ed.face_size = 16;
        st = snell_env_create(ctx, &ed, &own);
        if (st != SNELL_OK) return printf("  env_create: %s %s\n", snell_status_str(st), snell_last_error(ctx)), 0;
        env = own;
    }
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.shading = shading;
    st = snell_renderer_create(ctx, &rd, &r);
    if (st == SNELL_OK) {
        snell_frame_stats fs;
        scene_frame(s, env, &fd);
        st = snell_render(r, &fd, &fs);
        CHECK(st != SNELL_OK || (fs.water_drawn && fs.water_layers), "the host scene's water drawn, marching the layers");
        CHECK(st != SNELL_OK || fs.caustics_photons == 2 * 32 * 32, "the host scene's caustics made: %s",
              fs.caustics_reason);
    }
    if (st == SNELL_OK) st = snell_renderer_read_rgba(r, px);
    if (st != SNELL_OK) printf("  %s %s\n", snell_status_str(st), snell_last_error(ctx));
    snell_renderer_destroy(r);
    snell_env_destroy(own);
    return st == SNELL_OK;
}

static void check_external_state(void)
{
    static const snell_shading shadings[2] = {SNELL_SHADING_FORWARD, SNELL_SHADING_SCREEN};
    static const char *const shading_names[2] = {"forward", "screen-space"};
    EGLDisplay dpy;
    EGLContext host;
    snell_ctx *ctx = NULL;
    snell_ctx_desc d;
    snell_env *env;
    host_scene s;
    host_objects h;
    snell_renderer *r;
    snell_frame_desc fd;
    /* Large enough for any pack state the host may leave (row length, skips),
     * so that a read-back that honours it writes inside the buffer. */
    size_t big = (size_t)(W + 16) * (H + 4) * 4 + 64;
    uint8_t *clean[2], *px = (uint8_t *)malloc(big);
    int i, k;

    if (!test_host_context(&dpy, &host)) {
        printf("cannot make a host context here; EXTERNAL state not checked\n");
        free(px);
        return;
    }
    memset(&d, 0, sizeof d);
    d.backend = SNELL_BACKEND_EXTERNAL;
    CHECK_OK(snell_ctx_create(&d, &ctx));
    if (!ctx || !px) return;
    memset(&s, 0, sizeof s);
    s.sphere = shape(ctx, SNELL_SHAPE_SPHERE);
    s.torus = shape(ctx, SNELL_SHAPE_TORUS);
    s.cube = shape(ctx, SNELL_SHAPE_CUBE);
    backdrop_make(&s);
    CHECK_OK_CTX(ctx, snell_water_create(ctx, &(snell_water_desc){.grid = 64, .width = 3.0f,
                                                                   .sim = SNELL_WATER_SIM_CPU}, &s.water));
    CHECK_OK_CTX(ctx, snell_water_drop(s.water, 0.2f, 0.3f, 0.2f, -0.05f));
    CHECK_OK_CTX(ctx, snell_water_step(s.water, 0.0f, 40, NULL));
    env = env16(ctx);
    memset(&h, 0, sizeof h);
    host_objects_make(&h);
    host_defaults();

    for (k = 0; k < 2; k++) {
        clean[k] = (uint8_t *)calloc(1, W * H * 4);
        if (!clean[k] || !host_render(ctx, &s, env, shadings[k], clean[k])) {
            CHECK(0, "clean %s frame failed", shading_names[k]);
            return;
        }
        memset(px, 0, big);
        CHECK(host_render(ctx, &s, env, shadings[k], px) && memcmp(px, clean[k], W * H * 4) == 0,
              "%s: two clean frames differ", shading_names[k]);
    }
    for (i = 0; i < N_PIECES; i++) {
        const piece *p = &g_pieces[i];
        for (k = 0; k < 2; k++) {
            int ok, diff = 0, j;
            host_defaults();
            p->set(&h);
            memset(px, 0, big);
            ok = host_render(ctx, &s, p->fresh_env ? NULL : env, shadings[k], px);
            for (j = 0; ok && j < W * H * 4; j++) diff += px[j] != clean[k][j];
            CHECK(ok && diff == 0, "host %s, %s: the frame %s (%d of %d bytes differ)", p->name, shading_names[k],
                  ok ? "differs from a clean context's" : "failed", diff, W * H * 4);
            CHECK(glGetError() == GL_NO_ERROR, "host %s, %s: GL error left behind", p->name, shading_names[k]);
            CHECK(p->kept(&h), "host %s, %s: not restored", p->name, shading_names[k]);
        }
    }
    host_defaults();

    /* All of them at once. */
    for (k = 0; k < 2; k++) {
        int ok, j, diff = 0;
        for (i = 0; i < N_PIECES; i++)
            if (g_pieces[i].set != set_front_face) g_pieces[i].set(&h);
        memset(px, 0, big);
        ok = host_render(ctx, &s, NULL, shadings[k], px);
        for (j = 0; ok && j < W * H * 4; j++) diff += px[j] != clean[k][j];
        CHECK(ok && diff == 0, "all host state at once, %s: %d bytes differ", shading_names[k], diff);
        for (i = 0; i < N_PIECES; i++)
            if (g_pieces[i].set != set_front_face)
                CHECK(g_pieces[i].kept(&h), "all at once, %s: %s not restored", shading_names[k], g_pieces[i].name);
        host_defaults();
    }

    /* "Also" for EXTERNAL: the host's context must be current. */
    r = renderer(ctx, SNELL_SHADING_AUTO);
    scene_frame(&s, env, &fd);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    CHECK_FAILS(ctx, snell_ctx_make_current(ctx), SNELL_E_INVALID_ARG, "host");
    CHECK_FAILS(ctx, snell_render(r, &fd, NULL), SNELL_E_INVALID_ARG, "not current");
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, host);
    CHECK_OK_CTX(ctx, snell_ctx_make_current(ctx));
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    snell_renderer_destroy(r);

    /* 8 with EXTERNAL: objects destroyed after the snell context leave the
     * host's context current and its state alone. */
    r = renderer(ctx, SNELL_SHADING_AUTO);
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    snell_ctx_destroy(ctx);
    CHECK(eglGetCurrentContext() == host, "EXTERNAL destroy keeps the host's context current");
    CHECK_FAILS(ctx, snell_render(r, &fd, NULL), SNELL_E_INVALID_ARG, "destroyed");
    snell_renderer_destroy(r);
    snell_mesh_destroy(s.sphere);
    snell_mesh_destroy(s.torus);
    snell_mesh_destroy(s.cube);
    snell_water_destroy(s.water);
    snell_env_destroy(env);
    glDeleteTextures(2, s.bd_tex);
    CHECK(eglGetCurrentContext() == host, "destroying objects after their EXTERNAL context keeps the host current");
    CHECK(glGetError() == GL_NO_ERROR, "GL error after the late destroys");

    for (k = 0; k < 2; k++) free(clean[k]);
    free(px);
    glDeleteSamplers(1, &h.sampler);
    glDeleteBuffers(1, &h.pack_pbo);
    glDeleteBuffers(1, &h.unpack_pbo);
    glDeleteFramebuffers(1, &h.fbo_draw);
    glDeleteFramebuffers(1, &h.fbo_read);
    glDeleteRenderbuffers(1, &h.rb);
    glDeleteTextures(UNITS, h.tex);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, host);
    eglTerminate(dpy);
}

/* TEST_HOST_ONLY=name runs one part (to look at it alone, e.g. under a debugger). */
static void part(const char *name, void (*fn)(void))
{
    const char *only = getenv("TEST_HOST_ONLY");
    if (only && strcmp(only, name)) return;
    printf("-- %s\n", name);
    fn();
}

int main(void)
{
    part("env_sample", check_env_sample);
    part("camera", check_camera);
    part("two_contexts", check_two_contexts);
    part("destroy_order", check_destroy_order);
    part("external_state", check_external_state);
    return test_finish();
}
