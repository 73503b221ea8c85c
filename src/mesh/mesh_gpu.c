/* SPDX-License-Identifier: MIT */
/* mesh_gpu.c — the mesh as the GPU draws it (docs/ARCHITECTURE.md "One frame": geometry fed
 * well): triangles reordered for the post-transform vertex cache, vertices
 * for fetch locality (meshoptimizer, when built with it), 16-bit indices where
 * the vertex count allows. Only the GPU copy changes: the mesh's own arrays,
 * which users and the analysis see, keep their order. Measured on the bunny
 * (69,666 triangles): ACMR 2.08 in OBJ order, 0.68 after the reorder. */
#include "mesh/mesh.h"
#include "core/gl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef SNELL_WITH_MESHOPT
#include <meshoptimizer.h>
#endif

/* Post-transform cache the ACMR figures are for (meshoptimizer's default). */
#define CACHE_SIZE 16

float snell__mesh_acmr(const uint32_t *indices, uint32_t triangle_count, uint32_t vertex_count)
{
#ifdef SNELL_WITH_MESHOPT
    struct meshopt_VertexCacheStatistics s =
        meshopt_analyzeVertexCache(indices, 3 * (size_t)triangle_count, vertex_count, CACHE_SIZE, 0, 0);
    return s.acmr;
#else
    /* FIFO cache of CACHE_SIZE: misses per triangle */
    uint32_t cache[CACHE_SIZE];
    size_t i, misses = 0, head = 0, filled = 0, k;
    for (i = 0; i < 3 * (size_t)triangle_count; i++) {
        int hit = 0;
        for (k = 0; k < filled; k++) hit |= cache[k] == indices[i];
        if (hit) continue;
        misses++;
        cache[head] = indices[i];
        head = (head + 1) % CACHE_SIZE;
        if (filled < CACHE_SIZE) filled++;
    }
    (void)vertex_count;
    return triangle_count ? (float)misses / (float)triangle_count : 0.0f;
#endif
}

/* The vertex-cache optimisation's work bound. After each triangle it emits,
 * meshoptimizer re-scores the remaining triangles of every vertex in its
 * cache, so a vertex on d triangle corners costs about d^2 / 2 steps over
 * its time there: sum over vertices of d^2 is the cost, which real meshes
 * keep near 6 per corner (valence ~6) and a fan of n triangles on one vertex
 * makes n^2, so a hostile file (one face of many repeated corners, a large
 * fan) can take minutes. Above the bound the reorder is skipped for
 * meshoptimizer's FIFO order (Tipsify: each vertex's triangles are fanned
 * once, so it is linear in the corners). The bound lets any mesh within 64
 * steps a corner through (10x the real meshes', a UV sphere with 1024
 * segments needs 17) plus a base of 2^25 (a fan of 5,800 triangles), so what
 * it admits costs at most about half as much again as a real mesh of its size
 * plus a small constant. The simplifier of the coarse copy has the same quadratic cost (it
 * tests every triangle of a vertex for flips on each collapse onto it) and
 * the same bound (mesh_lod.c too). Timings: bench/notes/code.md, "mesh_gpu.c". */
#define ORDER_WORK_BASE 33554432.0 /* 2^25 */
#define ORDER_WORK_PER_CORNER 64.0

snell_status snell__mesh_work_estimate(const snell_ctx *ctx, const snell_alloc *al, const uint32_t *indices,
                                       size_t index_count, size_t vertex_count, double *work, uint32_t *max_valence)
{
    uint32_t *count = (uint32_t *)snell__calloc(al, vertex_count ? vertex_count : 1, sizeof *count), top = 0;
    double w = 0.0;
    size_t i;
    *work = 0.0;
    if (max_valence) *max_valence = 0;
    if (!count)
        return snell__fail(ctx, SNELL_E_NOMEM, "out of memory estimating the work of reordering %zu vertices",
                           vertex_count);
    for (i = 0; i < index_count; i++) count[indices[i]]++;
    for (i = 0; i < vertex_count; i++) {
        w += (double)count[i] * (double)count[i];
        if (count[i] > top) top = count[i];
    }
    snell__free(al, count);
    *work = w;
    if (max_valence) *max_valence = top;
    return SNELL_OK;
}

