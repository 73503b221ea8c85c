/* SPDX-License-Identifier: MIT */
/* test_lm2d_trace.c — light tracer: energy bookkeeping (no energy created; a
 * closed white box with a = 0 keeps all of it until the bounce cap), refraction
 * angles through a glass slab (shared optics kernel), clipping to the view,
 * determinism across thread counts, and the skip-work logic of the lightmap. */
#include "lm2d/lm2d_trace.h"
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static snell_scene2d *box_scene(float a, float d, float t, float ior, int light_inside_square)
{
    snell_scene2d *s;
    snell_object2d_desc o;
    snell_light2d_desc L;
    float sq[8] = {0, 0, 100, 0, 100, 100, 0, 100};
    CHECK_OK(snell_scene2d_create(NULL, &s));
    memset(&o, 0, sizeof o);
    o.points = sq;
    o.point_count = 4;
    o.material.absorption = a;
    o.material.diffuse = d;
    o.material.transmission = t;
    o.material.ior = ior;
    if (light_inside_square) CHECK_OK(snell_scene2d_add_object(s, &o, NULL));
    memset(&L, 0, sizeof L);
    L.type = SNELL_LIGHT2D_POINT;
    L.position[0] = 37;
    L.position[1] = 61;
    L.power = 3;
    L.rays = 5000;
    CHECK_OK(snell_scene2d_add_light(s, &L, NULL));
    CHECK_OK(lm2d_scene_prepare(s));
    return s;
}

static lm2d_path *trace_all(const snell_scene2d *s, int light, int bounces, size_t *n, lm2d_energy *e)
{
    lm2d_trace_params p;
    int N = s->lights[light].d.rays;
    size_t cap = (size_t)N * (size_t)(bounces + 1);
    lm2d_path *paths = (lm2d_path *)malloc(cap * sizeof *paths);
    memset(&p, 0, sizeof p);
    p.scene = s;
    p.view_lo[0] = -50;
    p.view_lo[1] = -50;
    p.view_hi[0] = 250;
    p.view_hi[1] = 250;
    p.max_bounces = bounces;
    p.seed = 7;
    memset(e, 0, sizeof *e);
    *n = lm2d_trace_rays(&p, light, 0, N, paths, cap, e);
    return paths;
}

static void test_closed_box(void)
{
    snell_scene2d *s = box_scene(0.0f, 1.0f, 0.0f, 0.0f, 1);
    lm2d_energy e;
    size_t n, i;
    int outside = 0;
    lm2d_path *p = trace_all(s, 0, 20, &n, &e);
    CHECK(fabs(e.emitted - 9.0) < 1e-3, "emitted %g, want 3 W x 3 channels", e.emitted);
    CHECK(e.absorbed == 0.0 && e.escaped == 0.0 && e.rr_killed == 0.0, "a=0 box lost energy: absorbed %g escaped %g rr %g",
          e.absorbed, e.escaped, e.rr_killed);
    CHECK(fabs(e.capped - e.emitted) < 1e-6 * e.emitted, "capped %g != emitted %g", e.capped, e.emitted);
    CHECK(n == 5000u * 21u, "every ray should bounce to the cap: %zu segments", n);
    for (i = 0; i < n; i++)
        if (p[i].x0 < -1e-3f || p[i].x0 > 100.001f || p[i].y1 < -1e-3f || p[i].y1 > 100.001f) outside++;
    CHECK(outside == 0, "%d segments leave the closed box", outside);
    free(p);
    snell_scene2d_destroy(s);
}

/* Mixed scene: absorption, colour, glass, escaping rays; bookkeeping balances
 * and no segment ever carries more flux than its ray was emitted with. */
static void test_balance(void)
{
    snell_scene2d *s;
    snell_object2d_desc o;
    snell_light2d_desc L;
    float wall[8] = {0, 0, 200, 0, 200, 10, 0, 10}, glass[6] = {60, 60, 120, 60, 90, 120};
    lm2d_energy e;
    size_t n, i;
    int grew = 0;
    lm2d_path *p;
    double sum;
    float per_ray;
    CHECK_OK(snell_scene2d_create(NULL, &s));
    memset(&o, 0, sizeof o);
    o.points = wall;
    o.point_count = 4;
    o.material.absorption = 0.3f;
    o.material.diffuse = 0.6f;
    o.material.color[0] = 1.0f;
    o.material.color[1] = 0.5f;
    o.material.color[2] = 0.2f;
    CHECK_OK(snell_scene2d_add_object(s, &o, NULL));
    memset(&o, 0, sizeof o);
    o.points = glass;
    o.point_count = 3;
    o.material.transmission = 0.8f;
    o.material.opaqueness = 0.01f;
    o.material.ior = 1.6f;
    o.material.diffuse = 0.2f;
    CHECK_OK(snell_scene2d_add_object(s, &o, NULL));
    memset(&L, 0, sizeof L);
    L.type = SNELL_LIGHT2D_BAR;
    L.position[0] = 40;
    L.position[1] = 180;
    L.end[0] = 160;
    L.end[1] = 180;
    L.two_sided = 1;
    L.power = 5;
    L.rays = 20000;
    CHECK_OK(snell_scene2d_add_light(s, &L, NULL));
    CHECK_OK(lm2d_scene_prepare(s));
    p = trace_all(s, 0, 12, &n, &e);
    sum = e.absorbed + e.escaped + e.capped + e.rr_killed - e.rr_gained;
    CHECK(fabs(sum - e.emitted) < 1e-5 * e.emitted, "emitted %.9g != absorbed+escaped+capped+rr %.9g", e.emitted, sum);
    CHECK(e.absorbed > 0.05 * e.emitted && e.escaped > 0.05 * e.emitted, "scene not exercising absorption/escape");
    per_ray = 5.0f / 20000.0f * 1.00001f;
    for (i = 0; i < n; i++) {
        int k;
        for (k = 0; k < 3; k++)
            if (p[i].c0[k] > per_ray || p[i].c1[k] > per_ray || p[i].c1[k] < 0.0f) grew++;
    }
    CHECK(grew == 0, "%d segment ends carry more flux than emitted per ray", grew);
    free(p);
    snell_scene2d_destroy(s);
}

