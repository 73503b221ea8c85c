/* method_cubemap.c — two-sided refraction with a normal+distance cubemap
 * (Li et al. 2007 as in Unger 4.1): per mesh version, analyze (centre, hidden
 * fraction; mesh_analyze.c) and bake (ndcube.c); per frame one pass of the
 * search shader (cubemap.frag) over the front faces. The per-mesh cache lives here, in the
 * method state (a few entries, least recently used replaced), and so do the
 * search programs: one per (encoding, iterations, linear steps, search or
 * none), because the step counts are compile-time constants of the shader
 * (cubemap.frag says why); the default one is built with the method, others
 * on first use. */
#include "render/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "methods/ndcube.h"
#include "core/program.h"

#include <math.h>
#include <string.h>

#define CACHE_SIZE 4
#define PROG_CACHE 8

/* Defaults of the glass desc's cubemap fields (snell.h documents them). */
/* encoding: PLAIN (filtered: lower error than OCT, which is 3-7% cheaper on llvmpipe) */

typedef struct cube_prog {
    snell__glass_program g;    /* g.prog == 0: empty slot */
    snell_ndcube_encoding enc;
    int iterations, linear, no_search;
    unsigned long last_use;
    int ndcube, inv_model, centre, radius, inner_radius, max_interfaces, texel_angle, absorb;
} cube_prog;

/* One mesh's analysis and baked cubemap. The key is the mesh pointer and
 * version plus counts, bounds and the positions pointer, so a destroyed mesh
 * whose address is reused by a new one is recognised unless all of these
 * coincide (see the report: a process-unique mesh id would make it exact). */
typedef struct cache_entry {
    const snell_mesh *mesh;
    unsigned version;
    uint32_t nv, nt;
    const float *positions;
    float bmin[3], bmax[3];
    snell_mesh_analysis an;
    snell__ndcube cube;
    int baked;                 /* cube holds the current version */
    unsigned long last_use;
} cache_entry;

typedef struct cubemap_state {
    snell__output_kind out;
    cube_prog prog[PROG_CACHE];
    snell__ndcube_baker baker;
    cache_entry cache[CACHE_SIZE];
    unsigned long clock;
} cubemap_state;

static void cubemap_destroy(snell_ctx *ctx, void *state);

static snell_status build_prog(snell_ctx *ctx, snell__output_kind out, snell_ndcube_encoding enc, int iterations,
                               int linear, int no_search, cube_prog *p)
{
    char def[200];
    snell_status st;
    snprintf(def, sizeof def,
             "#define SNELL_NDCUBE_%s 1\n#define SNELL_SEARCH_ITERATIONS %d\n#define SNELL_LINEAR_STEPS %d\n"
             "#define SNELL_NO_SEARCH %d\n",
             enc == SNELL_NDCUBE_OCT ? "OCT" : "PLAIN", iterations, linear, no_search);
    st = snell__glass_program_build(ctx, "cubemap.frag", out, def, &p->g);
    if (st != SNELL_OK) return st;
    p->enc = enc;
    p->iterations = iterations;
    p->linear = linear;
    p->no_search = no_search;
    p->ndcube = glGetUniformLocation(p->g.prog, "u_ndcube");
    p->inv_model = glGetUniformLocation(p->g.prog, "u_inv_model");
    p->centre = glGetUniformLocation(p->g.prog, "u_centre");
    p->radius = glGetUniformLocation(p->g.prog, "u_radius");
    p->inner_radius = glGetUniformLocation(p->g.prog, "u_inner_radius");
    p->max_interfaces = glGetUniformLocation(p->g.prog, "u_max_interfaces");
    p->texel_angle = glGetUniformLocation(p->g.prog, "u_texel_angle");
    p->absorb = glGetUniformLocation(p->g.prog, "u_absorb");
    return SNELL_OK;
}

/* The program of these settings: cached, else built into the least recently
 * used slot. */
