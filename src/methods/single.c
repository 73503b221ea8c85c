/* SPDX-License-Identifier: MIT */
/* single.c — single-surface refraction (Unger 3.3), the baseline: one pass,
 * refraction and reflection at the front surface only; and the thin-wall
 * (slab) model, which is exact for a thin-walled material whatever method
 * is asked for. Needs no analysis and prepares nothing. */
#include <stdio.h>
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"

/* Program variants: [snell__glass_variant: shading, scene layers][thin wall][absorption][dispersion variant,
 * snell__dispersion_variant: a thin wall has none]; the forward solid
 * one without absorption (the default) is built with the method, the others
 * on first use. */
typedef struct single_state {
    snell__output_kind out;
    snell__glass_program prog[SNELL__GLASS_VARIANTS][2][2][3];
    int u_thickness[SNELL__GLASS_VARIANTS][2][2][3];
} single_state;

static void single_destroy(snell_ctx *ctx, void *state);

static snell_status get_prog(snell_ctx *ctx, single_state *s, int screen, int thin, int absorb, int dispersion,
                             const snell__glass_program **out)
{
    snell__glass_program *p = &s->prog[screen][thin][absorb][dispersion];
    if (!p->prog) {
        char defines[128];
        snell_status st;
        snprintf(defines, sizeof defines, "%s%s#define SNELL_DISPERSION %d\n", thin ? "#define SNELL_THIN 1\n" : "",
                 absorb ? "#define SNELL_ABSORB 1\n" : "", dispersion);
        st = snell__glass_program_build(ctx, "single.frag", s->out, defines, screen, p);
        if (st != SNELL_OK) return st;
        s->u_thickness[screen][thin][absorb][dispersion] = glGetUniformLocation(p->prog, "u_thickness");
    }
    *out = p;
    return SNELL_OK;
}

static snell_status single_create(snell_ctx *ctx, snell__output_kind out, void **state)
{
    single_state *s = (single_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    const snell__glass_program *p;
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    s->out = out;
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
    single_state *s = (single_state *)state;
    int i;
    if (!s) return;
    for (i = 0; i < 12 * SNELL__GLASS_VARIANTS; i++)
        snell__glass_program_destroy(&s->prog[i / 12][(i / 6) % 2][(i / 3) % 2][i % 3]);
    snell__free(&ctx->alloc, s);
}

/* A thin wall is one slab: exact for a sheet; a closed thin-walled mesh's far
 * wall is not crossed (the FULL reference and the caustics' light cross
 * every wall; README "Methods"). For a solid it misses the exit surface. */
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
    const snell__glass_program *p;
    snell_status st = get_prog(ctx, s, screen, thin, absorb, snell__dispersion_variant(o->glass), &p);
    if (st != SNELL_OK) return st;
    snell__glass_program_use(p, v, o);
    if (thin) glUniform1f(s->u_thickness[screen][thin][absorb][0], o->glass->material.thickness);
    snell__draw_surface(o, stats);
    stats->passes++;
    return SNELL_OK;
}

static const snell_method_info g_info = {
    SNELL_METHOD_SINGLE, "single", "refraction at the front surface only (Unger 3.3); thin walls as slabs",
    "nothing", 1, 0, NULL, 0, NULL, 1, 1, ""};

/* llvmpipe (BENCHMARKS.md): screen space is the cheaper below about 5.5
 * estimated pixels a front triangle, forward above. */
const snell__method snell__method_single = {
    .info = &g_info,
    .fit = single_fit,
    .create = single_create,
    .destroy = single_destroy,
    .draw = single_draw,
    .software_screen_ppt = 8.0f,
};
