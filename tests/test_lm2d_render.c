/* SPDX-License-Identifier: MIT */
/* test_lm2d_render.c — the showcase lightmaps, written as PNGs for looking at
 * (lm2d_*.png in the test's build directory) and checked numerically:
 * a bar light casts a soft shadow (wide penumbra, dark umbra), a red diffuse
 * wall bleeds red into unlit space, a glass prism bends a beam by the minimum
 * deviation 2 asin(1.5 sin 30 deg) - 60 deg = 37.18 deg. GPU if available. */
#include "test_util.h"
#include "snell/snell_2d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include "stb_image_write.h"
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#define W 256
#define H 256

static float img[W * H * 3];

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Display: scale so the 99th percentile of the lit pixels is white, gamma 2.2
 * (the lightmap spans orders of magnitude around a light). */
static void tone(const float *rgb, uint8_t *rgba)
{
    static float l[W * H];
    int i, n = 0;
    float p;
    for (i = 0; i < W * H; i++) {
        float v = rgb[3 * i] > rgb[3 * i + 1] ? rgb[3 * i] : rgb[3 * i + 1];
        v = v > rgb[3 * i + 2] ? v : rgb[3 * i + 2];
        if (v > 0) l[n++] = v;
    }
    qsort(l, (size_t)n, sizeof(float), cmp_float);
    p = n ? l[(int)(0.99 * (n - 1))] : 1.0f;
    for (i = 0; i < W * H; i++) {
        int k;
        for (k = 0; k < 3; k++) {
            float v = powf(rgb[3 * i + k] / p, 1.0f / 2.2f);
            rgba[4 * i + k] = (uint8_t)(v >= 1.0f ? 255 : (int)(v * 255.0f + 0.5f));
        }
        rgba[4 * i + 3] = 255;
    }
}

static int render(snell_ctx *ctx, const char *scene, float exposure, int bounces, const char *png)
{
    snell_scene2d *s = NULL;
    snell_lightmap2d *lm = NULL;
    snell_lightmap2d_desc d;
    static uint8_t rgba[W * H * 4];
    CHECK_OK(snell_scene2d_load(ctx, test_data(scene), &s, NULL, NULL));
    if (!s) return 0;
    memset(&d, 0, sizeof d);
    d.width = W;
    d.height = H;
    d.exposure = exposure;
    d.max_bounces = bounces;
    d.seed = 3;
    CHECK_OK(snell_lightmap2d_create(ctx, &d, &lm));
    if (!lm) return 0;
    CHECK_OK(snell_lightmap2d_frame(lm, s, NULL));
    CHECK_OK(snell_lightmap2d_read_rgb(lm, img));
    (void)exposure;
    tone(img, rgba);
    CHECK(stbi_write_png(test_out(png), W, H, 4, rgba, W * 4) != 0, "cannot write %s", png);
    snell_lightmap2d_destroy(lm);
    snell_scene2d_destroy(s);
    return 1;
}

static float lum(int x, int y) { return img[3 * (y * W + x)] + img[3 * (y * W + x) + 1] + img[3 * (y * W + x) + 2]; }

/* mean over a box of rows y0..y1 at column x */
static float col_mean(int x, int y0, int y1)
{
    float s = 0;
    int y;
    for (y = y0; y <= y1; y++) s += lum(x, y);
    return s / (float)(y1 - y0 + 1);
}

static void shadow(snell_ctx *ctx)
{
    float lit, umbra, prof[W];
    int x, ramp = 0;
    if (!render(ctx, "lm2d/shadow.txt", 0.02f, 4, "lm2d_shadow.png")) return;
    /* air just above the floor, rows 225..235, smoothed over 5 columns */
    for (x = 2; x < W - 2; x++) {
        int k;
        prof[x] = 0;
        for (k = -2; k <= 2; k++) prof[x] += col_mean(x + k, 225, 235) / 5.0f;
    }
    lit = prof[20];
    umbra = prof[128];
    printf("shadow: lit %.4g umbra %.4g\n", (double)lit, (double)umbra);
    /* the umbra still receives light bounced off the diffuse floor (a = 0.5): ~27 % measured */
    CHECK(umbra < 0.4f * lit, "umbra (%g) not dark against lit floor (%g)", (double)umbra, (double)lit);
    /* penumbra: columns between 20% and 80% of the lit level, right of the umbra */
    for (x = 128; x < W - 2; x++)
        if (prof[x] > umbra + 0.2f * (lit - umbra) && prof[x] < umbra + 0.8f * (lit - umbra)) ramp++;
    printf("shadow: penumbra %d px wide\n", ramp);
    /* geometry (bar 100 wide at y=30, box 40 wide at y 120..160, floor at 240): penumbra ~ 60 px */
    CHECK(ramp > 25, "shadow edge too hard: %d px of penumbra", ramp);
}

static void bleed(snell_ctx *ctx)
{
    double r = 0, g = 0;
    int x, y;
    if (!render(ctx, "lm2d/bleed.txt", 0.03f, 4, "lm2d_bleed.png")) return;
    /* in front of the red wall but above the spot cone: only reflected light */
    for (y = 22; y < 50; y++)
        for (x = 150; x < 196; x++) {
            r += img[3 * (y * W + x)];
            g += img[3 * (y * W + x) + 1];
        }
    printf("bleed: red/green above the cone %.3f\n", r / g);
    CHECK(r > 0 && r / g > 2.0, "no red colour bleeding: r/g = %g", r / g);
}

/* intensity-weighted centroid row of column x */
static float centroid(int x)
{
    double s = 0, sy = 0;
    int y;
    for (y = 0; y < H; y++) {
        s += lum(x, y);
        sy += lum(x, y) * (y + 0.5);
    }
    return s > 0 ? (float)(sy / s) : -1.0f;
}

static void prism(snell_ctx *ctx)
{
    float y0, y1, ang;
    if (!render(ctx, "lm2d/prism.txt", 0.2f, 6, "lm2d_prism.png")) return;
    y0 = centroid(185);
    y1 = centroid(225);
    ang = atanf((y1 - y0) / 40.0f) * 57.29578f;
    printf("prism: exit beam %.2f deg below horizontal (entered 18.59 above; min deviation 37.18)\n", (double)ang);
    CHECK(fabsf(ang - 18.59f) < 2.0f, "prism exit angle %g, want 18.59", (double)ang);
}

int main(void)
{
    snell_ctx *ctx = test_ctx(); /* NULL: CPU path (exact rasteriser) */
    shadow(ctx);
    bleed(ctx);
    prism(ctx);
    if (ctx) snell_ctx_destroy(ctx);
    return test_finish();
}
