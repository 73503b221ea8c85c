/* SPDX-License-Identifier: MIT */
/* test_layered — the layered method (methods/layered.c, shaders_es/layered*.frag):
 * the bake (layers used and capped, its memory, once per mesh version: no
 * pass of its own in later frames, again after snell_mesh_set_vertices), exit
 * directions against the references (MATCHED on the sphere, FULL on the
 * torus, the goblet and an open mesh, each beside single's), no NaN. */
#include "test_util.h"
#include "snell/snell_metrics.h"
#include "render/gbuffer.h" /* the device class AUTO's shading rule reads */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 96
/* Bounds on the exit-direction error, degrees: what 96x96 measured
 * (2026-12-03, llvmpipe; forward and screen space alike) with a margin.
 * MATCHED sphere: median 0.003, mean 0.08 (single 18.7); FULL torus: median
 * 0.058, mean 9.0-9.1 (single 44.8; about the analysis' centre, in the
 * tube whose walls its rays graze, it was 3.1 and 32.1: choose_centre);
 * goblet: 0.024, 4.04 (single 27.9; 4 layers capped); open sphere: 0.005,
 * 2.75 (single 14.5). Before the bake closed the gaps at fold rims (pinch
 * in layered.c): torus 0.063, 11.5; goblet 0.025, 6.4. */
#define BOUND_SPHERE_MEDIAN 0.05
#define BOUND_SPHERE_MEAN 0.5
#define BOUND_TORUS_MEDIAN 0.2
#define BOUND_TORUS_MEAN 10.5
#define BOUND_GOBLET_MEDIAN 0.1
#define BOUND_GOBLET_MEAN 5.0
#define BOUND_OPEN_MEDIAN 0.1
#define BOUND_OPEN_MEAN 4.5
/* Real meshes (2026-12-03, 96x96, forward and screen space alike), the
 * bunny against MATCHED(8) at IOR 1.5: median 0.74, mean 20.0-20.1 (peel
 * 4.42, 25.9); before the rims were closed 0.93, 24.0-24.4. The horse
 * (open, non-manifold) against FULL at IOR 1.33: median 2.1-2.3, mean
 * 21.8-22.0 (cubemap 8.7, 26.3: issue 25's "half the cubemap's" is met for
 * the median, not the mean); before 12.7, 29.3. */
#define BOUND_BUNNY_MEDIAN 1.0
#define BOUND_BUNNY_MEAN 22.0
#define BOUND_HORSE_MEDIAN 3.0
#define BOUND_HORSE_MEAN 24.0
/* The convex path (test_convex) against MATCHED, iterations 6 (default) and
 * 2: cube median 0.003, mean 0.06 and 0.19 (0.00 with 2 before the first
 * step started from the sphere through the entry); the 12-segment sphere
 * median 0.003 and 0.008, mean 0.45 and 0.73 (0.97 before; the regula falsi
 * on the distance before it, bounding-sphere start, as many steps: cube 6
 * steps 0.88 mean in test_stress' grazing views, now 0.47). The sphere's
 * colour against FULL (pixel centres, a 64^2 environment): default 38.61
 * dB, iterations 2 38.57, 1 38.71 (38.88, 38.96 and 38.20 before that start
 * and the inner branch's nearest look-ups). */
#define BOUND_CUBE_MEDIAN 0.02
#define BOUND_CUBE_MEAN 0.3
#define BOUND_COARSE_MEDIAN 0.05
#define BOUND_COARSE_MEAN 1.5
#define BOUND_INNER_IT2_DB 37.5
#define BOUND_INNER_IT1_DB 37.5
/* The sphere with iterations 1 against MATCHED, its one step from the sphere
 * through the entry point (layered.frag convex_exit): median 0.013, mean
 * 0.20; from the bounding sphere's far side as before 0.044, 0.22. */
#define BOUND_SPHERE_IT1_MEDIAN 0.025
#define BOUND_SPHERE_IT1_MEAN 0.3

