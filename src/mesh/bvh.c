/* SPDX-License-Identifier: MIT */
/* mesh/bvh.c — double-precision triangle BVH: binned SAH build (32 bins per
 * axis over centroid bounds), depth-first flattened nodes with adjacent
 * children, near-first stack traversal, watertight ray-triangle test
 * (Woop/Benthin/Wald 2013), an optional per-part filter on hits. See bvh.h. */
#include "mesh/bvh.h"
#include "mesh/mesh.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define BINS 32
#define MAX_LEAF 4        /* a leaf never holds more unless the centroids coincide */
#define MAX_DEPTH 96      /* beyond this, split by halves (keeps recursion bounded) */
#define SMALL_NODE 24     /* nodes this small choose their split by sorting, not by sweeping the bins */
#define STACK_SIZE 128 /* >= MAX_DEPTH + log2(SNELL__BVH_MAX_TRIANGLES) + 1 */

/* ------------------------------------------------------------ ray setup */

typedef struct ray_pre {
    double org[3], dir[3], inv[3];
    int kx, ky, kz;
    double sx, sy, sz;
} ray_pre;

/* Per-ray constants of the watertight test: the dominant axis kz, the two
 * others (swapped to keep the winding when dir[kz] < 0) and the shear that
 * maps the ray onto +Z (paper, section 3). */
static void ray_setup(ray_pre *r, const double org[3], const double dir[3])
{
    double ax = fabs(dir[0]), ay = fabs(dir[1]), az = fabs(dir[2]);
    int k;
    for (k = 0; k < 3; k++) {
        r->org[k] = org[k];
        r->dir[k] = dir[k];
        r->inv[k] = 1.0 / dir[k]; /* +-inf for a zero component: handled by the slab test */
    }
    r->kz = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
    r->kx = (r->kz + 1) % 3;
    r->ky = (r->kx + 1) % 3;
    if (dir[r->kz] < 0.0) {
        int tmp = r->kx;
        r->kx = r->ky;
        r->ky = tmp;
    }
    r->sx = dir[r->kx] / dir[r->kz];
    r->sy = dir[r->ky] / dir[r->kz];
    r->sz = 1.0 / dir[r->kz];
}

static int tri_hit(const ray_pre *r, const double *v0, const double *v1, const double *v2, double tmin,
                   double tmax, double *t_out, double b_out[3])
{
    const int kx = r->kx, ky = r->ky, kz = r->kz;
    double A[3], B[3], C[3], ax, ay, bx, by, cx, cy, u, v, w, det, az, bz, cz, T, t, rcp;
    int k;
    for (k = 0; k < 3; k++) {
        A[k] = v0[k] - r->org[k];
        B[k] = v1[k] - r->org[k];
        C[k] = v2[k] - r->org[k];
    }
    ax = A[kx] - r->sx * A[kz];
    ay = A[ky] - r->sy * A[kz];
    bx = B[kx] - r->sx * B[kz];
    by = B[ky] - r->sy * B[kz];
    cx = C[kx] - r->sx * C[kz];
    cy = C[ky] - r->sy * C[kz];
    /* Scaled barycentrics (2D edge functions in the sheared space); the
     * paper's single->double fallback for exact zeros has no wider type to go
     * to here, and a zero edge function already counts as "on the edge". */
    u = cx * by - cy * bx;
    v = ax * cy - ay * cx;
    w = bx * ay - by * ax;
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return 0;
    det = u + v + w;
    if (det == 0.0) return 0;
    az = r->sz * A[kz];
    bz = r->sz * B[kz];
    cz = r->sz * C[kz];
    T = u * az + v * bz + w * cz;
    rcp = 1.0 / det;
    t = T * rcp;
    if (!(t > tmin && t < tmax)) return 0;
    *t_out = t;
    b_out[0] = u * rcp;
    b_out[1] = v * rcp;
    b_out[2] = w * rcp;
    return 1;
}

