/* SPDX-License-Identifier: MIT */
/* lm2d_bvh.c — perimeter-SAH BVH over 2D edges and its nearest-first traversal
 * (Brückner 6.3, 6.4.1.1-6.4.1.4). */
#include "lm2d/lm2d_bvh.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LM2D_MAX_EDGES (1 << 26)  /* leaf code packs first << 5 into an int32 */
#define MEDIAN_DEPTH 48           /* below this depth splits are by median: depth stays < 96 */

typedef struct box2 {
    float lo[2], hi[2];
} box2;

typedef struct key_idx {
    float key;
    int32_t idx;
} key_idx;

typedef struct build_state {
    const float *segs;   /* 4 floats per edge: p1, p2 */
    int32_t *order;      /* edge indices being partitioned */
    key_idx *keys;       /* scratch for sorting */
    int32_t *tmp;        /* scratch: sorted order per axis */
    float *left_cost;    /* scratch: prefix perimeters */
    lm2d_node *nodes;
    int n_nodes, cap_nodes;
    int leaf_size;
    float pad;           /* absolute box expansion */
} build_state;

static void box_empty(box2 *b)
{
    b->lo[0] = b->lo[1] = FLT_MAX;
    b->hi[0] = b->hi[1] = -FLT_MAX;
}

static void box_add_edge(box2 *b, const float *s)
{
    int k;
    for (k = 0; k < 2; k++) {
        float a = s[k], c = s[2 + k];
        float mn = a < c ? a : c, mx = a < c ? c : a;
        if (mn < b->lo[k]) b->lo[k] = mn;
        if (mx > b->hi[k]) b->hi[k] = mx;
    }
}

static float box_perimeter(const box2 *b)
{
    return 2.0f * ((b->hi[0] - b->lo[0]) + (b->hi[1] - b->lo[1]));
}

/* 6.4.1.4.1: boxes of two consecutive edges share a side exactly; a ray
 * (nearly) parallel to it can slip between them through rounding. Grow every
 * box by a few ulps of its coordinates plus a tiny absolute margin. */
static box2 box_expand(box2 b, float pad)
{
    int k;
    for (k = 0; k < 2; k++) {
        b.lo[k] -= fabsf(b.lo[k]) * 4.0f * FLT_EPSILON + pad;
        b.hi[k] += fabsf(b.hi[k]) * 4.0f * FLT_EPSILON + pad;
    }
    return b;
}

static int cmp_key(const void *a, const void *b)
{
    const key_idx *x = (const key_idx *)a, *y = (const key_idx *)b;
    if (x->key < y->key) return -1;
    if (x->key > y->key) return 1;
    return (x->idx > y->idx) - (x->idx < y->idx); /* deterministic ties */
}

static void sort_axis(build_state *st, int lo, int hi, int axis)
{
    int i;
    for (i = lo; i < hi; i++) {
        const float *s = st->segs + 4 * st->order[i];
        st->keys[i].key = s[axis] + s[2 + axis]; /* twice the centroid */
        st->keys[i].idx = st->order[i];
    }
    qsort(st->keys + lo, (size_t)(hi - lo), sizeof(key_idx), cmp_key);
}

/* Algorithm 2: every split position on both axes, cost eq. 6.2 with the
 * perimeter as probability. Leaves st->order[lo,hi) sorted on the best axis and
 * returns the split index (first of the right half). */
