/* SPDX-License-Identifier: MIT */
/* kernels_stage.c — the kernels: the objects shaded in screen space first
 * (they cover disjoint pixels of the G-buffer), then the forward ones back
 * to front (Franke), each depth-tested against all of those; an object at a
 * resolution scale through render/glass_scale.c. */
#include "render/stages.h"
#include "render/glass_scale.h"
#include "core/gl.h"

/* The object's method into the bound target, at the view's grid. */
static snell_status draw_method(void *user, const snell__view *v, const snell__object *o, snell_object_stats *st)
{
    const snell__services *sv = (const snell__services *)user;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    return o->method->draw(sv->ctx, o->method_state, v, o, st);
}

static snell_status draw_glass(const snell__frame *f, snell__glass_scale *gs, snell__object *o,
                               snell_object_stats *stats)
{
    void *sv = (void *)f->sv;
    if (o->scale > 1.0f) return snell__glass_scale_draw(f->sv->ctx, gs, &f->sc->view, o, stats, draw_method, sv);
    return draw_method(sv, &f->sc->view, o, &stats[o->index]);
}

static snell_status run(snell__frame *f, void *state)
{
    snell__scene *sc = f->sc;
    snell_status st = SNELL_OK;
    int pass, i;
    for (pass = 0; pass < 2; pass++)
        for (i = 0; i < sc->drawn && st == SNELL_OK; i++) {
            snell__object *o = &sc->obj[sc->order[i]];
            if ((o->screen_space != 0) == (pass == 0)) st = draw_glass(f, (snell__glass_scale *)state, o, f->s->glass);
        }
    return st;
}

static void destroy(snell_ctx *ctx, void *state)
{
    (void)ctx;
    snell__glass_scale_destroy((snell__glass_scale *)state);
}

const snell__stage snell__stage_kernels = {
    .name = "kernels",
    .state_size = sizeof(snell__glass_scale),
    .destroy = destroy,
    .run = run,
};
