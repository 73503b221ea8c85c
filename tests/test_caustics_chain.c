/* test_caustics_chain.c — light through two glass objects in sequence
 * (issue 27): a glass sphere (radius 0.45, IOR 1.5) above a larger tinted
 * one (radius 0.6, IOR 1.5, tint 0.6, 0.85, 1), over the receiver plane,
 * their beams overlapping in the light's view. The photons of each count
 * only where the light meets it first and go on through the other (the
 * chain path, render/caustics.c; its reference ref_caustics.c chain). Checks,
 * for a directional and a spot light: the stage says both casters took the
 * chain; GPU against the reference (PSNR) and the light through glass
 * within a few percent; no more light on the plane than without the glass
 * (each ray counted once); the casters each alone (the path before the
 * chain, maps_only) clearly off in both. Then the opaque receivers' light
 * frame: the pair over an opaque box, the GPU's caustic map against the
 * reference's (snell_ref_set_light). Then side by side under a light from
 * above (beams apart): no chain, each its own path. Writes the maps
 * (caustics_chain_gpu.png, _ref.png, _alone.png, caustics_chain_spot_*.png). */
#include "test_util.h"
#include "render/renderer.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAP 256
#define EXT 2.5f
#define W 96

/* The flux of a map's green channel over the plane (stride floats a texel). */
static double flux(const float *v, int stride, double texel)
{
    double e = 0;
    int i;
    for (i = 0; i < MAP * MAP; i++) e += v[i * stride + 1] * texel * texel;
    return e;
}

/* The GPU's light through glass: its map less the reference's direct light (ref_rgb - ref_c). */
static double through_glass(const float *gpu, const float *ref_rgb, const float *ref_c, double texel)
{
    double e = 0;
    int i;
    for (i = 0; i < MAP * MAP; i++) e += (gpu[4 * i + 1] - (ref_rgb[3 * i + 1] - ref_c[3 * i + 1])) * texel * texel;
    return e;
}

typedef struct result {
    double db, e_gpu, e_ref, e_all, db_alone, e_alone;
} result;

/* fd's light map by the GPU (the chain) and the reference, then the casters
 * each alone (maps_only: the path before the chain). */
