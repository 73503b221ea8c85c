/* SPDX-License-Identifier: MIT */
/* water_stage.c — the water stage: the water surface and its container,
 * opaque to what follows (glass behind them is depth-tested away, glass in
 * front is drawn over them). The glass kernels drawn after see the water
 * along their exit rays (kernel hook SNELL_WATER, common/water.glsl); the
 * water sees the glass and opaque objects in it through the scene layers. */
#include "render/stages.h"
#include "water/water_draw.h"
#include "frame/env.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "frame/glass_program.h"

static snell_status validate(const snell__services *sv, const snell_frame_desc *fd)
{
    snell_ctx *ctx = sv->ctx;
    if (fd->water && !SNELL_WITH_WATER)
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "frame has water: built without SNELL_WITH_WATER");
    if (fd->water && fd->water->ctx != ctx)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "the water belongs to another context (or to none)");
    return SNELL_OK;
}

static int wanted(const snell__frame *f, const void *state)
{
    (void)state;
    return f->fd->water != NULL;
}

#if SNELL_WITH_WATER

/* The stage's state: its programs and this frame's water, which its kernel hook reads. */
typedef struct water_stage {
    snell__water_programs programs;
    const snell_water *water;       /* the frame's, NULL none */
} water_stage;

static void plan(snell__frame *f, void *state) { ((water_stage *)state)->water = f->fd->water; }

static snell_status run(snell__frame *f, void *state)
{
    snell__water_programs *wp = &((water_stage *)state)->programs;
    const snell__services *sv = f->sv;
    const snell_frame_desc *fd = f->fd;
    snell_status st = SNELL_OK;
    /* Without layers (no glass), opaque objects in the water are searched
     * for in a copy of what the opaque pass drew: an offscreen single-sample
     * colour target (a host's framebuffer or a multisampled one cannot be
     * copied with its depth format known; exit directions need no colour).
     * Cheaper than peeling them into layers for the water alone, for the
     * same error (bench/notes). */
    int layers = f->sc->view.layers.active, i;
    int objects = !layers && fd->opaque_count > 0 && sv->target == SNELL_TARGET_OFFSCREEN && !sv->samples &&
                  sv->out == SNELL__OUT_COLOR;
    unsigned env_tex = fd->env->texture;
    int paraboloid = snell__env_lookup_paraboloid(sv->env_lookup, 0); /* the water sees the static environment */
    if (objects) {
        st = snell__water_copy_scene(sv->ctx, wp, sv->fbo, sv->width, sv->height);
        glBindFramebuffer(GL_FRAMEBUFFER, sv->fbo);
    }
    if (st == SNELL_OK && paraboloid) st = snell__env_paraboloid(sv->ctx, sv->dp, fd->env, &env_tex);
    if (st == SNELL_OK)
        st = snell__water_draw(sv->ctx, wp, sv->out, fd->water, &f->sc->view, env_tex, paraboloid, fd->opaque,
                               objects ? fd->opaque_count : 0, layers, f->s);
    if (st == SNELL_OK) snell__water_publish(fd->water, &f->sc->view.textures);
    f->s->water_objects = objects || layers; /* layers: at least one glass object drawn */
    f->s->water_layers = layers;
    f->depth_drawn = 1;
    for (i = 0; i < f->sc->drawn; i++) f->s->glass[f->sc->order[i]].sees_water = 1;
    return st;
}

/* Every kernel's exit rays meet the water (heights as the simulation keeps them). */
#define WATER_BIT 1u  /* the frame has water, heights in R32F (common/water.glsl) */
#define WATER_UINT 2u /* ... in the GPU simulation's RG32UI state */
static unsigned variant(const snell__frame *f, const void *state, const snell__object *o)
{
    (void)state, (void)o;
    if (!f->fd->water) return 0;
    return f->fd->water->d.sim == SNELL_WATER_SIM_GPU ? WATER_BIT | WATER_UINT : WATER_BIT;
}

static const char *hook_defines(unsigned bits)
{
    return bits & WATER_UINT ? "#define SNELL_WATER 1\n#define SNELL_WATER_STATE_UINT 1\n"
                                          : "#define SNELL_WATER 1\n";
}

static void hook_uniforms(const snell__glass_program *g, const int *locs, const void *state, const snell__view *v,
                          const snell__object *o)
{
    (void)g, (void)v, (void)o;
    snell__water_set_uniforms(locs, ((const water_stage *)state)->water);
}

static const snell__kernel_hook g_hook = {
    .variant_bits = 2,
    .defines = hook_defines,
    .uniform_names = snell__water_uniform_names,
    .uniform_count = SNELL__WATER_UNIFORMS,
    .uniforms = hook_uniforms,
};

static void destroy(snell_ctx *ctx, void *state)
{
    (void)ctx;
    snell__water_programs_destroy(&((water_stage *)state)->programs);
}

const snell__stage snell__stage_water = {
    .name = "water",
    .state_size = sizeof(water_stage),
    .destroy = destroy,
    .validate = validate,
    .plan = plan,
    .wanted = wanted,
    .run = run,
    .kernel_variant = variant,
    .kernel = &g_hook,
};

#else

/* Built without the water: a frame with water is refused, so the stage never runs. */
const snell__stage snell__stage_water = {
    .name = "water",
    .validate = validate,
    .wanted = wanted,
};

#endif
