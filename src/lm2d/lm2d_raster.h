/* SPDX-License-Identifier: MIT */
/* lm2d_raster.h — GLES rasteriser of light paths: additive GL_LINES with the
 * slope flux correction (Brückner 6.5.2.2, eq. 6.4) into a float (or, as a
 * fallback, stochastically rounded fixed-point) accumulation texture. */
#ifndef SNELL_LM2D_RASTER_H
#define SNELL_LM2D_RASTER_H

#include "lm2d/lm2d_raster_cpu.h"

typedef struct lm2d_gl lm2d_gl;

/* Creates FBO, texture, program and a VBO for `batch_lines` lines (allocated
 * once). format AUTO picks by extension; the chosen one is reported by lm2d_gl_format. */
snell_status lm2d_gl_create(snell_ctx *ctx, int width, int height, snell_format2d format, snell_blend2d blend,
                            lm2d_gl **out);
void lm2d_gl_destroy(lm2d_gl *g);
snell_format2d lm2d_gl_format(const lm2d_gl *g);
unsigned lm2d_gl_texture(const lm2d_gl *g);
/* Clears the accumulation to 0 (ADD) or 0 (SCREEN also starts from black). */
void lm2d_gl_clear(lm2d_gl *g);
/* Draws the segments additively; each segment's flux is multiplied by
 * scale x c (c = |p| / max(|px|,|py|) in pixels, clamped to [1, sqrt 2]).
 * GL state touched is saved and restored. */
snell_status lm2d_gl_draw(lm2d_gl *g, const lm2d_path *paths, size_t n, const lm2d_raster_view *v, float scale);
/* Reads the accumulation as float RGB, top row first, times `scale`. */
snell_status lm2d_gl_read(lm2d_gl *g, float *rgb, float scale);
void lm2d_gl_finish(lm2d_gl *g);
/* Replaces the accumulation texture with a CPU lightmap (LM2D_RASTER_PX floats
 * per pixel, bottom row first: the texture's layout), each value v stored as
 * mul * v, or as 1 - v when one_minus (SCREEN's product); fixed-point targets
 * clamp to [0,1]. A float target with mul 1 takes the image as it is. */
snell_status lm2d_gl_upload(lm2d_gl *g, const float *img, float mul, int one_minus);

/* The rasteriser rule of SNELL_RASTER2D_AUTO (snell_2d.h): CPU without GL, or
 * when `renderer` (GL_RENDERER) names a software rasteriser
 * (snell__software_rasteriser); GL otherwise. An explicit GL or CPU is kept (GL without GL is
 * reported by the caller). Writes why into reason (reason_size bytes). */
snell_raster2d lm2d_raster_pick(snell_raster2d want, int have_gl, const char *renderer, char *reason,
                                size_t reason_size);

#endif
