/* SPDX-License-Identifier: MIT */
/* test_backdrop — the host's scene behind the glass (snell_frame_desc.backdrop).
 * A host with its own EGL context, shaders and off-axis camera draws a
 * ground and a red box (lit as snell's opaque objects are lit) into its
 * framebuffer, and snell (EXTERNAL, the bound framebuffer, SNELL_DEPTH_TEST,
 * the host's matrices) draws a glass sphere that refracts that frame:
 *  - host world: the host's pixels outside the sphere unchanged, the glass
 *    on >= 97% of its pixels, the box in front of it kept on >= 98%, and the
 *    glass showing the host's ground where the reference (FULL, the same
 *    backdrop as a depth field: snell_ref_set_backdrop) does: on the pixels
 *    where the reference's glass differs from its glass without the
 *    backdrop, the GPU's is within 2 dB of its PSNR over the whole glass and
 *    above 20 dB; SNELL_BACKDROP_COPY_BOUND gives the same bytes as the
 *    textures it copies;
 *  - accuracy (the sphere, and glmark2's bunny where installed): the glass
 *    PSNR against FULL of the backdrop searched against its depth, of one
 *    screen-space look-up at a distance (the engines' way, its best of four
 *    distances), and of the same scene as snell_opaque objects with the
 *    scene layers (against FULL with those objects): the search beats the
 *    one look-up. `test_backdrop SIZE` prints the table at SIZE x SIZE
 *    (bench/notes/backdrop.md);
 *  - refusals: a texture that is not one, a region outside the textures,
 *    COPY_BOUND on an offscreen renderer or with SNELL_DEPTH_CLEAR. */
#include "test_util.h"
#include "gl_count.h"
#include "snell/snell_metrics.h"
#include "snell/snell_ref.h"

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char k_vs[] = "#version 300 es\nuniform mat4 u_mvp;\nin vec3 a_pos;\n"
                           "void main() { gl_Position = u_mvp * vec4(a_pos, 1.0); }\n";
/* opaque.frag's light: colour * (0.25 + 0.75 * half-Lambert from the sky) */
static const char k_fs[] = "#version 300 es\nprecision highp float;\nuniform vec3 u_color;\nuniform vec3 u_n;\n"
                           "out vec4 o;\nvoid main() {\n"
                           "  float l = 0.5 + 0.5 * dot(u_n, normalize(vec3(0.3, 1.0, 0.2)));\n"
                           "  o = vec4(u_color * (0.25 + 0.75 * l), 1.0);\n}\n";
/* the window depth in RGBA8, 24 bits (the reference's copy of the depth texture) */
static const char k_fs_depth[] = "#version 300 es\nprecision highp float;\nout vec4 o;\nvoid main() {\n"
                                 "  highp uint q = uint(gl_FragCoord.z * 16777215.0 + 0.5);\n"
                                 "  o = (vec4(uvec4(q >> 16u, (q >> 8u) & 255u, q & 255u, 255u)) + 0.25) / 255.0;\n}\n";

typedef struct host {
    int w, h;
    GLuint prog, prog_depth, vao, vbo;
    GLuint fbo_a, tex_color, tex_depth; /* the frame behind the glass, as textures */
    GLuint fbo_b, rb_color, rb_depth;   /* the host's framebuffer snell draws into */
    GLuint fbo_p, rb_p, rb_pd;          /* the depth packed into colour */
    mat4 view, proj, vp;
    float box[6];                       /* min xyz, max xyz */
} host;

static const float k_ground = -0.6f;
static const float k_ground_color[3] = {0.25f, 0.6f, 0.3f}, k_box_color[3] = {0.85f, 0.15f, 0.1f};

