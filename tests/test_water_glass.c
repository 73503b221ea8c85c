/* SPDX-License-Identifier: MIT */
/* test_water_glass.c — glass objects in the water (issue 17): a glass sphere
 * half under a rippled surface, another wholly under it and an opaque cube
 * on the floor, rendered by the library and by the reference
 * (snell_ref_water_render with the glass and the opaque objects, every
 * medium traced: the water's index around the glass under the surface).
 *
 * What must hold, with bounds from measurement:
 * - the water sees the glass through the scene layers (frame stats), and
 *   the glass's kernel sees the water (its program's SNELL_WATER variant);
 * - over the pixels where the glass changes the reference image (the glass
 *   class: the reference with the glass against the reference without it),
 *   the frame is far closer to the reference than the frame that draws the
 *   glass without the water seeing it (scene_layers -1, the glass then
 *   depth-tested against the water as before) or without the water in its
 *   exit rays;
 * - the whole frame is close to the reference;
 * - every kernel (single, cubemap, wyman, oliveira, peel, exact) sees the
 *   water and is seen through it, within its own model's error.
 * Both with the water simulated on the CPU and on the GPU. Writes
 * water_glass_{cpu,gpu}_{gpu,ref,nolayers}.png and water_glass_cpu_METHOD.png. */
#include "snell/snell_metrics.h"
#include "snell/snell_water.h"
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef W
#define W 256
#endif
#ifndef H
#define H 256
#endif

static void render(snell_ctx *ctx, const snell_frame_desc *fd, uint8_t *px, snell_frame_stats *fs)
{
    snell_renderer *r = NULL;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &(snell_renderer_desc){.width = W, .height = H}, &r));
    CHECK_OK_CTX(ctx, snell_render(r, fd, fs));
    CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, px));
    snell_renderer_destroy(r);
}

static void reference(snell_ctx *ctx, snell_water *w, const snell_frame_desc *fd, int with_glass, uint8_t *px)
{
    snell_ref *objects = NULL;
    snell_ref_params p;
    snell_ref_output out;
    float *rgb = (float *)malloc(W * H * 3 * sizeof(float));
    CHECK(rgb != NULL, "memory");
    CHECK_OK_CTX(ctx, snell_ref_create(ctx, &(snell_ref_desc){.glass = with_glass ? fd->glass : NULL,
                                                              .glass_count = with_glass ? fd->glass_count : 0,
                                                              .opaque = fd->opaque, .opaque_count = fd->opaque_count},
                                       &objects));
    memset(&p, 0, sizeof p);
    p.env = fd->env;
    p.camera = fd->camera;
    p.width = W;
    p.height = H;
    memset(&out, 0, sizeof out);
    out.rgb = rgb;
    CHECK_OK_CTX(ctx, snell_ref_water_render(w, objects, &p, &out));
    snell_ref_rgb_to_rgba8(rgb, W, H, px);
    snell_ref_destroy(objects);
    free(rgb);
}

static snell_image_error error(const uint8_t *test, const uint8_t *ref, const uint8_t *mask)
{
    snell_image_error e;
    CHECK_OK(snell_metrics_image_error(test, ref, W, H, mask, &e));
    return e;
}

/* The scene with the water simulated on the CPU or the GPU (the kernels then
 * read the heights from its RG32UI state: their SNELL_WATER_STATE_UINT variant). */
