/* SPDX-License-Identifier: MIT */
/* exact.c — exact refraction by ray traversal of the mesh's BVH in the
 * fragment shader (exact.frag): the MATCHED reference's model (ref_trace.c)
 * on the GPU. Prepared per mesh version: the reference tracer's SAH build
 * (mesh/bvh.c, object space; refitted for later versions) flattened into depth-first order with an
 * escape index per node (so the shader can walk it near-first with a short
 * stack, the default, or without any stack: the `walk` parameter), and packed
 * with the triangles (vertices and vertex normals, leaf order) into one 2D
 * texture read with texelFetch (core GLES 3.0). Per frame one pass over the
 * front faces; each pixel's node visits are capped by a compile-time budget,
 * past which it takes the single-surface answer (counted in
 * the fallback_pixels counter (snell_object_stats.counters) on RGBA32F exit-direction
 * renderers). A deformed mesh (snell_mesh_set_vertices: a new version) is
 * refitted, not rebuilt: see exact_prepare. */
#include "methods/exact.h"
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "mesh/bvh.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define DEFAULT_INTERFACES 8
#define DEFAULT_BUDGET 4096
#define PROG_CACHE 8
/* Texels per row of the BVH texture (exact.frag's TEX_SHIFT): GLES 3.0's
 * smallest GL_MAX_TEXTURE_SIZE, so every device takes the width. */
#define TEX_WIDTH 2048
/* mesh/bvh.c's MAX_LEAF (leaves hold 1..4 triangles; more only if its build
 * changes: prepare then fails with a message rather than drop triangles). */
#define LEAF_MAX 4
/* Node indices are stored as float values in the RGBA32F layout: exact below 2^24. */
#define F32_INDEX_LIMIT (1u << 24)

/* How node bounds are stored (the `nodes` parameter). */
enum { NODES_DEFAULT = 0, NODES_F32, NODES_Q16 };
/* How the tree is walked (the `walk` parameter): near-first with a short
 * stack is the faster (bench/BENCHMARKS.md "Exact"): it visits the nearer
 * child first, so the closest hit shortens the ray sooner. The stackless walk needs no per-pixel array and has no depth
 * bound (drei's 60-entry stack is what mobile GPUs choked on). */
enum { WALK_DEFAULT = 0, WALK_STACKLESS, WALK_STACK };

/* llvmpipe: per-pixel traversal costs so much more than the G-buffer pass
 * that full 4x4 blocks win at every density, as for the cubemap
 * (bench/BENCHMARKS.md, "Exact"). */
#define EXACT_SOFTWARE_SCREEN_PPT 1e9f

/* A node in depth-first order: a leaf's entries, or an interior node's
 * escape (the node after its subtree; its first child is the next node). */
typedef struct flat_node {
    uint32_t escape;           /* every node: where the walk goes on a miss */
    uint32_t first, count;     /* a leaf: its leaf-order entries; count 0: interior */
} flat_node;

/* One mesh's flattened BVH (the prepared resource), with what a refit needs:
 * the tree's shape and the CPU copy of the texture. */
typedef struct exact_prepared {
    snell_alloc alloc;         /* release() has no context */
    unsigned texture;          /* RGBA32F (f32 nodes) or RGBA32UI (q16 nodes), TEX_WIDTH wide */
    int format;                /* NODES_F32 or NODES_Q16 */
    int node_count;
    int tri_base;              /* texel of the first triangle entry */
    int rows;                  /* of the texture */
    int builds, refits;        /* SAH builds and refits this resource has had */
    float qlo[3], qstep[3];    /* NODES_Q16: bound = qlo + q * qstep (object space) */
    uint32_t triangle_count;
    flat_node *nodes;          /* node_count, depth-first */
    double *boxes;             /* 6 per node: lo, hi (object space) */
    uint32_t *tri_ids;         /* leaf order -> the mesh's triangle */
    void *texels;              /* rows * TEX_WIDTH texels of 16 bytes */
} exact_prepared;

typedef struct exact_prog {
    snell__program_slot slot; /* key: budget, q16, absorb, variant (snell__glass_variant), stack walk */
    int inv_model, node_count, tri_base, max_interfaces, eps, qlo, qstep, mark, cam_basis, cam_proj, pixel_to_ndc;
} exact_prog;

typedef struct exact_state {
    snell__output_kind out;
    exact_prog prog[PROG_CACHE];
    unsigned long clock;
    float *readback;           /* RGBA32F exit-direction renderers: the object's rectangle, to count fallbacks */
    size_t readback_size;      /* floats */
} exact_state;

