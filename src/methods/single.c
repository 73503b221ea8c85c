/* single.c — single-surface refraction (Unger 3.3), the baseline: one pass,
 * refraction and reflection at the front surface only; and the thin-wall
 * (slab) model, which is exact for a thin-walled material whatever method
 * is asked for. Needs no analysis and prepares nothing. */
#include "methods/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"

typedef struct single_state {
    snell__glass_program solid, thin;
    int u_thickness;
} single_state;

static snell_status single_create(snell_ctx *ctx, snell__output_kind out, void **state)
{
    single_state *s = (single_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    st = snell__glass_program_build(ctx, "single.frag", out, NULL, &s->solid);
    if (st == SNELL_OK) st = snell__glass_program_build(ctx, "single.frag", out, "#define SNELL_THIN 1\n", &s->thin);
    if (st != SNELL_OK) {
        snell__glass_program_destroy(&s->solid);
        snell__free(&ctx->alloc, s);
        return st;
    }
    s->u_thickness = glGetUniformLocation(s->thin.prog, "u_thickness");
    *state = s;
    return SNELL_OK;
}

static void single_destroy(snell_ctx *ctx, void *state)
{
    single_state *s = (single_state *)state;
    if (!s) return;
    snell__glass_program_destroy(&s->solid);
    snell__glass_program_destroy(&s->thin);
    snell__free(&ctx->alloc, s);
}

/* Exact for a thin wall (no interior); for a solid it misses the exit surface. */
static snell__fit single_fit(const snell_mesh_analysis *an, const snell_glass_resolved *g, char *why, size_t n)
{
    (void)an;
    if (g->material.thickness > 0.0f) {
        snell__why(why, n, "thin wall (thickness %g): the slab model is exact", g->material.thickness);
        return SNELL__FIT_ADEQUATE;
    }
    snell__why(why, n, "front surface only: the exit surface is not found");
    return SNELL__FIT_RUNS;
}

static snell_status single_draw(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                snell_object_stats *stats)
{
    single_state *s = (single_state *)state;
    int thin = o->glass->material.thickness > 0.0f;
    (void)ctx;
    snell__glass_program_use(thin ? &s->thin : &s->solid, v, o);
    if (thin) glUniform1f(s->u_thickness, o->glass->material.thickness);
    /* A thin wall is seen from both sides: its back faces are walls too. */
    else snell__cull_back_faces(o, stats);
    snell__draw_object(o);
    stats->passes++;
    return SNELL_OK;
}

static const snell_method_info g_info = {
    SNELL_METHOD_SINGLE, "single", "refraction at the front surface only (Unger 3.3); thin walls as slabs",
    "nothing", 1, 0, NULL};

const snell__method snell__method_single = {&g_info, NULL, 0, single_fit, single_create, single_destroy,
                                            0, NULL, NULL, NULL, single_draw};
