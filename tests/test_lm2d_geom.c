/* SPDX-License-Identifier: MIT */
/* test_lm2d_geom.c — ray/segment intersection (parallel, endpoint, vertex hits)
 * and BVH traversal against brute force on random scenes, for several leaf sizes. */
#include "lm2d/lm2d_bvh.h"
#include "core/core.h"
#include "test_util.h"

#include <math.h>
#include <stdlib.h>

static uint32_t rs = 12345u;
static float frand(void)
{
    rs = rs * 1664525u + 1013904223u;
    return (float)(rs >> 8) / 16777216.0f;
}

static void test_segment(void)
{
    float o[2] = {0, 0}, d[2] = {1, 0}, t;
    float p[2] = {5, -1}, e[2] = {0, 2};
    CHECK(lm2d_ray_segment(o, d, p, e, 0.0f, &t) && fabsf(t - 5.0f) < 1e-6f, "plain hit t=%g", (double)t);
    /* behind the origin */
    p[0] = -5;
    CHECK(!lm2d_ray_segment(o, d, p, e, 0.0f, &t), "hit behind the origin");
    /* parallel (and collinear) segments never hit */
    {
        float pp[2] = {2, 0}, ee[2] = {3, 0}, pq[2] = {2, 1};
        CHECK(!lm2d_ray_segment(o, d, pp, ee, 0.0f, &t), "collinear segment reported as hit");
        CHECK(!lm2d_ray_segment(o, d, pq, ee, 0.0f, &t), "parallel segment reported as hit");
    }
    /* endpoint hits count (s = 0 and s = 1) */
    {
        float p0[2] = {3, 0}, e0[2] = {0, 4}, p1[2] = {3, -4};
        CHECK(lm2d_ray_segment(o, d, p0, e0, 0.0f, &t) && fabsf(t - 3.0f) < 1e-6f, "endpoint s=0 missed");
        CHECK(lm2d_ray_segment(o, d, p1, e0, 0.0f, &t) && fabsf(t - 3.0f) < 1e-6f, "endpoint s=1 missed");
    }
    /* just outside the endpoint misses */
    {
        float p0[2] = {3, 0.001f}, e0[2] = {0, 4};
        CHECK(!lm2d_ray_segment(o, d, p0, e0, 0.0f, &t), "hit beyond the endpoint");
    }
    /* t_min excludes the start */
    {
        float p0[2] = {0, -1}, e0[2] = {0, 2};
        CHECK(!lm2d_ray_segment(o, d, p0, e0, 1e-4f, &t), "hit at t=0 passed t_min");
    }
}

/* A vertex shared by two edges is hit once at the right distance; skip works. */
static void test_vertex(void)
{
    /* wedge with its tip at (4,0) pointing at the ray origin */
    float segs[8] = {6, -2, 4, 0, 4, 0, 6, 2};
    lm2d_bvh bvh;
    const snell_alloc *al = snell__ctx_alloc(NULL);
    float o[2] = {0, 0}, d[2] = {1, 0}, t = INFINITY;
    int hit;
    CHECK_OK(lm2d_bvh_build(NULL, al, segs, 2, 1, &bvh));
    hit = lm2d_bvh_intersect(&bvh, o, d, 0.0f, &t, -1);
    CHECK(hit >= 0 && fabsf(t - 4.0f) < 1e-5f, "vertex hit: edge %d t=%g", hit, (double)t);
    t = INFINITY;
    hit = lm2d_bvh_intersect(&bvh, o, d, 0.0f, &t, 0);
    CHECK(hit == 1 && fabsf(t - 4.0f) < 1e-5f, "skip edge 0: edge %d t=%g", hit, (double)t);
    /* a ray grazing exactly along a box side between two boxes' shared corner */
    lm2d_bvh_free(al, &bvh);
}

/* Random segment soups; every ray must find the same nearest distance. */
static void test_bvh_random(int leaf, int n, int rays, float maxlen)
{
    const snell_alloc *al = snell__ctx_alloc(NULL);
    float *segs = (float *)malloc(sizeof(float) * 4 * (size_t)n);
    lm2d_bvh bvh;
    int i, mism = 0, hits = 0;
    for (i = 0; i < n; i++) {
        float x = frand() * 1000, y = frand() * 1000, a = frand() * 6.2831853f, l = 1 + frand() * maxlen;
        segs[4 * i] = x;
        segs[4 * i + 1] = y;
        segs[4 * i + 2] = x + l * cosf(a);
        segs[4 * i + 3] = y + l * sinf(a);
    }
    /* some axis-aligned edges sharing box sides exactly (6.4.1.4.1's failure case) */
    for (i = 0; i < n / 10; i++) {
        float x = (float)(i * 7 % 1000), y = 500.0f;
        segs[4 * i] = x;
        segs[4 * i + 1] = y;
        segs[4 * i + 2] = x + 7;
        segs[4 * i + 3] = y;
    }
    CHECK_OK(lm2d_bvh_build(NULL, al, segs, n, leaf, &bvh));
    for (i = 0; i < rays; i++) {
        float o[2], d[2], a = frand() * 6.2831853f, t1 = INFINITY, t2 = INFINITY;
        int h1, h2;
        o[0] = frand() * 1200 - 100;
        o[1] = frand() * 1200 - 100;
        if (i % 7 == 0) a = (float)(i % 4) * 1.5707963f; /* axis-parallel rays */
        d[0] = cosf(a);
        d[1] = sinf(a);
        if (i % 7 == 0) {
            d[0] = roundf(d[0]);
            d[1] = roundf(d[1]);
        }
        h1 = lm2d_bvh_intersect(&bvh, o, d, 1e-4f, &t1, -1);
        h2 = lm2d_brute_intersect(&bvh, o, d, 1e-4f, &t2, -1);
        hits += h2 >= 0;
        /* ties (shared endpoints) may pick either edge; the distance must agree */
        if ((h1 < 0) != (h2 < 0) || (h1 >= 0 && t1 != t2)) {
            if (mism < 5)
                fprintf(stderr, "ray %d: bvh %d t=%.9g, brute %d t=%.9g\n", i, h1, (double)t1, h2, (double)t2);
            mism++;
        }
    }
    CHECK(mism == 0, "leaf %d, %d edges: %d of %d rays differ from brute force", leaf, n, mism, rays);
    CHECK(hits > rays / 10, "too few hits (%d) for a meaningful test", hits);
    lm2d_bvh_free(al, &bvh);
    free(segs);
}

int main(void)
{
    int leaf;
    const snell_alloc *al = snell__ctx_alloc(NULL);
    lm2d_bvh bvh;
    float s[4] = {0, 0, 1, 1};
    test_segment();
    test_vertex();
    for (leaf = 1; leaf <= 16; leaf *= 2) test_bvh_random(leaf, 3000, 6000, 30.0f);
    test_bvh_random(3, 5, 2000, 500.0f);   /* root is a single leaf */
    test_bvh_random(4, 200, 5000, 900.0f); /* long overlapping edges */
    CHECK(lm2d_bvh_build(NULL, al, s, 1, 0, &bvh) == SNELL_E_INVALID_ARG, "leaf size 0 accepted");
    CHECK(lm2d_bvh_build(NULL, al, s, 1, 99, &bvh) == SNELL_E_INVALID_ARG, "leaf size 99 accepted");
    return test_finish();
}
