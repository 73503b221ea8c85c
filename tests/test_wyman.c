/* SPDX-License-Identifier: MIT */
/* test_wyman — the image-space two-surface method (Wyman 2005, methods/wyman.c).
 *
 * 1. Sphere (radius 1, IOR 1.5): against a CPU twin of Wyman's model on the
 *    analytic sphere, and against the reference tracer (MATCHED, 2
 *    interfaces). On a sphere every step of the method is exact except one:
 *    the entry (P1, N1, T1), d_V (the view ray's chord 2 cos th_i), d_N (the
 *    diameter, 2) and the back-face normal at P2's projection (the far hit of
 *    the view ray through P2's pixel) are what the twin computes in closed
 *    form; the interpolated d = (th_t/th_i) d_V + (1 - th_t/th_i) d_N is not
 *    the true chord 2 cos th_t (at th_i = 60 degrees it is 1.41 instead of
 *    1.63), and where P2 lands on the front half as the eye sees it the far
 *    hit is not P2. So the method's error against the reference is the
 *    twin's error, in closed form per pixel, plus the implementation's: mesh
 *    facets (64x32 UV sphere: positions within 1.2e-3, interpolated normals
 *    within ~2e-3 rad), the 16+16-bit octahedral normals (below 4e-5 rad) and
 *    24-bit depth of the maps, float arithmetic, and the pixel the
 *    projection of P2 snaps to: where P2 lies near a pixel border the GPU and
 *    the twin may pick neighbouring pixels, whose back normals differ by one
 *    pixel's angle (1/58 rad here) times the refraction gain (~2.5), about
 *    0.04 rad. Near the silhouette (incidence above 60 degrees) the facets
 *    matter far more: the refraction's gain grows as 1/cos th_t and P2 lands
 *    near the switches of the model (TIR at the exit, the silhouette fallback)
 *    where a facet-sized offset flips the branch; measured there 0.015-0.07
 *    rad mean. Required where the incidence is at most 60 degrees (chord >=
 *    1): 95% of the pixels within 0.01 rad of the twin (facets and
 *    quantisation times a gain of 2.5, with margin; measured 96-97%: the rest
 *    are the pixel-snapping ties) and the mean below 0.004 rad (measured
 *    0.0005-0.005 by band); over all the glass, the mean error against the
 *    reference within 10% of the twin's (the model error is what the method
 *    has, nothing more; measured 0.2143 vs 0.2107 rad) and below 0.75 x
 *    single's (0.33 rad).
 * 2b. The goblet (hidden 0.97: thin bowl walls, a view ray crosses 4
 *    surfaces) is the seed's stated limit: the farthest back face is the far
 *    wall, not where light leaves the near one; wyman is worse than single
 *    there (0.56 vs 0.46 rad), which is why its fit() is only RUNS above the
 *    cubemap's hidden-fraction threshold. Checked: it stays below 1.5 x.
 * 2. Torus (concave, not star-shaped: hidden fraction 0.45): the mean
 *    exit-direction error against the reference over the glass pixels must
 *    be well below single-surface's (the point of it; measured 0.32x).
 * 3. The back-face pass: absent in frames without the method, one pass for
 *    several objects that need it, d_N prepared once per mesh version. */
#include "test_util.h"
#include "test_twin.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 160
#define H 160

/* Wyman's model on the analytic unit sphere for pixel (x, y); 0 on a miss.
 * *fallback: P2 projected outside the silhouette (the paper's side normal). */
static int twin(const camera_d *c, int x, int y, double ior, double out[3], int *fallback)
{
    double v[3], p1[3], n[3], t1[3], t0, tf, p2[3], n2[3], q[4], d, w, th_i, th_t, dv;
    int k, qx, qy, back = 0;
    pixel_ray(c, x, y, v);
    if (!sphere_hits(c->eye, v, &t0, &tf)) return 0;
    for (k = 0; k < 3; k++) {
        p1[k] = c->eye[k] + t0 * v[k];
        n[k] = p1[k];
    }
    refract(v, n, 1.0 / ior, t1);
    normalize3(t1);
    dv = tf - t0;
    th_i = acos(fmin(fmax(-dot3(v, n), 0.0), 1.0));
    th_t = acos(fmin(fmax(-dot3(t1, n), 0.0), 1.0));
    w = th_i > 1e-3 ? th_t / th_i : 1.0 / ior;
    d = w * dv + (1.0 - w) * 2.0;
    for (k = 0; k < 3; k++) p2[k] = p1[k] + d * t1[k];
    for (k = 0; k < 4; k++) {
        const float *m = c->view_proj;
        q[k] = m[k] * p2[0] + m[4 + k] * p2[1] + m[8 + k] * p2[2] + m[12 + k];
    }
    qx = (int)floor((q[0] / q[3] * 0.5 + 0.5) * W);
    qy = H - 1 - (int)floor((q[1] / q[3] * 0.5 + 0.5) * H);
    if (q[3] > 0.0 && qx >= 0 && qx < W && qy >= 0 && qy < H) {
        double r[3];
        pixel_ray(c, qx, qy, r);
        if (sphere_hits(c->eye, r, &t0, &tf)) {
            for (k = 0; k < 3; k++) n2[k] = c->eye[k] + tf * r[k];
            back = 1;
        }
    }
    *fallback = !back;
    if (!back) {
        for (k = 0; k < 3; k++) n2[k] = t1[k] - dot3(t1, v) * v[k];
        normalize3(n2);
    }
    if (dot3(n2, t1) > 0.0)
        for (k = 0; k < 3; k++) n2[k] = -n2[k];
    refract(t1, n2, ior, out);
    normalize3(out);
    return 1;
}