static GLuint program(const char *fs)
{
    GLuint p = glCreateProgram(), s[2];
    const char *src[2] = {k_vs, fs};
    GLint ok = 0;
    int i;
    for (i = 0; i < 2; i++) {
        s[i] = glCreateShader(i ? GL_FRAGMENT_SHADER : GL_VERTEX_SHADER);
        glShaderSource(s[i], 1, &src[i], NULL);
        glCompileShader(s[i]);
        glAttachShader(p, s[i]);
        glDeleteShader(s[i]);
    }
    glBindAttribLocation(p, 0, "a_pos");
    glLinkProgram(p);
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    CHECK(ok, "host program links");
    return p;
}

static void target(GLuint *fbo, GLuint *color, GLuint *depth, int w, int h, int textures)
{
    glGenFramebuffers(1, fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
    if (textures) {
        glGenTextures(1, color);
        glBindTexture(GL_TEXTURE_2D, *color);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, w, h);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, *color, 0);
        glGenTextures(1, depth);
        glBindTexture(GL_TEXTURE_2D, *depth);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT24, w, h);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, *depth, 0);
        glBindTexture(GL_TEXTURE_2D, 0);
    } else {
        glGenRenderbuffers(1, color);
        glBindRenderbuffer(GL_RENDERBUFFER, *color);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, *color);
        glGenRenderbuffers(1, depth);
        glBindRenderbuffer(GL_RENDERBUFFER, *depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, *depth);
    }
    CHECK(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE, "host framebuffer complete");
}

/* The host's camera: eye at (0.4, 0.9, 3.2) looking at (0, -0.1, 0); off
 * axis (the lens shifted right and up) unless on_axis. */
static void host_make(host *h, int w, int h_, int on_axis, const float box[6])
{
    vec3 eye = {0.4f, 0.9f, 3.2f}, at = {0.0f, -0.1f, 0.0f}, up = {0.0f, 1.0f, 0.0f};
    const float n = 0.1f, f = 50.0f, t = 0.045f, aspect = (float)w / (float)h_;
    memset(h, 0, sizeof *h);
    h->w = w, h->h = h_;
    memcpy(h->box, box, sizeof h->box);
    h->prog = program(k_fs);
    h->prog_depth = program(k_fs_depth);
    glGenVertexArrays(1, &h->vao);
    glGenBuffers(1, &h->vbo);
    target(&h->fbo_a, &h->tex_color, &h->tex_depth, w, h_, 1);
    target(&h->fbo_b, &h->rb_color, &h->rb_depth, w, h_, 0);
    target(&h->fbo_p, &h->rb_p, &h->rb_pd, w, h_, 0);
    glm_lookat(eye, at, up, h->view);
    if (on_axis)
        glm_frustum(-t * aspect, t * aspect, -t, t, n, f, h->proj);
    else
        glm_frustum(-0.7f * t * aspect, 1.3f * t * aspect, -0.8f * t, 1.2f * t, n, f, h->proj);
    glm_mat4_mul(h->proj, h->view, h->vp);
}

static void host_free(host *h)
{
    glDeleteProgram(h->prog);
    glDeleteProgram(h->prog_depth);
    glDeleteVertexArrays(1, &h->vao);
    glDeleteBuffers(1, &h->vbo);
    glDeleteFramebuffers(1, &h->fbo_a);
    glDeleteFramebuffers(1, &h->fbo_b);
    glDeleteFramebuffers(1, &h->fbo_p);
    glDeleteTextures(1, &h->tex_color);
    glDeleteTextures(1, &h->tex_depth);
    glDeleteRenderbuffers(1, &h->rb_color);
    glDeleteRenderbuffers(1, &h->rb_depth);
    glDeleteRenderbuffers(1, &h->rb_p);
    glDeleteRenderbuffers(1, &h->rb_pd);
}

