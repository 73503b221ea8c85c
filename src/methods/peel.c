/* SPDX-License-Identifier: MIT */
/* peel.c — multi-layer refraction from depth-peeled layers (Wang 2014, seed
 * 001 3.1-3.6) for concave objects whose view rays cross more than two
 * surfaces: up to material.peel.layers peels of front and back faces into one
 * RGBA8 texture array, then peel.frag searches between them. Peels that cannot
 * hold anything are skipped (depth complexity, occlusion queries read a frame
 * later); in screen space layer 0 may come from the G-buffer. The design notes:
 * docs/methods.md, "src/methods/peel.c". */
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"
#include "frame/pass.h"
#include "frame/peel_targets.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define DEFAULT_LAYERS 4
#define DEFAULT_LINEAR 16
#define DEFAULT_BINARY 6
#define DEFAULT_INTERFACES 8
/* Fresnel reflectance model: 0 = Schlick (the MATCHED model), 1 = exact. */
#define DEFAULT_FRESNEL 0
/* The texture unit of the layers (render/gbuffer.h: 0 env, 1 the kernel's). */
#define LAYER_UNIT 1

/* AUTO shading on llvmpipe: the peels are drawn forward either way; the
 * kernel's per-pixel search is costlier than the cubemap's, whose measured
 * rule is "always screen space" (its full 4x4 blocks win at every density). */
#define PEEL_SOFTWARE_SCREEN_PPT 1e9f
/* Layer 0 comes from the G-buffer only for objects whose front triangles
 * are estimated below this many pixels each: there a peel of the mesh is
 * bound by triangle set-up and the conversion, one full-screen pass over
 * the scissor, costs less; on large triangles it costs more. On llvmpipe
 * the two cross near 20 pixels a triangle (bench/notes/code.md, "peel.c"). */
#define LAYER0_GBUFFER_PPT 16.0f

/* A program's own uniforms (over its cache slot's loc); its key: key: prog_key's fields in order */
typedef struct peel_locs {
    int layer_count, fwd, near_, inv_range, size, max_interfaces;
} peel_locs;
SNELL__PROGRAM_LOCS_FIT(peel_locs);

/* One glass object's (by its index in the frame) last peels: their
 * occlusion queries and what the last ones read found. */
typedef struct peel_history {
    unsigned version;                      /* of the mesh it is about; 0: none */
    unsigned query[SNELL_PEEL_MAX_LAYERS]; /* layer k's ANY_SAMPLES_PASSED (k >= 1; [0] marks them made) */
    int pending;                           /* layers of the peels whose queries are not read yet; 0: none */
    int found;                             /* non-empty layers the last read peels found; -1: none read */
    int full;                              /* 1: every layer they drew was non-empty (it may need more) */
} peel_history;

typedef struct peel_state {
    snell__output_kind out;
    snell__program_cache *programs; /* the renderer's */
    /* the peel pass */
    unsigned layer_prog;
    int u_model, u_normal_matrix, u_view_proj, u_eye, u_fwd, u_near, u_inv_range, u_first, u_prev;
    /* layer 0 from the G-buffer */
    unsigned zero_prog;
    snell__samplers z_samplers;     /* its G-buffer maps, published by the gbuffer stage */
    int z_inv_view_proj, z_inv_size, z_gid, z_eye, z_fwd, z_near, z_inv_range;
    snell__peel_targets t;
    peel_history hist[SNELL_MAX_GLASS];
} peel_state;

static void peel_destroy(snell_ctx *ctx, void *state);

/* What selects a kernel: its compile-time constants. */
typedef struct prog_key {
    int screen, absorb, linear, binary, fixes, fresnel_exact, inner, dispersion, layers;
} prog_key;