static void render_dirs(snell_ctx *ctx, snell_frame_desc *fd, snell_glass *g, snell_method m, float *dirs,
                        snell_frame_stats *stats)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r) return;
    g->material.method = m;
    CHECK_OK_CTX(ctx, snell_render(r, fd, stats));
    CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
    snell_renderer_destroy(r);
}

static void test_sphere(snell_ctx *ctx, snell_env *env)
{
    static float gpu[W * H * 3], ref_dir[W * H * 3], rgb[W * H * 3], single[W * H * 3];
    static uint8_t hit[W * H];
    snell_shape_desc sd;
    snell_mesh *mesh = NULL;
    snell_frame_desc fd;
    snell_glass g;
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_frame_stats stats;
    camera_d cam;
    int i, glass = 0, close = 0, central = 0, fallbacks = 0;
    double sum_twin = 0.0, sum_gpu_ref = 0.0, sum_twin_ref = 0.0, sum_single = 0.0, worst = 0.0;

    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    if (!mesh) return;
    test_frame_one(&fd, &g, mesh, env);
    fd.camera.azimuth = 0.4f;
    fd.camera.elevation = 0.3f;
    camera_setup(&fd.camera, W, H, &cam);
    render_dirs(ctx, &fd, &g, SNELL_METHOD_WYMAN, gpu, &stats);
    CHECK(stats.glass[0].method_used == SNELL_METHOD_WYMAN && stats.back_face_pass == 1, "method %d, back pass %d",
          (int)stats.glass[0].method_used, stats.back_face_pass);
    render_dirs(ctx, &fd, &g, SNELL_METHOD_SINGLE, single, &stats);
    CHECK(stats.back_face_pass == 0, "single ran the back-face pass");
    g.material.method = SNELL_METHOD_WYMAN;
    CHECK_OK(test_ref_create(ctx, &fd, &ref));
    if (!ref) goto out;
    test_ref_params(&fd, W, H, 2, &p);
    CHECK_OK(test_ref_render(ref, &p, rgb, ref_dir, hit));
    for (i = 0; i < W * H; i++) {
        double t[3], e;
        int fb;
        if (!hit[i] || !twin(&cam, i % W, i / W, 1.5, t, &fb)) continue;
        glass++;
        fallbacks += fb;
        e = angle(gpu + 3 * i, t);
        {
            double v[3], t0 = 0.0, tf = 0.0;
            pixel_ray(&cam, i % W, i / W, v);
            sphere_hits(cam.eye, v, &t0, &tf);
            if (tf - t0 >= 1.0) { /* the chord is 2 cos th_i: th_i <= 60 degrees */
                central++;
                sum_twin += e;
                close += e < 0.01;
                worst = fmax(worst, e);
            }
        }
        sum_gpu_ref += anglef(gpu + 3 * i, ref_dir + 3 * i);
        sum_twin_ref += angle(ref_dir + 3 * i, t);
        sum_single += anglef(single + 3 * i, ref_dir + 3 * i);
    }
    printf("sphere: %d glass px, %d with incidence <= 60 deg; there wyman vs twin: mean %.5f rad, %.1f%% within "
           "0.01, worst %.3f; all glass vs reference: wyman %.4f rad, twin (the model) %.4f, single %.4f\n",
           glass, central, sum_twin / central, 100.0 * close / central, worst, sum_gpu_ref / glass,
           sum_twin_ref / glass, sum_single / glass);
    /* How often the paper's fallback normal is used (P2 off the silhouette):
     * GLES 3.0 occlusion queries only say whether any sample passed, so the
     * renderer cannot count it per frame without a read-back; the twin does. */
    printf("sphere: the silhouette fallback serves %d of %d glass px (%.1f%%)\n", fallbacks, glass,
           100.0 * fallbacks / glass);
    CHECK(glass > W * H / 8, "sphere must cover the image (%d px)", glass);
    CHECK(central > glass / 2, "%d of %d pixels central", central, glass);
    CHECK(close >= 0.95 * central, "only %d of %d pixels within 0.01 rad of the twin", close, central);
    CHECK(sum_twin / central < 0.004, "mean distance to the twin %g rad", sum_twin / central);
    CHECK(fabs(sum_gpu_ref - sum_twin_ref) < 0.1 * sum_twin_ref, "error vs reference %g, the model's %g",
          sum_gpu_ref / glass, sum_twin_ref / glass);
    /* the model's own error (the twin's, 0.21 rad here) is two thirds of single's (0.33) */
    CHECK(sum_gpu_ref < 0.75 * sum_single, "wyman %g vs single %g", sum_gpu_ref / glass, sum_single / glass);
out:
    snell_ref_destroy(ref);
    snell_mesh_destroy(mesh);
}

