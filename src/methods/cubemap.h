/* SPDX-License-Identifier: MIT */
/* cubemap.h — the cubemap method's search pass with a doubt test per pixel
 * (hybrid.frag), for the hybrid method (methods/hybrid.c), which draws exact
 * on the pixels the cubemap doubts. */
#ifndef SNELL_CUBEMAP_H
#define SNELL_CUBEMAP_H

#include "frame/frame.h"

/* What a doubted pixel gets (SNELL_DOUBT_MODE in hybrid.frag). */
#define SNELL__CUBEMAP_DOUBT_DISCARD 1 /* nothing: forward, depth unwritten */
#define SNELL__CUBEMAP_DOUBT_NEAR 2    /* screen space: its depth at the near plane */
#define SNELL__CUBEMAP_DOUBT_SHOW 3    /* magenta, to see the mask */

/* The cubemap method's draw (state its create()'s, o->prepared its
 * prepared resource) with the doubt test of mode doubt, threshold in
 * units of the cube's radius. */
snell_status snell__cubemap_draw_doubt(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                       snell_object_stats *stats, int doubt, float threshold);

#endif
