/* exact.c — exact refraction by ray traversal of the mesh's BVH in the
 * fragment shader (exact.frag): the MATCHED reference's model (ref_trace.c)
 * on the GPU. Prepared once per mesh version: the reference tracer's SAH
 * build (ref_bvh.c, object space) flattened into depth-first order with an
 * escape index per node, so the shader walks it without a stack, and packed
 * with the triangles (vertices and vertex normals, leaf order) into one 2D
 * texture read with texelFetch (core GLES 3.0). Per frame one pass over the
 * front faces; each pixel's node visits are capped by a compile-time budget,
 * past which it takes the single-surface answer (counted in
 * snell_object_stats.exact_fallback_pixels on RGBA32F exit-direction
 * renderers). A deformed mesh (snell_mesh_set_vertices: a new version) is
 * rebuilt, not refitted: see exact_prepare. */
#include "methods/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "ref/ref_bvh.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define DEFAULT_INTERFACES 8
#define DEFAULT_BUDGET 4096
#define PROG_CACHE 8
#define BVH_UNIT 1
/* Texels per row of the BVH texture (exact.frag's TEX_SHIFT): GLES 3.0's
 * smallest GL_MAX_TEXTURE_SIZE, so every device takes the width. */
#define TEX_WIDTH 2048
/* ref_bvh.c's MAX_LEAF (leaves hold 1..4 triangles; more only if its build
 * changes: prepare then fails with a message rather than drop triangles). */
#define LEAF_MAX 4
/* Node indices are stored as float values in the RGBA32F layout: exact below 2^24. */
#define F32_INDEX_LIMIT (1u << 24)

/* How node bounds are stored (the `nodes` parameter). */
enum { NODES_DEFAULT = 0, NODES_F32, NODES_Q16 };

/* llvmpipe: per-pixel traversal costs so much more than the G-buffer pass
 * that full 4x4 blocks win at every density (as for the cubemap). */
#define EXACT_SOFTWARE_SCREEN_PPT 1e9f

/* One mesh version's flattened BVH (the prepared resource). */
typedef struct exact_prepared {
    unsigned texture;          /* RGBA32F (f32 nodes) or RGBA32UI (q16 nodes), TEX_WIDTH wide */
    int format;                /* NODES_F32 or NODES_Q16 */
    int node_count;
    int tri_base;              /* texel of the first triangle entry */
    int depth;                 /* of the tree (root = 1): nothing in the traversal depends on it */
    float qlo[3], qstep[3];    /* NODES_Q16: bound = qlo + q * qstep (object space) */
} exact_prepared;

typedef struct exact_prog {
    snell__program_slot slot; /* key: budget, q16, absorb, screen */
    int bvh, inv_model, node_count, tri_base, max_interfaces, eps, qlo, qstep, mark, cam_basis, cam_proj, pixel_to_ndc;
} exact_prog;

typedef struct exact_state {
    snell__output_kind out;
    exact_prog prog[PROG_CACHE];
    unsigned long clock;
    float *readback;           /* RGBA32F exit-direction renderers: the object's rectangle, to count fallbacks */
    size_t readback_size;      /* floats */
} exact_state;

static void exact_destroy(snell_ctx *ctx, void *state);

static snell_status get_prog(snell_ctx *ctx, exact_state *s, int budget, int q16, int absorb, int screen,
                             const exact_prog **out)
{
    const int key[4] = {budget, q16, absorb, screen};
    char def[160];
    int hit;
    exact_prog *p = (exact_prog *)snell__program_cache_get(s->prog, sizeof *s->prog, PROG_CACHE, key, 4, &s->clock, &hit);
    snell_status st;
    if (hit) {
        *out = p;
        return SNELL_OK;
    }
    snprintf(def, sizeof def, "#define SNELL_NODE_BUDGET %d\n#define SNELL_NODES_Q16 %d\n#define SNELL_ABSORB %d\n",
             budget, q16, absorb);
    st = snell__glass_program_build(ctx, "exact.frag", s->out, def, screen, &p->slot.g);
    if (st != SNELL_OK) return st;
    p->bvh = glGetUniformLocation(p->slot.g.prog, "u_bvh");
    p->inv_model = glGetUniformLocation(p->slot.g.prog, "u_inv_model");
    p->node_count = glGetUniformLocation(p->slot.g.prog, "u_node_count");
    p->tri_base = glGetUniformLocation(p->slot.g.prog, "u_tri_base");
    p->max_interfaces = glGetUniformLocation(p->slot.g.prog, "u_max_interfaces");
    p->eps = glGetUniformLocation(p->slot.g.prog, "u_eps");
    p->qlo = glGetUniformLocation(p->slot.g.prog, "u_qlo");
    p->qstep = glGetUniformLocation(p->slot.g.prog, "u_qstep");
    p->mark = glGetUniformLocation(p->slot.g.prog, "u_fallback_mark");
    p->cam_basis = glGetUniformLocation(p->slot.g.prog, "u_cam_basis");
    p->cam_proj = glGetUniformLocation(p->slot.g.prog, "u_cam_proj");
    p->pixel_to_ndc = glGetUniformLocation(p->slot.g.prog, "u_pixel_to_ndc");
    *out = p;
    return SNELL_OK;
}

