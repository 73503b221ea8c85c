/* SPDX-License-Identifier: MIT */
/* bench_classes.c — snell-bench's errors per object class: the pixels whose
 * view ray meets glass first, an opaque object first, or nothing, in the
 * reference (its first-hit object ids, snell_ref_output.object), and the
 * whole image, and the glass pixels where other glass shows (the whole-scene
 * and isolated references differ there); each with the existing metrics (snell_metrics_image_error,
 * snell_metrics_ssim) over a mask of that class. The classes partition the
 * image, so an error confined to one class shows in that class and in "all"
 * only (SSIM's 11x11 window reaches 5 pixels into the neighbouring classes). */
#include "bench.h"

const char *const bench_class_names[BENCH_CLASS_COUNT] = {"glass", "glass_through_glass", "opaque", "background",
                                                          "all"};

bench_class bench_class_of(int16_t object)
{
    if (object >= 0) return BENCH_CLASS_GLASS;
    return object == -1 ? BENCH_CLASS_BACKGROUND : BENCH_CLASS_OPAQUE;
}

snell_status bench_class_errors(const uint8_t *test, const uint8_t *ref, const int16_t *object, const uint8_t *through,
                                int w, int h, uint8_t *mask, bench_class_error out[BENCH_CLASS_COUNT])
{
    long i, n = (long)w * h;
    int c;
    snell_status st = SNELL_OK;
    for (c = 0; c < BENCH_CLASS_COUNT && st == SNELL_OK; c++) {
        const uint8_t *m = NULL; /* BENCH_CLASS_ALL: every pixel */
        if (c == BENCH_CLASS_GLASS_THROUGH) {
            for (i = 0; i < n; i++) mask[i] = (uint8_t)(through && through[i] && object[i] >= 0);
            m = mask;
        } else if (c != BENCH_CLASS_ALL) {
            for (i = 0; i < n; i++) mask[i] = (uint8_t)(bench_class_of(object[i]) == (bench_class)c);
            m = mask;
        }
        st = snell_metrics_image_error(test, ref, w, h, m, &out[c].img);
        if (st == SNELL_OK) st = snell_metrics_ssim(test, ref, w, h, m, &out[c].ssim);
    }
    return st;
}