/* One axis-aligned face (axis a, at coordinate v, normal sign s) of the box lo..hi. */
static void face(const host *h, GLuint prog, const float lo[3], const float hi[3], int a, int s, const float color[3])
{
    float q[18], n[3] = {0, 0, 0};
    int b = (a + 1) % 3, c = (a + 2) % 3, i;
    const float u[6] = {0, 1, 1, 0, 1, 0}, v[6] = {0, 0, 1, 0, 1, 1};
    for (i = 0; i < 6; i++) {
        q[3 * i + a] = s > 0 ? hi[a] : lo[a];
        q[3 * i + b] = u[i] ? hi[b] : lo[b];
        q[3 * i + c] = v[i] ? hi[c] : lo[c];
    }
    n[a] = (float)s;
    glBindBuffer(GL_ARRAY_BUFFER, h->vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof q, q, GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, 0);
    glUniform3fv(glGetUniformLocation(prog, "u_color"), 1, color);
    glUniform3fv(glGetUniformLocation(prog, "u_n"), 1, n);
    glDrawArrays(GL_TRIANGLES, 0, 6);
}

/* The host's scene into fbo: the ground's top face (y = k_ground, 6 x 6) and the box. */
static void host_draw(const host *h, GLuint fbo, GLuint prog)
{
    const float glo[3] = {-3, k_ground - 0.1f, -3}, ghi[3] = {3, k_ground, 3};
    int a;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, h->w, h->h);
    glBindVertexArray(h->vao);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearColor(prog == h->prog ? 0.1f : 1.0f, prog == h->prog ? 0.1f : 1.0f, prog == h->prog ? 0.3f : 1.0f, 1.0f);
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(prog);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_mvp"), 1, GL_FALSE, (const float *)h->vp);
    face(h, prog, glo, ghi, 1, 1, k_ground_color);
    for (a = 0; a < 6; a++) face(h, prog, h->box, h->box + 3, a / 2, a & 1 ? -1 : 1, k_box_color);
    glBindVertexArray(0);
}

/* The host's frame (bottom row first) and its window depths, for the reference. */
static void host_read(const host *h, uint8_t *rgba, float *depth)
{
    size_t i, n = (size_t)h->w * (size_t)h->h;
    host_draw(h, h->fbo_a, h->prog);
    glReadPixels(0, 0, h->w, h->h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    host_draw(h, h->fbo_p, h->prog_depth);
    glReadPixels(0, 0, h->w, h->h, GL_RGBA, GL_UNSIGNED_BYTE, (uint8_t *)depth);
    for (i = 0; i < n; i++) { /* in place: 4 bytes a pixel either way */
        const uint8_t *b = (const uint8_t *)&depth[i];
        uint32_t q = ((uint32_t)b[0] << 16) | ((uint32_t)b[1] << 8) | b[2];
        depth[i] = (float)((double)q / 16777215.0);
    }
}

static void flip_rows(uint8_t *px, int w, int h)
{
    size_t row = (size_t)w * 4;
    uint8_t tmp[4 * 1024];
    int y;
    for (y = 0; y < h / 2; y++) {
        memcpy(tmp, px + (size_t)y * row, row);
        memcpy(px + (size_t)y * row, px + (size_t)(h - 1 - y) * row, row);
        memcpy(px + (size_t)(h - 1 - y) * row, tmp, row);
    }
}

static void host_camera(const host *h, snell_camera *cam)
{
    memset(cam, 0, sizeof *cam);
    cam->kind = SNELL_CAMERA_MATRICES;
    memcpy(cam->view, h->view, sizeof cam->view);
    memcpy(cam->projection, h->proj, sizeof cam->projection);
}

/* The host's frame copied into its framebuffer, then snell's frame over it; px top row first. */
static snell_status draw_over(const host *h, snell_renderer *r, const snell_frame_desc *fd, uint8_t *px)
{
    snell_status st;
    host_draw(h, h->fbo_a, h->prog);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, h->fbo_a);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, h->fbo_b);
    glBlitFramebuffer(0, 0, h->w, h->h, 0, 0, h->w, h->h, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, h->fbo_b);
    st = snell_render(r, fd, NULL);
    glBindFramebuffer(GL_FRAMEBUFFER, h->fbo_b);
    glReadPixels(0, 0, h->w, h->h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    flip_rows(px, h->w, h->h);
    return st;
}

