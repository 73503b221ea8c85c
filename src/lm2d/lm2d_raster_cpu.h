/* SPDX-License-Identifier: MIT */
/* lm2d_raster_cpu.h — the exact CPU rasteriser of light paths (Brückner eq. 4.2):
 * every pixel receives the flux integrated along the part of each segment
 * inside it, length in pixel widths; threaded over row bands, bitwise the same
 * for any thread count. The reference the GL lines are measured against. */
#ifndef SNELL_LM2D_RASTER_CPU_H
#define SNELL_LM2D_RASTER_CPU_H

#include "lm2d/lm2d_trace.h"

typedef struct lm2d_raster_view {
    int width, height;
    float lo[2], hi[2];   /* world rectangle; lo = top-left corner of pixel (0,0) */
} lm2d_raster_view;

/* Rows per band: the unit of work a thread takes (17 bands at 1080p). A segment
 * costs a walk in every band it crosses, so narrower bands cost more CPU time
 * and wider ones leave fewer bands to share between threads
 * (bench/notes/code.md, "lm2d_raster_cpu.h"). The result does not depend on it. */
#ifndef LM2D_RASTER_BAND
#define LM2D_RASTER_BAND 64
#endif
/* Floats per pixel of the CPU image: RGB and a fourth lane (A: + 0, or x 1 for
 * SCREEN) so a pixel is one SIMD add, and the image is an RGBA32F texture as is. */
#define LM2D_RASTER_PX 4

/* One list of segments (a light's paths), rasterised in list order. */
typedef struct lm2d_raster_src {
    const lm2d_path *paths;
    size_t n;
} lm2d_raster_src;

typedef enum lm2d_raster_op {
    LM2D_RASTER_ADD = 0,  /* img += scale * integral */
    LM2D_RASTER_SCREEN    /* img *= 1 - min(scale * integral, 1) (thesis eq. 6.5; the image is 1 - img) */
} lm2d_raster_op;

/* Reusable scratch of the threaded rasteriser: which segments touch which band. */
typedef struct lm2d_raster_bins lm2d_raster_bins;
snell_status lm2d_raster_bins_create(const snell_ctx *ctx, const snell_alloc *al, lm2d_raster_bins **out);
void lm2d_raster_bins_destroy(lm2d_raster_bins *bins);
/* Bytes the bins need for n segments: a setup and one band entry each, with
 * the growth headroom (a segment crossing several bands needs more entries). */
size_t lm2d_raster_bins_bytes(size_t segments);
/* The most bytes the bins may hold (0: no limit); past it a frame's bands scan
 * every segment instead. */
void lm2d_raster_bins_limit(lm2d_raster_bins *bins, size_t bytes);

/* Rasterises src[0], src[1], ... into img (LM2D_RASTER_PX floats per pixel,
 * rows in the order of the view's y: lo[1] > hi[1] gives rows bottom first as
 * GL stores them; flux linear between c0 and c1 along each segment). clear: first sets img to
 * 0 (ADD) or 1 (SCREEN). The image is cut into bands of LM2D_RASTER_BAND rows
 * that the pool's threads take in turn (pool NULL: the calling thread alone);
 * one thread does a whole band, segments in list order, so the image is
 * bitwise the same for any thread count. bins (may be NULL: every band then
 * scans every segment) lists each band's segments first; it grows with the
 * segment count (allocation only when a frame has more than before). */
void lm2d_raster_exact(lm2d_raster_bins *bins, lm2d_pool *pool, const lm2d_raster_src *src, int n_src,
                       const lm2d_raster_view *v, float scale, lm2d_raster_op op, int clear, float *img);

/* Single-threaded shorthands, no clear (LM2D_RASTER_PX floats per pixel). */
void lm2d_raster_exact_add(const lm2d_path *paths, size_t n, const lm2d_raster_view *v, float scale, float *acc);
void lm2d_raster_exact_screen(const lm2d_path *paths, size_t n, const lm2d_raster_view *v, float scale,
                              float *prod);

#endif
