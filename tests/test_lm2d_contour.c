/* SPDX-License-Identifier: MIT */
/* test_lm2d_contour.c — image -> polygon (Brückner A.5 without OpenCV): a disc's
 * outline has the disc's area and radius, RDP keeps few points within epsilon,
 * the outer loop wins over a hole, empty images are rejected, and the CSV
 * loads back as a scene object. */
#include "test_util.h"
#include "snell/snell_2d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define N 128

static uint8_t im[N * N * 4];

static void disc(float cx, float cy, float r, float hole)
{
    int x, y;
    memset(im, 0, sizeof im);
    for (y = 0; y < N; y++)
        for (x = 0; x < N; x++) {
            float dx = x + 0.5f - cx, dy = y + 0.5f - cy, d = sqrtf(dx * dx + dy * dy);
            /* anti-aliased edge: alpha = coverage */
            float a = r + 0.5f - d, h = d - hole + 0.5f;
            a = a < 0 ? 0 : a > 1 ? 1 : a;
            if (hole > 0) a *= h < 0 ? 0 : h > 1 ? 1 : h;
            im[4 * (y * N + x) + 3] = (uint8_t)(a * 255.0f + 0.5f);
        }
}

int main(void)
{
    float *pts = NULL;
    int n = 0, i, far = 0;
    double area = 0;
    disc(64.0f, 60.0f, 40.0f, 0.0f);
    CHECK_OK(snell_contour2d_from_alpha(NULL, im, N, N, 128, 0.25f, &pts, &n));
    if (!pts) return test_finish();
    for (i = 0; i < n; i++) {
        int j = (i + 1) % n;
        float dx = pts[2 * i] - 64.0f, dy = pts[2 * i + 1] - 60.0f;
        area += (double)pts[2 * i] * pts[2 * j + 1] - (double)pts[2 * j] * pts[2 * i + 1];
        if (fabsf(sqrtf(dx * dx + dy * dy) - 40.0f) > 0.35f) far++;
    }
    area = fabs(area) * 0.5;
    printf("disc r=40: %d points, area %.1f (pi r^2 = %.1f)\n", n, area, 3.14159265 * 1600);
    CHECK(fabs(area / (3.14159265 * 1600) - 1) < 0.01, "area %.1f", area);
    CHECK(far == 0, "%d contour points off the circle by > 0.35 px", far);
    CHECK(n >= 20 && n < 120, "RDP left %d points", n);
    CHECK_OK(snell_contour2d_write_csv(test_out("lm2d_disc.csv"), pts, n));
    snell_contour2d_free(NULL, pts);
    /* coarser epsilon, fewer points (thesis A.19: epsilon relative to the outline) */
    {
        int n2;
        CHECK_OK(snell_contour2d_from_alpha(NULL, im, N, N, 128, 3.0f, &pts, &n2));
        CHECK(n2 < n && n2 >= 6, "epsilon 3 gives %d points (epsilon 0.25: %d)", n2, n);
        snell_contour2d_free(NULL, pts);
    }
    /* CSV round trip into a scene */
    {
        snell_scene2d *s;
        snell_material2d m;
        memset(&m, 0, sizeof m);
        CHECK_OK(snell_scene2d_create(NULL, &s));
        CHECK_OK(snell_scene2d_add_object_csv(s, test_out("lm2d_disc.csv"), &m, NULL, NULL));
        CHECK(snell_scene2d_edge_count(s) == n, "CSV round trip: %d edges, want %d", snell_scene2d_edge_count(s), n);
        snell_scene2d_destroy(s);
    }
    /* ring: the outer outline is chosen, not the hole */
    disc(64.0f, 64.0f, 50.0f, 20.0f);
    CHECK_OK(snell_contour2d_from_alpha(NULL, im, N, N, 128, 0.5f, &pts, &n));
    if (pts) {
        float maxr = 0;
        for (i = 0; i < n; i++) {
            float dx = pts[2 * i] - 64.0f, dy = pts[2 * i + 1] - 64.0f, r = sqrtf(dx * dx + dy * dy);
            if (r > maxr) maxr = r;
        }
        CHECK(maxr > 49.0f, "ring: picked the inner loop (max radius %g)", (double)maxr);
        snell_contour2d_free(NULL, pts);
    }
    /* full-image region touching the border still closes (transparent padding) */
    memset(im, 255, sizeof im);
    CHECK_OK(snell_contour2d_from_alpha(NULL, im, N, N, 128, 0.5f, &pts, &n));
    CHECK(n == 4, "full image outline has %d points, want 4", n);
    snell_contour2d_free(NULL, pts);
    /* empty image, bad args */
    memset(im, 0, sizeof im);
    CHECK(snell_contour2d_from_alpha(NULL, im, N, N, 128, 0.5f, &pts, &n) == SNELL_E_INVALID_ARG, "empty image accepted");
    CHECK(snell_contour2d_from_alpha(NULL, NULL, N, N, 128, 0.5f, &pts, &n) == SNELL_E_INVALID_ARG, "NULL image accepted");
    CHECK(snell_contour2d_from_alpha(NULL, im, N, N, 128, -1.0f, &pts, &n) == SNELL_E_INVALID_ARG, "negative epsilon");
    {
        float one[2] = {1, 2};
        CHECK(snell_contour2d_write_csv("/nonexistent_dir/x.csv", one, 1) == SNELL_E_IO, "write to a missing directory");
    }
    return test_finish();
}
