/* SPDX-License-Identifier: MIT */
/* bvh_gpu.c — the triangle BVH on the GPU (see bvh_gpu.h): the reference
 * tracer's SAH build (bvh.c, object space) flattened into depth-first order
 * with an escape index per node (so a shader can walk it near-first with a
 * short stack or without any stack, common/bvh.glsl), packed with the
 * triangles (vertices and vertex normals, leaf order) into one 2D texture
 * read with texelFetch (core GLES 3.0). */
#include "mesh/bvh_gpu.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "mesh/bvh.h"

#include <math.h>
#include <string.h>

#if SNELL__GPU_BVH

#define TEX_WIDTH SNELL__GPU_BVH_WIDTH
/* mesh/bvh.c's MAX_LEAF (leaves hold 1..4 triangles; more only if its build
 * changes: prepare then fails with a message rather than drop triangles). */
#define LEAF_MAX 4
/* Node indices are stored as float values in the RGBA32F layout: exact below 2^24. */
#define F32_INDEX_LIMIT (1u << 24)

typedef struct flat_node {
    uint32_t escape;           /* every node: where the walk goes on a miss */
    uint32_t first, count;     /* a leaf: its leaf-order entries; count 0: interior */
} flat_node;

/* One mesh's flattened BVH, with what a refit needs: the tree's shape and
 * the CPU copy of the texture. */
typedef struct bvh_data {
    snell_alloc alloc;         /* freed without a context */
    unsigned version;          /* the mesh version it holds */
    unsigned texture;          /* RGBA32F (f32 nodes) or RGBA32UI (q16 nodes), TEX_WIDTH wide */
    int format;                /* SNELL_EXACT_NODES_F32 or SNELL_EXACT_NODES_Q16 */
    int node_count;
    int tri_base;              /* texel of the first triangle entry */
    int rows;                  /* of the texture */
    int builds, refits;        /* SAH builds and refits this resource has had */
    float qlo[3], qstep[3];    /* SNELL_EXACT_NODES_Q16: bound = qlo + q * qstep (object space) */
    uint32_t triangle_count;
    flat_node *nodes;          /* node_count, depth-first */
    double *boxes;             /* 6 per node: lo, hi (object space) */
    uint32_t *tri_ids;         /* leaf order -> the mesh's triangle */
    void *texels;              /* rows * TEX_WIDTH texels of 16 bytes */
} bvh_data;

typedef struct flat_ctx {
    const snell__bvh *bvh;
    bvh_data *p;
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
static void refit_boxes(bvh_data *p, const snell_mesh *mesh)
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
static void pack_texels(bvh_data *p, const snell_mesh *mesh)
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
        if (p->format == SNELL_EXACT_NODES_F32) {
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
        memcpy(p->format == SNELL_EXACT_NODES_F32 ? (void *)(tf + 4 * ((size_t)p->tri_base + 6 * (size_t)i))
                                      : (void *)(tu + 4 * ((size_t)p->tri_base + 6 * (size_t)i)),
               v, sizeof v);
    }
}

