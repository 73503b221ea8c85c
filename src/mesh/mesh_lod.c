/* SPDX-License-Identifier: MIT */
/* mesh_lod.c — snell_mesh_simplify: an optional level of detail for meshes
 * whose triangles are far below a pixel, made with meshoptimizer's edge-collapse
 * simplifier on a copy, cleaned so that a closed mesh stays closed: weld by
 * position, meshopt_simplify, remove degenerate and paired triangles, compact
 * and recompute normals. meshoptimizer's scratch comes from its process-wide
 * allocator, bounded beforehand by the memory budget. Each step and why:
 * docs/ARCHITECTURE.md, "Design notes by file". */
#include "mesh/mesh.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef SNELL_WITH_MESHOPT
#include <meshoptimizer.h>
#endif

/* target_error with no target_ratio and no error given (relative to the extent). */
#define DEFAULT_ERROR 0.01f
/* Peak scratch of one call per source vertex and triangle, for the memory
 * budget check: meshoptimizer 0.18's simplifier holds ~82 bytes per vertex
 * (quadrics, remap, adjacency offsets) and ~84 per triangle (adjacency, edge
 * collapses and their order, a copy of the indices) while ours holds 17 and
 * 24 (welded copy, output); the repair afterwards needs less (57 per triangle). */
#define SCRATCH_PER_VERTEX 100u
#define SCRATCH_PER_TRIANGLE 120u

typedef struct lod_params {
    float ratio; /* 0: no count target */
    float error; /* relative; FLT_MAX: unbounded */
    int lock_border;
} lod_params;

static snell_status resolve(snell_ctx *ctx, const snell_simplify_desc *d, lod_params *p)
{
    if (!(d->target_ratio >= 0.0f && d->target_ratio <= 1.0f))
        return snell__fail(ctx, SNELL_E_INVALID_ARG,
                           "snell_mesh_simplify: target_ratio %g is not in [0, 1] (0 = no triangle target)",
                           (double)d->target_ratio);
    if (!(d->target_error >= 0.0f) || !isfinite(d->target_error))
        return snell__fail(ctx, SNELL_E_INVALID_ARG,
                           "snell_mesh_simplify: target_error %g is not a finite number >= 0 (0 = default)",
                           (double)d->target_error);
    p->ratio = d->target_ratio;
    p->error = d->target_error > 0.0f ? d->target_error : d->target_ratio > 0.0f ? FLT_MAX : DEFAULT_ERROR;
    p->lock_border = d->lock_border != 0;
    return SNELL_OK;
}

#ifdef SNELL_WITH_MESHOPT

/* A triangle's corner set with its orientation, for finding triangles on the
 * same three vertices: key = corners sorted, odd = the winding is the sorted
 * order's opposite. */
typedef struct tri_key {
    uint32_t v[3];
    uint32_t tri;
    int odd;
} tri_key;

static int cmp_tri_key(const void *x, const void *y)
{
    const tri_key *p = (const tri_key *)x, *q = (const tri_key *)y;
    int k;
    for (k = 0; k < 3; k++)
        if (p->v[k] != q->v[k]) return p->v[k] < q->v[k] ? -1 : 1;
    if (p->odd != q->odd) return p->odd - q->odd; /* even first, then odd */
    return p->tri < q->tri ? -1 : p->tri > q->tri;
}

static void make_key(const uint32_t *t, uint32_t tri, tri_key *k)
{
    /* rotate the smallest corner first (a rotation keeps the winding) */
    int r = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
    uint32_t a = t[r], b = t[(r + 1) % 3], c = t[(r + 2) % 3];
    k->v[0] = a;
    k->v[1] = b < c ? b : c;
    k->v[2] = b < c ? c : b;
    k->odd = b > c;
    k->tri = tri;
}

/* Drops triangles with a repeated corner and those on the same corner set as
 * another (opposite pairs whole, same-facing copies down to one), in place;
 * returns the number kept. */