static void water_case(snell_ctx *ctx, const snell_env *env, snell_water_sim sim, const char *name)
{
    snell_water *w = NULL;
    snell_mesh *sphere = NULL, *cube = NULL;
    snell_glass glass[2];
    snell_opaque opaque;
    snell_frame_desc fd;
    snell_frame_stats fs;
    /* a sphere through the surface, a smaller one under it, a cube on the floor */
    float m0[16] = {0.35f, 0, 0, 0, 0, 0.35f, 0, 0, 0, 0, 0.35f, 0, -0.1f, -0.2f, 0.05f, 1};
    float m1[16] = {0.2f, 0, 0, 0, 0, 0.2f, 0, 0, 0, 0, 0.2f, 0, 0.5f, -0.5f, -0.35f, 1};
    float m2[16] = {0.15f, 0, 0, 0, 0, 0.15f, 0, 0, 0, 0, 0.15f, 0, -0.5f, -0.65f, -0.5f, 1};
    uint8_t *gpu = (uint8_t *)malloc(W * H * 4), *ref = (uint8_t *)malloc(W * H * 4);
    uint8_t *ref_bare = (uint8_t *)malloc(W * H * 4), *off = (uint8_t *)malloc(W * H * 4), *mask = (uint8_t *)malloc(W * H);
    snell_image_error e_on, e_off, e_all, e_bare;
    long i, glass_px = 0;
    char path[256];
    CHECK(gpu && ref && ref_bare && off && mask, "memory");
    CHECK_OK_CTX(ctx, snell_water_create(ctx, &(snell_water_desc){.grid = 128, .sim = sim}, &w));
    CHECK_OK_CTX(ctx, snell_water_drop(w, 0.3f, -0.2f, 0.15f, -0.03f));
    CHECK_OK_CTX(ctx, snell_water_drop(w, -0.5f, 0.4f, 0.1f, 0.02f));
    CHECK_OK_CTX(ctx, snell_water_step(w, 0.0f, 60, NULL));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE}, &sphere));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_CUBE}, &cube));
    memset(glass, 0, sizeof glass);
    glass[0].mesh = glass[1].mesh = sphere;
    glass[0].model = m0;
    glass[1].model = m1;
    glass[0].material.ior = glass[1].material.ior = 1.5f;
    memset(&opaque, 0, sizeof opaque);
    opaque.mesh = cube;
    opaque.model = m2;
    opaque.color[0] = 0.9f, opaque.color[1] = 0.35f, opaque.color[2] = 0.3f;
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.water = w;
    fd.glass = glass;
    fd.glass_count = 2;
    fd.opaque = &opaque;
    fd.opaque_count = 1;
    fd.camera.azimuth = 0.5f;
    fd.camera.elevation = 0.6f;
    fd.camera.distance = 3.0f;
    fd.camera.target[1] = -0.2f;

    render(ctx, &fd, gpu, &fs);
    printf("methods: %s, %s\n", snell_method_str(fs.glass[0].method_used), snell_method_str(fs.glass[1].method_used));
    CHECK(fs.water_drawn && fs.water_layers && fs.water_objects, "the water's rays march the scene layers (%d %d)",
          fs.water_layers, fs.water_objects);
    CHECK(fs.scene_layers >= 2, "scene layers peeled: %d", fs.scene_layers);
    CHECK(fs.glass[0].sees_water && fs.glass[1].sees_water, "the glass kernels see the water");
    fd.scene_layers = -1;
    render(ctx, &fd, off, &fs);
    CHECK(!fs.water_layers, "scene_layers -1: the water does not march them");
    fd.scene_layers = 0;
    reference(ctx, w, &fd, 1, ref);
    reference(ctx, w, &fd, 0, ref_bare);
    for (i = 0; i < (long)W * H; i++) {
        int k, d = 0;
        for (k = 0; k < 3; k++) {
            int c = abs((int)ref[4 * i + k] - (int)ref_bare[4 * i + k]);
            if (c > d) d = c;
        }
        mask[i] = d > 8;
        glass_px += mask[i];
    }
    e_on = error(gpu, ref, mask);
    e_off = error(off, ref, mask);
    e_bare = error(ref_bare, ref, mask);
    e_all = error(gpu, ref, NULL);
    printf("%s: glass class (%ld pixels the glass changes in the reference): PSNR %.2f dB with the water seeing it, "
           "%.2f dB without (scene_layers -1), %.2f dB for no glass at all; whole frame %.2f dB (%ld pixels off "
           "by > 3)\n", name, glass_px, e_on.psnr_db, e_off.psnr_db, e_bare.psnr_db, e_all.psnr_db, e_all.above_3);
    snprintf(path, sizeof path, "%s_gpu.png", name);
    snell_write_png(test_out(path), W, H, gpu);
    snprintf(path, sizeof path, "%s_nolayers.png", name);
    snell_write_png(test_out(path), W, H, off);
    snprintf(path, sizeof path, "%s_ref.png", name);
    snell_write_png(test_out(path), W, H, ref);
    CHECK(glass_px > W * H / 40, "the glass changes %ld pixels of the reference", glass_px);
    /* Measured (256x256, llvmpipe): 21.50 dB over the glass class, 9.75
     * without the water seeing the glass, 10.78 for no glass drawn; whole
     * frame 32.95 dB (21.10 and 32.55 before the kernels' reflections were
     * marched too; the breakages below were measured then). Exit rays under the water left bent for air (no
     * re-bend with the layers' normal) gave 15.81 and 27.77; the kernels
     * not seeing the water (their exit rays to the environment) 14.59 and
     * 26.69; the single kernel in place of the cubemap one 12.58. Bounds 18 dB, and 8 dB over
     * the frame without it, and 29 dB for the whole frame. */
    CHECK(e_on.psnr_db >= 18.0, "glass in the water: %.2f dB below 18", e_on.psnr_db);
    CHECK(e_on.psnr_db >= e_off.psnr_db + 8.0, "the water seeing the glass gains %.2f dB, not 8",
          e_on.psnr_db - e_off.psnr_db);
    CHECK(e_all.psnr_db >= 29.0, "whole frame %.2f dB below 29", e_all.psnr_db);
    if (sim == SNELL_WATER_SIM_CPU) {
        /* Every kernel sees the water and is seen through it (each has the
         * SNELL_WATER variant and calls snell_exit), each within its own
         * model's error of the reference over the glass class. */
        int m;
        for (m = 0; m < snell_method_count(); m++) { /* every method of the registry */
            const snell_method_info *info = snell_method_info_at(m);
            snell_image_error e;
            glass[0].material.method = glass[1].material.method = info->method;
            render(ctx, &fd, gpu, &fs);
            e = error(gpu, ref, mask);
            printf("%s, %s: glass class %.2f dB\n", name, info->name, e.psnr_db);
            snprintf(path, sizeof path, "%s_%s.png", name, info->name);
            snell_write_png(test_out(path), W, H, gpu);
            CHECK(fs.glass[0].method_used == info->method && fs.glass[0].sees_water && fs.water_layers,
                  "%s drew the glass and sees the water", info->name);
            /* Measured: single 12.67 dB (one surface: its exit ray leaves the
             * front, so nothing is re-bent), cubemap 21.50, wyman 19.44,
             * oliveira 20.97, layered 21.50, peel 21.52, exact 21.70. Bounds:
             * the two-sided ones 18 dB, single (its registry model: one
             * interface) 2 dB over the water not seeing the glass. */
            CHECK(e.psnr_db >= (info->ref_interfaces == 1 ? e_off.psnr_db + 2.0 : 18.0),
                  "%s: glass class %.2f dB (the water not seeing the glass: %.2f)", info->name, e.psnr_db,
                  e_off.psnr_db);
        }
        glass[0].material.method = glass[1].material.method = SNELL_METHOD_AUTO;
    }

    snell_mesh_destroy(sphere);
    snell_mesh_destroy(cube);
    snell_water_destroy(w);
    free(gpu);
    free(ref);
    free(ref_bare);
    free(off);
    free(mask);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL;
    if (!ctx) return 1;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &(snell_env_desc){.face_size = 256}, &env));
    water_case(ctx, env, SNELL_WATER_SIM_CPU, "water_glass_cpu");
    water_case(ctx, env, SNELL_WATER_SIM_GPU, "water_glass_gpu");
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
