/* SPDX-License-Identifier: MIT */
/* bvh.h — 3D triangle BVH in double precision (world space): binned SAH build
 * over one or several parts (each with its model matrix, applied once: the BVH
 * owns a world-space copy), flattened nodes, closest/any hit with an optional
 * per-part filter. Used by the reference tracer and exact ray casts on meshes.
 * Ray-triangle test: Woop, Benthin, Wald, "Watertight Ray/Triangle
 * Intersection", JCGT 2(1), 2013 (no cracks); boxes padded so the box test is
 * conservative. */
#ifndef SNELL_REF_BVH_H
#define SNELL_REF_BVH_H

#include "core/core.h"

#define SNELL__BVH_NONE 0xffffffffu /* "no triangle" for skip_tri / hit.tri */

typedef struct snell__bvh_node {
    double bmin[3], bmax[3]; /* world space, padded */
    uint32_t index;          /* interior: first child (second = index + 1); leaf: first entry */
    uint32_t count;          /* 0 = interior, else number of triangles in the leaf */
} snell__bvh_node;

/* Triangle numbering: the triangles of all parts in part order, so part p's
 * triangle i has the id part_first[p] + i (with one part: the mesh's own index). */
typedef struct snell__bvh {
    snell_alloc alloc;
    snell__bvh_node *nodes;  /* nodes[0] is the root */
    uint32_t node_count;
    uint32_t triangle_count; /* over all parts */
    uint32_t part_count;
    uint32_t *part_first;    /* part_count + 1 entries: first triangle id of each part, then the total */
    double *tri_verts;       /* 9 doubles per entry (v0, v1, v2 in world space), leaf order */
    uint32_t *tri_ids;       /* leaf order -> triangle id */
    uint32_t *tri_parts;     /* leaf order -> part of the triangle */
    double bmin[3], bmax[3]; /* world-space bounds of all triangles (unpadded) */
    int depth;               /* depth of the tree (root = 1) */
} snell__bvh;

typedef struct snell__bvh_hit {
    double t;       /* ray parameter, in units of |dir| */
    uint32_t tri;   /* triangle id (see snell__bvh) */
    uint32_t part;  /* the part it belongs to */
    uint32_t entry; /* its leaf-order entry: tri_verts + 9 * entry are its world vertices */
    double b[3];    /* barycentric weights of the triangle's vertices 0, 1, 2 (sum 1) */
    double p[3];    /* hit point b0*v0 + b1*v1 + b2*v2 (lies on the triangle), world space */
} snell__bvh_hit;

/* One mesh of a multi-part build: positions 3*vertex_count floats (object
 * space), indices 3*triangle_count; model float[16] column-major
 * object-to-world, NULL = identity. */
typedef struct snell__bvh_part {
    const float *positions;
    uint32_t vertex_count;
    const uint32_t *indices;
    uint32_t triangle_count;
    const float *model;
} snell__bvh_part;

/* At most this many triangles over all parts (the traversal stack is sized for it). */
#define SNELL__BVH_MAX_TRIANGLES (1u << 26)

/* Builds over parts[0 .. part_count-1] (part_count >= 1). Every part is
 * validated (triangles present, indices in range, model finite and
 * invertible; messages name the part when there are several). Fails with a
 * message (SNELL_E_INVALID_ARG, SNELL_E_LIMIT, SNELL_E_NOMEM); ctx may be NULL
 * (libc allocator, thread-local message). */
snell_status snell__bvh_build_parts(snell_ctx *ctx, const snell__bvh_part *parts, uint32_t part_count,
                                    snell__bvh **out);
/* One part from raw arrays. */
snell_status snell__bvh_build(snell_ctx *ctx, const float *positions, uint32_t nv, const uint32_t *indices,
                              uint32_t nt, const float *model, snell__bvh **out);
/* Same, from a snell_mesh. */
snell_status snell__bvh_build_mesh(snell_ctx *ctx, const snell_mesh *mesh, const float *model, snell__bvh **out);
void snell__bvh_destroy(snell__bvh *bvh);

/* Closest hit with t in (tmin, tmax); dir need not be unit (must be nonzero).
 * skip_tri: a triangle id to ignore (the one a secondary ray starts on), or
 * SNELL__BVH_NONE. Returns 1 and fills *hit, or 0. Thread-safe (read only). */
int snell__bvh_closest(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin, double tmax,
                       uint32_t skip_tri, snell__bvh_hit *hit);
/* Which parts a query sees: nonzero = the triangles of `part` count. Called
 * only for triangles the ray hits closer than the best hit so far. */
typedef int (*snell__bvh_filter)(uint32_t part, const void *user);
/* snell__bvh_closest among the triangles of the parts `accept` admits
 * (accept NULL = all): the closest admitted hit, behind any rejected ones. */
int snell__bvh_closest_filtered(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin,
                                double tmax, uint32_t skip_tri, snell__bvh_filter accept, const void *user,
                                snell__bvh_hit *hit);
/* 1 if any triangle is hit with t in (tmin, tmax). */
int snell__bvh_any(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin, double tmax,
                   uint32_t skip_tri);

/* snell__bvh_closest / snell__bvh_any that add the work they do (nodes
 * visited + triangles tested; at most 3 * triangle_count per query) to *work,
 * for callers that bound their cost (the mesh analysis). Same results. */
int snell__bvh_closest_counted(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin,
                               double tmax, uint32_t skip_tri, snell__bvh_hit *hit, uint64_t *work);
int snell__bvh_any_counted(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin, double tmax,
                           uint32_t skip_tri, uint64_t *work);

/* The watertight test alone, for one triangle (v0, v1, v2 world space): 1 and
 * t, b[3] (weights of v0, v1, v2) if hit with t in (tmin, tmax). Exposed so
 * tests can brute-force the same predicate the BVH uses. */
int snell__bvh_triangle_hit(const double org[3], const double dir[3], const double v0[3], const double v1[3],
                            const double v2[3], double tmin, double tmax, double *t, double b[3]);

#endif