static snell_status build_prog(snell_ctx *ctx, peel_state *s, const prog_key *k, snell__program_slot *p)
{
    char def[360];
    snell_status st;
    snprintf(def, sizeof def,
             "#define SNELL_PEEL_LINEAR %d\n#define SNELL_PEEL_BINARY %d\n#define SNELL_PEEL_FIX_DISCONTINUITY %d\n"
             "#define SNELL_PEEL_FIX_MERGE %d\n#define SNELL_ABSORB %d\n#define SNELL_FRESNEL_EXACT %d\n"
             "#define SNELL_INNER_FRESNEL %d\n#define SNELL_DISPERSION %d\n#define SNELL_PEEL_LAYERS %d\n",
             k->linear, k->binary, k->fixes == SNELL_PEEL_FIXES_DISCONTINUITY || k->fixes == SNELL_PEEL_FIXES_BOTH,
             k->fixes == SNELL_PEEL_FIXES_MERGE || k->fixes == SNELL_PEEL_FIXES_BOTH, k->absorb, k->fresnel_exact,
             k->inner, k->dispersion, k->layers);
    st = snell__glass_program_build(ctx, "peel.frag", s->out, def, k->screen, &p->g);
    if (st != SNELL_OK) return st;
    peel_locs *loc = SNELL__PROGRAM_LOCS_OF(peel_locs, p);
    loc->layer_count = glGetUniformLocation(p->g.prog, "u_layer_count");
    loc->fwd = glGetUniformLocation(p->g.prog, "u_fwd");
    loc->near_ = glGetUniformLocation(p->g.prog, "u_near");
    loc->inv_range = glGetUniformLocation(p->g.prog, "u_inv_range");
    loc->size = glGetUniformLocation(p->g.prog, "u_size");
    loc->max_interfaces = glGetUniformLocation(p->g.prog, "u_max_interfaces");
    return SNELL_OK;
}

/* The kernel of these settings: cached, else built into the least recently used slot. */
static snell_status get_prog(snell_ctx *ctx, peel_state *s, const prog_key *k, const snell__program_slot **out)
{
    const int key[9] = {k->screen, k->absorb, k->linear, k->binary, k->fixes, k->fresnel_exact, k->inner,
                        k->dispersion, k->layers};
    int hit;
    snell__program_slot *p = snell__program_cache_get(s->programs, SNELL_METHOD_PEEL, key, 9, &hit);
    snell_status st = hit ? SNELL_OK : build_prog(ctx, s, k, p);
    if (st == SNELL_OK) *out = p;
    return st;
}

