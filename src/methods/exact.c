/* SPDX-License-Identifier: MIT */
/* exact.c — exact refraction by ray traversal of the mesh's BVH in the
 * fragment shader (exact.frag): the MATCHED reference's model (ref_trace.c)
 * on the GPU. The BVH is the mesh's (mesh/bvh_gpu.h: the reference tracer's
 * SAH build flattened with escape indices, walked near-first with a short
 * stack, the default, or without any stack: the `walk` parameter), refitted
 * when the mesh deforms. Per frame one pass over the front faces; each
 * pixel's node visits are capped by a compile-time budget, past which it
 * takes the single-surface answer (counted in the fallback_pixels counter,
 * snell_object_stats.counters, on RGBA32F exit-direction renderers). */
#include "mesh/bvh_gpu.h"
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/device_cost.h"
#include "core/gl.h"
#include "methods/exact.h"
#include "core/glstate.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>


/* The walk (snell_exact_walk) defaults to the short stack: it visits the
 * nearer child first, so the closest hit shortens the ray sooner
 * (bench/notes/history.md "Exact"). The stackless walk needs no per-pixel
 * array and has no depth bound (drei's 60-entry stack is what mobile GPUs
 * choked on): the default on GPUs whose compiler keeps the stack in
 * registers (core/device_cost.h, snell__exact_walk_stack), where the stack
 * walk spills (Mali-G52; bench/notes/device_tuning.md). */

/* llvmpipe: per-pixel traversal costs so much more than the G-buffer pass
 * that full 4x4 blocks win at every density, as for the cubemap
 * (bench/BENCHMARKS.md, "Exact"). */
#define EXACT_SOFTWARE_SCREEN_PPT 1e9f

/* A node in depth-first order: a leaf's entries, or an interior node's
 * escape (the node after its subtree; its first child is the next node). */
/* The prepared resource: the mesh's BVH (mesh/bvh_gpu.h, a mesh-level
 * resource the caustics' photons walk too) in the material's node format. */
typedef struct exact_prepared {
    snell__gpu_bvh bvh;
} exact_prepared;

/* A program's own uniforms (over its cache slot's loc); its key: key: budget, q16, absorb, variant (snell__glass_variant), stack walk */
typedef struct exact_locs {
    int inv_model, node_count, tri_base, max_interfaces, eps, qlo, qstep, mark, cam_basis, cam_proj, pixel_to_ndc;
} exact_locs;
SNELL__PROGRAM_LOCS_FIT(exact_locs);

typedef struct exact_state {
    snell__output_kind out;
    snell__program_cache *programs; /* the renderer's */
    float *readback;           /* RGBA32F exit-direction renderers: the object's rectangle, to count fallbacks */
    size_t readback_size;      /* floats */
} exact_state;

static void exact_destroy(snell_ctx *ctx, void *state);

/* Bits of a program's model (exact.frag's terms). */
enum { TERM_FRESNEL_EXACT = 1, TERM_INNER = 2, TERM_REENTRY = 4 };

