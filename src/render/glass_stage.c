/* SPDX-License-Identifier: MIT */
/* glass_stage.c — the glass stage: every drawn glass object's method (AUTO
 * walks the registry), its mesh on the GPU, prepared resources, dynamic
 * environment and where it is shaded (forward or screen space), before any
 * kernel draws. Its choices it leaves in the objects (o->method,
 * o->method_state, o->screen_space, o->stage_bits) for the stages after it. */
#include "render/stages.h"
#include "render/glass_scale.h"
#include "frame/env.h"
#include "core/ctx.h"
#include "frame/glass_program.h"

typedef struct glass_state {
    unsigned warned[SNELL_MAX_GLASS]; /* warn_once keys */
} glass_state;

/* Logs a method warning once per (object slot, mesh version, method). */
static void warn_once(const snell__services *sv, glass_state *g, const snell__object *o, const snell_object_stats *st)
{
    unsigned key = o->mesh->version * 16u + (unsigned)st->method_used;
    if (g->warned[o->index] == key) return;
    g->warned[o->index] = key;
    snell__log(sv->ctx, SNELL_LOG_WARN, "glass %d: %s %s", o->index, snell_method_str(st->method_used), st->reason);
}

/* Where an object is shaded (snell_shading): AUTO compares its projected
 * pixels per front triangle with the threshold for this device and method. */
static void choose_shading(const snell__services *sv, const snell__view *v, snell__object *o, snell_object_stats *st)
{
    snell__object_project(v, o);
    st->pixels_per_triangle = o->pixels_per_triangle;
    float threshold = snell__screen_threshold(sv->device, o->method, o->analysis && o->analysis->convex);
    /* With MSAA, AUTO draws glass forward: the screen-space stage shades
     * whole pixels from a single-sample G-buffer, so its silhouettes would
     * stay aliased. */
    int screen = sv->shading == SNELL_SHADING_SCREEN || o->method->screen_space_only ||
                 (sv->shading == SNELL_SHADING_AUTO && !sv->samples && st->pixels_per_triangle < threshold);
    /* An offscreen target's depth buffer is the renderer's own, so the
     * G-buffer pass can write it; a host's framebuffer, or a multisampled
     * one, gets gl_FragDepth. */
    o->screen_space = !screen ? 0 : sv->target == SNELL_TARGET_OFFSCREEN && !sv->samples ? SNELL__SCREEN_SHARED_DEPTH
                                                                                      : SNELL__SCREEN_WRITES_DEPTH;
    o->gid = o->index + 1;
    st->screen_space = screen;
}

/* Everything an object needs before any glass is drawn: its method, its
 * mesh on the GPU, its prepared resources and dynamic environment (passes
 * of their own), and where it is shaded. */
static snell_status set_up(const snell__frame *f, glass_state *g, snell__object *o, snell_object_stats *st)
{
    const snell__services *sv = f->sv;
    const snell_frame_desc *fd = f->fd;
    snell_status s;
    int i, beyond, dynamic;
    o->stage_bits = 0;
    beyond = 0;
    for (i = 0; i < snell__stage_count; i++) {
        unsigned bits = snell__stages[i]->kernel_variant ? snell__stages[i]->kernel_variant(f, f->state[i], o) : 0;
        o->stage_bits |= bits << sv->programs->hooks.shift[i];
        if (snell__stages[i] == &snell__stage_layers && bits) beyond = 1; /* its exit rays march the scene layers */
    }
    dynamic = fd->opaque_count > 0 && !beyond;         /* sees them through a dynamic environment */
    o->env_paraboloid = snell__env_lookup_paraboloid(sv->env_lookup, dynamic);
    st->env_paraboloid = o->env_paraboloid;
    s = snell__scene_choose(sv->ctx, o, sv->method_state, sv->user, &o->method, &o->method_state, st);
    if (s != SNELL_OK) return s;
    if (st->warning) warn_once(sv, g, o, st);
    if ((s = snell__mesh_upload(o->mesh)) != SNELL_OK) return s;
    if ((s = snell__prepared_get(sv->ctx, sv->prepared, o->method, o->method_state, o, st)) != SNELL_OK) return s;
    if (o->method->vertex_array && o->prepared) o->vao = o->method->vertex_array(o->prepared);
    o->env_texture = fd->env->texture;
    if (fd->opaque_count > 0 && beyond)
        st->skipped |= SNELL_SKIP_DYNAMIC_ENV; /* its exit rays meet them in the scene layers */
    if (dynamic) {
        /* The glass sees the opaque objects through its dynamic environment,
         * lit as the caustics stage (run before this one) lit them. */
        s = snell__env_dynamic_update(sv->ctx, sv->dyn, sv->comp, o->index, fd->env, fd->opaque, fd->opaque_count,
                                      o->bsphere, o->bsphere[3], fd->dynamic_env_size,
                                      o->env_paraboloid ? sv->dp : NULL,
                                      sv->env_lookup == SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT,
                                      f->lit_opaque, &o->env_texture, st);
        if (s != SNELL_OK) return s;
    } else if (o->env_paraboloid) {
        if ((s = snell__env_paraboloid(sv->ctx, sv->dp, fd->env, &o->env_texture)) != SNELL_OK) return s;
    }
    o->scale = snell__glass_scale_of(o->method, sv->out, o);
    st->scale = o->scale;
    choose_shading(sv, &f->sc->view, o, st);
    return SNELL_OK;
}

static snell_status run(snell__frame *f, void *state)
{
    snell__scene *sc = f->sc;
    snell_status st = SNELL_OK;
    int i;
    for (i = 0; i < sc->drawn && st == SNELL_OK; i++) {
        int k = sc->order[i];
        st = set_up(f, (glass_state *)state, &sc->obj[k], &f->s->glass[k]);
    }
    return st;
}

const snell__stage snell__stage_glass = {
    .name = "glass",
    .state_size = sizeof(glass_state),
    .run = run,
};