static void free_arrays(bvh_data *p)
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
static snell_status build(snell_ctx *ctx, const snell_mesh *mesh, int format, bvh_data *p)
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
            st = snell__fail(ctx, SNELL_E_LIMIT, "BVH: a BVH leaf holds %u triangles, the shader reads %d",
                             bvh->nodes[i].count, LEAF_MAX);
            goto out;
        }
    texels_n = (size_t)bvh->node_count * (format == SNELL_EXACT_NODES_F32 ? 2u : 1u) + 6 * (size_t)bvh->triangle_count;
    rows = (texels_n + TEX_WIDTH - 1) / TEX_WIDTH;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (rows > (size_t)max_size || (format == SNELL_EXACT_NODES_F32 && bvh->node_count >= F32_INDEX_LIMIT) ||
        bvh->triangle_count >= (1u << 29)) {
        st = snell__fail(ctx, SNELL_E_LIMIT, "BVH: %u triangles need a %dx%zu BVH texture (at most %d rows here)",
                         bvh->triangle_count, TEX_WIDTH, rows, (int)max_size);
        goto out;
    }
    free_arrays(p);
    p->format = format;
    p->node_count = (int)bvh->node_count;
    p->triangle_count = bvh->triangle_count;
    p->tri_base = (int)(bvh->node_count * (format == SNELL_EXACT_NODES_F32 ? 2u : 1u));
    p->rows = (int)rows;
    p->nodes = (flat_node *)snell__calloc(&p->alloc, bvh->node_count, sizeof *p->nodes);
    p->boxes = (double *)snell__calloc(&p->alloc, 6 * (size_t)bvh->node_count, sizeof(double));
    p->tri_ids = (uint32_t *)snell__calloc(&p->alloc, bvh->triangle_count, sizeof(uint32_t));
    p->texels = snell__calloc(&p->alloc, rows * TEX_WIDTH, 16);
    if (!p->nodes || !p->boxes || !p->tri_ids || !p->texels) {
        free_arrays(p);
        st = snell__fail(ctx, SNELL_E_NOMEM, "BVH: out of memory for a %u-node BVH", bvh->node_count);
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

/* Built once per mesh, refitted for each new version of it (a deformed
 * mesh, snell_mesh_set_vertices: the same triangles), so only the boxes are
 * recomputed (O(n), no SAH build: bench/notes/history.md "Exact"); the splits
 * stay those of the first shape, which a large deformation makes worse to
 * traverse, never wrong. A new triangle count builds again. */
static snell_status prepare_mesh(snell_ctx *ctx, bvh_data *p, const snell_mesh *mesh, int format)
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
        snell__texture_nearest(GL_TEXTURE_2D, 0);
        if (p->format == SNELL_EXACT_NODES_F32)
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, TEX_WIDTH, p->rows, 0, GL_RGBA, GL_FLOAT, p->texels);
        else
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32UI, TEX_WIDTH, p->rows, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                         p->texels);
    } else {
        glBindTexture(GL_TEXTURE_2D, p->texture);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, TEX_WIDTH, p->rows, p->format == SNELL_EXACT_NODES_F32 ? GL_RGBA : GL_RGBA_INTEGER,
                        p->format == SNELL_EXACT_NODES_F32 ? GL_FLOAT : GL_UNSIGNED_INT, p->texels);
    }
    snell__pixel_unpack_end(&unpack);
    if (glGetError() != GL_NO_ERROR)
        return snell__fail(ctx, SNELL_E_GL, "BVH: uploading a %dx%d BVH texture failed", TEX_WIDTH, p->rows);
    return SNELL_OK;
}

static void release(bvh_data *p)
{
    if (p->texture) glDeleteTextures(1, &p->texture);
    p->texture = 0;
    free_arrays(p);
}

static void view_of(const bvh_data *p, snell__gpu_bvh *out)
{
    out->texture = p->texture;
    out->q16 = p->format == SNELL_EXACT_NODES_Q16;
    out->node_count = p->node_count;
    out->tri_base = p->tri_base;
    out->qlo = p->qlo;
    out->qstep = p->qstep;
}

/* Makes or brings up to date the BVH in *slot for mesh (its current version). */
static snell_status update(snell_ctx *ctx, void **slot, const snell_mesh *mesh, int format, int force,
                           snell__gpu_bvh *out)
{
    bvh_data *p = (bvh_data *)*slot;
    snell_status st;
    out->built = 0;
    if (!p) {
        if (!(p = (bvh_data *)(*slot = snell__calloc(&ctx->alloc, 1, sizeof *p))))
            return snell__fail(ctx, SNELL_E_NOMEM, "BVH: out of memory");
        p->alloc = ctx->alloc;
    }
    if (force || !p->texture || p->version != mesh->version) {
        if ((st = prepare_mesh(ctx, p, mesh, format)) != SNELL_OK) {
            release(p);
            return st;
        }
        p->version = mesh->version;
        out->built = 1;
    }
    view_of(p, out);
    return SNELL_OK;
}

snell_status snell__mesh_gpu_bvh(snell_ctx *ctx, snell_mesh *mesh, snell_exact_nodes format, snell__gpu_bvh *out)
{
    int q16 = format == SNELL_EXACT_NODES_Q16;
    return update(ctx, &mesh->gpu_bvh[q16], mesh, q16 ? SNELL_EXACT_NODES_Q16 : SNELL_EXACT_NODES_F32, 0, out);
}

snell_status snell__gpu_bvh_make(snell_ctx *ctx, const snell_mesh *mesh, void **state, snell__gpu_bvh *out)
{
    /* the caller remakes the mesh in place each time: always brought up to date */
    return update(ctx, state, mesh, SNELL_EXACT_NODES_F32, 1, out);
}

void snell__gpu_bvh_free(void *state, int gl)
{
    bvh_data *p = (bvh_data *)state;
    if (!p) return;
    if (gl && p->texture) glDeleteTextures(1, &p->texture);
    free_arrays(p);
    snell__free(&p->alloc, p);
}

#else

void snell__gpu_bvh_free(void *state, int gl) { (void)state, (void)gl; }

#endif
