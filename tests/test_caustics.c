/* SPDX-License-Identifier: MIT */
/* test_caustics.c — the caustics stage (issue 27) against the reference's
 * light tracing (snell_ref_receiver_render) and the ball lens in closed
 * form: a glass sphere (radius 1, IOR 1.5) over a plane under a directional
 * light 30 degrees off vertical. The paraxial back focus of a ball lens lies
 * f = n R / (2 (n - 1)) = 1.5 from its centre along the light; the plane is
 * put through it, so the caustic's peak is there (on the lens's axis). Checks: the peak within
 * 2% of f of it (GPU and reference); straight down, the plane where the
 * flux near the axis is largest within 2% of f of where exact ball-lens rays
 * in closed form put it; the light through glass on the plane
 * within 5% of the reference's, PSNR of the lit receiver against the
 * reference >= 30 dB, the stage's skips and reuse, frames without light or
 * receiver byte-identical to frames without the fields, bad input refused. */
#include "test_util.h"
#include "core/ctx.h"
#include "core/glstate.h"
#include "core/gl.h"
#include "render/caustics.h"
#include "render/renderer.h"
#include "render/stages.h"
#include "ref/ref_trace.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAP 256
#define EXT 2.5f
#define CX 0.5f
#define W 192
#define PI_D 3.14159265358979323846
/* The reference's photons a side on the mesh: twice the frame's (the stage's
 * default, 256), so that its grid is not the GPU's. */
#define REF_PHOTONS 512

static const double kF = 1.5 * 1.0 / (2.0 * (1.5 - 1.0)); /* n R / (2 (n - 1)) */

/* Peak of a caustic map (one value per texel): the value-weighted centroid
 * of the 5 x 5 texels about the largest, in world x, z. */
static void peak(const float *v, const snell_receiver *rc, double out[2])
{
    int best = 0, i, j, n = rc->map_size;
    double sx = 0, sz = 0, sw = 0, texel = 2.0 * rc->extent / n;
    for (i = 1; i < n * n; i++)
        if (v[i] > v[best]) best = i;
    for (j = best / n - 2; j <= best / n + 2; j++)
        for (i = best % n - 2; i <= best % n + 2; i++) {
            double w;
            if (i < 0 || j < 0 || i >= n || j >= n) continue;
            w = v[j * n + i];
            sx += w * (rc->center[0] - rc->extent + (i + 0.5) * texel);
            sz += w * (rc->center[1] - rc->extent + (j + 0.5) * texel);
            sw += w;
        }
    out[0] = sx / sw, out[1] = sz / sw;
}

/* The light through glass in texel i of a GPU light map (4 floats a
 * texel): its alpha, the photons' own tally, in a float map. An RGB10_A2
 * map (a context without float targets: the gles30-min leg) has 2 bits of
 * alpha; there it is the green irradiance less the reference's direct light
 * (its total ref_rgb less its light through glass ref_c, 3 floats a texel). */
static int g_fixed;
static double through_glass(const float *gpu, const float *ref_rgb, const float *ref_c, int i)
{
    if (!g_fixed) return gpu[4 * i + 3];
    return gpu[4 * i + 1] - (ref_rgb[3 * i + 1] - ref_c[3 * i + 1]);
}

