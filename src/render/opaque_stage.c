/* SPDX-License-Identifier: MIT */
/* opaque_stage.c — the opaque stage: the frame's opaque objects, drawn with
 * depth write before any glass (render/composite.c). It resolves their
 * albedo for every stage that draws or lights them. */
#include "render/stages.h"
#include "frame/lighting.h"

typedef struct opaque_state {
    snell_opaque resolved[SNELL_MAX_OPAQUE];
} opaque_state;

static snell_status validate(const snell__services *sv, const snell_frame_desc *fd)
{
    return snell__opaque_validate(sv->ctx, fd->opaque, fd->opaque_count);
}

static void resolve(const snell__services *sv, snell_frame_desc *fd, void *state)
{
    opaque_state *s = (opaque_state *)state;
    int i;
    (void)sv;
    if (fd->opaque_count < 0 || fd->opaque_count > SNELL_MAX_OPAQUE || !fd->opaque) return; /* validate() says why */
    for (i = 0; i < fd->opaque_count; i++) snell__opaque_defaults(&fd->opaque[i], &s->resolved[i]);
    if (fd->opaque_count > 0) fd->opaque = s->resolved;
}

static snell_status run(snell__frame *f, void *state)
{
    const snell__services *sv = f->sv;
    snell_status st = snell__composite_opaque(sv->ctx, sv->comp, sv->out, f->fd->opaque, f->fd->opaque_count,
                                              (const float *)f->sc->view.view_proj, f->sc->view.eye,
                                              f->sc->view.view_axis, NULL);
    (void)state;
    if (f->fd->opaque_count > 0) {
        f->s->opaque_drawn = f->fd->opaque_count;
        f->depth_drawn = 1;
        f->s->passes++;
    }
    return st;
}

const snell__stage snell__stage_opaque = {
    .name = "opaque",
    .state_size = sizeof(opaque_state),
    .validate = validate,
    .resolve = resolve,
    .run = run,
};