static snell_status get_prog(snell_ctx *ctx, cubemap_state *s, snell_ndcube_encoding enc, int iterations, int linear,
                             int no_search, const cube_prog **out)
{
    cube_prog *p = &s->prog[0];
    snell_status st;
    int i;
    s->clock++;
    for (i = 0; i < PROG_CACHE; i++) {
        cube_prog *c = &s->prog[i];
        if (c->g.prog && c->enc == enc && c->iterations == iterations && c->linear == linear &&
            c->no_search == no_search) {
            c->last_use = s->clock;
            *out = c;
            return SNELL_OK;
        }
        if (!c->g.prog || (p->g.prog && c->last_use < p->last_use)) p = c;
    }
    snell__glass_program_destroy(&p->g);
    st = build_prog(ctx, s->out, enc, iterations, linear, no_search, p);
    if (st != SNELL_OK) return st;
    p->last_use = s->clock;
    *out = p;
    return SNELL_OK;
}

static snell_status cubemap_create(snell_ctx *ctx, snell__output_kind out, void **state)
{
    cubemap_state *s = (cubemap_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    const cube_prog *p;
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    s->out = out;
    st = get_prog(ctx, s, SNELL_NDCUBE_PLAIN, SNELL_CUBEMAP_DEFAULT_ITERATIONS, 0, 0, &p);
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
    int i;
    if (!s) return;
    for (i = 0; i < PROG_CACHE; i++) snell__glass_program_destroy(&s->prog[i].g);
    snell__ndcube_baker_destroy(&s->baker);
    for (i = 0; i < CACHE_SIZE; i++) snell__ndcube_release(&s->cache[i].cube);
    snell__free(&ctx->alloc, s);
}

static int entry_matches(const cache_entry *e, const snell_mesh *m)
{
    return e->mesh == m && e->version == m->version && e->nv == m->vertex_count && e->nt == m->triangle_count &&
           e->positions == m->positions && !memcmp(e->bmin, m->bmin, sizeof e->bmin) &&
           !memcmp(e->bmax, m->bmax, sizeof e->bmax);
}

/* The cache entry of the mesh's current version, analysed (not yet baked). */
static snell_status get_entry(cubemap_state *s, const snell_mesh *m, cache_entry **out)
{
    cache_entry *e = NULL;
    snell_status st;
    int i;
    s->clock++;
    for (i = 0; i < CACHE_SIZE; i++)
        if (entry_matches(&s->cache[i], m)) {
            e = &s->cache[i];
            e->last_use = s->clock;
            *out = e;
            return SNELL_OK;
        }
    /* Same mesh, new version (deformed): reuse its slot and texture; else the
     * least recently used slot. */
    for (i = 0; i < CACHE_SIZE && !e; i++)
        if (s->cache[i].mesh == m) e = &s->cache[i];
    if (!e) {
        e = &s->cache[0];
        for (i = 1; i < CACHE_SIZE; i++)
            if (s->cache[i].last_use < e->last_use) e = &s->cache[i];
    }
    e->mesh = NULL;
    e->baked = 0;
    st = snell_mesh_analyze(m, &e->an);
    if (st != SNELL_OK) return st;
    e->mesh = m;
    e->version = m->version;
    e->nv = m->vertex_count;
    e->nt = m->triangle_count;
    e->positions = m->positions;
    memcpy(e->bmin, m->bmin, sizeof e->bmin);
    memcpy(e->bmax, m->bmax, sizeof e->bmax);
    e->last_use = s->clock;
    *out = e;
    return SNELL_OK;
}

snell_status snell__cubemap_analysis(snell_ctx *ctx, void *method_state, const snell_mesh *mesh,
                                     const snell_mesh_analysis **out)
{
    cache_entry *e;
    snell_status st;
    if (!method_state || !mesh || !out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "cubemap analysis: NULL argument");
    st = get_entry((cubemap_state *)method_state, mesh, &e);
    if (st != SNELL_OK) return st;
    *out = &e->an;
    return SNELL_OK;
}

static snell_status cubemap_draw(snell_ctx *ctx, void *state, const snell__frame *f, snell_frame_stats *stats)
{
    cubemap_state *s = (cubemap_state *)state;
    const snell_glass_desc *g = &f->desc->glass;
    int iterations = g->search_iterations ? g->search_iterations : SNELL_CUBEMAP_DEFAULT_ITERATIONS;
    int max_if = g->max_interfaces ? g->max_interfaces : SNELL_CUBEMAP_DEFAULT_INTERFACES;
    int face = g->cube_face_size ? g->cube_face_size : SNELL_CUBEMAP_DEFAULT_FACE_SIZE;
    int absorb = g->absorption[0] > 0.0f || g->absorption[1] > 0.0f || g->absorption[2] > 0.0f;
    snell_ndcube_encoding enc = g->encoding == SNELL_NDCUBE_DEFAULT ? SNELL_NDCUBE_PLAIN : g->encoding;
    const cube_prog *p;
    cache_entry *e;
    snell_status st;
    mat4 inv_model;
    /* 1e-4 margin: the farthest vertex stays strictly inside the cube's range. */
    float radius;

    st = get_entry(s, f->mesh, &e);
    if (st == SNELL_OK) st = get_prog(ctx, s, enc, iterations, g->linear_steps, max_if == 1 && !absorb, &p);
    if (st != SNELL_OK) return st;
    stats->hidden_fraction = e->an.hidden_fraction;
    radius = e->an.radius * 1.0001f;
    if (!e->baked || e->cube.face_size != face || e->cube.encoding != enc) {
        GLint fbo = 0, vp[4];
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
        glGetIntegerv(GL_VIEWPORT, vp);
        st = snell__ndcube_bake(ctx, &s->baker, f->mesh, e->an.centre, radius, face, enc, &e->cube);
        glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
        glViewport(vp[0], vp[1], vp[2], vp[3]);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glActiveTexture(GL_TEXTURE0);
        if (st != SNELL_OK) return st;
        e->baked = 1;
        stats->ndcube_baked = 1;
        stats->passes += 6;
    }

    /* Back faces culled on closed meshes (snell__cull_back_faces). A depth
     * pre-pass would do the same for any mesh but cost more than it saved: it
     * doubles the triangle setup, which dominates on llvmpipe for the
     * 69k-triangle bunny (bench/BENCHMARKS.md). */
    snell__cull_back_faces(f);

    glm_mat4_inv((vec4 *)f->model, inv_model);
    snell__glass_program_use(&p->g, f);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_CUBE_MAP, e->cube.texture);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(p->ndcube, 1);
    glUniformMatrix4fv(p->inv_model, 1, GL_FALSE, (const GLfloat *)inv_model);
    glUniform3fv(p->centre, 1, e->cube.centre);
    glUniform1f(p->radius, e->cube.radius);
    /* The inner ball is surely inside only if the centre is; one 8-bit
     * distance step below its radius, as stored distances are rounded to that
     * step (the 16-bit OCT ones far finer). */
    glUniform1f(p->inner_radius, e->an.inside ? fmaxf(e->an.inner_radius - e->cube.radius / 255.0f, 0.0f) : 0.0f);
    glUniform1i(p->max_interfaces, max_if);
    /* A texel is 2/N wide in face coordinates; it subtends 2/N rad at a face
     * centre and sqrt(2)/3 * 2/N at a corner: the smaller is the stop bound. */
    glUniform1f(p->texel_angle, (float)(2.0 * sqrt(2.0) / 3.0) / (float)face);
    glUniform1i(p->absorb, absorb);
    snell__draw_mesh(f);
    glDisable(GL_CULL_FACE);
    stats->passes++;
    return SNELL_OK;
}

const snell__method snell__method_cubemap = {SNELL_METHOD_CUBEMAP, "cubemap", cubemap_create, cubemap_destroy,
                                             cubemap_draw};
