/* SPDX-License-Identifier: MIT */
/* metrics.c — error metrics against the reference (snell_metrics.h): angular
 * error of exit directions, RGBA8 image RMSE/PSNR, non-finite counts. */
#include "core/core.h"
#include "snell/snell_metrics.h"

#include <math.h>
#include <string.h>

#define HIST_BINS 2048
#define HIST_LO_DEG 1e-6
#define HIST_HI_DEG 180.0
#define RAD2DEG 57.295779513082320876798

double snell_metrics_angle(const float a[3], const float b[3])
{
    double x[3], y[3], c[3], la = 0.0, lb = 0.0, dot = 0.0, cr;
    int k;
    for (k = 0; k < 3; k++) {
        if (!isfinite(a[k]) || !isfinite(b[k])) return NAN;
        x[k] = a[k];
        y[k] = b[k];
        la += x[k] * x[k];
        lb += y[k] * y[k];
    }
    if (la == 0.0 || lb == 0.0) return NAN;
    c[0] = x[1] * y[2] - x[2] * y[1];
    c[1] = x[2] * y[0] - x[0] * y[2];
    c[2] = x[0] * y[1] - x[1] * y[0];
    for (k = 0; k < 3; k++) dot += x[k] * y[k];
    cr = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    /* Both lengths cancel in the ratio, so no normalisation is needed. */
    return atan2(cr, dot);
}

static int finite3(const float *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

/* Log-spaced bin of an angle in degrees; 0 for anything below the range. */
static int hist_bin(double deg)
{
    double t;
    int b;
    if (!(deg > HIST_LO_DEG)) return 0;
    t = log(deg / HIST_LO_DEG) / log(HIST_HI_DEG / HIST_LO_DEG);
    b = 1 + (int)(t * (HIST_BINS - 2));
    return b < 1 ? 1 : b > HIST_BINS - 1 ? HIST_BINS - 1 : b;
}

/* Upper edge of a bin, degrees (bin 0: HIST_LO_DEG). */
static double hist_edge(int b)
{
    if (b <= 0) return HIST_LO_DEG;
    return HIST_LO_DEG * pow(HIST_HI_DEG / HIST_LO_DEG, (double)b / (HIST_BINS - 2));
}

static double hist_quantile(const long *hist, long count, double q)
{
    long want = (long)ceil(q * (double)count), acc = 0;
    int b;
    if (count <= 0) return 0.0;
    if (want < 1) want = 1;
    for (b = 0; b < HIST_BINS; b++) {
        acc += hist[b];
        if (acc >= want) return hist_edge(b);
    }
    return HIST_HI_DEG;
}

snell_status snell_metrics_dir_error(const snell_dir_error_desc *desc, snell_dir_error *out)
{
    long hist[HIST_BINS];
    long i, n, above1 = 0, above5 = 0;
    double sum = 0.0, sum2 = 0.0;
    snell_dir_error e;
    if (!desc || !out || !desc->test || !desc->ref)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_metrics_dir_error: desc, out, test and ref are required");
    if (desc->width < 1 || desc->height < 1 || desc->width > 65536 || desc->height > 65536)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_metrics_dir_error: size %dx%d outside 1..65536",
                           desc->width, desc->height);
    memset(&e, 0, sizeof e);
    memset(hist, 0, sizeof hist);
    n = (long)desc->width * desc->height;
    e.pixels = n;
    for (i = 0; i < n; i++) {
        const float *t = desc->test + 3 * i, *r = desc->ref + 3 * i;
        int in_ref = desc->ref_mask ? desc->ref_mask[i] != 0 : 1;
        int in_test = desc->test_mask ? desc->test_mask[i] != 0 : in_ref;
        double deg;
        if (desc->error_deg) desc->error_deg[i] = NAN;
        e.glass_ref += in_ref;
        e.glass_test += in_test;
        if (!finite3(t)) {
            e.nan_inf++;
            continue;
        }
        if (in_ref != in_test) {
            e.mask_mismatch++;
            continue;
        }
        if (!in_ref) continue;
        deg = snell_metrics_angle(t, r) * RAD2DEG;
        if (isnan(deg)) {
            /* test is finite here, so it is zero-length (or the reference is bad). */
            e.zero_length += t[0] == 0.0f && t[1] == 0.0f && t[2] == 0.0f;
            continue;
        }
        if (desc->error_deg) desc->error_deg[i] = (float)deg;
        e.compared++;
        sum += deg;
        sum2 += deg * deg;
        if (deg > e.max_deg) e.max_deg = deg;
        above1 += deg > 1.0;
        above5 += deg > 5.0;
        hist[hist_bin(deg)]++;
    }
    if (e.compared > 0) {
        e.mean_deg = sum / (double)e.compared;
        e.rms_deg = sqrt(sum2 / (double)e.compared);
        e.median_deg = hist_quantile(hist, e.compared, 0.5);
        e.p99_deg = hist_quantile(hist, e.compared, 0.99);
        e.frac_above_1deg = (double)above1 / (double)e.compared;
        e.frac_above_5deg = (double)above5 / (double)e.compared;
        /* The histogram edge can exceed the true maximum by one bin. */
        if (e.median_deg > e.max_deg) e.median_deg = e.max_deg;
        if (e.p99_deg > e.max_deg) e.p99_deg = e.max_deg;
    }
    *out = e;
    return SNELL_OK;
}

