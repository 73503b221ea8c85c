/* SPDX-License-Identifier: MIT */
/* test_bench_classes — snell-bench's errors per object class (ports/cli/
 * bench_classes.c, issue 13 item 5) on images whose differences are placed
 * by hand, so every expected figure follows from the construction:
 *
 * An id map in the reference's convention (glass i -> i, opaque j -> -2 - j,
 * nothing -> -1): three glass blocks (ids 0, 1, 2), two opaque blocks (ids
 * -2, -3), background around them; the class sizes are counted off the
 * layout below.
 * 1. The test image is the reference: every class has RMSE 0, PSNR +inf,
 *    SSIM 1, and the class pixel counts of the layout (partitioning the image).
 * 2. Only background pixels at least 6 pixels from any object differ (by 10
 *    in every channel): the background class and "all" show it, with the
 *    RMSE that follows from the count of changed pixels; glass and opaque
 *    stay exact, SSIM included (the 11x11 window reaches 5 pixels).
 * 3. Only opaque pixels differ (id -3's block, by 20 in red): the opaque
 *    class's RMSE is 20 * sqrt(changed / (3 * opaque pixels)); glass and
 *    background stay exact in PSNR.
 * 4. Only glass object 1's pixels differ: the glass class alone, in PSNR.
 * 5. The glass-through-glass class is the through mask within glass: given
 *    glass object 2's block plus some background pixels, it counts the
 *    block only; with 4.'s change (object 1) it stays exact, with the block
 *    changed it shows the error; without a mask it is empty.
 * A mask or class mapping that put a pixel in the wrong class fails 2-5. */
#include "bench.h"
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 64
#define H 48

typedef struct block {
    int x0, y0, x1, y1; /* [x0, x1) x [y0, y1) */
    int16_t id;
} block;

/* glass 0, 1, 2 (1 overlaps 0's right edge: drawn later, it wins), opaque -2, -3 */
static const block g_blocks[] = {
    {8, 8, 20, 20, 0}, {16, 10, 28, 22, 1}, {34, 6, 44, 16, 2}, {8, 28, 18, 38, -2}, {30, 26, 46, 40, -3},
};
#define BLOCKS ((int)(sizeof g_blocks / sizeof *g_blocks))

static int16_t g_ids[W * H];
static uint8_t g_ref[W * H * 4], g_test[W * H * 4], g_mask[W * H], g_through[W * H];
static const uint8_t *g_through_in; /* the through mask given to bench_class_errors */

static void layout(long count[BENCH_CLASS_COUNT])
{
    int b, x, y, c;
    for (c = 0; c < BENCH_CLASS_COUNT; c++) count[c] = 0;
    for (x = 0; x < W * H; x++) g_ids[x] = -1;
    for (b = 0; b < BLOCKS; b++)
        for (y = g_blocks[b].y0; y < g_blocks[b].y1; y++)
            for (x = g_blocks[b].x0; x < g_blocks[b].x1; x++) g_ids[y * W + x] = g_blocks[b].id;
    for (x = 0; x < W * H; x++) {
        /* a textured reference, so that SSIM has structure to compare */
        g_ref[4 * x + 0] = (uint8_t)(40 + (x * 7) % 150);
        g_ref[4 * x + 1] = (uint8_t)(60 + (x * 13) % 120);
        g_ref[4 * x + 2] = (uint8_t)(80 + (g_ids[x] + 3) * 20);
        g_ref[4 * x + 3] = 255;
        count[g_ids[x] >= 0 ? BENCH_CLASS_GLASS : g_ids[x] == -1 ? BENCH_CLASS_BACKGROUND : BENCH_CLASS_OPAQUE]++;
    }
    count[BENCH_CLASS_ALL] = W * H;
    count[BENCH_CLASS_GLASS_THROUGH] = 0; /* no through mask */
}

/* Distance (Chebyshev) from pixel (x, y) to the nearest non-background pixel, capped at 99. */
static int object_distance(int x, int y)
{
    int best = 99, u, v;
    for (v = 0; v < H; v++)
        for (u = 0; u < W; u++)
            if (g_ids[v * W + u] != -1) {
                int d = abs(u - x) > abs(v - y) ? abs(u - x) : abs(v - y);
                if (d < best) best = d;
            }
    return best;
}

static void errors(bench_class_error e[BENCH_CLASS_COUNT])
{
    memset(e, 0, sizeof(bench_class_error) * BENCH_CLASS_COUNT);
    CHECK_OK(bench_class_errors(g_test, g_ref, g_ids, g_through_in, W, H, g_mask, e));
}

static void check_exact(const bench_class_error *e, const char *what, int with_ssim)
{
    CHECK(e->img.rmse == 0.0 && isinf(e->img.psnr_db) && e->img.psnr_db > 0, "%s: rmse %g psnr %g", what, e->img.rmse,
          e->img.psnr_db);
    if (with_ssim) CHECK(e->ssim == 1.0, "%s: ssim %.9f", what, e->ssim);
}

