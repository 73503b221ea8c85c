/* SPDX-License-Identifier: MIT */
/* caustics_stage.c — the caustics stage: the receiver plane lit by the
 * light, directly where no object shadows it and through the glass
 * (render/caustics.c), drawn like an opaque object before the glass, and
 * the opaque objects redrawn lit. Only in colour output. Its kernel hook
 * (SNELL_RECEIVER): every kernel's exit and reflected rays meet the lit
 * plane before the environment, and see the opaque objects lit. */
#include "render/stages.h"
#include "render/caustics.h"
#include "frame/glass_program.h"


static snell_status validate(const snell__services *sv, const snell_frame_desc *fd)
{
    return snell__caustics_validate(sv->ctx, fd);
}

static int wanted(const snell__frame *f, const void *state)
{
    (void)state;
    if (!snell__caustics_wanted(f->fd, f->s->caustics_reason, sizeof f->s->caustics_reason)) return 0;
    if (f->sv->out != SNELL__OUT_COLOR) {
        snell__why(f->s->caustics_reason, sizeof f->s->caustics_reason, "not in exit-direction output");
        return 0;
    }
    return 1;
}

static snell_status run(snell__frame *f, void *state)
{
    snell__caustics *c = (snell__caustics *)state;
    snell_status st = snell__caustics_run(f->sv->ctx, c, f->fd, f->sc, f->s);
    if (st != SNELL_OK) return st;
    snell__receiver_view(&f->sc->view, c, &f->fd->receiver);
    if (c->frame_opaque) f->lit_opaque = c; /* the glass stage's dynamic environments show them lit */
    if (c->frame_plane) f->depth_drawn = 1;
    return SNELL_OK;
}

/* Nothing lit yet this frame (a build without the stage keeps no state). */
static void plan(snell__frame *f, void *state)
{
    snell__caustics *c = (snell__caustics *)state;
    (void)f;
    if (c) c->frame_plane = c->frame_opaque = 0;
}

static unsigned variant(const snell__frame *f, const void *state, const snell__object *o)
{
    const snell__caustics *c = (const snell__caustics *)state;
    (void)f, (void)o;
    return c && (c->frame_plane || c->frame_opaque) ? 1u : 0u;
}

static void destroy(snell_ctx *ctx, void *state)
{
    (void)ctx;
    snell__caustics_destroy((snell__caustics *)state);
}

const snell__stage snell__stage_caustics = {
    .name = "caustics",
    .state_size = SNELL_WITH_CAUSTICS ? sizeof(snell__caustics) : 0,
    .destroy = destroy,
    .validate = validate,
    .plan = plan,
    .wanted = wanted,
    .run = run,
    .kernel_variant = variant,
    .kernel = &snell__receiver_hook,
};
