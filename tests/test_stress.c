/* SPDX-License-Identifier: MIT */
/* test_stress — every refraction method against the reference (MATCHED, the
 * method's own optical model) under conditions that break naive float code:
 * IOR 1.0 / 1.0001 (no or almost no bending), 1.33, 1.5, 2.42 (diamond), 4.0
 * (strong TIR), grazing views of flat faces, mesh scales 1e-3 and 1e3 (camera
 * scaled alike), and a thin shell (a bubble of glass 2% thick). For each case:
 * zero NaN/Inf exit directions, the object covers the pixels the reference
 * says it does (coverage mismatches only along the silhouette), and the
 * exit-direction error within the method's stated bounds (table below).
 *
 * Built with -DSNELL_FP16_EMULATION=ON the shaders round their mediump
 * intermediates to fp16; the test then shows which cases mediump breaks
 * (expected: IOR 1.0001 loses its bending entirely, 1/1.0001 rounds to 1).
 * Argument: a method name to test only that method, then "terms" for exact
 * with its FULL-model terms on as AUTO by budget's top exact rung draws
 * them (against MATCHED with the same snell_ref_terms and interface cap, the
 * same bounds); the environment variable
 * STRESS_ONLY=substring restricts the cases by label (for diagnosis). */
#include "test_util.h"
#include "core/pack.h"
#include "render/budget.h"
#include "snell/snell_metrics.h"
#include "snell/snell_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 128
#define H 128
#define PI 3.14159265358979323846

/* Bounds per method, vs the MATCHED reference with the method's interface
 * cap. Methods are named, not SNELL_METHOD_* values, so that this file stays
 * in a build that leaves some out (tests/stress.cmake registers one test per
 * method of the registry; a method without a row here runs the checks every
 * method must pass and reports its error bounds as not stated, exit 77).
 * single: the same optical model as MATCHED(1), so only float precision
 * and coverage separate them (measured mean ~0.02 deg at 256^2). cubemap:
 * loose, an approximate exit search; tighten as the method matures. */
typedef struct method_case {
    const char *name;
    int interfaces;             /* MATCHED cap; 0: the registry's model (ref_interfaces, else its
                                 * "max_interfaces" parameter's default) */
    int absorb;                 /* a snell_ref_absorption; -1: the registry's (ref_chord_absorption) */
    double max_mean_deg;        /* mean angular error over compared pixels */
    double max_frac_above_5;    /* share of compared pixels above 5 degrees */
    double max_median_deg;      /* median angular error (0: not bounded) */
    float max_hidden;           /* error bounds only where snell_mesh_analyze's hidden_fraction is at
                                 * most this (the method's domain; 1: every mesh) */
} method_case;

