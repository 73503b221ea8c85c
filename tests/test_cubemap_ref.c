/* SPDX-License-Identifier: MIT */
/* test_cubemap_ref — the cubemap method on the cube [-1,1]^3 (flat faces: many
 * internal reflections) at IOR 1.5 and at IOR 2.42 (diamond: TIR-heavy),
 * against the reference in MATCHED mode with the same max_interfaces.
 *
 * Per-pixel bound, from the reference path of the pixel (entry exact, as in
 * the single-surface method): on a flat face the stored normal is exact up to
 * quantisation q (C twin, pack.h), so each later interface adds a normal
 * error q, which turns the outgoing direction by G*q (reflection G = 2;
 * refraction G = 1 + eta cos(i)/cos(t)) and passes earlier direction errors
 * on with A = 1 (reflection) or max(eta, eta cos(i)/cos(t)) (refraction).
 * Excluded are pixels where that reasoning does not hold:
 *  - an interface point within a margin of a cube edge (the texel there can
 *    hold the other face: margin = texel footprint + search bracket + the
 *    direction error so far times the distance travelled + the distance
 *    quantisation stretched by the ray's slant, slant limited below);
 *  - an interface within the accumulated error of the critical angle (TIR
 *    may flip); a ray more slanted than cos 0.3 against the centre direction.
 * Required: all remaining pixels within their bound, and the remaining
 * pixels are most of the glass (else the test would test nothing); the
 * method's mean error over ALL glass pixels must be far below that of the
 * single-surface method against the same reference (the point of it). */
#include "test_util.h"
#include "core/pack.h"
#include "snell/snell_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 160
#define H 160

