/* SPDX-License-Identifier: MIT */
/* test_camera_engines — the cameras engines use (issue 48), as matrices,
 * each against its standard equivalent (glm's perspective, a rigid view) in
 * every method (forward and screen-space shading) and the reference, to a
 * few edge pixels: reversed-Z P' = [z -> -z] x P (depth 1 - d), finite,
 * infinite far (against far 1e6) and orthographic; an oblique near plane
 * (Lengyel 2005) beyond it; a view mirrored in x on either matrix (the image
 * flipped in x); a scaled view undone by the projection. Refused by name:
 * near 1e-7, a negated orthographic, singular or degenerate matrix, oblique
 * with the target's depth tested. */
#include "test_util.h"
#include "snell/snell_ref.h"

#include <cglm/cglm.h>
#include <math.h>
#include <string.h>

#define N 64
#define NR 24
#define EDGE 12 /* pixels a case may differ by (of N x N): a few along the glass's edges */

static const float k_model[16] = {0.9f, 0, 0, 0, 0, 0.45f, 0.78f, 0, 0, -0.78f, 0.45f, 0, 0.3f, 0.1f, 0, 1};

typedef struct cam {
    const char *name;
    mat4 view, proj;
    int flip;     /* the expected image is the standard one flipped in x */
    int base;     /* its standard equivalent: 0 far 50, 1 far 1e6 (an infinite far), 2 orthographic */
} cam;

static void standard(mat4 view, mat4 proj, int base)
{
    vec3 eye = {0.6f, 0.8f, 3.2f}, at = {0.0f, 0.0f, 0.0f}, up = {0.0f, 1.0f, 0.0f};
    glm_lookat(eye, at, up, view);
    if (base == 2) glm_ortho(-1.6f, 1.6f, -1.6f, 1.6f, 0.5f, 20.0f, proj);
    else glm_perspective(0.8f, 1.0f, 0.1f, base ? 1e6f : 50.0f, proj);
}

static void mul_left(const float l[16], mat4 m) /* m = l x m */
{
    mat4 a, b;
    memcpy(a, l, sizeof a);
    glm_mat4_mul(a, m, b);
    glm_mat4_copy(b, m);
}

/* P with its depth row through the eye-space clip plane c (Lengyel, "Oblique
 * view frustum depth projection and clipping", JGT 2005). */
static void oblique(mat4 p, const float c[4])
{
    vec4 q, cc;
    float s;
    int k;
    q[0] = ((c[0] > 0.0f) - (c[0] < 0.0f) + p[2][0]) / p[0][0];
    q[1] = ((c[1] > 0.0f) - (c[1] < 0.0f) + p[2][1]) / p[1][1];
    q[2] = -1.0f;
    q[3] = (1.0f + p[2][2]) / p[3][2];
    s = 2.0f / (c[0] * q[0] + c[1] * q[1] + c[2] * q[2] + c[3] * q[3]);
    for (k = 0; k < 4; k++) cc[k] = c[k] * s;
    p[0][2] = cc[0], p[1][2] = cc[1], p[2][2] = cc[2] + 1.0f, p[3][2] = cc[3];
}

static int make_cases(cam *c)
{
    static const float rev[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1};
    static const float flip[16] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    static const float grow[16] = {2.5f, 0, 0, 0, 0, 2.5f, 0, 0, 0, 0, 2.5f, 0, 0, 0, 0, 1};
    static const float clip[4] = {0.25f, 0.3f, -1.0f, -1.2f}; /* tilted, 1.2 ahead, the eye behind it */
    int n = 0, i;
    mat4 view, inf;
    standard(view, inf, 0);
    inf[2][2] = -1.0f, inf[3][2] = -0.2f; /* far -> infinity: -(f + n) / (f - n) -> -1, -2fn / (f - n) -> -2n */
    for (i = 0; i < 8; i++) standard(c[i].view, c[i].proj, i == 7 ? 2 : 0);
    c[n].name = "reversed-Z", mul_left(rev, c[n].proj), n++;
    c[n].name = "infinite far", glm_mat4_copy(inf, c[n].proj), c[n].base = 1, n++;
    c[n].name = "reversed-Z infinite far", glm_mat4_copy(inf, c[n].proj), mul_left(rev, c[n].proj);
    c[n].base = 1, n++;
    c[n].name = "oblique near plane", oblique(c[n].proj, clip), n++;
    c[n].name = "mirrored view", mul_left(flip, c[n].view), c[n].flip = 1, n++;
    c[n].name = "mirrored projection", mul_left(flip, c[n].proj), c[n].flip = 1, n++;
    c[n].name = "scaled view, projection undoing it", mul_left(grow, c[n].view);
    {
        mat4 shrink = GLM_MAT4_IDENTITY_INIT, p;
        shrink[0][0] = shrink[1][1] = shrink[2][2] = 0.4f;
        glm_mat4_mul(c[n].proj, shrink, p);
        glm_mat4_copy(p, c[n].proj);
    }
    n++;
    c[n].name = "reversed-Z orthographic", mul_left(rev, c[n].proj), c[n].base = 2, n++;
    return n;
}

