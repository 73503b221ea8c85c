/* SPDX-License-Identifier: MIT */
/* mesh_analyze.c — the "analyze" stage (docs/ARCHITECTURE.md "One frame"):
 * topology on position-welded vertices (boundary, non-manifold and flipped
 * edges, closed, convex, winding), the centre for the normal+distance cubemap
 * with the share of surface it cannot represent (snell_mesh_analyze), and its
 * per-version cache on the mesh (snell__mesh_analysis, snell__mesh_winding).
 * Why the centre is searched for (Unger 4.1, 4.4): docs/ARCHITECTURE.md,
 * "Design notes by file". */
#include "mesh/mesh.h"
#include "mesh/bvh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define COARSE_SAMPLES 192   /* per candidate while choosing */
#define FINE_SAMPLES 4096    /* for the reported hidden_fraction (sampling error 1/sqrt(4096)) */
#define GRID 4               /* interior grid candidates: GRID^3 cell centres of the box */
#define MAX_CANDIDATES (4 + GRID * GRID * GRID + 27)
#define MAX_CROSSINGS 100000 /* parity walk cap (a ray cannot cross more than all triangles anyway) */
/* The ray casts' work bound (BVH nodes visited + triangles tested, over the
 * whole analysis). Real meshes need well under 10^6 (bunny, 70k triangles:
 * 6.0e5; horse 4.6e5; every mesh of test_analyze at most 6.0e5): a ray tests
 * a few dozen triangles whatever the mesh size. A ray along which thousands
 * of triangles coincide tests all of them, whichever BVH: one OBJ face of
 * 40,000 repeated corners needed ~10^9 (8.5 s here, >100 s reported under
 * AUTO). The base leaves room for meshes of high depth complexity (a parity
 * ray through D surfaces costs ~20 D steps, 122 candidates x 3 rays: D = 1000
 * nested shells fit); the bound grows with the triangle count (one query may
 * cost up to 3 per triangle), so hitting it costs at most about as long as
 * analysing a clean mesh of that size; beyond it: SNELL_E_LIMIT. */
#define WORK_BASE 8388608.0 /* 2^23 */
/* Depth complexity (snell_mesh_analysis.depth_complexity): lines along
 * DEPTH_DIRS directions spread over a hemisphere (a line's crossings do not
 * depend on its sense), DEPTH_GRID^2 parallel lines each over the bounding
 * sphere's disc. Bunny: 2304 lines, ~2.5e5 BVH steps. */
#define DEPTH_DIRS 16
#define DEPTH_GRID 12
#define WORK_PER_TRIANGLE 256.0

/* Three fixed directions with irrational-looking components, so that a parity
 * ray through a vertex or along an edge has probability ~0. */
static const double k_parity_dirs[3][3] = {
    {0.5773502691896258, 0.6123724356957945, 0.5400617248673217},
    {-0.7071067811865476, 0.3141592653589793, -0.6324555320336759},
    {0.1234567890123457, -0.9238795325112867, 0.3623577544766736}};

typedef struct analyzer {
    const snell_mesh *m;
    snell__bvh *bvh;
    double *cdf;             /* cumulative triangle areas in canonical order, normalised to 1 */
    uint32_t *order;         /* triangles in canonical order (canonical_order): sampling does not
                              * depend on index order, so neither does the analysis */
    double area;
    int closed;
    uint64_t work;           /* BVH work done so far (snell__bvh_*_counted) */
    double work_limit;       /* WORK_BASE + WORK_PER_TRIANGLE * triangles */
} analyzer;

static int over_budget(const analyzer *an) { return (double)an->work > an->work_limit; }

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void tri_verts(const snell_mesh *m, uint32_t t, double v[3][3])
{
    int j, k;
    for (j = 0; j < 3; j++)
        for (k = 0; k < 3; k++) v[j][k] = m->positions[3 * m->indices[3 * t + j] + k];
}