static snell_status peel_create(snell_ctx *ctx, snell__output_kind out, snell__program_cache *programs,
                                 void **state)
{
    peel_state *s = (peel_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    const snell__program_slot *p;
    const prog_key d = {0, 0, DEFAULT_LINEAR, DEFAULT_BINARY, SNELL_PEEL_FIXES_BOTH, DEFAULT_FRESNEL, 0, 0, DEFAULT_LAYERS};
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    s->out = out;
    s->programs = programs;
    st = snell__program_build(ctx, "object.vert", "depth_peel.frag", NULL, &s->layer_prog);
    if (st == SNELL_OK) st = snell__program_build(ctx, "screen.vert", "peel_layer0.frag", NULL, &s->zero_prog);
    if (st == SNELL_OK) st = get_prog(ctx, s, &d, &p);
    if (st != SNELL_OK) {
        peel_destroy(ctx, s);
        return st;
    }
    s->u_model = glGetUniformLocation(s->layer_prog, "u_model");
    s->u_normal_matrix = glGetUniformLocation(s->layer_prog, "u_normal_matrix");
    s->u_view_proj = glGetUniformLocation(s->layer_prog, "u_view_proj");
    s->u_eye = glGetUniformLocation(s->layer_prog, "u_eye");
    s->u_fwd = glGetUniformLocation(s->layer_prog, "u_fwd");
    s->u_near = glGetUniformLocation(s->layer_prog, "u_near");
    s->u_inv_range = glGetUniformLocation(s->layer_prog, "u_inv_range");
    s->u_first = glGetUniformLocation(s->layer_prog, "u_first");
    s->u_prev = glGetUniformLocation(s->layer_prog, "u_prev");
    glUseProgram(s->layer_prog);
    glUniform1i(glGetUniformLocation(s->layer_prog, "u_id"), 1); /* the flag: non-empty */
    s->z_inv_view_proj = glGetUniformLocation(s->zero_prog, "u_inv_view_proj");
    s->z_inv_size = glGetUniformLocation(s->zero_prog, "u_inv_size");
    s->z_gid = glGetUniformLocation(s->zero_prog, "u_gid");
    s->z_eye = glGetUniformLocation(s->zero_prog, "u_eye");
    s->z_fwd = glGetUniformLocation(s->zero_prog, "u_fwd");
    s->z_near = glGetUniformLocation(s->zero_prog, "u_near");
    s->z_inv_range = glGetUniformLocation(s->zero_prog, "u_inv_range");
    st = snell__samplers_assign(ctx, s->zero_prog, "peel_layer0.frag", &s->z_samplers);
    if (st != SNELL_OK) {
        peel_destroy(ctx, s);
        return st;
    }
    *state = s;
    return SNELL_OK;
}

static void peel_destroy(snell_ctx *ctx, void *state)
{
    peel_state *s = (peel_state *)state;
    int i;
    if (!s) return;
    for (i = 0; i < SNELL_MAX_GLASS; i++)
        if (s->hist[i].query[0]) glDeleteQueries(SNELL_PEEL_MAX_LAYERS, s->hist[i].query);
    if (s->layer_prog) glDeleteProgram(s->layer_prog);
    if (s->zero_prog) glDeleteProgram(s->zero_prog);
    snell__peel_targets_release(&s->t);
    snell__free(&ctx->alloc, s);
}

/* The view axis and the object's depth range along it (the bounding sphere). */
static void depth_frame(const snell__view *v, const snell__object *o, float fwd[3], float *near_, float *inv_range)
{
    int k;
    float c = 0.0f;
    for (k = 0; k < 3; k++) {
        fwd[k] = -v->view[k][2];
        c += (o->bsphere[k] - v->eye[k]) * fwd[k];
    }
    *near_ = c - o->bsphere[3];
    *inv_range = 0.5f / o->bsphere[3];
}

/* Reads h's pending queries if the GPU has every result (else leaves them
 * pending): the layers found are the first one and those after it up to
 * the first empty one. */
static void history_read(peel_history *h)
{
    GLuint any = 1;
    int k;
    for (k = 1; k < h->pending; k++) {
        glGetQueryObjectuiv(h->query[k], GL_QUERY_RESULT_AVAILABLE, &any);
        if (!any) return;
    }
    for (k = 1; k < h->pending; k++) {
        glGetQueryObjectuiv(h->query[k], GL_QUERY_RESULT, &any);
        if (!any) break;
    }
    h->found = k;
    h->full = k == h->pending;
    h->pending = 0;
}

/* The peels of this frame: every wanted one without a result yet or after
 * peels that all came out full (the object may need more than they had),
 * else one more than the last found (the spare: its query sees growth). */
static int history_peels(const peel_history *h, int want)
{
    return h->found < 0 || h->full || h->found + 1 > want ? want : h->found + 1;
}

/* Layer 0 from the G-buffer (peel_layer0.frag), within peel_layers' pass
 * with layer 0 attached and cleared. */
static void convert_layer0(peel_state *s, const snell__view *v, const snell__object *o, const float fwd[3],
                           float near_, float inv_range)
{
    glUseProgram(s->zero_prog);
    snell__samplers_bind_published(&s->z_samplers, &v->textures);
    glUniformMatrix4fv(s->z_inv_view_proj, 1, GL_FALSE, (const GLfloat *)v->inv_view_proj);
    glUniform2f(s->z_inv_size, 1.0f / (float)v->width, 1.0f / (float)v->height);
    glUniform1i(s->z_gid, o->gid);
    glUniform3fv(s->z_eye, 1, v->eye);
    glUniform3fv(s->z_fwd, 1, fwd);
    glUniform1f(s->z_near, near_);
    glUniform1f(s->z_inv_range, inv_range);
    glDisable(GL_DEPTH_TEST); /* the triangle lies at the far plane; layer 1 clears the depth it tests */
    glBindVertexArray(0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(s->layer_prog);
    glActiveTexture(GL_TEXTURE0 + LAYER_UNIT); /* where peel_layers binds the previous layer */
}

/* Draws `n` peels of the object, each after the first with an occlusion
 * query of h's unless h's last ones are still pending (then none: those are
 * read first); layer 0 converted from the G-buffer where it holds it (the
 * return: 1 if so). */
static snell_status peel_layers(snell_ctx *ctx, peel_state *s, const snell__view *v, const snell__object *o,
                                peel_history *h, int n, int *gbuffer)
{
    float fwd[3], near_, inv_range, d2 = 0.0f;
    snell__pass pass;
    snell_status st;
    int k, winding = 0, flip = 0, query = h->pending == 0;
    if (query && !h->query[0]) glGenQueries(SNELL_PEEL_MAX_LAYERS, h->query);
    depth_frame(v, o, fwd, &near_, &inv_range);
    for (k = 0; k < 3; k++) d2 += (v->eye[k] - o->bsphere[k]) * (v->eye[k] - o->bsphere[k]);
    /* A closed solid of known winding seen from outside its bounding sphere:
     * along every view ray the surfaces alternate entry (front face) and exit
     * (back face), so layer k is a front face for even k and a back face for
     * odd k, and each peel draws only those (half the fragments; the
     * kernel's gap parity assumes the same). Else every face. */
    if (o->glass->material.thickness <= 0.0f && d2 > o->bsphere[3] * o->bsphere[3])
        winding = snell__mesh_winding(o->mesh);
    flip = (winding < 0) != (o->mirrored != 0);
    /* only where layer 1 draws back faces alone: otherwise its test against
     * a depth a few quanta off could keep layer 0's surface again */
    *gbuffer = winding != 0 && o->screen_space && o->front_whole && o->scale <= 1.0f &&
               o->pixels_per_triangle < LAYER0_GBUFFER_PPT &&
               o->glass->material.peel.layer0 != SNELL_PEEL_LAYER0_PEEL;
    snell__pass_begin(&pass, s->t.fbo, v->width, v->height, 0, GL_LESS, 1.0f);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s->t.depth_rb);
    glUseProgram(s->layer_prog);
    glUniformMatrix4fv(s->u_model, 1, GL_FALSE, (const GLfloat *)o->model);
    glUniformMatrix3fv(s->u_normal_matrix, 1, GL_FALSE, (const GLfloat *)o->normal_matrix);
    glUniformMatrix4fv(s->u_view_proj, 1, GL_FALSE, (const GLfloat *)v->view_proj);
    glUniform3fv(s->u_eye, 1, v->eye);
    glUniform3fv(s->u_fwd, 1, fwd);
    glUniform1f(s->u_near, near_);
    glUniform1f(s->u_inv_range, inv_range);
    glUniform1i(s->u_prev, LAYER_UNIT);
    /* only the object's rectangle: clears and peels */
    glEnable(GL_SCISSOR_TEST);
    glScissor(o->scissor[0], o->scissor[1], o->scissor[2], o->scissor[3]);
    glActiveTexture(GL_TEXTURE0 + LAYER_UNIT);
    for (k = 0; k < n; k++) {
        if ((st = snell__peel_layer_begin(ctx, &s->t, k)) != SNELL_OK) {
            glDisable(GL_SCISSOR_TEST);
            snell__pass_end(&pass);
            return st;
        }
        glUniform1i(s->u_first, k == 0);
        if (query && k > 0) glBeginQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE, h->query[k]);
        if (k == 0 && *gbuffer) {
            convert_layer0(s, v, o, fwd, near_, inv_range);
            continue;
        }
        if (winding != 0) {
            glEnable(GL_CULL_FACE);
            glCullFace(((k & 1) != 0) != flip ? GL_FRONT : GL_BACK); /* even k: cull the back faces */
            glFrontFace(GL_CCW);
        }
        snell__draw_object(o); /* disables culling */
        if (query && k > 0) glEndQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE);
    }
    if (query) h->pending = n;
    glDisable(GL_SCISSOR_TEST);
    snell__pass_end(&pass);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "GL error peeling layers");
}

