/* SPDX-License-Identifier: MIT */
/* fuzz_scene2d.c — libFuzzer target for the 2D lightmap's text inputs: every
 * input goes through the CSV polygon parser and the scene-file parser
 * (lm2d_parse_csv, lm2d_scene_parse). CSV references inside a fuzzed scene
 * resolve under a directory that does not exist, so no file is opened.
 * Either a parse fails with a message, or it yields finite points. */
#include "fuzz_common.h"
#include "lm2d/lm2d_scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const snell_alloc *al = snell__ctx_alloc(NULL);
    char *text = (char *)malloc(size + 1);
    float *pts = NULL, view[4];
    int n = 0, i, dims[2];
    snell_scene2d *scene = NULL;
    snell_status st;
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';

    st = lm2d_parse_csv(NULL, al, text, size, "fuzz.csv", &pts, &n);
    if (st != SNELL_OK) {
        if (pts || !snell_last_error(NULL)[0]) abort();
    } else {
        if (n < 0 || (n > 0 && !pts)) abort();
        for (i = 0; i < 2 * n; i++)
            if (!isfinite(pts[i])) abort();
        snell__free(al, pts);
    }

    if (snell_scene2d_create(NULL, &scene) == SNELL_OK) {
        st = lm2d_scene_parse(scene, text, "fuzz.txt", "/nonexistent-fuzz-dir/", view, dims);
        if (st != SNELL_OK && !snell_last_error(NULL)[0]) abort();
        snell_scene2d_destroy(scene);
    }
    free(text);
    return 0;
}