static void tri_cross(double v[3][3], double n[3])
{
    double e1[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
    double e2[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

/* ------------------------------------------------------------- welding */

/* Two vertices are the same point of the surface when a chain of vertices,
 * each within WELD_REL_TOL * (bounding-box diagonal) of the next, joins them
 * (single-linkage clusters): seams of flat-shaded or UV-mapped meshes split
 * vertices, and exporters round the copies differently. The clusters depend
 * on the positions only, not on vertex or triangle order.
 *
 * Method: a uniform grid of cell size h = tol / sqrt(3), so any two points of
 * one cell are within tol and a cell is one cluster without a test. Points
 * within tol lie at most 2 cells apart per axis (tol = 1.73 h), so each pair
 * of non-empty cells up to 2 apart is tested point by point until one pair is
 * within tol (then the cells are joined: union-find). Points straddling a
 * cell face are thereby found like any others. Cost: a sort of the vertices
 * by cell (O(n log n)) and a merge over the sorted cells for their 62
 * neighbours; the point tests are capped (WELD_MAX_TESTS) so that an adversarial
 * file with huge clusters of distinct points just farther apart than tol
 * cannot make the analysis quadratic: it fails with SNELL_E_LIMIT instead. */
#define WELD_REL_TOL 1e-5
#define WELD_KEY_BITS 21 /* per axis: the box spans at most sqrt(3)/WELD_REL_TOL < 2^18 cells */
#define WELD_MAX_TESTS(nv) (32.0 * (double)(nv) + 1048576.0)

typedef struct cell_pt {
    uint64_t key; /* packed cell coordinates */
    uint32_t v; /* vertex index */
} cell_pt;

static int cmp_cell_pt(const void *x, const void *y)
{
    const cell_pt *p = (const cell_pt *)x, *q = (const cell_pt *)y;
    if (p->key != q->key) return p->key < q->key ? -1 : 1;
    return p->v < q->v ? -1 : p->v > q->v;
}

typedef struct welder {
    const snell_mesh *m;
    cell_pt *pts; /* vertices sorted by cell */
    uint32_t *start; /* cell c holds pts[start[c] .. start[c + 1]) */
    uint32_t *parent; /* union-find over cells */
    uint64_t *ckey; /* cell c's key, ascending */
    uint32_t *num;  /* the welded vertex number of each cell, at the end */
    uint32_t ncells;
    double tol2;
    double tests; /* point pairs tested so far */
} welder;

static uint32_t uf_find(uint32_t *parent, uint32_t c)
{
    while (parent[c] != c) {
        parent[c] = parent[parent[c]]; /* path halving */
        c = parent[c];
    }
    return c;
}

/* Joins cells a and b if some point of one is within tol of some point of
 * the other. Returns 0 when the test budget is spent. */
static int weld_cells(welder *w, uint32_t a, uint32_t b, double budget)
{
    uint32_t i, j, ra = uf_find(w->parent, a), rb = uf_find(w->parent, b);
    if (ra == rb) return 1;
    for (i = w->start[a]; i < w->start[a + 1]; i++) {
        const float *p = w->m->positions + 3 * (size_t)w->pts[i].v;
        for (j = w->start[b]; j < w->start[b + 1]; j++) {
            const float *q = w->m->positions + 3 * (size_t)w->pts[j].v;
            double dx = (double)p[0] - q[0], dy = (double)p[1] - q[1], dz = (double)p[2] - q[2];
            if (++w->tests > budget) return 0;
            if (dx * dx + dy * dy + dz * dz <= w->tol2) {
                /* the smaller root wins: the result does not depend on visiting order */
                if (ra < rb)
                    w->parent[rb] = ra;
                else
                    w->parent[ra] = rb;
                return 1;
            }
        }
    }
    return 1;
}

static void weld_free(welder *w)
{
    const snell_alloc *al = &w->m->alloc;
    snell__free(al, w->pts);
    snell__free(al, w->start);
    snell__free(al, w->parent);
    snell__free(al, w->ckey);
    snell__free(al, w->num);
}

/* The weld tolerance: WELD_REL_TOL of the diagonal of the box around the
 * vertices the triangles use (used[v] != 0); that box's minimum in lo. */
static double weld_tolerance(const snell_mesh *m, const unsigned char *used, double lo[3])
{
    double hi[3], d2 = 0.0;
    uint32_t v;
    int k;
    for (k = 0; k < 3; k++) {
        lo[k] = HUGE_VAL;
        hi[k] = -HUGE_VAL;
    }
    for (v = 0; v < m->vertex_count; v++)
        if (used[v])
            for (k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], m->positions[3 * (size_t)v + k]);
                hi[k] = fmax(hi[k], m->positions[3 * (size_t)v + k]);
            }
    for (k = 0; k < 3; k++) d2 += hi[k] > lo[k] ? (hi[k] - lo[k]) * (hi[k] - lo[k]) : 0.0;
    return WELD_REL_TOL * sqrt(d2);
}

/* id[v] = welded vertex of each used vertex v (used[v] != 0; others are left
 * alone: vertices no triangle uses neither count nor join others), numbered
 * 0 .. *count-1 in the cells' sorted (position) order; *tol_out = the
 * tolerance (object units). */
static snell_status weld(const snell_mesh *m, const unsigned char *used, uint32_t *id, uint32_t *count, double *tol_out)
{
    const snell_alloc *al = &m->alloc;
    uint32_t nv = 0, i, c, n;
    double lo[3], tol, h;
    uint32_t near[13]; /* per (dx, dy) of the neighbourhood: the first cell not before its run */
    welder w;
    int k;
    memset(&w, 0, sizeof w);
    w.m = m;
    *tol_out = tol = weld_tolerance(m, used, lo);
    for (i = 0; i < m->vertex_count; i++) nv += used[i] != 0;
    if (!(tol > 0.0)) { /* every used vertex at one point */
        for (i = 0; i < m->vertex_count; i++) id[i] = 0;
        *count = nv ? 1 : 0;
        return SNELL_OK;
    }
    w.tol2 = tol * tol;
    h = tol / sqrt(3.0);
    w.pts = (cell_pt *)snell__calloc(al, nv, sizeof *w.pts);
    if (!w.pts) return snell__fail(m->ctx, SNELL_E_NOMEM, "snell_mesh_analyze: out of memory");
    for (i = 0, n = 0; i < m->vertex_count; i++) {
        uint64_t key = 0;
        if (!used[i]) continue;
        for (k = 0; k < 3; k++) {
            double cell = floor(((double)m->positions[3 * (size_t)i + k] - lo[k]) / h);
            uint64_t ci = cell < 0.0 ? 0u : (uint64_t)cell; /* 0 .. < 2^18 (see WELD_KEY_BITS) */
            key = (key << WELD_KEY_BITS) | ci;
        }
        w.pts[n].key = key;
        w.pts[n].v = i;
        n++;
    }
    qsort(w.pts, nv, sizeof *w.pts, cmp_cell_pt);
    for (i = 0, n = 0; i < nv; i++) n += i == 0 || w.pts[i].key != w.pts[i - 1].key;
    w.ncells = n;
    w.start = (uint32_t *)snell__calloc(al, (size_t)n + 1, sizeof *w.start);
    w.parent = (uint32_t *)snell__calloc(al, n, sizeof *w.parent);
    w.ckey = (uint64_t *)snell__calloc(al, n, sizeof *w.ckey);
    w.num = (uint32_t *)snell__calloc(al, n, sizeof *w.num);
    if (!w.start || !w.parent || !w.ckey || !w.num) {
        weld_free(&w);
        return snell__fail(m->ctx, SNELL_E_NOMEM, "snell_mesh_analyze: out of memory");
    }
    for (i = 0, c = 0; i < nv; i++)
        if (i == 0 || w.pts[i].key != w.pts[i - 1].key) {
            w.ckey[c] = w.pts[i].key;
            w.start[c] = i;
            w.parent[c] = c;
            c++;
        }
    w.start[n] = nv;

    memset(near, 0, sizeof near);
    for (c = 0; c < n; c++) {
        const uint64_t mask = ((uint64_t)1 << WELD_KEY_BITS) - 1, key = w.ckey[c];
        const int64_t cx = (int64_t)(key >> (2 * WELD_KEY_BITS)), cy = (int64_t)((key >> WELD_KEY_BITS) & mask),
                      cz = (int64_t)(key & mask);
        int dx, dy, j = 0;
        /* The 62 offsets lexicographically after (0, 0, 0), each pair of
         * cells once: for each (dx, dy) a run of z in the sorted cells, whose
         * start only moves forward as c does (a merge, not a look-up each). */
        for (dx = 0; dx <= 2; dx++)
            for (dy = dx ? -2 : 0; dy <= 2; dy++, j++) {
                int64_t x = cx + dx, y = cy + dy, z0 = cz + ((dx || dy) ? -2 : 1), z1 = cz + 2;
                uint64_t row, first, last;
                uint32_t q;
                if (y < 0 || x > (int64_t)mask || y > (int64_t)mask) continue;
                row = (uint64_t)x << (2 * WELD_KEY_BITS) | (uint64_t)y << WELD_KEY_BITS;
                first = row | (uint64_t)(z0 < 0 ? 0 : z0);
                last = row | (uint64_t)(z1 > (int64_t)mask ? (int64_t)mask : z1);
                while (near[j] < n && w.ckey[near[j]] < first) near[j]++;
                for (q = near[j]; q < n && w.ckey[q] <= last; q++)
                    if (!weld_cells(&w, c, q, WELD_MAX_TESTS(nv))) {
                        weld_free(&w);
                        return snell__fail(m->ctx, SNELL_E_LIMIT,
                                           "snell_mesh_analyze: %u vertices too densely clustered to weld", nv);
                    }
            }
    }

    /* Number the clusters in cell order: a root is the smallest cell of its
     * cluster (weld_cells keeps the smaller root), so it is numbered before
     * the others are met. */
    for (c = 0, n = 0; c < w.ncells; c++) {
        uint32_t r = uf_find(w.parent, c);
        w.num[c] = r == c ? n++ : w.num[r];
        for (i = w.start[c]; i < w.start[c + 1]; i++) id[w.pts[i].v] = w.num[c];
    }
    *count = n;
    weld_free(&w);
    return SNELL_OK;
}

/* ---------------------------------------------------- closed / convex */

typedef struct edge_rec {
    uint32_t a, b;   /* welded vertex ids, a < b */
    uint32_t tri;
    uint32_t fwd;    /* 1 if the triangle runs a->b */
} edge_rec;

static int cmp_edge(const void *x, const void *y)
{
    const edge_rec *p = (const edge_rec *)x, *q = (const edge_rec *)y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return p->tri < q->tri ? -1 : p->tri > q->tri;
}

/* What topology() finds; the counts are those of snell_mesh_analysis. */
typedef struct topo {
    uint32_t welded, boundary, nonmanifold, flipped, pieces;
    int closed, convex;
    double volume; /* signed, object units^3 (> 0: counter-clockwise faces outward) */
    double vcentroid[3]; /* volume centroid (0 when the volume is 0) */
} topo;

/* On the welded vertices, every edge (pair of welded vertices joined by a
 * triangle side) is counted once by the triangles that use it: one is a
 * boundary edge, three or more a non-manifold one, two running it the same
 * way a flipped one. Triangles with two welded corners equal are left out:
 * they cover no area (a sliver thinner than the weld tolerance, or an index
 * repeated), and their one proper side would pair with itself (a->b and
 * b->a) or add a third use to a good edge. Collinear triangles with three
 * distinct corners stay (they are part of the surface's connectivity, e.g.
 * T-junction fillers). If the mesh is closed, every edge is also tested for
 * local convexity: the far vertex of one triangle must not lie on the outer
 * side of the other's plane by more than CONVEX_SLACK weld tolerances (the
 * tolerance the vertices themselves may be off by). A closed connected
 * surface that is locally convex everywhere bounds a convex solid. Signed
 * volume decides which side is "outer" (the mesh may be wound inside out).
 * Vertices where otherwise separate sheets touch are not detected. A mesh of
 * several pieces (triangles joined by welded corners) is no convex solid,
 * however convex each piece is. */
#define CONVEX_SLACK 4.0

/* Connected pieces of the triangles over their welded corners (parent: room
 * for the welded ids, a union-find forest). */
static uint32_t count_pieces(const snell_mesh *m, const uint32_t *wid, uint32_t nw, uint32_t *parent)
{
    uint32_t i, n = 0, nt = m->triangle_count;
    for (i = 0; i < nw; i++) parent[i] = UINT32_MAX;
    for (i = 0; i < nt; i++) {
        const uint32_t *t = m->indices + 3 * (size_t)i;
        uint32_t j, r[3];
        for (j = 0; j < 3; j++) {
            uint32_t w = wid[t[j]];
            if (parent[w] == UINT32_MAX) {
                parent[w] = w;
                n++;
            }
            r[j] = uf_find(parent, w);
        }
        for (j = 1; j < 3; j++) {
            r[0] = uf_find(parent, r[0]);
            r[j] = uf_find(parent, r[j]);
            if (r[j] != r[0]) {
                parent[r[j]] = r[0];
                n--;
            }
        }
    }
    return n;
}

static snell_status topology(const snell_mesh *m, topo *out)
{
    const snell_alloc *al = &m->alloc;
    uint32_t nv = m->vertex_count, nt = m->triangle_count, i, run;
    uint32_t *wid = (uint32_t *)snell__calloc(al, nv, sizeof *wid);
    unsigned char *used = (unsigned char *)snell__calloc(al, nv, 1);
    edge_rec *e = (edge_rec *)snell__calloc(al, (size_t)nt * 3, sizeof *e);
    double vol = 0.0, c[3] = {0, 0, 0}, slack = 0.0;
    size_t ne = 0;
    int k, cvx = 1;
    snell_status st;
    memset(out, 0, sizeof *out);
    if (!wid || !used || !e) {
        snell__free(al, wid);
        snell__free(al, used);
        snell__free(al, e);
        return snell__fail(m->ctx, SNELL_E_NOMEM, "snell_mesh_analyze: out of memory");
    }
    for (i = 0; i < 3 * nt; i++) used[m->indices[i]] = 1;
    st = weld(m, used, wid, &out->welded, &slack);
    slack *= CONVEX_SLACK;
    snell__free(al, used);
    if (st != SNELL_OK) {
        snell__free(al, wid);
        snell__free(al, e);
        return st;
    }

    for (i = 0; i < nt; i++) {
        double v[3][3], n[3];
        uint32_t w[3];
        int j;
        tri_verts(m, i, v);
        tri_cross(v, n);
        /* Signed tetrahedron volumes against the origin (divergence theorem). */
        {
            double t6 = dot3(v[0], n);
            vol += t6;
            for (k = 0; k < 3; k++) c[k] += t6 * (v[0][k] + v[1][k] + v[2][k]);
        }
        for (j = 0; j < 3; j++) w[j] = wid[m->indices[3 * (size_t)i + j]];
        if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) continue; /* degenerate after welding */
        for (j = 0; j < 3; j++) {
            uint32_t a = w[j], b = w[(j + 1) % 3];
            edge_rec *r = &e[ne++];
            r->a = a < b ? a : b;
            r->b = a < b ? b : a;
            r->tri = i;
            r->fwd = a < b;
        }
    }
    out->volume = vol / 6.0;
    for (k = 0; k < 3; k++) out->vcentroid[k] = vol != 0.0 ? c[k] / (4.0 * vol) : 0.0;

    qsort(e, ne, sizeof *e, cmp_edge);
    for (i = 0; i < ne; i += run) {
        run = 1;
        while (i + run < ne && e[i + run].a == e[i].a && e[i + run].b == e[i].b) run++;
        if (run == 1)
            out->boundary++;
        else if (run > 2)
            out->nonmanifold++;
        else if (e[i].fwd == e[i + 1].fwd)
            out->flipped++;
        else if (cvx) {
            /* the vertex of triangle 2 off the shared edge against the plane of triangle 1 */
            double v1[3][3], v2[3][3], n[3], len;
            int j;
            tri_verts(m, e[i].tri, v1);
            tri_verts(m, e[i + 1].tri, v2);
            tri_cross(v1, n);
            len = sqrt(dot3(n, n));
            for (j = 0; j < 3 && len > 0.0; j++) {
                uint32_t wj = wid[m->indices[3 * (size_t)e[i + 1].tri + j]];
                double wv[3] = {v2[j][0] - v1[0][0], v2[j][1] - v1[0][1], v2[j][2] - v1[0][2]}, d;
                if (wj == e[i].a || wj == e[i].b) continue;
                d = dot3(wv, n) / len;
                /* outward normals: the neighbour must not rise above the plane */
                if ((vol >= 0.0 ? d : -d) > slack) cvx = 0;
            }
        }
    }
    out->closed = ne > 0 && !out->boundary && !out->nonmanifold && !out->flipped;
    /* e is done with: its room (an edge record a triangle side) holds the forest */
    out->pieces = (size_t)out->welded * sizeof(uint32_t) <= (size_t)nt * 3 * sizeof *e
                      ? count_pieces(m, wid, out->welded, (uint32_t *)e)
                      : 0;
    out->convex = out->closed && cvx && out->pieces == 1;
    snell__free(al, wid);
    snell__free(al, e);
    return SNELL_OK;
}