int snell__bvh_triangle_hit(const double org[3], const double dir[3], const double v0[3], const double v1[3],
                            const double v2[3], double tmin, double tmax, double *t, double b[3])
{
    ray_pre r;
    ray_setup(&r, org, dir);
    return tri_hit(&r, v0, v1, v2, tmin, tmax, t, b);
}

/* Slab test; returns the entry parameter or +inf when missed. A NaN from
 * 0 * inf (origin on a slab plane, zero direction component) fails every
 * comparison and so leaves the interval unchanged: conservative. */
static double box_enter(const ray_pre *r, const snell__bvh_node *n, double tmin, double tmax)
{
    int k;
    for (k = 0; k < 3; k++) {
        double t0 = (n->bmin[k] - r->org[k]) * r->inv[k];
        double t1 = (n->bmax[k] - r->org[k]) * r->inv[k];
        if (t0 > t1) {
            double tmp = t0;
            t0 = t1;
            t1 = tmp;
        }
        if (t0 > tmin) tmin = t0;
        if (t1 < tmax) tmax = t1;
    }
    return tmin <= tmax ? tmin : HUGE_VAL;
}

/* any_only: stop at the first hit. accept (NULL = all) filters by part.
 * work (NULL = not counted) gains the nodes visited and triangles tested.
 * Returns the leaf-order entry of the hit or SNELL__BVH_NONE. */
static uint32_t traverse(const snell__bvh *bvh, const ray_pre *r, double tmin, double *tmax, uint32_t skip,
                         int any_only, snell__bvh_filter accept, const void *user, double b[3], uint64_t *work)
{
    uint32_t stack[STACK_SIZE], best = SNELL__BVH_NONE;
    int sp = 0;
    if (box_enter(r, &bvh->nodes[0], tmin, *tmax) == HUGE_VAL) return SNELL__BVH_NONE;
    stack[sp++] = 0;
    while (sp > 0) {
        const snell__bvh_node *n = &bvh->nodes[stack[--sp]];
        if (work) *work += 1 + n->count;
        if (n->count) {
            uint32_t i;
            for (i = n->index; i < n->index + n->count; i++) {
                const double *v = bvh->tri_verts + 9 * (size_t)i;
                double t, bb[3];
                if (bvh->tri_ids[i] == skip) continue;
                if (tri_hit(r, v, v + 3, v + 6, tmin, *tmax, &t, bb)) {
                    if (accept && !accept(bvh->tri_parts[i], user)) continue;
                    *tmax = t;
                    best = i;
                    b[0] = bb[0];
                    b[1] = bb[1];
                    b[2] = bb[2];
                    if (any_only) return best;
                }
            }
        } else {
            const snell__bvh_node *c0 = &bvh->nodes[n->index], *c1 = c0 + 1;
            double t0 = box_enter(r, c0, tmin, *tmax), t1 = box_enter(r, c1, tmin, *tmax);
            /* Push the farther child first so the nearer is visited first. */
            if (t0 <= t1) {
                if (t1 != HUGE_VAL) stack[sp++] = n->index + 1;
                if (t0 != HUGE_VAL) stack[sp++] = n->index;
            } else {
                if (t0 != HUGE_VAL) stack[sp++] = n->index;
                if (t1 != HUGE_VAL) stack[sp++] = n->index + 1;
            }
        }
    }
    return best;
}

static int closest(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin, double tmax,
                   uint32_t skip_tri, snell__bvh_filter accept, const void *user, snell__bvh_hit *hit, uint64_t *work)
{
    ray_pre r;
    double b[3] = {0, 0, 0}, t = tmax;
    uint32_t e;
    const double *v;
    int k;
    if (!bvh || !bvh->node_count) return 0;
    ray_setup(&r, org, dir);
    e = traverse(bvh, &r, tmin, &t, skip_tri, 0, accept, user, b, work);
    if (e == SNELL__BVH_NONE) return 0;
    v = bvh->tri_verts + 9 * (size_t)e;
    hit->t = t;
    hit->tri = bvh->tri_ids[e];
    hit->part = bvh->tri_parts[e];
    hit->entry = e;
    for (k = 0; k < 3; k++) {
        hit->b[k] = b[k];
        hit->p[k] = b[0] * v[k] + b[1] * v[3 + k] + b[2] * v[6 + k];
    }
    return 1;
}

