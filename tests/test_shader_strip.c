/* SPDX-License-Identifier: MIT */
/* test_shader_strip — the shaders the library embeds are stored without
 * comments and spare whitespace (cmake/embed_shaders.cmake): every program
 * still compiles, and renders the same bytes as the sources as written, for
 * every method of this build's registry in both shading paths, glass through
 * glass with opaque objects (the scene layers), dual-paraboloid look-ups and
 * dispersion. The water's and the 2D kernel's programs: test_shader_strip_water. */
#include "shader_strip.h"

#define W 64
#define H 64

static const float k_place[3][16] = {
    {0.6f, 0, 0, 0, 0, 0.6f, 0, 0, 0, 0, 0.6f, 0, -0.7f, 0, 0, 1},
    {0.6f, 0, 0, 0, 0, 0.6f, 0, 0, 0, 0, 0.6f, 0, 0.7f, 0, 0, 1},
    {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, -2.0f, 1},
};

/* variant: method index * 2 + (screen shading); 100 the scene layers; 101
 * dual-paraboloid maps with a dynamic environment; 102 dispersion. */
static snell_status scene(snell_ctx *ctx, int variant, int w, int h, uint8_t *px)
{
    snell_mesh *torus = NULL, *goblet = NULL, *cube = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd = {.width = w, .height = h};
    snell_glass g[2];
    snell_opaque op;
    snell_frame_desc fd;
    snell_status st;
    memset(g, 0, sizeof g);
    memset(&op, 0, sizeof op);
    memset(&fd, 0, sizeof fd);
    st = snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = variant == 102 ? SNELL_SHAPE_PRISM : SNELL_SHAPE_TORUS,
                                                          .segments = 24, .rings = 12},
                                 &torus);
    if (st == SNELL_OK) st = snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_GOBLET, .segments = 24}, &goblet);
    if (st == SNELL_OK) st = snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_CUBE}, &cube);
    if (st == SNELL_OK) st = snell_env_create(ctx, &(snell_env_desc){.face_size = 64}, &env);
    if (variant < 100) rd.shading = variant % 2 ? SNELL_SHADING_SCREEN : SNELL_SHADING_FORWARD;
    if (variant == 101) rd.env_lookup = SNELL_ENV_LOOKUP_DUAL_PARABOLOID;
    if (st == SNELL_OK) st = snell_renderer_create(ctx, &rd, &r);
    g[0].mesh = torus;
    g[0].material.ior = 1.5f;
    g[1].mesh = goblet;
    g[1].material.ior = 1.4f;
    op.mesh = cube;
    fd.env = env;
    fd.glass = g;
    fd.glass_count = 1;
    fd.camera.distance = 3.5f;
    fd.camera.elevation = 0.3f;
    if (variant < 100) {
        g[0].material.method = snell_method_info_at(variant / 2)->method;
    } else if (variant == 100) {
        g[0].model = k_place[0];
        g[1].model = k_place[1];
        op.model = k_place[2];
        fd.glass_count = 2;
        fd.opaque = &op;
        fd.opaque_count = 1;
    } else if (variant == 101) {
        op.model = k_place[2];
        fd.opaque = &op;
        fd.opaque_count = 1;
        fd.scene_layers = -1; /* the dynamic environment, looked up in its paraboloid maps */
    } else {
        g[0].material.dispersion = 1.0f;
        g[0].material.dispersion_model = SNELL_DISPERSION_PER_CHANNEL;
    }
    if (st == SNELL_OK) st = snell_render(r, &fd, NULL);
    if (st == SNELL_OK) st = snell_renderer_read_rgba(r, px);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(cube);
    snell_mesh_destroy(goblet);
    snell_mesh_destroy(torus);
    return st;
}

int main(void)
{
    snell_ctx *probe = test_ctx();
    size_t stripped, readable, stored;
    int i;
    if (!probe) SKIP("no GL context");
    snell_ctx_destroy(probe);
    CHECK(snell__shader_source("object.vert") != NULL, "the embedded table unpacks"); /* before it is read below */
    stripped = strip_table_bytes(snell_shader_files);
    readable = strip_table_bytes(snell_shader_files_readable);
    stored = snell_shader_files_pack.packed ? snell_shader_files_pack.packed_size : stripped;
    printf("embedded shaders: %zu bytes as written, %zu stripped, %zu stored (%s)\n", readable, stripped, stored,
           snell_shader_files_pack.packed ? "packed" : "not packed");
    /* Measured for the full build: stripped 44% of the sources (comments are
     * half of them), packed 9.4% (LZ77 and a range coder; 18% with LZ77 alone),
     * the device preset's 10.5%. */
    CHECK(stripped < readable * 6 / 10, "stripping saved too little: %zu of %zu bytes", stripped, readable);
    CHECK(!snell_shader_files_pack.packed || stored < readable * 15 / 100, "packing saved too little: %zu of %zu bytes",
          stored, readable);
    for (i = 0; i < snell_method_count(); i++) {
        char name[64];
        snprintf(name, sizeof name, "torus, %s, forward", snell_method_info_at(i)->name);
        strip_compare(name, scene, 2 * i, W, H);
        snprintf(name, sizeof name, "torus, %s, screen space", snell_method_info_at(i)->name);
        strip_compare(name, scene, 2 * i + 1, W, H);
    }
    strip_compare("scene layers (2 glass + 1 opaque)", scene, 100, W, H);
    strip_compare("dual-paraboloid, dynamic env", scene, 101, W, H);
    strip_compare("dispersion per channel", scene, 102, W, H);
    return test_finish();
}
