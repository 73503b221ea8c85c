/* SPDX-License-Identifier: MIT */
/* test_components — the component options (cmake/components.cmake), in every
 * preset: snell_build_has() agrees with what works; a component left out
 * returns SNELL_E_UNSUPPORTED from its API with a message naming its option
 * (and leaves nothing usable behind: no method entry, no shaders); one built
 * in is really there. This test names every component on purpose.
 * snell-test: any-components */
#include "test_util.h"
#include "core/program.h"
#include "snell/snell_2d.h"
#include "snell/snell_metrics.h"
#include "snell/snell_water.h"

#include <string.h>

/* A left-out component's call: UNSUPPORTED and its option in the message. */
static void check_unsupported(const char *what, snell_status st, const snell_ctx *ctx, const char *option)
{
    const char *msg = snell_last_error(ctx);
    CHECK(st == SNELL_E_UNSUPPORTED, "%s: %s, not SNELL_E_UNSUPPORTED", what, snell_status_str(st));
    CHECK(strstr(msg, option) != NULL, "%s: the message names no %s: \"%s\"", what, option, msg);
}

static void check_methods(void)
{
    static const struct {
        snell_method id;
        const char *name, *option, *shader;
    } methods[] = {
        {SNELL_METHOD_WYMAN, "wyman", "SNELL_WITH_WYMAN", "wyman.frag"},
        {SNELL_METHOD_OLIVEIRA, "oliveira", "SNELL_WITH_OLIVEIRA", "oliveira.frag"},
        {SNELL_METHOD_PEEL, "peel", "SNELL_WITH_PEEL", "peel.frag"},
        {SNELL_METHOD_EXACT, "exact", "SNELL_WITH_EXACT", "exact.frag"},
    };
    size_t i;
    CHECK(snell_build_has("single") && snell_build_has("cubemap"), "the kernel floor is always built");
    CHECK(snell_method_info_of(SNELL_METHOD_SINGLE) && snell_method_info_of(SNELL_METHOD_CUBEMAP), "floor entries");
    for (i = 0; i < sizeof methods / sizeof *methods; i++) {
        int built = snell_build_has(methods[i].name);
        snell_method m = SNELL_METHOD_AUTO;
        snell_status st = snell_method_from_str(methods[i].name, &m);
        snell_glass_resolved res;
        snell_glass_material mat;
        memset(&mat, 0, sizeof mat);
        mat.method = methods[i].id;
        printf("%-9s %s\n", methods[i].name, built ? "built in" : "left out");
        CHECK((snell_method_info_of(methods[i].id) != NULL) == built, "%s: registry entry", methods[i].name);
        CHECK((snell__shader_source(methods[i].shader) != NULL) == built, "%s: its shader embedded or not",
              methods[i].name);
        if (built) {
            CHECK(st == SNELL_OK && m == methods[i].id, "%s by name: %s", methods[i].name, snell_status_str(st));
            CHECK_OK(snell_glass_defaults(&mat, &res));
        } else {
            check_unsupported(methods[i].name, st, NULL, methods[i].option);
            check_unsupported("a material asking for it", snell_glass_defaults(&mat, &res), NULL, methods[i].option);
        }
    }
}

static void check_ref(snell_ctx *ctx)
{
    snell_ref *ref = NULL;
    snell_ref_desc d;
    snell_dir_error_desc ed;
    snell_dir_error e;
    snell_status st;
    memset(&d, 0, sizeof d);
    st = snell_ref_create(ctx, &d, &ref);
    if (snell_build_has("ref")) {
        CHECK(st != SNELL_E_UNSUPPORTED, "ref built in: %s", snell_last_error(ctx)); /* an empty scene is refused */
    } else {
        check_unsupported("snell_ref_create", st, ctx, "SNELL_WITH_REF");
        CHECK(ref == NULL, "no reference made");
        memset(&ed, 0, sizeof ed);
        check_unsupported("snell_metrics_dir_error", snell_metrics_dir_error(&ed, &e), NULL, "SNELL_WITH_REF");
    }
    snell_ref_destroy(ref);
}

