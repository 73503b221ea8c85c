/* SPDX-License-Identifier: MIT */
/* lm2d_bvh.h — binary BVH over 2D edges: full-sweep SAH with the perimeter as
 * the hit-probability measure (Brückner 6.3), nodes in one array, and the
 * nearest-first stack traversal (Algorithm 4) with float-error-expanded slabs (6.4.1.4). */
#ifndef SNELL_LM2D_BVH_H
#define SNELL_LM2D_BVH_H

#include "core/core.h"

#define LM2D_BVH_DEFAULT_LEAF 4
#define LM2D_BVH_MAX_LEAF 31
#define LM2D_BVH_STACK 96

/* A node holds the boxes of its two children (so one visit tests both, and the
 * nearer is entered first). child[k] >= 0: index of an inner node; child[k] < 0:
 * a leaf, ~child[k] = first << 5 | count over the leaf-ordered edge arrays. 40 bytes. */
typedef struct lm2d_node {
    float lo_x[2], lo_y[2], hi_x[2], hi_y[2];
    int32_t child[2];
} lm2d_node;

typedef struct lm2d_bvh {
    lm2d_node *nodes;
    int n_nodes;
    /* leaf order: p1 and e = p2 - p1 per edge (x, y, ex, ey), and the original edge index */
    float *geo;
    int32_t *prim;
    int n_prims;
    int root_is_leaf;           /* tiny scenes: the whole set is one leaf, encoded in root_leaf */
    int32_t root_leaf;
    float lo[2], hi[2];         /* scene bounds (expanded) */
    int leaf_size;
} lm2d_bvh;

/* Builds over n segments given as p1 (x,y) / p2 (x,y) quadruples (4 floats each).
 * leaf_size in [1, LM2D_BVH_MAX_LEAF]; leaves hold at most leaf_size edges. */
snell_status lm2d_bvh_build(const snell_ctx *ctx, const snell_alloc *al, const float *segs, int n,
                            int leaf_size, lm2d_bvh *bvh);
void lm2d_bvh_free(const snell_alloc *al, lm2d_bvh *bvh);

/* Ray o + t d. Finds the nearest edge with t in (t_min, *t_hit) other than
 * `skip` (original index, -1 for none); on a hit updates *t_hit and returns the
 * original edge index, else -1. d need not be unit (t is in units of |d|). */
int lm2d_bvh_intersect(const lm2d_bvh *bvh, const float o[2], const float d[2], float t_min, float *t_hit,
                       int skip);
/* The same by testing every edge (reference for tests). */
int lm2d_brute_intersect(const lm2d_bvh *bvh, const float o[2], const float d[2], float t_min, float *t_hit,
                         int skip);

/* Ray/segment test (Brückner eq. 2.3 in cross-product form). p, e: segment
 * p + s e, s in [0,1] inclusive (endpoint hits count, LM2D_S_EPS slack). Returns 1 and t when the
 * ray hits with t > t_min; parallel rays (cross(d,e) == 0) never hit. */
/* Endpoint tolerance on the segment parameter: a ray through a shared vertex
 * must not slip between the two edges through rounding (both may then report
 * the same t; either is correct). */
#define LM2D_S_EPS 1e-6f

static inline int lm2d_ray_segment(const float o[2], const float d[2], const float p[2], const float e[2],
                                   float t_min, float *t)
{
    float den = d[0] * e[1] - d[1] * e[0];
    float wx = p[0] - o[0], wy = p[1] - o[1];
    float tn, sn, inv;
    if (den == 0.0f) return 0;
    inv = 1.0f / den;
    tn = (wx * e[1] - wy * e[0]) * inv;
    sn = (wx * d[1] - wy * d[0]) * inv;
    if (!(tn > t_min) || sn < -LM2D_S_EPS || sn > 1.0f + LM2D_S_EPS) return 0;
    *t = tn;
    return 1;
}

/* Slab test against [lo, hi] with inv = 1/d (no zeros in d, see .c); returns
 * the entry distance (clamped to 0 inside) or INFINITY on a miss / beyond t_max. */
float lm2d_slab(const float lo[2], const float hi[2], const float o[2], const float inv[2], float t_max);

#endif