static void set_camera(snell_camera *sc, mat4 view, mat4 proj)
{
    memset(sc, 0, sizeof *sc);
    sc->kind = SNELL_CAMERA_MATRICES;
    memcpy(sc->view, view, sizeof sc->view);
    memcpy(sc->projection, proj, sizeof sc->projection);
}

/* Pixels where a and b (RGBA8, w x h; b flipped in x if flip) differ by more than 24 in a channel. */
static int differ(const uint8_t *a, const uint8_t *b, int w, int h, int flip)
{
    int x, y, k, n = 0;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            const uint8_t *p = a + 4 * (y * w + x), *q = b + 4 * (y * w + (flip ? w - 1 - x : x));
            for (k = 0; k < 3 && abs(p[k] - q[k]) <= 24; k++) {}
            n += k < 3;
        }
    return n;
}

static void refusals(snell_ctx *ctx, snell_renderer *r, snell_frame_desc *fd, cam *oblique_cam)
{
    mat4 view, proj;
    snell_status st;
    standard(view, proj, 0);
    glm_perspective(0.8f, 1.0f, 1e-7f, 50.0f, proj);
    set_camera(&fd->camera, view, proj);
    st = snell_render(r, fd, NULL);
    CHECK(st == SNELL_E_UNSUPPORTED && strstr(snell_last_error(ctx), "near plane"), "near 1e-7: %s: %s",
          snell_status_str(st), snell_last_error(ctx));
    glm_ortho(-2, 2, -2, 2, 0.1f, 20.0f, proj);
    glm_mat4_scale(proj, -1.0f);
    set_camera(&fd->camera, view, proj);
    st = snell_render(r, fd, NULL);
    CHECK(st == SNELL_E_UNSUPPORTED && strstr(snell_last_error(ctx), "orthographic"), "negated ortho: %s: %s",
          snell_status_str(st), snell_last_error(ctx));
    standard(view, proj, 0);
    memset(view[2], 0, sizeof view[2]);
    set_camera(&fd->camera, view, proj);
    st = snell_render(r, fd, NULL);
    CHECK(st == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "singular"), "singular view: %s: %s",
          snell_status_str(st), snell_last_error(ctx));
    standard(view, proj, 0);
    /* invertible, but clip y and w vary along the same direction: no camera has these pixels */
    set_camera(&fd->camera, view, (mat4){{1, 0, 0, 0}, {0, 0, 1, 0}, {0, -1, 0.5f, -1}, {0, 1, -0.2f, 0}});
    st = snell_render(r, fd, NULL);
    CHECK(st == SNELL_E_UNSUPPORTED && strstr(snell_last_error(ctx), "degenerate"), "degenerate rows: %s: %s",
          snell_status_str(st), snell_last_error(ctx));
    mul_left((const float[16]){1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1}, proj);
    set_camera(&fd->camera, view, proj);
    fd->depth = SNELL_DEPTH_TEST;
    st = snell_render(r, fd, NULL); /* snell's own depth is its own convention (test_reversed_z_host: a host's) */
    CHECK(st == SNELL_OK, "reversed-Z, depth tested offscreen: %s: %s", snell_status_str(st), snell_last_error(ctx));
    set_camera(&fd->camera, oblique_cam->view, oblique_cam->proj);
    st = snell_render(r, fd, NULL);
    CHECK(st == SNELL_E_UNSUPPORTED && strstr(snell_last_error(ctx), "oblique"), "oblique, depth tested: %s: %s",
          snell_status_str(st), snell_last_error(ctx));
    fd->depth = SNELL_DEPTH_DEFAULT;
}