static double max_quant(snell_ndcube_encoding enc)
{
    double worst = 0.0;
    int i, j;
    for (i = 0; i <= 200; i++)
        for (j = 0; j < 400; j++) {
            double th = 3.14159265358979 * i / 200.0, ph = 6.28318530717959 * j / 400.0;
            float n[3] = {(float)(sin(th) * cos(ph)), (float)cos(th), (float)(sin(th) * sin(ph))}, m[3], d;
            uint8_t px[4];
            if (enc == SNELL_NDCUBE_PLAIN) {
                snell_pack_ndist_plain(n, 0.5f, px);
                snell_unpack_ndist_plain(px, m, &d);
            } else {
                snell_pack_ndist_oct(n, 0.5f, px);
                snell_unpack_ndist_oct(px, m, &d);
            }
            worst = fmax(worst, test_dir_angle(n, m));
        }
    /* axis normals (the cube's) exactly */
    {
        float n[3] = {0, 0, 1}, m[3], d;
        uint8_t px[4];
        if (enc == SNELL_NDCUBE_PLAIN) {
            snell_pack_ndist_plain(n, 0.5f, px);
            snell_unpack_ndist_plain(px, m, &d);
        } else {
            snell_pack_ndist_oct(n, 0.5f, px);
            snell_unpack_ndist_oct(px, m, &d);
        }
        worst = fmax(worst, test_dir_angle(n, m));
    }
    return worst;
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Distance of p (on the cube surface) to the nearest edge: the second
 * largest |coordinate| is how far the point is from leaving its face. */
static double edge_distance(const double p[3])
{
    double a[3] = {fabs(p[0]), fabs(p[1]), fabs(p[2])}, t;
    int i, j;
    for (i = 0; i < 2; i++)
        for (j = 0; j < 2 - i; j++)
            if (a[j] < a[j + 1]) { t = a[j]; a[j] = a[j + 1]; a[j + 1] = t; }
    return 1.0 - a[1];
}

static void run(snell_ctx *ctx, snell_mesh *cube, snell_env *env, float ior, int interfaces,
                snell_ndcube_encoding enc, int N, int K)
{
    static float gpu[W * H * 3], ref_dir[W * H * 3], rgb[W * H * 3], single[W * H * 3];
    static uint8_t hit[W * H];
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_glass g;
    snell_ref *ref = NULL;
    snell_ref_params p;
    double q = max_quant(enc), eta = ior, R = sqrt(3.0);
    double dq = enc == SNELL_NDCUBE_PLAIN ? 0.5 / 255.0 : 0.5 / 65535.0;
    double bracket = fmax(2.0 * R / pow(2.0, K), 0.943 / N * R);
    int i, glass = 0, checked = 0, over = 0, tir_px = 0;
    double sum_c = 0.0, sum_s = 0.0, worst = 0.0;

    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    test_frame_one(&fd, &g, cube, env);
    g.material.method = SNELL_METHOD_CUBEMAP;
    g.material.ior = ior;
    g.material.cubemap.encoding = enc;
    g.material.cubemap.face_size = N;
    g.material.cubemap.iterations = K;
    g.material.cubemap.max_interfaces = interfaces;
    fd.camera.azimuth = 0.6f;
    fd.camera.elevation = 0.45f;
    fd.camera.distance = 5.0f;
    CHECK_OK(test_ref_create(ctx, &fd, &ref));
    if (!r || !ref) goto out;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_exit_dirs(r, gpu));
    g.material.method = SNELL_METHOD_SINGLE;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_exit_dirs(r, single));

    test_ref_params(&fd, W, H, interfaces, &p);
    CHECK_OK(test_ref_render(ref, &p, rgb, ref_dir, hit));

    for (i = 0; i < W * H; i++) {
        snell_ref_path path;
        double err = 0.0, travelled = 0.0, e;
        int k, excluded = 0, had_tir = 0;
        if (!hit[i]) continue;
        glass++;
        e = test_dir_angle(gpu + 3 * i, ref_dir + 3 * i);
        sum_c += e;
        sum_s += test_dir_angle(single + 3 * i, ref_dir + 3 * i);
        CHECK_OK(snell_ref_trace_pixel(ref, &p, i % W, i / W, &path));
        for (k = 2; k <= path.interfaces && !excluded; k++) {
            const double *a = path.points[k - 1], *b = path.points[k];
            double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, len = sqrt(dot3(d, d)), n[3] = {0, 0, 0};
            double cos_i, sin_i, slant, margin, G, A;
            int ax = fabs(b[0]) >= fabs(b[1]) && fabs(b[0]) >= fabs(b[2]) ? 0 : (fabs(b[1]) >= fabs(b[2]) ? 1 : 2);
            travelled += len;
            n[ax] = b[ax] > 0 ? 1.0 : -1.0;
            cos_i = fabs(dot3(d, n)) / len;
            sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
            slant = fabs(dot3(d, b)) / (len * sqrt(dot3(b, b)));
            if (slant < 0.3) { excluded = 1; break; }
            margin = 2.0 * sqrt(2.0) / N * sqrt(dot3(b, b)) + bracket + err * travelled + dq * R / slant;
            if (edge_distance(b) < margin) { excluded = 1; break; }
            /* TIR may flip if the incidence is within the normal error of critical */
            if (fabs(asin(fmin(1.0, sin_i)) - asin(1.0 / eta)) < 2.0 * (q + err)) { excluded = 1; break; }
            if (path.events[k] == SNELL_REF_EVENT_TIR) {
                G = 2.0;
                A = 1.0;
                had_tir = 1;
            } else {
                double cos_t = sqrt(fmax(1e-12, 1.0 - eta * eta * sin_i * sin_i));
                G = 1.0 + eta * cos_i / cos_t;
                A = fmax(eta, eta * cos_i / cos_t);
            }
            err = err * A + G * q;
        }
        if (excluded) continue;
        checked++;
        tir_px += had_tir;
        /* + 2e-4: float rounding of the GPU path (highp) */
        if (e > err + 2e-4) over++;
        worst = fmax(worst, e - err);
    }
    printf("cube ior %.2f, %d interfaces, %s N=%d K=%d: %d glass px, %d checked (%d with TIR), %d over bound "
           "(worst excess %.4f rad); mean error cubemap %.4f rad vs single %.4f rad\n",
           ior, interfaces, enc == SNELL_NDCUBE_PLAIN ? "plain" : "oct", N, K, glass, checked, tir_px, over, worst,
           sum_c / glass, sum_s / glass);
    CHECK(glass > W * H / 10, "cube must cover the image");
    CHECK(checked > glass / 3, "the bound must apply to a good share of the glass (%d of %d)", checked, glass);
    CHECK(tir_px > checked / 20, "the case must exercise internal reflection (%d px)", tir_px);
    CHECK(over == 0, "%d pixels above their bound", over);
    CHECK(sum_c < 0.5 * sum_s, "cubemap must be far closer to the reference than single (%g vs %g)", sum_c / glass,
          sum_s / glass);
out:
    snell_ref_destroy(ref);
    snell_renderer_destroy(r);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_mesh *cube = NULL;
    snell_env *env = NULL;
    snell_shape_desc sd;
    if (!ctx) SKIP("no GL context");
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &cube));
    env = test_sky(ctx, 128);
    if (!cube || !env) return test_finish();
    run(ctx, cube, env, 1.5f, 3, SNELL_NDCUBE_OCT, 256, 8);
    run(ctx, cube, env, 1.5f, 3, SNELL_NDCUBE_PLAIN, 256, 8);
    run(ctx, cube, env, 2.42f, 4, SNELL_NDCUBE_OCT, 256, 12);
    snell_env_destroy(env);
    snell_mesh_destroy(cube);
    snell_ctx_destroy(ctx);
    return test_finish();
}
