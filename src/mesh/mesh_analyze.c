/* mesh_analyze.c — the "analyze" stage (DESIGN.md): closedness, convexity and
 * the centre for the normal+distance cubemap with the share of surface that
 * the cubemap cannot represent (snell_mesh_analyze, declared in snell.h).
 *
 * Why: Li et al.'s method as in Unger 4.1 stores, per direction from a centre,
 * only the farthest surface. It is exact only if every ray from the centre
 * crosses the surface once (the mesh is star-shaped about the centre); Unger
 * 4.4 shows what goes wrong otherwise (Abb. 22/23). The seed takes the vertex
 * average as the centre; here candidates are scored by exact ray casts against
 * a CPU BVH (ref_bvh.h) in object space and the best one is kept. */
#include "mesh/mesh.h"
#include "ref/ref_bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define COARSE_SAMPLES 192   /* per candidate while choosing */
#define FINE_SAMPLES 4096    /* for the reported hidden_fraction (sampling error ~1.6%) */
#define GRID 4               /* interior grid candidates: GRID^3 cell centres of the box */
#define MAX_CANDIDATES (4 + GRID * GRID * GRID + 27)
#define MAX_CROSSINGS 100000 /* parity walk cap (a ray cannot cross more than all triangles anyway) */

/* Three fixed directions with irrational-looking components, so that a parity
 * ray through a vertex or along an edge has probability ~0. */
static const double k_parity_dirs[3][3] = {
    {0.5773502691896258, 0.6123724356957945, 0.5400617248673217},
    {-0.7071067811865476, 0.3141592653589793, -0.6324555320336759},
    {0.1234567890123457, -0.9238795325112867, 0.3623577544766736}};

typedef struct analyzer {
    const snell_mesh *m;
    snell__bvh *bvh;
    double *cdf;             /* cumulative triangle areas, normalised to 1 */
    double area;
    int closed;
} analyzer;

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

typedef struct vert_rec {
    float p[3];
    uint32_t id;
} vert_rec;

static int cmp_vert(const void *x, const void *y)
{
    const vert_rec *p = (const vert_rec *)x, *q = (const vert_rec *)y;
    int k;
    for (k = 0; k < 3; k++)
        if (p->p[k] != q->p[k]) return p->p[k] < q->p[k] ? -1 : 1;
    return p->id < q->id ? -1 : p->id > q->id;
}

/* Welds vertices at identical positions (seams of flat-shaded or UV meshes
 * split them), then checks that every edge has exactly two triangles running
 * it in opposite directions (closed, consistently oriented 2-manifold) and,
 * if so, that every edge is locally convex: the far vertex of one triangle
 * lies on the inner side of the other's plane. A closed connected surface
 * that is locally convex everywhere bounds a convex solid. Signed volume
 * decides which side is "inner" (the mesh may be wound inside out). */
