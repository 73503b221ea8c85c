/* SPDX-License-Identifier: MIT */
/* exact.h — the exact method's draw for the hybrid (methods/hybrid.c): in
 * screen space without the G-buffer's object test, so that its depth test
 * alone picks the pixels and runs early. */
#ifndef SNELL_EXACT_H
#define SNELL_EXACT_H

#include "frame/frame.h"

/* The exact method's draw (state its create()'s, o->prepared its prepared
 * resource); in screen space every pixel the depth test passes is taken
 * as the object's (SNELL_SCREEN_OURS in exact.frag). */
snell_status snell__exact_draw_ours(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                    snell_object_stats *stats);

#endif