static const method_case g_methods[] = {
    {"single", 1, SNELL_REF_ABSORB_BOUNDING_SPHERE, 0.1, 0.002, 0.0, 1.0f},
    /* cubemap: star-shaped meshes (hidden_fraction <= 0.05, AUTO's rule) */
    {"cubemap", 3, SNELL_REF_ABSORB_PATH, 45.0, 0.9, 0.0, 0.05f},
    /* peel: MATCHED(8) is its path on convex meshes only (no re-entry), so
     * bounded on the star-shaped ones; measured at worst mean 1.3 deg, 2.6%
     * above 5 deg (sphere, IOR 4: grazing entries, steep exits) */
    {"peel", 8, SNELL_REF_ABSORB_PATH, 3.0, 0.05, 0.0, 0.05f},
    /* wyman, oliveira, exact: vs the registry's MATCHED model (wyman 2, oliveira
     * its interfaces default 2, exact 8; absorption over the path), bounds the
     * worst case measured at 128^2 in all three shading runs (auto, forward,
     * screen: within 0.01 deg of each other) plus about 10%, on llvmpipe.
     * wyman and oliveira on the star-shaped meshes (sphere, cube) only: the
     * torus (49% hidden) is inside their fit (0.6) but a view through its
     * hole breaks the back-face exit estimate (torus grazing el 0: wyman mean
     * 50.5, median 53.3 deg, 98.4% above 5; oliveira 41.3, 27.6, 74.5%) and
     * the shell (100% hidden) outside it; both are still checked for NaN and
     * coverage. Their worst star-shaped case is the sphere at IOR 4 (wyman mean
     * 39.72, median 12.75 deg, 66.6% above 5; oliveira 18.58, 6.01, 58.9%);
     * at IOR 1.5 wyman 12.26 / 1.55 / 31.3%, oliveira 3.49 / 0.96 / 6.2%. */
    {"wyman", 0, -1, 44.0, 0.72, 14.0, 0.05f},
    {"oliveira", 0, -1, 20.5, 0.65, 6.6, 0.05f},
    /* exact is MATCHED on the GPU, on every mesh: measured mean <= 0.0002,
     * median <= 0.0001, p99 <= 0.0031, max 0.307 deg (torus grazing el 0),
     * none above 5 deg; the bounds leave room for float paths that part from
     * the double ones after several bounces (0.2% of pixels above 5 deg). */
    {"exact", 0, -1, 0.01, 0.002, 0.001, 1.0f},
    /* layered: MATCHED(8) is its path where no ray meets the mesh again, so
     * bounded on the star-shaped meshes (sphere, cube), as peel; measured at
     * 128^2 in all three shading runs at worst mean 0.883 deg, 2.19% above 5
     * deg (the cube at grazing views: a texel's distance across an edge),
     * median 0.023 (sphere, IOR 4); plus about 15%. Outside: torus grazing
     * el 0 mean 9.0, the 2% shell 1.16 (median 0.57). */
    {"layered", 8, SNELL_REF_ABSORB_PATH, 1.0, 0.025, 0.03, 0.05f},
    /* hybrid: the cubemap (4 interfaces) where it trusts itself, exact (8)
     * where it doubts; vs MATCHED(8) on the star-shaped meshes, where the
     * cubemap's own bounds hold; measured at 128^2 in all three shading
     * runs at worst mean 1.75 deg, 1.17% above 5 (cube grazing az 45),
     * median 1.12; plus about 15%. Outside: torus grazing el 0 mean 35 deg
     * (a path crossing a surface hidden from the cube's centre between an
     * entry and an exit it holds is not doubted), the 2% shell 39. */
    {"hybrid", 8, SNELL_REF_ABSORB_PATH, 2.0, 0.014, 1.3, 0.05f},
};

/* A method as run: its registry entry, its row (NULL: none stated) and the
 * MATCHED model it is compared with. */
typedef struct stress_method {
    const char *name;
    snell_method id;
    const method_case *bounds;
    int interfaces;
    snell_ref_absorption absorb;
    unsigned terms;             /* exact's terms on: snell_ref_terms of the reference (0: none) */
    const snell_budget_rung *rung; /* with terms: the budget's rung that draws them, NULL none */
} stress_method;

/* AUTO by budget's exact rung with all three terms (its top one). */
static const snell_budget_rung *terms_rung(void)
{
    const snell_budget_rung *found = NULL;
    int i;
    for (i = 0; i < snell_budget_rung_count(); i++)
        if (snell_budget_rung_at(i)->method == SNELL_METHOD_EXACT && snell_budget_rung_at(i)->more &&
            strstr(snell_budget_rung_at(i)->more, "inner_fresnel=on"))
            found = snell_budget_rung_at(i);
    return found;
}

