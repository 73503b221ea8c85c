/* SPDX-License-Identifier: MIT */
/* glstate.h — snapshot and restore of the GL state the renderer touches, so
 * the library can draw inside a host application's context (EXTERNAL backend). */
#ifndef SNELL_GLSTATE_H
#define SNELL_GLSTATE_H

#include "snell/snell.h"

#define SNELL_GLSTATE_UNITS 16 /* texture units saved and restored: every unit a program may take (frame/textures.c checks) */

/* Pixel pack or unpack state (GLES 3.0 tables 6.29, 6.30) and the pixel
 * buffer bound for it. */
typedef struct snell__pixel_store {
    int buffer, alignment, row_length, skip_rows, skip_pixels, image_height, skip_images;
} snell__pixel_store;

typedef struct snell_glstate {
    int draw_fbo, read_fbo, renderbuffer, program, vao, array_buffer, active_texture;
    int tex_2d[SNELL_GLSTATE_UNITS], tex_cube[SNELL_GLSTATE_UNITS];
    int tex_2d_array[SNELL_GLSTATE_UNITS]; /* the depth-peeled layers (methods/peel.c) */
    int viewport[4], scissor_box[4];
    unsigned char depth_test, cull_face, blend, scissor_test, stencil_test, polygon_offset, dither;
    unsigned char color_mask[4], depth_mask;
    int depth_func, cull_mode, front_face;
    int blend_src_rgb, blend_dst_rgb, blend_src_a, blend_dst_a, blend_eq_rgb, blend_eq_a;
    float clear_color[4], clear_depth;
    int pack_alignment, unpack_alignment;
    int sampler[SNELL_GLSTATE_UNITS];
    float depth_range[2];
    unsigned char rasterizer_discard, alpha_to_coverage, sample_coverage, primitive_restart;
    snell__pixel_store pack, unpack;
} snell_glstate;

void snell__glstate_save(snell_glstate *s);
void snell__glstate_restore(const snell_glstate *s);

/* Sets the state a frame's output depends on that the passes do not set
 * themselves (all backends; EXTERNAL saved it first): no sampler objects on
 * the units above, depth range 0..1, no rasterizer discard, coverage or
 * primitive restart, counter-clockwise front faces culled from the back, no
 * pixel buffers bound and default pixel store state (texture allocations in a
 * frame pass NULL data, which a bound unpack buffer would turn into an offset). */
void snell__glstate_frame_defaults(void);

/* Around a read-back into (an upload from) client memory: saves the pack
 * (unpack) state, unbinds any pixel buffer and sets tight rows with the given
 * alignment and nothing skipped; end puts back what begin saved. */
void snell__pixel_pack_begin(snell__pixel_store *saved, int alignment);
void snell__pixel_pack_end(const snell__pixel_store *saved);
void snell__pixel_unpack_begin(snell__pixel_store *saved, int alignment);
void snell__pixel_unpack_end(const snell__pixel_store *saved);



/* Light maps (the caustics stage's, the water floor's) add irradiance up by
 * blending: RGBA32F where float targets blend (EXT_color_buffer_float +
 * EXT_float_blend), else RGBA16F (EXT_color_buffer_half_float or _float),
 * else RGB10_A2, which GLES 3.0 renders and blends without extensions,
 * holding irradiance / SNELL__LIGHT_RANGE (the programs' SNELL_LIGHT_RANGE,
 * core/program.c). */
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
