/* SPDX-License-Identifier: MIT */
/* caustics_stage.c — the caustics stage: the receiver plane lit by the
 * light, directly where no object shadows it and through the glass
 * (render/caustics.c), drawn like an opaque object before the glass, and
 * the opaque objects redrawn lit. Only in colour output. Its kernel hook
 * (SNELL_RECEIVER): every kernel's exit and reflected rays meet the lit
 * plane before the environment, and see the opaque objects lit. */
#include "render/stages.h"
#include "frame/glass_program.h"


static snell_status validate(const snell_renderer *r, const snell_frame_desc *fd)
{
    return snell__caustics_validate(r->ctx, fd);
}

static int wanted(const snell__frame *f, const void *state)
{
    (void)state;
    if (!snell__caustics_wanted(f->fd, f->s->caustics_reason, sizeof f->s->caustics_reason)) return 0;
    if (f->r->out != SNELL__OUT_COLOR) {
        snell__why(f->s->caustics_reason, sizeof f->s->caustics_reason, "not in exit-direction output");
        return 0;
    }
    return 1;
}

static snell_status run(snell__frame *f, void *state)
{
    snell__caustics *c = (snell__caustics *)state;
    snell_status st = snell__caustics_run(f->r->ctx, c, f->fd, f->sc, f->s);
    if (st == SNELL_OK) snell__receiver_view(&f->sc->view, c, &f->fd->receiver);
    return st;
}

static unsigned variant(const snell__frame *f, const void *state, const snell__object *o)
{
    (void)state, (void)o;
    return f->sc->view.receiver_map || f->sc->view.lit_opaque ? SNELL__GLASS_RECEIVER : 0;
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
    .wanted = wanted,
    .run = run,
    .kernel_variant = variant,
    .kernel = &snell__receiver_hook,
};
