/* SPDX-License-Identifier: MIT */
/* test_budget_render.c — AUTO by frame budget in real frames (issue 25
 * item 3; render/budget_stage.c): the stage runs only with a budget and
 * says what it did; with a budget no frame can miss it climbs its ladder to
 * the top rung, with one no frame can meet it stays on the lowest (or on the
 * quality floor's rung, a resolution-scale rung among them: drawn at its
 * scale, its stats say so); the rung drawn is exactly the explicit method at
 * its scale (the same pixels); bad budgets are refused; the frames are measured by the
 * GPU's timer query where the context has one, never by a reading longer
 * than the wall clock around them, and not while a host's own timer query
 * runs. Times are not asserted here (a shared machine): snell-bench
 * --budget measures them (bench/BENCHMARKS.md). */
#define _POSIX_C_SOURCE 199309L
#include "test_util.h"

#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define W 96
#define H 96

static snell_mesh *torus(snell_ctx *ctx)
{
    snell_shape_desc sd;
    snell_mesh *mesh = NULL;
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_TORUS;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    if (mesh) CHECK_OK(snell_mesh_normalize(mesh, 1.0f));
    return mesh;
}

/* The frame of one glass object of mesh with material m (test_frame_one), seen from the test's camera. */
static void frame_of(snell_frame_desc *f, snell_glass *g, const snell_mesh *mesh, const snell_glass_material *m,
                     const snell_env *env)
{
    test_frame_one(f, g, mesh, env);
    g->material = *m;
    f->camera.distance = 3.5f;
    f->camera.azimuth = 0.5f;
    f->camera.elevation = 0.35f;
}

/* The frame the explicit method draws at resolution scale (0: full), on renderer plain, into out. */
static void explicit_frame(snell_renderer *plain, const snell_env *env, const snell_glass *g, snell_method m,
                           float scale, uint8_t *out)
{
    snell_glass e;
    snell_frame_desc fe;
    frame_of(&fe, &e, g->mesh, &g->material, env);
    e.material.method = m;
    e.material.scale = scale;
    CHECK_OK(snell_render(plain, &fe, NULL));
    CHECK_OK(snell_renderer_read_rgba(plain, out));
}

/* The budget's frame (pixels a) is the one the explicit method draws at that scale (into b). */
static void same_as_explicit(snell_renderer *plain, const snell_env *env, const snell_glass *g, snell_method m,
                             float scale, const uint8_t *a, uint8_t *b)
{
    explicit_frame(plain, env, g, m, scale, b);
    CHECK(!memcmp(a, b, W * H * 4), "the budget's %s at scale %g differs from explicit %s", snell_method_str(m),
          (double)scale, snell_method_str(m));
}

/* Frames with the budget until the plan has held for 10 frames; the last frame's stats. */
static void settle_plan(snell_renderer *r, snell_frame_desc *f, snell_frame_stats *st)
{
    int k, still = 0;
    for (k = 0; k < 60 && still < 10; k++) {
        CHECK_OK(snell_render(r, f, st));
        snell_renderer_finish(r);
        still = st->budget_changed ? 0 : still + 1;
    }
    CHECK(still >= 10, "the plan did not settle in 60 frames (last: %s)", st->budget_reason);
}

