/* lm2d_raster_cpu.h — the exact CPU rasteriser of light paths (Brückner eq. 4.2):
 * every pixel receives the flux integrated along the part of each segment
 * inside it, length in pixel widths. The reference the GL lines are measured against. */
#ifndef SNELL_LM2D_RASTER_CPU_H
#define SNELL_LM2D_RASTER_CPU_H

#include "lm2d/lm2d_trace.h"

typedef struct lm2d_raster_view {
    int width, height;
    float lo[2], hi[2];   /* world rectangle; lo = top-left corner of pixel (0,0) */
} lm2d_raster_view;

/* acc[3 * (y * width + x)] += scale * integral of the flux over the segment
 * inside pixel (x, y) (rows top first). Flux is linear between c0 and c1. */
void lm2d_raster_exact_add(const lm2d_path *paths, size_t n, const lm2d_raster_view *v, float scale, float *acc);

/* Screen blend (thesis eq. 6.5) of the same per-pixel values x = scale * integral:
 * prod[i] *= (1 - min(x, 1)); the image is 1 - prod. */
void lm2d_raster_exact_screen(const lm2d_path *paths, size_t n, const lm2d_raster_view *v, float scale,
                              float *prod);

#endif
