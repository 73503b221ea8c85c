/* SPDX-License-Identifier: MIT */
/* oliveira.c — two-sided refraction by a conservative image-space search
 * (Oliveira and Brauwers 2007, the seed's 3.4.2): refract at the front
 * surface, walk the refracted ray in linear then binary steps against the
 * frame's back-face pass (and, after a total internal reflection, against the
 * G-buffer's front surface) until it leaves, refract out with the normal
 * found there (oliveira.frag). It prepares nothing: a deforming mesh costs
 * what a rigid one does. It always shades in screen space, because a
 * reflected ray leaves through the front surface, which only the G-buffer
 * holds for pixels other than its own. */
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define DEFAULT_LINEAR_STEPS 8
#define DEFAULT_ITERATIONS 6

/* fit(): as Wyman's (wyman.c): a solid's back faces, few enough surfaces
 * along a ray that the farthest back face is where light leaves. */
#define OLIVEIRA_MAX_HIDDEN 0.6f

/* A program's own uniforms (over its cache slot's loc); its key: key: get_prog's arguments in order */
typedef struct oli_locs {
    int max_interfaces, back_band;
} oli_locs;
SNELL__PROGRAM_LOCS_FIT(oli_locs);

typedef struct oliveira_state {
    snell__output_kind out;
    snell__program_cache *programs; /* the renderer's */
} oliveira_state;

static void oliveira_destroy(snell_ctx *ctx, void *state);

/* The program of these compile-time constants: cached, else built into the
 * least recently used slot. */
static snell_status get_prog(snell_ctx *ctx, oliveira_state *s, int linear, int iterations, int screen, int absorb,
                             int fresnel_exact, int inner, int dispersion, const snell__program_slot **out)
{
    const int key[7] = {linear, iterations, screen, absorb, fresnel_exact, inner, dispersion};
    char def[256];
    int hit;
    snell__program_slot *p = snell__program_cache_get(s->programs, SNELL_METHOD_OLIVEIRA, key, 7, &hit);
    snell_status st;
    if (hit) {
        *out = p;
        return SNELL_OK;
    }
    snprintf(def, sizeof def,
             "#define SNELL_LINEAR_STEPS %d\n#define SNELL_SEARCH_ITERATIONS %d\n#define SNELL_ABSORB %d\n"
             "#define SNELL_FRESNEL_EXACT %d\n#define SNELL_INNER_FRESNEL %d\n#define SNELL_DISPERSION %d\n",
             linear, iterations, absorb, fresnel_exact, inner, dispersion);
    st = snell__glass_program_build(ctx, "oliveira.frag", s->out, def, screen, &p->g);
    if (st != SNELL_OK) return st;
    oli_locs *loc = SNELL__PROGRAM_LOCS_OF(oli_locs, p);
    loc->max_interfaces = glGetUniformLocation(p->g.prog, "u_max_interfaces");
    loc->back_band = glGetUniformLocation(p->g.prog, "u_back_band");
    *out = p;
    return SNELL_OK;
}

static snell_status oliveira_create(snell_ctx *ctx, snell__output_kind out, snell__program_cache *programs,
                                 void **state)
{
    oliveira_state *s = (oliveira_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    const snell__program_slot *p;
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    s->out = out;
    s->programs = programs;
    /* the default program, so that a device that cannot build it fails here, once */
    st = get_prog(ctx, s, DEFAULT_LINEAR_STEPS, DEFAULT_ITERATIONS, SNELL__SCREEN_SHARED_DEPTH, 0, 0, 0, 0, &p);
    if (st != SNELL_OK) {
        oliveira_destroy(ctx, s);
        return st;
    }
    *state = s;
    return SNELL_OK;
}

static void oliveira_destroy(snell_ctx *ctx, void *state)
{
    oliveira_state *s = (oliveira_state *)state;
    if (!s) return;
    snell__free(&ctx->alloc, s);
}

/* The seed's limits (3.4.2) are Wyman's: the exit is searched on the
 * farthest back face (or, after a reflection, the nearest front face), so
 * light leaving through a surface between them is wrong by construction,
 * and an open or non-manifold mesh has no solid's back faces. */
static snell__fit oliveira_fit(const snell_mesh_analysis *an, const snell_glass_resolved *g, char *why, size_t n)
{
    (void)g;
    if (!snell__fit_solid_few_surfaces(an, OLIVEIRA_MAX_HIDDEN, why, n)) return SNELL__FIT_RUNS;
    snell__why(why, n, "closed, %.2f <= %.2f hidden: exit searched along the ray in image space, nothing prepared",
               an->hidden_fraction, OLIVEIRA_MAX_HIDDEN);
    return SNELL__FIT_ADEQUATE;
}

static snell_status oliveira_draw(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                  snell_object_stats *stats)
{
    oliveira_state *s = (oliveira_state *)state;
    const snell_oliveira_params *c = &o->glass->material.oliveira;
    const snell__program_slot *p;
    snell_status st;
    if (!o->screen_space)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "glass %d: oliveira shades in screen space only", o->index);
    /* AUTO inner Fresnel: on for convex meshes, as for the cubemap (measured
     * for this kernel in bench/notes/history.md "Inner-surface Fresnel") */
    int inner = c->inner_fresnel == SNELL_INNER_FRESNEL_ON ||
                (c->inner_fresnel == SNELL_INNER_FRESNEL_AUTO && o->analysis && o->analysis->convex);
    st = get_prog(ctx, s, c->linear_steps, c->iterations, snell__glass_variant(o), o->glass->absorbs,
                  c->fresnel == SNELL_FRESNEL_EXACT, inner, snell__dispersion_variant(o->glass), &p);
    if (st != SNELL_OK) return st;
    snell__glass_program_use(&p->g, v, o);
    const oli_locs *loc = SNELL__PROGRAM_LOCS_OF(const oli_locs, p);
    glUniform1i(loc->max_interfaces, c->max_interfaces);
    glUniform1i(loc->back_band, v->back.band);
    snell__draw_surface(o, stats);
    stats->passes++;
    return SNELL_OK;
}