/* Peels needed: the layers asked for, bounded by the mesh's depth
 * complexity rounded up to a front/back pair (a convex mesh: 2). */
static int layers_wanted(const snell__object *o)
{
    int want = o->glass->material.peel.layers;
    if (o->analysis && o->analysis->depth_complexity > 0) {
        int dc = (o->analysis->depth_complexity + 1) & ~1;
        if (dc < want) want = dc;
    }
    return want < 2 ? 2 : want;
}

/* Whether the last exit's Fresnel is applied (material.peel.inner_fresnel).
 * AUTO is on for every mesh (BENCHMARKS.md, "Inner-surface Fresnel in
 * peel"): unlike the cubemap's two-surface search, the layer search is
 * close enough on concave meshes too that the missing exit Fresnel is a
 * large part of the error left, on every mesh measured, for a modest share of
 * the frame (bench/notes/code.md, "peel.c"). */
static int inner_wanted(const snell__object *o)
{
    return o->glass->material.peel.inner_fresnel != SNELL_INNER_FRESNEL_OFF;
}

static snell_status peel_draw(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                              snell_object_stats *stats)
{
    peel_state *s = (peel_state *)state;
    const snell_peel_params *pp = &o->glass->material.peel;
    float fwd[3], near_, inv_range;
    const snell__program_slot *p;
    peel_history *h = &s->hist[o->index];
    int peeled, gbuffer = 0;
    prog_key k;
    snell_status st;
    k.screen = snell__glass_variant(o);
    k.absorb = o->glass->absorbs;
    k.linear = pp->linear_steps;
    k.binary = pp->binary_steps;
    k.fixes = (int)pp->fixes;
    k.fresnel_exact = pp->fresnel == SNELL_FRESNEL_EXACT;
    /* One interface is the single-surface model: no exit to weight. */
    k.inner = pp->max_interfaces > 1 && inner_wanted(o);
    k.dispersion = snell__dispersion_variant(o->glass);
    k.layers = layers_wanted(o);
    st = get_prog(ctx, s, &k, &p);
    if (st == SNELL_OK) {
        int remade;
        st = snell__peel_targets_ensure(ctx, &s->t, v->width, v->height, pp->layers, LAYER_UNIT, "peel layers", &remade);
    }
    if (h->version != o->mesh->version) { /* another object at this index: its history is not this one's */
        h->version = o->mesh->version;
        h->pending = 0;
        h->found = -1;
    }
    if (h->pending) history_read(h);
    peeled = history_peels(h, k.layers);
    if (st == SNELL_OK) st = peel_layers(ctx, s, v, o, h, peeled, &gbuffer);
    if (st != SNELL_OK) return st;
    stats->passes += peeled;
    stats->counters[0] = peeled;
    stats->counters[1] = h->found;
    stats->counters[2] = gbuffer;
    depth_frame(v, o, fwd, &near_, &inv_range);
    snell__glass_program_use(&p->g, v, o);
    snell__glass_program_bind(&p->g, "u_layers", GL_TEXTURE_2D_ARRAY, s->t.array_tex, 0);
    const peel_locs *loc = SNELL__PROGRAM_LOCS_OF(const peel_locs, p);
    glUniform1i(loc->layer_count, peeled); /* those drawn empty read as no surface */
    glUniform3fv(loc->fwd, 1, fwd);
    glUniform1f(loc->near_, near_);
    glUniform1f(loc->inv_range, inv_range);
    glUniform2f(loc->size, (float)v->width, (float)v->height);
    glUniform1i(loc->max_interfaces, pp->max_interfaces);
    snell__draw_surface(o, stats);
    stats->passes++;
    return SNELL_OK;
}