static snell_mesh *shape(snell_ctx *ctx, snell_shape s)
{
    snell_shape_desc sd;
    snell_mesh *mesh = NULL;
    memset(&sd, 0, sizeof sd);
    sd.shape = s;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    if (mesh && s != SNELL_SHAPE_SPHERE) CHECK_OK(snell_mesh_normalize(mesh, 1.0f));
    return mesh;
}

/* The sphere with every 7th triangle left out: open (boundary edges), so
 * rays leave through its holes. */
static snell_mesh *open_sphere(snell_ctx *ctx)
{
    snell_mesh *full = shape(ctx, SNELL_SHAPE_SPHERE), *open = NULL;
    snell_mesh_desc md;
    uint32_t *idx;
    uint32_t i, n = 0, tris;
    if (!full) return NULL;
    tris = snell_mesh_triangle_count(full);
    idx = (unsigned *)malloc(sizeof *idx * 3 * tris);
    for (i = 0; idx && i < tris; i++)
        if (i % 7 != 3) {
            memcpy(idx + 3 * n, snell_mesh_indices(full) + 3 * i, 3 * sizeof *idx);
            n++;
        }
    memset(&md, 0, sizeof md);
    md.positions = snell_mesh_positions(full);
    md.normals = snell_mesh_normals(full);
    md.vertex_count = snell_mesh_vertex_count(full);
    md.indices = idx;
    md.triangle_count = n;
    CHECK_OK(snell_mesh_create(ctx, &md, &open));
    free(idx);
    snell_mesh_destroy(full);
    return open;
}

/* layered's iterations in the frames below (0: its default) */
static int g_iterations;

static void render(snell_ctx *ctx, snell_frame_desc *fd, snell_glass *g, snell_method m, float *dirs,
                   snell_frame_stats *stats)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r) return;
    g->material.method = m;
    g->material.layered.binary_steps = g->material.layered.convex_steps = g_iterations; /* convex meshes */
    CHECK_OK_CTX(ctx, snell_render(r, fd, stats));
    CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
    snell_renderer_destroy(r);
}

static void reference(snell_ctx *ctx, const snell_frame_desc *fd, snell_ref_mode mode, int interfaces, float *dirs,
                      uint8_t *hit)
{
    test_ref_dirs(ctx, fd, W, H, mode, interfaces, dirs, hit);
}

static snell_dir_error compare(const float *test, const float *ref, const uint8_t *hit)
{
    return test_dir_error(test, ref, hit, W, H);
}

/* One mesh: layered and single against the reference of mode/interfaces;
 * bounds on layered's median and mean, and on its mean against single's. */
static void accuracy(snell_ctx *ctx, snell_env *env, const char *name, snell_mesh *mesh, snell_ref_mode mode,
                     double max_median, double max_mean, double max_mean_vs_single)
{
    static float ref[W * H * 3], lay[W * H * 3], one[W * H * 3];
    static uint8_t hit[W * H];
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    snell_dir_error el, es;
    if (!mesh) return;
    test_frame_one(&fd, &g, mesh, env);
    fd.camera.elevation = 0.35f;
    reference(ctx, &fd, mode, mode == SNELL_REF_FULL ? 10 : 8, ref, hit);
    render(ctx, &fd, &g, SNELL_METHOD_LAYERED, lay, &st);
    CHECK(st.glass[0].method_used == SNELL_METHOD_LAYERED, "%s: drawn by %s", name,
          snell_method_str(st.glass[0].method_used));
    render(ctx, &fd, &g, SNELL_METHOD_SINGLE, one, NULL);
    el = compare(lay, ref, hit);
    es = compare(one, ref, hit);
    printf("%-13s vs %s: layered median %.3f mean %.2f p99 %.1f >5deg %.1f%% (layers used %d, capped %d); "
           "single mean %.2f\n",
           name, mode == SNELL_REF_FULL ? "FULL" : "MATCHED", el.median_deg, el.mean_deg, el.p99_deg,
           100.0 * el.frac_above_5deg, snell_object_counter(&st.glass[0], "layers_used"),
           snell_object_counter(&st.glass[0], "layers_capped"), es.mean_deg);
    CHECK(el.compared > W * H / 20, "%s: %ld pixels compared", name, el.compared);
    CHECK(el.median_deg <= max_median, "%s: median %.3f > %.3f degrees", name, el.median_deg, max_median);
    CHECK(el.mean_deg <= max_mean, "%s: mean %.2f > %.2f degrees", name, el.mean_deg, max_mean);
    CHECK(el.mean_deg <= max_mean_vs_single * es.mean_deg, "%s: mean %.2f not below %.2f x single's %.2f", name,
          el.mean_deg, max_mean_vs_single, es.mean_deg);
}

