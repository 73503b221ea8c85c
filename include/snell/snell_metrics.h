/* SPDX-License-Identifier: MIT */
/* snell_metrics.h — error metrics of a method against the reference:
 * per-pixel exit-direction angle, image RMSE/PSNR, SSIM, shares above 1 and 5
 * degrees, NaN/Inf counts. Pure CPU functions on caller-owned buffers; no
 * allocation. Angular statistics are taken over the pixels that are glass in
 * BOTH masks; disagreeing pixels are counted in mask_mismatch, non-finite test
 * directions in nan_inf. Why: docs/ARCHITECTURE.md, "Design notes by file". */
#ifndef SNELL_SNELL_METRICS_H
#define SNELL_SNELL_METRICS_H

#include "snell.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Angular error statistics, degrees. Percentiles come from a log-spaced
 * histogram (1e-6 .. 180 degrees, 2048 bins): each bin about 1% of its value wide. */
typedef struct snell_dir_error {
    long pixels;            /* width * height */
    long glass_ref;         /* glass pixels of the reference mask */
    long glass_test;        /* glass pixels of the test mask */
    long compared;          /* glass in both, both directions finite and non-zero */
    long mask_mismatch;     /* glass in exactly one mask */
    long nan_inf;           /* test pixels with a non-finite component (all pixels) */
    long zero_length;       /* finite but zero test directions (cannot be normalised) */
    double mean_deg, rms_deg, max_deg;
    double median_deg, p99_deg;
    double frac_above_1deg; /* share of compared pixels with error > 1 degree */
    double frac_above_5deg; /* share of compared pixels with error > 5 degrees */
} snell_dir_error;

typedef struct snell_dir_error_desc {
    const float *test;          /* required: 3 floats per pixel (need not be unit) */
    const float *ref;           /* required: 3 floats per pixel */
    const uint8_t *ref_mask;    /* optional: nonzero = glass pixel; NULL = every pixel */
    const uint8_t *test_mask;   /* optional: nonzero = glass pixel; NULL = ref_mask */
    int width, height;          /* >= 1 */
    float *error_deg;           /* optional out: per-pixel angle in degrees, NaN where not compared */
} snell_dir_error_desc;

/* Angle between two directions, radians, computed as atan2(|a x b|, a . b)
 * in double (accurate near 0 and pi, unlike acos). NaN if either is zero
 * or not finite. */
double snell_metrics_angle(const float a[3], const float b[3]);

snell_status snell_metrics_dir_error(const snell_dir_error_desc *desc, snell_dir_error *out);

/* mask[i] = 1 where dirs differs from background in any component (bitwise,
 * NaN counts as different), else 0. n = pixel count. Blind to unbent exits
 * (see above): snell_renderer_read_coverage is the renderer's own mask. */
snell_status snell_metrics_coverage_mask(const float *dirs, const float *background, long n, uint8_t *mask);

/* Image error of RGBA8 images over the RGB channels (alpha ignored), in
 * 8-bit units: RMSE = sqrt(mean squared channel difference), PSNR = 20
 * log10(255 / RMSE) dB (+INFINITY when identical). */
typedef struct snell_image_error {
    long pixels;                /* pixels considered */
    double rmse;                /* 0..255 */
    double psnr_db;
    double mean_abs;            /* mean |difference| per channel, 0..255 */
    int max_abs;                /* largest channel difference */
    long above_3;               /* pixels with a channel off by more than 3/255 */
} snell_image_error;

/* mask optional: nonzero = pixel considered; NULL = all. A mask selecting no
 * pixel gives pixels = 0, rmse 0, psnr +INFINITY. */
snell_status snell_metrics_image_error(const uint8_t *test_rgba, const uint8_t *ref_rgba, int width, int height,
                                       const uint8_t *mask, snell_image_error *out);

/* Structural similarity (Wang, Bovik, Sheikh, Simoncelli 2004, "Image
 * quality assessment: from error visibility to structural similarity"), as
 * there defined: 11x11 Gaussian window, sigma 1.5 pixels (weights renormalised
 * where the window leaves the image), C1 = (0.01 * 255)^2, C2 = (0.03 *
 * 255)^2, on each of R, G, B in 8-bit units; *out = the mean over the
 * considered pixels (mask nonzero; NULL = all) of the mean over the channels
 * of SSIM(window centred there). 1 for identical images, 1 also for an empty
 * mask. A perceptual companion of PSNR: it weighs structure (edges, the
 * refracted pattern) over uniform offsets. */
snell_status snell_metrics_ssim(const uint8_t *test_rgba, const uint8_t *ref_rgba, int width, int height,
                                const uint8_t *mask, double *out);

/* Non-finite values in n floats. */
long snell_metrics_count_nonfinite(const float *v, long n);

#ifdef __cplusplus
}
#endif
#endif