int main(void)
{
    long count[BENCH_CLASS_COUNT], changed = 0;
    bench_class_error e[BENCH_CLASS_COUNT];
    int c, x, y;

    layout(count);
    CHECK(count[BENCH_CLASS_GLASS] == 12 * 12 + 12 * 12 - 4 * 10 + 10 * 10 &&
              count[BENCH_CLASS_OPAQUE] == 100 + 16 * 14,
          "layout: glass %ld opaque %ld", count[BENCH_CLASS_GLASS], count[BENCH_CLASS_OPAQUE]);
    CHECK(bench_class_of(0) == BENCH_CLASS_GLASS && bench_class_of(7) == BENCH_CLASS_GLASS &&
              bench_class_of(-1) == BENCH_CLASS_BACKGROUND && bench_class_of(-2) == BENCH_CLASS_OPAQUE &&
              bench_class_of(-9) == BENCH_CLASS_OPAQUE,
          "class of ids");

    /* 1. the reference itself */
    memcpy(g_test, g_ref, sizeof g_test);
    errors(e);
    for (c = 0; c < BENCH_CLASS_COUNT; c++) {
        CHECK(e[c].img.pixels == count[c], "%s: %ld pixels, layout %ld", bench_class_names[c], e[c].img.pixels,
              count[c]);
        check_exact(&e[c], bench_class_names[c], 1);
    }
    CHECK(e[BENCH_CLASS_GLASS].img.pixels + e[BENCH_CLASS_OPAQUE].img.pixels + e[BENCH_CLASS_BACKGROUND].img.pixels ==
              e[BENCH_CLASS_ALL].img.pixels,
          "classes do not partition");

    /* 2. background only, far from every object */
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++)
            if (g_ids[y * W + x] == -1 && object_distance(x, y) >= 6) {
                int k;
                for (k = 0; k < 3; k++) g_test[4 * (y * W + x) + k] = (uint8_t)(g_ref[4 * (y * W + x) + k] + 10);
                changed++;
            }
    errors(e);
    CHECK(changed > 500, "%ld background pixels changed", changed);
    check_exact(&e[BENCH_CLASS_GLASS], "glass, background changed", 1);
    check_exact(&e[BENCH_CLASS_OPAQUE], "opaque, background changed", 1);
    CHECK(fabs(e[BENCH_CLASS_BACKGROUND].img.rmse - 10.0 * sqrt((double)changed / count[BENCH_CLASS_BACKGROUND])) <
              1e-9,
          "background rmse %g", e[BENCH_CLASS_BACKGROUND].img.rmse);
    CHECK(fabs(e[BENCH_CLASS_ALL].img.rmse - 10.0 * sqrt((double)changed / (W * H))) < 1e-9, "all rmse %g",
          e[BENCH_CLASS_ALL].img.rmse);
    CHECK(e[BENCH_CLASS_BACKGROUND].ssim < 1.0 && e[BENCH_CLASS_BACKGROUND].img.max_abs == 10,
          "background ssim %g max %d", e[BENCH_CLASS_BACKGROUND].ssim, e[BENCH_CLASS_BACKGROUND].img.max_abs);

    /* 3. opaque object -3 only, red + 20 */
    memcpy(g_test, g_ref, sizeof g_test);
    changed = 0;
    for (x = 0; x < W * H; x++)
        if (g_ids[x] == -3) g_test[4 * x] = (uint8_t)(g_ref[4 * x] + 20), changed++;
    errors(e);
    check_exact(&e[BENCH_CLASS_GLASS], "glass, opaque changed", 0);
    check_exact(&e[BENCH_CLASS_BACKGROUND], "background, opaque changed", 0);
    CHECK(fabs(e[BENCH_CLASS_OPAQUE].img.rmse - 20.0 * sqrt((double)changed / (3.0 * count[BENCH_CLASS_OPAQUE]))) <
              1e-9,
          "opaque rmse %g", e[BENCH_CLASS_OPAQUE].img.rmse);

    /* 4. glass object 1 only */
    memcpy(g_test, g_ref, sizeof g_test);
    for (x = 0; x < W * H; x++)
        if (g_ids[x] == 1) g_test[4 * x + 1] = (uint8_t)(g_ref[4 * x + 1] + 5);
    errors(e);
    check_exact(&e[BENCH_CLASS_OPAQUE], "opaque, glass changed", 0);
    check_exact(&e[BENCH_CLASS_BACKGROUND], "background, glass changed", 0);
    CHECK(e[BENCH_CLASS_GLASS].img.rmse > 0 && e[BENCH_CLASS_GLASS].img.max_abs == 5, "glass rmse %g",
          e[BENCH_CLASS_GLASS].img.rmse);

    /* 5. through mask: glass object 2's block and a background strip */
    for (x = 0; x < W * H; x++) g_through[x] = (uint8_t)(g_ids[x] == 2 || (g_ids[x] == -1 && x < 2 * W));
    g_through_in = g_through;
    errors(e);
    CHECK(e[BENCH_CLASS_GLASS_THROUGH].img.pixels == 100, "through: %ld pixels, want object 2's 100",
          e[BENCH_CLASS_GLASS_THROUGH].img.pixels);
    check_exact(&e[BENCH_CLASS_GLASS_THROUGH], "through, object 1 changed", 0);
    for (x = 0; x < W * H; x++)
        if (g_ids[x] == 2) g_test[4 * x + 2] = (uint8_t)(g_ref[4 * x + 2] + 30);
    errors(e);
    CHECK(fabs(e[BENCH_CLASS_GLASS_THROUGH].img.rmse - 30.0 / sqrt(3.0)) < 1e-9, "through rmse %g",
          e[BENCH_CLASS_GLASS_THROUGH].img.rmse);
    return test_finish();
}