static snell_status topology(const snell_mesh *m, int *closed, int *convex, double *volume, double vcentroid[3])
{
    const snell_alloc *al = &m->alloc;
    uint32_t nv = m->vertex_count, nt = m->triangle_count, i, run;
    vert_rec *order = (vert_rec *)snell__calloc(al, nv, sizeof *order);
    uint32_t *weld = (uint32_t *)snell__calloc(al, nv, sizeof *weld);
    edge_rec *e = (edge_rec *)snell__calloc(al, (size_t)nt * 3, sizeof *e);
    double vol = 0.0, c[3] = {0, 0, 0}, scale = 0.0;
    int k, ok = 1, cvx = 1;
    if (!order || !weld || !e) {
        snell__free(al, order);
        snell__free(al, weld);
        snell__free(al, e);
        return snell__fail(m->ctx, SNELL_E_NOMEM, "snell_mesh_analyze: out of memory");
    }
    for (i = 0; i < nv; i++) {
        memcpy(order[i].p, m->positions + 3 * (size_t)i, sizeof order[i].p);
        order[i].id = i;
    }
    qsort(order, nv, sizeof *order, cmp_vert);
    for (i = 0; i < nv; i++)
        weld[order[i].id] = (i > 0 && order[i - 1].p[0] == order[i].p[0] &&
                                       order[i - 1].p[1] == order[i].p[1] && order[i - 1].p[2] == order[i].p[2])
                                ? weld[order[i - 1].id]
                                : order[i].id;
    for (k = 0; k < 3; k++) scale = fmax(scale, (double)m->bmax[k] - m->bmin[k]);

    for (i = 0; i < nt; i++) {
        double v[3][3], n[3];
        int j;
        tri_verts(m, i, v);
        tri_cross(v, n);
        /* Signed tetrahedron volumes against the origin (divergence theorem). */
        {
            double t6 = dot3(v[0], n);
            vol += t6;
            for (k = 0; k < 3; k++) c[k] += t6 * (v[0][k] + v[1][k] + v[2][k]);
        }
        for (j = 0; j < 3; j++) {
            uint32_t a = weld[m->indices[3 * i + j]], b = weld[m->indices[3 * i + (j + 1) % 3]];
            edge_rec *r = &e[3 * (size_t)i + j];
            r->a = a < b ? a : b;
            r->b = a < b ? b : a;
            r->tri = i;
            r->fwd = a < b;
        }
    }
    *volume = vol / 6.0;
    for (k = 0; k < 3; k++) vcentroid[k] = vol != 0.0 ? c[k] / (4.0 * vol) : 0.0;

    qsort(e, (size_t)nt * 3, sizeof *e, cmp_edge);
    for (i = 0; i < 3 * nt && ok; i += run) {
        run = 1;
        while (i + run < 3 * nt && e[i + run].a == e[i].a && e[i + run].b == e[i].b) run++;
        if (e[i].a == e[i].b) continue; /* degenerate edge of a degenerate triangle */
        if (run != 2 || e[i].fwd == e[i + 1].fwd) {
            ok = 0;
            break;
        }
        if (cvx) {
            /* far vertex of triangle 2 against the plane of triangle 1 */
            double v1[3][3], v2[3][3], n[3], len, best = 0.0, d;
            int j;
            tri_verts(m, e[i].tri, v1);
            tri_verts(m, e[i + 1].tri, v2);
            tri_cross(v1, n);
            len = sqrt(dot3(n, n));
            if (len > 0.0) {
                for (j = 0; j < 3; j++) {
                    double w[3] = {v2[j][0] - v1[0][0], v2[j][1] - v1[0][1], v2[j][2] - v1[0][2]};
                    d = dot3(w, n) / len;
                    if (fabs(d) > fabs(best)) best = d;
                }
                /* outward normals: the neighbour must not rise above the plane */
                if ((vol >= 0.0 ? best : -best) > 1e-6 * scale) cvx = 0;
            }
        }
    }
    *closed = ok && nt > 0;
    *convex = *closed && cvx;
    snell__free(al, order);
    snell__free(al, weld);
    snell__free(al, e);
    return SNELL_OK;
}

int snell__mesh_winding(snell_mesh *m)
{
    int closed = 0, convex = 0;
    double volume = 0.0, vc[3];
    if (m->winding_version == m->version) return m->winding;
    if (topology(m, &closed, &convex, &volume, vc) != SNELL_OK) return 0; /* not cached: retried */
    m->winding = closed && volume != 0.0 ? (volume > 0.0 ? 1 : -1) : 0;
    m->winding_version = m->version;
    return m->winding;
}

/* ------------------------------------------------------------ sampling */

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
    tri_verts(m, lo, v);
    for (k = 0; k < 3; k++) p[k] = (1.0 - s) * v[0][k] + s * (1.0 - r2) * v[1][k] + s * r2 * v[2][k];
    return lo;
}

/* Does the line from c through surface point q (on triangle tri) cross the
 * surface anywhere else? Then q is not the single surface the cubemap holds
 * in that direction: something hides it, or it hides something farther. */
