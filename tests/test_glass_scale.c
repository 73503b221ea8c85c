/* SPDX-License-Identifier: MIT */
/* test_glass_scale — a glass object shaded at a resolution scale
 * (snell_glass_material.scale, render/glass_scale.c, glass_scale.frag).
 * The torus with SNELL_METHOD_PEEL (4 layers), 96x96 with 2x2 supersampling
 * (a 192x192 frame), seen from 25 degrees above.
 *
 * 1. Values: 0 resolves to 1; negative, below 1, above SNELL_MAX_GLASS_SCALE,
 *    NaN and infinity are SNELL_E_INVALID_ARG naming "scale", from
 *    snell_glass_defaults and from snell_render.
 * 2. Scale 1 is the unscaled frame byte for byte (0 and 1 take one path:
 *    drawn as before the scale existed), and the stats say 1.
 * 3. Scale 2: the stats say 2; the image is close to scale 1: the kernel sees
 *    a quarter of the samples, so the glass differs where its refraction
 *    changes within two frame samples; PSNR over the glass pixels at least
 *    MIN_PSNR_2 (measured 28.9 dB; 24 dB allows 3x the error's power).
 * 4. No background bleeds into the silhouette: on the glass pixels with a
 *    background neighbour (the outline; the small target holds black where
 *    the object did not cover it) the mean signed difference from scale 1
 *    lies within MAX_EDGE_BIAS and the mean absolute one below MAX_EDGE_ERR
 *    (measured -0.9 and 11.6 of 255; interpolating over every texel, uncovered
 *    ones too, gives -28.3 and 30.8 and fails both: the outline pulled
 *    towards black).
 * 5. A method that reads the frame's full-resolution back faces (WYMAN) is
 *    drawn at 1 whatever its material asks, and its image is the unscaled one.
 * 6. After the first frame with objects at scales 2 and 4 beside one at 1,
 *    frames create no GL object (gl_count.h): the same objects alive, and
 *    no name handed out (a target made and deleted every frame fails this).
 * 7. A feature the small grid misses altogether: a needle (a sphere squashed
 *    to radius NEEDLE_R across, about 1.5 pixels wide, along the image's
 *    middle row) at scale 8, without supersampling, so the 12x12 grid's texel
 *    centres (4 pixels off the middle row) miss it. No needle pixel is black
 *    (what the upsample gave without a covered texel within two), and at
 *    least NEEDLE_SINGLE of them are the single-surface frame's pixel within
 *    3 of 255 (the fallback is single.frag's model at the pixel's own
 *    surface point; the rest take the nearest covered texel, near the tips):
 *    clear and absorbing needles drawn by peel, a thin-walled one (a slab,
 *    straight through) by single. */
#include "test_util.h"
#include "gl_count.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 96
#define MIN_PSNR_2 24.0
#define MAX_EDGE_BIAS 8.0
#define MAX_EDGE_ERR 20.0
#define NEEDLE_R 0.03f
#define NEEDLE_SINGLE 0.8

static uint8_t g_img[4][W * H * 4];

static snell_status render(snell_renderer *r, snell_frame_desc *fd, uint8_t *img, snell_frame_stats *st)
{
    snell_status s = snell_render(r, fd, st);
    return s == SNELL_OK ? snell_renderer_read_rgba(r, img) : s;
}

static void values(void)
{
    static const float bad[] = {-1.0f, 0.5f, 8.5f, 1000.0f, NAN, INFINITY};
    snell_glass_material m;
    snell_glass_resolved g;
    size_t i;
    memset(&m, 0, sizeof m);
    CHECK_OK(snell_glass_defaults(&m, &g));
    CHECK(g.material.scale == 1.0f, "scale 0 resolves to %g, want 1", g.material.scale);
    m.scale = (float)SNELL_MAX_GLASS_SCALE;
    CHECK_OK(snell_glass_defaults(&m, &g));
    for (i = 0; i < sizeof bad / sizeof *bad; i++) {
        m.scale = bad[i];
        CHECK(snell_glass_defaults(&m, &g) == SNELL_E_INVALID_ARG, "scale %g accepted", bad[i]);
        CHECK(strstr(snell_last_error(NULL), "scale") != NULL, "scale %g: message '%s' does not name it", bad[i],
              snell_last_error(NULL));
    }
}

