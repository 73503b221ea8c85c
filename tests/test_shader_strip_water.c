/* SPDX-License-Identifier: MIT */
/* test_shader_strip_water — as test_shader_strip, for the programs of the
 * optional components: the water (surface, walls, the GPU simulation's
 * steps and drops; glass in it) and the 2D lightmap's GL lines. Same bytes
 * from the stripped shaders as from the sources as written. */
#include "shader_strip.h"
#include "snell/snell_2d.h"
#include "snell/snell_water.h"

/* variant 0: rippled water (GPU simulation) with a glass sphere in it; 1: the
 * same with the CPU simulation; 2: the 2D lightmap drawn as GL lines. */
static snell_status water_scene(snell_ctx *ctx, int variant, int w, int h, uint8_t *px)
{
    snell_mesh *sphere = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_water *water = NULL;
    snell_glass g;
    snell_frame_desc fd;
    snell_status st;
    float model[16] = {0.4f, 0, 0, 0, 0, 0.4f, 0, 0, 0, 0, 0.4f, 0, 0.2f, 0, 0, 1};
    memset(&g, 0, sizeof g);
    memset(&fd, 0, sizeof fd);
    st = snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE, .segments = 24, .rings = 12}, &sphere);
    if (st == SNELL_OK) st = snell_env_create(ctx, &(snell_env_desc){.face_size = 64}, &env);
    if (st == SNELL_OK)
        st = snell_water_create(ctx,
                                &(snell_water_desc){.grid = 64,
                                                    .sim = variant ? SNELL_WATER_SIM_CPU : SNELL_WATER_SIM_GPU},
                                &water);
    if (st == SNELL_OK) st = snell_water_drop(water, 0.3f, 0.2f, 0.15f, 0.05f);
    if (st == SNELL_OK) st = snell_water_step(water, 0.02f, 10, NULL);
    if (st == SNELL_OK) st = snell_renderer_create(ctx, &(snell_renderer_desc){.width = w, .height = h}, &r);
    g.mesh = sphere;
    g.model = model;
    fd.env = env;
    fd.glass = &g;
    fd.glass_count = 1;
    fd.water = water;
    fd.camera.distance = 3.5f;
    fd.camera.elevation = 0.5f;
    if (st == SNELL_OK) st = snell_render(r, &fd, NULL);
    if (st == SNELL_OK) st = snell_renderer_read_rgba(r, px);
    snell_renderer_destroy(r);
    snell_water_destroy(water);
    snell_env_destroy(env);
    snell_mesh_destroy(sphere);
    return st;
}

static snell_status lightmap_scene(snell_ctx *ctx, int variant, int w, int h, uint8_t *px)
{
    snell_scene2d *scene = NULL;
    snell_lightmap2d *lm = NULL;
    snell_lightmap2d_desc d;
    float view[4];
    int size[2];
    snell_status st = snell_scene2d_load(ctx, test_data("lm2d/shadow.txt"), &scene, view, size);
    (void)variant;
    memset(&d, 0, sizeof d);
    d.width = w;
    d.height = h;
    d.view_min[0] = view[0], d.view_min[1] = view[1], d.view_max[0] = view[2], d.view_max[1] = view[3];
    d.threads = 1;
    d.raster = SNELL_RASTER2D_GL;
    if (st == SNELL_OK) st = snell_lightmap2d_create(ctx, &d, &lm);
    if (st == SNELL_OK) st = snell_lightmap2d_frame(lm, scene, NULL);
    if (st == SNELL_OK) st = snell_lightmap2d_read_rgba(lm, px);
    snell_lightmap2d_destroy(lm);
    snell_scene2d_destroy(scene);
    return st;
}

int main(void)
{
    snell_ctx *probe = test_ctx();
    if (!probe) SKIP("no GL context");
    snell_ctx_destroy(probe);
    strip_compare("water (GPU simulation) + glass", water_scene, 0, 64, 64);
    strip_compare("water (CPU simulation) + glass", water_scene, 1, 64, 64);
    strip_compare("2D lightmap, GL lines", lightmap_scene, 0, 64, 64);
    return test_finish();
}
