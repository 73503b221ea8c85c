/* SPDX-License-Identifier: MIT */
/* test_host_world — glass in a host's world: the host's own off-axis
 * camera given as matrices (SNELL_CAMERA_MATRICES), its depth kept and
 * tested (SNELL_DEPTH_TEST). A host with its own EGL context, shaders and
 * framebuffer draws a ground and a red box, then snell (EXTERNAL backend,
 * the bound framebuffer, no background) draws a glass sphere. Checked
 * against the sphere's exact silhouette under the host's camera: the host's
 * pixels outside it unchanged, the glass drawn on >= 97% of it, the box in
 * front of it kept on >= 98% of its pixels there. Also: the orbit camera
 * and the same camera as matrices give byte-identical frames for every
 * method; an off-axis frustum's glass PSNR against FULL (the reference
 * through the same matrices) within 1 dB of the on-axis one's; a projection
 * that is not perspective, and a singular matrix, are refused;
 * SNELL_DEPTH_TEST_NO_WRITE gives the host its depth back. */
#include "test_util.h"
#include "snell/snell_metrics.h"
#include "snell/snell_ref.h"

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <cglm/cglm.h>
#include <math.h>
#include <string.h>

#define W 128
#define H 96

static const float k_half[16] = {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1};

static const char k_vs[] = "#version 300 es\nuniform mat4 u_mvp;\nin vec3 a_pos;\n"
                           "void main() { gl_Position = u_mvp * vec4(a_pos, 1.0); }\n";
static const char k_fs[] = "#version 300 es\nprecision mediump float;\nuniform vec4 u_color;\nout vec4 o;\n"
                           "void main() { o = u_color; }\n";

static GLuint compile(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    GLint ok = 0;
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    CHECK(ok, "host shader compiles");
    return s;
}

/* The host's camera: eye at (0.4, 0.9, 3.2) looking at (0, -0.1, 0), an
 * off-axis frustum (the lens shifted right and up, as a VR eye's). */
static void host_camera(mat4 view, mat4 proj)
{
    vec3 eye = {0.4f, 0.9f, 3.2f}, at = {0.0f, -0.1f, 0.0f}, up = {0.0f, 1.0f, 0.0f};
    const float n = 0.1f, f = 50.0f, t = 0.045f, aspect = (float)W / (float)H;
    glm_lookat(eye, at, up, view);
    glm_frustum(-0.7f * t * aspect, 1.3f * t * aspect, -0.8f * t, 1.2f * t, n, f, proj);
}

/* Does the host camera's ray through pixel (x, y) (GL rows) meet the sphere
 * (centre c, radius r)? 1 inside, 0 outside, -1 within `band` pixels' worth of
 * the silhouette (tested at the pixel's corners too). */
static int sphere_covers(mat4 inv_vp, const float c[3], float r, int x, int y)
{
    int hits = 0, k;
    for (k = 0; k < 5; k++) {
        const float fx[5] = {0.5f, 0.0f, 1.0f, 0.0f, 1.0f}, fy[5] = {0.5f, 0.0f, 0.0f, 1.0f, 1.0f};
        vec4 a = {2.0f * ((float)x + fx[k]) / W - 1.0f, 2.0f * ((float)y + fy[k]) / H - 1.0f, -1.0f, 1.0f};
        vec4 b = {a[0], a[1], 1.0f, 1.0f}, pa, pb;
        float d[3], oc[3], bq = 0, cq = 0, len = 0;
        int i;
        glm_mat4_mulv(inv_vp, a, pa);
        glm_mat4_mulv(inv_vp, b, pb);
        for (i = 0; i < 3; i++) {
            pa[i] /= pa[3], pb[i] /= pb[3];
            d[i] = pb[i] - pa[i];
            len += d[i] * d[i];
        }
        len = sqrtf(len);
        for (i = 0; i < 3; i++) {
            d[i] /= len;
            oc[i] = pa[i] - c[i];
            bq += oc[i] * d[i];
            cq += oc[i] * oc[i];
        }
        hits += bq * bq - (cq - r * r) > 0.0f;
    }
    return hits == 5 ? 1 : hits == 0 ? 0 : -1;
}

static void draw_quad(GLuint prog, mat4 vp, const float *v, int n, const float color[4])
{
    GLuint vbo, vao;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * 3 * sizeof(float)), v, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, 0);
    glUseProgram(prog);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_mvp"), 1, GL_FALSE, (const float *)vp);
    glUniform4fv(glGetUniformLocation(prog, "u_color"), 1, color);
    glDrawArrays(GL_TRIANGLES, 0, n);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
}

/* The host's scene: a ground at y = -0.6 and a red box face at z = 0.9,
 * in front of the sphere's lower left quarter. */