/* A real mesh (glmark2's bunny, closed; its horse, non-manifold): layered
 * and `other` against the reference of mode (FULL: 10 interfaces; MATCHED:
 * 8, layered's cap) at IOR ior; bounds on layered's mean and on its mean
 * against other's. */
static void real_accuracy(snell_ctx *ctx, snell_env *env, const char *name, snell_mesh *mesh, snell_ref_mode mode,
                          float ior, snell_method other, double max_median, double max_mean, double max_mean_vs_other)
{
    static float ref[W * H * 3], lay[W * H * 3], oth[W * H * 3];
    static uint8_t hit[W * H];
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    snell_dir_error el, eo;
    if (!mesh) return;
    test_frame_one(&fd, &g, mesh, env);
    fd.camera.elevation = 0.35f;
    g.material.ior = ior;
    reference(ctx, &fd, mode, mode == SNELL_REF_FULL ? 10 : 8, ref, hit);
    render(ctx, &fd, &g, SNELL_METHOD_LAYERED, lay, &st);
    render(ctx, &fd, &g, other, oth, NULL);
    el = compare(lay, ref, hit);
    eo = compare(oth, ref, hit);
    printf("%-13s vs %s: layered median %.3f mean %.2f p99 %.1f >5deg %.1f%% (layers used %d, capped %d); "
           "%s median %.3f mean %.2f\n",
           name, mode == SNELL_REF_FULL ? "FULL" : "MATCHED", el.median_deg, el.mean_deg, el.p99_deg,
           100.0 * el.frac_above_5deg, snell_object_counter(&st.glass[0], "layers_used"),
           snell_object_counter(&st.glass[0], "layers_capped"), snell_method_str(other), eo.median_deg, eo.mean_deg);
    CHECK(el.compared > W * H / 40, "%s: %ld pixels compared", name, el.compared);
    CHECK(el.median_deg <= max_median, "%s: median %.3f > %.3f degrees", name, el.median_deg, max_median);
    CHECK(el.mean_deg <= max_mean, "%s: mean %.2f > %.2f degrees", name, el.mean_deg, max_mean);
    CHECK(el.mean_deg <= max_mean_vs_other * eo.mean_deg, "%s: mean %.2f not below %.2f x %s's %.2f", name,
          el.mean_deg, max_mean_vs_other, snell_method_str(other), eo.mean_deg);
}

/* Colour over the sphere's glass pixels against FULL: the exit's Fresnel
 * (inner, auto = on for a convex mesh) follows the internal reflection the
 * chain drops. Measured 2026-12-03 at 96x96, pixel centres: see the bounds. */