/* The panels' reference: drawn, or refused naming the option that left it out. */
static void check_panels_ref(void)
{
    static const uint8_t under[4 * 4 * 4];
    uint8_t out[4 * 4 * 4];
    snell_panel p = {.center = {2, 2}, .size = {2, 2}};
    snell_status st = snell_ref_panels(&p, 1, under, 4, 4, 1, out);
    if (snell_build_has("panels") && snell_build_has("ref"))
        CHECK(st == SNELL_OK, "the panels' reference built in: %s", snell_last_error(NULL));
    else
        check_unsupported("snell_ref_panels", st, NULL, snell_build_has("ref") ? "SNELL_WITH_PANELS" : "SNELL_WITH_REF");
}

static void check_lm2d(snell_ctx *ctx)
{
    snell_scene2d *s = NULL;
    snell_status st = snell_scene2d_create(ctx, &s);
    if (snell_build_has("lm2d")) {
        CHECK(st == SNELL_OK && s, "2D scene: %s", snell_last_error(ctx));
    } else {
        check_unsupported("snell_scene2d_create", st, ctx, "SNELL_WITH_LM2D");
        CHECK(snell__shader_source("lightmap2d/lines.frag") == NULL, "the 2D shaders left out");
    }
    snell_scene2d_destroy(s);
}

static void check_water(snell_ctx *ctx)
{
    snell_water *w = NULL;
    snell_water_desc d;
    snell_status st;
    memset(&d, 0, sizeof d);
    d.sim = SNELL_WATER_SIM_CPU;
    st = snell_water_create(ctx, &d, &w);
    if (snell_build_has("water")) {
        CHECK(st == SNELL_OK && w, "water: %s", snell_last_error(ctx));
    } else {
        check_unsupported("snell_water_create", st, ctx, "SNELL_WITH_WATER");
        CHECK(snell__shader_source("water_surface.frag") == NULL, "the water's shaders left out");
    }
    snell_water_destroy(w);
}

static void check_png(void)
{
    static const uint8_t px[4] = {255, 0, 0, 255};
    const char *path = test_out("components.png");
    int w = 0, h = 0;
    uint8_t *back = NULL;
    snell_status st = snell_write_png(path, 1, 1, px);
    if (snell_build_has("png")) {
        CHECK(st == SNELL_OK, "PNG written: %s", snell_last_error(NULL));
        CHECK_OK(snell_image_read(path, &w, &h, &back));
        CHECK(back && w == 1 && h == 1 && back[0] == 255, "PNG read back");
        snell_image_free(back);
    } else {
        check_unsupported("snell_write_png", st, NULL, "SNELL_WITH_PNG");
        check_unsupported("snell_image_decode", snell_image_decode(px, sizeof px, &w, &h, &back), NULL,
                          "SNELL_WITH_PNG");
    }
}

static void check_gltf(void)
{
    snell_mesh *m = NULL;
    snell_status st = snell_mesh_load(NULL, test_data("nodes.gltf"), &m);
    if (snell_build_has("gltf")) {
        CHECK(st == SNELL_OK, "glTF loads: %s", snell_last_error(NULL));
    } else {
        CHECK(st == SNELL_E_UNSUPPORTED && strstr(snell_last_error(NULL), "SNELL_WITH_GLTF"), "glTF left out: %s %s",
              snell_status_str(st), snell_last_error(NULL));
    }
    snell_mesh_destroy(m);
}

/* glmark2's formats (mesh_3ds.c): a .3ds file loads, or is refused naming the option. */
static void check_3ds(void)
{
    snell_mesh *m = NULL;
    snell_status st = snell_mesh_load(NULL, test_data("tetra.3ds"), &m);
    if (snell_build_has("3ds")) {
        CHECK(st == SNELL_OK, ".3ds loads: %s", snell_last_error(NULL));
    } else {
        CHECK(st == SNELL_E_UNSUPPORTED && strstr(snell_last_error(NULL), "SNELL_WITH_3DS"), ".3ds left out: %s %s",
              snell_status_str(st), snell_last_error(NULL));
    }
    snell_mesh_destroy(m);
}