/* The seed's case (3.1): convex meshes need two layers, and the cubemap and
 * Wyman's method serve them for less; this one is for meshes whose view
 * rays cross more surfaces. A closed mesh is what the layers' front/back
 * alternation assumes; on an open one the layers are still the surfaces, but
 * inside and outside are a guess. */
static snell__fit peel_fit(const snell_mesh_analysis *an, const snell_glass_resolved *g, char *why, size_t n)
{
    (void)g;
    if (!an) {
        snell__why(why, n, "mesh analysis failed: closedness and depth complexity unknown");
        return SNELL__FIT_RUNS;
    }
    if (!an->closed) {
        snell__why(why, n, "open or non-manifold (%u boundary, %u non-manifold, %u flipped edges): layers do not "
                           "alternate between glass and air", (unsigned)an->boundary_edges,
                   (unsigned)an->nonmanifold_edges, (unsigned)an->flipped_edges);
        return SNELL__FIT_RUNS;
    }
    if (an->depth_complexity <= 2) {
        snell__why(why, n, "closed, depth complexity %d: two surfaces, which two-sided methods serve for less",
                   an->depth_complexity);
        return SNELL__FIT_RUNS;
    }
    snell__why(why, n, "closed, depth complexity %d (%.0f%% of sampled lines cross more than 2 surfaces): "
                       "layers between them", an->depth_complexity, 100.0f * an->deep_fraction);
    return SNELL__FIT_ADEQUATE;
}