int snell__bvh_closest_filtered(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin,
                                double tmax, uint32_t skip_tri, snell__bvh_filter accept, const void *user,
                                snell__bvh_hit *hit)
{
    return closest(bvh, org, dir, tmin, tmax, skip_tri, accept, user, hit, NULL);
}

int snell__bvh_closest(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin, double tmax,
                       uint32_t skip_tri, snell__bvh_hit *hit)
{
    return closest(bvh, org, dir, tmin, tmax, skip_tri, NULL, NULL, hit, NULL);
}

int snell__bvh_closest_counted(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin,
                               double tmax, uint32_t skip_tri, snell__bvh_hit *hit, uint64_t *work)
{
    return closest(bvh, org, dir, tmin, tmax, skip_tri, NULL, NULL, hit, work);
}

int snell__bvh_any_counted(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin, double tmax,
                           uint32_t skip_tri, uint64_t *work)
{
    ray_pre r;
    double b[3], t = tmax;
    if (!bvh || !bvh->node_count) return 0;
    ray_setup(&r, org, dir);
    return traverse(bvh, &r, tmin, &t, skip_tri, 1, NULL, NULL, b, work) != SNELL__BVH_NONE;
}

int snell__bvh_any(const snell__bvh *bvh, const double org[3], const double dir[3], double tmin, double tmax,
                   uint32_t skip_tri)
{
    return snell__bvh_any_counted(bvh, org, dir, tmin, tmax, skip_tri, NULL);
}

/* --------------------------------------------------------------- build */

/* A source triangle's box and centroid, moved with it as the build
 * partitions: each node reads its triangles in order, not scattered. */
typedef struct build_prim {
    double lo[3], hi[3], c[3];
    uint32_t t; /* source triangle index */
} build_prim;

typedef struct build_ctx {
    snell__bvh *bvh;
    build_prim *prims;    /* one per source triangle, permuted into leaf order */
    uint32_t next_node;
} build_ctx;

typedef struct box3 {
    double lo[3], hi[3];
} box3;

static void box_empty(box3 *b)
{
    int k;
    for (k = 0; k < 3; k++) {
        b->lo[k] = HUGE_VAL;
        b->hi[k] = -HUGE_VAL;
    }
}

static void box_grow(box3 *b, const double *lo, const double *hi)
{
    int k;
    for (k = 0; k < 3; k++) {
        if (lo[k] < b->lo[k]) b->lo[k] = lo[k];
        if (hi[k] > b->hi[k]) b->hi[k] = hi[k];
    }
}

static double box_area(const box3 *b)
{
    double d0 = b->hi[0] - b->lo[0], d1 = b->hi[1] - b->lo[1], d2 = b->hi[2] - b->lo[2];
    if (d0 < 0.0) return 0.0; /* empty */
    return d0 * d1 + d1 * d2 + d2 * d0;
}

static int bin_of(double c, double lo, double scale)
{
    int b = (int)((c - lo) * scale);
    return b < 0 ? 0 : (b >= BINS ? BINS - 1 : b);
}

/* The same choice as the bins below for a node of few triangles (most
 * nodes), without clearing and sweeping every bin: the cost only changes
 * where a triangle's bin does, so the splits after each occupied bin are
 * tried, in the same order, with the same boxes (unions are exact). */
