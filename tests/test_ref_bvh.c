/* SPDX-License-Identifier: MIT */
/* test_ref_bvh — the reference BVH (src/mesh/bvh.c):
 *  - closest hit equals brute force (the same watertight predicate over every
 *    triangle, world vertices computed independently here) for random rays on
 *    a torus and on the glmark2 bunny, with a model matrix; skip_tri and any-hit
 *    agree with brute force too;
 *  - the watertight predicate agrees with Moller-Trumbore away from edges;
 *  - watertightness: rays from inside a closed mesh aimed exactly at vertices
 *    and edge midpoints always hit;
 *  - several parts (a torus, a cube and a sphere, each with its own model
 *    matrix) in one BVH: ids run over the parts in order (part_first), each
 *    hit reports its part, and the closest hit, with and without a per-part
 *    filter, equals brute force over the parts' world triangles;
 *  - bad input is rejected with a status and a message (naming the part). */
#include "test_util.h"
#include "mesh/mesh.h"
#include "mesh/bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double rnd(void) /* xorshift64*, uniform in [0, 1) */
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (double)((rng_state * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct world {
    double *v; /* 9 per triangle */
    uint32_t nt;
} world;

static world make_world(const snell_mesh *m, const float *model)
{
    world w;
    uint32_t t;
    int j, k;
    double M[16];
    for (k = 0; k < 16; k++) M[k] = model ? model[k] : (k % 5 == 0);
    w.nt = m->triangle_count;
    w.v = (double *)malloc(sizeof(double) * 9 * w.nt);
    for (t = 0; t < w.nt; t++)
        for (j = 0; j < 3; j++) {
            const float *p = m->positions + 3 * m->indices[3 * t + j];
            for (k = 0; k < 3; k++)
                w.v[9 * t + 3 * j + k] = M[k] * p[0] + M[4 + k] * p[1] + M[8 + k] * p[2] + M[12 + k];
        }
    return w;
}

static int brute(const world *w, const double o[3], const double d[3], uint32_t skip, double *t_out, uint32_t *tri)
{
    uint32_t t;
    int hit = 0;
    double best = HUGE_VAL;
    for (t = 0; t < w->nt; t++) {
        double tt, b[3];
        if (t == skip) continue;
        if (snell__bvh_triangle_hit(o, d, w->v + 9 * t, w->v + 9 * t + 3, w->v + 9 * t + 6, 1e-12, best, &tt, b)) {
            best = tt;
            *tri = t;
            hit = 1;
        }
    }
    *t_out = best;
    return hit;
}

/* Moller-Trumbore (1997) in double; u, v the weights of v1, v2. */
static int mt(const double o[3], const double d[3], const double *a, double *t_out, double *u_out, double *v_out)
{
    double e1[3], e2[3], pv[3], tv[3], qv[3], det, u, v;
    int c;
    for (c = 0; c < 3; c++) {
        e1[c] = a[3 + c] - a[c];
        e2[c] = a[6 + c] - a[c];
        tv[c] = o[c] - a[c];
    }
    pv[0] = d[1] * e2[2] - d[2] * e2[1];
    pv[1] = d[2] * e2[0] - d[0] * e2[2];
    pv[2] = d[0] * e2[1] - d[1] * e2[0];
    det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (fabs(det) < 1e-300) return 0;
    u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
    qv[0] = tv[1] * e1[2] - tv[2] * e1[1];
    qv[1] = tv[2] * e1[0] - tv[0] * e1[2];
    qv[2] = tv[0] * e1[1] - tv[1] * e1[0];
    v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
    *t_out = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
    *u_out = u;
    *v_out = v;
    return u >= 0 && v >= 0 && u + v <= 1;
}

static void random_rays(const char *name, const snell_mesh *m, const float *model, int nrays)
{
    snell__bvh *bvh = NULL;
    world w = make_world(m, model);
    int i, mism_t = 0, mism_any = 0, mism_skip = 0, hits = 0, mt_checked = 0, mt_bad = 0, bad_bary = 0;
    double lo[3], hi[3], c[3], ext = 0.0;
    clock_t t0 = clock();
    int k;
    CHECK_OK(snell__bvh_build_mesh(NULL, m, model, &bvh));
    if (!bvh) {
        free(w.v);
        return;
    }
    printf("%s: %u triangles, %u nodes, depth %d, build %.1f ms\n", name, bvh->triangle_count, bvh->node_count,
           bvh->depth, 1000.0 * (double)(clock() - t0) / CLOCKS_PER_SEC);
    CHECK(bvh->node_count <= 2 * bvh->triangle_count - 1, "node count %u", bvh->node_count);
    for (k = 0; k < 3; k++) {
        lo[k] = bvh->bmin[k];
        hi[k] = bvh->bmax[k];
        c[k] = 0.5 * (lo[k] + hi[k]);
        if (hi[k] - lo[k] > ext) ext = hi[k] - lo[k];
    }
    for (i = 0; i < nrays; i++) {
        double o[3], d[3], tb = 0, tf = 0;
        uint32_t trib = 0, trif = 0;
        snell__bvh_hit h;
        int hb, hf;
        /* Half the rays start outside and aim at a random point on a random
         * triangle (many hits); the others start anywhere in the bounds with a
         * random direction (inside and outside, many misses). */
        if (i & 1) {
            uint32_t t = (uint32_t)(rnd() * w.nt);
            double a = rnd(), b = rnd();
            if (a + b > 1) {
                a = 1 - a;
                b = 1 - b;
            }
            for (k = 0; k < 3; k++) {
                double p = w.v[9 * t + k] + a * (w.v[9 * t + 3 + k] - w.v[9 * t + k]) +
                           b * (w.v[9 * t + 6 + k] - w.v[9 * t + k]);
                o[k] = c[k] + (rnd() - 0.5) * 3.0 * ext;
                d[k] = p - o[k];
            }
        } else {
            for (k = 0; k < 3; k++) {
                o[k] = lo[k] + rnd() * (hi[k] - lo[k]);
                d[k] = rnd() - 0.5;
            }
        }
        hb = brute(&w, o, d, SNELL__BVH_NONE, &tb, &trib);
        hf = snell__bvh_closest(bvh, o, d, 1e-12, HUGE_VAL, SNELL__BVH_NONE, &h);
        hits += hb;
        if (hb != hf || (hb && h.t != tb)) {
            if (mism_t < 5)
                fprintf(stderr, "%s ray %d: brute %d t=%.17g, bvh %d t=%.17g\n", name, i, hb, tb, hf, hf ? h.t : 0.0);
            mism_t++;
        }
        if (hf) {
            double sum = h.b[0] + h.b[1] + h.b[2], q[3];
            /* The reported point is on the ray at t (to rounding). */
            for (k = 0; k < 3; k++) q[k] = o[k] + h.t * d[k] - h.p[k];
            if (fabs(sum - 1.0) > 1e-12 || h.b[0] < -1e-15 || h.b[1] < -1e-15 || h.b[2] < -1e-15 ||
                sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) > 1e-9 * ext)
                bad_bary++;
            /* Cross-check the predicate with Moller-Trumbore away from edges. */
            {
                double tm, u, v;
                const double *a = w.v + 9 * h.tri;
                if (h.b[0] > 1e-6 && h.b[1] > 1e-6 && h.b[2] > 1e-6) {
                    mt_checked++;
                    if (!mt(o, d, a, &tm, &u, &v) || fabs(tm - h.t) > 1e-9 * (1 + fabs(tm)) ||
                        fabs(u - h.b[1]) > 1e-8 || fabs(v - h.b[2]) > 1e-8)
                        mt_bad++;
                }
            }
        }
        if ((snell__bvh_any(bvh, o, d, 1e-12, HUGE_VAL, SNELL__BVH_NONE) != 0) != (hb != 0)) mism_any++;
        if (hb) {
            /* Skipping the hit triangle gives the next surface, as brute force. */
            double ts = 0;
            uint32_t tris = 0;
            int hs = brute(&w, o, d, trib, &ts, &tris);
            int hs2 = snell__bvh_closest(bvh, o, d, 1e-12, HUGE_VAL, trib, &h);
            if (hs != hs2 || (hs && h.t != ts)) mism_skip++;
            /* Any-hit with tmax just below the closest t finds nothing. */
            if (snell__bvh_any(bvh, o, d, 1e-12, tb * (1 - 1e-9), SNELL__BVH_NONE)) mism_any++;
        }
        (void)trif;
        (void)tf;
    }
    printf("%s: %d rays, %d hits, %d Moller-Trumbore cross-checks\n", name, nrays, hits, mt_checked);
    CHECK(hits > nrays / 4, "%s: too few hits (%d) for a meaningful test", name, hits);
    CHECK(mism_t == 0, "%s: %d closest-hit mismatches against brute force", name, mism_t);
    CHECK(mism_any == 0, "%s: %d any-hit mismatches", name, mism_any);
    CHECK(mism_skip == 0, "%s: %d skip_tri mismatches", name, mism_skip);
    CHECK(bad_bary == 0, "%s: %d hits with bad barycentrics/point", name, bad_bary);
    CHECK(mt_checked > 100 && mt_bad == 0, "%s: %d of %d disagree with Moller-Trumbore", name, mt_bad, mt_checked);
    snell__bvh_destroy(bvh);
    free(w.v);
}

/* From a point inside the tube of the torus, rays aimed exactly at vertices
 * and edge midpoints of the (closed) mesh must hit: a crack would let them out. */
static void watertight(const snell_mesh *m)
{
    snell__bvh *bvh = NULL;
    uint32_t t, tested = 0, leaks = 0;
    CHECK_OK(snell__bvh_build_mesh(NULL, m, NULL, &bvh));
    if (!bvh) return;
    for (t = 0; t < m->triangle_count; t++) {
        int j, k;
        for (j = 0; j < 3; j++) {
            const float *a = m->positions + 3 * m->indices[3 * t + j];
            const float *b = m->positions + 3 * m->indices[3 * t + (j + 1) % 3];
            double target[2][3], o[3], rr, phi;
            snell__bvh_hit h;
            int q;
            for (k = 0; k < 3; k++) {
                target[0][k] = a[k];
                target[1][k] = 0.5 * ((double)a[k] + (double)b[k]);
            }
            /* Origin on the core circle (radius 1 around +Y) nearest to the vertex. */
            phi = atan2(a[2], a[0]);
            rr = 1.0;
            o[0] = rr * cos(phi);
            o[1] = 0.0;
            o[2] = rr * sin(phi);
            for (q = 0; q < 2; q++) {
                double d[3] = {target[q][0] - o[0], target[q][1] - o[1], target[q][2] - o[2]};
                tested++;
                if (!snell__bvh_closest(bvh, o, d, 0.0, HUGE_VAL, SNELL__BVH_NONE, &h) || h.t > 1.0 + 1e-12) leaks++;
            }
        }
    }
    printf("watertight: %u rays at vertices/edge midpoints, %u leaks\n", tested, leaks);
    CHECK(tested > 1000 && leaks == 0, "%u of %u rays leaked through a vertex or edge", leaks, tested);
    snell__bvh_destroy(bvh);
}

/* Parts: world triangles of every part concatenated in part order, with the
 * part of each, built here independently of the BVH. */
typedef struct parts_world {
    world w;
    uint32_t *part;
} parts_world;

static int accept_mask(uint32_t part, const void *user) { return (*(const unsigned *)user >> part) & 1u; }

static int brute_mask(const parts_world *pw, unsigned mask, const double o[3], const double d[3], double *t_out,
                      uint32_t *tri)
{
    uint32_t t;
    int hit = 0;
    double best = HUGE_VAL;
    for (t = 0; t < pw->w.nt; t++) {
        double tt, b[3];
        const double *v = pw->w.v + 9 * t;
        if (!((mask >> pw->part[t]) & 1u)) continue;
        if (snell__bvh_triangle_hit(o, d, v, v + 3, v + 6, 1e-12, best, &tt, b)) {
            best = tt;
            *tri = t;
            hit = 1;
        }
    }
    *t_out = best;
    return hit;
}

static void multi_part(const snell_mesh *torus)
{
    snell_mesh *cube = NULL, *sphere = NULL;
    snell_shape_desc sd;
    snell__bvh_part parts[3];
    snell__bvh *bvh = NULL;
    parts_world pw;
    /* The cube squashed and moved beside the torus; the sphere inside the torus hole. */
    static const float cube_model[16] = {0.5f, 0, 0, 0, 0, 2.0f, 0, 0, 0, 0, 0.3f, 0, 2.5f, 0.1f, -0.2f, 1};
    static const float sph_model[16] = {0.4f, 0, 0, 0, 0, 0.4f, 0, 0, 0, 0, 0.4f, 0, 0.05f, 0, 0, 1};
    const snell_mesh *meshes[3];
    const float *models[3];
    uint32_t p, t, nt = 0;
    int i, k, mism = 0, mism_f = 0, bad_part = 0, hits = 0, parts_hit[3] = {0, 0, 0};
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &cube));
    sd.shape = SNELL_SHAPE_SPHERE;
    sd.segments = 24;
    sd.rings = 12;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &sphere));
    if (!cube || !sphere) {
        snell_mesh_destroy(cube);
        snell_mesh_destroy(sphere);
        return;
    }
    meshes[0] = torus;
    meshes[1] = cube;
    meshes[2] = sphere;
    models[0] = NULL;
    models[1] = cube_model;
    models[2] = sph_model;
    pw.w.nt = 0;
    for (p = 0; p < 3; p++) pw.w.nt += meshes[p]->triangle_count;
    pw.w.v = (double *)malloc(sizeof(double) * 9 * pw.w.nt);
    pw.part = (uint32_t *)malloc(sizeof(uint32_t) * pw.w.nt);
    for (p = 0; p < 3; p++) {
        world w = make_world(meshes[p], models[p]);
        memcpy(pw.w.v + 9 * (size_t)nt, w.v, sizeof(double) * 9 * w.nt);
        for (t = 0; t < w.nt; t++) pw.part[nt + t] = p;
        nt += w.nt;
        free(w.v);
        parts[p].positions = meshes[p]->positions;
        parts[p].vertex_count = meshes[p]->vertex_count;
        parts[p].indices = meshes[p]->indices;
        parts[p].triangle_count = meshes[p]->triangle_count;
        parts[p].model = models[p];
    }
    CHECK_OK(snell__bvh_build_parts(NULL, parts, 3, &bvh));
    if (bvh) {
        CHECK(bvh->part_count == 3 && bvh->triangle_count == nt && bvh->part_first[0] == 0 &&
                  bvh->part_first[1] == torus->triangle_count &&
                  bvh->part_first[2] == torus->triangle_count + cube->triangle_count && bvh->part_first[3] == nt,
              "part_first %u %u %u %u", bvh->part_first[0], bvh->part_first[1], bvh->part_first[2], bvh->part_first[3]);
        for (i = 0; i < 6000; i++) {
            double o[3], d[3], tb;
            uint32_t trib = 0; /* ties on shared edges may pick either triangle: compare t */
            unsigned mask = i < 2000 ? 7u : (unsigned)(1 + i % 7); /* every non-empty subset */
            snell__bvh_hit h;
            int hb, hf;
            for (k = 0; k < 3; k++) {
                o[k] = (rnd() - 0.5) * 8.0;
                d[k] = (k == 0 ? 0.3 : 0.0) - o[k] + (rnd() - 0.5) * 3.0; /* towards the objects */
            }
            hb = brute_mask(&pw, mask, o, d, &tb, &trib);
            hf = mask == 7u
                     ? snell__bvh_closest(bvh, o, d, 1e-12, HUGE_VAL, SNELL__BVH_NONE, &h)
                     : snell__bvh_closest_filtered(bvh, o, d, 1e-12, HUGE_VAL, SNELL__BVH_NONE, accept_mask, &mask, &h);
            if (hb != hf || (hb && (h.t != tb || !((mask >> h.part) & 1u)))) {
                if (mask == 7u)
                    mism++;
                else
                    mism_f++;
                continue;
            }
            if (!hf) continue;
            hits++;
            parts_hit[h.part < 3 ? h.part : 0]++;
            /* The part, the id range and the leaf entry agree. */
            if (h.part != pw.part[h.tri] || h.tri < bvh->part_first[h.part] || h.tri >= bvh->part_first[h.part + 1] ||
                bvh->tri_ids[h.entry] != h.tri ||
                memcmp(bvh->tri_verts + 9 * (size_t)h.entry, pw.w.v + 9 * (size_t)h.tri, 9 * sizeof(double)) != 0)
                bad_part++;
        }
    }
    printf("parts: %u triangles in 3 parts, %d hits (%d / %d / %d per part)\n", nt, hits, parts_hit[0], parts_hit[1],
           parts_hit[2]);
    CHECK(hits > 1500 && parts_hit[0] > 100 && parts_hit[1] > 100 && parts_hit[2] > 50,
          "too few hits for a meaningful test (%d: %d / %d / %d)", hits, parts_hit[0], parts_hit[1], parts_hit[2]);
    CHECK(mism == 0, "%d closest hits over all parts differ from brute force", mism);
    CHECK(mism_f == 0, "%d filtered closest hits differ from brute force over the admitted parts", mism_f);
    CHECK(bad_part == 0, "%d hits with a wrong part, id or entry", bad_part);
    {
        /* A bad part is named. */
        uint32_t bad[3] = {0, 1, 99999};
        snell__bvh *b2 = (snell__bvh *)&b2;
        parts[1].indices = bad;
        parts[1].triangle_count = 1;
        CHECK(snell__bvh_build_parts(NULL, parts, 3, &b2) == SNELL_E_INVALID_ARG && !b2, "bad part");
        CHECK(strstr(snell_last_error(NULL), "part 1") != NULL, "message: %s", snell_last_error(NULL));
        CHECK(snell__bvh_build_parts(NULL, parts, 0, &b2) == SNELL_E_INVALID_ARG, "no parts");
        CHECK(snell__bvh_build_parts(NULL, NULL, 2, &b2) == SNELL_E_INVALID_ARG, "NULL parts");
    }
    snell__bvh_destroy(bvh);
    free(pw.w.v);
    free(pw.part);
    snell_mesh_destroy(cube);
    snell_mesh_destroy(sphere);
}