static void test_inner_fresnel(snell_ctx *ctx, snell_env *env)
{
    static float rgb[W * H * 3], dirs[W * H * 3];
    static uint8_t hit[W * H], ref[W * H * 4], px[W * H * 4];
    snell_mesh *sphere = shape(ctx, SNELL_SHAPE_SPHERE);
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_glass g;
    snell_ref *sref = NULL;
    snell_ref_params p;
    double psnr[4] = {0, 0, 0, 0};
    int k;
    if (!sphere) return;
    test_frame_one(&fd, &g, sphere, env);
    CHECK_OK(test_ref_create(ctx, &fd, &sref));
    if (!sref) return;
    test_ref_params(&fd, W, H, 10, &p);
    p.mode = SNELL_REF_FULL;
    CHECK_OK(test_ref_render(sref, &p, rgb, dirs, hit));
    snell_ref_rgb_to_rgba8(rgb, W, H, ref);
    snell_ref_destroy(sref);
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    for (k = 0; r && k < 4; k++) {
        snell_image_error e;
        g.material.method = SNELL_METHOD_LAYERED;
        g.material.layered.inner_fresnel = k == 1 ? SNELL_INNER_FRESNEL_OFF : SNELL_INNER_FRESNEL_AUTO;
        g.material.layered.convex_steps = k < 2 ? 0 : 4 - k; /* 2 and 1: the inner branch's exit in 1 step */
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        CHECK_OK(snell_renderer_read_rgba(r, px));
        CHECK_OK(snell_metrics_image_error(px, ref, W, H, hit, &e));
        psnr[k] = e.psnr_db;
    }
    printf("sphere colour vs FULL: inner auto %.2f dB, off %.2f dB; auto, iterations 2 %.2f dB, 1 %.2f dB\n", psnr[0],
           psnr[1], psnr[2], psnr[3]);
    /* measured 96x96, forward and screen space: auto 38.6, off 32.7 dB */
    CHECK(psnr[0] >= 37.0 && psnr[0] >= psnr[1] + 5.0, "inner Fresnel: %.2f dB against %.2f without", psnr[0],
          psnr[1]);
    CHECK(psnr[2] >= BOUND_INNER_IT2_DB, "inner Fresnel, iterations 2: %.2f dB < %.1f", psnr[2], BOUND_INNER_IT2_DB);
    CHECK(psnr[3] >= BOUND_INNER_IT1_DB, "inner Fresnel, iterations 1: %.2f dB < %.1f", psnr[3], BOUND_INNER_IT1_DB);
    snell_renderer_destroy(r);
    snell_mesh_destroy(sphere);
}

/* The convex path (one layer, no re-entry: tangent-plane steps to each
 * exit) on flat faces and a coarse sphere, whose exits are far from the
 * bounding sphere's, against MATCHED (its path there), with the default
 * iterations and with 2; and the sphere's colour against FULL with 2 (the
 * inner Fresnel's branch then takes 1 step). Measured 96x96 (2026-12-03,
 * forward and screen space): see the bounds. */
static void test_convex(snell_ctx *ctx, snell_env *env)
{
    static const int iters[2] = {0, 2};
    snell_shape_desc sd;
    snell_mesh *cube = shape(ctx, SNELL_SHAPE_CUBE), *sphere = shape(ctx, SNELL_SHAPE_SPHERE), *coarse = NULL;
    int k;
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    sd.segments = 12;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &coarse));
    for (k = 0; k < 2; k++) {
        char name[32];
        g_iterations = iters[k];
        snprintf(name, sizeof name, "cube it %d", iters[k]);
        accuracy(ctx, env, name, cube, SNELL_REF_MATCHED, BOUND_CUBE_MEDIAN, BOUND_CUBE_MEAN, 0.1);
        snprintf(name, sizeof name, "sphere@12 it %d", iters[k]);
        accuracy(ctx, env, name, coarse, SNELL_REF_MATCHED, BOUND_COARSE_MEDIAN, BOUND_COARSE_MEAN, 0.1);
    }
    /* one step from the sphere through the entry point (convex_exit's start) */
    g_iterations = 1;
    accuracy(ctx, env, "sphere it 1", sphere, SNELL_REF_MATCHED, BOUND_SPHERE_IT1_MEDIAN, BOUND_SPHERE_IT1_MEAN, 0.1);
    g_iterations = 0;
    snell_mesh_destroy(cube);
    snell_mesh_destroy(coarse);
    snell_mesh_destroy(sphere);
}