static void host_scene(GLuint prog, mat4 vp)
{
    static const float ground[] = {-6, -0.6f, -6, 6, -0.6f, -6, 6, -0.6f, 6, -6, -0.6f, -6, 6, -0.6f, 6, -6, -0.6f, 6};
    static const float box[] = {-0.45f, -0.6f, 0.9f, 0.1f, -0.6f, 0.9f, 0.1f, 0.35f, 0.9f,
                                -0.45f, -0.6f, 0.9f, 0.1f, 0.35f, 0.9f, -0.45f, 0.35f, 0.9f};
    static const float green[4] = {0.2f, 0.5f, 0.25f, 1.0f}, red[4] = {0.8f, 0.1f, 0.1f, 1.0f};
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearColor(0.1f, 0.1f, 0.3f, 1.0f);
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_quad(prog, vp, ground, 6, green);
    draw_quad(prog, vp, box, 6, red);
}

static void host_world(void)
{
    EGLDisplay dpy;
    EGLContext hctx;
    snell_ctx *ctx = NULL;
    snell_ctx_desc cd = {.backend = SNELL_BACKEND_EXTERNAL};
    snell_renderer *r = NULL;
    snell_renderer_desc rd = {.width = W, .height = H, .target = SNELL_TARGET_BOUND_FRAMEBUFFER};
    snell_mesh *sphere = NULL;
    snell_env *env = NULL;
    snell_glass g;
    snell_frame_desc fd;
    GLuint fbo, crb, drb, prog;
    mat4 view, proj, vp, inv_vp;
    static uint8_t before[W * H * 4], after[W * H * 4], box_only[W * H * 4];
    const float c[3] = {0.0f, 0.0f, 0.0f}, radius = 0.5f;
    int x, y, glass = 0, drawn = 0, outside = 0, changed_outside = 0, box_front = 0, box_kept = 0;
    if (!test_host_context(&dpy, &hctx)) {
        printf("no host context: host world not checked\n");
        return;
    }
    prog = glCreateProgram();
    glAttachShader(prog, compile(GL_VERTEX_SHADER, k_vs));
    glAttachShader(prog, compile(GL_FRAGMENT_SHADER, k_fs));
    glBindAttribLocation(prog, 0, "a_pos");
    glLinkProgram(prog);
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &crb);
    glGenRenderbuffers(1, &drb);
    glBindRenderbuffer(GL_RENDERBUFFER, crb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
    glBindRenderbuffer(GL_RENDERBUFFER, drb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, W, H);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, crb);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, drb);
    glViewport(0, 0, W, H);
    host_camera(view, proj);
    glm_mat4_mul(proj, view, vp);
    glm_mat4_inv(vp, inv_vp);

    CHECK_OK(snell_ctx_create(&cd, &ctx));
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE, .segments = 48, .rings = 24},
                                              &sphere));
    env = test_sky(ctx, 32);
    if (!r || !sphere || !env) goto done;
    memset(&g, 0, sizeof g);
    test_frame_one(&fd, &g, sphere, env);
    g.material.ior = 1.5f;
    g.model = k_half; /* the unit sphere at radius 0.5 */
    fd.draw_background = -1;
    fd.camera.kind = SNELL_CAMERA_MATRICES;
    memcpy(fd.camera.view, view, sizeof fd.camera.view);
    memcpy(fd.camera.projection, proj, sizeof fd.camera.projection);

    /* the box alone, where it is drawn over the ground */
    host_scene(prog, vp);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, before);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL)); /* SNELL_DEPTH_DEFAULT: TEST for the bound framebuffer */
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, after);
    memcpy(box_only, before, sizeof box_only);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int i = 4 * (y * W + x), cov = sphere_covers(inv_vp, c, radius, x, y);
            int red = before[i] > 150 && before[i + 1] < 60;
            int diff = memcmp(before + i, after + i, 3) != 0;
            if (cov == 0) {
                outside++;
                changed_outside += diff;
            } else if (cov == 1 && red) {
                box_front++; /* the box face (z = 0.9) is nearer than the sphere (|z| <= 0.5) everywhere */
                box_kept += !diff;
            } else if (cov == 1) {
                glass++;
                drawn += diff;
            }
        }
    snell_write_png(test_out("host_world_before.png"), W, H, before);
    snell_write_png(test_out("host_world_after.png"), W, H, after);
    printf("host world: %d pixels outside the sphere (%d changed), %d of %d sphere pixels drawn, %d of %d box pixels "
           "in front kept\n", outside, changed_outside, drawn, glass, box_kept, box_front);
    CHECK(changed_outside == 0, "%d host pixels outside the glass changed", changed_outside);
    CHECK(glass > 500 && drawn >= glass * 97 / 100, "glass drawn on %d of %d pixels", drawn, glass);
    CHECK(box_front > 100 && box_kept >= box_front * 98 / 100, "the box in front kept on %d of %d pixels", box_kept,
          box_front);

    /* SNELL_DEPTH_TEST_NO_WRITE: the host's depth comes back as it was
     * (drawing the ground again with GL_EQUAL passes everywhere it was) */
    {
        static uint8_t probe[W * H * 4];
        static const float ground[] = {-6, -0.6f, -6, 6, -0.6f, -6, 6, -0.6f, 6, -6, -0.6f, -6, 6, -0.6f, 6, -6, -0.6f, 6};
        static const float white[4] = {1, 1, 1, 1};
        int n_ground = 0, n_white = 0, i;
        host_scene(prog, vp);
        fd.depth = SNELL_DEPTH_TEST_NO_WRITE;
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, W, H);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_EQUAL);
        glDepthMask(GL_FALSE);
        draw_quad(prog, vp, ground, 6, white);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, probe);
        for (i = 0; i < W * H; i++) {
            int was_ground = before[4 * i + 1] > 100 && before[4 * i] < 100;
            n_ground += was_ground;
            n_white += was_ground && probe[4 * i] == 255 && probe[4 * i + 1] == 255 && probe[4 * i + 2] == 255;
        }
        printf("NO_WRITE: %d of %d ground pixels keep their depth\n", n_white, n_ground);
        CHECK(n_ground > 1000 && n_white == n_ground, "the host's depth came back on %d of %d ground pixels", n_white,
              n_ground);
        fd.depth = SNELL_DEPTH_TEST;
    }
