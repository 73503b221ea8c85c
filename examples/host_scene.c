/* SPDX-License-Identifier: MIT */
/* host_scene.c — glass in an app's own world. The app has its own GLES 3.0
 * context, shaders and framebuffer, and a first-person camera that walks
 * and turns; each frame it draws its opaque scene (a checkered ground and
 * three pillars), then asks snell for a glass bunny and a glass sphere in
 * it: the app's camera as matrices, the app's depth kept and tested, and
 * the app's frame (copied by snell from the bound framebuffer) refracted by
 * the glass. Writes the last frame to the PNG named on the command line.
 *
 *   host_scene [out.png] [bunny.obj]
 *
 * The lines that matter are in draw_frame(): a snell_frame_desc with
 * camera.kind = SNELL_CAMERA_MATRICES, depth = SNELL_DEPTH_TEST,
 * draw_background = -1 and a backdrop of SNELL_BACKDROP_COPY_BOUND. */
#define _POSIX_C_SOURCE 200809L
#include <snell/snell.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 320
#define H 200
#define FRAMES 8

/* The app's own shaders: world position in, a checker on the ground, flat
 * colours elsewhere, half-Lambert from the sky. */
static const char k_vs[] = "#version 300 es\nuniform mat4 u_vp;\nin vec3 a_pos;\nout vec3 v_pos;\n"
                           "void main() { v_pos = a_pos; gl_Position = u_vp * vec4(a_pos, 1.0); }\n";
static const char k_fs[] =
    "#version 300 es\nprecision highp float;\nuniform vec3 u_color, u_n;\nuniform int u_checker;\nin vec3 v_pos;\n"
    "out vec4 o;\nvoid main() {\n"
    "  vec3 c = u_color;\n"
    "  if (u_checker == 1 && (int(floor(v_pos.x)) + int(floor(v_pos.z))) % 2 == 0) c *= 0.45;\n"
    "  o = vec4(c * (0.35 + 0.65 * max(dot(u_n, normalize(vec3(0.3, 1.0, 0.2))), 0.0)), 1.0);\n}\n";

typedef struct app {
    EGLDisplay dpy;
    EGLContext ctx;
    GLuint prog, vao, vbo, fbo, rb[2];
    float pos[3], yaw, pitch; /* the first-person camera */
} app;

