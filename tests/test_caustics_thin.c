/* SPDX-License-Identifier: MIT */
/* test_caustics_thin.c — the shadow and light of thin-walled glass (issue
 * 27; material.thickness > 0): a closed thin-walled sphere (radius 1,
 * thickness 0.02, IOR 1.5, tinted and absorbing) over the receiver plane.
 * A thin wall bends nothing: each photon goes straight on through both of
 * the sphere's walls, each one a slab (Schlick at both faces, Beer-Lambert
 * over thickness / cos_t, all inner bounces summed, the tint), so the plane
 * under it gets, per colour channel, the light times (tint T(c))^2 at the
 * incidence cosine c of its line, the same at both walls of a sphere:
 *   T(c) = (1 - R)^2 a / (1 - R^2 a^2),  R = R0 + (1 - R0) (1 - c)^5,
 *   R0 = ((n - 1) / (n + 1))^2,  a = exp(-sigma d / cos_t),
 *   cos_t = sqrt(1 - (1 - c^2) / n^2),
 * written out here from the formula, not taken from the library. With
 * attenuation_distance = thickness, exp(-sigma d) is attenuation_color.
 * Checks: (1) straight down, the shadow's centre is coloured as the slab
 * model at normal incidence says: every channel, and the channels' ratios,
 * between their values at normal incidence and at the largest impact
 * parameter that lands there; (2) the mean over the shadow's disc against
 * the model in closed form per texel (GPU and reference); (3) under a light
 * 25 degrees off vertical, the lit receiver against the reference (PSNR >= 40 dB) and
 * the light through the glass against the closed form's flux (the cross
 * section's integral, the same at any angle); (4) the photons of the BVH
 * path (exact's, every wall on the line) against the depth maps' and the
 * reference; (5) a spot light against the reference; (6) a standing torus
 * (up to four walls on a line) by the BVH against the reference, and
 * against the reference capped at two walls, which differs clearly; (7) an
 * opaque box under the sphere: the light through glass on it against the
 * closed form and the reference; (8) a clear thin wall (IOR 1, no tint nor
 * absorption) casts nothing and the stage says so. Writes
 * caustics_thin_gpu.png, caustics_thin_ref.png. */
#include "test_util.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/light_map.h"
#include "render/caustics.h"
#include "render/renderer.h"
#include "render/stages.h"
#include "ref/ref_trace.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAP 256
#define EXT 2.0f
#define W 128
#define PI_D 3.14159265358979323846

static const double kIor = 1.5, kThick = 0.02;
static const float kTint[3] = {1.0f, 0.8f, 0.6f}, kAtten[3] = {1.0f, 0.9f, 0.7f};

/* One wall's transmittance in channel k at incidence cosine c (the model above). */
static double wall_t(double c, int k)
{
    double r0 = pow((kIor - 1.0) / (kIor + 1.0), 2.0), r = r0 + (1.0 - r0) * pow(1.0 - c, 5.0);
    double ct = sqrt(1.0 - (1.0 - c * c) / (kIor * kIor)), a = pow(kAtten[k], 1.0 / ct);
    return (1.0 - r) * (1.0 - r) * a / (1.0 - r * r * a * a);
}

/* The light through both walls in channel k along a line of impact parameter b (< 1) off the centre. */
static double sphere_e(double b, int k)
{
    double t = kTint[k] * wall_t(sqrt(1.0 - b * b), k);
    return t * t;
}

/* Flux through glass (the light's colour 1 per unit area facing it) in channel k: the cross section's integral. */
static double sphere_flux(int k)
{
    double s = 0;
    int j;
    for (j = 0; j < 100000; j++) {
        double b = (j + 0.5) / 100000.0;
        s += 2.0 * PI_D * b / 100000.0 * sphere_e(b, k);
    }
    return s;
}

