/* SPDX-License-Identifier: MIT */
/* cubemap.c — two-sided refraction with a normal+distance cubemap (Li et
 * al. 2007 as in Unger 4.1): prepared once per (mesh version, face size,
 * encoding) by baking the cubemap about the analysed centre (ndcube.c,
 * mesh_analyze.c); per frame one pass of the search shader (cubemap.frag)
 * over the front faces. The search programs are kept here: one per
 * (encoding, iterations, linear steps, search or none), because the step
 * counts are compile-time constants of the shader (cubemap.frag says why);
 * the default one is built with the method, others on first use. */
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "frame/ndcube.h"
#include "core/program.h"
#include "methods/cubemap.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define DEFAULT_ITERATIONS 6
/* Schlick by default: the MATCHED model the tests and the reference share
 * (the exact reflectance gains little against FULL; BENCHMARKS.md).
 * DEFAULT_FRESNEL 1 = exact. */
#define DEFAULT_FRESNEL 0


/* The AUTO threshold on hidden_fraction (snell_mesh_analyze): the share of
 * surface the cubemap cannot represent. Against FULL the cubemap represents
 * meshes about as hidden as the bunny (0.25) but not the torus (0.45), where
 * the image-space search is far nearer; the threshold sits between them
 * (above it AUTO goes on to the image-space methods, which are adequate up to
 * 0.6). Errors: bench/notes/history.md "Oliveira", bench/notes/code.md "cubemap.c". */
#define AUTO_MAX_HIDDEN 0.35f

/* llvmpipe (BENCHMARKS.md): screen space is faster at every density, from a
 * 32-segment sphere's large triangles to the bunny's small ones: the search
 * costs so much per pixel that full 4x4 blocks always win. */
#define CUBEMAP_SOFTWARE_SCREEN_PPT 1e9f

/* One mesh version's baked cubemap (the prepared resource). */
typedef struct cube_prepared {
    snell__ndcube cube;
    float inner_radius;        /* object units; 0 when the centre may be outside */
} cube_prepared;

/* A program's own uniforms (over its cache slot's loc); its key: key: prog_key's fields in order */
typedef struct cube_locs {
    int inv_model, centre, radius, inner_radius, max_interfaces, texel_angle, doubt;
} cube_locs;
SNELL__PROGRAM_LOCS_FIT(cube_locs);

typedef struct cubemap_state {
    snell__output_kind out;
    snell__program_cache *programs; /* the renderer's */
    snell__ndcube_baker baker;
} cubemap_state;

static void cubemap_destroy(snell_ctx *ctx, void *state);

/* What selects a search program: its compile-time constants. */
typedef struct prog_key {
    snell_ndcube_encoding enc;
    int iterations, linear, no_search, screen, absorb, fresnel_exact, inner, dispersion;
    int doubt; /* SNELL__CUBEMAP_DOUBT_*: hybrid.frag's doubt test (methods/cubemap.h) */
} prog_key;

static snell_status build_prog(snell_ctx *ctx, snell__output_kind out, const prog_key *k, snell__program_slot *p)
{
    char def[360];
    const char *fs = "cubemap.frag";
    snell_status st;
    int n = snprintf(def, sizeof def,
             "#define SNELL_NDCUBE_%s 1\n#define SNELL_SEARCH_ITERATIONS %d\n#define SNELL_LINEAR_STEPS %d\n"
             "#define SNELL_NO_SEARCH %d\n#define SNELL_ABSORB %d\n#define SNELL_FRESNEL_EXACT %d\n"
             "#define SNELL_INNER_FRESNEL %d\n#define SNELL_DISPERSION %d\n",
             k->enc == SNELL_NDCUBE_OCT ? "OCT" : "PLAIN", k->iterations, k->linear, k->no_search, k->absorb,
             k->fresnel_exact, k->inner, k->dispersion);
#if SNELL__BUILT_hybrid
    if (k->doubt) {
        snprintf(def + n, sizeof def - (size_t)n, "#define SNELL_DOUBT_MODE %d\n", k->doubt);
        fs = "hybrid.frag";
    }
#endif
    (void)n;
    st = snell__glass_program_build(ctx, fs, out, def, k->screen, &p->g);
    if (st != SNELL_OK) return st;
    cube_locs *loc = SNELL__PROGRAM_LOCS_OF(cube_locs, p);
    loc->inv_model = glGetUniformLocation(p->g.prog, "u_inv_model");
    loc->centre = glGetUniformLocation(p->g.prog, "u_centre");
    loc->radius = glGetUniformLocation(p->g.prog, "u_radius");
    loc->inner_radius = glGetUniformLocation(p->g.prog, "u_inner_radius");
    loc->max_interfaces = glGetUniformLocation(p->g.prog, "u_max_interfaces");
    loc->texel_angle = glGetUniformLocation(p->g.prog, "u_texel_angle");
#if SNELL__BUILT_hybrid
    loc->doubt = glGetUniformLocation(p->g.prog, "u_doubt");
#endif
    return SNELL_OK;
}