double snell__mesh_work_limit(size_t index_count) { return ORDER_WORK_BASE + ORDER_WORK_PER_CORNER * (double)index_count; }

#ifdef SNELL_WITH_MESHOPT
/* A triangle's corners rotated so the smallest comes first (the winding is
 * kept: a rotation is the same triangle facing the same way). */
typedef struct tri_key {
    uint32_t v[3];
    uint32_t tri;
} tri_key;

static int cmp_tri_key(const void *x, const void *y)
{
    const tri_key *p = (const tri_key *)x, *q = (const tri_key *)y;
    int k;
    for (k = 0; k < 3; k++)
        if (p->v[k] != q->v[k]) return p->v[k] < q->v[k] ? -1 : 1;
    return p->tri < q->tri ? -1 : p->tri > q->tri;
}

/* Same-facing copies of a triangle after its first (in idx's order): counted
 * in *count and, with hide, made degenerate in place (three equal corners:
 * no fragments, so a copy, which would draw the same pixels at the same
 * depth again, costs no fill; the index count the renderer draws stays).
 * Triangles with a repeated corner are left as they are (they draw nothing).
 * Only for meshes over the reorder's bound: there one OBJ face of 120,000
 * repeated corners is 40,000 copies of one triangle, each covering a large
 * part of the view (2.9 s of fill under llvmpipe). */
static snell_status copies_of_triangles(const snell_mesh *m, uint32_t *idx, int hide, uint32_t *count)
{
    size_t nt = m->triangle_count, t, n = 0;
    tri_key *keys = (tri_key *)snell__calloc(&m->alloc, nt ? nt : 1, sizeof *keys);
    *count = 0;
    if (!keys) return snell__fail(m->ctx, SNELL_E_NOMEM, "out of memory finding the copies of %zu triangles", nt);
    for (t = 0; t < nt; t++) {
        const uint32_t *c = idx + 3 * t;
        int r = c[0] < c[1] ? (c[0] < c[2] ? 0 : 2) : (c[1] < c[2] ? 1 : 2);
        if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) continue;
        keys[n].v[0] = c[r];
        keys[n].v[1] = c[(r + 1) % 3];
        keys[n].v[2] = c[(r + 2) % 3];
        keys[n++].tri = (uint32_t)t;
    }
    qsort(keys, n, sizeof *keys, cmp_tri_key);
    for (t = 1; t < n; t++)
        if (!memcmp(keys[t].v, keys[t - 1].v, sizeof keys[t].v)) {
            (*count)++;
            if (hide) idx[3 * (size_t)keys[t].tri + 1] = idx[3 * (size_t)keys[t].tri + 2] = idx[3 * (size_t)keys[t].tri];
        }
    snell__free(&m->alloc, keys);
    return SNELL_OK;
}

#endif