/* AUTO shading (stages.c choose_shading): the convex program is shaded
 * forward on large triangles (LAYERED_SOFTWARE_SCREEN_PPT_CONVEX on
 * llvmpipe), the march in screen space at any size. A 12-segment sphere and
 * the torus at 256^2 (about 100 and 20 estimated pixels a front triangle)
 * and the sphere at 32^2 (under 2). */
static void test_shading_rule(snell_ctx *ctx, snell_env *env)
{
    static const int sizes[3] = {256, 32, 256};
    snell_shape_desc sd;
    snell_mesh *coarse = NULL, *torus = shape(ctx, SNELL_SHAPE_TORUS);
    int k;
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    sd.segments = 12;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &coarse));
    if (!coarse || !torus || snell__device_class_of(snell_ctx_gl_renderer(ctx)) != SNELL__DEVICE_SOFTWARE) {
        snell_mesh_destroy(coarse);
        snell_mesh_destroy(torus);
        return;
    }
    for (k = 0; k < 3; k++) {
        snell_renderer *r = NULL;
        snell_renderer_desc rd;
        snell_frame_desc fd;
        snell_glass g;
        snell_frame_stats st;
        int forward;
        memset(&rd, 0, sizeof rd);
        rd.width = rd.height = sizes[k];
        CHECK_OK(snell_renderer_create(ctx, &rd, &r));
        if (!r) continue;
        test_frame_one(&fd, &g, k < 2 ? coarse : torus, env);
        g.material.method = SNELL_METHOD_LAYERED;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
        forward = !st.glass[0].screen_space;
        printf("shading: %s at %d^2, %.1f px/triangle: %s\n", k < 2 ? "sphere@12" : "torus", sizes[k],
               st.glass[0].pixels_per_triangle, forward ? "forward" : "screen space");
        CHECK(forward == (k == 0), "%s at %d^2 (%.1f px/triangle): %s", k < 2 ? "sphere@12" : "torus", sizes[k],
              st.glass[0].pixels_per_triangle, forward ? "forward" : "screen space");
        snell_renderer_destroy(r);
    }
    snell_mesh_destroy(coarse);
    snell_mesh_destroy(torus);
}