/* settle_plan, and the last frame's image. */
static void settle(snell_renderer *r, snell_frame_desc *f, snell_frame_stats *st, uint8_t *px)
{
    settle_plan(r, f, st);
    CHECK_OK(snell_renderer_read_rgba(r, px));
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

/* The budget's clock (issue 25 item 3): with EXT_disjoint_timer_query the
 * frames are measured by the GPU's timer (budget_clock 2), and no
 * measurement is longer than the wall clock from the measured frame's start
 * to the end of the frame that reports it (llvmpipe's first timer query in
 * a context reads hours: it must fall back to the fence's clock). While the
 * host's own TIME_ELAPSED query runs (queries of a target cannot nest) the
 * budget leaves it running and measures by the fence (1). */
static void test_clock(snell_ctx *ctx, const snell_renderer_desc *rd, snell_frame_desc *f)
{
    const int timer = snell_ctx_has_gl_extension(ctx, "GL_EXT_disjoint_timer_query");
    snell_renderer *r = NULL;
    snell_frame_stats st;
    double t0 = 0.0, prev = 0.0, t1;
    int k, by_gpu = 0, by_fence = 0, longer = 0;
    CHECK_OK(snell_renderer_create(ctx, rd, &r));
    if (!r) return;
    f->budget_ms = 1e5f;
    for (k = 0; k < 12; k++) {
        prev = t0;
        t0 = now_ms();
        CHECK_OK(snell_render(r, f, &st));
        t1 = now_ms();
        snell_renderer_finish(r);
        if (k == 0) continue;
        by_gpu += st.budget_clock == 2;
        by_fence += st.budget_clock == 1;
        longer += st.budget_measured_ms > t1 - prev + 1.0;
    }
    printf("clock: %d of 11 frames measured by the GPU timer, %d by the fence (timer query %s)\n", by_gpu, by_fence,
           timer ? "present" : "absent");
    CHECK(by_gpu + by_fence == 11 && longer == 0, "%d + %d frames measured, %d longer than the wall clock", by_gpu,
          by_fence, longer);
    CHECK(timer ? by_gpu >= 9 : by_gpu == 0, "%d frames by the GPU timer", by_gpu);
    if (timer) {
        GLuint q = 0, ns = 0;
        GLint current = 0;
        glGenQueries(1, &q);
        glBeginQuery(GL_TIME_ELAPSED_EXT, q);
        by_gpu = 0;
        for (k = 0; k < 6; k++) {
            CHECK_OK(snell_render(r, f, &st));
            snell_renderer_finish(r);
            by_gpu += k > 0 && st.budget_clock == 2; /* frame 0 reports the frame before the host's query */
        }
        glGetQueryiv(GL_TIME_ELAPSED_EXT, GL_CURRENT_QUERY_EXT, &current);
        CHECK(by_gpu == 0 && current == (GLint)q, "host's query: %d frames by the GPU timer, current query %d of %u",
              by_gpu, current, q);
        glEndQuery(GL_TIME_ELAPSED_EXT);
        glGetQueryObjectuiv(q, GL_QUERY_RESULT, &ns);
        CHECK(glGetError() == GL_NO_ERROR && ns > 0, "host's query: GL error or %u ns", ns);
        glDeleteQueries(1, &q);
    }
    f->budget_ms = 0.0f;
    snell_renderer_destroy(r);
}

/* An open, non-manifold real mesh (glmark2's horse, IOR 1.33; issue 25's
 * "AUTO by budget at most half the cubemap's FULL mean angle"): with a
 * budget no frame misses and exact allowed on its ladder
 * (material.exact.auto_pick), AUTO climbs to exact with the FULL model's
 * terms (its top rung, issue 50), and its exit directions
 * are at most half as far from FULL's (10 interfaces) on average as the
 * cubemap's (plain AUTO's pick there is single: bench/notes/history.md).
 * Measured 2026-12-04 (96x96, elevation 0.35, as test_layered's horse):
 * exact mean 8.39 deg, median 0.000; the cubemap 24.71, 6.005 (0.34x the
 * mean). Without exact on the ladder its top is peel: 21.39, 3.222 (0.87x;
 * layered 21.8-22.0 in test_layered), not asserted. */
static void test_open_mesh(snell_ctx *ctx, const snell_env *env)
{
    static float ref[W * H * 3], cube[W * H * 3], dirs[W * H * 3];
    static uint8_t hit[W * H];
    snell_mesh *horse = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc f;
    snell_frame_stats st;
    snell_glass g;
    snell_dir_error ec, ea[2];
    int allow, traced;
    if (!snell_build_has("ref") || !snell_build_has("exact")) {
        printf("open mesh: skipped (built without the reference or exact)\n");
        return;
    }
    CHECK_OK(snell_mesh_load(ctx, test_data("real/horse.obj"), &horse));
    if (!horse) return;
    CHECK_OK(snell_mesh_normalize(horse, 1.0f));
    frame_of(&f, &g, horse, &(snell_glass_material){.ior = 1.33f}, env);
    traced = test_ref_dirs(ctx, &f, W, H, SNELL_REF_FULL, 10, ref, hit);
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r || !traced) goto done;
    g.material.method = SNELL_METHOD_CUBEMAP;
    CHECK_OK_CTX(ctx, snell_render(r, &f, NULL));
    CHECK_OK(snell_renderer_read_exit_dirs(r, cube));
    ec = test_dir_error(cube, ref, hit, W, H);
    g.material.method = SNELL_METHOD_AUTO;
    f.budget_ms = 1e5f;
    for (allow = 0; allow < 2; allow++) {
        g.material.exact.auto_pick = allow ? SNELL_EXACT_AUTO_ALLOW : SNELL_EXACT_AUTO_NEVER;
        settle_plan(r, &f, &st);
        CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
        ea[allow] = test_dir_error(dirs, ref, hit, W, H);
        CHECK(st.glass[0].method_used == (allow ? SNELL_METHOD_EXACT : SNELL_METHOD_PEEL),
              "horse, exact %s: the top rung drawn by %s (%s)", allow ? "allowed" : "not allowed",
              snell_method_str(st.glass[0].method_used), st.glass[0].reason);
        /* exact's top rung is the FULL model's terms (issue 50 item 4) */
        CHECK(!allow || (strstr(st.glass[0].reason, "inner_fresnel=on") && strstr(st.glass[0].reason, "reentry=on")),
              "horse, exact allowed: the top rung without the FULL model's terms (%s)", st.glass[0].reason);
        printf("horse, budget %g ms, exact %s: %s, FULL mean %.2f median %.3f deg (cubemap %.2f / %.3f)\n",
               (double)f.budget_ms, allow ? "allowed" : "never", snell_method_str(st.glass[0].method_used),
               ea[allow].mean_deg, ea[allow].median_deg, ec.mean_deg, ec.median_deg);
    }
    CHECK(ec.compared > W * H / 40, "horse: %ld pixels compared", ec.compared);
    CHECK(ea[1].mean_deg <= 0.5 * ec.mean_deg, "horse: AUTO by budget (exact allowed) mean %.2f > half the cubemap's %.2f",
          ea[1].mean_deg, ec.mean_deg);
done:
    snell_renderer_destroy(r);
    snell_mesh_destroy(horse);
}