static size_t clean_triangles(const snell_alloc *al, uint32_t *idx, size_t nt, snell_simplify_report *rep, int *nomem)
{
    tri_key *keys = (tri_key *)snell__calloc(al, nt ? nt : 1, sizeof *keys);
    unsigned char *drop;
    size_t i, n = 0, run, kept;
    *nomem = 0;
    if (!keys) return *nomem = 1, nt;
    drop = (unsigned char *)snell__calloc(al, nt ? nt : 1, 1);
    if (!drop) {
        snell__free(al, keys);
        return *nomem = 1, nt;
    }
    for (i = 0; i < nt; i++) {
        const uint32_t *t = idx + 3 * i;
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
            drop[i] = 1;
            rep->degenerate_removed++;
        } else {
            make_key(t, (uint32_t)i, &keys[n++]);
        }
    }
    qsort(keys, n, sizeof *keys, cmp_tri_key);
    for (i = 0; i < n; i += run) {
        size_t even = 0, odd, pairs, j;
        run = 1;
        while (i + run < n && !memcmp(keys[i + run].v, keys[i].v, sizeof keys[i].v)) run++;
        if (run == 1) continue;
        for (j = i; j < i + run; j++) even += !keys[j].odd;
        odd = run - even;
        pairs = even < odd ? even : odd;
        rep->duplicate_pairs_removed += (uint32_t)pairs;
        /* keep one of the surplus facing (if any): the first of its run */
        for (j = i; j < i + run; j++) drop[keys[j].tri] = 1;
        if (even != odd) {
            drop[keys[even > odd ? i : i + even].tri] = 0;
            rep->duplicates_removed += (uint32_t)((even > odd ? even - odd : odd - even) - 1);
        }
    }
    for (i = 0, kept = 0; i < nt; i++)
        if (!drop[i]) {
            if (kept != i) memmove(idx + 3 * kept, idx + 3 * i, 3 * sizeof *idx);
            kept++;
        }
    snell__free(al, keys);
    snell__free(al, drop);
    return kept;
}

/* ------------------------------------------------- non-manifold edges */
/* meshoptimizer 0.18 does not test the link condition, so a collapse can
 * make two sheets of the surface meet along an edge: four triangles on it,
 * two running it each way (seen on the sphere and the goblet at ratios 0.5 and
 * 0.25). The surface stays balanced there, but the analysis counts the edge
 * non-manifold and the mesh open. Such an edge is collapsed (its second end
 * joins its first, the four triangles vanish, the two sheets now touch at a
 * vertex, which the analysis does not check), then cleaning runs again; this
 * repeats until no edge made by the simplifier has more than two triangles.
 * Edges that were non-manifold in the source are left as they are, and with
 * lock_border a vertex of the source's boundary is never the one that moves. */
#define REPAIR_ROUNDS 32

typedef struct edge_use {
    uint32_t a, b; /* a < b */
    uint32_t fwd; /* 1: the triangle runs a->b */
} edge_use;

static int cmp_edge_use(const void *x, const void *y)
{
    const edge_use *p = (const edge_use *)x, *q = (const edge_use *)y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return (int)p->fwd - (int)q->fwd;
}

/* The sides of nt triangles (3 * nt entries of e), sorted by edge. */
static void edges_of(const uint32_t *idx, size_t nt, edge_use *e)
{
    size_t t;
    int j;
    for (t = 0; t < nt; t++)
        for (j = 0; j < 3; j++) {
            uint32_t a = idx[3 * t + j], b = idx[3 * t + (j + 1) % 3];
            edge_use *u = &e[3 * t + j];
            u->a = a < b ? a : b;
            u->b = a < b ? b : a;
            u->fwd = a < b;
        }
    qsort(e, 3 * nt, sizeof *e, cmp_edge_use);
}

/* Length of the run of equal edges starting at e[i] (n entries), and how many run forward. */
static size_t edge_run(const edge_use *e, size_t n, size_t i, size_t *fwd)
{
    size_t r = 0;
    *fwd = 0;
    while (i + r < n && e[i + r].a == e[i].a && e[i + r].b == e[i].b) *fwd += e[i + r++].fwd;
    return r;
}

/* What the repair must respect from the welded source: its non-manifold
 * edges (sorted, a < b pairs) and, with lock_border, its boundary vertices. */
typedef struct source_topo {
    edge_use *nonmanifold;
    size_t nonmanifold_count;
    unsigned char *pinned; /* NULL without lock_border */
} source_topo;

