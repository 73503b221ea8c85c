/* SPDX-License-Identifier: MIT */
/* test_metrics — the error metrics of snell_metrics.h on inputs whose answer
 * is known by construction: angles of rotated vectors (down to 1e-7 rad,
 * where acos would fail), statistics and mask handling on a hand-built
 * image, RMSE/PSNR of images with a known difference, NaN/Inf counting, and
 * the angular error of the packed RGBA8 exit-direction encoding (pack.h),
 * which must stay below the 1e-4 rad that snell.h documents. */
#include "test_util.h"
#include "core/pack.h"
#include "snell/snell_metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* a = +X, b = a rotated by theta about +Z, scaled by s. */
static void rotated(double theta, float s, float a[3], float b[3])
{
    a[0] = 1.0f;
    a[1] = a[2] = 0.0f;
    b[0] = (float)(s * cos(theta));
    b[1] = (float)(s * sin(theta));
    b[2] = 0.0f;
}

static void test_angle(void)
{
    const double thetas[] = {0.0, 1e-7, 1e-5, 1e-3, 0.5 * DEG, 1.0, PI / 2, 3.0, PI};
    size_t i;
    float a[3], b[3], z[3] = {0, 0, 0}, nan3[3] = {NAN, 0, 0};
    for (i = 0; i < sizeof thetas / sizeof *thetas; i++) {
        double got;
        rotated(thetas[i], 3.5f, a, b);
        got = snell_metrics_angle(a, b);
        /* float rounding of cos/sin: ~6e-8 absolute on the angle */
        CHECK(fabs(got - thetas[i]) < 1.2e-7, "angle %g: got %.10g", thetas[i], got);
    }
    CHECK(isnan(snell_metrics_angle(a, z)), "zero vector gives NaN");
    CHECK(isnan(snell_metrics_angle(nan3, a)), "NaN input gives NaN");
}

/* 4x2 image: pixel i has a known error, mask and finiteness. */
static void test_metrics_dir_error(void)
{
    enum { W = 4, H = 2, N = W * H };
    float test[N * 3], ref[N * 3], err[N];
    uint8_t ref_mask[N] = {1, 1, 1, 1, 1, 0, 1, 0};
    uint8_t test_mask[N] = {1, 1, 1, 1, 0, 1, 1, 1};
    /* errors in degrees of the compared pixels 0..3 and 6; 7 is NaN */
    const double deg[N] = {0.5, 2.0, 10.0, 0.0, 3.0, 3.0, 1.5, 0.0};
    snell_dir_error_desc d;
    snell_dir_error e;
    int i;
    for (i = 0; i < N; i++) rotated(deg[i] * DEG, 1.0f + 0.25f * (float)i, ref + 3 * i, test + 3 * i);
    test[3 * 7 + 1] = NAN;
    memset(&d, 0, sizeof d);
    d.test = test;
    d.ref = ref;
    d.ref_mask = ref_mask;
    d.test_mask = test_mask;
    d.width = W;
    d.height = H;
    d.error_deg = err;
    CHECK_OK(snell_metrics_dir_error(&d, &e));
    /* compared: 0,1,2,3,6 (both masks, finite); mismatches: 4 (ref only), 5 (test only); 7 NaN */
    CHECK(e.pixels == N, "pixels %ld", e.pixels);
    CHECK(e.compared == 5, "compared %ld", e.compared);
    CHECK(e.mask_mismatch == 2, "mask_mismatch %ld", e.mask_mismatch);
    CHECK(e.nan_inf == 1, "nan_inf %ld", e.nan_inf);
    CHECK(e.glass_ref == 6 && e.glass_test == 7, "glass %ld %ld", e.glass_ref, e.glass_test);
    CHECK(fabs(e.mean_deg - 14.0 / 5.0) < 1e-5, "mean %g", e.mean_deg);
    CHECK(fabs(e.rms_deg - sqrt((0.25 + 4.0 + 100.0 + 2.25) / 5.0)) < 1e-5, "rms %g", e.rms_deg);
    CHECK(fabs(e.max_deg - 10.0) < 1e-5, "max %g", e.max_deg);
    CHECK(fabs(e.frac_above_1deg - 3.0 / 5.0) < 1e-12, "above 1: %g", e.frac_above_1deg);
    CHECK(fabs(e.frac_above_5deg - 1.0 / 5.0) < 1e-12, "above 5: %g", e.frac_above_5deg);
    /* median of {0, 0.5, 1.5, 2, 10} is 1.5; the histogram is 1% coarse */
    CHECK(fabs(e.median_deg - 1.5) < 0.015 * 1.5 + 1e-6, "median %g", e.median_deg);
    CHECK(fabs(e.p99_deg - 10.0) < 1e-5, "p99 %g (clamped to the max)", e.p99_deg);
    CHECK(fabs(err[2] - 10.0f) < 1e-4f && isnan(err[4]) && isnan(err[5]) && isnan(err[7]), "per-pixel errors");

    /* No masks: every pixel compared except the NaN one. */
    d.ref_mask = d.test_mask = NULL;
    CHECK_OK(snell_metrics_dir_error(&d, &e));
    CHECK(e.compared == 7 && e.mask_mismatch == 0 && e.nan_inf == 1, "unmasked: %ld %ld %ld", e.compared,
          e.mask_mismatch, e.nan_inf);
    /* A zero-length test direction is not compared and is counted. */
    test[0] = test[1] = test[2] = 0.0f;
    CHECK_OK(snell_metrics_dir_error(&d, &e));
    CHECK(e.compared == 6 && e.zero_length == 1, "zero length: %ld %ld", e.compared, e.zero_length);

    d.width = 0;
    CHECK(snell_metrics_dir_error(&d, &e) == SNELL_E_INVALID_ARG, "width 0 rejected");
    d.width = W;
    d.test = NULL;
    CHECK(snell_metrics_dir_error(&d, &e) == SNELL_E_INVALID_ARG, "NULL test rejected");
    CHECK(strstr(snell_last_error(NULL), "required") != NULL, "message: %s", snell_last_error(NULL));
}

