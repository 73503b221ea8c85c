/* SPDX-License-Identifier: MIT */
/* mesh.h — the mesh object: CPU geometry (positions, unit smooth normals,
 * triangle indices, bounds), its cached analysis and lazily created GPU buffers. */
#ifndef SNELL_MESH_H
#define SNELL_MESH_H

#include "core/core.h"

struct snell_mesh {
    snell_ctx *ctx;            /* may be NULL (CPU-only mesh) */
    snell_alloc alloc;
    int dead;                  /* destroyed, kept only under SNELL_DEBUG_HANDLES */
    float *positions;          /* 3 * vertex_count */
    float *normals;            /* 3 * vertex_count, unit length */
    uint32_t *indices;         /* 3 * triangle_count */
    uint32_t vertex_count;
    uint32_t triangle_count;
    float bmin[3], bmax[3];
    float bradius;             /* distance of the farthest vertex from the box centre */
    unsigned version;          /* process-unique; renewed whenever the geometry changes */
    /* Orientation, computed on demand by snell__mesh_winding (mesh_analyze.c). */
    unsigned winding_version;  /* the version it was computed for; 0 = never */
    int winding;               /* +1 closed and outward, -1 closed and inward, 0 open */
    /* Analysis, computed on demand by snell__mesh_analysis (mesh_analyze.c). */
    unsigned analysis_version; /* the version of the last cached attempt; 0 = never */
    snell_status analysis_status; /* its outcome (SNELL_E_NOMEM is never cached) */
    snell_mesh_analysis analysis; /* valid when analysis_status == SNELL_OK */
    char analysis_error[128]; /* the failure message when it is not */
    /* GPU side, created by snell__mesh_upload in gpu_ctx's GL context (a VAO
     * names nothing in another context). gpu_ctx is ctx, or for a CPU-only
     * mesh the context of the first frame that drew it (snell__mesh_bind_ctx);
     * it holds a reference on it. */
    snell_ctx *gpu_ctx;
    unsigned vao, vbo, ibo;
    unsigned index_type;       /* GL_UNSIGNED_SHORT or GL_UNSIGNED_INT (mesh_gpu.c) */
    unsigned uploaded_version;
    /* A coarse index buffer over the same GPU vertices (snell__mesh_coarse),
     * made once: the GPU copy's vertex order depends only on the triangles,
     * which never change (snell_mesh_set_vertices moves vertices only). */
    int coarse_state;          /* 0 not tried, 1 made, -1 none (no gain, no meshoptimizer, failure) */
    int order_warned;          /* 1: the upload logged that the vertex-cache reorder was skipped (once a mesh) */
    unsigned coarse_vao, coarse_ibo;
    uint32_t coarse_index_count;
    void *gpu_bvh[2];          /* its BVH on the GPU, f32 and q16 nodes (mesh/bvh_gpu.c), made on first ask */
};

/* Limits that protect against absurd inputs (files claiming 2^40 vertices). */
#define SNELL_MESH_MAX_VERTICES (1u << 26)
#define SNELL_MESH_MAX_TRIANGLES (1u << 26)

/* SNELL_OK if a mesh of nv vertices and nt triangles fits the memory budget
 * with what it will allocate: its arrays, and at its first frame its analysis
 * (the largest: topology, BVH, area CDF), more than its GPU copy. Every loader
 * checks it before making the arrays; snell__mesh_adopt again. */
snell_status snell__mesh_budget_check(const snell_ctx *ctx, size_t nv, size_t nt, const char *what);

/* Takes ownership of positions/normals/indices (allocated with alloc). normals
 * may be NULL: smooth area-weighted normals are computed. Validates indices and
 * rejects non-finite positions. On failure the arrays are freed. */
snell_status snell__mesh_adopt(snell_ctx *ctx, const snell_alloc *alloc, float *positions,
                               float *normals, uint32_t *indices, uint32_t vertex_count,
                               uint32_t triangle_count, snell_mesh **out);

/* glmark2's .3ds and .jobj files by path (mesh_3ds.c; snell_mesh_load's). */
snell_status snell__mesh_load_3ds(snell_ctx *ctx, const char *path, snell_mesh **out);
snell_status snell__mesh_load_jobj(snell_ctx *ctx, const char *path, snell_mesh **out);