static int sample_hidden(const analyzer *an, const double c[3], const double q[3], uint32_t tri)
{
    double d[3] = {q[0] - c[0], q[1] - c[1], q[2] - c[2]};
    const double eps = 1e-7;
    if (dot3(d, d) < 1e-24) return 1; /* the centre lies on the surface: degenerate */
    return snell__bvh_any(an->bvh, c, d, 0.0, 1.0 - eps, tri) ||
           snell__bvh_any(an->bvh, q, d, eps, HUGE_VAL, tri);
}

static double hidden_fraction(const analyzer *an, const double c[3], int n)
{
    int i, hidden = 0;
    for (i = 0; i < n; i++) {
        double q[3];
        uint32_t tri = surface_sample(an, i, n, q);
        hidden += sample_hidden(an, c, q, tri);
    }
    return (double)hidden / n;
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
static int crossings(const analyzer *an, const double p[3], const double dir[3])
{
    double org[3] = {p[0], p[1], p[2]}, tmin = 0.0;
    uint32_t skip = SNELL__BVH_NONE;
    snell__bvh_hit h;
    int n = 0;
    while (n < MAX_CROSSINGS && snell__bvh_closest(an->bvh, org, dir, tmin, HUGE_VAL, skip, &h)) {
        n++;
        tmin = h.t;
        skip = h.tri;
    }
    return n;
}

/* Odd crossing count along all three parity rays: inside a closed mesh. */
static int parity_inside(const analyzer *an, const double p[3])
{
    int k;
    for (k = 0; k < 3; k++)
        if ((crossings(an, p, k_parity_dirs[k]) & 1) == 0) return 0;
    return 1;
}

/* --------------------------------------------------------------- public */

snell_status snell_mesh_analyze(const snell_mesh *m, snell_mesh_analysis *out)
{
    analyzer an;
    double cand[MAX_CANDIDATES][3], volume = 0.0, vc[3], best_c[3] = {0, 0, 0}, best_h = 2.0, sum_area = 0.0;
    double lo[3], hi[3], step[3];
    int ncand = 0, i, j, k, convex = 0, best_inside = 0, have_inside = 0;
    snell_status st;
    uint32_t t;

    if (!m || !out) return snell__fail(m ? m->ctx : NULL, SNELL_E_INVALID_ARG, "snell_mesh_analyze: NULL argument");
    memset(out, 0, sizeof *out);
    if (m->triangle_count == 0 || m->vertex_count == 0)
        return snell__fail(m->ctx, SNELL_E_INVALID_ARG, "snell_mesh_analyze: mesh has no triangles");
    memset(&an, 0, sizeof an);
    an.m = m;
    st = topology(m, &an.closed, &convex, &volume, vc);
    if (st != SNELL_OK) return st;
    an.cdf = (double *)snell__calloc(&m->alloc, m->triangle_count, sizeof *an.cdf);
    if (!an.cdf) return snell__fail(m->ctx, SNELL_E_NOMEM, "snell_mesh_analyze: out of memory");
    st = snell__bvh_build(m->ctx, m->positions, m->vertex_count, m->indices, m->triangle_count, NULL, &an.bvh);
    if (st != SNELL_OK) {
        snell__free(&m->alloc, an.cdf);
        return st;
    }

    /* Area CDF and the area centroid. */
    {
        double ac[3] = {0, 0, 0};
        for (t = 0; t < m->triangle_count; t++) {
            double v[3][3], n[3], a;
            tri_verts(m, t, v);
            tri_cross(v, n);
            a = 0.5 * sqrt(dot3(n, n));
            sum_area += a;
            an.cdf[t] = sum_area;
            for (k = 0; k < 3; k++) ac[k] += a * (v[0][k] + v[1][k] + v[2][k]) / 3.0;
        }
        if (!(sum_area > 0.0)) {
            snell__bvh_destroy(an.bvh);
            snell__free(&m->alloc, an.cdf);
            return snell__fail(m->ctx, SNELL_E_INVALID_ARG, "snell_mesh_analyze: mesh has zero surface area");
        }
        for (t = 0; t < m->triangle_count; t++) an.cdf[t] /= sum_area;
        an.cdf[m->triangle_count - 1] = 1.0;
        an.area = sum_area;
        /* Candidates in order of preference on ties: volume centroid (the
         * natural centre of a solid), area centroid, vertex average (Unger
         * 4.1), box centre, then an interior grid. */
        if (an.closed && fabs(volume) > 0.0)
            for (k = 0; k < 3; k++) cand[ncand][k] = vc[k];
        if (an.closed && fabs(volume) > 0.0) ncand++;
        for (k = 0; k < 3; k++) cand[ncand][k] = ac[k] / sum_area;
        ncand++;
    }
    {
        double avg[3] = {0, 0, 0};
        uint32_t v;
        for (v = 0; v < m->vertex_count; v++)
            for (k = 0; k < 3; k++) avg[k] += m->positions[3 * v + k];
        for (k = 0; k < 3; k++) cand[ncand][k] = avg[k] / m->vertex_count;
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

    /* Score: coarse hidden fraction; inside candidates beat outside ones
     * (parity is meaningful for closed meshes; for open ones it still sorts
     * "probably inside" first). Then refine around the winner on a half-step
     * 3x3x3 grid. */
    for (i = 0; i < ncand; i++) {
        int inside = parity_inside(&an, cand[i]);
        double h;
        if (have_inside && !inside) continue;
        h = hidden_fraction(&an, cand[i], COARSE_SAMPLES);
        if ((inside && !have_inside) || h < best_h) {
            best_h = h;
            memcpy(best_c, cand[i], sizeof best_c);
            best_inside = inside;
            have_inside |= inside;
        }
    }
    ncand = 0;
    for (i = -1; i <= 1; i++)
        for (j = -1; j <= 1; j++)
            for (k = -1; k <= 1; k++) {
                if (!i && !j && !k) continue;
                cand[ncand][0] = best_c[0] + 0.5 * i * step[0];
                cand[ncand][1] = best_c[1] + 0.5 * j * step[1];
                cand[ncand][2] = best_c[2] + 0.5 * k * step[2];
                ncand++;
            }
    if (best_h > 0.0)
        for (i = 0; i < ncand; i++) {
            int inside = parity_inside(&an, cand[i]);
            double h;
            if (best_inside && !inside) continue;
            h = hidden_fraction(&an, cand[i], COARSE_SAMPLES);
            if (h < best_h) {
                best_h = h;
                memcpy(best_c, cand[i], sizeof best_c);
                best_inside = inside;
            }
        }

    out->samples = FINE_SAMPLES;
    out->hidden_fraction = (float)hidden_fraction(&an, best_c, FINE_SAMPLES);
    for (k = 0; k < 3; k++) out->centre[k] = (float)best_c[k];
    {
        double r2 = 0.0;
        uint32_t v;
        for (v = 0; v < m->vertex_count; v++) {
            double d[3];
            for (k = 0; k < 3; k++) d[k] = m->positions[3 * v + k] - best_c[k];
            r2 = fmax(r2, dot3(d, d));
        }
        out->radius = (float)sqrt(r2);
    }
    {
        double r2 = HUGE_VAL, v[3][3];
        uint32_t t;
        for (t = 0; t < m->triangle_count; t++) {
            tri_verts(m, t, v);
            r2 = fmin(r2, dist2_point_triangle(best_c, v));
        }
        /* Rounded down to float: the ball must stay free of surface. */
        out->inner_radius = m->triangle_count ? nextafterf((float)sqrt(r2), 0.0f) : 0.0f;
    }
    out->closed = an.closed;
    out->convex = convex;
    out->inside = an.closed && best_inside;
    out->winding = an.closed && volume != 0.0 ? (volume > 0.0 ? 1 : -1) : 0;
    snell__bvh_destroy(an.bvh);
    snell__free(&m->alloc, an.cdf);
    return SNELL_OK;
}