static void sah_small(const build_ctx *bc, uint32_t begin, uint32_t count, const box3 *cb, const double scales[3],
                      double *best_cost, int *best_axis, int *best_split)
{
    uint32_t idx[SMALL_NODE], j;
    int bin[SMALL_NODE], k;
    box3 suffix[SMALL_NODE], acc;
    for (k = 0; k < 3; k++) {
        if (scales[k] == 0.0) continue;
        for (j = 0; j < count; j++) {
            uint32_t m = j;
            int b = bin_of(bc->prims[begin + j].c[k], cb->lo[k], scales[k]);
            for (; m > 0 && bin[idx[m - 1]] > b; m--) idx[m] = idx[m - 1]; /* insertion by bin */
            idx[m] = j;
            bin[j] = b;
        }
        box_empty(&acc);
        for (j = count; j-- > 0;) {
            const build_prim *p = &bc->prims[begin + idx[j]];
            box_grow(&acc, p->lo, p->hi);
            suffix[j] = acc;
        }
        box_empty(&acc);
        for (j = 0; j + 1 < count; j++) {
            const build_prim *p = &bc->prims[begin + idx[j]];
            uint32_t left_cnt = j + 1, right_cnt = count - j - 1;
            double cost;
            box_grow(&acc, p->lo, p->hi);
            if (bin[idx[j]] == bin[idx[j + 1]]) continue;
            cost = box_area(&acc) * left_cnt + box_area(&suffix[j + 1]) * right_cnt;
            if (cost < *best_cost) {
                *best_cost = cost;
                *best_axis = k;
                *best_split = bin[idx[j]];
            }
        }
    }
}

static void build_node(build_ctx *bc, uint32_t node, uint32_t begin, uint32_t end, int depth)
{
    snell__bvh_node *n = &bc->bvh->nodes[node];
    box3 nb, cb;
    uint32_t i, count = end - begin, mid = begin;
    int k, best_axis = -1, best_split = 0;
    double best_cost = HUGE_VAL, leaf_cost;
    box_empty(&nb);
    box_empty(&cb);
    for (i = begin; i < end; i++) {
        const build_prim *p = &bc->prims[i];
        box_grow(&nb, p->lo, p->hi);
        box_grow(&cb, p->c, p->c);
    }
    for (k = 0; k < 3; k++) {
        n->bmin[k] = nb.lo[k];
        n->bmax[k] = nb.hi[k];
    }
    if (depth > bc->bvh->depth) bc->bvh->depth = depth;
    if (count <= 1) goto leaf;

    /* Binned SAH (Wald 2007): cost of a split = A_L*N_L + A_R*N_R relative to
     * the node, traversal cost 1, intersection cost 1 per triangle. */
    if (depth < MAX_DEPTH && count <= SMALL_NODE) {
        double scales[3];
        for (k = 0; k < 3; k++) {
            double ext = cb.hi[k] - cb.lo[k];
            scales[k] = ext > 0.0 ? (double)BINS / ext : 0.0;
        }
        sah_small(bc, begin, count, &cb, scales, &best_cost, &best_axis, &best_split);
    } else if (depth < MAX_DEPTH) {
        box3 bins[3][BINS];
        uint32_t cnts[3][BINS];
        double scales[3];
        int b;
        /* The three axes' bins filled in one pass over the triangles. */
        for (k = 0; k < 3; k++) {
            double ext = cb.hi[k] - cb.lo[k];
            scales[k] = ext > 0.0 ? (double)BINS / ext : 0.0;
            for (b = 0; b < BINS; b++) {
                box_empty(&bins[k][b]);
                cnts[k][b] = 0;
            }
        }
        for (i = begin; i < end; i++) {
            const build_prim *p = &bc->prims[i];
            for (k = 0; k < 3; k++) {
                if (scales[k] == 0.0) continue;
                b = bin_of(p->c[k], cb.lo[k], scales[k]);
                cnts[k][b]++;
                box_grow(&bins[k][b], p->lo, p->hi);
            }
        }
        for (k = 0; k < 3; k++) {
            double right_area[BINS];
            box3 acc;
            const uint32_t *cnt = cnts[k];
            uint32_t right_cnt[BINS], left_cnt = 0;
            if (scales[k] == 0.0) continue;
            box_empty(&acc);
            right_cnt[BINS - 1] = 0;
            for (b = BINS - 1; b > 0; b--) {
                box_grow(&acc, bins[k][b].lo, bins[k][b].hi);
                right_cnt[b - 1] = (b < BINS - 1 ? right_cnt[b] : 0) + cnt[b];
                right_area[b - 1] = box_area(&acc);
            }
            box_empty(&acc);
            for (b = 0; b < BINS - 1; b++) {
                double cost;
                box_grow(&acc, bins[k][b].lo, bins[k][b].hi);
                left_cnt += cnt[b];
                if (!left_cnt || !right_cnt[b]) continue;
                cost = box_area(&acc) * left_cnt + right_area[b] * right_cnt[b];
                if (cost < best_cost) {
                    best_cost = cost;
                    best_axis = k;
                    best_split = b;
                }
            }
        }
    }
    leaf_cost = (double)count;
    if (best_axis >= 0) {
        double area = box_area(&nb);
        double split_cost = 1.0 + (area > 0.0 ? best_cost / area : (double)count);
        if (count <= MAX_LEAF && leaf_cost <= split_cost) goto leaf;
        {
            double scale = (double)BINS / (cb.hi[best_axis] - cb.lo[best_axis]);
            uint32_t lo_i = begin, hi_i = end;
            /* Partition by the same bin function used for the costs. */
            while (lo_i < hi_i) {
                if (bin_of(bc->prims[lo_i].c[best_axis], cb.lo[best_axis], scale) <= best_split) {
                    lo_i++;
                } else {
                    build_prim t = bc->prims[lo_i];
                    bc->prims[lo_i] = bc->prims[--hi_i];
                    bc->prims[hi_i] = t;
                }
            }
            mid = lo_i;
        }
    } else {
        /* Coincident centroids (or depth limit): no useful plane. Small sets
         * become a leaf; larger ones are split by halves of the list. */
        if (count <= MAX_LEAF) goto leaf;
        mid = begin + count / 2;
    }
    {
        uint32_t c = bc->next_node;
        bc->next_node += 2;
        n->index = c;
        n->count = 0;
        build_node(bc, c, begin, mid, depth + 1);
        build_node(bc, c + 1, mid, end, depth + 1);
    }
    return;
leaf:
    n->index = begin;
    n->count = count;
}