/* Area-weighted smooth normals; degenerate vertices get (0,1,0). */
void snell__mesh_compute_normals(const float *pos, const uint32_t *idx, uint32_t nv, uint32_t nt,
                                 float *normals);

/* +1/-1 if the mesh is a closed, consistently oriented surface wound with
 * outward/inward normals, 0 otherwise: snell_mesh_analysis.winding, on the
 * same welded topology. Computed once per geometry version (welds and sorts
 * the edges: allocates then, not on later calls; taken from the cached
 * analysis when there is one). */
int snell__mesh_winding(snell_mesh *mesh);

/* The mesh's analysis (snell_mesh_analyze), computed once per geometry
 * version and cached on the mesh; later calls for that version allocate
 * nothing and return the same pointer (*out, valid until the geometry changes
 * or the mesh is destroyed) and status. A failure is cached too (*out = NULL;
 * the message was recorded and logged once, when it happened, and is kept in
 * mesh->analysis_error), so an unanalysable mesh is not retried every frame;
 * SNELL_E_NOMEM is not cached: the next call tries again. */
snell_status snell__mesh_analysis(snell_mesh *mesh, const snell_mesh_analysis **out);

/* The analysis's weld (snell_mesh_analysis: chains of vertices within 1e-5
 * of the bounding-box diagonal): id[v] = welded vertex 0 .. *count-1 of each
 * vertex with used[v] != 0 (others are left alone). For the simplifier
 * (mesh_lod.c), so that what it keeps closed is what the analysis calls closed. */
snell_status snell__mesh_weld(const snell_mesh *mesh, const unsigned char *used, uint32_t *id, uint32_t *count);

/* The GPU copy (mesh_gpu.c): vertices interleaved (position, normal: 6
 * floats each, vertex_count of them) and indices (3 * triangle_count),
 * reordered for the vertex cache and fetch when built with meshoptimizer. */
snell_status snell__mesh_gpu_layout(const snell_mesh *mesh, float *vertices, uint32_t *indices);
/* How snell__mesh_gpu_layout orders the triangles and whether the coarse
 * copy may be made (snell_mesh_gpu_stats_get): from the triangles alone. */
snell_status snell__mesh_gpu_order(const snell_mesh *mesh, snell_mesh_gpu_stats *out);
/* The work estimate of meshoptimizer's vertex-cache order and simplifier on
 * index_count indices over vertex_count vertices: sum over vertices of
 * (corners on it)^2 (mesh_gpu.c says why), and the most corners on one
 * vertex (may be NULL); SNELL_E_NOMEM (reported on ctx) for its counts. */
snell_status snell__mesh_work_estimate(const snell_ctx *ctx, const snell_alloc *al, const uint32_t *indices,
                                       size_t index_count, size_t vertex_count, double *work, uint32_t *max_valence);
/* The bound on that estimate for index_count indices: 2^25 + 64 per index. */
double snell__mesh_work_limit(size_t index_count);
/* The uploaded mesh at about a quarter of its triangles (meshoptimizer's
 * simplifier on the GPU copy, within 1% of the extent), for passes that
 * need the surface only at pixel resolution: the VAO to draw with
 * snell__mesh_coarse_draw, or 0 (not built with meshoptimizer, fewer than
 * SNELL__COARSE_MIN_TRIANGLES triangles, no gain, out of budget or memory:
 * then draw the mesh itself). Allocates on the first call only. */
#define SNELL__COARSE_MIN_TRIANGLES 4096u
unsigned snell__mesh_coarse(snell_mesh *mesh);
void snell__mesh_coarse_draw(const snell_mesh *mesh);
/* Average cache miss ratio (transformed vertices per triangle, 16-entry cache). */
float snell__mesh_acmr(const uint32_t *indices, uint32_t triangle_count, uint32_t vertex_count);
/* Draws the uploaded mesh's triangles (its VAO and index type). */
void snell__mesh_draw(const snell_mesh *mesh);

/* Creates/updates VAO+VBO+IBO (attribute 0 = position, 1 = normal). Needs GL. */
snell_status snell__mesh_upload(snell_mesh *mesh);

/* For frame validation: 1 if a frame of ctx may draw the mesh (made with ctx,
 * or CPU-only and drawn in no other context yet: it is bound to ctx now, its
 * GPU buffers will live there), 0 if its GPU side belongs to another context. */
int snell__mesh_bind_ctx(snell_mesh *mesh, snell_ctx *ctx);

#endif