snell_status snell__mesh_gpu_order(const snell_mesh *m, snell_mesh_gpu_stats *out)
{
    size_t ni = 3 * (size_t)m->triangle_count;
    snell_status st;
    memset(out, 0, sizeof *out);
    st = snell__mesh_work_estimate(m->ctx, &m->alloc, m->indices, ni, m->vertex_count, &out->order_work,
                                   &out->max_valence);
    if (st != SNELL_OK) return st;
    out->order_work_limit = snell__mesh_work_limit(ni);
#ifdef SNELL_WITH_MESHOPT
    if (out->order_work <= out->order_work_limit) {
        out->order = SNELL_GPU_ORDER_CACHE;
        out->coarse_allowed = m->triangle_count >= SNELL__COARSE_MIN_TRIANGLES;
        snprintf(out->reason, sizeof out->reason,
                 "vertex-cache order (work %.3g within its bound %.3g; at most %u corners on a vertex)",
                 out->order_work, out->order_work_limit, out->max_valence);
    } else {
        out->order = SNELL_GPU_ORDER_LINEAR;
        st = copies_of_triangles(m, m->indices, 0, &out->copies_hidden);
        if (st != SNELL_OK) return st;
        snprintf(out->reason, sizeof out->reason,
                 "vertex-cache reorder skipped for the linear FIFO order: work %.3g over its bound %.3g (%u "
                 "corners on one vertex); %u copies of triangles not drawn; no coarse copy",
                 out->order_work, out->order_work_limit, out->max_valence, out->copies_hidden);
    }
#else
    out->order = SNELL_GPU_ORDER_SOURCE;
    snprintf(out->reason, sizeof out->reason, "the mesh's own order (built without meshoptimizer)");
#endif
    return SNELL_OK;
}

snell_status snell__mesh_gpu_layout(const snell_mesh *m, float *vertices, uint32_t *indices)
{
    size_t nv = m->vertex_count, ni = 3 * (size_t)m->triangle_count, i;
    for (i = 0; i < nv; i++) {
        memcpy(vertices + 6 * i, m->positions + 3 * i, 3 * sizeof(float));
        memcpy(vertices + 6 * i + 3, m->normals + 3 * i, 3 * sizeof(float));
    }
#ifdef SNELL_WITH_MESHOPT
    {
        snell_mesh_gpu_stats gs;
        float *fetched;
        snell_status st = snell__mesh_gpu_order(m, &gs);
        if (st != SNELL_OK) return st;
        fetched = (float *)snell__calloc(&m->alloc, 6 * nv, sizeof(float));
        if (!fetched) return snell__fail(m->ctx, SNELL_E_NOMEM, "out of memory laying out a mesh for the GPU");
        /* Triangle order for the vertex cache keeps each triangle's corner
         * order, so winding (and back-face culling) is unchanged; so does the
         * FIFO order. */
        if (gs.order == SNELL_GPU_ORDER_CACHE)
            meshopt_optimizeVertexCache(indices, m->indices, ni, nv);
        else
            meshopt_optimizeVertexCacheFifo(indices, m->indices, ni, nv, CACHE_SIZE);
        if (gs.order == SNELL_GPU_ORDER_LINEAR && gs.copies_hidden &&
            (st = copies_of_triangles(m, indices, 1, &gs.copies_hidden)) != SNELL_OK) {
            snell__free(&m->alloc, fetched);
            return st;
        }
        /* Vertices in first-use order; unreferenced ones are dropped (linear). */
        meshopt_optimizeVertexFetch(fetched, indices, ni, vertices, nv, 6 * sizeof(float));
        memcpy(vertices, fetched, 6 * nv * sizeof(float));
        snell__free(&m->alloc, fetched);
    }
#else
    memcpy(indices, m->indices, ni * sizeof(uint32_t));
#endif
    return SNELL_OK;
}

snell_status snell_mesh_gpu_stats_get(const snell_mesh *mesh, snell_mesh_gpu_stats *out)
{
    if (out) memset(out, 0, sizeof *out);
    if (!mesh || !out)
        return snell__fail(mesh ? mesh->ctx : NULL, SNELL_E_INVALID_ARG, "snell_mesh_gpu_stats_get: NULL argument");
    return snell__mesh_gpu_order(mesh, out);
}

/* Target and bound of the coarse copy: a quarter of the triangles, and no
 * vertex of it farther than 1% of the extent from the full surface
 * (meshoptimizer's relative error). */
#define COARSE_RATIO 0.25
#define COARSE_ERROR 0.01f
/* meshoptimizer 0.18's simplifier scratch per vertex and per index (see
 * mesh_lod.c), for the memory budget. */