/* FULL of the glass (and opaque objects) with the backdrop b (NULL none), top row first. */
static int reference(snell_ctx *ctx, const snell_frame_desc *fd, const snell_ref_backdrop *b, int w, int h,
                     uint8_t *px, uint8_t *hit)
{
    snell_ref *ref = NULL;
    snell_ref_params p;
    float *rgb = (float *)malloc((size_t)w * h * 3 * sizeof(float));
    int ok = 0;
    CHECK_OK(test_ref_create(ctx, fd, &ref));
    if (ref && rgb && (!b || snell_ref_set_backdrop(ref, b) == SNELL_OK)) {
        test_ref_params(fd, w, h, 0, &p);
        p.mode = SNELL_REF_FULL;
        p.isolate_glass = 1;
        ok = test_ref_render(ref, &p, rgb, NULL, hit) == SNELL_OK;
        snell_ref_rgb_to_rgba8(rgb, w, h, px);
    }
    CHECK(ok, "reference: %s", snell_last_error(ctx));
    snell_ref_destroy(ref);
    free(rgb);
    return ok;
}

static double psnr(const uint8_t *a, const uint8_t *b, const uint8_t *mask, int w, int h)
{
    snell_image_error e;
    memset(&e, 0, sizeof e);
    CHECK_OK(snell_metrics_image_error(a, b, w, h, mask, &e));
    return e.psnr_db;
}

/* Does the host camera's ray through pixel (x, y) (top row 0) meet the sphere
 * (centre 0, radius r)? 1 at the centre and the four corners, 0 at none, -1 between. */
static int sphere_covers(const host *hs, float r, int x, int y)
{
    mat4 inv;
    int hits = 0, k, i;
    glm_mat4_inv((vec4 *)hs->vp, inv);
    for (k = 0; k < 5; k++) {
        const float fx[5] = {0.5f, 0.0f, 1.0f, 0.0f, 1.0f}, fy[5] = {0.5f, 0.0f, 0.0f, 1.0f, 1.0f};
        float gy = (float)(hs->h - 1 - y) + fy[k];
        vec4 a = {2.0f * ((float)x + fx[k]) / hs->w - 1.0f, 2.0f * gy / hs->h - 1.0f, -1.0f, 1.0f};
        vec4 b = {a[0], a[1], 1.0f, 1.0f}, pa, pb;
        float d[3], bq = 0, cq = 0, len = 0;
        glm_mat4_mulv(inv, a, pa);
        glm_mat4_mulv(inv, b, pb);
        for (i = 0; i < 3; i++) {
            pa[i] /= pa[3], pb[i] /= pb[3];
            d[i] = pb[i] - pa[i];
            len += d[i] * d[i];
        }
        for (i = 0; i < 3; i++) {
            d[i] /= sqrtf(len);
            bq += pa[i] * d[i];
            cq += pa[i] * pa[i];
        }
        hits += bq * bq - (cq - r * r) > 0.0f;
    }
    return hits == 5 ? 1 : hits == 0 ? 0 : -1;
}

/* snell's allocations, counted (none per frame after the first) */
static long g_allocs;
static void *count_alloc(size_t n, void *u) { (void)u; g_allocs++; return malloc(n); }
static void *count_realloc(void *p, size_t n, void *u) { (void)u; g_allocs++; return realloc(p, n); }
static void count_free(void *p, void *u) { (void)u; free(p); }

static const float k_half[16] = {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1};