static snell_status get_prog(snell_ctx *ctx, exact_state *s, int budget, int q16, int absorb, int variant,
                             int stack, int dispersion, int terms, int ours, const snell__program_slot **out)
{
    const int key[8] = {budget, q16, absorb, variant, stack, dispersion, terms, ours};
    char def[288];
    int hit;
    snell__program_slot *p = snell__program_cache_get(s->programs, SNELL_METHOD_EXACT, key, 8, &hit);
    snell_status st;
    if (hit) {
        *out = p;
        return SNELL_OK;
    }
    snprintf(def, sizeof def,
             "#define SNELL_NODE_BUDGET %d\n#define SNELL_NODES_Q16 %d\n#define SNELL_ABSORB %d\n#define SNELL_STACK_WALK %d\n"
             "#define SNELL_DISPERSION %d\n#define SNELL_FRESNEL_EXACT %d\n#define SNELL_EXACT_INNER %d\n"
             "#define SNELL_EXACT_REENTRY %d\n%s",
             budget, q16, absorb, stack, dispersion, (terms & TERM_FRESNEL_EXACT) != 0, (terms & TERM_INNER) != 0,
             (terms & TERM_REENTRY) != 0, ours ? "#define SNELL_SCREEN_OURS 1\n" : "");
    st = snell__glass_program_build(ctx, "exact.frag", s->out, def, variant, &p->g);
    if (st != SNELL_OK) return st;
    exact_locs *loc = SNELL__PROGRAM_LOCS_OF(exact_locs, p);
    loc->inv_model = glGetUniformLocation(p->g.prog, "u_inv_model");
    loc->node_count = glGetUniformLocation(p->g.prog, "u_node_count");
    loc->tri_base = glGetUniformLocation(p->g.prog, "u_tri_base");
    loc->max_interfaces = glGetUniformLocation(p->g.prog, "u_max_interfaces");
    loc->eps = glGetUniformLocation(p->g.prog, "u_eps");
    loc->qlo = glGetUniformLocation(p->g.prog, "u_qlo");
    loc->qstep = glGetUniformLocation(p->g.prog, "u_qstep");
    loc->mark = glGetUniformLocation(p->g.prog, "u_fallback_mark");
    loc->cam_basis = glGetUniformLocation(p->g.prog, "u_cam_basis");
    loc->cam_proj = glGetUniformLocation(p->g.prog, "u_cam_proj");
    loc->pixel_to_ndc = glGetUniformLocation(p->g.prog, "u_pixel_to_ndc");
    *out = p;
    return SNELL_OK;
}

static snell_status exact_create(snell_ctx *ctx, snell__output_kind out, snell__program_cache *programs,
                                 void **state)
{
    exact_state *s = (exact_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    const snell__program_slot *p;
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    s->out = out;
    s->programs = programs;
    st = get_prog(ctx, s, SNELL_EXACT_DEFAULT_BUDGET, 0, 0, 0, snell__exact_walk_stack(ctx->cost, SNELL_EXACT_WALK_DEFAULT),
                  0, 0, 0, &p);
    if (st != SNELL_OK) {
        exact_destroy(ctx, s);
        return st;
    }
    *state = s;
    return SNELL_OK;
}

static void exact_destroy(snell_ctx *ctx, void *state)
{
    exact_state *s = (exact_state *)state;
    if (!s) return;
    snell__free(&ctx->alloc, s->readback);
    snell__free(&ctx->alloc, s);
}

/* Exact for any mesh, open ones included (the reference's model: a ray that
 * finds no surface ahead leaves in its direction). AUTO may take it only when
 * the material allows: it is the expensive ceiling. */
static snell__fit exact_fit(const snell_mesh_analysis *an, const snell_glass_resolved *g, char *why, size_t n)
{
    (void)an;
    if (g->material.method != SNELL_METHOD_EXACT && g->material.exact.auto_pick != SNELL_EXACT_AUTO_ALLOW) {
        snell__why(why, n, "is the expensive ceiling, not picked unless material.exact.auto_pick allows it");
        return SNELL__FIT_FAILS;
    }
    snell__why(why, n, "BVH traversal per pixel: the MATCHED model for any mesh, %d interfaces",
               g->material.exact.max_interfaces);
    return SNELL__FIT_ADEQUATE;
}

static void exact_key(const snell__object *o, int key[4])
{
    key[0] = o->glass->material.exact.node_format;
    key[1] = key[2] = key[3] = 0;
}

static snell_status exact_prepare(snell_ctx *ctx, void *state, const snell__object *o, void *prepared,
                                  snell_object_stats *stats)
{
    (void)state, (void)stats;
    return snell__mesh_gpu_bvh(ctx, o->mesh, o->glass->material.exact.node_format, &((exact_prepared *)prepared)->bvh);
}

/* Pixels of this object that took the fallback: the kernel marks them with
 * alpha -(index + 1) in the RGBA32F exit-direction target (other kernels and
 * the background write 1), read back over the object's rectangle right after
 * its draw, before a nearer object can cover them. */
static snell_status count_fallbacks(snell_ctx *ctx, exact_state *s, const snell__object *o, int *count)
{
    const int *rc = o->scissor;
    size_t n = (size_t)rc[2] * (size_t)rc[3] * 4, i;
    snell__pixel_store pack;
    float mark = -(float)(o->index + 1);
    *count = 0;
    if (!n) return SNELL_OK;
    if (n > s->readback_size) { /* grows to the largest rectangle once, then never again */
        float *b = (float *)snell__calloc(&ctx->alloc, n, sizeof(float));
        if (!b) return snell__fail(ctx, SNELL_E_NOMEM, "exact: out of memory counting fallbacks");
        snell__free(&ctx->alloc, s->readback);
        s->readback = b;
        s->readback_size = n;
    }
    snell__pixel_pack_begin(&pack, 4);
    glReadPixels(rc[0], rc[1], rc[2], rc[3], GL_RGBA, GL_FLOAT, s->readback);
    snell__pixel_pack_end(&pack);
    for (i = 3; i < n; i += 4) *count += s->readback[i] == mark;
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "exact: reading fallbacks failed");
}