/* The program of these settings: cached, else built into the least recently
 * used slot. */
static snell_status get_prog(snell_ctx *ctx, cubemap_state *s, const prog_key *k, const snell__program_slot **out)
{
    const int key[10] = {(int)k->enc, k->iterations, k->linear, k->no_search, k->screen, k->absorb, k->fresnel_exact,
                         k->inner, k->dispersion, k->doubt};
    int hit;
    snell__program_slot *p = snell__program_cache_get(s->programs, SNELL_METHOD_CUBEMAP, key, 10, &hit);
    snell_status st = hit ? SNELL_OK : build_prog(ctx, s->out, k, p);
    if (st == SNELL_OK) *out = p;
    return st;
}

static snell_status cubemap_create(snell_ctx *ctx, snell__output_kind out, snell__program_cache *programs,
                                 void **state)
{
    cubemap_state *s = (cubemap_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    const snell__program_slot *p;
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    s->out = out;
    s->programs = programs;
    prog_key k = {SNELL_NDCUBE_PLAIN, DEFAULT_ITERATIONS, 0, 0, 0, 0, DEFAULT_FRESNEL, 0, 0, 0};
    st = get_prog(ctx, s, &k, &p);
    if (st == SNELL_OK) st = snell__ndcube_baker_create(ctx, &s->baker);
    if (st != SNELL_OK) {
        cubemap_destroy(ctx, s);
        return st;
    }
    *state = s;
    return SNELL_OK;
}

static void cubemap_destroy(snell_ctx *ctx, void *state)
{
    cubemap_state *s = (cubemap_state *)state;
    if (!s) return;
    snell__ndcube_baker_destroy(&s->baker);
    snell__free(&ctx->alloc, s);
}

static snell__fit cubemap_fit(const snell_mesh_analysis *an, const snell_glass_resolved *g, char *why, size_t n)
{
    (void)g;
    if (!an) {
        snell__why(why, n, "needs the mesh analysis, which failed");
        return SNELL__FIT_FAILS;
    }
    if (!an->closed) {
        snell__why(why, n, "needs a closed mesh: %u boundary, %u non-manifold, %u flipped edges",
                   (unsigned)an->boundary_edges, (unsigned)an->nonmanifold_edges, (unsigned)an->flipped_edges);
        return SNELL__FIT_FAILS;
    }
    if (!an->inside) {
        snell__why(why, n, "needs its centre inside the mesh; no inside candidate was found");
        return SNELL__FIT_FAILS;
    }
    if (an->pieces > 1) {
        snell__why(why, n, "closed, but %u separate pieces: the cube from one centre serves one of them",
                   (unsigned)an->pieces);
        return SNELL__FIT_RUNS;
    }
    if (an->hidden_fraction > AUTO_MAX_HIDDEN) {
        snell__why(why, n, "closed, centre inside, but %.2f > %.2f of the surface is hidden from the centre",
                   an->hidden_fraction, AUTO_MAX_HIDDEN);
        return SNELL__FIT_RUNS;
    }
    snell__why(why, n, "closed, centre inside, %.2f <= %.2f of the surface hidden from the centre",
               an->hidden_fraction, AUTO_MAX_HIDDEN);
    return SNELL__FIT_ADEQUATE;
}

static void cubemap_key(const snell__object *o, int key[4])
{
    key[0] = o->glass->material.cubemap.face_size;
    key[1] = (int)o->glass->material.cubemap.encoding;
    key[2] = key[3] = 0;
}

/* Bakes about the analysed centre; a mesh that could not be analysed (drawn
 * only when asked for explicitly, with a warning) uses its box centre. */
static snell_status cubemap_prepare(snell_ctx *ctx, void *state, const snell__object *o, void *prepared,
                                    snell_object_stats *stats)
{
    cubemap_state *s = (cubemap_state *)state;
    cube_prepared *p = (cube_prepared *)prepared;
    const snell_mesh_analysis *an = o->analysis;
    const snell_cubemap_params *c = &o->glass->material.cubemap;
    float centre[3], radius;
    snell_status st;
    int k;
    for (k = 0; k < 3; k++) centre[k] = an ? an->centre[k] : 0.5f * (o->mesh->bmin[k] + o->mesh->bmax[k]);
    /* 1e-4 margin: the farthest vertex stays strictly inside the cube's range. */
    radius = (an ? an->radius : o->mesh->bradius) * 1.0001f;
    if (!(radius > 0.0f)) radius = 1.0f;
    st = snell__ndcube_bake(ctx, &s->baker, o->mesh, centre, radius, c->face_size, c->encoding, &p->cube);
    if (st != SNELL_OK) return st;
    /* The inner ball is surely inside only if the centre is; one 8-bit
     * distance step below its radius, as stored distances are rounded to that
     * step (the 16-bit OCT ones far finer). */
    p->inner_radius = an && an->inside ? fmaxf(an->inner_radius - p->cube.radius / 255.0f, 0.0f) : 0.0f;
    stats->passes += 6;
    return SNELL_OK;
}

static void cubemap_release(void *prepared)
{
    snell__ndcube_release(&((cube_prepared *)prepared)->cube);
}

/* The search pass; doubt (SNELL__CUBEMAP_DOUBT_*, 0 none) and its threshold
 * for the hybrid (methods/cubemap.h). */
static snell_status draw_search(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                snell_object_stats *stats, int doubt, float threshold)
{
    cubemap_state *s = (cubemap_state *)state;
    const snell_cubemap_params *c = &o->glass->material.cubemap;
    const cube_prepared *cp = (const cube_prepared *)o->prepared;
    prog_key k;
    const snell__program_slot *p;
    snell_status st;

    k.enc = c->encoding;
    k.iterations = c->iterations;
    k.linear = c->linear_steps;
    k.no_search = c->max_interfaces == 1 && !o->glass->absorbs;
    k.screen = snell__glass_variant(o);
    k.absorb = o->glass->absorbs;
    k.fresnel_exact = c->fresnel == SNELL_FRESNEL_EXACT;
    /* Where it pays (BENCHMARKS.md, "Inner-surface Fresnel"): on a convex
     * mesh the two-interface search is nearly exact and the missing exit
     * Fresnel is the largest error left; on the torus and the bunny the exit
     * search's own error dominates, so the branch costs more than it gains. */
    k.inner = !k.no_search && (c->inner_fresnel == SNELL_INNER_FRESNEL_ON ||
                               (c->inner_fresnel == SNELL_INNER_FRESNEL_AUTO && o->analysis && o->analysis->convex));
    k.dispersion = snell__dispersion_variant(o->glass);
    k.doubt = doubt;
    st = get_prog(ctx, s, &k, &p);
    if (st != SNELL_OK) return st;
    if (k.no_search) stats->skipped |= SNELL_SKIP_SEARCH;
    snell__glass_program_use(&p->g, v, o);
    snell__glass_program_bind(&p->g, "u_ndcube", GL_TEXTURE_CUBE_MAP, cp->cube.texture, 0);
    const cube_locs *loc = SNELL__PROGRAM_LOCS_OF(const cube_locs, p);
    glUniformMatrix4fv(loc->inv_model, 1, GL_FALSE, (const GLfloat *)o->inv_model);
    glUniform3fv(loc->centre, 1, cp->cube.centre);
    glUniform1f(loc->radius, cp->cube.radius);
    glUniform1f(loc->inner_radius, cp->inner_radius);
    glUniform1i(loc->max_interfaces, c->max_interfaces);
    /* A texel is 2/N wide in face coordinates; it subtends 2/N rad at a face
     * centre and sqrt(2)/3 * 2/N at a corner: the smaller is the stop bound. */
    glUniform1f(loc->texel_angle, (float)(2.0 * sqrt(2.0) / 3.0) / (float)c->face_size);
#if SNELL__BUILT_hybrid
    if (doubt) glUniform1f(loc->doubt, threshold * cp->cube.radius);
#else
    (void)threshold;
#endif
    /* Back faces are culled on closed meshes (snell__draw_surface). A depth
     * pre-pass would do the same for any mesh but cost more than it saved: it
     * doubles the triangle setup, which dominates on llvmpipe for the
     * 69k-triangle bunny (bench/BENCHMARKS.md). */
    snell__draw_surface(o, stats);
    stats->passes++;
    return SNELL_OK;
}

static snell_status cubemap_draw(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                 snell_object_stats *stats)
{
    return draw_search(ctx, state, v, o, stats, 0, 0.0f);
}

#if SNELL__BUILT_hybrid
snell_status snell__cubemap_draw_doubt(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                       snell_object_stats *stats, int doubt, float threshold)
{
    return draw_search(ctx, state, v, o, stats, doubt, threshold);
}
#endif

static const char *const g_encoding_names[] = {"default", "plain", "oct"};

static const snell_param_info g_params[] = {
    {.name = "iterations",
     .offset = offsetof(snell_glass_material, cubemap.iterations),
     .help = "binary-search steps per interface",
     .min = 1, .max = SNELL_CUBEMAP_MAX_ITERATIONS, .def = DEFAULT_ITERATIONS},
    {.name = "linear_steps",
     .offset = offsetof(snell_glass_material, cubemap.linear_steps),
     .help = "linear pre-search steps before the binary search",
     .min = 0, .max = SNELL_CUBEMAP_MAX_LINEAR_STEPS, .def = 0},
    {.name = "max_interfaces",
     .offset = offsetof(snell_glass_material, cubemap.max_interfaces),
     .help = "surfaces processed per path (1 = single surface, 2 = entry + exit, more = TIR bounces)",
     .min = 1, .max = SNELL_CUBEMAP_MAX_INTERFACES, .def = 2},
    {.name = "face_size",
     .offset = offsetof(snell_glass_material, cubemap.face_size),
     .help = "normal+distance cubemap face size, texels",
     .min = 16, .max = 2048, .def = 256},
    {.name = "encoding",
     .offset = offsetof(snell_glass_material, cubemap.encoding),
     .help = "texel packing: plain (Unger 4.1, filtered) or oct (octahedral normal, 16-bit distance)",
     .min = 0, .max = 2, .def = SNELL_NDCUBE_PLAIN, .value_names = g_encoding_names},
    {.name = "fresnel",
     .offset = offsetof(snell_glass_material, cubemap.fresnel),
     .help = "reflectance at the interfaces: schlick (the MATCHED model) or exact (unpolarised, as FULL)",
     .min = 0, .max = 2, .def = DEFAULT_FRESNEL == 1 ? SNELL_FRESNEL_EXACT : SNELL_FRESNEL_SCHLICK, .value_names = snell__fresnel_names},
    {.name = "inner_fresnel",
     .offset = offsetof(snell_glass_material, cubemap.inner_fresnel),
     .help = "Fresnel at the exit too (1 - F out, the internal reflection followed by one more search): auto (on for convex meshes), off, on",
     .min = 0, .max = 2, .def = SNELL_INNER_FRESNEL_AUTO, .value_names = snell__inner_fresnel_names},
};


static const snell_method_info g_info = {
    .method = SNELL_METHOD_CUBEMAP,
    .name = "cubemap",
    .summary = "two-sided: exit found in a normal+distance cubemap, TIR bounces (Li et al., Unger 4.1)",
    .needs = "a closed mesh with its analysed centre inside; exact when star-shaped about it",
    .param_count = (int)(sizeof g_params / sizeof *g_params),
    .params = g_params,
    .counter_count = 0,
    .counters = NULL,
    .ref_interfaces = 0,
    .ref_chord_absorption = 0,
    .default_sweep = "iterations=4,6,12",
};

/* AUTO by budget's rungs (frame/method.h): method, parameter, value; frame
 * time over single's and glass PSNR vs FULL for a convex, a bunny-like, a
 * torus-like and an open mesh; resolution scale (bench/notes/budget_rungs.md). */
static const snell_budget_rung g_rungs[] = {
    {SNELL_METHOD_CUBEMAP, NULL, 0, {2.14f, 1.08f, 1.44f, 1.02f}, {34.95f, 17.09f, 15.50f, 15.98f}, 1, NULL},
};

const snell__method snell__method_cubemap = {
    .info = &g_info,
    .needs_analysis = 1,
    .fit = cubemap_fit,
    .create = cubemap_create,
    .destroy = cubemap_destroy,
    .prepared_size = sizeof(cube_prepared),
    .key = cubemap_key,
    .prepare = cubemap_prepare,
    .release = cubemap_release,
    .draw = cubemap_draw,
    .software_screen_ppt = CUBEMAP_SOFTWARE_SCREEN_PPT,
    .rungs = g_rungs,
    .rung_count = (int)(sizeof g_rungs / sizeof *g_rungs),
};
