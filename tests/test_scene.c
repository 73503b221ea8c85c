/* SPDX-License-Identifier: MIT */
/* test_scene — a frame of many glass and opaque objects (issue 9): the
 * method registry and the material resolve step; AUTO's choice per object
 * and its reason (an open mesh never gets the cubemap); an explicit method
 * whose preconditions fail renders with a warning in the stats and the log;
 * back-to-front order; what is skipped (outside the view, passthrough,
 * prepared resources and dynamic environments reused); and the image of 8
 * glass + 4 opaque objects against the CPU reference tracer given the same
 * scene, per object class. */
#include "test_util.h"
#include "render/renderer.h" /* to mark a method unavailable, as a device that cannot run it would */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 256
#define H 192
#define NG 8
#define NO 4

/* ------------------------------------------------ registry and materials */

static void test_registry(void)
{
    snell_glass_resolved rg;
    snell_glass_material m;
    snell_method id;
    int i, j;
    CHECK(snell_method_count() >= 2, "count %d", snell_method_count());
    for (i = 0; i < snell_method_count(); i++) {
        const snell_method_info *mi = snell_method_info_at(i);
        CHECK(mi && mi->name && mi->summary && mi->needs, "entry %d incomplete", i);
        if (!mi) continue;
        CHECK(snell_method_info_of(mi->method) == mi, "info_of(%s)", mi->name);
        CHECK(strcmp(snell_method_str(mi->method), mi->name) == 0, "str(%s)", mi->name);
        CHECK(snell_method_from_str(mi->name, &id) == SNELL_OK && id == mi->method, "from_str(%s)", mi->name);
        for (j = 0; j < mi->param_count; j++) {
            const snell_param_info *p = &mi->params[j];
            CHECK(p->def >= p->min && p->def <= p->max, "%s.%s default %d outside %d..%d", mi->name, p->name,
                  p->def, p->min, p->max);
        }
    }
    CHECK(snell_method_info_at(snell_method_count()) == NULL, "past the end");
    CHECK(snell_method_from_str("auto", &id) == SNELL_OK && id == SNELL_METHOD_AUTO, "auto");
    CHECK(snell_method_from_str("nosuch", &id) == SNELL_E_INVALID_ARG, "unknown name accepted");
    CHECK(strcmp(snell_method_str((snell_method)99), "unknown") == 0, "unknown value");

    /* Defaults: the registry's param defaults are what snell_glass_defaults gives. */
    CHECK_OK(snell_glass_defaults(NULL, &rg));
    CHECK(rg.material.ior == 1.5f && rg.material.tint[0] == 1.0f && !rg.absorbs, "ior %g", rg.material.ior);
    CHECK(rg.material.cubemap.iterations == 6 && rg.material.cubemap.max_interfaces == 2 &&
              rg.material.cubemap.face_size == 256 && rg.material.cubemap.encoding == SNELL_NDCUBE_PLAIN &&
              rg.material.cubemap.linear_steps == 0,
          "cubemap defaults %d %d %d %d", rg.material.cubemap.iterations, rg.material.cubemap.max_interfaces,
          rg.material.cubemap.face_size, (int)rg.material.cubemap.encoding);
    {
        const snell_method_info *ci = snell_method_info_of(SNELL_METHOD_CUBEMAP);
        for (j = 0; ci && j < ci->param_count; j++)
            if (strcmp(ci->params[j].name, "iterations") == 0)
                CHECK(ci->params[j].def == rg.material.cubemap.iterations, "iterations default");
    }

    /* glTF attenuation -> per-unit absorption: colour 0.5 after 2 units = ln 2 / 2. */
    memset(&m, 0, sizeof m);
    m.attenuation_color[0] = 0.5f;
    m.attenuation_color[1] = 1.0f;
    m.attenuation_color[2] = 0.25f;
    m.attenuation_distance = 2.0f;
    CHECK_OK(snell_glass_defaults(&m, &rg));
    CHECK(fabsf(rg.absorption[0] - 0.34657359f) < 1e-6f && rg.absorption[1] == 0.0f &&
              fabsf(rg.absorption[2] - 0.69314718f) < 1e-6f && rg.absorbs,
          "absorption %g %g %g", rg.absorption[0], rg.absorption[1], rg.absorption[2]);
    {
        const float sigma[3] = {0.2f, 0.0f, 3.0f};
        memset(&m, 0, sizeof m);
        snell_glass_set_absorption(&m, sigma);
        CHECK_OK(snell_glass_defaults(&m, &rg));
        for (j = 0; j < 3; j++)
            CHECK(fabsf(rg.absorption[j] - sigma[j]) <= 1e-5f * (1.0f + sigma[j]), "round trip %d: %g", j,
                  rg.absorption[j]);
    }

    /* Parameters by name, range-checked; enum values by name. */
    memset(&m, 0, sizeof m);
    CHECK_OK(snell_glass_set_param(&m, SNELL_METHOD_CUBEMAP, "iterations", "9"));
    CHECK_OK(snell_glass_set_param(&m, SNELL_METHOD_CUBEMAP, "encoding", "oct"));
    CHECK(m.cubemap.iterations == 9 && m.cubemap.encoding == SNELL_NDCUBE_OCT, "set_param");
    CHECK(snell_glass_set_param(&m, SNELL_METHOD_CUBEMAP, "iterations", "33") == SNELL_E_INVALID_ARG, "33");
    CHECK(snell_glass_set_param(&m, SNELL_METHOD_CUBEMAP, "iterations", "4x") == SNELL_E_INVALID_ARG, "4x");
    CHECK(snell_glass_set_param(&m, SNELL_METHOD_CUBEMAP, "bogus", "1") == SNELL_E_INVALID_ARG, "bogus");
    CHECK(snell_glass_set_param(&m, SNELL_METHOD_SINGLE, "iterations", "1") == SNELL_E_INVALID_ARG, "single");
    m.cubemap.face_size = 8;
    CHECK(snell_glass_defaults(&m, &rg) == SNELL_E_INVALID_ARG && strstr(snell_last_error(NULL), "face"),
          "face 8 accepted: %s", snell_last_error(NULL));
    memset(&m, 0, sizeof m);
    m.ior = NAN;
    CHECK(snell_glass_defaults(&m, &rg) == SNELL_E_INVALID_ARG, "NaN ior accepted");
    memset(&m, 0, sizeof m);
    m.attenuation_color[0] = 1.5f;
    CHECK(snell_glass_defaults(&m, &rg) == SNELL_E_INVALID_ARG, "attenuation colour 1.5 accepted");
}