/* The model's terms a material asks for (resolved parameters). */
static int exact_terms(const snell_exact_params *e)
{
    return (e->fresnel == SNELL_FRESNEL_EXACT ? TERM_FRESNEL_EXACT : 0) |
           (e->inner_fresnel == SNELL_INNER_FRESNEL_ON ? TERM_INNER : 0) |
           (e->reentry == SNELL_EXACT_REENTRY_ON ? TERM_REENTRY : 0);
}

/* ours: in screen space, every pixel the depth test passes is the object's
 * (SNELL_SCREEN_OURS in exact.frag: the hybrid, methods/exact.h). */
static snell_status draw_with(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                              snell_object_stats *stats, int ours)
{
    exact_state *s = (exact_state *)state;
    const snell_exact_params *e = &o->glass->material.exact;
    const snell__gpu_bvh *ep = &((const exact_prepared *)o->prepared)->bvh;
    const snell__program_slot *p;
    /* Dispersion: always three traces (SNELL_DISPERSION 1), whatever the
     * material's model: exact is the accuracy ceiling, and one path would
     * give red and blue estimated exits where the traversal finds the true ones. */
    snell_status st = get_prog(ctx, s, e->node_budget, ep->q16, o->glass->absorbs,
                                snell__glass_variant(o), snell__exact_walk_stack(ctx->cost, e->walk),
                                o->glass->disperses ? 1 : 0, exact_terms(e), ours, &p);
    if (st != SNELL_OK) return st;
    snell__glass_program_use(&p->g, v, o);
    snell__glass_program_bind(&p->g, "u_bvh", GL_TEXTURE_2D, ep->texture, 0);
    const exact_locs *loc = SNELL__PROGRAM_LOCS_OF(const exact_locs, p);
    glUniformMatrix4fv(loc->inv_model, 1, GL_FALSE, (const GLfloat *)o->inv_model);
    glUniform1i(loc->node_count, ep->node_count);
    glUniform1i(loc->tri_base, ep->tri_base);
    glUniform1i(loc->max_interfaces, e->max_interfaces);
    /* Secondary rays skip the triangle they start on, as the reference's do;
     * this minimum distance (world units, 1e-5 of the bounding radius; the
     * reference's is 1e-9 of its extent, in double) keeps them off the
     * neighbours of an edge they start on, within float rounding. */
    glUniform1f(loc->eps, SNELL__BVH_EPS(o->bsphere[3]));
    glUniform3fv(loc->qlo, 1, ep->qlo);
    glUniform3fv(loc->qstep, 1, ep->qstep);
    glUniform1f(loc->mark, -(float)(o->index + 1));
    {
        /* the eye rays (exact.frag main): view -> world rotation, projection terms */
        float basis[9];
        int i, j;
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) basis[3 * i + j] = v->view[j][i];
        glUniformMatrix3fv(loc->cam_basis, 1, GL_FALSE, basis);
        if (v->view_axis[3] > 0.5f)
            glUniform4f(loc->cam_proj, v->proj[0][0], v->proj[1][1], -v->proj[3][0], -v->proj[3][1]);
        else
            glUniform4f(loc->cam_proj, v->proj[0][0], v->proj[1][1], v->proj[2][0], v->proj[2][1]);
        glUniform2f(loc->pixel_to_ndc, 2.0f / (float)v->width, 2.0f / (float)v->height);
    }
    snell__draw_surface(o, stats);
    stats->passes++;
    if (v->out == SNELL__OUT_DIR_FLOAT) return count_fallbacks(ctx, s, o, &stats->counters[0]);
    return SNELL_OK;
}