static int invert3(const double m[9], double inv[9])
{
    /* m column-major 3x3; inv = m^-1. Returns 0 if singular. */
    double a = m[0], b = m[3], c = m[6], d = m[1], e = m[4], f = m[7], g = m[2], h = m[5], i = m[8];
    double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
    double det = a * A + b * B + c * C, r;
    if (!(fabs(det) > 0.0) || !isfinite(det)) return 0;
    r = 1.0 / det;
    inv[0] = A * r;
    inv[3] = -(b * i - c * h) * r;
    inv[6] = (b * f - c * e) * r;
    inv[1] = B * r;
    inv[4] = (a * i - c * g) * r;
    inv[7] = -(a * f - c * d) * r;
    inv[2] = C * r;
    inv[5] = -(a * h - b * g) * r;
    inv[8] = (a * e - b * d) * r;
    return 1;
}

/* Model matrix m (double, column-major) of a part; 0 and a message if it is
 * not finite or its 3x3 is singular. */
static snell_status part_model(snell_ctx *ctx, const snell__bvh_part *pt, const char *who, double m[16])
{
    double m3[9], inv[9];
    int k;
    for (k = 0; k < 16; k++) m[k] = pt->model ? (double)pt->model[k] : (k % 5 == 0 ? 1.0 : 0.0);
    for (k = 0; k < 16; k++)
        if (!isfinite(m[k]))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "bvh build: %smodel matrix is not finite", who);
    for (k = 0; k < 3; k++) {
        m3[3 * k] = m[4 * k];
        m3[3 * k + 1] = m[4 * k + 1];
        m3[3 * k + 2] = m[4 * k + 2];
    }
    if (!invert3(m3, inv)) return snell__fail(ctx, SNELL_E_INVALID_ARG, "bvh build: %smodel matrix is singular", who);
    return SNELL_OK;
}