static int app_context(app *a)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC gpd = (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLint cfg_attrs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    EGLint ctx_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLConfig cfg;
    EGLint n = 0;
    if (!gpd) return 0;
    a->dpy = gpd(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (a->dpy == EGL_NO_DISPLAY || !eglInitialize(a->dpy, NULL, NULL)) return 0;
    eglBindAPI(EGL_OPENGL_ES_API);
    if (!eglChooseConfig(a->dpy, cfg_attrs, &cfg, 1, &n) || n < 1) return 0;
    a->ctx = eglCreateContext(a->dpy, cfg, EGL_NO_CONTEXT, ctx_attrs);
    return a->ctx != EGL_NO_CONTEXT && eglMakeCurrent(a->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, a->ctx);
}

static int app_gl(app *a)
{
    const char *src[2] = {k_vs, k_fs};
    GLint ok = 0;
    int i;
    a->prog = glCreateProgram();
    for (i = 0; i < 2; i++) {
        GLuint s = glCreateShader(i ? GL_FRAGMENT_SHADER : GL_VERTEX_SHADER);
        glShaderSource(s, 1, &src[i], NULL);
        glCompileShader(s);
        glAttachShader(a->prog, s);
        glDeleteShader(s);
    }
    glBindAttribLocation(a->prog, 0, "a_pos");
    glLinkProgram(a->prog);
    glGetProgramiv(a->prog, GL_LINK_STATUS, &ok);
    glGenVertexArrays(1, &a->vao);
    glGenBuffers(1, &a->vbo);
    glGenRenderbuffers(2, a->rb);
    glBindRenderbuffer(GL_RENDERBUFFER, a->rb[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
    glBindRenderbuffer(GL_RENDERBUFFER, a->rb[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, W, H);
    glGenFramebuffers(1, &a->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, a->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, a->rb[0]);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, a->rb[1]);
    return ok && glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

/* Column-major view (first person: position, yaw about +Y, pitch) and perspective. */
static void app_camera(const app *a, float view[16], float proj[16])
{
    float cy = cosf(a->yaw), sy = sinf(a->yaw), cp = cosf(a->pitch), sp = sinf(a->pitch);
    float f[3] = {-sy * cp, sp, -cy * cp}, r[3] = {cy, 0.0f, -sy}, u[3];
    const float n = 0.05f, far_ = 60.0f, t = n * tanf(0.5f * 1.0f), aspect = (float)W / H;
    int k;
    u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2], u[2] = r[0] * f[1] - r[1] * f[0];
    memset(view, 0, 16 * sizeof *view);
    memset(proj, 0, 16 * sizeof *proj);
    for (k = 0; k < 3; k++) {
        view[4 * k] = r[k], view[4 * k + 1] = u[k], view[4 * k + 2] = -f[k];
    }
    view[12] = -(r[0] * a->pos[0] + r[1] * a->pos[1] + r[2] * a->pos[2]);
    view[13] = -(u[0] * a->pos[0] + u[1] * a->pos[1] + u[2] * a->pos[2]);
    view[14] = f[0] * a->pos[0] + f[1] * a->pos[1] + f[2] * a->pos[2];
    view[15] = 1.0f;
    proj[0] = n / (t * aspect), proj[5] = n / t;
    proj[10] = -(far_ + n) / (far_ - n), proj[11] = -1.0f, proj[14] = -2.0f * far_ * n / (far_ - n);
}

static void mul(const float a[16], const float b[16], float o[16])
{
    int r, c, k;
    for (c = 0; c < 4; c++)
        for (r = 0; r < 4; r++) {
            o[4 * c + r] = 0.0f;
            for (k = 0; k < 4; k++) o[4 * c + r] += a[4 * k + r] * b[4 * c + k];
        }
}

static void quad(const app *a, const float v[18], const float n[3], const float color[3], int checker)
{
    glBindBuffer(GL_ARRAY_BUFFER, a->vbo);
    glBufferData(GL_ARRAY_BUFFER, 18 * sizeof(float), v, GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, 0);
    glUniform3fv(glGetUniformLocation(a->prog, "u_n"), 1, n);
    glUniform3fv(glGetUniformLocation(a->prog, "u_color"), 1, color);
    glUniform1i(glGetUniformLocation(a->prog, "u_checker"), checker);
    glDrawArrays(GL_TRIANGLES, 0, 6);
}

/* A pillar's four sides, x0..x1 by z0..z1, from the ground to height h. */
static void pillar(const app *a, float x0, float z0, float x1, float z1, float h, const float color[3])
{
    const float xs[4][2] = {{x0, x1}, {x1, x1}, {x1, x0}, {x0, x0}}, zs[4][2] = {{z1, z1}, {z1, z0}, {z0, z0}, {z0, z1}};
    const float ns[4][3] = {{0, 0, 1}, {1, 0, 0}, {0, 0, -1}, {-1, 0, 0}};
    int s;
    for (s = 0; s < 4; s++) {
        float v[18] = {xs[s][0], -1, zs[s][0], xs[s][1], -1, zs[s][1], xs[s][1], h, zs[s][1],
                       xs[s][0], -1, zs[s][0], xs[s][1], h, zs[s][1], xs[s][0], h, zs[s][0]};
        quad(a, v, ns[s], color, 0);
    }
}

/* The app's own scene, with its own shaders, into its framebuffer. */
static void app_draw(const app *a, const float vp[16])
{
    static const float ground[18] = {-20, -1, -20, 20, -1, 20, 20, -1, -20, -20, -1, -20, -20, -1, 20, 20, -1, 20};
    static const float up[3] = {0, 1, 0}, sand[3] = {0.9f, 0.8f, 0.55f};
    static const float red[3] = {0.85f, 0.2f, 0.15f}, blue[3] = {0.2f, 0.35f, 0.85f}, green[3] = {0.2f, 0.7f, 0.3f};
    glBindFramebuffer(GL_FRAMEBUFFER, a->fbo);
    glViewport(0, 0, W, H);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClearColor(0.55f, 0.7f, 0.9f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(a->prog);
    glUniformMatrix4fv(glGetUniformLocation(a->prog, "u_vp"), 1, GL_FALSE, vp);
    glBindVertexArray(a->vao);
    quad(a, ground, up, sand, 1);
    pillar(a, -2.5f, -6.5f, -1.5f, -5.5f, 2.0f, red);
    pillar(a, 0.8f, -8.0f, 1.8f, -7.0f, 3.0f, blue);
    pillar(a, 2.5f, -4.5f, 3.0f, -4.0f, 1.0f, green);
    glBindVertexArray(0);
}

/* snell's frame over the app's: the app's camera, depth and scene. */
static snell_status draw_frame(snell_renderer *r, const snell_env *env, const snell_glass *glass, const float view[16],
                               const float proj[16], snell_frame_stats *stats)
{
    snell_frame_desc fd;
    snell_backdrop backdrop;
    memset(&fd, 0, sizeof fd);
    memset(&backdrop, 0, sizeof backdrop);
    backdrop.source = SNELL_BACKDROP_COPY_BOUND; /* snell copies the app's colour and depth itself */
    fd.env = env;
    fd.glass = glass;
    fd.glass_count = 2;
    fd.camera.kind = SNELL_CAMERA_MATRICES;      /* the app's camera */
    memcpy(fd.camera.view, view, sizeof fd.camera.view);
    memcpy(fd.camera.projection, proj, sizeof fd.camera.projection);
    fd.depth = SNELL_DEPTH_TEST;                 /* the app's depth kept and tested */
    fd.draw_background = -1;                     /* the app's pixels stay the app's */
    fd.backdrop = &backdrop;
    return snell_render(r, &fd, stats);
}

int main(int argc, char **argv)
{
    static uint8_t before[W * H * 4], after[W * H * 4];
    const char *out = argc > 1 ? argv[1] : NULL, *bunny_path = argc > 2 ? argv[2] : "/usr/share/glmark2/models/bunny.obj";
    app a;
    snell_ctx *ctx = NULL;
    snell_ctx_desc cd;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_mesh *bunny = NULL, *sphere = NULL;
    snell_env *env = NULL;
    snell_glass glass[2];
    snell_frame_stats stats;
    snell_status st;
    float bunny_model[16], sphere_model[16], lo[3], hi[3], s = 0.0f;
    int f, k, changed = 0, rc = 1;
    memset(&a, 0, sizeof a);
    if (!app_context(&a) || !app_gl(&a)) {
        fprintf(stderr, "host_scene: no GLES 3.0 context or framebuffer here\n");
        return 77;
    }
    memset(&cd, 0, sizeof cd);
    cd.backend = SNELL_BACKEND_EXTERNAL; /* snell draws in the app's context */
    memset(&rd, 0, sizeof rd);
    rd.width = W, rd.height = H, rd.target = SNELL_TARGET_BOUND_FRAMEBUFFER;
    st = snell_ctx_create(&cd, &ctx);
    if (st == SNELL_OK) st = snell_renderer_create(ctx, &rd, &r);
    if (st == SNELL_OK && snell_mesh_load(ctx, bunny_path, &bunny) != SNELL_OK) /* no glmark2: a torus */
        st = snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_TORUS}, &bunny);
    if (st == SNELL_OK) st = snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE}, &sphere);
    if (st == SNELL_OK) st = snell_env_create(ctx, &(snell_env_desc){.face_size = 64}, &env);
    if (st != SNELL_OK) {
        fprintf(stderr, "host_scene: %s: %s\n", snell_status_str(st), snell_last_error(ctx));
        goto done;
    }
    /* the bunny fitted into a sphere of radius 0.9 standing on the ground, the sphere beside it */
    snell_mesh_bounds(bunny, lo, hi);
    for (k = 0; k < 3; k++) s += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    s = 0.9f / sqrtf(s);
    memset(bunny_model, 0, sizeof bunny_model);
    memset(sphere_model, 0, sizeof sphere_model);
    for (k = 0; k < 3; k++) bunny_model[5 * k] = s, sphere_model[5 * k] = 0.6f;
    bunny_model[12] = -0.6f - s * 0.5f * (lo[0] + hi[0]);
    bunny_model[13] = -1.0f - s * lo[1];
    bunny_model[14] = -4.0f - s * 0.5f * (lo[2] + hi[2]);
    sphere_model[12] = 1.1f, sphere_model[13] = -0.4f, sphere_model[14] = -3.6f;
    bunny_model[15] = sphere_model[15] = 1.0f;
    memset(glass, 0, sizeof glass);
    glass[0].mesh = bunny, glass[0].model = bunny_model, glass[0].material.ior = 1.5f;
    glass[1].mesh = sphere, glass[1].model = sphere_model, glass[1].material.ior = 1.45f;
    a.pos[1] = 0.2f;
    for (f = 0; f < FRAMES; f++) { /* the app's frame loop: walk forward, turn a little */
        float view[16], proj[16], vp[16];
        a.pos[2] = 1.0f - 0.15f * f;
        a.yaw = 0.03f * f;
        a.pitch = -0.12f;
        app_camera(&a, view, proj);
        mul(proj, view, vp);
        app_draw(&a, vp);
        if (f == FRAMES - 1) glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, before);
        st = draw_frame(r, env, glass, view, proj, &stats);
        if (st != SNELL_OK) {
            fprintf(stderr, "host_scene: frame %d: %s\n", f, snell_last_error(ctx));
            goto done;
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, a.fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, after);
    for (k = 0; k < W * H; k++) changed += memcmp(before + 4 * k, after + 4 * k, 3) != 0;
    printf("host_scene: %d frames of %dx%d, glass on %d pixels of the app's last frame; stages: %s; backdrop %s\n",
           FRAMES, W, H, changed, stats.stages, stats.backdrop == 2 ? "searched against the app's depth" : "at a distance");
    if (out) {
        for (k = 0; k < H / 2; k++) { /* GL rows bottom first: the image top first */
            static uint8_t row[W * 4];
            memcpy(row, after + (size_t)k * W * 4, W * 4);
            memcpy(after + (size_t)k * W * 4, after + (size_t)(H - 1 - k) * W * 4, W * 4);
            memcpy(after + (size_t)(H - 1 - k) * W * 4, row, W * 4);
        }
        if (snell_write_png(out, W, H, after) == SNELL_OK) printf("wrote %s\n", out);
    }
    rc = changed > W * H / 50 && stats.backdrop == 2 ? 0 : 1;
done:
    snell_env_destroy(env);
    snell_mesh_destroy(bunny);
    snell_mesh_destroy(sphere);
    snell_renderer_destroy(r);
    snell_ctx_destroy(ctx);
    glDeleteProgram(a.prog);
    glDeleteFramebuffers(1, &a.fbo);
    glDeleteRenderbuffers(2, a.rb);
    glDeleteBuffers(1, &a.vbo);
    glDeleteVertexArrays(1, &a.vao);
    eglMakeCurrent(a.dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(a.dpy, a.ctx);
    return rc;
}