static snell_status exact_draw(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                               snell_object_stats *stats)
{
    return draw_with(ctx, state, v, o, stats, 0);
}

#if SNELL__BUILT_hybrid
snell_status snell__exact_draw_ours(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                    snell_object_stats *stats)
{
    return draw_with(ctx, state, v, o, stats, 1);
}
#endif

static const char *const g_nodes_names[] = {"default", "f32", "q16"};
static const char *const g_auto_names[] = {"default", "never", "allow"};
static const char *const g_walk_names[] = {"default", "stackless", "stack"};
static const char *const g_reentry_names[] = {"default", "off", "on"};

static const snell_param_info g_params[] = {
    {.name = "max_interfaces",
     .offset = offsetof(snell_glass_material, exact.max_interfaces),
     .help = "surfaces processed per path (1 = single surface with the exact path length; more = exit and TIR bounces), the MATCHED reference's cap",
     .min = 1, .max = SNELL_EXACT_MAX_INTERFACES, .def = SNELL_EXACT_DEFAULT_INTERFACES},
    {.name = "node_budget",
     .offset = offsetof(snell_glass_material, exact.node_budget),
     .help = "BVH nodes a pixel may visit over all its rays; past it the single-surface answer",
     .min = SNELL_EXACT_MIN_BUDGET, .max = SNELL_EXACT_MAX_BUDGET, .def = SNELL_EXACT_DEFAULT_BUDGET},
    {.name = "node_format",
     .offset = offsetof(snell_glass_material, exact.node_format),
     .help = "node bounds: f32 (RGBA32F, 2 texels) or q16 (16-bit quantised, rounded outward, 1 RGBA32UI texel)",
     .min = 0, .max = 2, .def = SNELL_EXACT_NODES_F32, .value_names = g_nodes_names},
    {.name = "auto_pick",
     .offset = offsetof(snell_glass_material, exact.auto_pick),
     .help = "whether AUTO may pick it (where no cheaper method is adequate): never or allow",
     .min = 0, .max = 2, .def = SNELL_EXACT_AUTO_NEVER, .value_names = g_auto_names},
    {.name = "walk",
     .offset = offsetof(snell_glass_material, exact.walk),
     .help = "traversal: stack (near-first, a 32-entry stack a pixel; deeper trees fall back) or stackless (escape indices: no stack, no depth bound, for GPUs where the stack spills); default: stack, stackless on GPUs whose compiler keeps the stack in registers (Mali-G52)",
     .min = 0, .max = 2, .def = SNELL_EXACT_WALK_DEFAULT, .value_names = g_walk_names},
    {.name = "fresnel",
     .offset = offsetof(snell_glass_material, exact.fresnel),
     .help = "reflectance at the interfaces: schlick (the MATCHED model) or exact (unpolarised, as FULL)",
     .min = 0, .max = 2, .def = SNELL_FRESNEL_SCHLICK, .value_names = snell__fresnel_names},
    {.name = "inner_fresnel",
     .offset = offsetof(snell_glass_material, exact.inner_fresnel),
     .help = "the first exit transmits 1 - F and its internal reflection is followed to its own exit: auto (off), off, on",
     .min = 0, .max = 2, .def = SNELL_INNER_FRESNEL_OFF, .value_names = snell__inner_fresnel_names},
    {.name = "reentry",
     .offset = offsetof(snell_glass_material, exact.reentry),
     .help = "light that left the object and meets it again enters it again (concave meshes): off (the MATCHED model) or on",
     .min = 0, .max = 2, .def = SNELL_EXACT_REENTRY_OFF, .value_names = g_reentry_names},
};


