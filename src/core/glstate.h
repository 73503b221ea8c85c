/* SPDX-License-Identifier: MIT */
/* glstate.h — snapshot and restore of the GL state the renderer touches, so
 * the library can draw inside a host application's context (EXTERNAL backend). */
#ifndef SNELL_GLSTATE_H
#define SNELL_GLSTATE_H

#include "snell/snell.h"

/* Texture units a scope tracks: bit u of a mask is GL_TEXTURE0 + u (a
 * program takes at most 16, frame/textures.c checks). */
#define SNELL__UNITS_MAX 32

/* Pixel pack or unpack state (GLES 3.0 tables 6.29, 6.30) and the pixel
 * buffer bound for it. */
typedef struct snell__pixel_store {
    int buffer, alignment, row_length, skip_rows, skip_pixels, image_height, skip_images;
} snell__pixel_store;

/* A scope of the calling thread's GL work that follows its texture units
 * (glActiveTexture, glBindTexture and glBindSampler go through core/gl.h's
 * wrappers): each unit's first use in the scope saves its bindings (save)
 * and unbinds its sampler object (reset_samplers: the frame's defaults).
 * Scopes nest; a use counts in every open scope. */
typedef struct snell__units {
    struct snell__units *outer;
    unsigned used; /* units selected or bound on so far */
    int save, reset_samplers;
    int tex_2d[SNELL__UNITS_MAX], tex_cube[SNELL__UNITS_MAX], tex_2d_array[SNELL__UNITS_MAX];
    int sampler[SNELL__UNITS_MAX];
} snell__units;

/* Opens the scope u. The outermost scope without save selects unit 0 (a
 * context snell owns: nothing to ask). */
void snell__units_begin(snell__units *u, int save, int reset_samplers);
/* Closes the scope u (the innermost), restoring the saved units' bindings;
 * the active unit is left to the caller. */
void snell__units_end(snell__units *u);
/* Units used in the scope u so far. */
int snell__units_count(const snell__units *u);

typedef struct snell_glstate {
    int draw_fbo, read_fbo, renderbuffer, program, vao, array_buffer, active_texture;
    snell__units units; /* the texture units used since the save, as they were */
    int viewport[4], scissor_box[4];
    unsigned caps; /* glIsEnabled of each capability in glstate.c's table, a bit each */
    unsigned char color_mask[4], depth_mask;
    int depth_func, cull_mode, front_face;
    int blend_src_rgb, blend_dst_rgb, blend_src_a, blend_dst_a, blend_eq_rgb, blend_eq_a;
    float clear_color[4], clear_depth;
    float depth_range[2];
    snell__pixel_store pack, unpack;
    unsigned char tf_paused; /* the host's transform feedback, paused by the save */
    unsigned host_errors;    /* GL errors pending at the save, raised again by the restore */
} snell_glstate;

/* Saves the state and opens a units scope that saves each unit at its
 * first use; restore closes it and puts everything back (innermost first).
 * Errors pending at the save wait outside: a check before the restore sees
 * only snell's own. */
void snell__glstate_save(snell_glstate *s);
void snell__glstate_restore(snell_glstate *s);

/* Sets the state a frame's output depends on that the passes do not set
 * themselves (all backends; EXTERNAL saved it first): depth range 0..1, no
 * rasterizer discard, coverage or primitive restart, counter-clockwise front
 * faces culled from the back, no pixel buffers bound and default pixel store
 * state (texture allocations in a frame pass NULL data, which a bound unpack
 * buffer would turn into an offset). The frame's units scope unbinds sampler
 * objects from each unit it uses. */
void snell__glstate_frame_defaults(void);

/* Around a read-back into (an upload from) client memory: saves the pack
 * (unpack) state, unbinds any pixel buffer and sets tight rows with the given
 * alignment and nothing skipped; end puts back what begin saved. */
void snell__pixel_pack_begin(snell__pixel_store *saved, int alignment);
void snell__pixel_pack_end(const snell__pixel_store *saved);
void snell__pixel_unpack_begin(snell__pixel_store *saved, int alignment);
void snell__pixel_unpack_end(const snell__pixel_store *saved);

/* The GL errors pending now, taken (a bit per kind: 1 << (error -
 * GL_INVALID_ENUM)), and raised again. GL_OUT_OF_MEMORY and context loss
 * cannot be raised on purpose: taken, they are gone (docs/integrating.md). */
unsigned snell__gl_errors_take(void);
void snell__gl_errors_give(unsigned mask);

#endif