snell_status snell_metrics_coverage_mask(const float *dirs, const float *background, long n, uint8_t *mask)
{
    long i;
    if (!dirs || !background || !mask || n < 0)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_metrics_coverage_mask: NULL argument or n < 0");
    for (i = 0; i < n; i++)
        mask[i] = (uint8_t)(memcmp(dirs + 3 * i, background + 3 * i, 3 * sizeof(float)) != 0 ||
                            !finite3(dirs + 3 * i));
    return SNELL_OK;
}

snell_status snell_metrics_image_error(const uint8_t *test_rgba, const uint8_t *ref_rgba, int width, int height,
                                       const uint8_t *mask, snell_image_error *out)
{
    long i, n;
    double sum2 = 0.0, sum = 0.0;
    snell_image_error e;
    if (!test_rgba || !ref_rgba || !out)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_metrics_image_error: NULL argument");
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_metrics_image_error: size %dx%d outside 1..65536", width,
                           height);
    memset(&e, 0, sizeof e);
    n = (long)width * height;
    for (i = 0; i < n; i++) {
        int c, worst = 0;
        if (mask && !mask[i]) continue;
        e.pixels++;
        for (c = 0; c < 3; c++) {
            int d = (int)test_rgba[4 * i + c] - (int)ref_rgba[4 * i + c];
            int a = d < 0 ? -d : d;
            sum += a;
            sum2 += (double)d * d;
            if (a > worst) worst = a;
        }
        if (worst > e.max_abs) e.max_abs = worst;
        e.above_3 += worst > 3;
    }
    if (e.pixels > 0) {
        e.rmse = sqrt(sum2 / (3.0 * (double)e.pixels));
        e.mean_abs = sum / (3.0 * (double)e.pixels);
    }
    e.psnr_db = e.rmse > 0.0 ? 20.0 * log10(255.0 / e.rmse) : INFINITY;
    *out = e;
    return SNELL_OK;
}

#define SSIM_RADIUS 5 /* 11 x 11 */

snell_status snell_metrics_ssim(const uint8_t *test_rgba, const uint8_t *ref_rgba, int width, int height,
                                const uint8_t *mask, double *out)
{
    const double c1 = (0.01 * 255.0) * (0.01 * 255.0), c2 = (0.03 * 255.0) * (0.03 * 255.0);
    double g[2 * SSIM_RADIUS + 1], sum = 0.0;
    long count = 0;
    int x, y, k;
    if (!test_rgba || !ref_rgba || !out)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_metrics_ssim: NULL argument");
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_metrics_ssim: size %dx%d outside 1..65536", width,
                           height);
    for (k = -SSIM_RADIUS; k <= SSIM_RADIUS; k++) g[k + SSIM_RADIUS] = exp(-(double)(k * k) / (2.0 * 1.5 * 1.5));
    for (y = 0; y < height; y++)
        for (x = 0; x < width; x++) {
            double m[3][5] = {{0}}, wsum = 0.0, s = 0.0;
            int dx, dy, c;
            if (mask && !mask[(size_t)y * width + x]) continue;
            for (dy = -SSIM_RADIUS; dy <= SSIM_RADIUS; dy++) {
                int yy = y + dy;
                if (yy < 0 || yy >= height) continue;
                for (dx = -SSIM_RADIUS; dx <= SSIM_RADIUS; dx++) {
                    int xx = x + dx;
                    size_t i = 4 * ((size_t)yy * width + xx);
                    double w;
                    if (xx < 0 || xx >= width) continue;
                    w = g[dx + SSIM_RADIUS] * g[dy + SSIM_RADIUS];
                    wsum += w;
                    for (c = 0; c < 3; c++) {
                        double a = test_rgba[i + c], b = ref_rgba[i + c];
                        m[c][0] += w * a;
                        m[c][1] += w * b;
                        m[c][2] += w * a * a;
                        m[c][3] += w * b * b;
                        m[c][4] += w * a * b;
                    }
                }
            }
            for (c = 0; c < 3; c++) {
                double ma = m[c][0] / wsum, mb = m[c][1] / wsum;
                double va = m[c][2] / wsum - ma * ma, vb = m[c][3] / wsum - mb * mb, cov = m[c][4] / wsum - ma * mb;
                s += (2.0 * ma * mb + c1) * (2.0 * cov + c2) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            }
            sum += s / 3.0;
            count++;
        }
    *out = count ? sum / (double)count : 1.0;
    return SNELL_OK;
}

long snell_metrics_count_nonfinite(const float *v, long n)
{
    long i, c = 0;
    if (!v) return 0;
    for (i = 0; i < n; i++) c += !isfinite(v[i]);
    return c;
}