static int winding_of(const topo *t) { return t->closed && t->volume != 0.0 ? (t->volume > 0.0 ? 1 : -1) : 0; }

int snell__mesh_winding(snell_mesh *m)
{
    topo t;
    snell_status st;
    if (m->winding_version == m->version) return m->winding;
    if (m->analysis_version == m->version && m->analysis_status == SNELL_OK) {
        m->winding = m->analysis.winding; /* the same topology, already found */
    } else {
        st = topology(m, &t);
        if (st == SNELL_E_NOMEM) return 0; /* not cached: retried */
        m->winding = st == SNELL_OK ? winding_of(&t) : 0;
    }
    m->winding_version = m->version;
    return m->winding;
}

/* ------------------------------------------------------------ sampling */

/* A triangle's corners rotated so the lexicographically smallest comes
 * first (winding kept): independent of which corner the index list starts at. */
static void canonical_verts(const snell_mesh *m, uint32_t t, double v[3][3])
{
    double w[3][3];
    int first = 0, j, k;
    tri_verts(m, t, w);
    for (j = 1; j < 3; j++)
        for (k = 0; k < 3; k++) {
            if (w[j][k] < w[first][k]) {
                first = j;
                break;
            }
            if (w[j][k] > w[first][k]) break;
        }
    for (j = 0; j < 3; j++) memcpy(v[j], w[(first + j) % 3], sizeof v[j]);
}