/* A beam entering a glass slab at 40 degrees travels inside at asin(sin 40 / 1.5). */
static void test_refraction(void)
{
    snell_scene2d *s;
    snell_object2d_desc o;
    snell_light2d_desc L;
    float slab[8] = {0, 100, 300, 100, 300, 140, 0, 140};
    lm2d_energy e;
    size_t n, i;
    int inside = 0, wrong = 0, below = 0;
    float th = 40.0f * 3.14159265f / 180.0f, want = asinf(sinf(th) / 1.5f);
    lm2d_path *p;
    CHECK_OK(snell_scene2d_create(NULL, &s));
    memset(&o, 0, sizeof o);
    o.points = slab;
    o.point_count = 4;
    o.material.transmission = 1.0f;
    o.material.ior = 1.5f;
    CHECK_OK(snell_scene2d_add_object(s, &o, NULL));
    memset(&L, 0, sizeof L);
    L.type = SNELL_LIGHT2D_BEAM;
    L.position[0] = 20;
    L.position[1] = 0;
    L.end[0] = 40;
    L.end[1] = 0;
    L.direction = 3.14159265f / 2.0f - th; /* 40 degrees from the slab normal (+y) */
    L.power = 1;
    L.rays = 2000;
    CHECK_OK(snell_scene2d_add_light(s, &L, NULL));
    CHECK_OK(lm2d_scene_prepare(s));
    p = trace_all(s, 0, 8, &n, &e);
    for (i = 0; i < n; i++) {
        float my = 0.5f * (p[i].y0 + p[i].y1);
        float dx = p[i].x1 - p[i].x0, dy = p[i].y1 - p[i].y0, ang = atanf(fabsf(dx) / fabsf(dy));
        if (my > 100.5f && my < 139.5f) {
            inside++;
            if (fabsf(ang - want) > 1e-3f) wrong++;
        }
        if (my > 141.0f && p[i].y1 > p[i].y0) { /* transmitted out of the bottom: parallel to the input */
            below++;
            if (fabsf(ang - th) > 1e-3f) wrong++;
        }
    }
    CHECK(inside > 1500 && below > 1500, "beam did not go through the slab (%d inside, %d below)", inside, below);
    CHECK(wrong == 0, "%d segments at the wrong angle (want %.4f rad inside)", wrong, (double)want);
    free(p);
    snell_scene2d_destroy(s);
}

static snell_lightmap2d *cpu_lm(int threads, uint64_t seed, int progressive)
{
    snell_lightmap2d_desc d;
    snell_lightmap2d *lm = NULL;
    memset(&d, 0, sizeof d);
    d.width = 64;
    d.height = 64;
    d.view_min[0] = -10;
    d.view_min[1] = -10;
    d.view_max[0] = 310;
    d.view_max[1] = 150;
    d.threads = threads;
    d.seed = seed;
    d.progressive = progressive;
    d.max_bounces = 6;
    d.cpu_only = 1;
    CHECK_OK(snell_lightmap2d_create(NULL, &d, &lm));
    return lm;
}

/* Two lights, each in its own closed diffuse box (rays stay bounded). */
static snell_scene2d *two_rooms(void)
{
    snell_scene2d *s;
    snell_object2d_desc o;
    snell_light2d_desc L;
    float room[8] = {0, 0, 100, 0, 100, 100, 0, 100}, blk[8] = {40, 40, 60, 40, 60, 60, 40, 60};
    CHECK_OK(snell_scene2d_create(NULL, &s));
    memset(&o, 0, sizeof o);
    o.points = room;
    o.point_count = 4;
    o.material.diffuse = 1.0f;
    o.material.absorption = 0.5f;
    CHECK_OK(snell_scene2d_add_object(s, &o, NULL));
    o.offset[0] = 200;
    CHECK_OK(snell_scene2d_add_object(s, &o, NULL));
    o.points = blk;
    o.offset[0] = 0;
    o.material.color[0] = 1.0f;
    o.material.color[1] = 0.2f;
    o.material.color[2] = 0.2f;
    CHECK_OK(snell_scene2d_add_object(s, &o, NULL)); /* object 2, in room 0 */
    memset(&L, 0, sizeof L);
    L.position[0] = 20;
    L.position[1] = 20;
    L.power = 1;
    L.rays = 3000;
    CHECK_OK(snell_scene2d_add_light(s, &L, NULL));
    L.position[0] = 220;
    CHECK_OK(snell_scene2d_add_light(s, &L, NULL));
    return s;
}

