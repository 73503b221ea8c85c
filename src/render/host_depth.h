/* SPDX-License-Identifier: MIT */
/* host_depth.h — the target's depth buffer as the frame's snell_depth_mode
 * asks: cleared, kept and tested, or kept, tested and given back unchanged
 * (SNELL_DEPTH_TEST_NO_WRITE: blitted into a renderbuffer of the same format
 * before the frame and back after it). */
#ifndef SNELL_HOST_DEPTH_H
#define SNELL_HOST_DEPTH_H

#include "core/core.h"

typedef struct snell__host_depth {
    unsigned fbo, rb;               /* the copy, made on first use, remade when its format or size changes */
    unsigned format;
    int width, height;
    unsigned target_fbo;            /* the framebuffer the copy came from (this frame) */
    int saved;                      /* a copy waits to be given back */
} snell__host_depth;

/* The depth format of the bound draw framebuffer fbo (0: the default one),
 * as glBlitFramebuffer needs it matched; 0 if none is known. */
unsigned snell__host_depth_format(int fbo);
/* The mode the frame uses: DEFAULT resolved for the target. */
snell_depth_mode snell__depth_mode_of(snell_depth_mode asked, snell_target target);
/* At the frame's start, with the target bound and the viewport set:
 * clears, or for NO_WRITE copies the depth (SNELL_E_UNSUPPORTED naming why
 * when it cannot be copied back: a multisampled or depthless target, or a
 * format the copy cannot match). */
snell_status snell__host_depth_begin(snell_ctx *ctx, snell__host_depth *d, snell_depth_mode mode, int width,
                                     int height);
/* At the frame's end (the target bound again): gives the copy back. */
snell_status snell__host_depth_end(snell_ctx *ctx, snell__host_depth *d);
void snell__host_depth_destroy(snell__host_depth *d);

#endif