/* Glass pixels: where the frame differs from the background alone. */
static void glass_mask(const uint8_t *img, const uint8_t *bg, uint8_t *mask, int *count)
{
    int i;
    *count = 0;
    for (i = 0; i < W * H; i++) {
        mask[i] = memcmp(img + 4 * i, bg + 4 * i, 3) != 0;
        *count += mask[i];
    }
}

static double psnr_masked(const uint8_t *a, const uint8_t *b, const uint8_t *mask)
{
    double se = 0.0;
    int i, k, n = 0;
    for (i = 0; i < W * H; i++) {
        if (!mask[i]) continue;
        for (k = 0; k < 3; k++) se += (double)(a[4 * i + k] - b[4 * i + k]) * (a[4 * i + k] - b[4 * i + k]);
        n += 3;
    }
    return se > 0.0 ? 10.0 * log10(255.0 * 255.0 / (se / n)) : 99.0;
}

/* Outline pixels (glass with a background 4-neighbour): mean signed and absolute differences b - a. */
static void edge_error(const uint8_t *a, const uint8_t *b, const uint8_t *mask, double *bias, double *err, int *n)
{
    int x, y, k;
    double s = 0.0, e = 0.0;
    *n = 0;
    for (y = 1; y < H - 1; y++)
        for (x = 1; x < W - 1; x++) {
            int i = y * W + x;
            if (!mask[i] || (mask[i - 1] && mask[i + 1] && mask[i - W] && mask[i + W])) continue;
            for (k = 0; k < 3; k++) {
                double d = (double)b[4 * i + k] - a[4 * i + k];
                s += d;
                e += fabs(d);
            }
            ++*n;
        }
    *bias = *n ? s / (3.0 * *n) : 0.0;
    *err = *n ? e / (3.0 * *n) : 0.0;
}

/* Test 7: r draws without supersampling; g[0] is the object whose model is
 * set here, drawn by method at scale 8 (what the fallback stands in for:
 * peel for a solid, single for a thin wall, which it draws as a slab). */