static void host_world(void)
{
    enum { W = 128, H = 96 };
    static const float box_front[6] = {-0.45f, k_ground, 0.75f, 0.1f, 0.35f, 0.9f};
    static uint8_t before[W * H * 4], after[W * H * 4], copied[W * H * 4], plain[W * H * 4], ref_bd[W * H * 4],
        ref_env[W * H * 4], hit[W * H], hit_env[W * H], ground_mask[W * H], glass_mask[W * H], rgba[W * H * 4];
    static float depth[W * H];
    EGLDisplay dpy;
    EGLContext hctx;
    snell_ctx *ctx = NULL;
    snell_ctx_desc cd = {.backend = SNELL_BACKEND_EXTERNAL,
                         .allocator = {.alloc = count_alloc, .realloc = count_realloc, .free = count_free}};
    snell_renderer *r = NULL;
    snell_renderer_desc rd = {.width = W, .height = H, .target = SNELL_TARGET_BOUND_FRAMEBUFFER};
    snell_mesh *sphere = NULL;
    snell_env *env = NULL;
    snell_glass g;
    snell_frame_desc fd;
    snell_backdrop bd;
    snell_ref_backdrop rb;
    snell_frame_stats fs;
    host hs;
    int x, y, glass = 0, drawn = 0, outside = 0, changed = 0, box_front_n = 0, box_kept = 0, n_ground = 0;
    double all, ground, without;
    if (!test_host_context(&dpy, &hctx)) {
        printf("no host context: host world not checked\n");
        return;
    }
    host_make(&hs, W, H, 0, box_front);
    CHECK_OK(snell_ctx_create(&cd, &ctx));
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE, .segments = 48,
                                                                         .rings = 24}, &sphere));
    env = test_sky(ctx, 32);
    if (!r || !sphere || !env) goto done;
    test_frame_one(&fd, &g, sphere, env);
    g.material.ior = 1.5f;
    g.material.tint[0] = 0.9f, g.material.tint[1] = 0.95f, g.material.tint[2] = 1.0f; /* every glass pixel differs */
    g.model = k_half;
    fd.draw_background = -1;
    fd.depth = SNELL_DEPTH_TEST;
    host_camera(&hs, &fd.camera);
    memset(&bd, 0, sizeof bd);
    bd.color_texture = hs.tex_color;
    bd.depth_texture = hs.tex_depth;
    bd.width = W, bd.height = H;
    fd.backdrop = &bd;

    host_draw(&hs, hs.fbo_b, hs.prog);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, before);
    flip_rows(before, W, H);
    CHECK_OK_CTX(ctx, draw_over(&hs, r, &fd, after));
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs)); /* again: the stats (over its own glass: not read) */
    CHECK(fs.backdrop == 2 && strstr(fs.stages, "backdrop"), "backdrop searched against its depth: %d, stages %s",
          fs.backdrop, fs.stages);
    /* the same frame with snell copying the host's framebuffer itself */
    bd.source = SNELL_BACKDROP_COPY_BOUND;
    host_draw(&hs, hs.fbo_b, hs.prog);
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    glBindFramebuffer(GL_FRAMEBUFFER, hs.fbo_b);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, copied);
    flip_rows(copied, W, H);
    CHECK(!memcmp(copied, after, sizeof after), "COPY_BOUND differs from the textures it copies");
    { /* after the first frames of each: no allocation, no GL object made */
        long allocs = g_allocs;
        gl_counts before_n = gl_count_objects(), after_n;
        int k;
        for (k = 0; k < 4; k++) {
            bd.source = k & 1 ? SNELL_BACKDROP_COPY_BOUND : SNELL_BACKDROP_TEXTURES;
            bd.distance = k < 2 ? 0.0f : 1.5f;
            bd.depth_texture = k < 2 ? hs.tex_depth : 0;
            glBindFramebuffer(GL_FRAMEBUFFER, hs.fbo_b);
            CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        }
        after_n = gl_count_objects();
        CHECK(g_allocs == allocs, "%ld allocations in 4 frames after the first", g_allocs - allocs);
        CHECK(gl_counts_equal(&before_n, &after_n), "GL objects made in frames after the first");
        bd.depth_texture = hs.tex_depth;
        bd.distance = 0.0f;
    }
    bd.source = SNELL_BACKDROP_TEXTURES;
    fd.backdrop = NULL;
    CHECK_OK_CTX(ctx, draw_over(&hs, r, &fd, plain));
    fd.backdrop = &bd;

    /* the reference with and without the backdrop: where they differ, the glass shows the host's scene */
    host_read(&hs, rgba, depth);
    memset(&rb, 0, sizeof rb);
    rb.rgba = rgba, rb.depth = depth, rb.width = W, rb.height = H;
    rb.camera = fd.camera;
    if (!reference(ctx, &fd, &rb, W, H, ref_bd, hit) || !reference(ctx, &fd, NULL, W, H, ref_env, hit_env)) goto done;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int i = y * W + x, cov = sphere_covers(&hs, 0.5f, x, y);
            int red = before[4 * i] > 150 && before[4 * i + 1] < 60;
            int diff = memcmp(before + 4 * i, after + 4 * i, 3) != 0;
            if (cov == 0) {
                outside++;
                changed += diff;
            } else if (cov == 1 && red) {
                box_front_n++; /* the box face (z = 0.9) is nearer than the sphere everywhere */
                box_kept += !diff;
            } else if (cov == 1) {
                glass++;
                drawn += diff;
            }
            glass_mask[i] = cov == 1 && hit[i];
            ground_mask[i] = glass_mask[i] && (abs(ref_bd[4 * i] - ref_env[4 * i]) + abs(ref_bd[4 * i + 1] - ref_env[4 * i + 1]) +
                                               abs(ref_bd[4 * i + 2] - ref_env[4 * i + 2])) > 12;
            n_ground += ground_mask[i];
        }
    all = psnr(after, ref_bd, glass_mask, W, H);
    ground = psnr(after, ref_bd, ground_mask, W, H);
    without = psnr(plain, ref_bd, ground_mask, W, H);
    snell_write_png(test_out("backdrop_host_before.png"), W, H, before);
    snell_write_png(test_out("backdrop_host_after.png"), W, H, after);
    snell_write_png(test_out("backdrop_host_ref.png"), W, H, ref_bd);
    printf("host world: %d pixels outside the sphere (%d changed), %d of %d sphere pixels drawn, %d of %d box pixels "
           "in front kept; the reference's glass shows the host's scene on %d of %d pixels: GPU %.2f dB there "
           "(%.2f without the backdrop), %.2f dB on the whole glass\n", outside, changed, drawn, glass, box_kept,
           box_front_n, n_ground, glass, ground, without, all);
    CHECK(changed == 0, "%d host pixels outside the glass changed", changed);
    CHECK(glass > 300 && drawn >= glass * 97 / 100, "glass drawn on %d of %d pixels", drawn, glass);
    CHECK(box_front_n > 100 && box_kept >= box_front_n * 98 / 100, "the box in front kept on %d of %d pixels", box_kept,
          box_front_n);
    CHECK(n_ground > glass / 2, "the reference's glass shows the host's scene on only %d of %d pixels", n_ground, glass);
    CHECK(ground > 20.0 && ground >= all - 2.0 && ground > without + 6.0,
          "where the reference shows the host's scene: %.2f dB (whole glass %.2f, without the backdrop %.2f)", ground,
          all, without);

    /* refusals */
    bd.color_texture = 999999;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "color_texture"),
          "not a texture: %s", snell_last_error(ctx));
    bd.color_texture = hs.tex_color;
    bd.region[0] = 100, bd.region[2] = 64, bd.region[3] = 64;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "region"),
          "region outside: %s", snell_last_error(ctx));
    memset(bd.region, 0, sizeof bd.region);
    bd.source = SNELL_BACKDROP_COPY_BOUND;
    fd.depth = SNELL_DEPTH_CLEAR;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "SNELL_DEPTH_CLEAR"),
          "copy after clear: %s", snell_last_error(ctx));
    bd.source = (snell_backdrop_source)5;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "source"),
          "source 5: %s", snell_last_error(ctx));