static int is_source_nonmanifold(const source_topo *s, uint32_t a, uint32_t b)
{
    edge_use key;
    size_t lo = 0, hi = s->nonmanifold_count;
    key.a = a;
    key.b = b;
    key.fwd = 0;
    while (lo < hi) { /* the entries have fwd 0: compare a, b only */
        size_t mid = (lo + hi) / 2;
        const edge_use *m = &s->nonmanifold[mid];
        if (m->a < key.a || (m->a == key.a && m->b < key.b))
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < s->nonmanifold_count && s->nonmanifold[lo].a == a && s->nonmanifold[lo].b == b;
}

static snell_status source_topology(const snell_alloc *al, const uint32_t *idx, size_t nt, uint32_t nw, int lock_border,
                                    source_topo *s)
{
    edge_use *e = (edge_use *)snell__calloc(al, 3 * nt, sizeof *e);
    size_t i, run, fwd, n = 0;
    memset(s, 0, sizeof *s);
    if (lock_border) s->pinned = (unsigned char *)snell__calloc(al, nw, 1);
    if (!e || (lock_border && !s->pinned)) {
        snell__free(al, e);
        snell__free(al, s->pinned);
        s->pinned = NULL;
        return SNELL_E_NOMEM;
    }
    edges_of(idx, nt, e);
    for (i = 0; i < 3 * nt; i += run) {
        run = edge_run(e, 3 * nt, i, &fwd);
        if (run > 2) {
            e[n] = e[i]; /* n <= i: compacted in place, still sorted */
            e[n++].fwd = 0;
        }
        if (s->pinned && 2 * fwd != run) s->pinned[e[i].a] = s->pinned[e[i].b] = 1; /* unpaired side */
    }
    s->nonmanifold = e;
    s->nonmanifold_count = n;
    if (n < 3 * nt) { /* give back what the list does not use (none, for a closed source) */
        edge_use *shrunk = (edge_use *)snell__realloc(al, e, (n ? n : 1) * sizeof *e);
        if (shrunk) s->nonmanifold = shrunk;
    }
    return SNELL_OK;
}

/* Cleans idx (nt triangles on vertices 0..nw-1) and collapses the
 * non-manifold edges the simplifier made; returns the triangles kept. */
static size_t repair(const snell_alloc *al, uint32_t *idx, size_t nt, uint32_t nw, const source_topo *src,
                     snell_simplify_report *rep, int *nomem)
{
    edge_use *e = (edge_use *)snell__calloc(al, 3 * (nt ? nt : 1), sizeof *e);
    uint32_t *to = (uint32_t *)snell__calloc(al, nw, sizeof *to);
    unsigned char *touched = (unsigned char *)snell__calloc(al, nw, 1);
    int round;
    *nomem = !e || !to || !touched;
    for (round = 0; round < REPAIR_ROUNDS && !*nomem; round++) {
        size_t i, run, fwd, found = 0;
        uint32_t v;
        nt = clean_triangles(al, idx, nt, rep, nomem);
        if (*nomem) break;
        edges_of(idx, nt, e);
        for (v = 0; v < nw; v++) to[v] = v;
        memset(touched, 0, nw);
        for (i = 0; i < 3 * nt; i += run) {
            uint32_t a = e[i].a, b = e[i].b, keep, move;
            run = edge_run(e, 3 * nt, i, &fwd);
            if (run <= 2 || is_source_nonmanifold(src, a, b)) continue;
            if (src->pinned && src->pinned[a] && src->pinned[b]) continue;
            if (touched[a] || touched[b]) continue; /* one collapse per vertex and round */
            move = src->pinned && src->pinned[b] ? a : b;
            keep = move == a ? b : a;
            to[move] = keep;
            touched[a] = touched[b] = 1;
            found++;
        }
        if (!found) break;
        rep->nonmanifold_collapsed += (uint32_t)found;
        for (i = 0; i < 3 * nt; i++) idx[i] = to[idx[i]];
    }
    if (round == REPAIR_ROUNDS && !*nomem) nt = clean_triangles(al, idx, nt, rep, nomem);
    snell__free(al, e);
    snell__free(al, to);
    snell__free(al, touched);
    return nt;
}

/* Scratch of one simplification. */
typedef struct lod_work {
    const snell_alloc *al; /* the context's */
    unsigned char *used;
    uint32_t *wid; /* source vertex -> welded vertex */
    float *wpos; /* welded positions */
    uint32_t *widx, *dst; /* welded triangles; simplified triangles */
    uint32_t *remap; /* welded vertex -> output vertex */
} lod_work;

static void work_free(lod_work *w)
{
    snell__free(w->al, w->used);
    snell__free(w->al, w->wid);
    snell__free(w->al, w->wpos);
    snell__free(w->al, w->widx);
    snell__free(w->al, w->dst);
    snell__free(w->al, w->remap);
}

/* Steps 1 and 2: the welded mesh (w->wpos, *nw vertices; w->widx, *ntw
 * triangles with three distinct welded corners). */
static snell_status weld_copy(snell_ctx *ctx, const snell_mesh *src, lod_work *w, uint32_t *nw, size_t *ntw,
                              snell_simplify_report *rep)
{
    uint32_t nv = src->vertex_count, v, i;
    size_t nt = src->triangle_count, t, n = 0;
    snell_status st;
    w->used = (unsigned char *)snell__calloc(w->al, nv, 1);
    w->wid = (uint32_t *)snell__calloc(w->al, nv, sizeof *w->wid);
    w->widx = (uint32_t *)snell__calloc(w->al, 3 * nt, sizeof *w->widx);
    if (!w->used || !w->wid || !w->widx)
        return snell__fail(ctx, SNELL_E_NOMEM, "snell_mesh_simplify: out of memory for %u vertices", nv);
    for (i = 0; i < 3 * nt; i++) w->used[src->indices[i]] = 1;
    st = snell__mesh_weld(src, w->used, w->wid, nw);
    if (st != SNELL_OK)
        return ctx == src->ctx ? st : snell__fail(ctx, st, "snell_mesh_simplify: %s", snell_last_error(src->ctx));
    w->wpos = (float *)snell__calloc(w->al, 3 * (size_t)*nw, sizeof *w->wpos);
    if (!w->wpos) return snell__fail(ctx, SNELL_E_NOMEM, "snell_mesh_simplify: out of memory for %u vertices", nv);
    /* a welded vertex sits where its lowest-numbered source vertex does */
    for (v = nv; v-- > 0;)
        if (w->used[v]) memcpy(w->wpos + 3 * (size_t)w->wid[v], src->positions + 3 * (size_t)v, 3 * sizeof(float));
    for (t = 0; t < nt; t++) {
        uint32_t a = w->wid[src->indices[3 * t]], b = w->wid[src->indices[3 * t + 1]],
                 c = w->wid[src->indices[3 * t + 2]];
        if (a == b || b == c || c == a) { /* no area after welding: the analysis ignores it too */
            rep->degenerate_removed++;
            continue;
        }
        w->widx[3 * n] = a;
        w->widx[3 * n + 1] = b;
        w->widx[3 * n + 2] = c;
        n++;
    }
    *ntw = n;
    if (n == 0) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_simplify: no triangle has area after welding");
    return SNELL_OK;
}

static snell_status simplify(snell_ctx *ctx, const snell_mesh *src, const lod_params *p, snell_mesh **out,
                             snell_simplify_report *rep)
{
    lod_work w;
    uint32_t nw = 0, nout = 0, i;
    size_t ntw = 0, target, nidx, nt;
    float *pos;
    uint32_t *idx;
    float res_error = 0.0f;
    source_topo topo;
    int nomem;
    snell_status st;
    memset(&w, 0, sizeof w);
    w.al = snell__ctx_alloc(ctx);
    st = snell__budget_check(
        ctx, (size_t)SCRATCH_PER_VERTEX * src->vertex_count + (size_t)SCRATCH_PER_TRIANGLE * src->triangle_count,
        "snell_mesh_simplify: scratch");
    if (st == SNELL_OK) st = weld_copy(ctx, src, &w, &nw, &ntw, rep);
    if (st != SNELL_OK) {
        work_free(&w);
        return st;
    }
    /* Step 3's cleaning before the simplifier too: it would remove the same
     * triangles afterwards, and each copy costs the simplifier as a distinct
     * triangle on the same vertices (one OBJ face of 120,000 repeated
     * corners is 40,000 copies of one triangle, 1.3 s in meshopt_simplify). */
    ntw = clean_triangles(w.al, w.widx, ntw, rep, &nomem);
    if (nomem) {
        work_free(&w);
        return snell__fail(ctx, SNELL_E_NOMEM, "snell_mesh_simplify: out of memory for %zu triangles", ntw);
    }
    {
        /* meshoptimizer's simplifier tests each triangle of a vertex on every
         * collapse onto it: its cost grows with the square of the corners on
         * a vertex, as the vertex-cache reorder's does (mesh_gpu.c: the
         * estimate and its bound, which real meshes stay far below; a large
         * fan about one vertex takes minutes without it) */
        double work = 0.0, limit = snell__mesh_work_limit(3 * ntw);
        uint32_t top = 0;
        st = snell__mesh_work_estimate(ctx, w.al, w.widx, 3 * ntw, nw, &work, &top);
        if (st == SNELL_OK && work > limit)
            st = snell__fail(ctx, SNELL_E_LIMIT,
                             "snell_mesh_simplify: the simplifier's work estimate %.3g (sum over vertices of their "
                             "triangle corners squared) is over its bound %.3g: %u corners on one vertex",
                             work, limit, top);
        if (st != SNELL_OK) {
            work_free(&w);
            return st;
        }
    }
    w.dst = (uint32_t *)snell__calloc(w.al, 3 * ntw, sizeof *w.dst);
    w.remap = (uint32_t *)snell__calloc(w.al, nw, sizeof *w.remap);
    if (!w.dst || !w.remap) {
        work_free(&w);
        return snell__fail(ctx, SNELL_E_NOMEM, "snell_mesh_simplify: out of memory for %zu triangles", ntw);
    }
    if (source_topology(w.al, w.widx, ntw, nw, p->lock_border, &topo) != SNELL_OK) {
        work_free(&w);
        return snell__fail(ctx, SNELL_E_NOMEM, "snell_mesh_simplify: out of memory for %zu triangles", ntw);
    }
    /* the ratio is of the source's triangles; at least one triangle is asked for */
    target = 0;
    if (p->ratio > 0.0f) {
        double want = floor((double)p->ratio * (double)src->triangle_count + 0.5);
        target = 3 * (size_t)(want < 1.0 ? 1.0 : want);
        if (target > 3 * ntw) target = 3 * ntw; /* degenerate ones were dropped: meshoptimizer asserts */
    }
    nidx = meshopt_simplify(w.dst, w.widx, 3 * ntw, w.wpos, nw, 3 * sizeof(float), target, p->error,
                            p->lock_border ? meshopt_SimplifyLockBorder : 0, &res_error);
    nt = repair(w.al, w.dst, nidx / 3, nw, &topo, rep, &nomem);
    snell__free(w.al, topo.nonmanifold);
    snell__free(w.al, topo.pinned);
    if (nomem) {
        work_free(&w);
        return snell__fail(ctx, SNELL_E_NOMEM, "snell_mesh_simplify: out of memory for %zu triangles", ntw);
    }
    if (nt == 0) {
        work_free(&w);
        return snell__fail(ctx, SNELL_E_INVALID_ARG,
                           "snell_mesh_simplify: nothing is left of the mesh (%zu triangles before cleaning)",
                           nidx / 3);
    }
    /* step 4: vertices in first-use order */
    memset(w.remap, 0xff, (size_t)nw * sizeof *w.remap);
    for (i = 0; i < 3 * nt; i++)
        if (w.remap[w.dst[i]] == 0xffffffffu) w.remap[w.dst[i]] = nout++;
    pos = (float *)snell__calloc(w.al, 3 * (size_t)nout, sizeof *pos);
    idx = (uint32_t *)snell__calloc(w.al, 3 * nt, sizeof *idx);
    if (!pos || !idx) {
        snell__free(w.al, pos);
        snell__free(w.al, idx);
        work_free(&w);
        return snell__fail(ctx, SNELL_E_NOMEM, "snell_mesh_simplify: out of memory for %zu triangles", nt);
    }
    for (i = 0; i < nw; i++)
        if (w.remap[i] != 0xffffffffu) memcpy(pos + 3 * (size_t)w.remap[i], w.wpos + 3 * (size_t)i, 3 * sizeof *pos);
    for (i = 0; i < 3 * nt; i++) idx[i] = w.remap[w.dst[i]];
    rep->error = res_error;
    rep->error_abs = res_error * meshopt_simplifyScale(w.wpos, nw, 3 * sizeof(float));
    rep->welded_vertices = nw;
    work_free(&w);
    /* takes pos and idx (freed on failure); normals computed: smooth, area-weighted */
    st = snell__mesh_adopt(ctx, snell__ctx_alloc(ctx), pos, NULL, idx, nout, (uint32_t)nt, out);
    if (st == SNELL_OK) {
        rep->triangles_after = (uint32_t)nt;
        rep->vertices_after = nout;
    }
    return st;
}

#endif /* SNELL_WITH_MESHOPT */

snell_status snell_mesh_simplify(snell_ctx *ctx, const snell_mesh *src, const snell_simplify_desc *desc,
                                 snell_mesh **out, snell_simplify_report *report)
{
    snell_simplify_report rep;
    lod_params p;
    snell_status st;
    memset(&rep, 0, sizeof rep);
    memset(&p, 0, sizeof p);
    if (report) *report = rep;
    if (out) *out = NULL;
    if (!src || !desc || !out)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_simplify: src, desc and out are required");
    if ((st = resolve(ctx, desc, &p)) != SNELL_OK) return st;
    rep.triangles_before = src->triangle_count;
    rep.vertices_before = src->vertex_count;
#ifdef SNELL_WITH_MESHOPT
    st = simplify(ctx, src, &p, out, &rep);
#else
    (void)p;
    st = snell__fail(ctx, SNELL_E_UNSUPPORTED,
                     "snell_mesh_simplify: built without meshoptimizer (configure with -DSNELL_WITH_MESHOPT=ON)");
#endif
    if (report) *report = rep;
    return st;
}