static void test_coverage(void)
{
    float bg[9] = {0, 0, 1, 0, 1, 0, 1, 0, 0}, dirs[9];
    uint8_t m[3];
    memcpy(dirs, bg, sizeof dirs);
    dirs[4] = nextafterf(1.0f, 0.0f); /* one ulp off: the glass wrote this pixel */
    CHECK_OK(snell_metrics_coverage_mask(dirs, bg, 3, m));
    CHECK(m[0] == 0 && m[1] == 1 && m[2] == 0, "mask %d %d %d", m[0], m[1], m[2]);
    CHECK(snell_metrics_coverage_mask(NULL, bg, 3, m) == SNELL_E_INVALID_ARG, "NULL rejected");
}

static void test_image_error(void)
{
    enum { W = 8, H = 4, N = W * H };
    uint8_t a[N * 4], b[N * 4], mask[N];
    snell_image_error e;
    int i;
    for (i = 0; i < N * 4; i++) a[i] = b[i] = (uint8_t)(i * 7);
    CHECK_OK(snell_metrics_image_error(a, b, W, H, NULL, &e));
    CHECK(e.rmse == 0.0 && isinf(e.psnr_db) && e.max_abs == 0, "identical: rmse %g psnr %g", e.rmse, e.psnr_db);
    /* Every other pixel: red off by +10, green by -5; alpha changes are ignored. */
    for (i = 0; i < N; i += 2) {
        b[4 * i + 0] = (uint8_t)(a[4 * i + 0] > 200 ? a[4 * i + 0] - 10 : a[4 * i + 0] + 10);
        b[4 * i + 1] = (uint8_t)(a[4 * i + 1] >= 5 ? a[4 * i + 1] - 5 : a[4 * i + 1] + 5);
        b[4 * i + 3] = (uint8_t)(a[4 * i + 3] ^ 0xff);
    }
    CHECK_OK(snell_metrics_image_error(a, b, W, H, NULL, &e));
    /* mean squared channel difference = (N/2) * (100 + 25) / (3N) */
    {
        double rmse = sqrt(125.0 / 6.0), psnr = 20.0 * log10(255.0 / rmse);
        CHECK(fabs(e.rmse - rmse) < 1e-9, "rmse %g want %g", e.rmse, rmse);
        CHECK(fabs(e.psnr_db - psnr) < 1e-9, "psnr %g want %g", e.psnr_db, psnr);
        CHECK(fabs(e.mean_abs - 15.0 / 6.0) < 1e-9, "mean abs %g", e.mean_abs);
        CHECK(e.max_abs == 10 && e.above_3 == N / 2, "max %d above3 %ld", e.max_abs, e.above_3);
    }
    /* Masking out the changed pixels leaves identical images. */
    for (i = 0; i < N; i++) mask[i] = (uint8_t)(i & 1);
    CHECK_OK(snell_metrics_image_error(a, b, W, H, mask, &e));
    CHECK(e.pixels == N / 2 && e.rmse == 0.0, "masked: %ld pixels rmse %g", e.pixels, e.rmse);
    CHECK(snell_metrics_image_error(a, NULL, W, H, NULL, &e) == SNELL_E_INVALID_ARG, "NULL rejected");
    CHECK(snell_metrics_image_error(a, b, W, -1, NULL, &e) == SNELL_E_INVALID_ARG, "bad size rejected");
}

static void test_nonfinite(void)
{
    float v[6] = {0.0f, 1.0f, NAN, INFINITY, -INFINITY, -0.0f};
    CHECK(snell_metrics_count_nonfinite(v, 6) == 3, "non-finite count");
    CHECK(snell_metrics_count_nonfinite(v, 2) == 0, "finite prefix");
}