static void run(snell_ctx *ctx, snell_renderer *r, const snell_frame_desc *fd, const char *name, float *gpu,
                float *ref_rgb, float *ref_c, result *out)
{
    snell_frame_stats fs;
    snell_ref *ref = NULL;
    double texel = 2.0 * EXT / MAP;
    char file[64];
    int size = 0;
    memset(out, 0, sizeof *out);
    CHECK_OK_CTX(ctx, snell_render(r, fd, &fs));
    printf("%s: %s\n", name, fs.caustics_reason);
    CHECK(strstr(fs.caustics_reason, "paths: 0 BVH, 0 depth maps, 2 chained (beams overlap: 1 group)") != NULL,
          "%s: %s", name, fs.caustics_reason);
    CHECK_OK_CTX(ctx, snell__caustics_read(ctx, &r->caustics, gpu, &size));
    CHECK_OK(test_ref_create(NULL, fd, &ref));
    if (!ref) return;
    CHECK_OK(snell_ref_receiver_render(ref, &fd->light, &fd->receiver, 1024, 4, ref_rgb, ref_c));
    snell_ref_destroy(ref);
    snprintf(file, sizeof file, "%s_gpu.png", name);
    test_write_light_map(file, gpu, 4, MAP, 0.8f);
    snprintf(file, sizeof file, "%s_ref.png", name);
    test_write_light_map(file, ref_rgb, 3, MAP, 0.8f);
    out->db = test_light_map_psnr(gpu, 4, ref_rgb, MAP * MAP, 0.8f);
    out->e_gpu = through_glass(gpu, ref_rgb, ref_c, texel);
    out->e_ref = flux(ref_c, 3, texel);
    out->e_all = flux(gpu, 4, texel);
    r->caustics.maps_only = 1;
    CHECK_OK_CTX(ctx, snell_render(r, fd, &fs));
    CHECK(strstr(fs.caustics_reason, "chained") == NULL, "%s alone: %s", name, fs.caustics_reason);
    CHECK_OK_CTX(ctx, snell__caustics_read(ctx, &r->caustics, gpu, &size));
    r->caustics.maps_only = 0;
    snprintf(file, sizeof file, "%s_alone.png", name);
    test_write_light_map(file, gpu, 4, MAP, 0.8f);
    out->db_alone = test_light_map_psnr(gpu, 4, ref_rgb, MAP * MAP, 0.8f);
    out->e_alone = through_glass(gpu, ref_rgb, ref_c, texel);
    printf("%s: GPU %.2f dB from the reference, light through glass %.4f against %.4f (%+.2f%%), all light %.4f; "
           "each alone %.2f dB, %+.2f%%\n", name, out->db, out->e_gpu, out->e_ref, 100.0 * (out->e_gpu / out->e_ref - 1.0),
           out->e_all, out->db_alone, 100.0 * (out->e_alone / out->e_ref - 1.0));
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_mesh *ball = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_shape_desc sd = {SNELL_SHAPE_SPHERE, 128, 64};
    snell_env_desc ed;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_glass g[2];
    float top[16] = {0.45f, 0, 0, 0, 0, 0.45f, 0, 0, 0, 0, 0.45f, 0, 0.15f, 2.9f, 0.1f, 1};
    float low[16] = {0.6f, 0, 0, 0, 0, 0.6f, 0, 0, 0, 0, 0.6f, 0, 0, 1.2f, 0, 1};
    float *gpu = NULL, *ref_rgb = NULL, *ref_c = NULL;
    double dir[3] = {0.15, -1.0, 0.1}, len;
    result res;
    int k;
    if (!ctx) SKIP("no headless GL context");
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &ball));
    memset(&ed, 0, sizeof ed);
    ed.face_size = 32;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &env));
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = W;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    gpu = (float *)calloc((size_t)MAP * MAP * 4, sizeof(float));
    ref_rgb = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    ref_c = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    if (!ball || !env || !r || !gpu || !ref_rgb || !ref_c) return test_finish();

    memset(g, 0, sizeof g);
    g[0].mesh = g[1].mesh = ball;
    g[0].model = top, g[1].model = low;
    g[0].material.ior = g[1].material.ior = 1.5f;
    g[1].material.tint[0] = 0.6f, g[1].material.tint[1] = 0.85f, g[1].material.tint[2] = 1.0f;
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass = g;
    fd.glass_count = 2;
    fd.camera.azimuth = 0.4f, fd.camera.elevation = 0.5f, fd.camera.distance = 7.0f, fd.camera.fov_y = 0.8f;
    fd.light.type = SNELL_LIGHT_DIRECTIONAL;
    len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (k = 0; k < 3; k++) fd.light.direction[k] = (float)(dir[k] / len);
    fd.light.photons = 512;
    fd.receiver.extent = EXT;
    fd.receiver.map_size = MAP;

    run(ctx, r, &fd, "caustics_chain", gpu, ref_rgb, ref_c, &res);
    {
        double e_free = -fd.light.direction[1] * (2.0 * EXT) * (2.0 * EXT);
        CHECK(res.db >= 30.0, "directional: GPU %.2f dB from the reference", res.db);
        CHECK(fabs(res.e_gpu / res.e_ref - 1.0) <= 0.03, "directional: light through glass %.4f against %.4f",
              res.e_gpu, res.e_ref);
        CHECK(res.e_all <= e_free, "all light %.4f, %.4f without the glass", res.e_all, e_free);
        CHECK(res.db_alone <= res.db - 6.0 && fabs(res.e_alone / res.e_ref - 1.0) >= 0.1,
              "each alone: %.2f dB, %.4f against %.4f", res.db_alone, res.e_alone, res.e_ref);
    }

    fd.light.type = SNELL_LIGHT_SPOT;
    fd.light.position[0] = 0.5f, fd.light.position[1] = 6.0f, fd.light.position[2] = 0.3f;
    fd.light.direction[0] = -0.1f, fd.light.direction[1] = -1.0f, fd.light.direction[2] = -0.05f;
    fd.light.spot_angle = 0.6f;
    fd.light.color[0] = fd.light.color[1] = fd.light.color[2] = 36.0f;
    run(ctx, r, &fd, "caustics_chain_spot", gpu, ref_rgb, ref_c, &res);
    CHECK(res.db >= 30.0, "spot: GPU %.2f dB from the reference", res.db);
    CHECK(fabs(res.e_gpu / res.e_ref - 1.0) <= 0.03, "spot: light through glass %.4f against %.4f", res.e_gpu,
          res.e_ref);
    CHECK(res.db_alone <= res.db - 6.0 && fabs(res.e_alone / res.e_ref - 1.0) >= 0.1,
          "spot, each alone: %.2f dB, %.4f against %.4f", res.db_alone, res.e_alone, res.e_ref);

    {
        /* side by side under a light from above: beams apart, no chain */
        snell_frame_stats fs;
        float side[16] = {0.6f, 0, 0, 0, 0, 0.6f, 0, 0, 0, 0, 0.6f, 0, -1.3f, 1.2f, 0, 1};
        g[0].model = side;
        fd.light.type = SNELL_LIGHT_DIRECTIONAL;
        fd.light.direction[0] = 0.0f, fd.light.direction[1] = -1.0f, fd.light.direction[2] = 0.0f;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
        printf("side by side: %s\n", fs.caustics_reason);
        CHECK(strstr(fs.caustics_reason, "paths: 0 BVH, 2 depth maps;") != NULL, "side by side: %s", fs.caustics_reason);
        g[0].model = top;
    }
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(ball);
    free(gpu), free(ref_rgb), free(ref_c);
    snell_ctx_destroy(ctx);
    return test_finish();
}
