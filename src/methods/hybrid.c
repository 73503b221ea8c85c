/* SPDX-License-Identifier: MIT */
/* hybrid.c — the cubemap method where it trusts its answer, exact where it
 * doubts it, in one frame, without a read-back or a stencil (a host's
 * framebuffer may have none): the cubemap's pass (hybrid.frag) leaves the
 * doubted pixels' depth apart and exact's pass, depth-tested, shades only
 * those. Forward: the cubemap discards them, exact passes LESS. Screen
 * space: their depth goes to the near plane, exact's full-screen triangle
 * just behind it passes there only (no object test: its discard would turn
 * early depth tests off), and hybrid_depth.frag writes the G-buffer's depth
 * back. Design notes: docs/methods.md, "src/methods/hybrid.c". */
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"
#include "methods/cubemap.h"
#include "methods/exact.h"

#include <stddef.h>

/* The depth of exact's full-screen triangle in screen space: above the 0
 * the doubted pixels hold, below any surface drawn (two steps of a 24-bit
 * depth buffer). */
#define NEAR_STEP (2.0f / 16777215.0f)

extern const snell__method snell__method_cubemap;
extern const snell__method snell__method_exact;

/* Each part's prepared resource in one block: the cache allocates
 * prepared_size, a constant, so each part gets a fixed room, checked at
 * create() against the methods' sizes. */
#define PART_BYTES 256
typedef union part {
    unsigned char bytes[PART_BYTES];
    double align_d;
    void *align_p;
} part;
typedef struct hybrid_prepared {
    part cube, exact;
} hybrid_prepared;

typedef struct hybrid_state {
    void *cube, *exact;         /* the two methods' states */
    unsigned depth_prog;        /* hybrid_depth.frag, made on first use */
    snell__samplers depth_samplers;
    int depth_gid;
} hybrid_state;

static void hybrid_destroy(snell_ctx *ctx, void *state)
{
    hybrid_state *s = (hybrid_state *)state;
    if (!s) return;
    if (s->cube) snell__method_cubemap.destroy(ctx, s->cube);
    if (s->exact) snell__method_exact.destroy(ctx, s->exact);
    if (s->depth_prog) glDeleteProgram(s->depth_prog);
    snell__free(&ctx->alloc, s);
}

