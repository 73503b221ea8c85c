/* method_single.c — single-surface refraction (Unger 3.3), the baseline:
 * one pass, refraction and reflection at the front surface only. */
#include "render/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"

typedef struct single_state {
    snell__glass_program prog;
} single_state;

static snell_status single_create(snell_ctx *ctx, snell__output_kind out, void **state)
{
    single_state *s = (single_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    st = snell__glass_program_build(ctx, "single.frag", out, NULL, &s->prog);
    if (st != SNELL_OK) {
        snell__free(&ctx->alloc, s);
        return st;
    }
    *state = s;
    return SNELL_OK;
}

static void single_destroy(snell_ctx *ctx, void *state)
{
    single_state *s = (single_state *)state;
    if (!s) return;
    snell__glass_program_destroy(&s->prog);
    snell__free(&ctx->alloc, s);
}

static snell_status single_draw(snell_ctx *ctx, void *state, const snell__frame *f, snell_frame_stats *stats)
{
    single_state *s = (single_state *)state;
    (void)ctx;
    snell__glass_program_use(&s->prog, f);
    snell__cull_back_faces(f);
    snell__draw_mesh(f);
    glDisable(GL_CULL_FACE);
    stats->passes++;
    return SNELL_OK;
}

const snell__method snell__method_single = {SNELL_METHOD_SINGLE, "single", single_create, single_destroy, single_draw};