typedef struct tri_order {
    double key[9];           /* canonical corners */
    uint32_t t;
} tri_order;

static int cmp_tri_order(const void *x, const void *y)
{
    const tri_order *a = (const tri_order *)x, *b = (const tri_order *)y;
    int k;
    for (k = 0; k < 9; k++)
        if (a->key[k] != b->key[k]) return a->key[k] < b->key[k] ? -1 : 1;
    return 0; /* the same triangle twice: either serves */
}

/* Triangles sorted by their canonical corners: a reordered index list (a
 * vertex-cache optimisation, another exporter) gives the same samples. */
static snell_status canonical_order(const snell_mesh *m, uint32_t *order)
{
    tri_order *tmp = (tri_order *)snell__calloc(&m->alloc, m->triangle_count, sizeof *tmp);
    uint32_t t;
    if (!tmp) return snell__fail(m->ctx, SNELL_E_NOMEM, "snell_mesh_analyze: out of memory");
    for (t = 0; t < m->triangle_count; t++) {
        double v[3][3];
        canonical_verts(m, t, v);
        memcpy(tmp[t].key, v, sizeof tmp[t].key);
        tmp[t].t = t;
    }
    qsort(tmp, m->triangle_count, sizeof *tmp, cmp_tri_order);
    for (t = 0; t < m->triangle_count; t++) order[t] = tmp[t].t;
    snell__free(&m->alloc, tmp);
    return SNELL_OK;
}

