/* SPDX-License-Identifier: MIT */
/* bench_ref.h — reference images for snell-bench (snell_ref_render of the
 * configuration's whole scene), cached on disk so that reruns only time the GPU. */
#ifndef SNELL_BENCH_REF_H
#define SNELL_BENCH_REF_H

#include "snell/snell_ref.h"

/* Reference results of one scene/camera/size/material/mode, width*height pixels. */
typedef struct bench_ref_image {
    int width, height;
    float *rgb, *exit_dir;
    uint8_t *hit, *rgba;
    int16_t *object;               /* what the view ray hits first (snell_ref_output.object) */
} bench_ref_image;

/* Renders the reference of scene with params p, or loads it from cache_dir
 * (NULL: no cache). The cache key holds everything the result depends on:
 * each object's mesh content (hashed), model matrix and resolved material or
 * colour, and every field of p that matters; env_key names p's environment.
 * *cached tells which happened. */
snell_status bench_ref_get(const snell_ref_desc *scene, const snell_ref_params *p, const char *env_key,
                           const char *cache_dir, bench_ref_image *out, int *cached);
void bench_ref_free(bench_ref_image *img);

#endif