static void test_determinism_and_skip(void)
{
    snell_scene2d *s = two_rooms();
    snell_lightmap2d *a = cpu_lm(1, 42, 0), *b = cpu_lm(3, 42, 0), *c = cpu_lm(2, 43, 0);
    snell_lightmap2d_stats st;
    float *ia = (float *)malloc(64 * 64 * 3 * sizeof(float)), *ib = (float *)malloc(64 * 64 * 3 * sizeof(float));
    float *ic = (float *)malloc(64 * 64 * 3 * sizeof(float));
    snell_light2d_desc L;
    float off[2] = {5, 0};
    CHECK_OK(snell_lightmap2d_frame(a, s, &st));
    CHECK(st.traced && st.lights_traced == 2 && st.rays == 6000, "first frame: traced %d lights %d rays %llu", st.traced,
          st.lights_traced, (unsigned long long)st.rays);
    CHECK_OK(snell_lightmap2d_frame(b, s, NULL));
    CHECK_OK(snell_lightmap2d_frame(c, s, NULL));
    CHECK_OK(snell_lightmap2d_read_rgb(a, ia));
    CHECK_OK(snell_lightmap2d_read_rgb(b, ib));
    CHECK_OK(snell_lightmap2d_read_rgb(c, ic));
    CHECK(memcmp(ia, ib, 64 * 64 * 3 * sizeof(float)) == 0, "1 thread and 3 threads give different images");
    CHECK(memcmp(ia, ic, 64 * 64 * 3 * sizeof(float)) != 0, "seed does not change the image");
    /* static: nothing traced */
    CHECK_OK(snell_lightmap2d_frame(a, s, &st));
    CHECK(!st.traced && st.rays == 0, "static scene re-traced");
    /* one light changed: only it is traced */
    L = s->lights[1].d;
    L.power = 2;
    CHECK_OK(snell_scene2d_set_light(s, 1, &L));
    CHECK_OK(snell_lightmap2d_frame(a, s, &st));
    CHECK(st.traced && st.lights_traced == 1 && st.rays == 3000, "light change: %d lights traced", st.lights_traced);
    /* zero power: skipped at no cost */
    L.power = 0;
    CHECK_OK(snell_scene2d_set_light(s, 1, &L));
    CHECK_OK(snell_lightmap2d_frame(a, s, &st));
    CHECK(st.lights_traced == 0 && st.lights_skipped == 2 && st.rays == 0, "zero-power light traced (%d, %d)",
          st.lights_traced, st.lights_skipped);
    L.power = 1;
    CHECK_OK(snell_scene2d_set_light(s, 1, &L));
    CHECK_OK(snell_lightmap2d_frame(a, s, &st));
    /* moving the block in room 0 re-traces light 0 only (light 1's paths stay in room 1) */
    CHECK_OK(snell_scene2d_set_object_offset(s, 2, off));
    CHECK_OK(snell_lightmap2d_frame(a, s, &st));
    CHECK(st.lights_traced == 1, "object move re-traced %d lights, want 1", st.lights_traced);
    /* after all that, the image equals a fresh trace of the same scene state */
    CHECK_OK(snell_lightmap2d_read_rgb(a, ia));
    snell_lightmap2d_destroy(b);
    b = cpu_lm(2, 42, 0);
    CHECK_OK(snell_lightmap2d_frame(b, s, NULL));
    CHECK_OK(snell_lightmap2d_read_rgb(b, ib));
    CHECK(memcmp(ia, ib, 64 * 64 * 3 * sizeof(float)) == 0, "incremental image differs from a fresh trace");
    snell_lightmap2d_destroy(a);
    snell_lightmap2d_destroy(b);
    snell_lightmap2d_destroy(c);
    /* progressive: passes accumulate and the mean converges (noise drops) */
    {
        snell_lightmap2d *p = cpu_lm(2, 1, 1);
        int f;
        for (f = 0; f < 4; f++) CHECK_OK(snell_lightmap2d_frame(p, s, &st));
        CHECK(st.passes == 4 && st.traced, "progressive: %d passes", st.passes);
        snell_lightmap2d_destroy(p);
    }
    free(ia);
    free(ib);
    free(ic);
    snell_scene2d_destroy(s);
}

int main(void)
{
    test_closed_box();
    test_balance();
    test_refraction();
    test_determinism_and_skip();
    return test_finish();
}