static void exact_destroy(snell_ctx *ctx, void *state);

static snell_status get_prog(snell_ctx *ctx, exact_state *s, int budget, int q16, int absorb, int variant,
                             int stack, int dispersion, const exact_prog **out)
{
    const int key[6] = {budget, q16, absorb, variant, stack, dispersion};
    char def[192];
    int hit;
    exact_prog *p = (exact_prog *)snell__program_cache_get(s->prog, sizeof *s->prog, PROG_CACHE, key, 6, &s->clock, &hit);
    snell_status st;
    if (hit) {
        *out = p;
        return SNELL_OK;
    }
    snprintf(def, sizeof def,
             "#define SNELL_NODE_BUDGET %d\n#define SNELL_NODES_Q16 %d\n#define SNELL_ABSORB %d\n#define SNELL_STACK_WALK %d\n"
             "#define SNELL_DISPERSION %d\n",
             budget, q16, absorb, stack, dispersion);
    st = snell__glass_program_build(ctx, "exact.frag", s->out, def, variant, &p->slot.g);
    if (st != SNELL_OK) return st;
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
    st = get_prog(ctx, s, DEFAULT_BUDGET, 0, 0, 0, 1, 0, &p);
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
    exact_prepared *p;
    uint32_t next;
} flat_ctx;

/* Depth-first (pre-order) numbering of the build's tree: a node's first
 * child follows it, and its escape is where the walk goes when the ray
 * misses it (or is done with a leaf): the next node after its subtree.
 * Recursion is bounded by the tree's depth (mesh/bvh.c keeps it below 128). */
static void flatten(flat_ctx *f, uint32_t node)
{
    const snell__bvh_node *n = &f->bvh->nodes[node];
    uint32_t at = f->next++;
    int k;
    for (k = 0; k < 3; k++) {
        f->p->boxes[6 * (size_t)at + k] = n->bmin[k];
        f->p->boxes[6 * (size_t)at + 3 + k] = n->bmax[k];
    }
    f->p->nodes[at].first = n->count ? n->index : 0;
    f->p->nodes[at].count = n->count;
    if (!n->count) {
        flatten(f, n->index);
        flatten(f, n->index + 1);
    }
    f->p->nodes[at].escape = f->next;
}

/* Refit: every box again from the moved vertices, children before parents
 * (reverse depth-first order: an interior node's children are the next
 * node and that one's escape), padded as mesh/bvh.c pads. */