/* Sample i of n: an area-weighted stratified point on the surface (triangle by
 * the area CDF at (i+0.5)/n, point by an R2 sequence), deterministic. */
static uint32_t surface_sample(const analyzer *an, int i, int n, double p[3])
{
    const snell_mesh *m = an->m;
    double u = (i + 0.5) / n, r1, r2, s, v[3][3];
    uint32_t lo = 0, hi = m->triangle_count - 1;
    int k;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (an->cdf[mid] < u) lo = mid + 1;
        else hi = mid;
    }
    r1 = fmod(0.5 + 0.7548776662466927 * i, 1.0);
    r2 = fmod(0.5 + 0.5698402909980532 * i, 1.0);
    s = sqrt(r1);
    canonical_verts(m, an->order[lo], v);
    for (k = 0; k < 3; k++) p[k] = (1.0 - s) * v[0][k] + s * (1.0 - r2) * v[1][k] + s * r2 * v[2][k];
    return an->order[lo];
}

/* Does the line from c through surface point q (on triangle tri) cross the
 * surface anywhere else? Then q is not the single surface the cubemap holds
 * in that direction: something hides it, or it hides something farther. */
static int sample_hidden(analyzer *an, const double c[3], const double q[3], uint32_t tri)
{
    double d[3] = {q[0] - c[0], q[1] - c[1], q[2] - c[2]};
    const double eps = 1e-7;
    if (dot3(d, d) < 1e-24) return 1; /* the centre lies on the surface: degenerate */
    return snell__bvh_any_counted(an->bvh, c, d, 0.0, 1.0 - eps, tri, &an->work) ||
           snell__bvh_any_counted(an->bvh, q, d, eps, HUGE_VAL, tri, &an->work);
}

/* Stops early (a meaningless value) once the work bound is spent; the
 * caller then fails. clearance (may be NULL): the distance from c to the
 * nearest sample point, an estimate of how deep inside c lies. */
static double hidden_fraction_clear(analyzer *an, const double c[3], int n, double *clearance)
{
    int i, hidden = 0;
    double near2 = HUGE_VAL;
    for (i = 0; i < n && !over_budget(an); i++) {
        double q[3], d[3];
        uint32_t tri = surface_sample(an, i, n, q);
        hidden += sample_hidden(an, c, q, tri);
        d[0] = q[0] - c[0];
        d[1] = q[1] - c[1];
        d[2] = q[2] - c[2];
        near2 = fmin(near2, dot3(d, d));
    }
    if (clearance) *clearance = sqrt(near2);
    return (double)hidden / n;
}

static double hidden_fraction(analyzer *an, const double c[3], int n)
{
    return hidden_fraction_clear(an, c, n, NULL);
}

/* Is candidate (h, clear) better than the best so far? Lower hidden
 * fraction, but within the coarse estimate's noise (2 sigma at p = 1/2) the
 * one deeper inside wins: a centre near the surface leaves the cubemap few
 * texels and a thin search bracket (the torus: a centre 0.10 from the
 * surface instead of 0.21 doubled the exit-direction error at a hidden
 * fraction 0.02 lower). */
static int better_centre(double h, double clear, double best_h, double best_clear)
{
    const double tie = 1.0 / sqrt((double)COARSE_SAMPLES);
    if (h < best_h - tie) return 1;
    if (h > best_h + tie) return 0;
    return clear > best_clear || (clear == best_clear && h < best_h);
}

/* Squared distance from p to triangle abc (closest point by Voronoi regions,
 * Ericson, Real-Time Collision Detection 5.1.5). */
static double dist2_point_triangle(const double p[3], double v[3][3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3], q[3], d1, d2, d3, d4, d5, d6, va, vb, vc, den, t, w;
    int k;
    for (k = 0; k < 3; k++) {
        ab[k] = v[1][k] - v[0][k];
        ac[k] = v[2][k] - v[0][k];
        ap[k] = p[k] - v[0][k];
        bp[k] = p[k] - v[1][k];
        cp[k] = p[k] - v[2][k];
    }
    d1 = dot3(ab, ap);
    d2 = dot3(ac, ap);
    d3 = dot3(ab, bp);
    d4 = dot3(ac, bp);
    d5 = dot3(ab, cp);
    d6 = dot3(ac, cp);
    vc = d1 * d4 - d3 * d2;
    vb = d5 * d2 - d1 * d6;
    va = d3 * d6 - d5 * d4;
    if (d1 <= 0.0 && d2 <= 0.0) return dot3(ap, ap);                                  /* vertex a */
    if (d3 >= 0.0 && d4 <= d3) return dot3(bp, bp);                                   /* vertex b */
    if (d6 >= 0.0 && d5 <= d6) return dot3(cp, cp);                                   /* vertex c */
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {                                        /* edge ab */
        t = d1 / (d1 - d3);
        for (k = 0; k < 3; k++) q[k] = ap[k] - t * ab[k];
        return dot3(q, q);
    }
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {                                        /* edge ac */
        t = d2 / (d2 - d6);
        for (k = 0; k < 3; k++) q[k] = ap[k] - t * ac[k];
        return dot3(q, q);
    }
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {                              /* edge bc */
        t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (k = 0; k < 3; k++) q[k] = bp[k] - t * (v[2][k] - v[1][k]);
        return dot3(q, q);
    }
    den = va + vb + vc;                                                               /* face */
    if (!(den > 0.0)) return dot3(ap, ap);                                            /* degenerate */
    t = vb / den;
    w = vc / den;
    for (k = 0; k < 3; k++) q[k] = ap[k] - t * ab[k] - w * ac[k];
    return dot3(q, q);
}

