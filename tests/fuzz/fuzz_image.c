/* SPDX-License-Identifier: MIT */
/* fuzz_image.c — libFuzzer target for environment image input
 * (snell_image_decode: PNG, HDR; JPEG is refused). Built with -DSNELL_LIBFUZZER for
 * libFuzzer; otherwise a replay program (see fuzz_common.h). An input either
 * fails with a message and no pixels, or decodes to a sane size. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int w = 0, h = 0;
    uint8_t *px = NULL;
    snell_status st;
    data = fuzz_at_end_of_mapping(data, size);
    st = snell_image_decode(data, size, &w, &h, &px);
    if (st != SNELL_OK) {
        if (px || !snell_last_error(NULL)[0]) abort();
        return 0;
    }
    if (!px || w < 1 || h < 1 || w > 16384 || h > 16384) abort();
    /* Read the last texel: the buffer must hold w * h RGBA texels (ASan checks). */
    {
        volatile uint8_t last = px[(size_t)w * h * 4 - 1];
        (void)last;
    }
    snell_image_free(px);
    return 0;
}
