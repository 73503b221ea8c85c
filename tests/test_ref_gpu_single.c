/* SPDX-License-Identifier: MIT */
/* test_ref_gpu_single — the reference in MATCHED mode with max_interfaces = 1
 * and the bounding-sphere absorption model must reproduce the GPU
 * single-surface method (SNELL_METHOD_SINGLE, Unger 3.3) pixel for pixel, up
 * to GPU float precision: this pins the shared conventions (camera, pixel
 * centres, y = 0 at the top, model and normal matrices, smooth normals,
 * Fresnel, absorption distance, env filtering). Sphere (scaled, offset) and
 * the bunny (rotated), 99% of pixels within 3/255 on every channel, mean
 * error below 0.5/255 — the tolerance of test_render_single; the rest is the
 * silhouette (coverage decided at a triangle edge) and cube seams. */
#include "test_util.h"
#include "snell/snell_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 192
#define H 160

static void compare(const char *name, snell_ctx *ctx, snell_renderer *r, const snell_mesh *mesh, snell_env *env,
                    const float *model)
{
    static uint8_t gpu[W * H * 4], cpu[W * H * 4];
    static float rgb[W * H * 3];
    static uint8_t hit[W * H];
    snell_frame_desc fd;
    snell_glass g;
    snell_ref *ref = NULL;
    snell_ref_params p;
    const float sigma[3] = {0.3f, 0.1f, 0.05f};
    int i, c, within = 0, hits = 0;
    double sum_err = 0.0;
    char png[64];

    test_frame_one(&fd, &g, mesh, env);
    g.material.method = SNELL_METHOD_SINGLE;
    g.model = model;
    g.material.ior = 1.5f;
    snell_glass_set_absorption(&g.material, sigma);
    g.material.tint[0] = 1.0f;
    g.material.tint[1] = 0.95f;
    g.material.tint[2] = 0.9f;
    fd.camera.azimuth = 0.6f;
    fd.camera.elevation = 0.25f;
    fd.camera.distance = 3.0f;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_rgba(r, gpu));

    CHECK_OK(test_ref_create(ctx, &fd, &ref));
    if (!ref) return;
    test_ref_params(&fd, W, H, 1, &p);
    p.absorption_model = SNELL_REF_ABSORB_BOUNDING_SPHERE;
    CHECK_OK(test_ref_render(ref, &p, rgb, NULL, hit));
    snell_ref_rgb_to_rgba8(rgb, W, H, cpu);

    for (i = 0; i < W * H; i++) {
        int worst = 0;
        hits += hit[i];
        for (c = 0; c < 3; c++) {
            int e = abs(gpu[4 * i + c] - cpu[4 * i + c]);
            if (e > worst) worst = e;
            sum_err += e;
        }
        within += worst <= 3;
    }
    printf("%s: %d glass pixels of %d; %.2f%% within 3/255; mean abs error %.3f/255\n", name, hits, W * H,
           100.0 * within / (W * H), sum_err / (3.0 * W * H));
    CHECK(hits > W * H / 10, "%s: the object must cover a good part of the image (%d)", name, hits);
    CHECK(within >= 0.99 * W * H, "%s: only %d of %d pixels within 3/255", name, within, W * H);
    CHECK(sum_err / (3.0 * W * H) < 0.5, "%s: mean error %.3f/255", name, sum_err / (3.0 * W * H));
    snprintf(png, sizeof png, "ref_gpu_single_%s_gpu.png", name);
    snell_write_png(test_out(png), W, H, gpu);
    snprintf(png, sizeof png, "ref_gpu_single_%s_ref.png", name);
    snell_write_png(test_out(png), W, H, cpu);
    snell_ref_destroy(ref);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_mesh *sphere = NULL, *bunny = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rdesc;
    snell_shape_desc sd;
    snell_env_desc ed;
    float model[16];
    if (!ctx) SKIP("no GL context");
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    memset(&ed, 0, sizeof ed);
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &sphere));
    CHECK_OK(snell_env_create(ctx, &ed, &env));
    memset(&rdesc, 0, sizeof rdesc);
    rdesc.width = W;
    rdesc.height = H;
    rdesc.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rdesc, &r));
    if (!sphere || !env || !r) return test_finish();

    memset(model, 0, sizeof model);
    model[0] = model[5] = model[10] = 0.8f;
    model[12] = 0.1f;
    model[13] = -0.05f;
    model[15] = 1.0f;
    compare("sphere", ctx, r, sphere, env, model);

    if (snell_mesh_load_obj(ctx, "/usr/share/glmark2/models/bunny.obj", &bunny) == SNELL_OK) {
        const double th = 0.9;
        CHECK_OK(snell_mesh_normalize(bunny, 1.0f));
        /* rotation about +Y, scale 1.1 */
        memset(model, 0, sizeof model);
        model[0] = (float)(1.1 * cos(th));
        model[2] = (float)(-1.1 * sin(th));
        model[5] = 1.1f;
        model[8] = (float)(1.1 * sin(th));
        model[10] = (float)(1.1 * cos(th));
        model[15] = 1.0f;
        compare("bunny", ctx, r, bunny, env, model);
        snell_mesh_destroy(bunny);
    } else {
        printf("bunny not available: sphere only\n");
    }
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(sphere);
    snell_ctx_destroy(ctx);
    return test_finish();
}
