/* backdrop.h — the host's scene behind the glass (snell_frame_desc.backdrop):
 * a stage that publishes the host's colour and depth textures (or its own
 * copies of the bound framebuffer's) and a kernel hook, SNELL_BACKDROP, by
 * which every glass kernel's rays that leave the glass search them in screen
 * space before the environment (common/backdrop.glsl via common/beyond.glsl). */
#ifndef SNELL_BACKDROP_H
#define SNELL_BACKDROP_H

#include "frame/stage.h"

typedef struct snell__backdrop snell__backdrop; /* its state, made on the first frame with a backdrop */

/* The frame's backdrop for the renderer's target kind: SNELL_E_INVALID_ARG naming the field. */
snell_status snell__backdrop_validate(snell_ctx *ctx, const snell_frame_desc *fd, snell_target target);
/* The stage (render/stages.c): wanted where the frame has a backdrop; run
 * copies the bound framebuffer (COPY_BOUND) and publishes the textures. */
int snell__backdrop_wanted(const snell__frame *f);
snell_status snell__backdrop_run(snell__frame *f);
unsigned snell__backdrop_variant(const snell__frame *f, const snell__object *o);
#define SNELL__BACKDROP_UNIFORMS 4
extern const snell__kernel_hook snell__backdrop_hook;
void snell__backdrop_destroy(snell_ctx *ctx, snell__backdrop *b);

#endif