done:
    snell_env_destroy(env);
    snell_mesh_destroy(sphere);
    snell_renderer_destroy(r);
    snell_ctx_destroy(ctx);
    glDeleteProgram(prog);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &crb);
    glDeleteRenderbuffers(1, &drb);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, hctx);
}

/* The orbit camera and its own matrices: the same bytes, every method. */
static void orbit_as_matrices(snell_ctx *ctx)
{
    snell_renderer *r = test_renderer(ctx, 64, 48);
    snell_mesh *torus = NULL;
    snell_env *env = test_sky(ctx, 32);
    snell_glass g;
    snell_frame_desc fd;
    static uint8_t a[64 * 48 * 4], b[64 * 48 * 4];
    float eye[3];
    int i;
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_TORUS, .segments = 32, .rings = 16},
                                              &torus));
    if (!r || !torus || !env) goto done;
    memset(&g, 0, sizeof g);
    test_frame_one(&fd, &g, torus, env);
    g.material.ior = 1.45f;
    for (i = 0; i < snell_method_count(); i++) {
        snell_frame_desc m = fd;
        fd.camera = (snell_camera){.azimuth = 0.6f, .elevation = 0.4f, .distance = 3.0f, .fov_y = 0.8f,
                                   .target = {0.1f, 0.0f, 0.0f}};
        m.camera = fd.camera;
        g.material.method = snell_method_info_at(i)->method;
        m.camera.kind = SNELL_CAMERA_MATRICES;
        snell_camera_matrices(&fd.camera, 64.0f / 48.0f, eye, m.camera.view, m.camera.projection);
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, a));
        CHECK_OK_CTX(ctx, snell_render(r, &m, NULL));
        CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, b));
        CHECK(!memcmp(a, b, sizeof a), "%s: the orbit camera and its matrices differ", snell_method_info_at(i)->name);
    }
    /* refused: a projection neither perspective nor orthographic, a singular
     * view, a kind out of range */
    {
        snell_frame_desc m = fd;
        m.camera.kind = SNELL_CAMERA_MATRICES;
        mat4 view, proj; /* cglm's matrices are 16-byte aligned: made here, then copied */
        glm_lookat((vec3){0, 0, 3}, (vec3){0, 0, 0}, (vec3){0, 1, 0}, view);
        glm_perspective(0.8f, 1.0f, 0.1f, 10.0f, proj);
        memcpy(m.camera.view, view, sizeof m.camera.view);
        memcpy(m.camera.projection, proj, sizeof m.camera.projection);
        m.camera.projection[3] = 0.2f; /* a bottom row 0.2 0 -1 0: a tilted image plane */
        CHECK(snell_render(r, &m, NULL) == SNELL_E_UNSUPPORTED && strstr(snell_last_error(ctx), "camera.projection"),
              "projective: %s", snell_last_error(ctx));
        memcpy(m.camera.projection, proj, sizeof m.camera.projection);
        memset(m.camera.view, 0, sizeof m.camera.view);
        CHECK(snell_render(r, &m, NULL) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "camera.view"),
              "singular view: %s", snell_last_error(ctx));
        m.camera.kind = (snell_camera_kind)7;
        CHECK(snell_render(r, &m, NULL) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "camera.kind"),
              "kind 7: %s", snell_last_error(ctx));
        m = fd;
        m.depth = (snell_depth_mode)9;
        CHECK(snell_render(r, &m, NULL) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "depth"),
              "depth 9: %s", snell_last_error(ctx));
        m.depth = SNELL_DEPTH_TEST_NO_WRITE;
        CHECK(snell_render(r, &m, NULL) == SNELL_E_INVALID_ARG, "NO_WRITE on the offscreen target: %s",
              snell_last_error(ctx));
    }
