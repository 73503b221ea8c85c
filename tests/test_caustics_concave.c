/* SPDX-License-Identifier: MIT */
/* test_caustics_concave.c — caustic photons through concave glass (issue
 * 27): a torus (major radius 1, minor 0.4, IOR 1.5) standing over a plane,
 * its axis along z, under a directional light 16 degrees off vertical: light
 * through the upper ring crosses the hole into the lower ring and out again.
 * The photons follow the mesh's BVH there (caustics_photon.vert; its
 * reference, ref_caustics.c through): entries, TIR, exits and re-entries up
 * to the material's exact.max_interfaces. Checks: the stage says its photons
 * took the BVH; the lit receiver against the reference's light tracing (PSNR), and
 * closer to it than to the reference with one crossing (exact.max_interfaces
 * 2: entry and exit, no re-entry), which itself differs from the full path by
 * a clear margin in the light through glass and in PSNR; the light through
 * glass within a few percent of the reference's; no more light on the plane
 * than it has without the torus, and no more through glass than the torus
 * takes (energy). Then TIR: a cube of the exact method (convex, its
 * material asking for the interfaces) under light 45 degrees off vertical,
 * whose light in through the top is totally reflected at the far side:
 * photons by the BVH against the reference, and the depth maps' path (which
 * drops TIR) clearly off. A spot light through the torus by the BVH: PSNR
 * and the light through glass within 1% of the reference (its photons'
 * solid angle). Writes the maps (caustics_torus_gpu.png, _ref.png,
 * caustics_torus_spot_gpu.png, _ref.png, caustics_cube_tir_gpu.png, _ref.png). */
#include "test_util.h"
#include "core/gl.h"
#include "frame/method.h"
#include "render/caustics.h"
#include "render/renderer.h"
#include "render/stages.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAP 256
#define EXT 2.5f
#define W 160

/* The GPU's light through glass (gpu, 4 floats a texel, less the
 * reference's direct light: ref_rgb - ref_c) into out (3 a texel); its flux. */