/* The reference through each camera against it through the standard one. */
static void reference(snell_ctx *ctx, snell_frame_desc *fd, cam *c, int n)
{
    static float base[3][NR * NR * 3], img[NR * NR * 3];
    static uint8_t a[NR * NR * 4], b[NR * NR * 4];
    snell_ref *ref = NULL;
    snell_ref_params p;
    mat4 view, proj;
    int i, f;
    CHECK_OK_CTX(ctx, test_ref_create(ctx, fd, &ref));
    if (!ref) return;
    for (f = 0; f < 3; f++) {
        standard(view, proj, f);
        set_camera(&fd->camera, view, proj);
        test_ref_params(fd, NR, NR, 6, &p);
        CHECK_OK_CTX(ctx, test_ref_render(ref, &p, base[f], NULL, NULL));
    }
    for (i = 0; i < n; i++) {
        int d;
        set_camera(&fd->camera, c[i].view, c[i].proj);
        test_ref_params(fd, NR, NR, 6, &p);
        CHECK_OK_CTX(ctx, test_ref_render(ref, &p, img, NULL, NULL));
        snell_ref_rgb_to_rgba8(img, NR, NR, a);
        snell_ref_rgb_to_rgba8(base[c[i].base], NR, NR, b);
        d = differ(a, b, NR, NR, c[i].flip);
        printf("reference, %s: %d pixels differ\n", c[i].name, d);
        CHECK(d <= 2, "reference, %s: %d of %d pixels differ", c[i].name, d, NR * NR);
    }
    snell_ref_destroy(ref);
}

int main(void)
{
    static uint8_t base[3][N * N * 4], img[N * N * 4];
    snell_ctx *ctx = test_ctx();
    snell_renderer *r, *rs[2] = {NULL, NULL};
    snell_renderer_desc rd = {.width = N, .height = N, .shading = SNELL_SHADING_FORWARD};
    snell_env *env;
    snell_mesh *torus = NULL;
    snell_glass g;
    snell_frame_desc fd;
    cam c[9];
    int n, m, i, f, sh;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 32);
    r = test_renderer(ctx, N, N);
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &rs[0]));
    rd.shading = SNELL_SHADING_SCREEN;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &rs[1]));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_TORUS}, &torus));
    if (!env || !r || !rs[0] || !rs[1] || !torus) return test_finish();
    memset(c, 0, sizeof c);
    n = make_cases(c);
    test_frame_one(&fd, &g, torus, env);
    g.model = k_model;
    g.material.ior = 1.5f;
    for (sh = 0; sh < 2; sh++)
        for (m = 0; m < snell_method_count(); m++) {
            const char *name = snell_method_info_at(m)->name, *how = sh ? "screen" : "forward";
            g.material.method = snell_method_info_at(m)->method;
            for (f = 0; f < 3; f++) {
                mat4 view, proj;
                standard(view, proj, f);
                set_camera(&fd.camera, view, proj);
                CHECK_OK_CTX(ctx, snell_render(rs[sh], &fd, NULL));
                CHECK_OK_CTX(ctx, snell_renderer_read_rgba(rs[sh], base[f]));
            }
            for (i = 0; i < n; i++) {
                snell_status st;
                int d;
                set_camera(&fd.camera, c[i].view, c[i].proj);
                memset(img, 0, sizeof img);
                st = snell_render(rs[sh], &fd, NULL);
                CHECK(st == SNELL_OK, "%s %s, %s: %s", name, how, c[i].name, snell_last_error(ctx));
                CHECK_OK_CTX(ctx, snell_renderer_read_rgba(rs[sh], img));
                d = differ(img, base[c[i].base], N, N, c[i].flip);
                printf("%s %s, %s: %d pixels differ\n", name, how, c[i].name, d);
                CHECK(d <= EDGE, "%s %s, %s: %d of %d pixels differ from the standard camera's%s", name, how,
                      c[i].name, d, N * N, c[i].flip ? " flipped in x" : "");
            }
        }
    g.material.method = SNELL_METHOD_AUTO;
    reference(ctx, &fd, c, n);
    refusals(ctx, r, &fd, &c[3]);
    snell_mesh_destroy(torus);
    snell_renderer_destroy(r);
    snell_renderer_destroy(rs[0]);
    snell_renderer_destroy(rs[1]);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