static void refit_boxes(exact_prepared *p, const snell_mesh *mesh)
{
    double ext = 0.0, pad;
    int i, k;
    for (i = p->node_count - 1; i >= 0; i--) {
        const flat_node *n = &p->nodes[i];
        double *b = p->boxes + 6 * (size_t)i;
        for (k = 0; k < 3; k++) {
            b[k] = HUGE_VAL;
            b[3 + k] = -HUGE_VAL;
        }
        if (n->count) {
            uint32_t e, j;
            for (e = n->first; e < n->first + n->count; e++)
                for (j = 0; j < 3; j++) {
                    const float *v = mesh->positions + 3 * (size_t)mesh->indices[3 * (size_t)p->tri_ids[e] + j];
                    for (k = 0; k < 3; k++) {
                        b[k] = fmin(b[k], (double)v[k]);
                        b[3 + k] = fmax(b[3 + k], (double)v[k]);
                    }
                }
        } else {
            const double *c0 = p->boxes + 6 * (size_t)(i + 1), *c1 = p->boxes + 6 * (size_t)p->nodes[i + 1].escape;
            for (k = 0; k < 3; k++) {
                b[k] = fmin(c0[k], c1[k]);
                b[3 + k] = fmax(c0[3 + k], c1[3 + k]);
            }
        }
    }
    for (k = 0; k < 6; k++) ext = fmax(ext, fabs(p->boxes[k]));
    pad = 1e-10 * (ext > 0.0 ? ext : 1.0);
    for (i = 0; i < p->node_count; i++)
        for (k = 0; k < 3; k++) {
            p->boxes[6 * (size_t)i + k] -= pad;
            p->boxes[6 * (size_t)i + 3 + k] += pad;
        }
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
 * 6 texels: v0, v1, v2, n0, n1, n2 (object space; q16: the floats' bits), v0's w the
 * mesh's triangle index (a float: exact below 2^24). */
static void pack_texels(exact_prepared *p, const snell_mesh *mesh)
{
    float *tf = (float *)p->texels;
    uint32_t *tu = (uint32_t *)p->texels, i;
    const double *root = p->boxes;
    double lo[3], step[3], scale = 0.0;
    float pad;
    int k;
    /* the largest coordinate: float slab tests round at a few ulps of it */
    for (k = 0; k < 6; k++) scale = fmax(scale, fabs(root[k]));
    pad = (float)(1e-5 * scale);
    for (k = 0; k < 3; k++) {
        /* 65531 steps over the extent (a flat axis: 1e-6 of the scale), 2 more a side */
        step[k] = fmax(root[3 + k] - root[k], 1e-6 * scale + 1e-30) / 65531.0;
        lo[k] = root[k] - 2.0 * step[k];
        p->qlo[k] = (float)lo[k];
        p->qstep[k] = (float)step[k];
    }
    for (i = 0; i < (uint32_t)p->node_count; i++) {
        const flat_node *n = &p->nodes[i];
        const double *b = p->boxes + 6 * (size_t)i;
        if (p->format == NODES_F32) {
            float *t = tf + 8 * (size_t)i;
            for (k = 0; k < 3; k++) {
                t[k] = (float)b[k] - pad;
                t[4 + k] = (float)b[3 + k] + pad;
            }
            t[3] = (float)(n->count ? n->first : n->escape);
            t[7] = (float)n->count;
        } else {
            uint32_t *t = tu + 4 * (size_t)i, q[6];
            for (k = 0; k < 3; k++) {
                q[k] = quant(b[k], lo[k], step[k], 0);
                q[3 + k] = quant(b[3 + k], lo[k], step[k], 1);
            }
            t[0] = q[0] | q[1] << 16;
            t[1] = q[2] | q[3] << 16;
            t[2] = q[4] | q[5] << 16;
            t[3] = n->count ? 0x80000000u | n->first << 2 | (n->count - 1) : n->escape;
        }
    }
    for (i = 0; i < p->triangle_count; i++) {
        const uint32_t *tri = mesh->indices + 3 * (size_t)p->tri_ids[i];
        float v[24];
        int j;
        memset(v, 0, sizeof v);
        v[3] = (float)p->tri_ids[i]; /* the mesh's triangle, unread by exact (the caustics' chain: its object) */
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

static void free_arrays(exact_prepared *p)
{
    snell__free(&p->alloc, p->nodes);
    snell__free(&p->alloc, p->boxes);
    snell__free(&p->alloc, p->tri_ids);
    snell__free(&p->alloc, p->texels);
    p->nodes = NULL;
    p->boxes = NULL;
    p->tri_ids = NULL;
    p->texels = NULL;
}

/* The reference tracer's SAH build in object space (one BVH serves every
 * model matrix), flattened. */
static snell_status build(snell_ctx *ctx, const snell_mesh *mesh, int format, exact_prepared *p)
{
    snell__bvh *bvh = NULL;
    flat_ctx f;
    GLint max_size = 0;
    size_t texels_n, rows;
    uint32_t i;
    snell_status st = snell__bvh_build_mesh(ctx, mesh, NULL, &bvh);
    if (st != SNELL_OK) return st;
    for (i = 0; i < bvh->node_count; i++)
        if (bvh->nodes[i].count > LEAF_MAX) {
            st = snell__fail(ctx, SNELL_E_LIMIT, "exact: a BVH leaf holds %u triangles, the shader reads %d",
                             bvh->nodes[i].count, LEAF_MAX);
            goto out;
        }
    texels_n = (size_t)bvh->node_count * (format == NODES_F32 ? 2u : 1u) + 6 * (size_t)bvh->triangle_count;
    rows = (texels_n + TEX_WIDTH - 1) / TEX_WIDTH;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (rows > (size_t)max_size || (format == NODES_F32 && bvh->node_count >= F32_INDEX_LIMIT) ||
        bvh->triangle_count >= (1u << 29)) {
        st = snell__fail(ctx, SNELL_E_LIMIT, "exact: %u triangles need a %dx%zu BVH texture (at most %d rows here)",
                         bvh->triangle_count, TEX_WIDTH, rows, (int)max_size);
        goto out;
    }
    free_arrays(p);
    p->format = format;
    p->node_count = (int)bvh->node_count;
    p->triangle_count = bvh->triangle_count;
    p->tri_base = (int)(bvh->node_count * (format == NODES_F32 ? 2u : 1u));
    p->rows = (int)rows;
    p->nodes = (flat_node *)snell__calloc(&p->alloc, bvh->node_count, sizeof *p->nodes);
    p->boxes = (double *)snell__calloc(&p->alloc, 6 * (size_t)bvh->node_count, sizeof(double));
    p->tri_ids = (uint32_t *)snell__calloc(&p->alloc, bvh->triangle_count, sizeof(uint32_t));
    p->texels = snell__calloc(&p->alloc, rows * TEX_WIDTH, 16);
    if (!p->nodes || !p->boxes || !p->tri_ids || !p->texels) {
        free_arrays(p);
        st = snell__fail(ctx, SNELL_E_NOMEM, "exact: out of memory for a %u-node BVH", bvh->node_count);
        goto out;
    }
    memcpy(p->tri_ids, bvh->tri_ids, bvh->triangle_count * sizeof(uint32_t));
    f.bvh = bvh;
    f.p = p;
    f.next = 0;
    flatten(&f, 0);
    p->builds++;
    p->refits = 0;
out:
    snell__bvh_destroy(bvh);
    return st;
}

/* Built once per mesh, refitted for each new version of it: the prepared
 * cache hands a deformed mesh (snell_mesh_set_vertices: a new version, the
 * same triangles) the slot of its previous version, so the tree's shape is
 * here and only its boxes are recomputed (O(n), no SAH build: bunny 69k
 * triangles, bench/BENCHMARKS.md "Exact"); the splits stay those of the
 * first shape, which a large deformation makes worse to traverse, never
 * wrong. A new node format or triangle count builds again. */
static snell_status prepare_mesh(snell_ctx *ctx, exact_prepared *p, const snell_mesh *mesh, int format)
{
    const int refit = p->texture && p->nodes && p->format == format && p->triangle_count == mesh->triangle_count;
    snell__pixel_store unpack;
    snell_status st;
    p->alloc = ctx->alloc;
    if (refit) {
        refit_boxes(p, mesh);
        p->refits++;
    } else if ((st = build(ctx, mesh, format, p)) != SNELL_OK) {
        return st;
    }
    pack_texels(p, mesh);
    snell__pixel_unpack_begin(&unpack, 4);
    if (!refit) {
        if (p->texture) glDeleteTextures(1, &p->texture);
        glGenTextures(1, &p->texture);
        glBindTexture(GL_TEXTURE_2D, p->texture);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        if (p->format == NODES_F32)
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, TEX_WIDTH, p->rows, 0, GL_RGBA, GL_FLOAT, p->texels);
        else
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32UI, TEX_WIDTH, p->rows, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                         p->texels);
    } else {
        glBindTexture(GL_TEXTURE_2D, p->texture);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, TEX_WIDTH, p->rows, p->format == NODES_F32 ? GL_RGBA : GL_RGBA_INTEGER,
                        p->format == NODES_F32 ? GL_FLOAT : GL_UNSIGNED_INT, p->texels);
    }
    snell__pixel_unpack_end(&unpack);
    if (glGetError() != GL_NO_ERROR)
        return snell__fail(ctx, SNELL_E_GL, "exact: uploading a %dx%d BVH texture failed", TEX_WIDTH, p->rows);
    return SNELL_OK;
}

static snell_status exact_prepare(snell_ctx *ctx, void *state, const snell__object *o, void *prepared,
                                  snell_object_stats *stats)
{
    (void)state;
    (void)stats;
    return prepare_mesh(ctx, (exact_prepared *)prepared, o->mesh, o->glass->material.exact.node_format);
}

void snell__exact_bvh_of(const void *prepared, const snell_glass_material *m, snell__exact_bvh *out)
{
    const exact_prepared *p = (const exact_prepared *)prepared;
    out->texture = p->texture;
    out->q16 = p->format == NODES_Q16;
    out->node_count = p->node_count;
    out->tri_base = p->tri_base;
    out->qlo = p->qlo;
    out->qstep = p->qstep;
    out->stack = m->exact.walk == WALK_STACK;
}

static void exact_release(void *prepared)
{
    exact_prepared *p = (exact_prepared *)prepared;
    if (p->texture) glDeleteTextures(1, &p->texture);
    p->texture = 0;
    free_arrays(p);
    p->builds = p->refits = 0;
}

#if SNELL_WITH_CAUSTICS
snell_status snell__exact_bvh_make(snell_ctx *ctx, const snell_mesh *mesh, void **prepared, snell__exact_bvh *out)
{
    snell_glass_material stack;
    snell_status st;
    if (!*prepared && !(*prepared = snell__calloc(&ctx->alloc, 1, sizeof(exact_prepared))))
        return snell__fail(ctx, SNELL_E_NOMEM, "exact: out of memory");
    if ((st = prepare_mesh(ctx, (exact_prepared *)*prepared, mesh, NODES_F32)) != SNELL_OK) return st;
    memset(&stack, 0, sizeof stack);
    stack.exact.walk = WALK_STACK;
    snell__exact_bvh_of(*prepared, &stack, out);
    return SNELL_OK;
}

void snell__exact_bvh_free(void *prepared)
{
    exact_prepared *p = (exact_prepared *)prepared;
    if (!p) return;
    exact_release(p);
    snell__free(&p->alloc, p);
}
#endif

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
    /* Dispersion: always three traces (SNELL_DISPERSION 1), whatever the
     * material's model: exact is the accuracy ceiling, and one path would
     * give red and blue estimated exits where the traversal finds the true ones. */
    snell_status st = get_prog(ctx, s, e->node_budget, ep->format == NODES_Q16, o->glass->absorbs,
                                snell__glass_variant(o), e->walk == WALK_STACK, o->glass->disperses ? 1 : 0, &p);
    if (st != SNELL_OK) return st;
    snell__glass_program_use(&p->slot.g, v, o);
    snell__glass_program_bind(&p->slot.g, "u_bvh", GL_TEXTURE_2D, ep->texture, 0);
    glUniformMatrix4fv(p->inv_model, 1, GL_FALSE, (const GLfloat *)o->inv_model);
    glUniform1i(p->node_count, ep->node_count);
    glUniform1i(p->tri_base, ep->tri_base);
    glUniform1i(p->max_interfaces, e->max_interfaces);
    /* Secondary rays skip the triangle they start on, as the reference's do;
     * this minimum distance (world units, 1e-5 of the bounding radius; the
     * reference's is 1e-9 of its extent, in double) keeps them off the
     * neighbours of an edge they start on, within float rounding. */
    glUniform1f(p->eps, SNELL__EXACT_EPS(o->bsphere[3]));
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
        if (v->view_axis[3] > 0.5f)
            glUniform4f(p->cam_proj, v->proj[0][0], v->proj[1][1], -v->proj[3][0], -v->proj[3][1]);
        else
            glUniform4f(p->cam_proj, v->proj[0][0], v->proj[1][1], v->proj[2][0], v->proj[2][1]);
        glUniform2f(p->pixel_to_ndc, 2.0f / (float)v->width, 2.0f / (float)v->height);
    }
    snell__draw_surface(o, stats);
    stats->passes++;
    if (v->out == SNELL__OUT_DIR_FLOAT) return count_fallbacks(ctx, s, o, &stats->counters[0]);
    return SNELL_OK;
}