static const snell_param_info g_params[] = {
    {.name = "linear_steps",
     .offset = offsetof(snell_glass_material, oliveira.linear_steps),
     .help = "linear steps along the refracted ray before the binary search",
     .min = 0, .max = SNELL_OLIVEIRA_MAX_LINEAR_STEPS, .def = DEFAULT_LINEAR_STEPS},
    {.name = "iterations",
     .offset = offsetof(snell_glass_material, oliveira.iterations),
     .help = "binary-search steps per interface (stops earlier at one pixel)",
     .min = 1, .max = SNELL_OLIVEIRA_MAX_ITERATIONS, .def = DEFAULT_ITERATIONS},
    {.name = "max_interfaces",
     .offset = offsetof(snell_glass_material, oliveira.max_interfaces),
     .help = "surfaces processed per path (2 = entry + exit, more = TIR bounces)",
     .min = 2, .max = SNELL_OLIVEIRA_MAX_INTERFACES, .def = 2},
    {.name = "back_detail",
     .offset = offsetof(snell_glass_material, oliveira.back_detail),
     .help = SNELL__BACK_DETAIL_HELP,
     .min = 0, .max = 2, .def = SNELL_BACK_DETAIL_AUTO, .value_names = snell__back_detail_names},
    {.name = "guard_band",
     .offset = offsetof(snell_glass_material, oliveira.guard_band),
     .help = SNELL__GUARD_HELP,
     .min = -1, .max = SNELL_MAX_GUARD_BAND, .def = SNELL__GUARD_DEFAULT},
    {.name = "fresnel",
     .offset = offsetof(snell_glass_material, oliveira.fresnel),
     .help = "reflectance model: schlick (the MATCHED model) or exact (unpolarised dielectric)",
     .min = 0, .max = 2, .def = SNELL_FRESNEL_SCHLICK, .value_names = snell__fresnel_names},
    {.name = "inner_fresnel",
     .offset = offsetof(snell_glass_material, oliveira.inner_fresnel),
     .help = "Fresnel at the exit and one internal reflection: auto (on for convex meshes), off, on",
     .min = 0, .max = 2, .def = SNELL_INNER_FRESNEL_AUTO, .value_names = snell__inner_fresnel_names},
};


static snell_back_detail oliveira_back_detail(const snell_glass_resolved *g) { return g->material.oliveira.back_detail; }
static int oliveira_guard(const snell_glass_resolved *g) { return g->material.oliveira.guard_band; }

static const snell_method_info g_info = {
    .method = SNELL_METHOD_OLIVEIRA,
    .name = "oliveira",
    .summary = "two-sided in image space: exit by a conservative linear + binary search against the back faces, TIR bounces (Oliveira and Brauwers 2007)",
    .needs = "a closed mesh (no centre, no star shape, nothing prepared); per frame a back-face pass; screen space",
    .param_count = (int)(sizeof g_params / sizeof *g_params),
    .params = g_params,
    .counter_count = 0,
    .counters = NULL,
    .ref_interfaces = 0,
    .ref_chord_absorption = 0,
    .default_sweep = "linear_steps=1,8,16",
}; /* 0 reads as the default 8: 1 is the fewest */

/* AUTO by budget's rungs (frame/method.h): method, parameter, value; frame
 * time over single's and glass PSNR vs FULL for a convex, a bunny-like, a
 * torus-like and an open mesh; resolution scale (bench/notes/budget_rungs.md). */
static const snell_budget_rung g_rungs[] = {
    {SNELL_METHOD_OLIVEIRA, NULL, 0, {3.84f, 1.31f, 1.86f, 1.41f}, {27.98f, 16.34f, 20.29f, 17.52f}, 1, NULL},
};

const snell__method snell__method_oliveira = {
    .info = &g_info,
    .needs_analysis = 1,
    .fit = oliveira_fit,
    .create = oliveira_create,
    .destroy = oliveira_destroy,
    .draw = oliveira_draw,
    .software_screen_ppt = 1e9f,
    .needs_back_faces = 1,
    .back_detail = oliveira_back_detail,
    .back_guard_percent = oliveira_guard,
    .screen_space_only = 1,
    .rungs = g_rungs,
    .rung_count = (int)(sizeof g_rungs / sizeof *g_rungs),
};