static const char *const g_fix_names[] = {"default", "none", "discontinuity", "merge", "both"};
static const char *const g_layer0_names[] = {"gbuffer", "peel"};

static const snell_param_info g_params[] = {
    {.name = "layers",
     .offset = offsetof(snell_glass_material, peel.layers),
     .help = "depth layers peeled (front and back faces alternate; fewer where the mesh needs fewer)",
     .min = 2, .max = SNELL_PEEL_MAX_LAYERS, .def = DEFAULT_LAYERS},
    {.name = "linear_steps",
     .offset = offsetof(snell_glass_material, peel.linear_steps),
     .help = "linear search steps over the bounding diameter (0: the default)",
     .min = 0, .max = 128, .def = DEFAULT_LINEAR},
    {.name = "binary_steps",
     .offset = offsetof(snell_glass_material, peel.binary_steps),
     .help = "binary refinement steps after a linear crossing",
     .min = 1, .max = 16, .def = DEFAULT_BINARY},
    {.name = "max_interfaces",
     .offset = offsetof(snell_glass_material, peel.max_interfaces),
     .help = "surfaces processed per path (1 = single surface; exits, re-entries, TIR bounces)",
     .min = 1, .max = SNELL_PEEL_MAX_INTERFACES, .def = DEFAULT_INTERFACES},
    {.name = "fixes",
     .offset = offsetof(snell_glass_material, peel.fixes),
     .help = "the seed's search fixes (3.5): none, discontinuity, merge or both",
     .min = 0, .max = 4, .def = SNELL_PEEL_FIXES_BOTH, .value_names = g_fix_names},
    {.name = "fresnel",
     .offset = offsetof(snell_glass_material, peel.fresnel),
     .help = "reflectance at the interfaces: schlick (the MATCHED model) or exact (unpolarised, as FULL)",
     .min = 0, .max = 2, .def = DEFAULT_FRESNEL == 1 ? SNELL_FRESNEL_EXACT : SNELL_FRESNEL_SCHLICK, .value_names = snell__fresnel_names},
    {.name = "inner_fresnel",
     .offset = offsetof(snell_glass_material, peel.inner_fresnel),
     .help = "Fresnel at the last exit too (1 - F out, the internal reflection followed by one more search): auto (on), off, on",
     .min = 0, .max = 2, .def = SNELL_INNER_FRESNEL_AUTO, .value_names = snell__inner_fresnel_names},
    {.name = "layer0",
     .offset = offsetof(snell_glass_material, peel.layer0),
     .help = "the front layer: gbuffer (converted from the screen-space G-buffer where it holds the whole front surface, the peels are culled and the triangles are below 16 px; else peeled) or peel (always peeled)",
     .min = 0, .max = 1, .def = SNELL_PEEL_LAYER0_GBUFFER, .value_names = g_layer0_names},
};