static int sah_split(build_state *st, int lo, int hi, int depth)
{
    int axis, i, best_axis = 0, best = (lo + hi) / 2;
    float best_cost = FLT_MAX;
    if (depth >= MEDIAN_DEPTH) {
        box2 b;
        box_empty(&b);
        for (i = lo; i < hi; i++) box_add_edge(&b, st->segs + 4 * st->order[i]);
        best_axis = (b.hi[0] - b.lo[0]) >= (b.hi[1] - b.lo[1]) ? 0 : 1;
    } else {
        for (axis = 0; axis < 2; axis++) {
            box2 b;
            sort_axis(st, lo, hi, axis);
            box_empty(&b);
            for (i = lo; i < hi - 1; i++) {
                box_add_edge(&b, st->segs + 4 * st->keys[i].idx);
                st->left_cost[i] = box_perimeter(&b) * (float)(i - lo + 1);
            }
            box_empty(&b);
            for (i = hi - 1; i > lo; i--) {
                float c;
                box_add_edge(&b, st->segs + 4 * st->keys[i].idx);
                c = st->left_cost[i - 1] + box_perimeter(&b) * (float)(hi - i);
                if (c < best_cost) {
                    best_cost = c;
                    best_axis = axis;
                    best = i;
                }
            }
        }
    }
    sort_axis(st, lo, hi, best_axis);
    for (i = lo; i < hi; i++) st->order[i] = st->keys[i].idx;
    return best;
}

/* Returns the child code of [lo,hi) and its box; -1 - ... codes are leaves. */
static int32_t build_rec(build_state *st, int lo, int hi, int depth, box2 *out_box)
{
    box2 b;
    int i, mid, node;
    box2 cb[2];
    int32_t cc[2];
    box_empty(&b);
    for (i = lo; i < hi; i++) box_add_edge(&b, st->segs + 4 * st->order[i]);
    *out_box = box_expand(b, st->pad);
    if (hi - lo <= st->leaf_size) return ~(int32_t)(((uint32_t)lo << 5) | (uint32_t)(hi - lo));
    mid = sah_split(st, lo, hi, depth);
    node = st->n_nodes++; /* capacity n - 1 inner nodes is enough for a binary tree */
    cc[0] = build_rec(st, lo, mid, depth + 1, &cb[0]);
    cc[1] = build_rec(st, mid, hi, depth + 1, &cb[1]);
    for (i = 0; i < 2; i++) {
        st->nodes[node].lo_x[i] = cb[i].lo[0];
        st->nodes[node].lo_y[i] = cb[i].lo[1];
        st->nodes[node].hi_x[i] = cb[i].hi[0];
        st->nodes[node].hi_y[i] = cb[i].hi[1];
        st->nodes[node].child[i] = cc[i];
    }
    return node;
}

void lm2d_bvh_free(const snell_alloc *al, lm2d_bvh *bvh)
{
    if (!bvh) return;
    snell__free(al, bvh->nodes);
    snell__free(al, bvh->geo);
    snell__free(al, bvh->prim);
    memset(bvh, 0, sizeof *bvh);
}