/* ------------------------------------------------------------ the scene */

static char g_log[8192];

static void log_fn(snell_log_level level, const char *msg, void *user)
{
    size_t n = strlen(g_log);
    (void)user;
    if (level >= SNELL_LOG_WARN && n + strlen(msg) + 2 < sizeof g_log) {
        strcat(g_log, msg);
        strcat(g_log, "\n");
    }
}

/* The shape with its first `drop` triangles removed: an open mesh. */
static snell_mesh *open_shape(snell_ctx *ctx, snell_shape shape, uint32_t drop)
{
    snell_shape_desc sd = {shape, 32, 16};
    snell_mesh *full = NULL, *open = NULL;
    snell_mesh_desc md;
    if (snell_mesh_create_shape(ctx, &sd, &full) != SNELL_OK) return NULL;
    memset(&md, 0, sizeof md);
    md.positions = snell_mesh_positions(full);
    md.normals = snell_mesh_normals(full);
    md.vertex_count = snell_mesh_vertex_count(full);
    md.indices = snell_mesh_indices(full) + 3 * drop;
    md.triangle_count = snell_mesh_triangle_count(full) - drop;
    snell_mesh_create(ctx, &md, &open);
    snell_mesh_destroy(full);
    return open;
}

/* AUTO's method for a convex mesh (layered where it is built, else the
 * cubemap) and a word its reason holds. */