static const snell_counter_info g_counters[] = {
    /* Counted only by SNELL_OUTPUT_EXIT_DIRECTION renderers with an RGBA32F
     * target (the pixel's alpha marks it, read back once per object and
     * frame; GLES 3.0's occlusion queries say only whether any sample
     * passed, and it has no atomic counters); -1 where not counted (colour
     * output, the packed RGBA8 target). */
    {"fallback_pixels", "pixels that ran out of exact.budget and took the single-surface answer (exit-direction "
                        "output on an RGBA32F target only)"},
};

/* It is the MATCHED model itself: its error there is float rounding. */
static const snell_method_info g_info = {
    .method = SNELL_METHOD_EXACT,
    .name = "exact",
    .summary = "exact: the mesh's BVH traversed per pixel (watertight triangles, TIR), the MATCHED reference on the GPU",
    .needs = "nothing (any mesh); AUTO only where material.exact.auto_pick allows",
    .param_count = (int)(sizeof g_params / sizeof *g_params),
    .params = g_params,
    .counter_count = (int)(sizeof g_counters / sizeof *g_counters),
    .counters = g_counters,
    .ref_interfaces = 0,
    .ref_chord_absorption = 0,
    .default_sweep = "",
};

/* AUTO by budget's rungs (frame/method.h): method, parameter, value; frame
 * time over single's and glass PSNR vs FULL for a convex, a bunny-like, a
 * torus-like and an open mesh; resolution scale; further parameters
 * (bench/notes/budget_rungs.md). The last two add the FULL model's terms:
 * re-entry first, it is most of the gain on concave meshes; then all three
 * at the FULL reference's cap. */
static const snell_budget_rung g_rungs[] = {
    {SNELL_METHOD_EXACT, "max_interfaces", 2, {14.50f, 5.68f, 11.78f, 5.30f}, {32.30f, 18.17f, 20.65f, 18.80f}, 1,
     NULL},
    {SNELL_METHOD_EXACT, NULL, 0, {14.74f, 10.16f, 16.00f, 8.19f}, {32.31f, 24.95f, 24.48f, 22.71f}, 1, NULL},
    {SNELL_METHOD_EXACT, "max_interfaces", 8, {16.12f, 13.13f, 23.28f, 7.09f}, {32.67f, 27.08f, 27.88f, 25.41f}, 1,
     "reentry=on:fresnel=exact:node_format=q16"},
    {SNELL_METHOD_EXACT, "max_interfaces", 10, {28.32f, 27.00f, 38.20f, 14.93f}, {42.69f, 29.98f, 34.00f, 28.16f}, 1,
     "fresnel=exact:inner_fresnel=on:reentry=on:node_format=q16"},
};

const snell__method snell__method_exact = {
    .info = &g_info,
    .fit = exact_fit,
    .create = exact_create,
    .destroy = exact_destroy,
    .prepared_size = sizeof(exact_prepared),
    .key = exact_key,
    .prepare = exact_prepare,
    .draw = exact_draw,
    .software_screen_ppt = EXACT_SOFTWARE_SCREEN_PPT,
    .rungs = g_rungs,
    .rung_count = (int)(sizeof g_rungs / sizeof *g_rungs),
};