static const snell_counter_info g_counters[] = {
    {"layers_peeled", "depth layers drawn this frame (at most peel.layers, fewer where the mesh's depth complexity "
                      "bounds them, or one more than layers_found where those peels were not all full)"},
    {"layers_found", "non-empty layers found by the object's last peels whose occlusion queries were read "
                     "(a frame or more ago: never waited for); -1 before the first"},
    {"layer0_gbuffer", "1: layer 0 was converted from the G-buffer (peel.layer0), 0: peeled"},
};

/* Its cap goes on through re-entries as FULL's dominant branch does, where
 * MATCHED stops at the first exit: snell-bench measures it against FULL too. */
static const snell_method_info g_info = {
    .method = SNELL_METHOD_PEEL,
    .name = "peel",
    .summary = "multi-layer in image space: depth-peeled layers, ray-height-field search between them, TIR (Wang 2014)",
    .needs = "a closed mesh of depth complexity above 2 (concave); per object and frame a few depth peels",
    .param_count = (int)(sizeof g_params / sizeof *g_params),
    .params = g_params,
    .counter_count = (int)(sizeof g_counters / sizeof *g_counters),
    .counters = g_counters,
    .ref_interfaces = 0,
    .ref_chord_absorption = 0,
    .default_sweep = "linear_steps=8,16",
}; /* layers and fixes: bench/BENCHMARKS.md */

/* AUTO by budget's rungs (frame/method.h): method, parameter, value; frame
 * time over single's and glass PSNR vs FULL for a convex, a bunny-like, a
 * torus-like and an open mesh; resolution scale (bench/notes/budget_rungs.md). */
static const snell_budget_rung g_rungs[] = {
    {SNELL_METHOD_PEEL, "layers", 2, {7.94f, 3.58f, 5.89f, 3.62f}, {40.32f, 21.88f, 22.70f, 20.71f}, 1, NULL},
    {SNELL_METHOD_PEEL, NULL, 0, {8.03f, 5.89f, 8.43f, 5.56f}, {40.32f, 22.47f, 26.42f, 21.65f}, 1, NULL},
    {SNELL_METHOD_PEEL, "layers", 2, {4.73f, 4.06f, 4.22f, 3.42f}, {34.25f, 19.10f, 22.02f, 18.56f}, 2, NULL},
    {SNELL_METHOD_PEEL, NULL, 0, {4.63f, 5.43f, 5.21f, 4.38f}, {34.25f, 19.30f, 24.16f, 18.86f}, 2, NULL},
    {SNELL_METHOD_PEEL, "layers", 2, {3.53f, 3.44f, 3.12f, 2.66f}, {27.22f, 17.10f, 20.65f, 16.77f}, 4, NULL},
    {SNELL_METHOD_PEEL, NULL, 0, {3.42f, 4.96f, 3.86f, 3.50f}, {27.22f, 17.25f, 21.58f, 16.80f}, 4, NULL},
};

const snell__method snell__method_peel = {
    .info = &g_info,
    .needs_analysis = 1,
    .fit = peel_fit,
    .create = peel_create,
    .destroy = peel_destroy,
    .draw = peel_draw,
    .software_screen_ppt = PEEL_SOFTWARE_SCREEN_PPT,
    .rungs = g_rungs,
    .rung_count = (int)(sizeof g_rungs / sizeof *g_rungs),
};