static snell_method convex_method_of(void)
{
    return snell_build_has("layered") ? SNELL_METHOD_LAYERED : SNELL_METHOD_CUBEMAP;
}

static const char *convex_why_of(void) { return snell_build_has("layered") ? "convex" : "closed"; }

static void place(float m[16], float x, float y, float z, float s)
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = s;
    m[12] = x;
    m[13] = y;
    m[14] = z;
    m[15] = 1.0f;
}

typedef struct class_err {
    double sum;
    long n, within;           /* pixels, pixels within 8/255 on every channel */
} class_err;

static void add_err(class_err *c, const uint8_t *gpu, const float *ref)
{
    int k, ok = 1;
    for (k = 0; k < 3; k++) {
        /* GL's unorm8 conversion of the reference value */
        double r = floor(fmin(fmax(ref[k], 0.0), 1.0) * 255.0 + 0.5), d = fabs(gpu[k] - r);
        c->sum += d / 3.0;
        ok &= d <= 8.0;
    }
    c->n++;
    c->within += ok;
}

/* Renders fd's scene with the reference (isolate_glass: each glass sees the
 * environment and the opaque objects, as the GPU's dynamic environments do)
 * and compares it with the renderer's image of the frame just drawn, per
 * class of pixel by what the reference's view ray hits first. Single-surface
 * objects against one interface and bounding-sphere absorption, cubemap
 * objects against two interfaces and path absorption (their defaults). */
static void compare_to_ref(snell_ctx *ctx, snell_renderer *r, const snell_frame_desc *fd, const char *name,
                           class_err *bg, class_err *op, class_err per[NG])
{
    snell_ref *ref = NULL;
    snell_ref_desc rdsc;
    snell_ref_params rp;
    snell_ref_output ro;
    float *rgb1 = (float *)malloc(sizeof(float) * 3 * W * H), *rgb2 = (float *)malloc(sizeof(float) * 3 * W * H);
    int16_t *obj = (int16_t *)malloc(sizeof(int16_t) * W * H);
    uint8_t *px = (uint8_t *)malloc((size_t)W * H * 4), *refpx = (uint8_t *)malloc((size_t)W * H * 4);
    snell_frame_stats st;
    char file[64];
    long p;
    int k;
    memset(bg, 0, sizeof *bg);
    memset(op, 0, sizeof *op);
    memset(per, 0, NG * sizeof *per);
    CHECK_OK(snell_render(r, fd, &st));
    CHECK_OK(snell_renderer_read_rgba(r, px));
    memset(&rdsc, 0, sizeof rdsc);
    rdsc.glass = fd->glass;
    rdsc.glass_count = fd->glass_count;
    rdsc.opaque = fd->opaque;
    rdsc.opaque_count = fd->opaque_count;
    CHECK_OK(snell_ref_create(ctx, &rdsc, &ref));
    memset(&rp, 0, sizeof rp);
    rp.mode = SNELL_REF_MATCHED;
    rp.env = fd->env;
    rp.camera = fd->camera;
    rp.width = W;
    rp.height = H;
    rp.isolate_glass = 1;
    memset(&ro, 0, sizeof ro);
    rp.max_interfaces = 1;
    rp.absorption_model = SNELL_REF_ABSORB_BOUNDING_SPHERE;
    ro.rgb = rgb1;
    ro.object = obj;
    if (ref) CHECK_OK(snell_ref_render(ref, &rp, &ro));
    rp.max_interfaces = 2;
    rp.absorption_model = SNELL_REF_ABSORB_PATH;
    ro.rgb = rgb2;
    ro.object = NULL;
    if (ref) CHECK_OK(snell_ref_render(ref, &rp, &ro));
    for (p = 0; ref && p < (long)W * H; p++) {
        int o = obj[p];
        /* single: its one surface; the two-sided methods (the cubemap, layered on these convex meshes): two */
        const float *src = o >= 0 && st.glass[o].method_used != SNELL_METHOD_SINGLE ? rgb2 : rgb1;
        const uint8_t *g = px + 4 * p; /* both images: top row first */
        if (o >= 0) add_err(&per[o], g, src + 3 * p);
        else add_err(o == -1 ? bg : op, g, src + 3 * p);
        for (k = 0; k < 3; k++) refpx[4 * p + k] = (uint8_t)floor(fmin(fmax(src[3 * p + k], 0.0), 1.0) * 255.0 + 0.5);
        refpx[4 * p + 3] = 255;
    }
    snprintf(file, sizeof file, "%s.png", name);
    snell_write_png(test_out(file), W, H, px);
    snprintf(file, sizeof file, "%s_ref.png", name);
    snell_write_png(test_out(file), W, H, refpx);
    printf("%s vs reference (mean |d|/255, share within 8/255): background %.3f %.4f (%ld px), opaque %.3f %.4f "
           "(%ld px)\n",
           name, bg->sum / (bg->n ? bg->n : 1), (double)bg->within / (bg->n ? bg->n : 1), bg->n,
           op->sum / (op->n ? op->n : 1), (double)op->within / (op->n ? op->n : 1), op->n);
    for (k = 0; k < NG; k++)
        printf("  glass %d (%s): mean %.3f/255, within 8/255 %.4f of %ld px\n", k, snell_method_str(st.glass[k].method_used),
               per[k].sum / (per[k].n ? per[k].n : 1), (double)per[k].within / (per[k].n ? per[k].n : 1), per[k].n);
    snell_ref_destroy(ref);
    free(rgb1);
    free(rgb2);
    free(obj);
    free(px);
    free(refpx);
}