done:
    snell_env_destroy(env);
    snell_mesh_destroy(sphere);
    snell_renderer_destroy(r);
    snell_ctx_destroy(ctx);
    host_free(&hs);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, hctx);
}

/* A snell_opaque axis-aligned box lo..hi from the unit cube (-1..1). */
static void box_model(const float b[6], float m[16])
{
    int k;
    memset(m, 0, 16 * sizeof *m);
    for (k = 0; k < 3; k++) {
        m[5 * k] = 0.5f * (b[3 + k] - b[k]);
        m[12 + k] = 0.5f * (b[3 + k] + b[k]);
    }
    m[15] = 1.0f;
}

/* The glass (mesh, model) in front of the host's ground and a box behind
 * it, N x N, on axis: the glass PSNR against FULL of the three ways. */
static void accuracy(const char *name, const char *path, int n, int check)
{
    static const float box_back[6] = {-0.3f, k_ground, -1.5f, 0.7f, 0.6f, -0.9f};
    static const float ground_box[6] = {-3, k_ground - 0.1f, -3, 3, k_ground, 3};
    static const float distances[4] = {0.5f, 1.0f, 2.0f, 4.0f};
    size_t px = (size_t)n * n;
    uint8_t *gpu = (uint8_t *)malloc(px * 4), *ref = (uint8_t *)malloc(px * 4), *hit = (uint8_t *)malloc(px);
    uint8_t *rgba = (uint8_t *)malloc(px * 4);
    float *depth = (float *)malloc(px * sizeof(float)), model[16], m_ground[16], m_box[16], lo[3], hi[3];
    EGLDisplay dpy;
    EGLContext hctx;
    snell_ctx *ctx = NULL;
    snell_ctx_desc cd = {.backend = SNELL_BACKEND_EXTERNAL};
    snell_renderer *r = NULL;
    snell_renderer_desc rd = {.width = n, .height = n, .target = SNELL_TARGET_BOUND_FRAMEBUFFER};
    snell_mesh *mesh = NULL, *cube = NULL;
    snell_env *env = NULL;
    snell_glass g;
    snell_opaque op[2];
    snell_frame_desc fd;
    snell_backdrop bd;
    snell_ref_backdrop rb;
    host hs;
    double searched, look = 0.0, opaque;
    float best_d = 0.0f, s = 0.0f;
    int i, k;
    if (!test_host_context(&dpy, &hctx)) {
        printf("no host context: accuracy not measured\n");
        goto out;
    }
    host_make(&hs, n, n, 1, box_back);
    CHECK_OK(snell_ctx_create(&cd, &ctx));
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (path)
        CHECK_OK_CTX(ctx, snell_mesh_load(ctx, path, &mesh));
    else
        CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE, .segments = 64,
                                                                             .rings = 32}, &mesh));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_CUBE}, &cube));
    env = test_sky(ctx, 64);
    if (!r || !mesh || !cube || !env) goto done;
    /* the mesh fitted into the sphere of radius 0.5 at the origin */
    snell_mesh_bounds(mesh, lo, hi);
    for (k = 0; k < 3; k++) s += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    s = 0.5f / sqrtf(s);
    memset(model, 0, sizeof model);
    for (k = 0; k < 3; k++) {
        model[5 * k] = s;
        model[12 + k] = -s * 0.5f * (lo[k] + hi[k]);
    }
    model[15] = 1.0f;
    test_frame_one(&fd, &g, mesh, env);
    g.model = model;
    g.material.ior = 1.5f;
    host_camera(&hs, &fd.camera);
    fd.draw_background = -1;
    fd.depth = SNELL_DEPTH_TEST;
    memset(&bd, 0, sizeof bd);
    bd.color_texture = hs.tex_color;
    bd.depth_texture = hs.tex_depth;
    bd.width = bd.height = n;
    fd.backdrop = &bd;
    host_read(&hs, rgba, depth);
    memset(&rb, 0, sizeof rb);
    rb.rgba = rgba, rb.depth = depth, rb.width = rb.height = n;
    rb.camera = fd.camera;
    if (!reference(ctx, &fd, &rb, n, n, ref, hit)) goto done;
    CHECK_OK_CTX(ctx, draw_over(&hs, r, &fd, gpu));
    searched = psnr(gpu, ref, hit, n, n);
    if (n >= 256) snell_write_png(test_out("backdrop_searched.png"), n, n, gpu);
    bd.depth_texture = 0;
    for (i = 0; i < 4; i++) {
        double p;
        bd.distance = distances[i];
        CHECK_OK_CTX(ctx, draw_over(&hs, r, &fd, gpu));
        p = psnr(gpu, ref, hit, n, n);
        if (p > look) look = p, best_d = distances[i];
    }
    /* the same scene as snell's opaque objects, peeled with the glass into the scene layers */
    fd.backdrop = NULL;
    fd.draw_background = 0;
    fd.depth = SNELL_DEPTH_CLEAR;
    memset(op, 0, sizeof op);
    box_model(ground_box, m_ground);
    box_model(box_back, m_box);
    op[0].mesh = op[1].mesh = cube;
    op[0].model = m_ground, op[1].model = m_box;
    memcpy(op[0].color, k_ground_color, sizeof op[0].color);
    memcpy(op[1].color, k_box_color, sizeof op[1].color);
    fd.opaque = op;
    fd.opaque_count = 2;
    if (!reference(ctx, &fd, NULL, n, n, ref, hit)) goto done;
    glBindFramebuffer(GL_FRAMEBUFFER, hs.fbo_b);
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    glBindFramebuffer(GL_FRAMEBUFFER, hs.fbo_b);
    glReadPixels(0, 0, n, n, GL_RGBA, GL_UNSIGNED_BYTE, gpu);
    flip_rows(gpu, n, n);
    opaque = psnr(gpu, ref, hit, n, n);
    printf("%s %dx%d: glass PSNR vs FULL: backdrop searched against its depth %.2f dB, one look-up %.2f dB (best "
           "distance %.1f), snell_opaque + scene layers %.2f dB\n", name, n, n, searched, look, (double)best_d, opaque);
    if (check) CHECK(searched > look, "%s: the search %.2f dB is not better than one look-up %.2f dB", name, searched, look);