static int resolve_method(const snell_method_info *info, stress_method *out)
{
    size_t i;
    int v = 0;
    memset(out, 0, sizeof *out);
    out->name = info->name;
    out->id = info->method;
    for (i = 0; i < sizeof g_methods / sizeof *g_methods; i++)
        if (!strcmp(g_methods[i].name, info->name)) out->bounds = &g_methods[i];
    /* the registry's MATCHED model (what snell-bench compares with) */
    out->interfaces = info->ref_interfaces;
    if (out->interfaces <= 0) {
        for (i = 0; i < (size_t)info->param_count; i++)
            if (!strcmp(info->params[i].name, "max_interfaces")) v = info->params[i].def;
        out->interfaces = v > 0 ? v : 10;
    }
    out->absorb = info->ref_chord_absorption ? SNELL_REF_ABSORB_BOUNDING_SPHERE : SNELL_REF_ABSORB_PATH;
    if (out->bounds && out->bounds->interfaces > 0) out->interfaces = out->bounds->interfaces;
    if (out->bounds && out->bounds->absorb >= 0) out->absorb = (snell_ref_absorption)out->bounds->absorb;
    return 1;
}

typedef struct scene_case {
    const char *label;
    const snell_mesh *mesh;
    float ior;
    float az_deg, el_deg;
    float scale;
} scene_case;

static snell_status make_shell(snell_ctx *ctx, const snell_mesh *sphere, float inner, snell_mesh **out)
{
    uint32_t nv = snell_mesh_vertex_count(sphere), nt = snell_mesh_triangle_count(sphere), i;
    const float *p = snell_mesh_positions(sphere), *n = snell_mesh_normals(sphere);
    const uint32_t *idx = snell_mesh_indices(sphere);
    float *pos = (float *)malloc(sizeof(float) * 6 * nv), *nor = (float *)malloc(sizeof(float) * 6 * nv);
    uint32_t *ind = (uint32_t *)malloc(sizeof(uint32_t) * 6 * nt);
    snell_mesh_desc d;
    snell_status st = SNELL_E_NOMEM;
    if (pos && nor && ind) {
        for (i = 0; i < 3 * nv; i++) {
            pos[i] = p[i];
            nor[i] = n[i];
            pos[3 * nv + i] = inner * p[i];
            nor[3 * nv + i] = -n[i]; /* the inner wall faces the cavity */
        }
        for (i = 0; i < nt; i++) {
            ind[3 * i] = idx[3 * i];
            ind[3 * i + 1] = idx[3 * i + 1];
            ind[3 * i + 2] = idx[3 * i + 2];
            ind[3 * (nt + i)] = nv + idx[3 * i];
            ind[3 * (nt + i) + 1] = nv + idx[3 * i + 2]; /* reversed winding */
            ind[3 * (nt + i) + 2] = nv + idx[3 * i + 1];
        }
        memset(&d, 0, sizeof d);
        d.positions = pos;
        d.normals = nor;
        d.indices = ind;
        d.vertex_count = 2 * nv;
        d.triangle_count = 2 * nt;
        st = snell_mesh_create(ctx, &d, out);
    }
    free(pos);
    free(nor);
    free(ind);
    return st;
}

/* Silhouette pixels of a mask: set, with a 4-neighbour unset (or the border). */
static long edge_pixels(const uint8_t *m)
{
    long c = 0;
    int x, y;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int i = y * W + x;
            if (!m[i]) continue;
            if (x == 0 || y == 0 || x == W - 1 || y == H - 1 || !m[i - 1] || !m[i + 1] || !m[i - W] || !m[i + W]) c++;
        }
    return c;
}

#define STRESS_CHECK(cond, ...)                                                                                        \
    do {                                                                                                               \
        ok &= !!(cond);                                                                                                \
        CHECK(cond, __VA_ARGS__);                                                                                      \
    } while (0)