/* The reference's counterpart (green where the GPU's is). */
static double ref_through_glass(const float *ref_rgb, const float *ref_c, int i)
{
    (void)ref_rgb;
    return g_fixed ? ref_c[3 * i + 1] : (ref_c[3 * i] + ref_c[3 * i + 1] + ref_c[3 * i + 2]) / 3.0;
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    g_fixed = ctx && snell__light_fixed(ctx);
    snell_mesh *sphere = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_ref *ref = NULL, *ref_exact = NULL;
    snell_shape_desc sd = {SNELL_SHAPE_SPHERE, 256, 128};
    snell_renderer_desc rd;
    snell_frame_desc fd, plain;
    snell_frame_stats fs;
    snell_glass g;
    float model[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1.5f, 0, 1};
    const double dir[3] = {0.5, -sqrt(3.0) / 2.0, 0.0}; /* 30 degrees off vertical, towards +x */
    double focus[3], p_gpu[2], p_ref[2], p_exact[2], e_gpu = 0, e_ref = 0, texel;
    float *gpu = NULL, *ref_rgb = NULL, *ref_caustic = NULL, *mono = NULL;
    uint8_t *img0 = NULL, *img1 = NULL;
    int size = 0, i, k;
    if (!ctx) SKIP("no headless GL context");
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &sphere));
    env = test_sky(ctx, 64);
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = W;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    gpu = (float *)calloc((size_t)MAP * MAP * 4, sizeof(float));
    ref_rgb = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    ref_caustic = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    mono = (float *)calloc((size_t)MAP * MAP, sizeof(float));
    img0 = (uint8_t *)malloc((size_t)W * W * 4);
    img1 = (uint8_t *)malloc((size_t)W * W * 4);
    if (!sphere || !env || !r || !gpu || !ref_rgb || !ref_caustic || !mono || !img0 || !img1) return test_finish();

    memset(&g, 0, sizeof g);
    g.mesh = sphere;
    g.model = model;
    g.material.ior = 1.5f;
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass = &g;
    fd.glass_count = 1;
    fd.camera.azimuth = 0.5f, fd.camera.elevation = 0.6f, fd.camera.distance = 7.0f, fd.camera.fov_y = 0.8f;
    plain = fd; /* no light, no receiver */
    fd.light.type = SNELL_LIGHT_DIRECTIONAL;
    for (k = 0; k < 3; k++) fd.light.direction[k] = (float)dir[k];
    for (k = 0; k < 3; k++) focus[k] = model[12 + k] + kF * dir[k];
    fd.receiver.height = (float)focus[1]; /* the plane through the paraxial focus */
    fd.receiver.center[0] = CX;
    fd.receiver.extent = EXT;
    fd.receiver.map_size = MAP;
    texel = 2.0 * EXT / MAP;

    /* the stage runs, its light map is read */
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(strstr(fs.stages, "caustics") != NULL, "stages '%s'", fs.stages);
    CHECK(fs.caustics_photons == 256 * 256 && !fs.caustics_reused, "photons %d reused %d (%s)", fs.caustics_photons,
          fs.caustics_reused, fs.caustics_reason);
    printf("frame 1: %s\n", fs.caustics_reason);
    CHECK(strstr(fs.caustics_reason, g_fixed ? "RGB10_A2" : "RGBA32F") != NULL, "the light map's format: %s",
          fs.caustics_reason);
    /* convex: the depth maps' one crossing is its whole path (the BVH's is test_caustics_concave's) */
    CHECK(strstr(fs.caustics_reason, "paths: 0 BVH, 1 depth maps") != NULL, "the sphere's photons: %s",
          fs.caustics_reason);
    CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, img0));
    CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &size));
    CHECK(size == MAP, "map size %d", size);
    snell_write_png(test_out("caustics_view.png"), W, W, img0);

    /* the reference: the same mesh, and the exact sphere */
    CHECK_OK(test_ref_create(NULL, &fd, &ref));
    CHECK_OK(snell__ref_create_sphere(NULL, (double[3]){0.0, 1.5, 0.0}, 1.0, &ref_exact));
    if (!ref || !ref_exact) return test_finish();
    CHECK_OK(snell_ref_receiver_render(ref, &fd.light, &fd.receiver, REF_PHOTONS, 4, ref_rgb, ref_caustic));

    /* 1. the caustic's peak at the ball lens's paraxial focus */
    for (i = 0; i < MAP * MAP; i++) mono[i] = (float)through_glass(gpu, ref_rgb, ref_caustic, i);
    peak(mono, &fd.receiver, p_gpu);
    for (i = 0; i < MAP * MAP; i++) mono[i] = (ref_caustic[3 * i] + ref_caustic[3 * i + 1] + ref_caustic[3 * i + 2]) / 3;
    peak(mono, &fd.receiver, p_ref);
    {
        float *exact_c = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float)), *exact_rgb = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
        if (exact_c && exact_rgb) {
            snell_glass_material m15;
            memset(&m15, 0, sizeof m15);
            m15.ior = 1.5f;
            CHECK_OK(snell_ref_set_material(ref_exact, 0, &m15));
            CHECK_OK(snell_ref_receiver_render(ref_exact, &fd.light, &fd.receiver, 1024, 1, exact_rgb, exact_c));
            for (i = 0; i < MAP * MAP; i++) mono[i] = exact_c[3 * i + 1];
            peak(mono, &fd.receiver, p_exact);
        }
        free(exact_c);
        free(exact_rgb);
    }
    printf("focus expected (%.4f, %.4f); peak GPU (%.4f, %.4f) ref mesh (%.4f, %.4f) ref exact sphere (%.4f, %.4f); "
           "texel %.4f\n", focus[0], focus[2], p_gpu[0], p_gpu[1], p_ref[0], p_ref[1], p_exact[0], p_exact[1], texel);
    if (g_fixed) /* the focus's 212 times the light is a plateau at the RGB10_A2 map's range */
        printf("skipped: the GPU's focus (an RGB10_A2 map saturates there; the float leg checks it)\n");
    else
        CHECK(hypot(p_gpu[0] - focus[0], p_gpu[1] - focus[2]) <= 0.02 * kF, "GPU peak %.4f from the focus (2%% of f: %.4f)",
              hypot(p_gpu[0] - focus[0], p_gpu[1] - focus[2]), 0.02 * kF);
    CHECK(hypot(p_ref[0] - focus[0], p_ref[1] - focus[2]) <= 0.02 * kF, "reference peak %.4f from the focus",
          hypot(p_ref[0] - focus[0], p_ref[1] - focus[2]));
    CHECK(hypot(p_exact[0] - focus[0], p_exact[1] - focus[2]) <= 0.02 * kF, "exact-sphere peak %.4f from the focus",
          hypot(p_exact[0] - focus[0], p_exact[1] - focus[2]));

    /* 2. the light through the glass on the plane: GPU against reference */
    for (i = 0; i < MAP * MAP; i++) {
        e_gpu += through_glass(gpu, ref_rgb, ref_caustic, i) * texel * texel;
        e_ref += ref_through_glass(ref_rgb, ref_caustic, i) * texel * texel;
    }
    printf("flux through glass on the plane: GPU %.4f, reference %.4f (%.2f%%), pi R^2 = %.4f\n", e_gpu, e_ref,
           100.0 * (e_gpu / e_ref - 1.0), PI_D);
    {
        double excess = test_light_map_excess(ctx, ref_rgb, MAP * MAP, texel); /* 0 with float maps */
        CHECK(fabs(e_gpu - e_ref) <= 0.05 * e_ref + excess, "GPU %.4f against reference %.4f (%.4f above an RGB10_A2 "
              "map's range)", e_gpu, e_ref, excess);
    }

    /* 3. the lit receiver (albedo 0.8) against the reference */
    {
        double db = test_light_map_psnr(gpu, 4, ref_rgb, MAP * MAP, 0.8f), se = 0, mx = 0;
        for (i = 0; i < MAP * MAP * 3; i++) mx = fmax(mx, ref_caustic[i]);
        for (i = 0; i < MAP * MAP; i++)
            for (k = 0; k < 3; k++) se += pow((gpu[4 * i + k] - ref_rgb[3 * i + k]) / mx, 2);
        printf("receiver PSNR against the reference: %.2f dB shown (albedo 0.8, clamped); light map %.2f dB of its "
               "peak %.1f\n", db, 10.0 * log10(3.0 * MAP * MAP / se), mx);
        CHECK(db >= 30.0, "PSNR %.2f dB", db);
    }
    test_write_light_map("caustics_map_gpu.png", gpu, 4, MAP, 0.8f);
    test_write_light_map("caustics_map_ref.png", ref_rgb, 3, MAP, 0.8f);

    /* 2b. flux-correct: glass of IOR 1.0001 bends nothing, so the photons
     * must fill its shadow with the light it takes, less Schlick's loss at
     * two surfaces (whose (1 - cos)^5 rim does not vanish as n -> 1): in
     * closed form per texel from the impact parameter of its photons. */
    {
        snell_glass flat = g;
        snell_frame_desc fdf = fd;
        double sum = 0, sum_ref = 0, sum_want = 0, lo = 1e9, hi = 0, want = -dir[1];
        const double schlick_r0 = pow(0.0001 / 2.0001, 2.0);
        int inside = 0;
        flat.material.ior = 1.0001f;
        fdf.glass = &flat;
        CHECK_OK_CTX(ctx, snell_render(r, &fdf, &fs));
        CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &size));
        CHECK_OK(snell_ref_set_material(ref, 0, &flat.material));
        CHECK_OK(snell_ref_receiver_render(ref, &fdf.light, &fdf.receiver, REF_PHOTONS, 4, ref_rgb, NULL));
        CHECK_OK(snell_ref_set_material(ref, 0, &g.material));
        /* the shadow's ellipse: centre below the sphere along the light, half axes 1 / cos 30 (x) and 1 (z) */
        for (k = 0; k < MAP; k++)
            for (i = 0; i < MAP; i++) {
                double x = CX - EXT + (i + 0.5) * texel, z = -EXT + (k + 0.5) * texel;
                double ex = (x - (0.0 + dir[0] * (focus[1] - 1.5) / dir[1])) * (-dir[1]), v = gpu[4 * (k * MAP + i) + 1];
                if (ex * ex + z * z > 0.9 * 0.9) continue; /* well inside the shadow */
                {
                    /* what the photon here carries: its impact parameter b
                     * off the light's axis through the centre, Schlick at
                     * both surfaces (cos = sqrt(1 - b^2) in and out) */
                    double q[3] = {x - 0.0, focus[1] - 1.5, z}, t = q[0] * dir[0] + q[1] * dir[1], b2, c, f;
                    b2 = (q[0] - t * dir[0]) * (q[0] - t * dir[0]) + (q[1] - t * dir[1]) * (q[1] - t * dir[1]) + z * z;
                    c = sqrt(fmax(0.0, 1.0 - b2));
                    f = schlick_r0 + (1.0 - schlick_r0) * pow(1.0 - c, 5.0);
                    sum_want += want * (1.0 - f) * (1.0 - f);
                }
                inside++;
                sum += v;
                sum_ref += ref_rgb[3 * (k * MAP + i) + 1];
                lo = fmin(lo, v), hi = fmax(hi, v);
            }
        printf("IOR 1.0001: in the shadow (%d texels) mean irradiance GPU %.5f, reference %.5f, closed form %.5f "
               "(cos 30 = %.4f); GPU texels %.3f..%.3f\n", inside, sum / inside, sum_ref / inside, sum_want / inside,
               want, lo, hi);
        CHECK(inside > 1000 && fabs(sum / sum_want - 1.0) < 0.002, "GPU mean %.5f", sum / inside);
        CHECK(fabs(sum_ref / sum_want - 1.0) < 0.002, "reference mean %.5f", sum_ref / inside);
        CHECK(lo > 0.8 * want && hi < 1.2 * want, "GPU texels %.3f..%.3f", lo, hi);
    }

    /* 1b. the focal distance. Straight down, the receiver moved along the
     * axis: where is the flux within RHO of the axis largest? In closed form
     * (exact ball-lens rays, not paraxial): the zone of impact parameter b
     * enters at theta_i = asin b, runs inside at theta_t = asin(b / n) over
     * the chord 2 cos theta_t turned by theta_i - theta_t, leaves turned by
     * delta = 2 (theta_i - theta_t) and meets the plane at a radius r_b(z);
     * it carries 2 pi b db (1 - Schlick)^2. Spherical aberration puts that
     * brightest plane short of the paraxial focus f = n R / (2 (n - 1)). */
    {
        const double RHO = 0.02, n_ior = 1.5, r0 = 0.04;
        snell_frame_desc fv = fd;
        double best = 0, best_ref = 0, best_cf = 0, at = 0, at_ref = 0, at_cf = 0;
        int step;
        float *rc3 = (float *)calloc(128 * 128 * 3, sizeof(float));
        fv.light.direction[0] = 0.0f, fv.light.direction[1] = -1.0f, fv.light.direction[2] = 0.0f;
        fv.receiver.center[0] = 0.0f, fv.receiver.center[1] = 0.0f;
        fv.receiver.extent = 0.3f;
        fv.receiver.map_size = 128;
        for (step = 0; step <= 30 && rc3; step++) {
            double z = 1.30 + 0.01 * step, v = 0, v_ref = 0, v_cf = 0, tx = 0.6 / 128;
            int n = 0, j;
            fv.receiver.height = (float)(1.5 - z);
            CHECK_OK_CTX(ctx, snell_render(r, &fv, &fs));
            CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &n));
            CHECK_OK(snell_ref_receiver_render(ref_exact, &fv.light, &fv.receiver, 384, 1, ref_rgb, rc3));
            for (j = 0; j < 128; j++)
                for (i = 0; i < 128; i++) {
                    double x = -0.3 + (i + 0.5) * tx, y = -0.3 + (j + 0.5) * tx;
                    if (x * x + y * y > RHO * RHO) continue;
                    v += through_glass(gpu, ref_rgb, rc3, j * 128 + i) * tx * tx;
                    v_ref += rc3[3 * (j * 128 + i) + 1] * tx * tx;
                }
            for (j = 0; j < 20000; j++) { /* the zones, midpoint rule */
                double b = (j + 0.5) / 20000.0, ti = asin(b), tt = asin(b / n_ior), dl = 2.0 * (ti - tt);
                double c = sqrt(1.0 - b * b), f = r0 + (1.0 - r0) * pow(1.0 - c, 5.0);
                double x2 = b - 2.0 * cos(tt) * sin(ti - tt), y2 = c - 2.0 * cos(tt) * cos(ti - tt);
                double sp = (y2 + z) / cos(dl), rb = fabs(x2 - sp * sin(dl));
                if (dl < 1.5 && sp > 0.0 && rb < RHO) v_cf += 2.0 * PI_D * b / 20000.0 * (1.0 - f) * (1.0 - f);
            }
            if (v > best) best = v, at = z;
            if (v_ref > best_ref) best_ref = v_ref, at_ref = z;
            if (v_cf > best_cf) best_cf = v_cf, at_cf = z;
        }
        free(rc3);
        printf("flux within %.2f of the axis largest %.2f below the centre (closed form, %.4f), %.2f (GPU, %.4f), "
               "%.2f (reference, %.4f); paraxial focus f = %.2f\n", RHO, at_cf, best_cf, at, best, at_ref, best_ref,
               kF);
        CHECK(fabs(at_ref - at_cf) <= 0.02 * kF, "reference brightest at %.3f, closed form %.3f", at_ref, at_cf);
        if (g_fixed) {
            printf("skipped: the GPU's flux near the focus (it saturates an RGB10_A2 map; the float leg checks it)\n");
        } else {
            CHECK(fabs(at - at_cf) <= 0.02 * kF, "GPU brightest at %.3f, closed form %.3f", at, at_cf);
            CHECK(fabs(best / best_ref - 1.0) < 0.05, "GPU flux there %.4f, reference %.4f", best, best_ref);
        }
    }

    /* 3b. a spot light 6 above the centre (a point-like light; the ball
     * lens images it at 1 / (1/f - 1/6) = 2 below the centre, paraxially):
     * against the reference, the lit receiver, the flux through the glass,
     * and the plane where the flux near the axis is largest (scanned) */
    {
        snell_frame_desc sp = fd;
        double eg = 0, er = 0, best = 0, best_ref = 0, at = 0, at_ref = 0, s_i = 1.0 / (1.0 / kF - 1.0 / 6.0);
        int step, n = 0;
        sp.light.type = SNELL_LIGHT_SPOT;
        sp.light.position[0] = 0.0f, sp.light.position[1] = 7.5f, sp.light.position[2] = 0.0f;
        sp.light.direction[0] = 0.2f, sp.light.direction[1] = -1.0f, sp.light.direction[2] = 0.0f;
        sp.light.spot_angle = 0.45f;
        sp.light.color[0] = sp.light.color[1] = sp.light.color[2] = 36.0f; /* 1 at the sphere's centre */
        sp.receiver.height = -1.0f, sp.receiver.center[0] = 0.0f, sp.receiver.extent = 3.0f;
        CHECK_OK_CTX(ctx, snell_render(r, &sp, &fs));
        CHECK(strstr(fs.caustics_reason, "made") && fs.caustics_photons == 256 * 256, "spot: %s", fs.caustics_reason);
        CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &n));
        CHECK_OK(snell_ref_receiver_render(ref, &sp.light, &sp.receiver, REF_PHOTONS, 4, ref_rgb, ref_caustic));
        for (i = 0; i < MAP * MAP; i++) {
            eg += through_glass(gpu, ref_rgb, ref_caustic, i);
            er += ref_through_glass(ref_rgb, ref_caustic, i);
        }
        {
            double db = test_light_map_psnr(gpu, 4, ref_rgb, MAP * MAP, 0.8f);
            printf("spot: flux through glass GPU %.4f reference %.4f (%.2f%%), receiver %.2f dB\n", eg * 0.0234375 * 0.0234375,
                   er * 0.0234375 * 0.0234375, 100.0 * (eg / er - 1.0), db);
            double excess = test_light_map_excess(ctx, ref_rgb, MAP * MAP, 1.0); /* texels, as eg and er */
            CHECK(fabs(eg - er) <= 0.05 * er + excess, "spot flux GPU %.4f reference %.4f (%.4f above the range)", eg,
                  er, excess);
            CHECK(db >= 30.0, "spot PSNR %.2f dB", db);
        }
        test_write_light_map("caustics_spot_gpu.png", gpu, 4, MAP, 0.8f);
        test_write_light_map("caustics_spot_ref.png", ref_rgb, 3, MAP, 0.8f);
        sp.receiver.extent = 0.3f, sp.receiver.map_size = 128;
        for (step = 0; step <= 16; step++) {
            double z = 1.60 + 0.025 * step, v = 0, v_ref = 0, tx = 0.6 / 128;
            int j;
            sp.receiver.height = (float)(1.5 - z);
            CHECK_OK_CTX(ctx, snell_render(r, &sp, &fs));
            CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &n));
            CHECK_OK(snell_ref_receiver_render(ref_exact, &sp.light, &sp.receiver, 384, 1, ref_rgb, ref_caustic));
            for (j = 0; j < 128; j++)
                for (i = 0; i < 128; i++) {
                    double x = -0.3 + (i + 0.5) * tx, y = -0.3 + (j + 0.5) * tx;
                    if (x * x + y * y > 0.02 * 0.02) continue;
                    v += through_glass(gpu, ref_rgb, ref_caustic, j * 128 + i);
                    v_ref += ref_caustic[3 * (j * 128 + i) + 1];
                }
            if (v > best) best = v, at = z;
            if (v_ref > best_ref) best_ref = v_ref, at_ref = z;
        }
        printf("spot: flux within 0.02 of the axis largest %.3f (GPU), %.3f (reference) below the centre; paraxial "
               "image %.3f\n", at, at_ref, s_i);
        if (g_fixed) {
            printf("skipped: the spot's image (it saturates an RGB10_A2 map; the float leg checks it)\n");
        } else {
            CHECK(fabs(at - at_ref) <= 0.02 * s_i, "spot: GPU %.3f reference %.3f", at, at_ref);
            CHECK(at < s_i && at > 0.8 * s_i, "spot: brightest %.3f short of the paraxial image %.3f (aberration)", at,
                  s_i);
        }
    }

    /* 4. reuse: nothing moved; then the light moves */
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(fs.caustics_reused == 0, "the glass changed back: made again");
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(fs.caustics_reused == 1 && fs.caustics_photons == 0 && strstr(fs.caustics_reason, "nothing moved"),
          "reused %d photons %d (%s)", fs.caustics_reused, fs.caustics_photons, fs.caustics_reason);
    CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, img1));
    CHECK(memcmp(img0, img1, (size_t)W * W * 4) == 0, "the reused frame differs");
    fd.light.direction[2] = 0.1f;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(fs.caustics_reused == 0 && fs.caustics_photons > 0, "moved light: reused %d", fs.caustics_reused);
    fd.light.direction[2] = 0.0f;
    /* a map too coarse for the caster says so: 256 texels over a 200-unit square are 0.78 units each,
     * over a quarter of the sphere's radius (the map of the test's square, 0.02 units, does not) */
    CHECK(!strstr(fs.caustics_reason, "blurred"), "the test's map called coarse: %s", fs.caustics_reason);
    fd.receiver.extent = 100.0f;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(strstr(fs.caustics_reason, "(texels > caster radius/4: blurred)") != NULL,
          "a 200-unit square in 256 texels: %s", fs.caustics_reason);
    fd.receiver.extent = EXT;
    /* a clear glass object casts nothing: its size does not make the map coarse (a bead of radius 0.01
     * beside the sphere, IOR 1: 0.02-unit texels are over a quarter of its radius) */
    {
        snell_glass pair[2];
        snell_frame_desc two = fd;
        float bead[16] = {0.01f, 0, 0, 0, 0, 0.01f, 0, 0, 0, 0, 0.01f, 0, 2.0f, 1.5f, 0, 1};
        pair[0] = g, pair[1] = g;
        pair[1].model = bead;
        pair[1].material.ior = 1.0f;
        two.glass = pair;
        two.glass_count = 2;
        CHECK_OK_CTX(ctx, snell_render(r, &two, &fs));
        /* the whole reason fits (SNELL_REASON_SIZE): the map's words end it */
        CHECK(strstr(fs.caustics_reason, "light map") && !strstr(fs.caustics_reason, "(texels >"),
              "a clear bead called the map coarse: %s", fs.caustics_reason);
    }

    /* 5. no light, or no receiver: the frame of a descriptor without them */
    CHECK_OK_CTX(ctx, snell_render(r, &plain, &fs));
    CHECK(!strstr(fs.stages, "caustics") && !strcmp(fs.caustics_reason, "no light"), "stages '%s' reason '%s'",
          fs.stages, fs.caustics_reason);
    CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, img0));
    {
        snell_frame_desc lit = fd;
        lit.receiver.extent = 0.0f;
        CHECK_OK_CTX(ctx, snell_render(r, &lit, &fs));
        CHECK(!strstr(fs.stages, "caustics") && !strcmp(fs.caustics_reason, "no receiver"), "reason '%s'",
              fs.caustics_reason);
        CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, img1));
        CHECK(memcmp(img0, img1, (size_t)W * W * 4) == 0, "a light without a receiver changed the frame");
    }

    /* 5b. why a context without float blending (GL_EXT_float_blend) takes
     * RGB10_A2, not RGBA16F: a fresh renderer made to take RGBA16F, against
     * the RGBA32F map of frame 1 (a context without float blending has
     * RGB10_A2, which the whole test then runs on: the gles30-min and
     * powervr-rogue legs) */
    if (!snell__light_fixed(ctx)) {
        snell_renderer *r16 = NULL;
        float *m16 = (float *)calloc((size_t)MAP * MAP * 4, sizeof(float));
        CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r16));
        if (r16 && m16) {
            double e16 = 0, e32 = 0;
            int n = 0;
            snell__renderer_caustics(r16)->map_format = GL_RGBA16F;
            CHECK_OK_CTX(ctx, snell_render(r16, &fd, &fs));
            CHECK(strstr(fs.caustics_reason, "RGBA16F") != NULL, "16F: %s", fs.caustics_reason);
            CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r16), m16, &n));
            CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
            CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &n));
            for (i = 0; i < MAP * MAP; i++) e16 += m16[4 * i + 3], e32 += gpu[4 * i + 3];
            {
                double db = 0, se = 0;
                for (i = 0; i < MAP * MAP * 4; i++)
                    if (i % 4 != 3) se += pow(fmin(1.0, 0.8 * m16[i]) - fmin(1.0, 0.8 * gpu[i]), 2.0);
                db = 10.0 * log10(3.0 * MAP * MAP / se);
                printf("RGBA16F light map: flux through glass %.3f%% of RGBA32F's, %.1f dB against it shown\n",
                       100.0 * e16 / e32, db);
                /* half floats stop adding a photon's share once a texel holds
                 * 2^12 of it: at this focus (212 times the light) 26% of the
                 * light through the glass is lost, the shown image (the focus
                 * saturates) barely changes */
                CHECK(e16 / e32 > 0.7 && e16 / e32 <= 1.001 && db > 40.0, "16F flux ratio %.4f, %.1f dB", e16 / e32, db);
            }
        }
        free(m16);
        snell_renderer_destroy(r16);
    }

    /* 5c. exit-direction output has no receiver: the stage is left out, said why */
    {
        snell_renderer *rx = NULL;
        snell_renderer_desc xd = rd;
        xd.output = SNELL_OUTPUT_EXIT_DIRECTION;
        CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &xd, &rx));
        if (rx) {
            CHECK_OK_CTX(ctx, snell_render(rx, &fd, &fs));
            CHECK(!strstr(fs.stages, "caustics") && strstr(fs.caustics_reason, "exit-direction"), "exit dirs: '%s' (%s)",
                  fs.stages, fs.caustics_reason);
        }
        snell_renderer_destroy(rx);
    }

    /* 6. bad input: a clear status, the frame not drawn */
    {
        snell_frame_desc bad = fd;
        bad.light.direction[0] = bad.light.direction[1] = bad.light.direction[2] = 0.0f;
        CHECK(snell_render(r, &bad, &fs) == SNELL_E_INVALID_ARG, "zero direction");
        bad = fd;
        bad.light.direction[1] = NAN;
        CHECK(snell_render(r, &bad, &fs) == SNELL_E_INVALID_ARG, "NaN direction");
        bad = fd;
        bad.light.photons = 8;
        CHECK(snell_render(r, &bad, &fs) == SNELL_E_INVALID_ARG, "8 photons");
        bad = fd;
        bad.receiver.albedo[1] = 2.0f;
        CHECK(snell_render(r, &bad, &fs) == SNELL_E_INVALID_ARG, "albedo 2");
        bad = fd;
        bad.receiver.extent = -1.0f;
        CHECK(snell_render(r, &bad, &fs) == SNELL_E_INVALID_ARG, "extent -1");
        bad = fd;
        bad.light.type = (snell_light_type)7;
        CHECK(snell_render(r, &bad, &fs) == SNELL_E_INVALID_ARG, "type 7");
        bad = fd;
        bad.light.type = SNELL_LIGHT_SPOT;
        bad.light.spot_angle = 2.0f;
        CHECK(snell_render(r, &bad, &fs) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "spot_angle"),
              "spot angle 2: %s", snell_last_error(ctx));
        bad.light.spot_angle = 0.0f;
        bad.light.position[0] = INFINITY;
        CHECK(snell_render(r, &bad, &fs) == SNELL_E_INVALID_ARG, "spot position inf");
        /* a spot light inside the glass's bounding sphere: no photons, said so */
        bad.light.position[0] = 0.0f, bad.light.position[1] = 1.5f;
        CHECK_OK_CTX(ctx, snell_render(r, &bad, &fs));
        CHECK(fs.caustics_photons == 0 && strstr(fs.caustics_reason, "inside"), "light inside: %s", fs.caustics_reason);
    }

    free(gpu), free(ref_rgb), free(ref_caustic), free(mono), free(img0), free(img1);
    snell_ref_destroy(ref);
    snell_ref_destroy(ref_exact);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(sphere);
    snell_ctx_destroy(ctx);
    return test_finish();
}