/* Crossings of the ray from p along dir (counted one by one, nearest first). */
static int crossings(analyzer *an, const double p[3], const double dir[3])
{
    double org[3] = {p[0], p[1], p[2]}, tmin = 0.0;
    uint32_t skip = SNELL__BVH_NONE;
    snell__bvh_hit h;
    int n = 0;
    while (n < MAX_CROSSINGS && !over_budget(an) &&
           snell__bvh_closest_counted(an->bvh, org, dir, tmin, HUGE_VAL, skip, &h, &an->work)) {
        n++;
        tmin = h.t;
        skip = h.tri;
    }
    return n;
}

/* The most surfaces a line crosses, and the share of hitting lines that
 * cross more than two, over parallel lines in directions of a Fibonacci
 * hemisphere (irrational offsets: no line through a grid of vertices). */
static void depth_complexity(analyzer *an, const double c[3], double radius, int *most, float *deep)
{
    int d, i, j, k, hits = 0, deep_lines = 0;
    *most = 0;
    for (d = 0; d < DEPTH_DIRS && !over_budget(an); d++) {
        double z = 1.0 - (d + 0.5) / DEPTH_DIRS, s = sqrt(fmax(1.0 - z * z, 0.0)), phi = 2.399963229728653 * d;
        double dir[3] = {s * cos(phi), s * sin(phi), z}, a[3], b[3], len;
        /* a, b: an orthonormal basis of the plane across dir */
        if (fabs(dir[0]) < 0.9) {
            a[0] = 0.0, a[1] = dir[2], a[2] = -dir[1];
        } else {
            a[0] = -dir[2], a[1] = 0.0, a[2] = dir[0];
        }
        len = sqrt(dot3(a, a));
        for (k = 0; k < 3; k++) a[k] /= len;
        b[0] = dir[1] * a[2] - dir[2] * a[1];
        b[1] = dir[2] * a[0] - dir[0] * a[2];
        b[2] = dir[0] * a[1] - dir[1] * a[0];
        for (i = 0; i < DEPTH_GRID; i++)
            for (j = 0; j < DEPTH_GRID; j++) {
                double u = ((i + 0.5 + 0.0618 * d) / DEPTH_GRID * 2.0 - 1.0) * radius;
                double v = ((j + 0.5 + 0.0377 * d) / DEPTH_GRID * 2.0 - 1.0) * radius, p[3];
                int n;
                if (u * u + v * v > radius * radius) continue;
                for (k = 0; k < 3; k++) p[k] = c[k] + u * a[k] + v * b[k] - 2.0 * radius * dir[k];
                n = crossings(an, p, dir);
                if (n == 0) continue;
                hits++;
                deep_lines += n > 2;
                if (n > *most) *most = n;
            }
    }
    *deep = hits ? (float)deep_lines / (float)hits : 0.0f;
}

/* Odd crossing count along all three parity rays: inside a closed mesh. */
static int parity_inside(analyzer *an, const double p[3])
{
    int k;
    for (k = 0; k < 3; k++)
        if ((crossings(an, p, k_parity_dirs[k]) & 1) == 0) return 0;
    return 1;
}

/* --------------------------------------------------------------- public */

/* The analyzer of m: its topology (tp), its triangles in canonical order
 * and the BVH its ray casts walk. analyzer_free releases it, whatever failed. */
static snell_status analyzer_init(analyzer *an, const snell_mesh *m, topo *tp)
{
    snell_status st;
    memset(an, 0, sizeof *an);
    an->m = m;
    an->work_limit = WORK_BASE + WORK_PER_TRIANGLE * (double)m->triangle_count;
    st = topology(m, tp);
    if (st != SNELL_OK) return st;
    an->closed = tp->closed;
    an->cdf = (double *)snell__calloc(&m->alloc, m->triangle_count, sizeof *an->cdf);
    an->order = (uint32_t *)snell__calloc(&m->alloc, m->triangle_count, sizeof *an->order);
    st = an->cdf && an->order ? canonical_order(m, an->order)
                              : snell__fail(m->ctx, SNELL_E_NOMEM, "snell_mesh_analyze: out of memory");
    if (st == SNELL_OK)
        st = snell__bvh_build(m->ctx, m->positions, m->vertex_count, m->indices, m->triangle_count, NULL, &an->bvh);
    return st;
}

static void analyzer_free(analyzer *an)
{
    snell__bvh_destroy(an->bvh);
    snell__free(&an->m->alloc, an->cdf);
    snell__free(&an->m->alloc, an->order);
}

/* The area CDF over the triangles in canonical order (surface sampling)
 * and the area centroid, ac. */
static snell_status area_cdf(analyzer *an, double ac[3])
{
    const snell_mesh *m = an->m;
    double sum_area = 0.0;
    uint32_t t;
    int k;
    ac[0] = ac[1] = ac[2] = 0.0;
    for (t = 0; t < m->triangle_count; t++) {
        double v[3][3], n[3], a;
        canonical_verts(m, an->order[t], v);
        tri_cross(v, n);
        a = 0.5 * sqrt(dot3(n, n));
        sum_area += a;
        an->cdf[t] = sum_area;
        for (k = 0; k < 3; k++) ac[k] += a * (v[0][k] + v[1][k] + v[2][k]) / 3.0;
    }
    if (!(sum_area > 0.0))
        return snell__fail(m->ctx, SNELL_E_INVALID_ARG, "snell_mesh_analyze: mesh has zero surface area");
    for (t = 0; t < m->triangle_count; t++) an->cdf[t] /= sum_area;
    an->cdf[m->triangle_count - 1] = 1.0;
    an->area = sum_area;
    for (k = 0; k < 3; k++) ac[k] /= sum_area;
    return SNELL_OK;
}