/* The light through glass on the plane of a map (stride floats a texel, channel k). */
static double map_flux(const float *v, int stride, int k)
{
    double s = 0, texel = 2.0 * EXT / MAP;
    int i;
    for (i = 0; i < MAP * MAP; i++) s += v[i * stride + k] * texel * texel;
    return s;
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_mesh *sphere = NULL, *torus = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_ref *ref = NULL;
    snell_shape_desc sd = {SNELL_SHAPE_SPHERE, 256, 128}, td = {SNELL_SHAPE_TORUS, 96, 48};
    snell_frame_desc fd;
    snell_frame_stats fs;
    snell_glass g;
    float model[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1.2f, 0, 1};
    float *gpu = NULL, *gpu2 = NULL, *ref_rgb = NULL, *ref_c = NULL;
    double texel = 2.0 * EXT / MAP;
    int size = 0, i, j, k;
    if (!ctx) SKIP("no headless GL context");
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &sphere));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &td, &torus));
    env = test_sky(ctx, 32);
    r = test_renderer(ctx, W, W);
    gpu = (float *)calloc((size_t)MAP * MAP * 4, sizeof(float));
    gpu2 = (float *)calloc((size_t)MAP * MAP * 4, sizeof(float));
    ref_rgb = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    ref_c = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
    if (!sphere || !torus || !env || !r || !gpu || !gpu2 || !ref_rgb || !ref_c) return test_finish();

    memset(&g, 0, sizeof g);
    g.mesh = sphere;
    g.model = model;
    g.material.ior = (float)kIor;
    g.material.thickness = (float)kThick;
    g.material.attenuation_distance = (float)kThick;
    memcpy(g.material.tint, kTint, sizeof kTint);
    memcpy(g.material.attenuation_color, kAtten, sizeof kAtten);
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass = &g;
    fd.glass_count = 1;
    fd.camera.azimuth = 0.5f, fd.camera.elevation = 0.5f, fd.camera.distance = 6.0f, fd.camera.fov_y = 0.8f;
    fd.light.type = SNELL_LIGHT_DIRECTIONAL;
    fd.light.direction[1] = -1.0f;
    fd.receiver.extent = EXT;
    fd.receiver.map_size = MAP;
    CHECK_OK(test_ref_create(NULL, &fd, &ref));
    if (!ref) return test_finish();

    /* the stage casts the thin sphere: its photons by the depth maps */
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    printf("straight down: %s\n", fs.caustics_reason);
    CHECK(fs.caustics_photons == 256 * 256 && strstr(fs.caustics_reason, "made: 1 glass casting;") &&
              strstr(fs.caustics_reason, "0 BVH, 1 depth maps"),
          "photons %d: %s", fs.caustics_photons, fs.caustics_reason);
    CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &size));
    CHECK_OK(snell_ref_receiver_render(ref, &fd.light, &fd.receiver, 512, 2, ref_rgb, ref_c));

    /* 1. the shadow's centre: texels within RHO of the axis hold photons of
     * impact parameter up to RHO + 2 texels (the splat's reach) */
    {
        const double RHO = 0.08, bmax = RHO + 2.0 * texel;
        double m[3] = {0, 0, 0}, hi[3], lo[3], tol[3];
        int n = 0;
        for (j = 0; j < MAP; j++)
            for (i = 0; i < MAP; i++) {
                double x = -EXT + (i + 0.5) * texel, z = -EXT + (j + 0.5) * texel;
                if (x * x + z * z > RHO * RHO) continue;
                for (k = 0; k < 3; k++) m[k] += gpu[4 * (j * MAP + i) + k];
                n++;
            }
        for (k = 0; k < 3; k++) {
            m[k] /= n;
            hi[k] = sphere_e(0.0, k), lo[k] = sphere_e(bmax, k);
        }
        printf("shadow centre (%d texels): GPU %.5f %.5f %.5f; the slab model twice at normal incidence %.5f %.5f "
               "%.5f (at b = %.3f: %.5f %.5f %.5f)\n", n, m[0], m[1], m[2], hi[0], hi[1], hi[2], bmax, lo[0], lo[1],
               lo[2]);
        printf("channel ratios G/R %.5f B/R %.5f; the model at normal incidence %.5f %.5f\n", m[1] / m[0], m[2] / m[0],
               hi[1] / hi[0], hi[2] / hi[0]);
        /* float rounding of the photons' sums: 1e-3 relative. An RGB10_A2 map (no float colour
         * target) stores each share s (in steps q = range / 1023) as floor(s + u) q, u uniform: an
         * error of mean 0 and variance f (1 - f) q^2 <= s q^2 (f the fraction of s), so a texel
         * summing e holds it with variance at most q e, and the mean of n texels, their rounding
         * independent, at most q e / n: 4 standard deviations more (tol, absolute) */
        for (k = 0; k < 3; k++) {
            tol[k] = snell__light_fixed(ctx) ? 4.0 * sqrt(SNELL__LIGHT_RANGE / 1023.0 * hi[k] / (n > 0 ? n : 1)) : 0.0;
            if (snell__light_fixed(ctx)) printf("channel %d: +-%.5f for an RGB10_A2 map's rounding\n", k, tol[k]);
        }
        for (k = 0; k < 3; k++)
            CHECK(n > 50 && m[k] <= hi[k] * 1.001 + tol[k] && m[k] >= lo[k] * 0.999 - tol[k],
                  "channel %d: %.5f outside %.5f..%.5f (+-%.5f)", k, m[k], lo[k], hi[k], tol[k]);
        for (k = 1; k < 3; k++) { /* a ratio's relative error: at most the sum of its terms' */
            double rt = tol[k] / (lo[k] * 0.999 - tol[k]) + tol[0] / (lo[0] * 0.999 - tol[0]);
            CHECK(m[k] / m[0] <= hi[k] / hi[0] * (1.001 + rt) && m[k] / m[0] >= lo[k] / lo[0] * (0.999 - rt),
                  "ratio %d/0: %.5f outside %.5f..%.5f (+-%.3f%%)", k, m[k] / m[0], lo[k] / lo[0], hi[k] / hi[0],
                  100.0 * rt);
        }
    }

    /* 2. the shadow's disc (b <= 0.8): the mean against the model per texel
     * centre (the mesh's facets and the splat's tent smooth it by far less
     * than the 0.5% allowed) */
    {
        double sg[3] = {0, 0, 0}, sr[3] = {0, 0, 0}, sw[3] = {0, 0, 0};
        for (j = 0; j < MAP; j++)
            for (i = 0; i < MAP; i++) {
                double x = -EXT + (i + 0.5) * texel, z = -EXT + (j + 0.5) * texel;
                if (x * x + z * z > 0.8 * 0.8) continue;
                for (k = 0; k < 3; k++) {
                    sg[k] += gpu[4 * (j * MAP + i) + k];
                    sr[k] += ref_rgb[3 * (j * MAP + i) + k];
                    sw[k] += sphere_e(sqrt(x * x + z * z), k);
                }
            }
        for (k = 0; k < 3; k++) {
            printf("shadow disc, channel %d: GPU/model %.5f, reference/model %.5f\n", k, sg[k] / sw[k], sr[k] / sw[k]);
            CHECK(fabs(sg[k] / sw[k] - 1.0) < 0.005, "GPU channel %d %.5f of the model", k, sg[k] / sw[k]);
            CHECK(fabs(sr[k] / sw[k] - 1.0) < 0.005, "reference channel %d %.5f of the model", k, sr[k] / sw[k]);
        }
    }

    /* 3. 25 degrees off vertical: the receiver against the reference, the
     * light through glass against the closed form */
    fd.light.direction[0] = (float)sin(25.0 * PI_D / 180.0), fd.light.direction[1] = (float)-cos(25.0 * PI_D / 180.0);
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu, &size));
    CHECK_OK(snell_ref_receiver_render(ref, &fd.light, &fd.receiver, 512, 2, ref_rgb, ref_c));
    {
        double db = test_light_map_psnr(gpu, 4, ref_rgb, MAP * MAP, 0.8f);
        printf("25 degrees: receiver PSNR against the reference %.2f dB\n", db);
        CHECK(db >= 40.0, "PSNR %.2f dB", db);
        /* the mesh's cross section is pi to 0.1%; the rim's grazing walls pass almost nothing */
        for (k = 0; k < 3; k++) {
            double want = sphere_flux(k), fg, fr = map_flux(ref_c, 3, k);
            /* the GPU's light through glass: its map less the reference's direct light */
            for (i = 0; i < MAP * MAP; i++) gpu2[4 * i + k] = gpu[4 * i + k] - (ref_rgb[3 * i + k] - ref_c[3 * i + k]);
            fg = map_flux(gpu2, 4, k);
            printf("  channel %d flux through glass: GPU %.5f reference %.5f closed form %.5f\n", k, fg, fr, want);
            CHECK(fabs(fg / want - 1.0) < 0.01, "GPU flux %d %.5f, closed form %.5f", k, fg, want);
            CHECK(fabs(fr / want - 1.0) < 0.01, "reference flux %d %.5f, closed form %.5f", k, fr, want);
        }
        test_write_light_map("caustics_thin_gpu.png", gpu, 4, MAP, 0.8f);
        test_write_light_map("caustics_thin_ref.png", ref_rgb, 3, MAP, 0.8f);
    }

    /* 4. the BVH's path (the exact method's material): every wall on the line, here the same two */
    g.material.method = SNELL_METHOD_EXACT;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(strstr(fs.caustics_reason, "1 BVH, 0 depth maps") != NULL, "exact: %s", fs.caustics_reason);
    CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu2, &size));
    {
        double db = test_light_map_psnr(gpu2, 4, ref_rgb, MAP * MAP, 0.8f), se = 0;
        for (i = 0; i < MAP * MAP * 4; i++)
            if (i % 4 != 3) se += pow(gpu2[i] - gpu[i], 2.0);
        printf("BVH path: %.2f dB against the reference, light map %.2f dB against the depth maps'\n", db,
               10.0 * log10(3.0 * MAP * MAP / se));
        CHECK(db >= 40.0, "BVH path PSNR %.2f dB", db);
        CHECK(10.0 * log10(3.0 * MAP * MAP / se) >= 40.0, "BVH against maps %.2f dB", 10.0 * log10(3.0 * MAP * MAP / se));
    }
    g.material.method = SNELL_METHOD_AUTO;

    /* 5. a spot light 5 above the sphere's centre: its photons leave it along the maps' texels */
    {
        snell_frame_desc sp = fd;
        sp.light.type = SNELL_LIGHT_SPOT;
        sp.light.position[0] = 0.3f, sp.light.position[1] = 6.2f, sp.light.position[2] = 0.0f;
        sp.light.direction[0] = 0.0f, sp.light.direction[1] = -1.0f, sp.light.direction[2] = 0.0f;
        sp.light.spot_angle = 0.5f;
        sp.light.color[0] = sp.light.color[1] = sp.light.color[2] = 25.0f;
        CHECK_OK_CTX(ctx, snell_render(r, &sp, &fs));
        CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu2, &size));
        CHECK_OK(snell_ref_receiver_render(ref, &sp.light, &sp.receiver, 512, 2, ref_rgb, ref_c));
        {
            double db = test_light_map_psnr(gpu2, 4, ref_rgb, MAP * MAP, 0.8f);
            printf("spot: receiver PSNR against the reference %.2f dB\n", db);
            CHECK(fs.caustics_photons > 0 && db >= 40.0, "spot: %d photons, PSNR %.2f dB", fs.caustics_photons, db);
        }
    }

    /* 6. a standing torus, thin-walled: lines through its hole's sides cross four walls */
    {
        float tm[16] = {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1.6f, 0, 1};
        snell_ref *ref_t = NULL;
        snell_frame_desc tf = fd;
        double fg, fr, f2;
        float *cap_rgb = (float *)calloc((size_t)MAP * MAP * 3, sizeof(float));
        g.mesh = torus;
        g.model = tm;
        tf.light.direction[0] = 0.0f, tf.light.direction[1] = -1.0f;
        CHECK_OK_CTX(ctx, snell_render(r, &tf, &fs));
        CHECK(strstr(fs.caustics_reason, "1 BVH, 0 depth maps") != NULL, "torus: %s", fs.caustics_reason);
        CHECK_OK_CTX(ctx, snell__caustics_read(ctx, snell__renderer_caustics(r), gpu2, &size));
        CHECK_OK(test_ref_create(NULL, &tf, &ref_t));
        if (ref_t && cap_rgb) {
            double db, db2;
            CHECK_OK(snell_ref_receiver_render(ref_t, &tf.light, &tf.receiver, 512, 2, ref_rgb, ref_c));
            db = test_light_map_psnr(gpu2, 4, ref_rgb, MAP * MAP, 0.8f);
            fr = map_flux(ref_c, 3, 2);
            for (i = 0; i < MAP * MAP; i++) gpu[4 * i + 2] = gpu2[4 * i + 2] - (ref_rgb[3 * i + 2] - ref_c[3 * i + 2]);
            fg = map_flux(gpu, 4, 2);
            g.material.exact.max_interfaces = 2; /* the reference crossing two walls only */
            CHECK_OK(snell_ref_set_material(ref_t, 0, &g.material));
            CHECK_OK(snell_ref_receiver_render(ref_t, &tf.light, &tf.receiver, 512, 2, cap_rgb, ref_c));
            f2 = map_flux(ref_c, 3, 2);
            db2 = test_light_map_psnr(cap_rgb, 3, ref_rgb, MAP * MAP, 0.8f);
            g.material.exact.max_interfaces = 0;
            printf("torus: receiver PSNR against the reference %.2f dB (the two-wall reference against it %.2f dB); "
                   "blue flux through glass GPU %.5f reference %.5f, two walls %.5f\n", db, db2, fg, fr, f2);
            CHECK(db >= 40.0 && db >= db2 + 3.0, "torus PSNR %.2f dB (two walls %.2f)", db, db2);
            CHECK(fabs(fg / fr - 1.0) < 0.01 && f2 / fr > 1.5, "torus flux GPU %.5f reference %.5f two walls %.5f", fg,
                  fr, f2);
        }
        free(cap_rgb);
        snell_ref_destroy(ref_t);
        g.mesh = sphere;
        g.model = model;
    }

    /* 7. an opaque box under it, straight down: all the light through glass
     * lands on the box's top, which faces the light; its caustic map's flux
     * (per light-frame texel area) against the closed form and the reference */
    {
        snell_mesh *cube = NULL;
        snell_shape_desc cd = {SNELL_SHAPE_CUBE, 0, 0};
        float box[16] = {1.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1.5f, 0, 0, -0.5f, 0, 1}; /* [-1.5, 1.5] x [-1, 0] */
        float *map = (float *)calloc((size_t)512 * 512 * 4, sizeof(float));
        snell_opaque op;
        snell_frame_desc of = fd;
        snell_ref *ref_o = NULL;
        CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &cd, &cube));
        memset(&op, 0, sizeof op);
        op.mesh = cube, op.model = box;
        of.opaque = &op, of.opaque_count = 1;
        of.receiver.extent = 0.0f;
        of.light.direction[0] = 0.0f, of.light.direction[1] = -1.0f;
        CHECK_OK_CTX(ctx, snell_render(r, &of, &fs));
        CHECK_OK(test_ref_create(NULL, &of, &ref_o));
        if (cube && map && ref_o) {
            int rs = 0, n = 0;
            double ra = 0.0;
            const double *rm;
            CHECK_OK(snell_ref_set_light(ref_o, &of.light, &of.receiver, 512));
            rm = snell__ref_lit_map(ref_o, &rs, &ra);
            CHECK_OK_CTX(ctx, snell__caustics_read_opaque(ctx, snell__renderer_caustics(r), map, &n));
            CHECK(rm && n == rs, "caustic maps %d and %d texels a side", n, rs);
            for (k = 0; k < 3 && rm && n == rs; k++) {
                double eg = 0.0, er = 0.0, want = sphere_flux(k);
                for (i = 0; i < n * n; i++) eg += map[4 * i + k] * ra, er += rm[3 * i + k] * ra;
                printf("on the box, channel %d flux through glass: GPU %.5f reference %.5f closed form %.5f\n", k, eg,
                       er, want);
                CHECK(fabs(eg / want - 1.0) < 0.01 && fabs(er / want - 1.0) < 0.01,
                      "box channel %d: GPU %.5f reference %.5f closed form %.5f", k, eg, er, want);
            }
        }
        snell_ref_destroy(ref_o);
        snell_mesh_destroy(cube);
        free(map);
    }

    /* 8. a clear thin wall changes no light: it casts nothing */
    {
        snell_glass clear = g;
        snell_frame_desc cf = fd;
        memset(&clear.material, 0, sizeof clear.material);
        clear.material.ior = 1.0f;
        clear.material.thickness = (float)kThick;
        cf.glass = &clear;
        CHECK_OK_CTX(ctx, snell_render(r, &cf, &fs));
        CHECK(fs.caustics_photons == 0 && strstr(fs.caustics_reason, "made: 0 glass casting (clear ones pass)"),
              "clear: %s", fs.caustics_reason);
    }

    free(gpu), free(gpu2), free(ref_rgb), free(ref_c);
    snell_ref_destroy(ref);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(torus);
    snell_ctx_destroy(ctx);
    return test_finish();
}