snell_status lm2d_bvh_build(const snell_ctx *ctx, const snell_alloc *al, const float *segs, int n,
                            int leaf_size, lm2d_bvh *bvh)
{
    build_state st;
    box2 root;
    int i;
    float extent = 0.0f;
    int32_t code;
    memset(bvh, 0, sizeof *bvh);
    if (leaf_size < 1 || leaf_size > LM2D_BVH_MAX_LEAF)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "bvh2d: leaf size %d outside [1,%d]", leaf_size,
                           LM2D_BVH_MAX_LEAF);
    if (n < 0 || n >= LM2D_MAX_EDGES)
        return snell__fail(ctx, SNELL_E_LIMIT, "bvh2d: %d edges (limit %d)", n, LM2D_MAX_EDGES - 1);
    bvh->leaf_size = leaf_size;
    if (n == 0) return SNELL_OK;
    memset(&st, 0, sizeof st);
    st.segs = segs;
    st.leaf_size = leaf_size;
    st.order = (int32_t *)snell__calloc(al, (size_t)n, sizeof(int32_t));
    st.keys = (key_idx *)snell__calloc(al, (size_t)n, sizeof(key_idx));
    st.left_cost = (float *)snell__calloc(al, (size_t)n, sizeof(float));
    st.nodes = (lm2d_node *)snell__calloc(al, (size_t)n, sizeof(lm2d_node));
    bvh->geo = (float *)snell__calloc(al, (size_t)n, 4 * sizeof(float));
    bvh->prim = (int32_t *)snell__calloc(al, (size_t)n, sizeof(int32_t));
    if (!st.order || !st.keys || !st.left_cost || !st.nodes || !bvh->geo || !bvh->prim) {
        snell__free(al, st.order);
        snell__free(al, st.keys);
        snell__free(al, st.left_cost);
        snell__free(al, st.nodes);
        lm2d_bvh_free(al, bvh);
        return snell__fail(ctx, SNELL_E_NOMEM, "bvh2d: out of memory for %d edges", n);
    }
    box_empty(&root);
    for (i = 0; i < n; i++) {
        st.order[i] = i;
        box_add_edge(&root, segs + 4 * i);
    }
    extent = (root.hi[0] - root.lo[0]) + (root.hi[1] - root.lo[1]);
    st.pad = extent * 1e-6f;
    code = build_rec(&st, 0, n, 0, &root);
    bvh->nodes = st.nodes;
    bvh->n_nodes = st.n_nodes;
    bvh->root_is_leaf = code < 0;
    bvh->root_leaf = code;
    bvh->lo[0] = root.lo[0];
    bvh->lo[1] = root.lo[1];
    bvh->hi[0] = root.hi[0];
    bvh->hi[1] = root.hi[1];
    for (i = 0; i < n; i++) {
        const float *s = segs + 4 * st.order[i];
        bvh->geo[4 * i + 0] = s[0];
        bvh->geo[4 * i + 1] = s[1];
        bvh->geo[4 * i + 2] = s[2] - s[0];
        bvh->geo[4 * i + 3] = s[3] - s[1];
        bvh->prim[i] = st.order[i];
    }
    bvh->n_prims = n;
    snell__free(al, st.order);
    snell__free(al, st.keys);
    snell__free(al, st.left_cost);
    return SNELL_OK;
}

/* A zero direction component would give inf * 0 = NaN in the slab test; a tiny
 * stand-in keeps every product finite and ordered (the box is then hit exactly
 * when the origin lies within that slab). */
static inline float safe_inv(float v)
{
    if (fabsf(v) < 1e-30f) v = v < 0.0f ? -1e-30f : 1e-30f;
    return 1.0f / v;
}

/* min/max as one instruction: fminf/fmaxf are library calls without
 * -ffast-math (they must return the non-NaN operand); the slab operands here
 * are finite (safe_inv), so the results are the same, without the calls
 * (bench/notes/code.md, "lm2d_bvh.c"). */
static inline float min2(float a, float b) { return a < b ? a : b; }
static inline float max2(float a, float b) { return a > b ? a : b; }

float lm2d_slab(const float lo[2], const float hi[2], const float o[2], const float inv[2], float t_max)
{
    float tx0 = (lo[0] - o[0]) * inv[0], tx1 = (hi[0] - o[0]) * inv[0];
    float ty0 = (lo[1] - o[1]) * inv[1], ty1 = (hi[1] - o[1]) * inv[1];
    float tn = max2(min2(tx0, tx1), min2(ty0, ty1));
    float tf = min2(max2(tx0, tx1), max2(ty0, ty1));
    if (tn < 0.0f) tn = 0.0f; /* origin inside: entry at 0 (6.4.1.1) */
    if (tn > tf || tn >= t_max) return INFINITY;
    return tn;
}

static inline void test_leaf(const lm2d_bvh *bvh, int32_t code, const float o[2], const float d[2], float t_min,
                             float *t_best, int *best, int skip)
{
    uint32_t c = (uint32_t)~code;
    int first = (int)(c >> 5), cnt = (int)(c & 31u), i;
    const float *g = bvh->geo + 4 * first;
    for (i = 0; i < cnt; i++, g += 4) {
        float den = d[0] * g[3] - d[1] * g[2];
        float wx = g[0] - o[0], wy = g[1] - o[1];
        float tn, sn, inv;
        if (den == 0.0f) continue;
        inv = 1.0f / den;
        tn = (wx * g[3] - wy * g[2]) * inv;
        if (!(tn > t_min) || !(tn < *t_best)) continue;
        sn = (wx * d[1] - wy * d[0]) * inv;
        if (sn < -LM2D_S_EPS || sn > 1.0f + LM2D_S_EPS) continue;
        if (bvh->prim[first + i] == skip) continue;
        *t_best = tn;
        *best = bvh->prim[first + i];
    }
}