/* The caustics stage: a frame with a light on a receiver draws it, or is refused naming the option. */
static void check_caustics(snell_ctx *ctx)
{
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_mesh *m = NULL;
    snell_shape_desc sd;
    snell_glass g;
    snell_frame_desc f;
    snell_frame_stats st;
    snell_status s;
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &(snell_env_desc){0}, &env));
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &(snell_renderer_desc){.width = 32, .height = 32}, &r));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &m));
    if (env && r && m) {
        test_frame_one(&f, &g, m, env);
        f.camera.distance = 4.0f;
        f.light.type = SNELL_LIGHT_DIRECTIONAL;
        f.light.direction[1] = -1.0f;
        f.receiver.height = -1.5f;
        f.receiver.extent = 3.0f;
        s = snell_render(r, &f, &st);
        if (snell_build_has("caustics")) {
            CHECK(s == SNELL_OK && strstr(st.stages, "caustics"), "caustics: %s, stages \"%s\"", snell_last_error(ctx),
                  st.stages);
        } else {
            check_unsupported("a frame with a light and a receiver", s, ctx, "SNELL_WITH_CAUSTICS");
            CHECK(snell__shader_source("caustics_receiver.frag") == NULL, "the caustics' shaders left out");
            memset(&f.light, 0, sizeof f.light);
            memset(&f.receiver, 0, sizeof f.receiver);
            CHECK_OK_CTX(ctx, snell_render(r, &f, NULL)); /* without them the frame is as in any build */
        }
    }
    snell_mesh_destroy(m);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
}

/* The refine stage: a renderer that asks for it is made, or refused naming the option. */
static void check_refine(snell_ctx *ctx)
{
    snell_renderer *r = NULL;
    snell_status s = snell_renderer_create(ctx, &(snell_renderer_desc){.width = 16, .height = 16, .refine = 4}, &r);
    if (snell_build_has("refine")) {
        CHECK_OK_CTX(ctx, s);
    } else {
        check_unsupported("a renderer with refine", s, ctx, "SNELL_WITH_REFINE");
        CHECK(snell__shader_source("refine_mean.frag") == NULL, "the refine stage's shader left out");
    }
    snell_renderer_destroy(r);
}

/* Glass panels: a frame of panels only (no environment) is drawn, or
 * refused naming the option. */
static void check_panels(snell_ctx *ctx)
{
    snell_renderer *r = NULL;
    snell_panel p;
    snell_frame_desc f;
    snell_frame_stats st;
    snell_status s;
    memset(&p, 0, sizeof p);
    memset(&f, 0, sizeof f);
    p.center[0] = p.center[1] = 8.0f, p.size[0] = p.size[1] = 12.0f;
    f.panels = &p, f.panel_count = 1, f.draw_background = SNELL_BACKGROUND_NONE;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &(snell_renderer_desc){.width = 16, .height = 16}, &r));
    if (!r) return;
    s = snell_render(r, &f, &st);
    if (snell_build_has("panels")) {
        CHECK(s == SNELL_OK && strstr(st.stages, "panels") && st.panels_drawn == 1, "panels: %s, stages \"%s\"",
              snell_last_error(ctx), st.stages);
    } else {
        check_unsupported("a frame with panels", s, ctx, "SNELL_WITH_PANELS");
        CHECK(snell__shader_source("panel.frag") == NULL, "the panels' shaders left out");
    }
    snell_renderer_destroy(r);
}

int main(void)
{
    snell_ctx *ctx = NULL;
    printf("built in: %s\n", snell_build_components());
    CHECK(!snell_build_has("") && !snell_build_has(NULL) && !snell_build_has("sing"), "unknown names are not built");
    check_methods();
    check_png();
    check_gltf();
    check_3ds();
    check_panels_ref();
    ctx = test_ctx();
    if (!ctx) {
        printf("no GL context: the reference, 2D and water checks are not run\n");
        return test_finish();
    }
    check_ref(ctx);
    check_lm2d(ctx);
    check_water(ctx);
    check_caustics(ctx);
    check_refine(ctx);
    check_panels(ctx);
    snell_ctx_destroy(ctx);
    return test_finish();
}