static void bad_input(void)
{
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t idx[3] = {0, 1, 2}, bad[3] = {0, 1, 7};
    float singular[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
    float nan_model[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    snell__bvh *bvh = (snell__bvh *)&bvh;
    nan_model[13] = NAN;
    CHECK(snell__bvh_build(NULL, pos, 3, idx, 0, NULL, &bvh) == SNELL_E_INVALID_ARG && !bvh, "no triangles");
    CHECK(strstr(snell_last_error(NULL), "no triangles") != NULL, "message: %s", snell_last_error(NULL));
    CHECK(snell__bvh_build(NULL, pos, 3, bad, 1, NULL, &bvh) == SNELL_E_INVALID_ARG, "bad index");
    CHECK(strstr(snell_last_error(NULL), "vertex 7") != NULL, "message: %s", snell_last_error(NULL));
    CHECK(snell__bvh_build(NULL, pos, 3, idx, 1, singular, &bvh) == SNELL_E_INVALID_ARG, "singular model");
    CHECK(snell__bvh_build(NULL, pos, 3, idx, 1, nan_model, &bvh) == SNELL_E_INVALID_ARG, "NaN model");
    CHECK(snell__bvh_build(NULL, NULL, 3, idx, 1, NULL, &bvh) == SNELL_E_INVALID_ARG, "NULL positions");
    CHECK(snell__bvh_build(NULL, pos, 3, idx, 0x7fffffffu, NULL, &bvh) == SNELL_E_LIMIT, "absurd count");
    CHECK(snell__bvh_build_mesh(NULL, NULL, NULL, &bvh) == SNELL_E_INVALID_ARG, "NULL mesh");
    CHECK(snell__bvh_build(NULL, pos, 3, idx, 1, NULL, NULL) == SNELL_E_INVALID_ARG, "NULL out");
    /* A single triangle: hit in its interior, miss outside, tmax respected. */
    CHECK_OK(snell__bvh_build(NULL, pos, 3, idx, 1, NULL, &bvh));
    if (bvh) {
        double o[3] = {0.25, 0.25, 1}, d[3] = {0, 0, -1}, o2[3] = {0.75, 0.75, 1};
        snell__bvh_hit h;
        CHECK(snell__bvh_closest(bvh, o, d, 0, HUGE_VAL, SNELL__BVH_NONE, &h) && h.t == 1.0 && h.tri == 0,
              "single triangle hit");
        CHECK(!snell__bvh_closest(bvh, o2, d, 0, HUGE_VAL, SNELL__BVH_NONE, &h), "outside the triangle");
        CHECK(!snell__bvh_any(bvh, o, d, 0, 0.5, SNELL__BVH_NONE), "tmax respected");
        CHECK(!snell__bvh_any(bvh, o, d, 0, HUGE_VAL, 0), "skip_tri respected");
        snell__bvh_destroy(bvh);
    }
}

int main(void)
{
    snell_mesh *torus = NULL, *bunny = NULL;
    snell_shape_desc sd;
    /* Rotation about (1,2,3)/|..| by 0.7 rad, scale 1.7, translation (0.3,-2,5). */
    float model[16];
    {
        double ax[3] = {1, 2, 3}, l = sqrt(14.0), th = 0.7, c = cos(th), s = sin(th), x, y, z, R[9];
        int i, j;
        x = ax[0] / l;
        y = ax[1] / l;
        z = ax[2] / l;
        R[0] = c + x * x * (1 - c); R[3] = x * y * (1 - c) - z * s; R[6] = x * z * (1 - c) + y * s;
        R[1] = y * x * (1 - c) + z * s; R[4] = c + y * y * (1 - c); R[7] = y * z * (1 - c) - x * s;
        R[2] = z * x * (1 - c) - y * s; R[5] = z * y * (1 - c) + x * s; R[8] = c + z * z * (1 - c);
        memset(model, 0, sizeof model);
        for (j = 0; j < 3; j++)
            for (i = 0; i < 3; i++) model[4 * j + i] = (float)(1.7 * R[3 * j + i]);
        model[12] = 0.3f;
        model[13] = -2.0f;
        model[14] = 5.0f;
        model[15] = 1.0f;
    }
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_TORUS;
    sd.segments = 48;
    sd.rings = 24;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &torus));
    if (torus) {
        random_rays("torus", torus, NULL, 4000);
        random_rays("torus (model)", torus, model, 4000);
        watertight(torus);
        multi_part(torus);
        snell_mesh_destroy(torus);
    }
    if (snell_mesh_load_obj(NULL, "/usr/share/glmark2/models/bunny.obj", &bunny) == SNELL_OK) {
        snell_mesh_normalize(bunny, 1.0f);
        random_rays("bunny (model)", bunny, model, 400);
        snell_mesh_destroy(bunny);
    } else {
        printf("bunny not available (%s): torus only\n", snell_last_error(NULL));
    }
    bad_input();
    return test_finish();
}
