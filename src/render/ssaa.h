/* SPDX-License-Identifier: MIT */
/* ssaa.h — supersampling for offscreen colour renderers
 * (snell_renderer_desc.ssaa = S): the frame is drawn into an S-times larger
 * colour texture, then resolved by a box filter into the w x h target that
 * snell_renderer_read_rgba reads. */
#ifndef SNELL_SSAA_H
#define SNELL_SSAA_H

#include "core/core.h"

typedef struct snell__ssaa {
    int factor;                     /* S; 1 = off (nothing made) */
    unsigned frame_tex;             /* RGBA8, S*w x S*h: the frame's colour attachment */
    unsigned resolve_fbo, resolve_rb; /* RGBA8, w x h */
    unsigned prog, vao;
    int u_frame;
} snell__ssaa;

/* Makes the resolve target (w x h) and program, and the large colour texture
 * (S*w x S*h) that the caller attaches to its frame framebuffer. */
snell_status snell__ssaa_create(snell_ctx *ctx, snell__ssaa *s, int factor, int w, int h);
void snell__ssaa_destroy(snell__ssaa *s);
/* Box-filters the frame texture into the resolve target (changes the
 * framebuffer binding, viewport, program, VAO and texture unit 0). */
void snell__ssaa_resolve(const snell__ssaa *s, int w, int h);

#endif