/* Mean exit-direction error of wyman and single against the reference (2 interfaces). */
static void test_concave(snell_ctx *ctx, snell_env *env, snell_shape shape, const char *name, double ratio)
{
    static float gpu[W * H * 3], ref_dir[W * H * 3], rgb[W * H * 3], single[W * H * 3];
    static uint8_t hit[W * H];
    snell_shape_desc sd;
    snell_mesh *mesh = NULL;
    snell_frame_desc fd;
    snell_glass g;
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_frame_stats stats;
    int i, glass = 0;
    double sum_w = 0.0, sum_s = 0.0;

    memset(&sd, 0, sizeof sd);
    sd.shape = shape;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    if (!mesh) return;
    CHECK_OK(snell_mesh_normalize(mesh, 1.0f));
    test_frame_one(&fd, &g, mesh, env);
    fd.camera.azimuth = 0.3f;
    fd.camera.elevation = 0.5f;
    render_dirs(ctx, &fd, &g, SNELL_METHOD_WYMAN, gpu, &stats);
    render_dirs(ctx, &fd, &g, SNELL_METHOD_SINGLE, single, &stats);
    CHECK_OK(test_ref_create(ctx, &fd, &ref));
    if (!ref) goto out;
    test_ref_params(&fd, W, H, 2, &p);
    CHECK_OK(test_ref_render(ref, &p, rgb, ref_dir, hit));
    for (i = 0; i < W * H; i++) {
        if (!hit[i]) continue;
        glass++;
        sum_w += anglef(gpu + 3 * i, ref_dir + 3 * i);
        sum_s += anglef(single + 3 * i, ref_dir + 3 * i);
    }
    printf("%s: %d glass px; mean error vs reference: wyman %.4f rad, single %.4f rad (ratio %.2f)\n", name, glass,
           sum_w / glass, sum_s / glass, sum_w / sum_s);
    CHECK(glass > W * H / 20, "%s must cover the image (%d px)", name, glass);
    CHECK(sum_w < ratio * sum_s, "%s: wyman %g not below %.2f x single %g", name, sum_w / glass, ratio,
          sum_s / glass);
out:
    snell_ref_destroy(ref);
    snell_mesh_destroy(mesh);
}

/* The back-face pass runs only in frames that use it, once for all objects. */
static void test_pass_sharing(snell_ctx *ctx, snell_env *env)
{
    snell_shape_desc sd;
    snell_mesh *mesh = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_glass g[3];
    snell_frame_stats s1, s2;
    float models[3][16];
    int i, k;
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    memset(&rd, 0, sizeof rd);
    rd.width = 96;
    rd.height = 64;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!mesh || !r) goto out;
    memset(&fd, 0, sizeof fd);
    memset(g, 0, sizeof g);
    for (i = 0; i < 3; i++) {
        for (k = 0; k < 16; k++) models[i][k] = k % 5 == 0 ? 0.5f : 0.0f;
        models[i][12] = -1.2f + 1.2f * (float)i;
        models[i][15] = 1.0f;
        g[i].mesh = mesh;
        g[i].model = models[i];
        g[i].material.method = i == 1 ? SNELL_METHOD_SINGLE : SNELL_METHOD_WYMAN;
    }
    fd.env = env;
    fd.glass = g;
    fd.camera.distance = 4.0f;
    fd.glass_count = 3;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &s1));
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &s2));
    CHECK(s1.back_face_pass == 1 && s2.back_face_pass == 1, "back pass %d %d", s1.back_face_pass, s2.back_face_pass);
    CHECK(s1.glass[0].prepared == 1 && s2.glass[0].prepared == 0 && (s2.glass[0].skipped & SNELL_SKIP_PREPARE) &&
              (s2.glass[2].skipped & SNELL_SKIP_PREPARE),
          "d_N prepared %d then %d (skipped 0x%x, 0x%x)", s1.glass[0].prepared, s2.glass[0].prepared,
          s2.glass[0].skipped, s2.glass[2].skipped);
    /* wyman objects: back-face pass + kernel (+ G-buffer in screen space); single: kernel (+ G-buffer) */
    for (i = 0; i < 3; i++) {
        int want = (i == 1 ? 1 : 2) + s2.glass[i].screen_space;
        CHECK(s2.glass[i].passes == want, "glass %d: %d passes, want %d", i, s2.glass[i].passes, want);
    }
    g[0].material.method = g[2].material.method = SNELL_METHOD_SINGLE;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &s1));
    CHECK(s1.back_face_pass == 0, "back-face pass ran in a frame without wyman");
out:
    snell_renderer_destroy(r);
    snell_mesh_destroy(mesh);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 128);
    if (!env) return test_finish();
    test_pass_sharing(ctx, env);
    test_sphere(ctx, env);
    test_concave(ctx, env, SNELL_SHAPE_TORUS, "torus", 0.75);
    test_concave(ctx, env, SNELL_SHAPE_GOBLET, "goblet", 1.5);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