done:
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
    snell_mesh_destroy(cube);
    snell_renderer_destroy(r);
    snell_ctx_destroy(ctx);
    host_free(&hs);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, hctx);
out:
    free(gpu), free(ref), free(hit), free(rgba), free(depth);
}

/* COPY_BOUND needs a bound framebuffer to copy. */
static void offscreen_refusal(void)
{
    snell_ctx *ctx = test_ctx();
    snell_renderer *r = ctx ? test_renderer(ctx, 16, 16) : NULL;
    snell_mesh *sphere = NULL;
    snell_env *env = ctx ? test_sky(ctx, 16) : NULL;
    snell_glass g;
    snell_frame_desc fd;
    snell_backdrop bd;
    if (!r || !env || snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE}, &sphere) != SNELL_OK)
        goto done;
    test_frame_one(&fd, &g, sphere, env);
    memset(&bd, 0, sizeof bd);
    bd.source = SNELL_BACKDROP_COPY_BOUND;
    fd.backdrop = &bd;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "BOUND_FRAMEBUFFER"),
          "COPY_BOUND offscreen: %s", snell_last_error(ctx));
done:
    snell_mesh_destroy(sphere);
    snell_env_destroy(env);
    snell_renderer_destroy(r);
    snell_ctx_destroy(ctx);
}

int main(int argc, char **argv)
{
    const char *bunny = "/usr/share/glmark2/models/bunny.obj";
    FILE *f = fopen(bunny, "rb");
    int n = argc > 1 ? atoi(argv[1]) : 0;
    if (f) fclose(f);
    if (n > 0) { /* the figures of bench/notes/backdrop.md */
        accuracy("sphere", NULL, n, 0);
        if (f) accuracy("bunny", bunny, n, 0);
        return test_finish();
    }
    offscreen_refusal();
    host_world();
    accuracy("sphere", NULL, 64, 1);
    if (f) accuracy("bunny", bunny, 64, 1);
    else printf("no %s: the bunny not measured\n", bunny);
    return test_finish();
}