static snell_status part_check(snell_ctx *ctx, const snell__bvh_part *pt, const char *who)
{
    uint32_t i;
    if (!pt->positions || !pt->indices || pt->triangle_count == 0 || pt->vertex_count < 3)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "bvh build: %smesh has no triangles", who);
    if (pt->triangle_count > SNELL_MESH_MAX_TRIANGLES || pt->vertex_count > SNELL_MESH_MAX_VERTICES)
        return snell__fail(ctx, SNELL_E_LIMIT, "bvh build: %s%u triangles / %u vertices exceed the mesh limits", who,
                           pt->triangle_count, pt->vertex_count);
    for (i = 0; i < 3 * pt->triangle_count; i++)
        if (pt->indices[i] >= pt->vertex_count)
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "bvh build: %striangle %u references vertex %u of %u", who,
                               i / 3, pt->indices[i], pt->vertex_count);
    return SNELL_OK;
}

snell_status snell__bvh_build_parts(snell_ctx *ctx, const snell__bvh_part *parts, uint32_t part_count, snell__bvh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    snell__bvh *bvh = NULL;
    build_ctx bc;
    double *tv = NULL, m[16], pad, ext = 0.0;
    uint64_t total = 0;
    uint32_t i, j, p, nt;
    int k;
    snell_status st;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "bvh build: out is NULL");
    *out = NULL;
    if (!parts || part_count == 0) return snell__fail(ctx, SNELL_E_INVALID_ARG, "bvh build: no parts");
    for (p = 0; p < part_count; p++) {
        char who[32] = "";
        if (part_count > 1) snprintf(who, sizeof who, "part %u: ", p);
        if ((st = part_check(ctx, &parts[p], who)) != SNELL_OK) return st;
        if ((st = part_model(ctx, &parts[p], who, m)) != SNELL_OK) return st;
        total += parts[p].triangle_count;
    }
    if (total > SNELL__BVH_MAX_TRIANGLES)
        return snell__fail(ctx, SNELL_E_LIMIT, "bvh build: %llu triangles in all exceed the limit %u",
                           (unsigned long long)total, SNELL__BVH_MAX_TRIANGLES);
    nt = (uint32_t)total;

    memset(&bc, 0, sizeof bc);
    bvh = (snell__bvh *)snell__calloc(al, 1, sizeof *bvh);
    if (!bvh) return snell__fail(ctx, SNELL_E_NOMEM, "bvh build: out of memory");
    bvh->alloc = *al;
    bvh->triangle_count = nt;
    bvh->part_count = part_count;
    tv = (double *)snell__calloc(al, 9 * (size_t)nt, sizeof(double));
    bc.prims = (build_prim *)snell__calloc(al, nt, sizeof(build_prim));
    bvh->nodes = (snell__bvh_node *)snell__calloc(al, 2 * (size_t)nt, sizeof(snell__bvh_node));
    bvh->tri_verts = (double *)snell__calloc(al, 9 * (size_t)nt, sizeof(double));
    bvh->tri_ids = (uint32_t *)snell__calloc(al, nt, sizeof(uint32_t));
    bvh->tri_parts = (uint32_t *)snell__calloc(al, nt, sizeof(uint32_t));
    bvh->part_first = (uint32_t *)snell__calloc(al, (size_t)part_count + 1, sizeof(uint32_t));
    if (!tv || !bc.prims || !bvh->nodes || !bvh->tri_verts || !bvh->tri_ids || !bvh->tri_parts ||
        !bvh->part_first) {
        snell__free(al, tv);
        snell__free(al, bc.prims);
        snell__bvh_destroy(bvh);
        return snell__fail(ctx, SNELL_E_NOMEM, "bvh build: out of memory for %u triangles", nt);
    }
    for (k = 0; k < 3; k++) {
        bvh->bmin[k] = HUGE_VAL;
        bvh->bmax[k] = -HUGE_VAL;
    }
    for (p = 0, i = 0; p < part_count; p++) {
        const snell__bvh_part *pt = &parts[p];
        uint32_t t;
        part_model(ctx, pt, "", m); /* validated above */
        bvh->part_first[p] = i;
        for (t = 0; t < pt->triangle_count; t++, i++) {
            build_prim *bp = &bc.prims[i];
            for (j = 0; j < 3; j++) {
                const float *q = pt->positions + 3 * (size_t)pt->indices[3 * (size_t)t + j];
                double *w = tv + 9 * (size_t)i + 3 * j;
                for (k = 0; k < 3; k++) {
                    w[k] = m[k] * q[0] + m[4 + k] * q[1] + m[8 + k] * q[2] + m[12 + k];
                    if (j == 0 || w[k] < bp->lo[k]) bp->lo[k] = w[k];
                    if (j == 0 || w[k] > bp->hi[k]) bp->hi[k] = w[k];
                }
            }
            for (k = 0; k < 3; k++) {
                bp->c[k] = 0.5 * (bp->lo[k] + bp->hi[k]);
                if (bp->lo[k] < bvh->bmin[k]) bvh->bmin[k] = bp->lo[k];
                if (bp->hi[k] > bvh->bmax[k]) bvh->bmax[k] = bp->hi[k];
            }
            bp->t = i;
        }
    }
    bvh->part_first[part_count] = nt;
    bc.bvh = bvh;
    bc.next_node = 1;
    build_node(&bc, 0, 0, nt, 1);
    bvh->node_count = bc.next_node;

    /* Pad every box by a margin far above the rounding of the slab test
     * (a few ulps of the coordinates) so traversal never culls a box that the
     * watertight triangle test would hit. */
    for (k = 0; k < 3; k++) {
        double e = fabs(bvh->bmin[k]) > fabs(bvh->bmax[k]) ? fabs(bvh->bmin[k]) : fabs(bvh->bmax[k]);
        if (e > ext) ext = e;
    }
    pad = 1e-10 * (ext > 0.0 ? ext : 1.0);
    for (i = 0; i < bvh->node_count; i++)
        for (k = 0; k < 3; k++) {
            bvh->nodes[i].bmin[k] -= pad;
            bvh->nodes[i].bmax[k] += pad;
        }
    for (i = 0; i < nt; i++) {
        uint32_t id = bc.prims[i].t, lo = 0, hi = part_count - 1;
        memcpy(bvh->tri_verts + 9 * (size_t)i, tv + 9 * (size_t)id, 9 * sizeof(double));
        bvh->tri_ids[i] = id;
        while (lo < hi) { /* the last part whose first id is <= id */
            uint32_t mid = (lo + hi + 1) / 2;
            if (bvh->part_first[mid] <= id)
                lo = mid;
            else
                hi = mid - 1;
        }
        bvh->tri_parts[i] = lo;
    }
    snell__free(al, tv);
    snell__free(al, bc.prims);
    *out = bvh;
    return SNELL_OK;
}

snell_status snell__bvh_build(snell_ctx *ctx, const float *positions, uint32_t nv, const uint32_t *indices, uint32_t nt,
                              const float *model, snell__bvh **out)
{
    snell__bvh_part pt;
    pt.positions = positions;
    pt.vertex_count = nv;
    pt.indices = indices;
    pt.triangle_count = nt;
    pt.model = model;
    return snell__bvh_build_parts(ctx, &pt, 1, out);
}

snell_status snell__bvh_build_mesh(snell_ctx *ctx, const snell_mesh *mesh, const float *model, snell__bvh **out)
{
    if (!mesh) {
        if (out) *out = NULL;
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "bvh build: mesh is NULL");
    }
    return snell__bvh_build(ctx, mesh->positions, mesh->vertex_count, mesh->indices, mesh->triangle_count, model,
                            out);
}

void snell__bvh_destroy(snell__bvh *bvh)
{
    snell_alloc al;
    if (!bvh) return;
    al = bvh->alloc;
    snell__free(&al, bvh->nodes);
    snell__free(&al, bvh->tri_verts);
    snell__free(&al, bvh->tri_ids);
    snell__free(&al, bvh->tri_parts);
    snell__free(&al, bvh->part_first);
    snell__free(&al, bvh);
}
