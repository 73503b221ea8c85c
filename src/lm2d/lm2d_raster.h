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

#endif