static int run_case(snell_ctx *ctx, snell_renderer *r, const snell_env *env, const stress_method *mc,
                    const scene_case *sc)
{
    static float dirs[W * H * 3], rgb[W * H * 3], ref_dirs[W * H * 3];
    static uint8_t mask[W * H], hit[W * H];
    snell_frame_desc fd;
    snell_glass g;
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_dir_error_desc dd;
    snell_dir_error e;
    float model[16];
    long edges, bg_marked = 0, i;
    int ok = 1;
    snell_status st;

    memset(model, 0, sizeof model);
    model[0] = model[5] = model[10] = sc->scale;
    model[15] = 1.0f;
    test_frame_one(&fd, &g, sc->mesh, env);
    g.model = model;
    g.material.method = mc->id;
    g.material.ior = sc->ior;
    if (mc->terms) {
        g.material.exact.fresnel = SNELL_FRESNEL_EXACT;
        g.material.exact.inner_fresnel = SNELL_INNER_FRESNEL_ON;
        g.material.exact.reentry = SNELL_EXACT_REENTRY_ON;
        if (mc->rung) CHECK_OK(snell__rung_apply(mc->rung, &g.material));
    }
    fd.camera.azimuth = (float)(sc->az_deg * PI / 180.0);
    fd.camera.elevation = (float)(sc->el_deg * PI / 180.0);
    fd.camera.distance = 3.5f * sc->scale;
    fd.glass_count = 0; /* the background alone: no pixel of it is glass */
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_coverage(r, mask));
    for (i = 0; i < W * H; i++) bg_marked += mask[i] != 0;
    STRESS_CHECK(bg_marked == 0, "%s %s: %ld pixels of the background alone marked as glass", mc->name, sc->label,
                 bg_marked);
    fd.glass_count = 1;
    st = snell_render(r, &fd, NULL);
    if (st != SNELL_OK) {
        CHECK(0, "%s %s: render failed: %s", mc->name, sc->label, snell_last_error(ctx));
        return 0;
    }
    CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
    /* The renderer's own coverage, not 'the direction differs from the
     * background's' (snell_metrics_coverage_mask): a path that leaves unbent
     * (IOR 1, or through a cube's opposite faces, a slab at any IOR) has the
     * view ray's direction; the float target told it apart only by rounding,
     * the packed one not at all. */
    CHECK_OK(snell_renderer_read_coverage(r, mask));

    CHECK_OK(test_ref_create(ctx, &fd, &ref));
    if (!ref) return 0;
    test_ref_params(&fd, W, H, mc->interfaces, &p);
    p.absorption_model = mc->absorb;
    p.terms = mc->terms;
    CHECK_OK(test_ref_render(ref, &p, rgb, ref_dirs, hit));
    snell_ref_destroy(ref);
    if (strcmp(snell_renderer_exit_dir_encoding(r), "float") != 0)
        /* The reference stored as the target stores it (pack.h, the shader's
         * twin bit for bit, test_exit_dir): the error measured is then the
         * method's, not the packing's (median about 0.002 deg on its own,
         * above exact's float-rounding bound). */
        for (i = 0; i < W * H; i++) {
            uint8_t px[4];
            snell_pack_exit_rgba8(ref_dirs + 3 * i, 1, px);
            (void)snell_unpack_exit_rgba8(px, ref_dirs + 3 * i);
        }

    memset(&dd, 0, sizeof dd);
    dd.test = dirs;
    dd.ref = ref_dirs;
    dd.ref_mask = hit;
    dd.test_mask = mask;
    dd.width = W;
    dd.height = H;
    CHECK_OK(snell_metrics_dir_error(&dd, &e));
    edges = edge_pixels(hit);
    printf("%-8s %-22s glass %5ld/%5ld mismatch %4ld (edge %4ld) NaN %ld  mean %.4f median %.4f p99 %.4f max %.3f "
           "deg  >1 %.2f%% >5 %.2f%%\n",
           mc->name, sc->label, e.glass_ref, e.glass_test, e.mask_mismatch, edges, e.nan_inf, e.mean_deg,
           e.median_deg, e.p99_deg, e.max_deg, 100.0 * e.frac_above_1deg, 100.0 * e.frac_above_5deg);
    STRESS_CHECK(e.nan_inf == 0, "%s %s: %ld NaN/Inf exit directions", mc->name, sc->label, e.nan_inf);
    STRESS_CHECK(e.zero_length == 0, "%s %s: %ld zero exit directions", mc->name, sc->label, e.zero_length);
    STRESS_CHECK(e.glass_ref > W * H / 50, "%s %s: object too small (%ld pixels)", mc->name, sc->label, e.glass_ref);
    /* Coverage differs only along the silhouette (a triangle edge vs the BVH
     * hit); in a flat grazing view the whole face is 'silhouette'. */
    STRESS_CHECK(e.mask_mismatch <= edges + W * H / 1000, "%s %s: %ld coverage mismatches vs %ld silhouette pixels",
                 mc->name, sc->label, e.mask_mismatch, edges);
    if (!mc->bounds) return ok; /* no bounds stated: main says so */
    if (mc->bounds->max_hidden < 1.0f) {
        snell_mesh_analysis an;
        CHECK_OK(snell_mesh_analyze(sc->mesh, &an));
        if (an.hidden_fraction > mc->bounds->max_hidden) {
            printf("  (%s: %.0f%% of the surface hidden from the centre, above %.0f%%: outside the method's domain, "
                   "error not bounded)\n", mc->name, 100.0 * an.hidden_fraction, 100.0 * mc->bounds->max_hidden);
            return ok;
        }
    }
    STRESS_CHECK(e.mean_deg <= mc->bounds->max_mean_deg, "%s %s: mean error %.4f deg > %.4f", mc->name, sc->label,
                 e.mean_deg, mc->bounds->max_mean_deg);
    STRESS_CHECK(e.frac_above_5deg <= mc->bounds->max_frac_above_5, "%s %s: %.3f%% above 5 deg > %.3f%%", mc->name,
                 sc->label, 100.0 * e.frac_above_5deg, 100.0 * mc->bounds->max_frac_above_5);
    if (mc->bounds->max_median_deg > 0.0)
        STRESS_CHECK(e.median_deg <= mc->bounds->max_median_deg, "%s %s: median error %.4f deg > %.4f", mc->name,
                     sc->label, e.median_deg, mc->bounds->max_median_deg);
    return ok;
}