int lm2d_bvh_intersect(const lm2d_bvh *bvh, const float o[2], const float d[2], float t_min, float *t_hit,
                       int skip)
{
    int32_t stack_code[LM2D_BVH_STACK];
    float stack_t[LM2D_BVH_STACK];
    int sp = 0, best = -1;
    float t_best = *t_hit;
    float inv[2];
    int32_t cur;
    int nx, ny;
    if (bvh->n_prims == 0) return -1;
    if (bvh->root_is_leaf) {
        test_leaf(bvh, bvh->root_leaf, o, d, t_min, &t_best, &best, skip);
        if (best >= 0) *t_hit = t_best;
        return best;
    }
    inv[0] = safe_inv(d[0]);
    inv[1] = safe_inv(d[1]);
    /* Per-ray slab order: for a negative direction the far plane is lo (saves min/max). */
    nx = inv[0] < 0.0f;
    ny = inv[1] < 0.0f;
    cur = 0;
    for (;;) {
        if (cur >= 0) {
            const lm2d_node *n = bvh->nodes + cur;
            const float *xn = nx ? n->hi_x : n->lo_x, *xf = nx ? n->lo_x : n->hi_x;
            const float *yn = ny ? n->hi_y : n->lo_y, *yf = ny ? n->lo_y : n->hi_y;
            float a0 = max2((xn[0] - o[0]) * inv[0], (yn[0] - o[1]) * inv[1]);
            float b0 = min2((xf[0] - o[0]) * inv[0], (yf[0] - o[1]) * inv[1]);
            float a1 = max2((xn[1] - o[0]) * inv[0], (yn[1] - o[1]) * inv[1]);
            float b1 = min2((xf[1] - o[0]) * inv[0], (yf[1] - o[1]) * inv[1]);
            int h0, h1;
            b0 = min2(b0, t_best);
            b1 = min2(b1, t_best);
            h0 = a0 <= b0 && b0 >= 0.0f;
            h1 = a1 <= b1 && b1 >= 0.0f;
            if (h0 && h1) {
                /* nearer child first, the other waits on the stack with its entry distance */
                if (a1 < a0) {
                    stack_code[sp] = n->child[0];
                    stack_t[sp++] = a0;
                    cur = n->child[1];
                } else {
                    stack_code[sp] = n->child[1];
                    stack_t[sp++] = a1;
                    cur = n->child[0];
                }
                continue;
            }
            if (h0) {
                cur = n->child[0];
                continue;
            }
            if (h1) {
                cur = n->child[1];
                continue;
            }
        } else {
            test_leaf(bvh, cur, o, d, t_min, &t_best, &best, skip);
        }
        /* Algorithm 4 lines 21-24: resume with a stacked node only if it may hold a nearer hit. */
        for (;;) {
            if (sp == 0) goto done;
            --sp;
            if (stack_t[sp] < t_best) break;
        }
        cur = stack_code[sp];
    }
done:
    if (best >= 0) *t_hit = t_best;
    return best;
}

int lm2d_brute_intersect(const lm2d_bvh *bvh, const float o[2], const float d[2], float t_min, float *t_hit,
                         int skip)
{
    int i, best = -1;
    float t_best = *t_hit, t;
    for (i = 0; i < bvh->n_prims; i++) {
        if (bvh->prim[i] == skip) continue;
        if (lm2d_ray_segment(o, d, bvh->geo + 4 * i, bvh->geo + 4 * i + 2, t_min, &t) && t < t_best) {
            t_best = t;
            best = bvh->prim[i];
        }
    }
    if (best >= 0) *t_hit = t_best;
    return best;
}