/* Candidate centres in order of preference on ties: volume centroid (the
 * natural centre of a solid), area centroid ac, vertex average (Unger 4.1),
 * box centre, then an interior grid of cells step. Returns how many. */
static int candidates(const analyzer *an, const topo *tp, const double ac[3], double cand[][3], double step[3])
{
    const snell_mesh *m = an->m;
    double lo[3], hi[3];
    int ncand = 0, i, j, k;
    if (an->closed && fabs(tp->volume) > 0.0) {
        for (k = 0; k < 3; k++) cand[ncand][k] = tp->vcentroid[k];
        ncand++;
    }
    for (k = 0; k < 3; k++) cand[ncand][k] = ac[k];
    ncand++;
    {
        /* Neumaier-compensated: the sum does not depend on the vertex order */
        double avg[3] = {0, 0, 0}, comp[3] = {0, 0, 0};
        uint32_t v;
        for (v = 0; v < m->vertex_count; v++)
            for (k = 0; k < 3; k++) {
                double x = m->positions[3 * v + k], t2 = avg[k] + x;
                comp[k] += fabs(avg[k]) >= fabs(x) ? (avg[k] - t2) + x : (x - t2) + avg[k];
                avg[k] = t2;
            }
        for (k = 0; k < 3; k++) cand[ncand][k] = (avg[k] + comp[k]) / m->vertex_count;
        ncand++;
    }
    for (k = 0; k < 3; k++) {
        lo[k] = m->bmin[k];
        hi[k] = m->bmax[k];
        step[k] = (hi[k] - lo[k]) / GRID;
        cand[ncand][k] = 0.5 * (lo[k] + hi[k]);
    }
    ncand++;
    for (i = 0; i < GRID; i++)
        for (j = 0; j < GRID; j++)
            for (k = 0; k < GRID; k++) {
                cand[ncand][0] = lo[0] + (i + 0.5) * step[0];
                cand[ncand][1] = lo[1] + (j + 0.5) * step[1];
                cand[ncand][2] = lo[2] + (k + 0.5) * step[2];
                ncand++;
            }
    return ncand;
}

/* The best centre so far: its hidden fraction, its clearance, whether it is inside. */
typedef struct centre {
    double c[3], hidden, clear;
    int inside;
} centre;

/* Scores the candidates by a coarse hidden fraction; inside candidates beat
 * outside ones (parity is meaningful for closed meshes; for open ones it
 * still sorts "probably inside" first). */
static void choose_centre(analyzer *an, double cand[][3], int ncand, centre *best)
{
    int i, have_inside = 0;
    for (i = 0; i < ncand && !over_budget(an); i++) {
        int inside = parity_inside(an, cand[i]);
        double h, clear;
        if (have_inside && !inside) continue;
        h = hidden_fraction_clear(an, cand[i], COARSE_SAMPLES, &clear);
        if ((inside && !have_inside) || better_centre(h, clear, best->hidden, best->clear)) {
            best->hidden = h;
            best->clear = clear;
            memcpy(best->c, cand[i], sizeof best->c);
            best->inside = inside;
            have_inside |= inside;
        }
    }
}

/* Then refines around the winner on a half-step 3x3x3 grid. */
static void refine_centre(analyzer *an, const double step[3], centre *best)
{
    double cand[26][3];
    int ncand = 0, i, j, k;
    for (i = -1; i <= 1; i++)
        for (j = -1; j <= 1; j++)
            for (k = -1; k <= 1; k++) {
                if (!i && !j && !k) continue;
                cand[ncand][0] = best->c[0] + 0.5 * i * step[0];
                cand[ncand][1] = best->c[1] + 0.5 * j * step[1];
                cand[ncand][2] = best->c[2] + 0.5 * k * step[2];
                ncand++;
            }
    if (best->hidden > 0.0)
        for (i = 0; i < ncand && !over_budget(an); i++) {
            int inside = parity_inside(an, cand[i]);
            double h, clear;
            if (best->inside && !inside) continue;
            h = hidden_fraction_clear(an, cand[i], COARSE_SAMPLES, &clear);
            if (better_centre(h, clear, best->hidden, best->clear)) {
                best->hidden = h;
                best->clear = clear;
                memcpy(best->c, cand[i], sizeof best->c);
                best->inside = inside;
            }
        }
}

/* The centre as reported (c rounded to float in place), its hidden
 * fraction finely sampled, and the depth complexity about the box centre. */
static void report_centre(analyzer *an, double c[3], snell_mesh_analysis *out)
{
    const snell_mesh *m = an->m;
    double bc[3];
    int k;
    /* The radii are about the centre as reported (float): rounding it
     * moves it by up to half a float ulp, which on a small inner radius far
     * from the origin is more than the radius's own rounding. */
    for (k = 0; k < 3; k++) {
        out->centre[k] = (float)c[k];
        c[k] = out->centre[k];
    }
    out->samples = FINE_SAMPLES;
    out->hidden_fraction = (float)hidden_fraction(an, c, FINE_SAMPLES);
    /* over the sphere about the box centre that holds every vertex */
    for (k = 0; k < 3; k++) bc[k] = 0.5 * ((double)m->bmin[k] + m->bmax[k]);
    depth_complexity(an, bc, (double)m->bradius * 1.0001, &out->depth_complexity, &out->deep_fraction);
}

/* The radii about c: of the sphere holding every vertex, and of the ball
 * free of surface. */
static void report_radii(const snell_mesh *m, const double c[3], snell_mesh_analysis *out)
{
    double r2 = 0.0, v[3][3];
    uint32_t i;
    int k;
    for (i = 0; i < m->vertex_count; i++) {
        double d[3];
        for (k = 0; k < 3; k++) d[k] = m->positions[3 * i + k] - c[k];
        r2 = fmax(r2, dot3(d, d));
    }
    out->radius = (float)sqrt(r2);
    r2 = HUGE_VAL;
    for (i = 0; i < m->triangle_count; i++) {
        tri_verts(m, i, v);
        r2 = fmin(r2, dist2_point_triangle(c, v));
    }
    /* Rounded down to float: the ball must stay free of surface. */
    out->inner_radius = m->triangle_count ? nextafterf((float)sqrt(r2), 0.0f) : 0.0f;
}