/* The bake: what it reports, and that it runs once per mesh version. */
static void test_bake(snell_ctx *ctx, snell_env *env)
{
    static float dirs[W * H * 3];
    snell_mesh *sphere = shape(ctx, SNELL_SHAPE_SPHERE), *torus = shape(ctx, SNELL_SHAPE_TORUS);
    snell_renderer *r = NULL;
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    int pass1, pass2;
    if (!sphere || !torus) return;
    r = test_renderer(ctx, 32, 32);
    if (!r) return;
    test_frame_one(&fd, &g, sphere, env);
    g.material.method = SNELL_METHOD_LAYERED;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
    pass1 = st.glass[0].passes;
    /* one layer holds the sphere from its centre, and a convex mesh is baked into one layer whatever
     * `layers` says: 128^2 faces x 6 x (1 layer + 1 slice of its distances) x 8 bytes (4 layers + 1
     * before: 3840 KiB) */
    CHECK(snell_object_counter(&st.glass[0], "layers_used") == 1, "sphere: %d layers used",
          snell_object_counter(&st.glass[0], "layers_used"));
    CHECK(snell_object_counter(&st.glass[0], "layers_capped") == 0, "sphere: capped");
    CHECK(snell_object_counter(&st.glass[0], "layers_kib") == 128 * 128 * 6 * (1 + 1) * 8 / 1024, "sphere: %d KiB",
          snell_object_counter(&st.glass[0], "layers_kib"));
    CHECK(st.glass[0].prepared == 1, "the first frame bakes");
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
    pass2 = st.glass[0].passes;
    CHECK(st.glass[0].prepared == 0 && pass1 == pass2 + 6 * 1, "baked once: %d then %d passes, prepared %d", pass1,
          pass2, st.glass[0].prepared);
    /* A new version of the mesh (moved vertices) is baked again. */
    CHECK_OK(snell_mesh_set_vertices(sphere, snell_mesh_positions(sphere), snell_mesh_normals(sphere)));
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
    CHECK(st.glass[0].prepared == 1, "a new mesh version is baked again");
    /* The torus from the box centre (in its hole) needs 2 layers; with 1 the bake is capped. */
    fd.glass = &g;
    g.mesh = torus;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
    CHECK(snell_object_counter(&st.glass[0], "layers_used") == 2 &&
              snell_object_counter(&st.glass[0], "layers_capped") == 0,
          "torus: %d layers used, capped %d", snell_object_counter(&st.glass[0], "layers_used"),
          snell_object_counter(&st.glass[0], "layers_capped"));
    g.material.layered.layers = 1;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
    CHECK(snell_object_counter(&st.glass[0], "layers_used") == 1 &&
              snell_object_counter(&st.glass[0], "layers_capped") == 1,
          "torus, 1 layer: %d used, capped %d", snell_object_counter(&st.glass[0], "layers_used"),
          snell_object_counter(&st.glass[0], "layers_capped"));
    snell_renderer_destroy(r);
    (void)dirs;
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(torus);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL;
    snell_mesh *m;
    if (!ctx) SKIP("no GL context");
    CHECK_OK(snell_env_create(ctx, &(snell_env_desc){.face_size = 64}, &env));
    test_bake(ctx, env);
    test_inner_fresnel(ctx, env);
    test_shading_rule(ctx, env);
    /* Bounds: the measured values (printed) with a margin, see the note per line. */
    m = shape(ctx, SNELL_SHAPE_SPHERE);
    accuracy(ctx, env, "sphere", m, SNELL_REF_MATCHED, BOUND_SPHERE_MEDIAN, BOUND_SPHERE_MEAN, 0.2);
    snell_mesh_destroy(m);
    test_convex(ctx, env);
    m = shape(ctx, SNELL_SHAPE_TORUS);
    accuracy(ctx, env, "torus", m, SNELL_REF_FULL, BOUND_TORUS_MEDIAN, BOUND_TORUS_MEAN, 0.35);
    snell_mesh_destroy(m);
    m = shape(ctx, SNELL_SHAPE_GOBLET);
    accuracy(ctx, env, "goblet", m, SNELL_REF_FULL, BOUND_GOBLET_MEDIAN, BOUND_GOBLET_MEAN, 0.35);
    snell_mesh_destroy(m);
    m = open_sphere(ctx);
    accuracy(ctx, env, "open sphere", m, SNELL_REF_FULL, BOUND_OPEN_MEDIAN, BOUND_OPEN_MEAN, 0.3);
    snell_mesh_destroy(m);
    m = NULL;
    if (snell_mesh_load(ctx, "/usr/share/glmark2/models/bunny.obj", &m) == SNELL_OK) {
        CHECK_OK(snell_mesh_normalize(m, 1.0f));
        real_accuracy(ctx, env, "bunny", m, SNELL_REF_MATCHED, 1.5f, SNELL_METHOD_PEEL, BOUND_BUNNY_MEDIAN,
                      BOUND_BUNNY_MEAN, 0.85);
        snell_mesh_destroy(m);
    } else {
        printf("bunny: glmark2's model not installed, not checked\n");
    }
    m = NULL;
    CHECK_OK(snell_mesh_load(ctx, test_data("real/horse.obj"), &m));
    if (m) {
        CHECK_OK(snell_mesh_normalize(m, 1.0f));
        real_accuracy(ctx, env, "horse", m, SNELL_REF_FULL, 1.33f, SNELL_METHOD_CUBEMAP, BOUND_HORSE_MEDIAN,
                      BOUND_HORSE_MEAN, 0.95);
        snell_mesh_destroy(m);
    }
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