static snell_status exact_create(snell_ctx *ctx, snell__output_kind out, void **state)
{
    exact_state *s = (exact_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    const exact_prog *p;
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    s->out = out;
    st = get_prog(ctx, s, DEFAULT_BUDGET, 0, 0, 0, &p);
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
    int i;
    if (!s) return;
    for (i = 0; i < PROG_CACHE; i++) snell__glass_program_destroy(&s->prog[i].slot.g);
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

/* ------------------------------------------------------------- flatten */

typedef struct flat_ctx {
    const snell__bvh *bvh;
    uint32_t *order;           /* depth-first position -> node of the build */
    uint32_t *escape;          /* per depth-first position: the position after its subtree */
    uint32_t next;
} flat_ctx;

/* Depth-first (pre-order) numbering of the build's tree: a node's first
 * child follows it, and its escape is where the walk goes when the ray
 * misses it (or is done with a leaf): the next node after its subtree.
 * Recursion is bounded by the tree's depth (ref_bvh.c keeps it below 128). */
static void flatten(flat_ctx *f, uint32_t node)
{
    const snell__bvh_node *n = &f->bvh->nodes[node];
    uint32_t at = f->next++;
    f->order[at] = node;
    if (!n->count) {
        flatten(f, n->index);
        flatten(f, n->index + 1);
    }
    f->escape[at] = f->next;
}

static float fmax3(const double v[3])
{
    return (float)fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
}

/* Quantised 16-bit bounds, rounded outward: the frame is the root box grown
 * by two steps a side, each bound moves one more step out, so that float
 * rounding of qlo + q * qstep in the shader (far below a step) cannot pull
 * a box inside the triangles it holds. */
static uint32_t quant(double x, double lo, double step, int up)
{
    double q = up ? ceil((x - lo) / step) + 1.0 : floor((x - lo) / step) - 1.0;
    return q < 0.0 ? 0u : (q > 65535.0 ? 65535u : (uint32_t)q);
}

/* Writes the texture's texels: nodes (f32: 2 texels, lo + escape or first,
 * hi + count; q16: 1 texel, bounds as 6 x 16 bits + a word: interior the
 * escape, leaf 0x80000000 | first << 2 | count - 1), then per triangle entry
 * 6 texels: v0, v1, v2, n0, n1, n2 (object space; q16: the floats' bits). */
static void pack_texels(const snell__bvh *bvh, const snell_mesh *mesh, const flat_ctx *f, exact_prepared *p,
                        void *texels)
{
    float *tf = (float *)texels;
    uint32_t *tu = (uint32_t *)texels, i;
    double lo[3], step[3];
    int k;
    /* the largest coordinate: float slab tests round at a few ulps of it */
    const float scale = fmax3(bvh->bmin) > fmax3(bvh->bmax) ? fmax3(bvh->bmin) : fmax3(bvh->bmax);
    const float pad = 1e-5f * scale;
    for (k = 0; k < 3; k++) {
        /* 65531 steps over the extent (a flat axis: 1e-6 of the scale), 2 more a side */
        step[k] = fmax(bvh->bmax[k] - bvh->bmin[k], 1e-6 * scale + 1e-30) / 65531.0;
        lo[k] = bvh->bmin[k] - 2.0 * step[k];
        p->qlo[k] = (float)lo[k];
        p->qstep[k] = (float)step[k];
    }
    for (i = 0; i < bvh->node_count; i++) {
        const snell__bvh_node *n = &bvh->nodes[f->order[i]];
        if (p->format == NODES_F32) {
            float *t = tf + 8 * (size_t)i;
            for (k = 0; k < 3; k++) {
                t[k] = (float)n->bmin[k] - pad;
                t[4 + k] = (float)n->bmax[k] + pad;
            }
            t[3] = (float)(n->count ? n->index : f->escape[i]);
            t[7] = (float)n->count;
        } else {
            uint32_t *t = tu + 4 * (size_t)i, q[6];
            for (k = 0; k < 3; k++) {
                /* the node's bounds are the double ones, padded 1e-10 (ref_bvh.c) */
                q[k] = quant(n->bmin[k], lo[k], step[k], 0);
                q[3 + k] = quant(n->bmax[k], lo[k], step[k], 1);
            }
            t[0] = q[0] | q[1] << 16;
            t[1] = q[2] | q[3] << 16;
            t[2] = q[4] | q[5] << 16;
            t[3] = n->count ? 0x80000000u | n->index << 2 | (n->count - 1) : f->escape[i];
        }
    }
    for (i = 0; i < bvh->triangle_count; i++) {
        const uint32_t *tri = mesh->indices + 3 * (size_t)bvh->tri_ids[i];
        float v[24];
        int j;
        memset(v, 0, sizeof v);
        for (j = 0; j < 3; j++)
            for (k = 0; k < 3; k++) {
                v[4 * j + k] = mesh->positions[3 * (size_t)tri[j] + k];
                v[12 + 4 * j + k] = mesh->normals[3 * (size_t)tri[j] + k];
            }
        memcpy(p->format == NODES_F32 ? (void *)(tf + 4 * ((size_t)p->tri_base + 6 * (size_t)i))
                                      : (void *)(tu + 4 * ((size_t)p->tri_base + 6 * (size_t)i)),
               v, sizeof v);
    }
}

/* Builds with the reference tracer's SAH builder in object space (so one
 * BVH serves every model matrix), flattens, uploads. A deformed mesh is a new
 * version and is rebuilt from scratch: the SAH build of the 69k-triangle
 * bunny takes tens of milliseconds (bench/BENCHMARKS.md), and a refit would
 * keep a tree whose splits no longer suit the moved triangles. */
static snell_status exact_prepare(snell_ctx *ctx, void *state, const snell__object *o, void *prepared,
                                  snell_object_stats *stats)
{
    exact_prepared *p = (exact_prepared *)prepared;
    snell__bvh *bvh = NULL;
    flat_ctx f;
    void *texels = NULL;
    GLint max_size = 0;
    size_t texels_n, rows;
    uint32_t i;
    snell_status st;
    (void)state;
    (void)stats;
    memset(&f, 0, sizeof f);
    p->format = o->glass->material.exact.node_format;
    st = snell__bvh_build_mesh(ctx, o->mesh, NULL, &bvh);
    if (st != SNELL_OK) return st;
    for (i = 0; i < bvh->node_count; i++)
        if (bvh->nodes[i].count > LEAF_MAX) {
            st = snell__fail(ctx, SNELL_E_LIMIT, "exact: a BVH leaf holds %u triangles, the shader reads %d",
                             bvh->nodes[i].count, LEAF_MAX);
            goto out;
        }
    p->node_count = (int)bvh->node_count;
    p->depth = bvh->depth;
    p->tri_base = (int)(bvh->node_count * (p->format == NODES_F32 ? 2u : 1u));
    texels_n = (size_t)p->tri_base + 6 * (size_t)bvh->triangle_count;
    rows = (texels_n + TEX_WIDTH - 1) / TEX_WIDTH;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (rows > (size_t)max_size || (p->format == NODES_F32 && bvh->node_count >= F32_INDEX_LIMIT) ||
        bvh->triangle_count >= (1u << 29)) {
        st = snell__fail(ctx, SNELL_E_LIMIT, "exact: %u triangles need a %dx%zu BVH texture (at most %d rows here)",
                         bvh->triangle_count, TEX_WIDTH, rows, (int)max_size);
        goto out;
    }
    f.bvh = bvh;
    f.order = (uint32_t *)snell__calloc(&ctx->alloc, bvh->node_count, sizeof(uint32_t));
    f.escape = (uint32_t *)snell__calloc(&ctx->alloc, bvh->node_count, sizeof(uint32_t));
    texels = snell__calloc(&ctx->alloc, rows * TEX_WIDTH, 16);
    if (!f.order || !f.escape || !texels) {
        st = snell__fail(ctx, SNELL_E_NOMEM, "exact: out of memory for a %u-node BVH", bvh->node_count);
        goto out;
    }
    flatten(&f, 0);
    pack_texels(bvh, o->mesh, &f, p, texels);
    {
        snell__pixel_store unpack;
        snell__pixel_unpack_begin(&unpack, 4);
        glGenTextures(1, &p->texture);
        glActiveTexture(GL_TEXTURE0 + BVH_UNIT);
        glBindTexture(GL_TEXTURE_2D, p->texture);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        if (p->format == NODES_F32)
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, TEX_WIDTH, (GLsizei)rows, 0, GL_RGBA, GL_FLOAT, texels);
        else
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32UI, TEX_WIDTH, (GLsizei)rows, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                         texels);
        glActiveTexture(GL_TEXTURE0);
        snell__pixel_unpack_end(&unpack);
    }
    if (glGetError() != GL_NO_ERROR)
        st = snell__fail(ctx, SNELL_E_GL, "exact: uploading a %dx%zu BVH texture failed", TEX_WIDTH, rows);
out:
    snell__free(&ctx->alloc, texels);
    snell__free(&ctx->alloc, f.order);
    snell__free(&ctx->alloc, f.escape);
    snell__bvh_destroy(bvh);
    return st;
}