static const char *const g_nodes_names[] = {"default", "f32", "q16"};
static const char *const g_auto_names[] = {"default", "never", "allow"};
static const char *const g_walk_names[] = {"default", "stackless", "stack"};

static const snell_param_info g_params[] = {
    {"interfaces", "surfaces processed per path (1 = single surface with the exact path length; more = exit and "
     "TIR bounces), the MATCHED reference's cap", 1, SNELL_EXACT_MAX_INTERFACES, DEFAULT_INTERFACES, NULL},
    {"budget", "BVH nodes a pixel may visit over all its rays; past it the single-surface answer", SNELL_EXACT_MIN_BUDGET,
     SNELL_EXACT_MAX_BUDGET, DEFAULT_BUDGET, NULL},
    {"nodes", "node bounds: f32 (RGBA32F, 2 texels) or q16 (16-bit quantised, rounded outward, 1 RGBA32UI texel)", 0,
     2, NODES_F32, g_nodes_names},
    {"auto", "whether AUTO may pick it (where no cheaper method is adequate): never or allow", 0, 2,
     SNELL_EXACT_AUTO_NEVER, g_auto_names},
    {"walk", "traversal: stack (near-first, a 32-entry stack a pixel; deeper trees fall back) or stackless (escape "
     "indices: no stack, no depth bound, for GPUs where the stack spills)", 0, 2, WALK_STACK, g_walk_names},
};

static const size_t g_offsets[] = {
    offsetof(snell_glass_material, exact.max_interfaces), offsetof(snell_glass_material, exact.node_budget),
    offsetof(snell_glass_material, exact.node_format), offsetof(snell_glass_material, exact.auto_pick),
    offsetof(snell_glass_material, exact.walk)};

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
    SNELL_METHOD_EXACT, "exact",
    "exact: the mesh's BVH traversed per pixel (watertight triangles, TIR), the MATCHED reference on the GPU",
    "nothing (any mesh); AUTO only where material.exact.auto_pick allows", 7,
    (int)(sizeof g_params / sizeof *g_params), g_params, (int)(sizeof g_counters / sizeof *g_counters), g_counters,
    0, 0, ""};

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
