/* SPDX-License-Identifier: MIT */
/* single.c — single-surface refraction (Unger 3.3), the baseline: one pass,
 * refraction and reflection at the front surface only; and the thin-wall
 * (slab) model, which is exact for a thin-walled material whatever method
 * is asked for. Needs no analysis and prepares nothing. */
#include <stdio.h>
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"

/* Programs are keyed by variant (snell__glass_variant), thin wall,
 * absorption and dispersion variant (snell__dispersion_variant: a thin wall
 * has none); the forward solid one without absorption (the default) is
 * built with the method, the others on first use. loc[0]: u_thickness. */
typedef struct single_state {
    snell__output_kind out;
    snell__program_cache *programs;
} single_state;

static void single_destroy(snell_ctx *ctx, void *state);

static snell_status get_prog(snell_ctx *ctx, single_state *s, int screen, int thin, int absorb, int dispersion,
                             const snell__program_slot **out)
{
    const int key[4] = {screen, thin, absorb, dispersion};
    int hit;
    snell__program_slot *p = snell__program_cache_get(s->programs, SNELL_METHOD_SINGLE, key, 4, &hit);
    if (!hit) {
        char defines[128];
        snell_status st;
        snprintf(defines, sizeof defines, "%s%s#define SNELL_DISPERSION %d\n", thin ? "#define SNELL_THIN 1\n" : "",
                 absorb ? "#define SNELL_ABSORB 1\n" : "", dispersion);
        st = snell__glass_program_build(ctx, "single.frag", s->out, defines, screen, &p->g);
        if (st != SNELL_OK) return st;
        p->loc[0] = glGetUniformLocation(p->g.prog, "u_thickness");
    }
    *out = p;
    return SNELL_OK;
}

static snell_status single_create(snell_ctx *ctx, snell__output_kind out, snell__program_cache *programs,
                                  void **state)
{
    single_state *s = (single_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    const snell__program_slot *p;
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    s->out = out;
    s->programs = programs;
    st = get_prog(ctx, s, 0, 0, 0, 0, &p);
    if (st != SNELL_OK) {
        single_destroy(ctx, s);
        return st;
    }
    *state = s;
    return SNELL_OK;
}

static void single_destroy(snell_ctx *ctx, void *state)
{
    if (state) snell__free(&ctx->alloc, state);
}

/* A thin wall is one slab: exact for a sheet; a closed thin-walled mesh's far
 * wall is not crossed (the FULL reference and the caustics' light cross
 * every wall; docs/methods.md). For a solid it misses the exit surface. */
static snell__fit single_fit(const snell_mesh_analysis *an, const snell_glass_resolved *g, char *why, size_t n)
{
    (void)an;
    if (g->material.thickness > 0.0f) {
        snell__why(why, n, "thin wall (thickness %g): one slab, exact for a sheet (a closed one's far wall is not crossed)", g->material.thickness);
        return SNELL__FIT_ADEQUATE;
    }
    snell__why(why, n, "front surface only: the exit surface is not found");
    return SNELL__FIT_RUNS;
}

static snell_status single_draw(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                snell_object_stats *stats)
{
    single_state *s = (single_state *)state;
    int thin = o->glass->material.thickness > 0.0f, screen = snell__glass_variant(o), absorb = o->glass->absorbs;
    const snell__program_slot *p;
    snell_status st = get_prog(ctx, s, screen, thin, absorb, snell__dispersion_variant(o->glass), &p);
    if (st != SNELL_OK) return st;
    snell__glass_program_use(&p->g, v, o);
    if (thin) glUniform1f(p->loc[0], o->glass->material.thickness);
    snell__draw_surface(o, stats);
    stats->passes++;
    return SNELL_OK;
}

static const snell_method_info g_info = {
    .method = SNELL_METHOD_SINGLE,
    .name = "single",
    .summary = "refraction at the front surface only (Unger 3.3); thin walls as slabs",
    .needs = "nothing",
    .ref_interfaces = 1,
    .ref_chord_absorption = 1,
    .default_sweep = "",
};

/* llvmpipe (BENCHMARKS.md): screen space is the cheaper below about 5.5
 * estimated pixels a front triangle, forward above. */
/* AUTO by budget's rungs (frame/method.h): method, parameter, value; frame
 * time over single's and glass PSNR vs FULL for a convex, a bunny-like, a
 * torus-like and an open mesh; resolution scale (bench/notes/budget_rungs.md). */
static const snell_budget_rung g_rungs[] = {
    {SNELL_METHOD_SINGLE, NULL, 0, {1.00f, 1.00f, 1.00f, 1.00f}, {9.89f, 11.60f, 11.23f, 12.62f}, 1, NULL},
};

const snell__method snell__method_single = {
    .info = &g_info,
    .fit = single_fit,
    .create = single_create,
    .destroy = single_destroy,
    .draw = single_draw,
    .software_screen_ppt = 8.0f,
    .rungs = g_rungs,
    .rung_count = (int)(sizeof g_rungs / sizeof *g_rungs),
};