int main(void)
{
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_mesh *sphere = NULL, *cube = NULL, *torus = NULL, *open = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd = {W, H, SNELL_TARGET_OFFSCREEN, SNELL_OUTPUT_COLOR, SNELL_SHADING_AUTO, 0, 0, SNELL_ENV_LOOKUP_AUTO, 0, 0};
    snell_shape_desc sd = {SNELL_SHAPE_SPHERE, 32, 16};
    snell_glass glass[NG + 1];
    snell_opaque opaque[NO];
    float gm[NG + 1][16], om[NO][16];
    snell_frame_desc fd;
    static snell_frame_stats st, st2;
    int i, order_seen[NG];

    test_registry();

    memset(&cd, 0, sizeof cd);
    cd.log = log_fn;
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK) SKIP("no headless GL context: %s", snell_last_error(NULL));
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &sphere));
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &cube));
    sd.shape = SNELL_SHAPE_TORUS;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &torus));
    open = open_shape(ctx, SNELL_SHAPE_SPHERE, 6);
    CHECK(open != NULL, "open sphere");
    env = test_sky(ctx, 128);
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!sphere || !cube || !torus || !open || !env || !r) return test_finish();

    /* 8 glass objects on two rows at staggered depths; 4 opaque cubes behind. */
    memset(glass, 0, sizeof glass);
    for (i = 0; i < NG; i++) {
        place(gm[i], -1.65f + 1.1f * (i % 4), i < 4 ? 0.6f : -0.6f, -0.4f * (float)((i * 3) % 5), 0.45f);
        glass[i].mesh = sphere;
        glass[i].model = gm[i];
        glass[i].material.ior = 1.3f + 0.05f * (float)i;
        /* compared with the MATCHED model, which has no Fresnel at the exit */
        glass[i].material.cubemap.inner_fresnel = SNELL_INNER_FRESNEL_OFF;
        glass[i].material.layered.inner_fresnel = SNELL_INNER_FRESNEL_OFF;
    }
    glass[1].mesh = cube;                                   /* closed, split at its edges: still closed */
    glass[2].mesh = open;                                   /* AUTO must not take the cubemap */
    glass[3].mesh = open;
    glass[3].material.method = SNELL_METHOD_CUBEMAP;        /* explicit on an open mesh: warning */
    glass[4].material.method = SNELL_METHOD_SINGLE;         /* explicit, adequate or not: no warning */
    glass[5].material.thickness = 0.02f;                    /* thin wall: slab model */
    glass[6].mesh = torus;
    glass[6].material.method = SNELL_METHOD_CUBEMAP;        /* its known limit, checked below (AUTO: oliveira) */
    {
        const float sigma[3] = {0.9f, 0.3f, 0.05f};
        snell_glass_set_absorption(&glass[7].material, sigma);
    }
    for (i = 0; i < NO; i++) {
        place(om[i], -1.8f + 1.2f * (float)i, 0.0f, -3.0f, 0.5f);
        opaque[i].mesh = cube;
        opaque[i].model = om[i];
        opaque[i].color[0] = 0.2f + 0.2f * (float)i;
        opaque[i].color[1] = 0.8f - 0.15f * (float)i;
        opaque[i].color[2] = 0.3f;
    }
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass = glass;
    fd.glass_count = NG;
    fd.opaque = opaque;
    fd.opaque_count = NO;
    fd.camera.distance = 6.0f;
    fd.camera.elevation = 0.15f;
    fd.camera.azimuth = 0.2f;
    fd.dynamic_env_size = 128; /* the static map's own size: the comparison is not about its blur */
    /* the dynamic environments and each object against the reference with
     * isolate_glass: the scene layers (the default here) are test_scene_layers' */
    fd.scene_layers = -1;

    g_log[0] = '\0';
    CHECK_OK(snell_render(r, &fd, &st));
    CHECK(st.glass_count == NG, "glass_count %d", st.glass_count);
    memset(order_seen, 0, sizeof order_seen);
    for (i = 0; i < NG; i++) {
        const snell_object_stats *o = &st.glass[i];
        printf("glass %d: %-7s order %d depth %.2f passes %d prepared %d env %d skipped 0x%x%s: %s\n", i,
               snell_method_str(o->method_used), o->draw_order, o->view_depth, o->passes, o->prepared,
               o->env_updated, o->skipped, o->warning ? " WARNING" : "", o->reason);
        CHECK(o->draw_order >= 0 && o->draw_order < NG, "object %d not drawn", i);
        if (o->draw_order >= 0 && o->draw_order < NG) order_seen[o->draw_order]++;
        CHECK(o->reason[0] != '\0', "object %d has no reason", i);
        CHECK(o->env_updated == 1, "object %d: dynamic environment not rendered on the first frame", i);
    }
    for (i = 0; i < NG; i++) CHECK(order_seen[i] == 1, "draw order %d used %d times", i, order_seen[i]);
    /* Shading: forced, or AUTO's rule on the estimated pixels per front triangle. */
    for (i = 0; i < NG; i++) {
        snell_mesh_analysis an;
        int convex = snell_mesh_analyze(glass[i].mesh, &an) == SNELL_OK && an.convex;
        int want = test_shading() == SNELL_SHADING_SCREEN ||
                   (test_shading() == SNELL_SHADING_AUTO &&
                    st.glass[i].pixels_per_triangle <
                        snell__screen_threshold(snell__device_class_of(snell_ctx_gl_renderer(ctx)),
                                                snell__method_get(st.glass[i].method_used), convex));
        CHECK(st.glass[i].screen_space == want && st.glass[i].pixels_per_triangle > 0.0f,
              "object %d: screen_space %d at %.1f px/triangle", i, st.glass[i].screen_space,
              st.glass[i].pixels_per_triangle);
    }
    /* Back to front: a larger draw order never has a larger view depth. */
    for (i = 0; i < NG; i++) {
        int j;
        for (j = 0; j < NG; j++)
            if (st.glass[j].draw_order > st.glass[i].draw_order)
                CHECK(st.glass[j].view_depth <= st.glass[i].view_depth, "objects %d/%d drawn front to back", i, j);
    }
    /* convex meshes: layered where it is built (measured cheaper and nearer FULL there), else the cubemap */
    CHECK(st.glass[0].method_used == convex_method_of() && strstr(st.glass[0].reason, convex_why_of()), "sphere: %s: %s",
          snell_method_str(st.glass[0].method_used), st.glass[0].reason);
    CHECK(st.glass[1].method_used == convex_method_of(), "cube (split vertices, welded closed): %s",
          st.glass[1].reason);
    CHECK(st.glass[2].method_used == SNELL_METHOD_SINGLE && strstr(st.glass[2].reason, "boundary") &&
              !st.glass[2].warning,
          "open sphere under AUTO: %s: %s", snell_method_str(st.glass[2].method_used), st.glass[2].reason);
    CHECK(st.glass[3].method_used == SNELL_METHOD_CUBEMAP && st.glass[3].warning &&
              strstr(st.glass[3].reason, "closed"),
          "explicit cubemap on an open mesh: warning %d: %s", st.glass[3].warning, st.glass[3].reason);
    CHECK(strstr(g_log, "glass 3") != NULL, "no WARN log for glass 3; log: %s", g_log);
    CHECK(st.glass[4].method_used == SNELL_METHOD_SINGLE && !st.glass[4].warning &&
              (st.glass[4].skipped & SNELL_SKIP_ANALYSIS),
          "explicit single: %s, skipped 0x%x", st.glass[4].reason, st.glass[4].skipped);
    CHECK(st.glass[5].method_used == SNELL_METHOD_SINGLE && strstr(st.glass[5].reason, "thin"),
          "thin wall: %s", st.glass[5].reason);
    CHECK(st.glass[0].prepared == 1 && st.glass[1].prepared == 1, "first frame bakes");
    /* Objects 0 and 7 share the sphere mesh and settings: one bake serves both. */
    CHECK(st.glass[0].prepared + st.glass[7].prepared == 1, "the shared sphere baked %d times",
          st.glass[0].prepared + st.glass[7].prepared);

    /* The same scene again: nothing is prepared or re-rendered. */
    g_log[0] = '\0';
    CHECK_OK(snell_render(r, &fd, &st2));
    for (i = 0; i < NG; i++) {
        CHECK(st2.glass[i].prepared == 0, "object %d prepared again", i);
        CHECK(st2.glass[i].env_updated == 0 && (st2.glass[i].skipped & SNELL_SKIP_ENV_UPDATE),
              "object %d: environment re-rendered", i);
        if (st2.glass[i].method_used == SNELL_METHOD_CUBEMAP)
            CHECK(st2.glass[i].skipped & SNELL_SKIP_PREPARE, "object %d: bake not reported reused", i);
        CHECK(st2.glass[i].method_used == st.glass[i].method_used, "object %d changed method", i);
    }
    CHECK(g_log[0] == '\0', "the warning is logged once, not every frame: %s", g_log);

    /* Against the reference, with and without the opaque objects. */
    {
        class_err bg, op, per[NG];
        compare_to_ref(ctx, r, &fd, "scene_8x4", &bg, &op, per);
        /* Background and opaque pixels: the same shading on both sides. */
        CHECK(bg.n > 1000 && bg.sum / bg.n < 0.25 && bg.within == bg.n, "background %.3f %ld/%ld", bg.sum / bg.n,
              bg.within, bg.n);
        CHECK(op.n > 1000 && op.sum / op.n < 0.25 && op.within == op.n, "opaque %.3f %ld/%ld",
              op.sum / (op.n ? op.n : 1), op.within, op.n);
        /* Glass sees the opaque objects through its dynamic environment, a
         * direction-only lookup from its centre (Unger 4.1): parallax makes
         * the nearby cubes land in the wrong place. Measured (256x192,
         * llvmpipe): mean 4-22/255 per object, 55-93% of pixels within
         * 8/255; bounds at about 1.5x that, to catch regressions. */
        for (i = 0; i < NG; i++) {
            if (i == 3 || i == 6) continue; /* explicit on an open mesh; torus: see below */
            CHECK(per[i].n > 300 && per[i].sum / per[i].n < 33.0 && per[i].within > 0.4 * per[i].n,
                  "glass %d with opaque objects: mean %.2f, %ld/%ld within", i, per[i].sum / (per[i].n ? per[i].n : 1),
                  per[i].within, per[i].n);
        }
        fd.opaque_count = 0;
        CHECK_OK(snell_render(r, &fd, &st));
        compare_to_ref(ctx, r, &fd, "scene_8x0", &bg, &op, per);
        /* Without opaque objects every difference is the method's own
         * (measured 2026-12-04: single 0.05-0.10/255 mean; AUTO's layered on
         * the spheres 0.14-0.23, the cube 1.21 (filtered normals across its
         * edges), where the cubemap, AUTO's pick for them before, measured
         * 0.7-0.8 and 1.8; the explicit cubemap on the open sphere 1.75; torus
         * 31.6-31.8: hidden_fraction 0.48, the cubemap's known limit on
         * non-star-shaped meshes). */
        for (i = 0; i < NG; i++) {
            double mean = per[i].sum / (per[i].n ? per[i].n : 1), within = (double)per[i].within / (per[i].n ? per[i].n : 1);
            printf("without opaque objects, glass %d %s: mean %.3f within %.4f\n", i,
                   snell_method_str(st.glass[i].method_used), mean, within);
            if (st.glass[i].method_used == SNELL_METHOD_SINGLE)
                CHECK(mean < 0.5 && within > 0.99, "glass %d single: mean %.3f within %.4f", i, mean, within);
            else if (i == 6)
                CHECK(mean < 45.0, "torus cubemap: mean %.3f", mean);
            else
                CHECK(mean < 3.0 && within > 0.85, "glass %d %s: mean %.3f within %.4f", i,
                      snell_method_str(st.glass[i].method_used), mean, within);
        }
        fd.opaque_count = NO;
    }

    /* Skips: an object behind the camera and a passthrough one are not drawn. */
    place(gm[NG], 0.0f, 0.0f, 30.0f, 0.5f);
    glass[NG].mesh = sphere;
    glass[NG].model = gm[NG];
    fd.glass_count = NG + 1;
    glass[6].material.ior = 1.0f;
    glass[6].material.tint[0] = glass[6].material.tint[1] = glass[6].material.tint[2] = 1.0f;
    CHECK_OK(snell_render(r, &fd, &st));
    CHECK((st.glass[NG].skipped & SNELL_SKIP_OUTSIDE_VIEW) && st.glass[NG].draw_order == -1 &&
              st.glass[NG].passes == 0,
          "behind the camera: skipped 0x%x order %d", st.glass[NG].skipped, st.glass[NG].draw_order);
    CHECK((st.glass[6].skipped & SNELL_SKIP_PASSTHROUGH) && st.glass[6].draw_order == -1, "passthrough: 0x%x",
          st.glass[6].skipped);

    /* Real meshes (tests/data/real, from Debian's glmark2-data): AUTO never
     * gives the cubemap to the open or non-manifold ones. */
    {
        static const char *const names[3] = {"real/horse.obj", "real/cat.obj", "/usr/share/glmark2/models/bunny.obj"};
        static const char *const expect[3] = {"non-manifold", "boundary", "closed"};
        for (i = 0; i < 3; i++) {
            snell_mesh *m = NULL;
            snell_glass g1;
            snell_frame_desc f1 = fd;
            const char *path = i < 2 ? test_data(names[i]) : names[i];
            if (snell_mesh_load(ctx, path, &m) != SNELL_OK) {
                CHECK(i == 2, "cannot load %s: %s", path, snell_last_error(ctx));
                if (i == 2) printf("bunny check skipped: %s not installed (glmark2-data)\n", path);
                continue;
            }
            CHECK_OK(snell_mesh_normalize(m, 1.0f));
            memset(&g1, 0, sizeof g1);
            g1.mesh = m;
            f1.glass = &g1;
            f1.glass_count = 1;
            f1.opaque_count = 0;
            CHECK_OK(snell_render(r, &f1, &st));
            printf("%s: %s, %s shading at %.1f px/triangle: %s\n", names[i], snell_method_str(st.glass[0].method_used),
                   st.glass[0].screen_space ? "screen" : "forward", st.glass[0].pixels_per_triangle,
                   st.glass[0].reason);
            /* every real mesh here has triangles of a few pixels: AUTO shades it in screen space */
            if (test_shading() == SNELL_SHADING_AUTO && strstr(snell_ctx_gl_renderer(ctx), "llvmpipe"))
                CHECK(st.glass[0].screen_space, "%s shaded forward at %.1f px/triangle", names[i],
                      st.glass[0].pixels_per_triangle);
            CHECK(st.glass[0].method_used == (i == 2 ? SNELL_METHOD_CUBEMAP : SNELL_METHOD_SINGLE) &&
                      strstr(st.glass[0].reason, expect[i]) && !st.glass[0].warning,
                  "%s: %s", names[i], st.glass[0].reason);
            snell_mesh_destroy(m);
        }
    }

    /* A method the device cannot run fails alone: AUTO skips it, an explicit
     * request fails with its status and message. Marked the way a failed
     * creation marks it (renderer.c method_state). */
    {
        snell_renderer *r2 = NULL;
        snell_glass g1;
        snell_frame_desc f1 = fd;
        rd.shading = test_shading();
        CHECK_OK(snell_renderer_create(ctx, &rd, &r2));
        if (r2) {
            r2->method_status[SNELL_METHOD_CUBEMAP] = SNELL_E_UNSUPPORTED;
            snprintf(r2->method_error[SNELL_METHOD_CUBEMAP], sizeof r2->method_error[0], "test: no such device");
            /* layered, AUTO's first pick for the sphere where it is built (unmarked where it is not) */
            r2->method_status[SNELL_METHOD_LAYERED] = SNELL_E_UNSUPPORTED;
            snprintf(r2->method_error[SNELL_METHOD_LAYERED], sizeof r2->method_error[0], "test: no such device");
            /* the image-space method, which AUTO would take next for the sphere */
            r2->method_status[SNELL_METHOD_OLIVEIRA] = SNELL_E_UNSUPPORTED;
            snprintf(r2->method_error[SNELL_METHOD_OLIVEIRA], sizeof r2->method_error[0], "test: no such device");
            memset(&g1, 0, sizeof g1);
            g1.mesh = sphere;
            f1.glass = &g1;
            f1.glass_count = 1;
            CHECK_OK(snell_render(r2, &f1, &st));
            CHECK(st.glass[0].method_used == SNELL_METHOD_SINGLE && strstr(st.glass[0].reason, "unavailable") &&
                      strstr(st.glass[0].reason, "no such device"),
                  "AUTO with layered, the cubemap and oliveira unavailable: %s: %s", snell_method_str(st.glass[0].method_used),
                  st.glass[0].reason);
            g1.material.method = SNELL_METHOD_CUBEMAP;
            CHECK(snell_render(r2, &f1, &st) == SNELL_E_UNSUPPORTED && strstr(snell_last_error(ctx), "no such device"),
                  "explicit unavailable method: %s", snell_last_error(ctx));
            g1.material.method = SNELL_METHOD_SINGLE;
            CHECK_OK(snell_render(r2, &f1, &st));
            snell_renderer_destroy(r2);
        }
    }

    /* Bad scenes fail clearly. */
    fd.glass_count = SNELL_MAX_GLASS + 1;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "too many glass objects");
    fd.glass_count = NG;
    glass[0].mesh = NULL;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "glass 0"),
          "glass without a mesh: %s", snell_last_error(ctx));
    glass[0].mesh = sphere;
    glass[1].material.cubemap.iterations = 99;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "glass 1"),
          "bad cubemap iterations: %s", snell_last_error(ctx));

    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(cube);
    snell_mesh_destroy(torus);
    snell_mesh_destroy(open);
    snell_ctx_destroy(ctx);
    return test_finish();
}