int main(int argc, char **argv)
{
    snell_ctx *ctx = test_ctx();
    snell_mesh *sphere = NULL, *cube = NULL, *torus = NULL, *shell = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rdesc;
    snell_shape_desc sd;
    snell_env_desc ed;
    size_t m, k;
    int broken = 0, ran = 0, not_run = 0, unbounded = 0, named = 0, rc;
    if (!ctx) SKIP("no GL context");
    memset(&sd, 0, sizeof sd);
    memset(&ed, 0, sizeof ed);
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &sphere));
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &cube));
    sd.shape = SNELL_SHAPE_TORUS;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &torus));
    if (sphere) CHECK_OK(make_shell(ctx, sphere, 0.98f, &shell));
    CHECK_OK(snell_env_create(ctx, &ed, &env));
    memset(&rdesc, 0, sizeof rdesc);
    rdesc.width = W;
    rdesc.height = H;
    rdesc.output = SNELL_OUTPUT_EXIT_DIRECTION;
    rdesc.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rdesc, &r));
    if (!sphere || !cube || !torus || !shell || !env || !r) return test_finish();
    printf("exit directions stored as %s%s\n", snell_renderer_exit_dir_encoding(r),
#ifdef SNELL_FP16_EMULATION
           "; FP16 EMULATION build"
#else
           ""
#endif
    );
    if (strcmp(snell_renderer_exit_dir_encoding(r), "float"))
        printf("note: packed directions cannot hold NaN/Inf; the NaN check is weaker here\n");
    {
        const scene_case cases[] = {
            {"sphere ior 1.0", sphere, 1.0f, 30, 20, 1.0f},
            {"sphere ior 1.0001", sphere, 1.0001f, 30, 20, 1.0f},
            {"sphere ior 1.33", sphere, 1.33f, 30, 20, 1.0f},
            {"sphere ior 1.5", sphere, 1.5f, 30, 20, 1.0f},
            {"sphere ior 2.42", sphere, 2.42f, 30, 20, 1.0f},
            {"sphere ior 4.0", sphere, 4.0f, 30, 20, 1.0f},
            {"torus ior 4.0", torus, 4.0f, 10, 35, 1.0f},
            {"cube grazing el 0.5", cube, 1.5f, 0.5f, 0.5f, 1.0f},
            {"cube grazing az 45", cube, 1.5f, 45.0f, 0.3f, 1.0f},
            {"torus grazing el 0", torus, 1.5f, 20.0f, 0.0f, 1.0f},
            {"sphere scale 1e-3", sphere, 1.5f, 30, 20, 1e-3f},
            {"sphere scale 1e3", sphere, 1.5f, 30, 20, 1e3f},
            {"torus scale 1e-3", torus, 1.5f, 30, 20, 1e-3f},
            {"torus scale 1e3", torus, 1.5f, 30, 20, 1e3f},
            {"thin shell 2%", shell, 1.5f, 30, 20, 1.0f},
        };
        /* the registry's methods, or the one named (tests/stress.cmake: one test per method) */
        for (m = 0; m < (size_t)snell_method_count(); m++) {
            const snell_method_info *info = snell_method_info_at((int)m);
            stress_method sm;
            snell_frame_desc probe;
            snell_glass pg;
            if (argc > 1 && strcmp(argv[1], info->name)) continue;
            resolve_method(info, &sm);
            if (argc > 2 && !strcmp(argv[2], "terms")) {
                if (sm.id != SNELL_METHOD_EXACT) continue;
                sm.terms = SNELL_REF_TERMS_ALL;
                sm.rung = terms_rung();
                CHECK(sm.rung != NULL, "no exact rung with the terms in the budget's table");
                if (sm.rung && !strcmp(sm.rung->param ? sm.rung->param : "", "max_interfaces"))
                    sm.interfaces = sm.rung->value;
            }
            named = 1;
            test_frame_one(&probe, &pg, sphere, env);
            pg.material.method = sm.id;
            if (snell_render(r, &probe, NULL) != SNELL_OK) {
                /* e.g. a method that shades in screen space only, with forward shading forced */
                printf("%s: does not render here (%s)\n", sm.name, snell_last_error(ctx));
                not_run++;
                continue;
            }
            ran++;
            printf("%s%s vs MATCHED(%d), absorption %s\n", sm.name,
                   sm.terms ? " with its terms (the budget's rung)" : "", sm.interfaces,
                   sm.absorb == SNELL_REF_ABSORB_BOUNDING_SPHERE ? "over the bounding-sphere chord" : "over the path");
            for (k = 0; k < sizeof cases / sizeof *cases; k++)
                if (getenv("STRESS_ONLY") && !strstr(cases[k].label, getenv("STRESS_ONLY"))) continue;
                else if (!run_case(ctx, r, env, &sm, &cases[k])) {
                    printf("  ^ BROKEN: %s %s\n", sm.name, cases[k].label);
                    broken++;
                }
            if (!sm.bounds) unbounded++, printf("%s: no error bounds stated in tests/test_stress.c (g_methods)\n", sm.name);
        }
    }
    printf("%d case(s) broken\n", broken);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(shell);
    snell_mesh_destroy(torus);
    snell_mesh_destroy(cube);
    snell_mesh_destroy(sphere);
    snell_ctx_destroy(ctx);
    if (argc > 1 && !named) CHECK(0, "%s: not a method of this build's registry", argv[1]);
    rc = test_finish();
    /* what was not checked is reported as skipped, not passed */
    if (rc == 0 && ran == 0 && not_run > 0) SKIP("%s does not render with this shading", argc > 1 ? argv[1] : "nothing");
    if (rc == 0 && unbounded > 0 && broken == 0) SKIP("%d method(s) without stated error bounds (NaN and coverage checked)", unbounded);
    return rc;
}