static void exact_release(void *prepared)
{
    exact_prepared *p = (exact_prepared *)prepared;
    if (p->texture) glDeleteTextures(1, &p->texture);
    p->texture = 0;
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

static snell_status exact_draw(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                               snell_object_stats *stats)
{
    exact_state *s = (exact_state *)state;
    const snell_exact_params *e = &o->glass->material.exact;
    const exact_prepared *ep = (const exact_prepared *)o->prepared;
    const exact_prog *p;
    snell_status st = get_prog(ctx, s, e->node_budget, ep->format == NODES_Q16, o->glass->absorbs, o->screen_space, &p);
    if (st != SNELL_OK) return st;
    snell__glass_program_use(&p->slot.g, v, o);
    glActiveTexture(GL_TEXTURE0 + BVH_UNIT);
    glBindTexture(GL_TEXTURE_2D, ep->texture);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(p->bvh, BVH_UNIT);
    glUniformMatrix4fv(p->inv_model, 1, GL_FALSE, (const GLfloat *)o->inv_model);
    glUniform1i(p->node_count, ep->node_count);
    glUniform1i(p->tri_base, ep->tri_base);
    glUniform1i(p->max_interfaces, e->max_interfaces);
    /* Secondary rays skip the triangle they start on, as the reference's do;
     * this minimum distance (world units, 1e-5 of the bounding radius; the
     * reference's is 1e-9 of its extent, in double) keeps them off the
     * neighbours of an edge they start on, within float rounding. */
    glUniform1f(p->eps, 1e-5f * o->bsphere[3]);
    glUniform3fv(p->qlo, 1, ep->qlo);
    glUniform3fv(p->qstep, 1, ep->qstep);
    glUniform1f(p->mark, -(float)(o->index + 1));
    {
        /* the eye rays (exact.frag main): view -> world rotation, projection terms */
        float basis[9];
        int i, j;
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) basis[3 * i + j] = v->view[j][i];
        glUniformMatrix3fv(p->cam_basis, 1, GL_FALSE, basis);
        glUniform4f(p->cam_proj, v->proj[0][0], v->proj[1][1], v->proj[2][0], v->proj[2][1]);
        glUniform2f(p->pixel_to_ndc, 2.0f / (float)v->width, 2.0f / (float)v->height);
    }
    snell__draw_surface(o, stats);
    stats->passes++;
    stats->exact_fallback_pixels = -1;
    if (v->out == SNELL__OUT_DIR_FLOAT) return count_fallbacks(ctx, s, o, &stats->exact_fallback_pixels);
    return SNELL_OK;
}