int main(void)
{
    snell_ctx *ctx = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL, *plain = NULL;
    snell_mesh *mesh;
    snell_glass g;
    snell_frame_desc f;
    snell_frame_stats st;
    uint8_t *a = (uint8_t *)malloc(W * H * 4), *b = (uint8_t *)malloc(W * H * 4);
    snell_renderer_desc rd;
    snell_status s;

    if (snell_ctx_create(NULL, &ctx) != SNELL_OK) SKIP("no EGL/GLES 3.0 context: %s", snell_last_error(NULL));
    CHECK_OK(snell_env_create(ctx, &(snell_env_desc){0}, &env));
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    CHECK_OK(snell_renderer_create(ctx, &rd, &plain));
    mesh = torus(ctx);
    if (!r || !plain || !mesh || !a || !b) return test_finish();
    frame_of(&f, &g, mesh, &(snell_glass_material){.ior = 1.5f}, env);

    /* No budget: no stage, no budget stats. */
    CHECK_OK(snell_render(r, &f, &st));
    CHECK(!strstr(st.stages, "budget") && st.budget_ms == 0.0f && !st.budget_reason[0], "no budget: stages \"%s\"",
          st.stages);

    /* A budget no frame misses: the top of the torus's ladder (a closed concave mesh the cubemap does not
     * serve: peel). */
    f.budget_ms = 1e5f;
    settle(r, &f, &st, a);
    CHECK(!strncmp(st.stages, "budget ", 7), "stages \"%s\"", st.stages);
    CHECK(st.budget_ms == 1e5f && st.budget_measured_ms > 0.0 && st.budget_predicted_ms > 0.0,
          "budget stats: %g / %g / %g", (double)st.budget_ms, st.budget_measured_ms, st.budget_predicted_ms);
    CHECK(st.glass[0].method_used == SNELL_METHOD_PEEL, "top rung drawn by %s (%s)",
          snell_method_str(st.glass[0].method_used), st.glass[0].reason);
    CHECK(!strncmp(st.glass[0].reason, "auto by budget: peel (rung ", 27), "reason \"%s\"", st.glass[0].reason);
    printf("huge budget: %s; %s\n", st.glass[0].reason, st.budget_reason);
    /* ... drawn exactly as the explicit method draws it */
    same_as_explicit(plain, env, &g, SNELL_METHOD_PEEL, 0.0f, a, b);

    /* A budget no frame meets: the lowest rung, single, drawn as single draws. */
    f.budget_ms = 1e-3f;
    settle(r, &f, &st, a);
    CHECK(st.glass[0].method_used == SNELL_METHOD_SINGLE, "tiny budget drawn by %s (%s)",
          snell_method_str(st.glass[0].method_used), st.glass[0].reason);
    CHECK(st.budget_measured_ms > 1e-3, "measured %g ms", st.budget_measured_ms);
    printf("tiny budget: %s; %s\n", st.glass[0].reason, st.budget_reason);
    same_as_explicit(plain, env, &g, SNELL_METHOD_SINGLE, 0.0f, a, b);

    /* The quality floor wins over the budget: the first rung of the torus's ladder predicted at its
     * value or more. At peel at scale 2's predicted PSNR for the torus (the class of closed concave meshes the
     * cubemap does not serve, 2), with the budget no frame meets, AUTO draws that rung (issue 25 item 3):
     * its stats say scale 2, its pixels are explicit peel's at scale 2, not at full resolution. A little
     * above it: unscaled peel, the rung above. */
    {
        const snell_budget_rung *pick = NULL;
        int k;
        for (k = 0; k < snell_budget_rung_count(); k++)
            if (snell_budget_rung_at(k)->method == SNELL_METHOD_PEEL && !snell_budget_rung_at(k)->param &&
                snell_budget_rung_at(k)->scale == 2)
                pick = snell_budget_rung_at(k);
        CHECK(pick && pick->db[2] > 0.0f, "no rung peel scale=2 for the torus in the table");
        if (pick) {
            f.quality_floor_db = pick->db[2];
            settle(r, &f, &st, a);
            CHECK(st.glass[0].method_used == SNELL_METHOD_PEEL && st.glass[0].scale == 2.0f &&
                      strstr(st.glass[0].reason, "auto by budget: peel scale=2 (rung"),
                  "floor %.2f dB drawn by %s at scale %g (%s)", (double)f.quality_floor_db,
                  snell_method_str(st.glass[0].method_used), (double)st.glass[0].scale, st.glass[0].reason);
            printf("floor at peel scale=2's PSNR: %s\n", st.glass[0].reason);
            same_as_explicit(plain, env, &g, SNELL_METHOD_PEEL, 2.0f, a, b);
            explicit_frame(plain, env, &g, SNELL_METHOD_PEEL, 1.0f, b);
            CHECK(memcmp(a, b, W * H * 4), "peel at scale 2 drew the unscaled frame's pixels");
            f.quality_floor_db = pick->db[2] + 0.01f;
            settle(r, &f, &st, a);
            CHECK(st.glass[0].method_used == SNELL_METHOD_PEEL && st.glass[0].scale == 1.0f &&
                      strstr(st.glass[0].reason, "auto by budget: peel (rung"),
                  "floor above peel scale=2's drawn by %s at scale %g (%s)", snell_method_str(st.glass[0].method_used),
                  (double)st.glass[0].scale, st.glass[0].reason);
        }
    }
    f.quality_floor_db = 0.0f;

    /* Off again: plain AUTO (cubemap for the torus), the same pixels as a renderer that never had a budget. */
    f.budget_ms = 0.0f;
    CHECK_OK(snell_render(r, &f, &st));
    CHECK_OK(snell_renderer_read_rgba(r, a));
    CHECK_OK(snell_render(plain, &f, NULL));
    CHECK_OK(snell_renderer_read_rgba(plain, b));
    CHECK(!memcmp(a, b, W * H * 4) && !strstr(st.stages, "budget"), "budget off: not plain AUTO's frame");

    /* snell_renderer_warm: with a budget it times every rung of the ladder (the frame without glass, the
     * lowest rung, then each rung above once built: 1 + 4 + 3 + 4 x (rungs - 1) frames), and the frames
     * after it are planned from those costs: the first one already on the top rung, none a first use. */
    {
        snell_renderer *w = NULL;
        snell_warm_stats ws;
        int k, first_uses = 0;
        CHECK_OK(snell_renderer_create(ctx, &rd, &w));
        f.budget_ms = 1e5f;
        CHECK_OK(snell_renderer_warm(w, &f, &ws));
        printf("warm: %d frames, %.1f ms, %d rungs timed, base %.2f ms\n", ws.frames, ws.ms, ws.rungs, ws.base_ms);
        CHECK(ws.rungs >= 3 && ws.frames == 8 + 4 * (ws.rungs - 1) && ws.base_ms > 0.0 && ws.ms > 0.0,
              "warm: %d frames, %d rungs, base %g ms", ws.frames, ws.rungs, ws.base_ms);
        for (k = 0; k < 12; k++) {
            CHECK_OK(snell_render(w, &f, &st));
            snell_renderer_finish(w);
            first_uses += st.budget_first_use;
            if (k == 0)
                CHECK(st.glass[0].method_used == SNELL_METHOD_PEEL && st.budget_predicted_ms > 0.0,
                      "first frame after warm drawn by %s (%s; %s)", snell_method_str(st.glass[0].method_used),
                      st.glass[0].reason, st.budget_reason);
        }
        CHECK(first_uses == 0, "%d frames after warm drew a configuration for the first time", first_uses);
        CHECK_OK(snell_renderer_read_rgba(w, a));
        same_as_explicit(plain, env, &g, SNELL_METHOD_PEEL, 0.0f, a, b);
        /* without a budget: the frame once */
        f.budget_ms = 0.0f;
        CHECK_OK(snell_renderer_warm(w, &f, &ws));
        CHECK(ws.frames == 1 && ws.rungs == 0, "warm without a budget: %d frames, %d rungs", ws.frames, ws.rungs);
        /* a frame snell_render refuses is refused, and so are NULLs */
        f.budget_ms = NAN;
        CHECK(snell_renderer_warm(w, &f, &ws) == SNELL_E_INVALID_ARG && ws.rungs == 0, "warm took a NaN budget");
        CHECK(snell_renderer_warm(NULL, &f, NULL) == SNELL_E_INVALID_ARG, "warm took a NULL renderer");
        CHECK(snell_renderer_warm(w, NULL, NULL) == SNELL_E_INVALID_ARG, "warm took a NULL frame");
        f.budget_ms = 0.0f;
        snell_renderer_destroy(w);
    }

    test_clock(ctx, &rd, &f);
    test_open_mesh(ctx, env);

    /* Refusals. */
    f.budget_ms = NAN;
    s = snell_render(r, &f, NULL);
    CHECK(s == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "budget_ms"), "NaN budget: %s",
          snell_last_error(ctx));
    f.budget_ms = -5.0f;
    CHECK(snell_render(r, &f, NULL) == SNELL_E_INVALID_ARG, "negative budget accepted");
    f.budget_ms = 30.0f;
    f.quality_floor_db = 150.0f;
    s = snell_render(r, &f, NULL);
    CHECK(s == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "quality_floor_db"), "floor 150: %s",
          snell_last_error(ctx));

    snell_renderer_destroy(r);
    snell_renderer_destroy(plain);
    snell_mesh_destroy(mesh);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    free(a);
    free(b);
    return test_finish();
}
