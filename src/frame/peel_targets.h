/* SPDX-License-Identifier: MIT */
/* peel_targets.h — the targets of a depth peel (Everitt; Wang 2014 3.4) and
 * the per-layer set-up, shared by the peel kernel (methods/peel.c: one
 * object's layers) and the scene layers (render/layers.c: every object's):
 * an RGBA8 texture array (slice 2k: layer k's normal, 2k + 1: its depth and
 * flag/id, 0 = empty), two ping-pong RGBA8 textures holding the previous
 * layer's depth for depth_peel.frag's test, a depth renderbuffer, an
 * ANY_SAMPLES_PASSED query to stop at the first empty layer. */
#ifndef SNELL_PEEL_TARGETS_H
#define SNELL_PEEL_TARGETS_H

#include "core/core.h"

typedef struct snell__peel_targets {
    unsigned fbo, array_tex, next_tex[2], depth_rb, query;
    int width, height, capacity; /* target size, layers */
} snell__peel_targets;

void snell__peel_targets_release(snell__peel_targets *t);
/* Made (or remade) for a w x h target and at least `layers` layers, the
 * array left bound on texture unit `unit`; kept as long as they fit (a
 * larger target serves a smaller grid drawn at its corner: an object at a
 * resolution scale, render/glass_scale.h, beside one at full resolution).
 * *remade: 1 if they were (their contents are gone). what names them in
 * the error message. */
snell_status snell__peel_targets_ensure(snell_ctx *ctx, snell__peel_targets *t, int w, int h, int layers, int unit,
                                        const char *what, int *remade);
/* Within a pass on t->fbo (depth renderbuffer attached, the peel program
 * bound, the previous layer's unit active): attaches layer k and the
 * ping-pong texture it writes, clears them (flag 0: empty) and the depth,
 * and binds the previous layer's depth on the active unit. Layer 0 checks
 * the framebuffer's completeness: SNELL_E_GL if not. */
snell_status snell__peel_layer_begin(snell_ctx *ctx, const snell__peel_targets *t, int k);

#endif