static const char *const g_nodes_names[] = {"default", "f32", "q16"};
static const char *const g_auto_names[] = {"default", "never", "allow"};

static const snell_param_info g_params[] = {
    {"interfaces", "surfaces processed per path (1 = single surface with the exact path length; more = exit and "
     "TIR bounces), the MATCHED reference's cap", 1, SNELL_EXACT_MAX_INTERFACES, DEFAULT_INTERFACES, NULL},
    {"budget", "BVH nodes a pixel may visit over all its rays; past it the single-surface answer", SNELL_EXACT_MIN_BUDGET,
     SNELL_EXACT_MAX_BUDGET, DEFAULT_BUDGET, NULL},
    {"nodes", "node bounds: f32 (RGBA32F, 2 texels) or q16 (16-bit quantised, rounded outward, 1 RGBA32UI texel)", 0,
     2, NODES_F32, g_nodes_names},
    {"auto", "whether AUTO may pick it (where no cheaper method is adequate): never or allow", 0, 2,
     SNELL_EXACT_AUTO_NEVER, g_auto_names},
};

static const size_t g_offsets[] = {
    offsetof(snell_glass_material, exact.max_interfaces), offsetof(snell_glass_material, exact.node_budget),
    offsetof(snell_glass_material, exact.node_format), offsetof(snell_glass_material, exact.auto_pick)};

static const snell_method_info g_info = {
    SNELL_METHOD_EXACT, "exact",
    "exact: the mesh's BVH traversed per pixel (watertight triangles, TIR), the MATCHED reference on the GPU",
    "nothing (any mesh); AUTO only where material.exact.auto_pick allows", 6,
    (int)(sizeof g_params / sizeof *g_params), g_params};

const snell__method snell__method_exact = {
    .info = &g_info,
    .param_offsets = g_offsets,
    .fit = exact_fit,
    .create = exact_create,
    .destroy = exact_destroy,
    .prepared_size = sizeof(exact_prepared),
    .key = exact_key,
    .prepare = exact_prepare,
    .release = exact_release,
    .draw = exact_draw,
    .software_screen_ppt = EXACT_SOFTWARE_SCREEN_PPT,
};