static double through_glass(const float *gpu, const float *ref_rgb, const float *ref_c, float *out, double texel)
{
    int i, k;
    for (i = 0; i < MAP * MAP; i++)
        for (k = 0; k < 3; k++) out[3 * i + k] = gpu[4 * i + k] - (ref_rgb[3 * i + k] - ref_c[3 * i + k]);
    return test_light_map_flux(out, 3, MAP * MAP, texel);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_mesh *torus = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_ref *ref = NULL;
    snell_shape_desc sd = {SNELL_SHAPE_TORUS, 96, 48};
    snell_frame_desc fd;
    snell_frame_stats fs;
    snell_glass g;
    snell_glass_material one;
    float model[16] = {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1.6f, 0, 1}; /* standing: its axis along z */
    float *gpu = NULL, *ref_rgb = NULL, *ref_c = NULL, *one_rgb = NULL, *one_c = NULL, *gpu_c = NULL;
    double texel = 2.0 * EXT / MAP, dir[3] = {0.25, -1.0, 0.15}, len;
    int size = 0, k;
    if (!ctx) SKIP("no headless GL context");
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &torus));
    env = test_sky(ctx, 32);
    r = test_renderer(ctx, W, W);
    gpu = (float *)calloc((size_t)MAP * MAP * 4, sizeof(float));
    gpu_c = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    ref_rgb = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    ref_c = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    one_rgb = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    one_c = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    if (!torus || !env || !r || !gpu || !gpu_c || !ref_rgb || !ref_c || !one_rgb || !one_c) return test_finish();

    memset(&g, 0, sizeof g);
    g.mesh = torus;
    g.model = model;
    g.material.ior = 1.5f;
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass = &g;
    fd.glass_count = 1;
    fd.camera.azimuth = 0.4f, fd.camera.elevation = 0.7f, fd.camera.distance = 6.0f, fd.camera.fov_y = 0.8f;
    fd.light.type = SNELL_LIGHT_DIRECTIONAL;
    len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (k = 0; k < 3; k++) fd.light.direction[k] = (float)(dir[k] /= len);
    fd.receiver.height = 0.0f;
    fd.receiver.center[0] = 0.2f;
    fd.receiver.extent = EXT;
    fd.receiver.map_size = MAP;

    /* the GPU's light map; its photons took the BVH */
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    printf("frame: %s\n", fs.caustics_reason);
    CHECK(strstr(fs.caustics_reason, "paths: 1 BVH, 0 depth maps") != NULL, "the torus's photons: %s", fs.caustics_reason);
    CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &size));
    CHECK(size == MAP, "map size %d", size);
    {
        uint8_t *img = (uint8_t *)malloc((size_t)W * W * 4);
        if (img && snell_renderer_read_rgba(r, img) == SNELL_OK) snell_write_png(test_out("caustics_torus_view.png"), W, W, img);
        free(img);
    }

    /* the reference: the full path (the material's default exact.max_interfaces), then one crossing */
    CHECK_OK(test_ref_create(NULL, &fd, &ref));
    if (!ref) return test_finish();
    CHECK_OK(snell_ref_receiver_render(ref, &fd.light, &fd.receiver, 1024, 4, ref_rgb, ref_c));
    one = g.material;
    one.exact.max_interfaces = 2; /* in and out once, as the depth maps' photons */
    CHECK_OK(snell_ref_set_material(ref, 0, &one));
    CHECK_OK(snell_ref_receiver_render(ref, &fd.light, &fd.receiver, 1024, 4, one_rgb, one_c));
    test_write_light_map("caustics_torus_gpu.png", gpu, 4, MAP, 0.8f);
    test_write_light_map("caustics_torus_ref.png", ref_rgb, 3, MAP, 0.8f);
    test_write_light_map("caustics_torus_ref_one.png", one_rgb, 3, MAP, 0.8f);

    {
        /* the light through glass: the GPU's map less its direct part (the reference's direct light) */
        double e_gpu, e_ref = test_light_map_flux(ref_c, 3, MAP * MAP, texel), e_one = test_light_map_flux(one_c, 3, MAP * MAP, texel), e_all = test_light_map_flux(gpu, 4, MAP * MAP, texel);
        double e_free = -dir[1] * (2.0 * EXT) * (2.0 * EXT), db, db_one, db_ref_one;
        e_gpu = through_glass(gpu, ref_rgb, ref_c, gpu_c, texel);
        db = test_light_map_psnr(gpu, 4, ref_rgb, MAP * MAP, 0.8f);
        db_one = test_light_map_psnr(gpu, 4, one_rgb, MAP * MAP, 0.8f);
        db_ref_one = test_light_map_psnr(ref_rgb, 3, one_rgb, MAP * MAP, 0.8f);
        printf("light through glass on the plane: GPU %.4f, reference %.4f (%+.2f%%), reference with one crossing "
               "%.4f (%+.2f%%)\n", e_gpu, e_ref, 100.0 * (e_gpu / e_ref - 1.0), e_one, 100.0 * (e_one / e_ref - 1.0));
        printf("all light on the plane: GPU %.4f, without the torus %.4f\n", e_all, e_free);
        printf("receiver PSNR (albedo 0.8, clamped): GPU vs reference %.2f dB, GPU vs one-crossing reference %.2f dB, "
               "reference vs its one crossing %.2f dB\n", db, db_one, db_ref_one);
        /* (a) measured 36.6 dB (256^2 photons against the reference's 1024^2:
         * the GPU's sparse photons' moire where the ring spreads them) */
        CHECK(db >= 32.0, "GPU against the reference: %.2f dB", db);
        /* (b) one crossing (the cap at the first exit: the photon then
         * passes the lower ring unbent, as it passes g in both models) puts
         * +24% of light through glass and a different caustic on the plane:
         * 23.2 dB from the full path (the GPU 23.0), 13.7 dB below the
         * GPU's match; a GPU falling back to one crossing fails here (the
         * depth maps' one crossing: 22.7 dB, -14% light) */
        CHECK(db_ref_one <= 28.0 && fabs(e_one / e_ref - 1.0) >= 0.1,
              "the reference's one crossing is %.2f dB and %+.1f%% from its full path", db_ref_one,
              100.0 * (e_one / e_ref - 1.0));
        CHECK(db - db_one >= 6.0, "GPU %.2f dB from the full path, %.2f dB from one crossing", db, db_one);
        /* (c) measured +0.05%; glass adds no light: all of it on the plane at
         * most what the plane has without the torus (22.8 against 24.0) */
        CHECK(fabs(e_gpu - e_ref) <= 0.03 * e_ref + test_light_map_excess(ctx, ref_rgb, MAP * MAP, texel),
              "light through glass: GPU %.4f, reference %.4f (%.4f above an RGB10_A2 map's range)", e_gpu, e_ref,
              test_light_map_excess(ctx, ref_rgb, MAP * MAP, texel));
        CHECK(e_all <= e_free && test_light_map_flux(ref_rgb, 3, MAP * MAP, texel) <= e_free, "all light %.4f (reference %.4f), %.4f without",
              e_all, test_light_map_flux(ref_rgb, 3, MAP * MAP, texel), e_free);
        /* and the light through glass is no more than the light the torus takes */
        CHECK(e_gpu <= e_free - (e_all - e_gpu), "through glass %.4f, the torus's shadow takes %.4f", e_gpu,
              e_free - (e_all - e_gpu));
    }
    {
        /* the depth maps' one crossing (the stage's only path before) is
         * wrong here: measured 22.7 dB, -14% light through glass */
        double db_maps, e_maps;
        snell__renderer_caustics(r)->maps_only = 1;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
        CHECK(strstr(fs.caustics_reason, "paths: 0 BVH, 1 depth maps") != NULL, "maps only: %s", fs.caustics_reason);
        CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &size));
        db_maps = test_light_map_psnr(gpu, 4, ref_rgb, MAP * MAP, 0.8f);
        e_maps = through_glass(gpu, ref_rgb, ref_c, gpu_c, texel);
        printf("depth maps' one crossing: %.2f dB from the reference, light through glass %+.2f%%\n", db_maps,
               100.0 * (e_maps / test_light_map_flux(ref_c, 3, MAP * MAP, texel) - 1.0));
        CHECK(db_maps <= 28.0 && fabs(e_maps / test_light_map_flux(ref_c, 3, MAP * MAP, texel) - 1.0) >= 0.08, "depth maps: %.2f dB", db_maps);
        snell__renderer_caustics(r)->maps_only = 0;
    }
    {
        /* the BVH is the mesh's (mesh/bvh_gpu.h), made once: the light
         * moved (the map made again), the same BVH, f32 nodes */
        const void *data[2] = {NULL, NULL};
        int pass;
        for (pass = 0; pass < 2; pass++) {
            fd.light.direction[0] += 0.01f;
            CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
            CHECK(!fs.caustics_reused, "light moved: %s", fs.caustics_reason);
            data[pass] = torus->gpu_bvh[0];
        }
        CHECK(data[0] && data[0] == data[1], "the torus's BVH %p then %p", data[0], data[1]);
    }
    {
        /* A spot light (a perspective light frame, the flux per photon
         * falling with distance squared and the cone) through the same
         * torus by the BVH: 5 above the plane, off to the side so that its
         * light crosses the ring slanted, the cone covering the whole torus */
        snell_frame_desc fs_spot = fd;
        snell_ref *ref_spot = NULL;
        double db_s, e_s, e_sref;
        fs_spot.light.type = SNELL_LIGHT_SPOT;
        fs_spot.light.position[0] = 1.2f, fs_spot.light.position[1] = 5.0f, fs_spot.light.position[2] = 0.5f;
        fs_spot.light.direction[0] = -0.35f, fs_spot.light.direction[1] = -1.0f, fs_spot.light.direction[2] = -0.15f;
        fs_spot.light.spot_angle = 0.7f;
        /* irradiance falls as 1 / distance^2: about the directional light's on the plane */
        fs_spot.light.color[0] = fs_spot.light.color[1] = fs_spot.light.color[2] = 25.0f;
        fs_spot.light.photons = 512; /* the grid holds the bounding sphere, which a near light sees wide */
        CHECK_OK(test_ref_create(NULL, &fs_spot, &ref_spot));
        if (ref_spot) {
            CHECK_OK(snell_ref_receiver_render(ref_spot, &fs_spot.light, &fs_spot.receiver, 1024, 4, ref_rgb, ref_c));
            CHECK_OK_CTX(ctx, snell_render(r, &fs_spot, &fs));
            CHECK(strstr(fs.caustics_reason, "paths: 1 BVH, 0 depth maps") != NULL, "spot: %s", fs.caustics_reason);
            CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &size));
            test_write_light_map("caustics_torus_spot_gpu.png", gpu, 4, MAP, 0.8f);
            test_write_light_map("caustics_torus_spot_ref.png", ref_rgb, 3, MAP, 0.8f);
            db_s = test_light_map_psnr(gpu, 4, ref_rgb, MAP * MAP, 0.8f);
            e_s = through_glass(gpu, ref_rgb, ref_c, gpu_c, texel);
            e_sref = test_light_map_flux(ref_c, 3, MAP * MAP, texel);
            printf("spot light through the torus: the BVH %.2f dB from the reference, light through glass %.4f "
                   "against %.4f (%+.2f%%)\n", db_s, e_s, e_sref, 100.0 * (e_s / e_sref - 1.0));
            /* measured 38.6 dB, +0.13% (512^2 photons); a photon's solid angle
             * without the cos^3 (cos^2) gives +2.0%, and 256^2 photons' moire 31.8 dB */
            CHECK(db_s >= 34.0 && fabs(e_s - e_sref) <= 0.01 * e_sref + test_light_map_excess(ctx, ref_rgb, MAP * MAP, texel),
                  "spot: %.2f dB, %.4f against %.4f (%.4f above an RGB10_A2 map's range)", db_s, e_s, e_sref,
                  test_light_map_excess(ctx, ref_rgb, MAP * MAP, texel));
        }
        snell_ref_destroy(ref_spot);
    }
    {
        /* TIR: a cube (convex) of the exact method, whose interfaces ask for
         * the whole path, under light 45 degrees off vertical: light in
         * through the top meets the far side at 61.9 degrees, past the
         * critical 41.8, and is reflected down and out through the bottom
         * (the depth maps' path drops it). Measured: the BVH 42.9 dB from
         * the reference, light through glass +0.5%; the depth maps 18.4 dB,
         * -36%; the BVH's path dropping TIR as the maps do: 18.5 dB, -36% */
        snell_shape_desc cd = {SNELL_SHAPE_CUBE, 0, 0};
        snell_mesh *cube = NULL;
        snell_ref *ref_cube = NULL;
        snell_glass gc = g;
        snell_frame_desc fc = fd;
        float cube_model[16] = {0.8f, 0, 0, 0, 0, 0.8f, 0, 0, 0, 0, 0.8f, 0, 0, 1.2f, 0, 1};
        double db_c, e_c, e_ref, db_m, e_m;
        CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &cd, &cube));
        gc.mesh = cube, gc.model = cube_model;
        gc.material.method = SNELL_METHOD_EXACT;
        fc.glass = &gc;
        fc.light.direction[0] = 1.0f, fc.light.direction[1] = -1.0f, fc.light.direction[2] = 0.0f;
        fc.receiver.center[0] = 1.2f, fc.receiver.center[1] = 0.0f;
        CHECK_OK(test_ref_create(NULL, &fc, &ref_cube));
        if (cube && ref_cube) {
            CHECK_OK(snell_ref_receiver_render(ref_cube, &fc.light, &fc.receiver, 1024, 4, ref_rgb, ref_c));
            e_ref = test_light_map_flux(ref_c, 3, MAP * MAP, texel);
            CHECK_OK_CTX(ctx, snell_render(r, &fc, &fs));
            CHECK(strstr(fs.caustics_reason, "paths: 1 BVH, 0 depth maps") != NULL, "the cube's: %s", fs.caustics_reason);
            CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &size));
            test_write_light_map("caustics_cube_tir_gpu.png", gpu, 4, MAP, 0.8f);
            test_write_light_map("caustics_cube_tir_ref.png", ref_rgb, 3, MAP, 0.8f);
            db_c = test_light_map_psnr(gpu, 4, ref_rgb, MAP * MAP, 0.8f);
            e_c = through_glass(gpu, ref_rgb, ref_c, gpu_c, texel);
            snell__renderer_caustics(r)->maps_only = 1;
            CHECK_OK_CTX(ctx, snell_render(r, &fc, &fs));
            CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &size));
            snell__renderer_caustics(r)->maps_only = 0;
            db_m = test_light_map_psnr(gpu, 4, ref_rgb, MAP * MAP, 0.8f);
            e_m = through_glass(gpu, ref_rgb, ref_c, gpu_c, texel);
            printf("cube, TIR: the BVH %.2f dB from the reference, light through glass %+.2f%%; the depth maps %.2f dB, "
                   "%+.2f%%\n", db_c, 100.0 * (e_c / e_ref - 1.0), db_m, 100.0 * (e_m / e_ref - 1.0));
            CHECK(db_c >= 32.0 && fabs(e_c / e_ref - 1.0) <= 0.03, "the cube by the BVH: %.2f dB, %.4f against %.4f",
                  db_c, e_c, e_ref);
            CHECK(db_m <= 28.0 && e_m / e_ref - 1.0 <= -0.1, "the cube by the depth maps: %.2f dB, %.4f", db_m, e_m);
        }
        snell_ref_destroy(ref_cube);
        snell_mesh_destroy(cube);
    }
    snell_ref_destroy(ref);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(torus);
    free(gpu), free(gpu_c), free(ref_rgb), free(ref_c), free(one_rgb), free(one_c);
    snell_ctx_destroy(ctx);
    return test_finish();
}