#define COARSE_SCRATCH_PER_VERTEX 100u
#define COARSE_SCRATCH_PER_INDEX 40u

unsigned snell__mesh_coarse(snell_mesh *m)
{
#ifdef SNELL_WITH_MESHOPT
    size_t nv = m->vertex_count, ni = 3 * (size_t)m->triangle_count, n = 0, i;
    float *vert = NULL, err = 0.0f;
    uint32_t *idx = NULL, *out = NULL;
    if (m->coarse_state) return m->coarse_state > 0 ? m->coarse_vao : 0;
    m->coarse_state = -1;
    if (m->triangle_count < SNELL__COARSE_MIN_TRIANGLES || !m->vao) return 0;
    {
        /* the simplifier's cost grows as the vertex-cache reorder's (above) */
        snell_mesh_gpu_stats gs;
        if (snell__mesh_gpu_order(m, &gs) != SNELL_OK) return 0;
        if (!gs.coarse_allowed) {
            snell__log(m->gpu_ctx, SNELL_LOG_WARN,
                       "no coarse copy for the back-face pass (the full mesh is drawn): the simplifier's work "
                       "%.3g is over its bound %.3g (%u corners on one vertex)",
                       gs.order_work, gs.order_work_limit, gs.max_valence);
            return 0;
        }
    }
    if (snell__budget_check(m->gpu_ctx, nv * (24 + COARSE_SCRATCH_PER_VERTEX) + ni * (8 + COARSE_SCRATCH_PER_INDEX),
                            "the coarse copy of a mesh") != SNELL_OK)
        return 0;
    vert = (float *)snell__calloc(&m->alloc, 6 * nv, sizeof(float));
    idx = (uint32_t *)snell__calloc(&m->alloc, ni, sizeof(uint32_t));
    out = (uint32_t *)snell__calloc(&m->alloc, ni, sizeof(uint32_t));
    /* the GPU copy's own vertex numbering, so the copy indexes its buffer */
    if (vert && idx && out && snell__mesh_gpu_layout(m, vert, idx) == SNELL_OK)
        n = meshopt_simplify(out, idx, ni, vert, nv, 6 * sizeof(float), (size_t)(COARSE_RATIO * (double)ni), COARSE_ERROR,
                             0, &err);
    /* worth a buffer only if it saves a third of the triangles */
    if (n > 0 && n < 2 * ni / 3) {
        if (m->index_type == GL_UNSIGNED_SHORT)
            for (i = 0; i < n; i++) ((uint16_t *)out)[i] = (uint16_t)out[i];
        glGenVertexArrays(1, &m->coarse_vao);
        glGenBuffers(1, &m->coarse_ibo);
        glBindVertexArray(m->coarse_vao);
        glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)0);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)(3 * sizeof(float)));
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->coarse_ibo);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                     (GLsizeiptr)((m->index_type == GL_UNSIGNED_SHORT ? sizeof(uint16_t) : sizeof(uint32_t)) * n), out,
                     GL_STATIC_DRAW);
        glBindVertexArray(0);
        m->coarse_index_count = (uint32_t)n;
        m->coarse_state = glGetError() == GL_NO_ERROR ? 1 : -1;
        snell__log(m->gpu_ctx, SNELL_LOG_INFO,
                   "coarse copy for the back-face pass: %zu of %zu triangles, error %.4f of the extent", n / 3, ni / 3,
                   (double)err);
    }
    snell__free(&m->alloc, vert);
    snell__free(&m->alloc, idx);
    snell__free(&m->alloc, out);
    return m->coarse_state > 0 ? m->coarse_vao : 0;
#else
    (void)m;
    return 0;
#endif
}

void snell__mesh_coarse_draw(const snell_mesh *m)
{
    glBindVertexArray(m->coarse_vao);
    glDrawElements(GL_TRIANGLES, (GLsizei)m->coarse_index_count, m->index_type, (const void *)0);
}