static void report_topology(const topo *tp, int inside, snell_mesh_analysis *out)
{
    out->welded_vertices = tp->welded;
    out->boundary_edges = tp->boundary;
    out->nonmanifold_edges = tp->nonmanifold;
    out->flipped_edges = tp->flipped;
    out->closed = tp->closed;
    /* Bends below the edge test's tolerance add up on a finely tessellated
     * concave mesh (a torus of 512 segments): a line crossing it more than
     * twice settles it. Call after report_centre. */
    out->convex = tp->convex && out->depth_complexity <= 2;
    out->pieces = tp->pieces;
    out->inside = tp->closed && inside;
    out->winding = winding_of(tp);
}

static snell_status analyze_unit(const snell_mesh *m, snell_mesh_analysis *out)
{
    analyzer an;
    topo tp;
    double cand[MAX_CANDIDATES][3], ac[3], step[3];
    centre best = {{0, 0, 0}, 2.0, 0.0, 0};
    int ncand;
    snell_status st;

    memset(out, 0, sizeof *out);
    if (m->triangle_count == 0 || m->vertex_count == 0)
        return snell__fail(m->ctx, SNELL_E_INVALID_ARG, "snell_mesh_analyze: mesh has no triangles");
    st = analyzer_init(&an, m, &tp);
    if (st == SNELL_OK) st = area_cdf(&an, ac);
    if (st != SNELL_OK) {
        analyzer_free(&an);
        return st;
    }
    ncand = candidates(&an, &tp, ac, cand, step);
    choose_centre(&an, cand, ncand, &best);
    refine_centre(&an, step, &best);
    report_centre(&an, best.c, out);
    if (over_budget(&an)) {
        analyzer_free(&an);
        memset(out, 0, sizeof *out);
        return snell__fail(m->ctx, SNELL_E_LIMIT,
                           "snell_mesh_analyze: the ray casts exceeded their work bound (%.0f BVH steps for %u "
                           "triangles): many triangles lie on top of each other (duplicated faces?)",
                           an.work_limit, m->triangle_count);
    }
    report_radii(m, best.c, out);
    report_topology(&tp, best.inside, out);
    analyzer_free(&an);
    return SNELL_OK;
}

/* The ray casts' tolerances suit meshes of about unit size: one far smaller
 * (subnormal coordinates included) or larger is analysed as a copy scaled by
 * a power of two, which is exact, and its lengths are scaled back. */
static snell_status analyze(const snell_mesh *m, snell_mesh_analysis *out)
{
    snell_mesh_desc d;
    snell_mesh *copy = NULL;
    float *pos;
    size_t i, n = 3 * (size_t)m->vertex_count;
    snell_status st;
    int e, k;
    frexp((double)m->bradius, &e);
    if (!(m->bradius > 0.0f) || (e >= -16 && e <= 16)) return analyze_unit(m, out);
    if ((st = snell__budget_check(m->ctx, 2 * n * sizeof(float), "the analysis's scaled copy")) != SNELL_OK) return st;
    if (!(pos = (float *)snell__malloc(&m->alloc, n * sizeof *pos)))
        return snell__fail(m->ctx, SNELL_E_NOMEM, "snell_mesh_analyze: out of memory");
    for (i = 0; i < n; i++) pos[i] = ldexpf(m->positions[i], -e);
    memset(&d, 0, sizeof d);
    d.positions = pos;
    d.indices = m->indices;
    d.vertex_count = m->vertex_count;
    d.triangle_count = m->triangle_count;
    st = snell_mesh_create(m->ctx, &d, &copy);
    snell__free(&m->alloc, pos);
    if (st == SNELL_OK) st = analyze_unit(copy, out);
    snell_mesh_destroy(copy);
    if (st != SNELL_OK) return st;
    for (k = 0; k < 3; k++) out->centre[k] = ldexpf(out->centre[k], e);
    out->radius = ldexpf(out->radius, e);
    out->inner_radius = ldexpf(out->inner_radius, e);
    return SNELL_OK;
}

snell_status snell_mesh_analyze(const snell_mesh *m, snell_mesh_analysis *out)
{
    if (!m || !out) return snell__fail(m ? m->ctx : NULL, SNELL_E_INVALID_ARG, "snell_mesh_analyze: NULL argument");
    if (m->analysis_version == m->version && m->analysis_status == SNELL_OK) {
        *out = m->analysis; /* the renderer's cached result for this geometry */
        return SNELL_OK;
    }
    return analyze(m, out);
}

snell_status snell__mesh_analysis(snell_mesh *m, const snell_mesh_analysis **out)
{
    snell_status st;
    if (out) *out = NULL;
    if (!m || !out) return snell__fail(m ? m->ctx : NULL, SNELL_E_INVALID_ARG, "snell__mesh_analysis: NULL argument");
    if (m->analysis_version != m->version) {
        st = analyze(m, &m->analysis);
        if (st == SNELL_E_NOMEM) return st; /* not cached: the next call tries again */
        m->analysis_status = st;
        m->analysis_version = m->version;
        m->analysis_error[0] = '\0';
        if (st != SNELL_OK) snprintf(m->analysis_error, sizeof m->analysis_error, "%s", snell_last_error(m->ctx));
    }
    if (m->analysis_status == SNELL_OK) *out = &m->analysis;
    return m->analysis_status;
}

snell_status snell__mesh_weld(const snell_mesh *m, const unsigned char *used, uint32_t *id, uint32_t *count)
{
    double tol;
    return weld(m, used, id, count, &tol);
}