static snell_status hybrid_create(snell_ctx *ctx, snell__output_kind out, snell__program_cache *programs,
                                  void **state)
{
    hybrid_state *s;
    snell_status st;
    if (snell__method_cubemap.prepared_size > PART_BYTES || snell__method_exact.prepared_size > PART_BYTES)
        return snell__fail(ctx, SNELL_E_LIMIT, "hybrid: a part's prepared resource exceeds %d bytes", PART_BYTES);
    s = (hybrid_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    st = snell__method_cubemap.create(ctx, out, programs, &s->cube);
    if (st == SNELL_OK) st = snell__method_exact.create(ctx, out, programs, &s->exact);
    if (st != SNELL_OK) {
        hybrid_destroy(ctx, s);
        return st;
    }
    *state = s;
    return SNELL_OK;
}

/* The cubemap's preconditions. For AUTO it only runs: plain AUTO takes the
 * cheaper cubemap first, and AUTO by budget puts it on the ladder where its
 * rung is on the Pareto front (render/budget.c). */
static snell__fit hybrid_fit(const snell_mesh_analysis *an, const snell_glass_resolved *g, char *why, size_t n)
{
    snell__fit f = snell__method_cubemap.fit(an, g, why, n);
    if (f == SNELL__FIT_FAILS) return f;
    if (g->material.method != SNELL_METHOD_HYBRID) {
        snell__why(why, n, "costs the cubemap plus exact on the doubted pixels: AUTO by budget's, not plain AUTO's");
        return SNELL__FIT_RUNS;
    }
    return SNELL__FIT_ADEQUATE;
}

static void hybrid_key(const snell__object *o, int key[4])
{
    int k[4];
    snell__method_cubemap.key(o, key);     /* face size, encoding */
    snell__method_exact.key(o, k);         /* node format */
    key[2] = k[0];
    key[3] = 0;
}

/* An object whose prepared resource is one part's. */
static snell__object with_part(const snell__object *o, part *p)
{
    snell__object c = *o;
    c.prepared = p->bytes;
    return c;
}

static snell_status hybrid_prepare(snell_ctx *ctx, void *state, const snell__object *o, void *prepared,
                                   snell_object_stats *stats)
{
    hybrid_state *s = (hybrid_state *)state;
    hybrid_prepared *hp = (hybrid_prepared *)prepared;
    snell__object c = with_part(o, &hp->cube), e = with_part(o, &hp->exact);
    snell_status st = snell__method_cubemap.prepare(ctx, s->cube, &c, hp->cube.bytes, stats);
    if (st == SNELL_OK) st = snell__method_exact.prepare(ctx, s->exact, &e, hp->exact.bytes, stats);
    return st;
}

static void hybrid_release(void *prepared)
{
    hybrid_prepared *hp = (hybrid_prepared *)prepared;
    snell__method_cubemap.release(hp->cube.bytes);
    if (snell__method_exact.release) snell__method_exact.release(hp->exact.bytes);
}

/* Writes the object's depth back from the G-buffer over its rectangle. */
static snell_status restore_depth(snell_ctx *ctx, hybrid_state *s, const snell__view *v, const snell__object *o)
{
    snell_status st;
    if (!s->depth_prog) {
        st = snell__program_build(ctx, "screen.vert", "hybrid_depth.frag", NULL, &s->depth_prog);
        if (st == SNELL_OK) st = snell__samplers_assign(ctx, s->depth_prog, "hybrid_depth", &s->depth_samplers);
        if (st != SNELL_OK) return st;
        s->depth_gid = glGetUniformLocation(s->depth_prog, "u_gid");
    }
    glUseProgram(s->depth_prog);
    snell__samplers_bind_published(&s->depth_samplers, &v->textures);
    glUniform1i(s->depth_gid, o->gid);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glEnable(GL_SCISSOR_TEST);
    glScissor(o->scissor[0], o->scissor[1], o->scissor[2], o->scissor[3]);
    glBindVertexArray(0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_LESS);
    return SNELL_OK;
}

static snell_status hybrid_draw(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                snell_object_stats *stats)
{
    hybrid_state *s = (hybrid_state *)state;
    hybrid_prepared *hp = (hybrid_prepared *)o->prepared;
    const snell_hybrid_params *h = &o->glass->material.hybrid;
    float threshold = (float)h->doubt / 1000.0f;
    snell__object c = with_part(o, &hp->cube), e = with_part(o, &hp->exact);
    snell_glass_resolved cheap = *o->glass;
    snell_status st;
    cheap.material.cubemap.max_interfaces = h->max_interfaces;
    c.glass = &cheap;
    if (h->doubted == SNELL_HYBRID_DOUBTED_SHOW)
        return snell__cubemap_draw_doubt(ctx, s->cube, v, &c, stats, SNELL__CUBEMAP_DOUBT_SHOW, threshold);
    if (o->screen_space == SNELL__SCREEN_SHARED_DEPTH) {
        /* the cubemap on the G-buffer, writing its depth, the doubted
         * pixels' at 0 (the near plane); exact's full-screen triangle at a
         * depth just above 0 (GREATER) then passes there only; then the
         * G-buffer's depth written back */
        c.screen_space = SNELL__SCREEN_WRITES_DEPTH;
        glDepthFunc(GL_ALWAYS);
        st = snell__cubemap_draw_doubt(ctx, s->cube, v, &c, stats, SNELL__CUBEMAP_DOUBT_NEAR, threshold);
        glDepthFunc(GL_LESS);
        glDepthRangef(NEAR_STEP, NEAR_STEP);
        if (st == SNELL_OK) st = snell__exact_draw_ours(ctx, s->exact, v, &e, stats);
        glDepthRangef(0.0f, 1.0f);
        if (st == SNELL_OK) st = restore_depth(ctx, s, v, o);
        stats->passes++;
        return st;
    }
    /* Forward; a G-buffer with a depth buffer of its own is not in the
     * target's, so the object is drawn forward there too. */
    c.screen_space = e.screen_space = 0;
    st = snell__cubemap_draw_doubt(ctx, s->cube, v, &c, stats, SNELL__CUBEMAP_DOUBT_DISCARD, threshold);
    if (st == SNELL_OK) st = snell__method_exact.draw(ctx, s->exact, v, &e, stats);
    return st;
}

static const char *const g_doubted_names[] = {"default", "exact", "show"};

static const snell_param_info g_params[] = {
    {.name = "doubt",
     .offset = offsetof(snell_glass_material, hybrid.doubt),
     .help = "doubt threshold: the front surface or exit this far off the cubemap's surface, thousandths of its "
             "radius, is drawn by exact",
     .min = 1, .max = 1000, .def = SNELL_HYBRID_DEFAULT_DOUBT},
    {.name = "max_interfaces",
     .offset = offsetof(snell_glass_material, hybrid.max_interfaces),
     .help = "the cubemap pass's surfaces per path (its cubemap.max_interfaces); a path still inside after "
             "them is doubted",
     .min = 1, .max = SNELL_CUBEMAP_MAX_INTERFACES, .def = 4},
    {.name = "doubted",
     .offset = offsetof(snell_glass_material, hybrid.doubted),
     .help = "what the doubted pixels get: exact, or show (magenta, no exact pass: the mask)",
     .min = 0, .max = 2, .def = SNELL_HYBRID_DOUBTED_EXACT, .value_names = g_doubted_names},
};

static const snell_method_info g_info = {
    .method = SNELL_METHOD_HYBRID,
    .name = "hybrid",
    .summary = "the cubemap where it trusts its answer, exact (BVH traversal) on the pixels it doubts",
    .needs = "what the cubemap needs (a closed mesh, centre inside); AUTO by budget only (its rung)",
    .param_count = (int)(sizeof g_params / sizeof *g_params),
    .params = g_params,
    .default_sweep = "doubt=5,20,80",
};

/* AUTO by budget's rung (frame/method.h), measured as exact's
 * (bench/notes/budget_rungs.md); none on the open class: the cubemap's
 * preconditions fail there. */
static const snell_budget_rung g_rungs[] = {
    {SNELL_METHOD_HYBRID, NULL, 0, {3.99f, 11.10f, 14.69f, 0.0f}, {34.95f, 22.44f, 20.90f, 0.0f}, 1, NULL},
};

const snell__method snell__method_hybrid = {
    .info = &g_info,
    .needs_analysis = 1,
    .fit = hybrid_fit,
    .create = hybrid_create,
    .destroy = hybrid_destroy,
    .prepared_size = sizeof(hybrid_prepared),
    .key = hybrid_key,
    .prepare = hybrid_prepare,
    .release = hybrid_release,
    .draw = hybrid_draw,
    .software_screen_ppt = 1e9f,
    .rungs = g_rungs,
    .rung_count = (int)(sizeof g_rungs / sizeof *g_rungs),
};