/* The packed RGBA8 exit-direction encoding: worst angular error over a dense
 * set of directions (Fibonacci sphere plus the octahedron's folds and the
 * poles), measured with the metric itself. */
static void test_packed_encoding_error(void)
{
    const int n = 200000;
    double worst = 0.0, sum = 0.0;
    int i;
    for (i = 0; i < n + 6; i++) {
        float d[3], back[3];
        uint8_t px[4];
        double a;
        if (i < n) {
            double z = 1.0 - (2.0 * i + 1.0) / n, r = sqrt(1.0 - z * z), phi = i * 2.399963229728653;
            d[0] = (float)(r * cos(phi));
            d[1] = (float)(r * sin(phi));
            d[2] = (float)z;
        } else {
            d[0] = d[1] = d[2] = 0.0f;
            d[(i - n) / 2] = (i - n) % 2 ? -1.0f : 1.0f;
        }
        snell_pack_dir_rgba8(d, px);
        snell_unpack_dir_rgba8(px, back);
        a = snell_metrics_angle(d, back);
        sum += a;
        if (a > worst) worst = a;
    }
    printf("packed RGBA8 exit direction: max error %.3g rad (%.3g deg), mean %.3g rad\n", worst, worst / DEG,
           sum / (n + 6));
    CHECK(worst < 1e-4, "packed encoding error %g rad >= 1e-4", worst);
    /* 16 bits over [-1,1]: a step of 3e-5; the error cannot be far below half of it */
    CHECK(worst > 5e-6, "packed encoding error %g rad implausibly small", worst);
}

/* SSIM: 1 for identical images; for two constant images a and b the
 * variances vanish and SSIM = (2ab + C1) / (a^2 + b^2 + C1) exactly; a
 * pattern against its inverted copy scores below 0 (negative covariance)
 * while the same pattern shifted by a constant keeps the structure term 1
 * (SSIM > 0.9 for a small offset), which PSNR cannot tell apart; masks. */
static void test_ssim(void)
{
    enum { W = 24, H = 20 };
    static uint8_t a[W * H * 4], b[W * H * 4], m[W * H];
    double s, c1 = (0.01 * 255) * (0.01 * 255), want;
    int i;
    for (i = 0; i < W * H; i++) {
        int x = i % W, y = i / W, v = ((x / 3 + y / 3) & 1) ? 200 : 60;
        a[4 * i] = a[4 * i + 1] = a[4 * i + 2] = (uint8_t)v;
        b[4 * i] = b[4 * i + 1] = b[4 * i + 2] = (uint8_t)(260 - v);
        a[4 * i + 3] = b[4 * i + 3] = 255;
        m[i] = x > 5 && y > 4;
    }
    CHECK_OK(snell_metrics_ssim(a, a, W, H, NULL, &s));
    CHECK(fabs(s - 1.0) < 1e-12, "SSIM of an image with itself %.15f", s);
    CHECK_OK(snell_metrics_ssim(a, b, W, H, m, &s));
    CHECK(s < 0.0, "SSIM of a pattern and its inverse %.4f should be negative", s);
    for (i = 0; i < W * H * 4; i++) b[i] = (uint8_t)(i % 4 == 3 ? 255 : a[i] + 10);
    CHECK_OK(snell_metrics_ssim(a, b, W, H, NULL, &s));
    CHECK(s > 0.9 && s < 1.0, "SSIM of a pattern and its copy +10 %.4f", s);
    for (i = 0; i < W * H * 4; i++) {
        a[i] = (uint8_t)(i % 4 == 3 ? 255 : 100);
        b[i] = (uint8_t)(i % 4 == 3 ? 255 : 140);
    }
    want = (2.0 * 100 * 140 + c1) / (100.0 * 100 + 140.0 * 140 + c1);
    CHECK_OK(snell_metrics_ssim(a, b, W, H, m, &s));
    CHECK(fabs(s - want) < 1e-12, "SSIM of constants 100, 140: %.15f, want %.15f", s, want);
    memset(m, 0, sizeof m);
    CHECK_OK(snell_metrics_ssim(a, b, W, H, m, &s));
    CHECK(s == 1.0, "SSIM over an empty mask is 1");
    CHECK(snell_metrics_ssim(NULL, b, W, H, NULL, &s) == SNELL_E_INVALID_ARG, "NULL image refused");
    CHECK(snell_metrics_ssim(a, b, 0, H, NULL, &s) == SNELL_E_INVALID_ARG, "zero width refused");
}

int main(void)
{
    test_ssim();
    test_angle();
    test_metrics_dir_error();
    test_coverage();
    test_image_error();
    test_nonfinite();
    test_packed_encoding_error();
    return test_finish();
}
