/* SPDX-License-Identifier: MIT */
/* host_target.h — the host's bound draw framebuffer (SNELL_TARGET_BOUND_FRAMEBUFFER),
 * checked before a frame draws into it: complete, a normalised or float
 * colour buffer, a depth buffer, alpha where the output is premultiplied;
 * an sRGB one written unencoded (GL_EXT_sRGB_write_control) or refused; the
 * host's viewport honoured. All of it with SNELL_WITH_HOST_FRAMEBUFFERS.
 * Only its draw buffer 0 (what snell's location 0 writes) stays on for the
 * frame; the host's list comes back at its end. */
#ifndef SNELL_HOST_TARGET_H
#define SNELL_HOST_TARGET_H

#include "core/core.h"
#include "render/host_depth_map.h"

#define SNELL__HOST_DRAW_BUFFERS 8

typedef struct snell__host_target {
    unsigned fbo;                                    /* the framebuffer checked (this frame) */
    unsigned draw_buffers[SNELL__HOST_DRAW_BUFFERS]; /* its list, when snell narrowed it */
    int draw_buffer_count;                           /* 0: left as it was */
    int srgb_write;                                  /* an sRGB target's encoding, off for the frame */
    int viewport[4];                                 /* the host's, at the frame's start */
    /* A viewport off the origin, or a depth of another convention: the
     * frame's rectangle copied in here, drawn, copied back */
    int rect[4];
    unsigned copy_fbo, copy_rb[2], copy_format, copy_depth; /* copy_depth: a mapped depth's texture */
    int copy_size[2], copied;
    snell__depth_map map; /* its map[] set: the host's depth is mapped, not copied */
    int mapped;
} snell__host_target;

/* glGetFramebufferAttachmentParameteriv of the bound draw framebuffer. */
int snell__fb_attachment(unsigned att, unsigned pname);
#ifdef SNELL_WITH_HOST_FRAMEBUFFERS
/* With the host's draw framebuffer bound: SNELL_OK, or SNELL_E_INVALID_ARG /
 * SNELL_E_UNSUPPORTED naming what it lacks (no GL error left). depth_map:
 * snell's depth as an affine function of the host's (snell__camera_depth_map),
 * NULL when they agree. */
snell_status snell__host_target_begin(snell_ctx *ctx, snell__host_target *t, int width, int height,
                                      int premultiplied, const double *depth_map);
/* The host's draw buffers back (the framebuffer bound again), the copy of
 * a viewport off the origin copied back into it, a mapped depth mapped back. */
snell_status snell__host_target_end(snell_ctx *ctx, snell__host_target *t);
void snell__host_target_destroy(snell__host_target *t);
#else
/* Without it (the device preset, whose apps draw into their own window's
 * framebuffer) the bound framebuffer is taken as it is. */
#define snell__host_target_begin(ctx, t, width, height, premultiplied, depth_map) ((void)(depth_map), SNELL_OK)
#define snell__host_target_end(ctx, t) ((void)(ctx), (void)(t), SNELL_OK)
#define snell__host_target_destroy(t) ((void)(t))
#endif

#endif