static void needle(snell_renderer *r, snell_frame_desc *fd, snell_glass *g, snell_method method, const char *what)
{
    static const float model[16] = {0.9f, 0, 0, 0, 0, NEEDLE_R, 0, 0, 0, 0, NEEDLE_R, 0, 0, 0, 0, 1};
    static uint8_t mask[W * H];
    char name[64];
    snell_frame_stats st;
    int n, i, black = 0, same = 0;
    g->model = model;
    fd->glass_count = 0;
    CHECK_OK(render(r, fd, g_img[3], NULL));
    fd->glass_count = 1;
    g->material.method = SNELL_METHOD_SINGLE;
    g->material.scale = 1.0f;
    CHECK_OK(render(r, fd, g_img[1], NULL));
    g->material.method = method;
    g->material.scale = 8.0f;
    CHECK_OK(render(r, fd, g_img[2], &st));
    CHECK(st.glass[0].scale == 8.0f, "needle (%s): stats say scale %g", what, st.glass[0].scale);
    glass_mask(g_img[1], g_img[3], mask, &n);
    for (i = 0; i < W * H; i++) {
        const uint8_t *a = &g_img[1][4 * i], *b = &g_img[2][4 * i];
        if (!mask[i]) continue;
        black += b[0] == 0 && b[1] == 0 && b[2] == 0;
        same += abs(a[0] - b[0]) <= 3 && abs(a[1] - b[1]) <= 3 && abs(a[2] - b[2]) <= 3;
    }
    printf("needle (%s) at scale 8: %d glass pixels, %d black, %d the single-surface frame's\n", what, n, black, same);
    snprintf(name, sizeof name, "glass_scale_needle_%s.png", what);
    snell_write_png(test_out(name), W, H, g_img[2]);
    CHECK(n > W / 2, "the needle (%s) covers only %d pixels", what, n);
    CHECK(black == 0, "needle (%s) at scale 8: %d of %d pixels black (no covered texel near)", what, black, n);
    CHECK(same >= NEEDLE_SINGLE * n,
          "needle (%s) at scale 8: %d of %d pixels are the single-surface answer, want >= %g", what, same, n,
          NEEDLE_SINGLE);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_mesh *torus = NULL, *sphere = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_env_desc ed;
    snell_frame_desc fd;
    snell_frame_stats st;
    snell_glass g[3];
    static uint8_t mask[W * H];
    double psnr, bias, err;
    int n, edges, i;
    if (!ctx) SKIP("no GL context");
    values();
    memset(&ed, 0, sizeof ed);
    ed.face_size = 64;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.ssaa = 2;
    rd.shading = test_shading();
    CHECK_OK(snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_TORUS, 48, 24}, &torus));
    CHECK_OK(snell_env_create(ctx, &ed, &env));
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    test_frame_one(&fd, &g[0], torus, env);
    fd.camera.elevation = 25.0f * 3.14159265f / 180.0f;
    fd.camera.distance = 3.2f;

    /* the background alone: what the glass mask is told from */
    fd.glass_count = 0;
    CHECK_OK_CTX(ctx, render(r, &fd, g_img[3], NULL));
    fd.glass_count = 1;

    g[0].material.method = SNELL_METHOD_PEEL;
    g[0].material.peel.layers = 4;
    g[0].material.scale = NAN;
    CHECK(snell_render(r, &fd, &st) == SNELL_E_INVALID_ARG, "a frame with scale NaN was drawn");
    g[0].material.scale = 0.0f;
    CHECK_OK_CTX(ctx, render(r, &fd, g_img[0], &st));
    CHECK(st.glass[0].scale == 1.0f, "scale 0: stats say %g", st.glass[0].scale);
    g[0].material.scale = 1.0f;
    CHECK_OK_CTX(ctx, render(r, &fd, g_img[1], &st));
    CHECK(st.glass[0].scale == 1.0f, "scale 1: stats say %g", st.glass[0].scale);
    CHECK(!memcmp(g_img[0], g_img[1], sizeof g_img[0]), "scale 1 differs from the unscaled frame");

    g[0].material.scale = 2.0f;
    CHECK_OK_CTX(ctx, render(r, &fd, g_img[2], &st));
    CHECK(st.glass[0].scale == 2.0f, "scale 2: stats say %g", st.glass[0].scale);
    glass_mask(g_img[1], g_img[3], mask, &n);
    CHECK(n > W * H / 8, "the torus covers %d pixels", n);
    psnr = psnr_masked(g_img[1], g_img[2], mask);
    edge_error(g_img[1], g_img[2], mask, &bias, &err, &edges);
    printf("scale 2 against 1: %.2f dB over %d glass pixels; outline (%d pixels) mean %+.2f, |mean| %.2f of 255\n",
           psnr, n, edges, bias, err);
    CHECK(psnr >= MIN_PSNR_2, "scale 2: %.2f dB against scale 1, want >= %g", psnr, MIN_PSNR_2);
    CHECK(edges > 100, "only %d outline pixels", edges);
    CHECK(fabs(bias) <= MAX_EDGE_BIAS, "scale 2: the outline is %+.2f of 255 off scale 1 on average, want within %g",
          bias, MAX_EDGE_BIAS);
    CHECK(err <= MAX_EDGE_ERR, "scale 2: the outline differs by %.2f of 255 from scale 1, want <= %g", err,
          MAX_EDGE_ERR);
    snell_write_png(test_out("glass_scale_1.png"), W, H, g_img[1]);
    snell_write_png(test_out("glass_scale_2.png"), W, H, g_img[2]);

    if (snell_build_has("wyman")) {
        g[0].material.method = SNELL_METHOD_WYMAN;
        g[0].material.scale = 1.0f;
        CHECK_OK_CTX(ctx, render(r, &fd, g_img[0], &st));
        g[0].material.scale = 4.0f;
        CHECK_OK_CTX(ctx, render(r, &fd, g_img[1], &st));
        CHECK(st.glass[0].scale == 1.0f, "wyman at scale 4: stats say %g, want 1 (it reads full-resolution back "
              "faces)", st.glass[0].scale);
        CHECK(!memcmp(g_img[0], g_img[1], sizeof g_img[0]), "wyman at scale 4 differs from scale 1");
    }

    /* three objects at scales 1, 2, 4: no GL object made after the first frame */
    {
        static const float place[3][3] = {{-1.2f, 0.0f, 0.0f}, {1.2f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.5f}};
        float model[3][16];
        gl_counts before, after;
        GLuint names;
        for (i = 0; i < 3; i++) {
            memset(model[i], 0, sizeof model[i]);
            model[i][0] = model[i][5] = model[i][10] = 0.5f;
            model[i][15] = 1.0f;
            memcpy(&model[i][12], place[i], sizeof place[i]);
            g[i] = g[0];
            g[i].model = model[i];
            g[i].material.method = SNELL_METHOD_PEEL;
            g[i].material.scale = i == 0 ? 1.0f : i == 1 ? 2.0f : 4.0f;
        }
        fd.glass_count = 3;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
        before = gl_count_objects();
        names = gl_count_name_limit();
        for (i = 0; i < 3; i++) CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
        /* one more name each: gl_count_name_limit's own (Mesa never reuses a name) */
        CHECK(gl_count_name_limit() == names + 1, "frames after the first made and deleted GL objects (names %u -> %u)",
              names, gl_count_name_limit() - 1);
        after = gl_count_objects();
        CHECK(st.glass[1].scale == 2.0f && st.glass[2].scale == 4.0f, "stats say scales %g, %g", st.glass[1].scale,
              st.glass[2].scale);
        CHECK(!memcmp(&before, &after, sizeof before), "frames after the first made GL objects (textures %d -> %d, "
              "framebuffers %d -> %d, programs %d -> %d)", before.textures, after.textures, before.framebuffers,
              after.framebuffers, before.programs, after.programs);
    }
    snell_renderer_destroy(r);

    rd.ssaa = 1;
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    CHECK_OK(snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_SPHERE, 48, 24}, &sphere));
    test_frame_one(&fd, &g[0], sphere, env);
    fd.camera.elevation = 0.0f;
    fd.camera.distance = 3.2f;
    needle(r, &fd, &g[0], SNELL_METHOD_PEEL, "clear");
    /* absorbing (dark red after 0.02 units: the needle's own width) and a thin wall: the fallback
     * follows single's model for both (Beer-Lambert over the bounding sphere's chord; the slab) */
    g[0].material.attenuation_color[0] = 0.8f, g[0].material.attenuation_color[1] = 0.2f;
    g[0].material.attenuation_color[2] = 0.1f;
    g[0].material.attenuation_distance = 0.02f;
    needle(r, &fd, &g[0], SNELL_METHOD_PEEL, "absorbing");
    g[0].material.attenuation_distance = 0.0f;
    g[0].material.thickness = 0.01f;
    needle(r, &fd, &g[0], SNELL_METHOD_SINGLE, "thin");
    snell_renderer_destroy(r);
    snell_mesh_destroy(sphere);
    snell_env_destroy(env);
    snell_mesh_destroy(torus);
    snell_ctx_destroy(ctx);
    return test_finish();
}
