/* SPDX-License-Identifier: MIT */
/* test_mesh_shapes.c — procedural shapes: closed and consistently wound (every
 * directed edge once, its reverse once, after welding equal positions), positive
 * volume near the analytic one, outward analytic normals, inside/outside by the
 * generalised winding number (concave goblet bowl), and argument limits. */
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static const float *g_pos; /* for qsort */

static int cmp_vertex(const void *a, const void *b)
{
    const float *p = g_pos + 3 * *(const uint32_t *)a, *q = g_pos + 3 * *(const uint32_t *)b;
    int k;
    for (k = 0; k < 3; k++)
        if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
    return 0;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Closed, consistently oriented 2-manifold (after welding bit-equal positions)? */
static int check_closed(const snell_mesh *m, const char *name)
{
    uint32_t nv = snell_mesh_vertex_count(m), nt = snell_mesh_triangle_count(m), i, *order, *weld;
    const uint32_t *idx = snell_mesh_indices(m);
    uint64_t *edges;
    int ok = 1;
    order = (uint32_t *)malloc(nv * sizeof *order);
    weld = (uint32_t *)malloc(nv * sizeof *weld);
    edges = (uint64_t *)malloc(3 * (size_t)nt * sizeof *edges);
    if (!order || !weld || !edges) return 0;
    for (i = 0; i < nv; i++) order[i] = i;
    g_pos = snell_mesh_positions(m);
    qsort(order, nv, sizeof *order, cmp_vertex);
    for (i = 0; i < nv; i++)
        weld[order[i]] = (i > 0 && cmp_vertex(&order[i], &order[i - 1]) == 0) ? weld[order[i - 1]] : order[i];
    for (i = 0; i < nt; i++) {
        int k;
        for (k = 0; k < 3; k++) {
            uint32_t a = weld[idx[3 * i + k]], b = weld[idx[3 * i + (k + 1) % 3]];
            if (a == b) ok = 0; /* degenerate triangle */
            edges[3 * i + k] = ((uint64_t)a << 32) | b;
        }
    }
    CHECK(ok, "%s: degenerate triangles", name);
    qsort(edges, 3 * (size_t)nt, sizeof *edges, cmp_u64);
    for (i = 0; i < 3 * nt && ok; i++) {
        uint64_t rev = (edges[i] << 32) | (edges[i] >> 32);
        if (i > 0 && edges[i] == edges[i - 1]) ok = 0; /* same direction twice: flipped face or non-manifold */
        if (!bsearch(&rev, edges, 3 * (size_t)nt, sizeof *edges, cmp_u64)) ok = 0; /* boundary edge */
    }
    CHECK(ok, "%s: not a closed consistently wound manifold", name);
    free(order);
    free(weld);
    free(edges);
    return ok;
}

static double signed_volume(const snell_mesh *m)
{
    const float *p = snell_mesh_positions(m);
    const uint32_t *idx = snell_mesh_indices(m);
    double v = 0.0;
    uint32_t t;
    for (t = 0; t < snell_mesh_triangle_count(m); t++) {
        const float *a = p + 3 * idx[3 * t], *b = p + 3 * idx[3 * t + 1], *c = p + 3 * idx[3 * t + 2];
        v += (double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) +
             (double)a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
             (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
    }
    return v / 6.0;
}

/* Generalised winding number (sum of signed solid angles / 4 pi, Van
 * Oosterom & Strackee): 1 inside a closed outward-oriented surface, 0 outside. */
static double winding(const snell_mesh *m, double x, double y, double z)
{
    const float *p = snell_mesh_positions(m);
    const uint32_t *idx = snell_mesh_indices(m);
    double w = 0.0;
    uint32_t t;
    for (t = 0; t < snell_mesh_triangle_count(m); t++) {
        double a[3], b[3], c[3], la, lb, lc, det, den;
        int k;
        for (k = 0; k < 3; k++) {
            a[k] = p[3 * idx[3 * t] + k] - (k == 0 ? x : k == 1 ? y : z);
            b[k] = p[3 * idx[3 * t + 1] + k] - (k == 0 ? x : k == 1 ? y : z);
            c[k] = p[3 * idx[3 * t + 2] + k] - (k == 0 ? x : k == 1 ? y : z);
        }
        la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        det = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
        den = la * lb * lc + (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) * lc +
              (a[0] * c[0] + a[1] * c[1] + a[2] * c[2]) * lb + (b[0] * c[0] + b[1] * c[1] + b[2] * c[2]) * la;
        w += 2.0 * atan2(det, den);
    }
    return w / (4.0 * PI);
}

/* Every vertex normal agrees with the geometric normal of each face using it
 * (cos > min_cos) and is unit length. */
static void check_normals_outward(const snell_mesh *m, const char *name, double min_cos)
{
    const float *p = snell_mesh_positions(m), *n = snell_mesh_normals(m);
    const uint32_t *idx = snell_mesh_indices(m);
    uint32_t t, bad = 0, badlen = 0, i;
    double worst = 1.0;
    for (t = 0; t < snell_mesh_triangle_count(m); t++) {
        const float *a = p + 3 * idx[3 * t], *b = p + 3 * idx[3 * t + 1], *c = p + 3 * idx[3 * t + 2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double gl = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        int k;
        for (k = 0; k < 3; k++) {
            const float *vn = n + 3 * idx[3 * t + k];
            double cs = (g[0] * vn[0] + g[1] * vn[1] + g[2] * vn[2]) / gl;
            if (cs < worst) worst = cs;
            if (!(cs > min_cos)) bad++;
        }
    }
    for (i = 0; i < snell_mesh_vertex_count(m); i++) {
        const float *v = n + 3 * i;
        if (fabs(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1.0) > 1e-5) badlen++;
    }
    CHECK(bad == 0, "%s: %u vertex normals disagree with their face (worst cos %.3f)", name, bad, worst);
    CHECK(badlen == 0, "%s: %u normals not unit", name, badlen);
}

static snell_mesh *make(snell_shape s, int seg, int rings)
{
    snell_shape_desc d;
    snell_mesh *m = NULL;
    memset(&d, 0, sizeof d);
    d.shape = s;
    d.segments = seg;
    d.rings = rings;
    CHECK_OK(snell_mesh_create_shape(NULL, &d, &m));
    return m;
}

static void test_sphere(int seg, int rings)
{
    snell_mesh *m = make(SNELL_SHAPE_SPHERE, seg, rings);
    int S = seg ? seg : 64, R = rings ? rings : 32;
    double v, vin;
    uint32_t i, bad = 0;
    if (!m) return;
    CHECK(snell_mesh_vertex_count(m) == (uint32_t)(S * (R - 1) + 2), "sphere vertices %u", snell_mesh_vertex_count(m));
    CHECK(snell_mesh_triangle_count(m) == (uint32_t)(2 * S * (R - 1)), "sphere triangles");
    check_closed(m, "sphere");
    /* inscribed polyhedron: volume a little below 4/3 pi, never above */
    v = signed_volume(m);
    vin = 4.0 / 3.0 * PI;
    CHECK(v > 0.0 && v <= vin && v > vin * (1.0 - 2.0 * (PI / R) * (PI / R) - 2.0 * (PI / S) * (PI / S)),
          "sphere %dx%d volume %.5f vs %.5f", S, R, v, vin);
    for (i = 0; i < snell_mesh_vertex_count(m); i++) {
        const float *p = snell_mesh_positions(m) + 3 * i, *n = snell_mesh_normals(m) + 3 * i;
        if (fabsf(p[0] - n[0]) + fabsf(p[1] - n[1]) + fabsf(p[2] - n[2]) > 1e-6f ||
            fabsf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 1.0f) > 1e-6f)
            bad++;
    }
    CHECK(bad == 0, "sphere: %u vertices off the unit sphere or with a non-radial normal", bad);
    /* coarse spheres (3 x 2 is a bipyramid) deviate more from the analytic normal */
    check_normals_outward(m, "sphere", S * R < 64 ? 0.4 : 0.5);
    CHECK(fabs(winding(m, 0, 0, 0) - 1.0) < 1e-6, "sphere: origin inside");
    CHECK(fabs(winding(m, 0.1, -0.1, 0.15) - 1.0) < 1e-6, "sphere: interior point inside");
    CHECK(fabs(winding(m, 0, 0, 1.5)) < 1e-6, "sphere: outside point");
    snell_mesh_destroy(m);
}

static void test_cube(void)
{
    snell_mesh *m = make(SNELL_SHAPE_CUBE, 0, 0);
    float mn[3], mx[3];
    if (!m) return;
    CHECK(snell_mesh_vertex_count(m) == 24 && snell_mesh_triangle_count(m) == 12, "cube counts");
    check_closed(m, "cube");
    CHECK(fabs(signed_volume(m) - 8.0) < 1e-9, "cube volume %.9f", signed_volume(m));
    check_normals_outward(m, "cube", 0.9999999); /* flat: vertex normal == face normal */
    snell_mesh_bounds(m, mn, mx);
    CHECK(mn[0] == -1 && mn[1] == -1 && mn[2] == -1 && mx[0] == 1 && mx[1] == 1 && mx[2] == 1, "cube bounds");
    CHECK(fabs(winding(m, 0.9, -0.9, 0.5) - 1.0) < 1e-9 && fabs(winding(m, 1.1, 0, 0)) < 1e-9, "cube inside/outside");
    snell_mesh_destroy(m);
}

static void test_prism(void)
{
    snell_mesh *m = make(SNELL_SHAPE_PRISM, 0, 0);
    double area = 3.0 * sqrt(3.0) / 4.0; /* equilateral triangle of circumradius 1 */
    float mn[3], mx[3];
    if (!m) return;
    CHECK(snell_mesh_vertex_count(m) == 18 && snell_mesh_triangle_count(m) == 8, "prism counts");
    check_closed(m, "prism");
    CHECK(fabs(signed_volume(m) - 2.0 * area) < 1e-6, "prism volume %.9f vs %.9f", signed_volume(m), 2.0 * area);
    check_normals_outward(m, "prism", 0.9999999); /* flat: vertex normal == face normal */
    snell_mesh_bounds(m, mn, mx);
    CHECK(mn[0] == -0.5f && mx[0] == 1.0f && mn[1] == -1.0f && mx[1] == 1.0f &&
          fabsf(mx[2] - 0.8660254f) < 1e-6f && fabsf(mn[2] + 0.8660254f) < 1e-6f, "prism bounds");
    CHECK(fabs(winding(m, 0.9, 0.5, 0.0) - 1.0) < 1e-9 && fabs(winding(m, -0.45, -0.9, 0.9)) < 1e-9 && fabs(winding(m, -0.45, -0.9, 0.8) - 1.0) < 1e-9 &&
          fabs(winding(m, -0.6, 0, 0)) < 1e-9, "prism inside/outside");
    snell_mesh_destroy(m);
}

static void test_torus(void)
{
    snell_mesh *m = make(SNELL_SHAPE_TORUS, 64, 32);
    double v, vt = 2.0 * PI * PI * 1.0 * 0.4 * 0.4; /* Pappus: 2 pi R * pi r^2 */
    float mn[3], mx[3];
    uint32_t i, bad = 0;
    if (!m) return;
    CHECK(snell_mesh_vertex_count(m) == 64 * 32 && snell_mesh_triangle_count(m) == 2 * 64 * 32, "torus counts");
    check_closed(m, "torus");
    v = signed_volume(m);
    CHECK(v > 0.98 * vt && v < vt, "torus volume %.5f vs %.5f", v, vt);
    /* analytic normal: from the nearest point of the core circle (radius 1, y = 0) */
    for (i = 0; i < snell_mesh_vertex_count(m); i++) {
        const float *p = snell_mesh_positions(m) + 3 * i, *n = snell_mesh_normals(m) + 3 * i;
        double rxz = sqrt((double)p[0] * p[0] + (double)p[2] * p[2]);
        double c[3] = {p[0] / rxz, 0.0, p[2] / rxz};
        double d[3] = {(p[0] - c[0]) / 0.4, p[1] / 0.4, (p[2] - c[2]) / 0.4};
        if (fabs(d[0] - n[0]) + fabs(d[1] - n[1]) + fabs(d[2] - n[2]) > 1e-5) bad++;
    }
    CHECK(bad == 0, "torus: %u non-analytic normals", bad);
    check_normals_outward(m, "torus", 0.5);
    snell_mesh_bounds(m, mn, mx);
    CHECK(fabsf(mx[0] - 1.4f) < 1e-6f && fabsf(mn[1] + 0.4f) < 1e-6f && fabsf(mx[1] - 0.4f) < 1e-6f, "torus bounds");
    CHECK(fabs(winding(m, 1.0, 0, 0) - 1.0) < 1e-6 && fabs(winding(m, 0, 0, -1.0) - 1.0) < 1e-6, "torus: tube inside");
    CHECK(fabs(winding(m, 0, 0, 0)) < 1e-6, "torus: hole outside");
    snell_mesh_destroy(m);
}

static void test_goblet(int seg, int rings)
{
    snell_mesh *m = make(SNELL_SHAPE_GOBLET, seg, rings);
    float mn[3], mx[3];
    double v;
    if (!m) return;
    check_closed(m, "goblet");
    v = signed_volume(m);
    /* glass volume: positive and far below its bounding cylinder (it is mostly air) */
    snell_mesh_bounds(m, mn, mx);
    CHECK(v > 0.0 && v < 0.25 * PI * mx[0] * mx[0] * (mx[1] - mn[1]), "goblet volume %.5f", v);
    CHECK(mn[1] == -1.0f && mx[1] <= 1.0f && mx[1] > 0.995f, "goblet height: y %g..%g", mn[1], mx[1]);
    CHECK(mx[0] > 0.5f && mx[0] < 0.6f && fabsf(mx[0] + mn[0]) < 1e-3f && fabsf(mx[2] + mn[2]) < 1e-3f,
          "goblet radius %g..%g, centred on the axis", mn[0], mx[0]);
    check_normals_outward(m, "goblet", 0.3);
    /* solid parts are inside, the bowl's cavity is outside (the shape is concave) */
    CHECK(fabs(winding(m, 0, -0.98, 0) - 1.0) < 1e-6, "goblet: foot centre inside");
    CHECK(fabs(winding(m, 0.4, -0.975, 0.0) - 1.0) < 1e-6, "goblet: foot rim inside");
    CHECK(fabs(winding(m, 0, 0, 0) - 1.0) < 1e-6, "goblet: stem inside");
    CHECK(fabs(winding(m, 0, 0.6, 0)) < 1e-6, "goblet: bowl cavity outside");
    CHECK(fabs(winding(m, 0.3, 0.6, 0.2)) < 1e-6, "goblet: bowl cavity off-axis outside");
    CHECK(fabs(winding(m, 0.3, 0.0, 0)) < 1e-6, "goblet: beside the stem outside");
    CHECK(fabs(winding(m, 0, 1.2, 0)) < 1e-6, "goblet: above outside");
    /* a point inside the bowl wall (between inner radius 0.525 and outer 0.575
     * about the bowl centre, which lies on the axis at y = 1 - 0.025 - 0.55 sin 15deg) */
    {
        double yc = 1.0 - 0.025 - 0.55 * sin(15.0 * PI / 180.0);
        CHECK(fabs(winding(m, 0.55, yc, 0) - 1.0) < 1e-6, "goblet: bowl wall inside");
        CHECK(fabs(winding(m, 0, yc - 0.55, 0) - 1.0) < 1e-6, "goblet: bowl bottom inside");
    }
    snell_mesh_destroy(m);
}

static void test_limits(void)
{
    snell_shape_desc d;
    snell_mesh *m = (snell_mesh *)&d;
    snell_status st;
    memset(&d, 0, sizeof d);
    d.segments = 5000;
    st = snell_mesh_create_shape(NULL, &d, &m);
    CHECK(st == SNELL_E_LIMIT && m == NULL && snell_last_error(NULL)[0], "segments 5000: %s", snell_status_str(st));
    d.segments = 64;
    d.rings = -3;
    st = snell_mesh_create_shape(NULL, &d, &m);
    CHECK(st == SNELL_E_INVALID_ARG, "negative rings: %s", snell_status_str(st));
    d.rings = 1;
    st = snell_mesh_create_shape(NULL, &d, &m);
    CHECK(st == SNELL_E_INVALID_ARG, "1 ring: %s", snell_status_str(st));
    d.rings = 0;
    d.shape = (snell_shape)99;
    st = snell_mesh_create_shape(NULL, &d, &m);
    CHECK(st == SNELL_E_INVALID_ARG, "unknown shape: %s", snell_status_str(st));
    /* 4096 x 4096 goblet: refused by the vertex/triangle limit before allocating */
    d.shape = SNELL_SHAPE_GOBLET;
    d.segments = 4096;
    d.rings = 4096;
    st = snell_mesh_create_shape(NULL, &d, &m);
    CHECK(st == SNELL_E_LIMIT, "huge goblet: %s", snell_status_str(st));
    CHECK(snell_mesh_create_shape(NULL, NULL, &m) == SNELL_E_INVALID_ARG, "NULL desc");
}

/* snell_mesh_set_vertices: deformation keeps the triangles, recomputes
 * bounds and (when not given) normals; bad input leaves the mesh unchanged. */
static void test_set_vertices(void)
{
    snell_mesh *m = make(SNELL_SHAPE_CUBE, 0, 0);
    float pos[24 * 3], nrm[24 * 3], mn[3], mx[3], before[24 * 3];
    uint32_t i;
    if (!m) return;
    memcpy(before, snell_mesh_positions(m), sizeof before);
    for (i = 0; i < 24 * 3; i++) pos[i] = before[i] * (i % 3 == 1 ? 0.5f : 2.0f);
    CHECK(snell_mesh_set_vertices(m, pos, NULL) == SNELL_OK, "set_vertices: %s", snell_last_error(NULL));
    snell_mesh_bounds(m, mn, mx);
    CHECK(mn[0] == -2 && mx[0] == 2 && mn[1] == -0.5f && mx[1] == 0.5f && mx[2] == 2, "bounds after deformation");
    check_closed(m, "deformed cube");
    check_normals_outward(m, "deformed cube", 0.9999999); /* recomputed: still flat faces */
    CHECK(fabs(signed_volume(m) - 16.0) < 1e-6, "deformed volume %.9f", signed_volume(m));
    memcpy(before, snell_mesh_positions(m), sizeof before);
    memcpy(pos, before, sizeof pos);
    pos[7] = NAN;
    CHECK(snell_mesh_set_vertices(m, pos, NULL) == SNELL_E_INVALID_ARG, "NaN coordinate accepted");
    pos[7] = 3e38f;
    pos[10] = -3e38f;
    CHECK(snell_mesh_set_vertices(m, pos, NULL) == SNELL_E_LIMIT, "extent beyond the float range accepted");
    memcpy(pos, before, sizeof pos);
    memset(nrm, 0, sizeof nrm);
    CHECK(snell_mesh_set_vertices(m, pos, nrm) == SNELL_E_INVALID_ARG, "zero normals accepted");
    CHECK(memcmp(before, snell_mesh_positions(m), sizeof before) == 0, "a refused call changed the mesh");
    CHECK(snell_mesh_set_vertices(m, NULL, NULL) == SNELL_E_INVALID_ARG && snell_mesh_set_vertices(NULL, pos, NULL) ==
              SNELL_E_INVALID_ARG, "NULL arguments accepted");
    for (i = 0; i < 24; i++) {
        nrm[3 * i] = 0.0f;
        nrm[3 * i + 1] = 3.0f; /* renormalised */
        nrm[3 * i + 2] = 0.0f;
    }
    CHECK(snell_mesh_set_vertices(m, pos, nrm) == SNELL_OK && fabsf(snell_mesh_normals(m)[1] - 1.0f) < 1e-7f,
          "caller normals not renormalised");
    snell_mesh_destroy(m);
}

int main(void)
{
    test_sphere(0, 0);
    test_sphere(3, 2);
    test_sphere(7, 5);
    test_cube();
    test_prism();
    test_torus();
    test_goblet(0, 0);
    test_goblet(24, 12);
    test_limits();
    test_set_vertices();
    return test_finish();
}