done:
    snell_env_destroy(env);
    snell_mesh_destroy(torus);
    snell_renderer_destroy(r);
}

/* The sphere's glass PSNR against FULL under camera cam (64 x 64): the
 * renderer's AUTO pick and the reference, both through the same matrices. */
static double sphere_psnr(snell_ctx *ctx, const snell_camera *cam, snell_method method)
{
    enum { N = 64 };
    static uint8_t px[N * N * 4], refpx[N * N * 4], hit[N * N];
    static float rgb[N * N * 3];
    snell_renderer *r = test_renderer(ctx, N, N);
    snell_mesh *sphere = NULL;
    snell_env *env = test_sky(ctx, 64);
    snell_ref *ref = NULL;
    snell_glass g;
    snell_frame_desc fd;
    snell_ref_params p;
    snell_ref_output o = {0};
    snell_image_error e = {0};
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE, .segments = 64, .rings = 32},
                                              &sphere));
    if (!r || !sphere || !env) goto done;
    memset(&g, 0, sizeof g);
    test_frame_one(&fd, &g, sphere, env);
    g.material.ior = 1.5f;
    g.material.method = method;
    fd.camera = *cam;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, px));
    CHECK_OK(test_ref_create(ctx, &fd, &ref));
    test_ref_params(&fd, N, N, 0, &p); /* 0: the default interface cap */
    p.mode = SNELL_REF_FULL;
    p.isolate_glass = 1;
    o.rgb = rgb;
    o.hit = hit;
    if (ref) CHECK_OK(snell_ref_render(ref, &p, &o));
    snell_ref_rgb_to_rgba8(rgb, N, N, refpx);
    CHECK_OK(snell_metrics_image_error(px, refpx, N, N, hit, &e));
done:
    snell_ref_destroy(ref);
    snell_env_destroy(env);
    snell_mesh_destroy(sphere);
    snell_renderer_destroy(r);
    return e.psnr_db;
}

/* An off-axis frustum (the lens shifted, as a VR eye's) of the orbit
 * camera's focal length and pixel size, and an orthographic projection of the
 * same pixel size at the sphere: for every method, the glass within 1 dB of
 * the on-axis camera's PSNR against FULL, or better. */
static void projections_accuracy(snell_ctx *ctx)
{
    const snell_camera orbit = {.azimuth = 0.3f, .elevation = 0.25f, .distance = 4.0f, .fov_y = 0.7f};
    snell_camera off = orbit, ortho;
    mat4 proj; /* cglm's matrices are 16-byte aligned: made here, then copied */
    float eye[3], t = 0.04f * tanf(0.35f), half = 4.0f * tanf(0.35f);
    int i;
    off.kind = SNELL_CAMERA_MATRICES;
    snell_camera_matrices(&orbit, 1.0f, eye, off.view, off.projection);
    glm_frustum(-0.6f * t, 1.4f * t, -1.3f * t, 0.7f * t, 0.04f, 400.0f, proj);
    memcpy(off.projection, proj, sizeof off.projection);
    ortho = off;
    glm_ortho(-half, half, -half, half, 0.04f, 400.0f, proj);
    memcpy(ortho.projection, proj, sizeof ortho.projection);
    for (i = -1; i < snell_method_count(); i++) {
        snell_method method = i < 0 ? SNELL_METHOD_AUTO : snell_method_info_at(i)->method;
        double on_axis = sphere_psnr(ctx, &orbit, method), shifted = sphere_psnr(ctx, &off, method);
        double parallel = sphere_psnr(ctx, &ortho, method);
        printf("%s: glass PSNR vs FULL %.2f dB on axis, %.2f off axis, %.2f orthographic\n", snell_method_str(method),
               on_axis, shifted, parallel);
        CHECK(shifted >= on_axis - 1.0, "%s: off axis %.2f dB against %.2f on axis", snell_method_str(method),
              shifted, on_axis);
        CHECK(parallel >= on_axis - 1.0, "%s: orthographic %.2f dB against %.2f on axis", snell_method_str(method),
              parallel, on_axis);
    }
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    if (!ctx) SKIP("no GL context");
    orbit_as_matrices(ctx);
    projections_accuracy(ctx);
    snell_ctx_destroy(ctx);
    host_world();
    return test_finish();
}
