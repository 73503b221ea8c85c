/* SPDX-License-Identifier: MIT */
/* light_map.h — the light maps' format policy: which format a context's
 * light maps take, their storage and their read-back as irradiance. */
#ifndef SNELL_LIGHT_MAP_H
#define SNELL_LIGHT_MAP_H

#include "snell/snell.h"

/* Light maps (the caustics stage's, the water floor's) add irradiance up by
 * blending: RGBA32F where float targets blend (EXT_color_buffer_float +
 * EXT_float_blend; snell__light_fixed says they do not, core/ctx.c), else
 * RGB10_A2, which GLES 3.0 renders and blends without extensions, holding
 * irradiance / SNELL__LIGHT_RANGE (the programs' SNELL_LIGHT_RANGE,
 * core/program.c) with each photon's share rounded stochastically. Not
 * RGBA16F: half floats drop every share under half the sum's last place, so
 * a map loses light wherever photons pile up. */
#define SNELL__LIGHT_RANGE 8.0f
unsigned snell__light_map_format(snell_ctx *ctx);
/* Allocates the bound 2D texture as a size x size light map of format. */
void snell__light_map_image(unsigned format, int size);
const char *snell__light_map_str(unsigned format);
/* Reads light map fbo of format, size x size RGBA floats of irradiance, into
 * rgba (tightly packed; the host's read framebuffer and pack state kept). A tool's
 * read, not a frame's: it finishes first, as Mesa 22.3's llvmpipe waits before
 * a read only for the current framebuffer and for what queued scenes sample,
 * not for a queued scene's own render target (the water's light map read after
 * the frame moved on came back stale or half drawn in 2 of 7 loaded runs).
 * what names the map in the error. */
snell_status snell__read_light_map(snell_ctx *ctx, unsigned format, unsigned fbo, int size, float *rgba,
                                   const char *what);

#endif
