/* SPDX-License-Identifier: MIT */
/* test_cubemap — the cubemap method (Unger 4.1) on a sphere, where every
 * error term can be bounded:
 *  1. packing twin: the exact worst-case normal quantisation of both
 *     encodings (src/core/pack.h), found by brute force over many unit vectors;
 *  2. bake: every texel of the baked normal+distance cubemap (read back)
 *     against a CPU ray cast from the centre through the texel centre (the
 *     farthest hit, via the BVH), within one quantisation step (+ float);
 *  3. max_interfaces = 1 is the single-surface method: same exit directions;
 *  4. exit directions vs the reference (MATCHED, 2 interfaces, same mesh)
 *     below a bound derived from face size N and iterations K, for pixels
 *     whose entry incidence angle is at most 60 degrees (see bound());
 *  5. the image shows the bent, upside-down view (floor seen in the top half);
 *  6. prepared resources (the bakes) are cached per (mesh version, settings)
 *     for the whole scene: five meshes in a frame bake once, then never.
 */
#include "test_util.h"
#include "core/gl.h"
#include "mesh/mesh.h"
#include "frame/ndcube.h"
#include "core/pack.h"
#include "mesh/bvh.h"
#include "frame/env.h"
#include "snell/snell_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 160
#define H 160

/* 1. Worst normal quantisation angle of an encoding over a fine sphere grid
 * (plus the axes, where PLAIN's 127.5 rounds away from 0). */
static double max_quant(snell_ndcube_encoding enc)
{
    double worst = 0.0;
    int i, j;
    for (i = 0; i <= 400; i++)
        for (j = 0; j < 800; j++) {
            double th = SNELL_PI * i / 400.0, ph = 2.0 * SNELL_PI * j / 800.0;
            float n[3] = {(float)(sin(th) * cos(ph)), (float)cos(th), (float)(sin(th) * sin(ph))}, m[3], d;
            uint8_t px[4];
            if (enc == SNELL_NDCUBE_PLAIN) {
                snell_pack_ndist_plain(n, 0.5f, px);
                snell_unpack_ndist_plain(px, m, &d);
            } else {
                snell_pack_ndist_oct(n, 0.5f, px);
                snell_unpack_ndist_oct(px, m, &d);
            }
            if (test_dir_angle(n, m) > worst) worst = test_dir_angle(n, m);
        }
    return worst;
}

/* 2. Bake check. */
static void check_bake(snell_ctx *ctx, snell_mesh *mesh, snell_ndcube_encoding enc, int N)
{
    snell__ndcube_baker b;
    snell__ndcube cube;
    snell__bvh *bvh = NULL;
    snell_mesh_analysis an;
    uint8_t *face_px = (uint8_t *)malloc((size_t)4 * N * N);
    int f, i, j, bad = 0, total = 0;
    double worst_d = 0.0, worst_n = 0.0, tol_d, tol_n;
    memset(&cube, 0, sizeof cube);
    CHECK_OK(snell_mesh_analyze(mesh, &an));
    CHECK_OK(snell__mesh_upload(mesh));
    CHECK_OK(snell__ndcube_baker_create(ctx, &b));
    CHECK_OK(snell__ndcube_bake(ctx, &b, mesh, an.centre, an.radius * 1.0001f, N, enc, &cube));
    CHECK_OK(snell__bvh_build_mesh(NULL, mesh, NULL, &bvh));
    if (!bvh || !face_px || !cube.texture) goto out;
    /* Distance: half a step of the stored precision, plus float rounding of
     * the GPU's interpolation (1e-5 of the radius). Normal: the quantisation
     * bound plus the same float slack. */
    tol_d = (enc == SNELL_NDCUBE_PLAIN ? 0.5 / 255.0 : 0.5 / 65535.0) + 1e-5;
    tol_n = max_quant(enc) + 1e-4;
    for (f = 0; f < 6; f++) {
        CHECK_OK(snell__ndcube_read_face(ctx, &b, &cube, f, face_px));
        for (j = 0; j < N; j++)
            for (i = 0; i < N; i++) {
                double dir[3], org[3] = {an.centre[0], an.centre[1], an.centre[2]}, tmin = 0.0;
                uint32_t skip = SNELL__BVH_NONE;
                snell__bvh_hit h, last;
                int any = 0, k;
                float n[3] = {0, 0, 0}, gn[3], gd, ed;
                snell__cube_dir(f, (i + 0.5) / N, (j + 0.5) / N, dir);
                while (snell__bvh_closest(bvh, org, dir, tmin, HUGE_VAL, skip, &h)) {
                    last = h;
                    any = 1;
                    tmin = h.t;
                    skip = h.tri;
                }
                if (!any) continue;
                for (k = 0; k < 3; k++) {
                    const uint32_t *tri = mesh->indices + 3 * last.tri;
                    n[k] = (float)(last.b[0] * mesh->normals[3 * tri[0] + k] + last.b[1] * mesh->normals[3 * tri[1] + k] +
                                   last.b[2] * mesh->normals[3 * tri[2] + k]);
                }
                {
                    float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                    n[0] /= l; n[1] /= l; n[2] /= l;
                }
                ed = (float)(last.t / (an.radius * 1.0001f)); /* |dir| = 1 */
                if (enc == SNELL_NDCUBE_PLAIN) snell_unpack_ndist_plain(face_px + 4 * ((size_t)j * N + i), gn, &gd);
                else snell_unpack_ndist_oct(face_px + 4 * ((size_t)j * N + i), gn, &gd);
                total++;
                if (fabs(gd - ed) > worst_d) worst_d = fabs(gd - ed);
                if (test_dir_angle(gn, n) > worst_n) worst_n = test_dir_angle(gn, n);
                bad += fabs(gd - ed) > tol_d || test_dir_angle(gn, n) > tol_n;
            }
    }
    printf("bake %s N=%d: %d texels, worst distance error %.3g (tol %.3g), worst normal %.4f rad (tol %.4f), %d outside\n",
           enc == SNELL_NDCUBE_PLAIN ? "plain" : "oct", N, total, worst_d, tol_d, worst_n, tol_n, bad);
    CHECK(total == 6 * N * N, "every texel of a closed mesh holds a surface (%d of %d)", total, 6 * N * N);
    /* Texels whose ray passes within float precision of a triangle edge may
     * take the neighbour triangle (same point, same interpolated normal up
     * to float): allow 0.1% of texels. */
    CHECK(bad <= total / 1000, "%d of %d texels outside the quantisation tolerance", bad, total);
out:
    snell__bvh_destroy(bvh);
    snell__ndcube_release(&cube);
    snell__ndcube_baker_destroy(&b);
    free(face_px);
}

/* 4. Error bound for the sphere (radius R = 1 about the centre), entry
 * incidence theta_e <= 60 deg, IOR eta = 1.5, 2 interfaces:
 *  - exit point along the ray: the bracket starts between the inner ball
 *    (radius r_in, less one 8-bit step: no surface inside) and the bounding
 *    sphere R_out, whose crossings are at most (R_out - r_in) / cos(theta_i)
 *    apart near the exit, and never more than the chord 2R; after K
 *    halvings it is that / 2^K, or the search stopped at one texel
 *    (0.943/N rad at radius R); the secant step lands inside it;
 *  - stored distance error dq (half a quantisation step) moves the point
 *    by dq / cos(theta_i), cos(theta_i) >= sqrt(1 - (sin60/1.5)^2) = 0.816;
 *  - a position error s turns the sphere's normal by at most s / R;
 *  - normal quantisation nq (max_quant) and, for GL_NEAREST (OCT), the offset
 *    of the texel centre: at most half a texel diagonal, sqrt(2)/N rad;
 *    GL_LINEAR (PLAIN) interpolates the normal field: error below
 *    (2/N)^2 / 8 (chord vs arc over a texel);
 *  - a normal error delta turns the refracted exit direction by at most
 *    delta * (1 + eta cos(theta_i) / cos(theta_t)); on a sphere theta_t =
 *    theta_e, so the gain is at most 1 + 1.5 / cos(60) = 4. */
static double bound(snell_ndcube_encoding enc, int N, int K, double bracket0)
{
    double bracket = fmax(bracket0 / pow(2.0, K), 0.943 / N);
    double dq = enc == SNELL_NDCUBE_PLAIN ? 0.5 / 255.0 : 0.5 / 65535.0;
    double pos = bracket + dq / 0.816;
    double texel = enc == SNELL_NDCUBE_PLAIN ? (2.0 / N) * (2.0 / N) / 8.0 : sqrt(2.0) / N;
    return 4.0 * (pos + max_quant(enc) + texel);
}

static void check_sphere(snell_ctx *ctx, snell_mesh *sphere, snell_env *env, snell_ndcube_encoding enc, int N, int K)
{
    static float gpu[W * H * 3], ref_dir[W * H * 3], rgb[W * H * 3], single[W * H * 3];
    static uint8_t hit[W * H];
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats fs;
    snell_ref *ref = NULL;
    snell_ref_params p;
    int i, n = 0, over = 0;
    double worst = 0.0, lim, worst1 = 0.0, r_out, r_in;
    snell_mesh_analysis an;
    CHECK_OK(snell_mesh_analyze(sphere, &an));
    r_out = an.radius * 1.0001; /* as methods/cubemap.c sets them */
    r_in = an.inner_radius - r_out / 255.0;
    lim = bound(enc, N, K, fmin(2.0, (r_out - r_in) / 0.816));
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    test_frame_one(&fd, &g, sphere, env);
    g.material.method = SNELL_METHOD_CUBEMAP;
    g.material.ior = 1.5f;
    g.material.cubemap.encoding = enc;
    g.material.cubemap.face_size = N;
    g.material.cubemap.iterations = K;
    g.material.cubemap.max_interfaces = 2;
    fd.camera.azimuth = 0.4f;
    fd.camera.elevation = 0.3f;
    fd.camera.distance = 3.0f;
    CHECK_OK(test_ref_create(ctx, &fd, &ref));
    if (!r || !ref) goto out;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(fs.glass[0].method_used == SNELL_METHOD_CUBEMAP && fs.glass[0].prepared == 1 &&
              !(fs.glass[0].skipped & SNELL_SKIP_PREPARE) && fs.glass[0].passes == 7 + fs.glass[0].screen_space,
          "first frame bakes (6 face passes + [G-buffer] + the kernel: %d passes)", fs.glass[0].passes);
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(fs.glass[0].prepared == 0 && (fs.glass[0].skipped & SNELL_SKIP_PREPARE) &&
              fs.glass[0].passes == 1 + fs.glass[0].screen_space,
          "second frame reuses the cubemap");
    CHECK_OK(snell_renderer_read_exit_dirs(r, gpu));

    /* 3. One interface = single surface. */
    g.material.cubemap.max_interfaces = 1;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK((fs.glass[0].skipped & SNELL_SKIP_SEARCH) && (fs.glass[0].skipped & SNELL_SKIP_PREPARE),
          "one interface without absorption: no search, the same bake (skipped 0x%x)", fs.glass[0].skipped);
    CHECK_OK(snell_renderer_read_exit_dirs(r, single));
    g.material.method = SNELL_METHOD_SINGLE;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_exit_dirs(r, rgb));
    for (i = 0; i < W * H; i++) worst1 = fmax(worst1, test_dir_angle(single + 3 * i, rgb + 3 * i));
    printf("max_interfaces 1 vs single: worst %.2g rad\n", worst1);
    /* single.frag is mediump (fp16 on some drivers: 2^-11 relative per
     * component, ~5e-4 rad per direction, up to twice that after Snell's law
     * at grazing entry); cubemap.frag is highp. */
    CHECK(worst1 < 2e-3, "max_interfaces 1 must equal the single-surface method (worst %g rad)", worst1);

    test_ref_params(&fd, W, H, 2, &p);
    CHECK_OK(test_ref_render(ref, &p, rgb, ref_dir, hit));
    for (i = 0; i < W * H; i++) {
        snell_ref_path path;
        double v[3], e, cos_e, len;
        int k;
        if (!hit[i]) continue;
        CHECK_OK(snell_ref_trace_pixel(ref, &p, i % W, i / W, &path));
        /* entry incidence: view ray vs the sphere's radial direction there */
        for (k = 0; k < 3; k++) v[k] = path.points[1][k] - path.points[0][k];
        len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        cos_e = -(v[0] * path.points[1][0] + v[1] * path.points[1][1] + v[2] * path.points[1][2]) /
                (len * sqrt(path.points[1][0] * path.points[1][0] + path.points[1][1] * path.points[1][1] +
                            path.points[1][2] * path.points[1][2]));
        if (cos_e < 0.5) continue;
        e = test_dir_angle(gpu + 3 * i, ref_dir + 3 * i);
        n++;
        worst = fmax(worst, e);
        over += e > lim;
    }
    printf("sphere %s N=%d K=%d: %d pixels with entry <= 60 deg, worst exit error %.4f rad, bound %.4f rad\n",
           enc == SNELL_NDCUBE_PLAIN ? "plain" : "oct", N, K, n, worst, lim);
    CHECK(n > W * H / 8, "the sphere must cover the image (%d)", n);
    CHECK(over == 0, "%d pixels above the derived bound %.4f (worst %.4f)", over, lim, worst);
out:
    snell_ref_destroy(ref);
    snell_renderer_destroy(r);
}

/* 5. The view through a sphere is upside down: the floor (below the horizon)
 * appears in the upper half of the sphere. Exit directions of pixels in the
 * sphere's upper half must point down (y < 0) for most pixels. */
static void check_inverted(snell_ctx *ctx, snell_mesh *sphere, snell_env *env)
{
    static float dirs[W * H * 3];
    static uint8_t px[W * H * 4];
    snell_renderer *r = NULL, *rc = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_glass g;
    int x, y, down = 0, up_half = 0;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &rc));
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r || !rc) goto out;
    test_frame_one(&fd, &g, sphere, env);
    g.material.method = SNELL_METHOD_CUBEMAP;
    fd.camera.distance = 3.0f; /* level camera looking at the sphere */
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
    /* the sphere (radius 1 at distance 3, fov 45) spans about rows 30..130;
     * sample the upper central part (rows 45..75, columns 60..100) */
    for (y = 45; y < 75; y++)
        for (x = 60; x < 100; x++) {
            up_half++;
            down += dirs[3 * (y * W + x) + 1] < 0.0f;
        }
    CHECK(down > up_half * 9 / 10, "upper half of the sphere must look downward (inverted image): %d of %d", down,
          up_half);
    CHECK_OK_CTX(ctx, snell_render(rc, &fd, NULL));
    CHECK_OK(snell_renderer_read_rgba(rc, px));
    snell_write_png(test_out("cubemap_sphere.png"), W, H, px);
out:
    snell_renderer_destroy(r);
    snell_renderer_destroy(rc);
}

/* 6. The prepare stage's cache is sized by the scene: five different meshes
 * (and one of them twice) in one frame each bake once in the first frame,
 * the repeated mesh reuses its bake within that frame, and the next frames
 * bake nothing (SNELL_SKIP_PREPARE on every object). A new face size for one
 * object re-bakes that object only, once. */
static void check_prepare_cache(snell_ctx *ctx, snell_env *env)
{
    enum { NM = 5, NG = 6 };
    snell_mesh *mesh[NM] = {NULL};
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_frame_stats fs;
    snell_glass g[NG];
    float model[NG][16];
    int i, f, baked, reused;
    const snell_shape_desc shapes[NM] = {{SNELL_SHAPE_SPHERE, 16, 8},
                                         {SNELL_SHAPE_SPHERE, 24, 12},
                                         {SNELL_SHAPE_SPHERE, 32, 16},
                                         {SNELL_SHAPE_CUBE, 0, 0},
                                         {SNELL_SHAPE_SPHERE, 12, 6}};
    for (i = 0; i < NM; i++) CHECK_OK(snell_mesh_create_shape(ctx, &shapes[i], &mesh[i]));
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = 64;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r || !mesh[0] || !mesh[1] || !mesh[2] || !mesh[3] || !mesh[4]) goto out;
    memset(g, 0, sizeof g);
    memset(model, 0, sizeof model);
    for (i = 0; i < NG; i++) {
        model[i][0] = model[i][5] = model[i][10] = 0.25f;
        model[i][12] = -1.25f + 0.5f * (float)i;
        model[i][15] = 1.0f;
        g[i].mesh = mesh[i % NM];
        g[i].model = model[i];
        g[i].material.method = SNELL_METHOD_CUBEMAP;
        g[i].material.cubemap.face_size = 32;
    }
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass = g;
    fd.glass_count = NG;
    fd.camera.distance = 3.5f;
    for (f = 0; f < 3; f++) {
        CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
        for (i = 0, baked = 0, reused = 0; i < NG; i++) {
            baked += fs.glass[i].prepared;
            reused += !!(fs.glass[i].skipped & SNELL_SKIP_PREPARE);
            CHECK(fs.glass[i].method_used == SNELL_METHOD_CUBEMAP && fs.glass[i].draw_order >= 0,
                  "frame %d object %d: drawn with the cubemap method", f, i);
        }
        printf("frame %d: %d of %d objects baked, %d reused\n", f, baked, NG, reused);
        if (f == 0)
            CHECK(baked == NM && reused == NG - NM && fs.glass[0].prepared + fs.glass[NM].prepared == 1,
                  "first frame: each of %d meshes bakes once (%d baked, %d reused)", NM, baked, reused);
        else
            CHECK(baked == 0 && reused == NG, "frame %d: nothing bakes (%d baked, %d reused)", f, baked, reused);
    }
    /* New settings for one object (its mesh not shared): only it bakes. */
    g[2].material.cubemap.face_size = 64;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    for (i = 0, baked = 0; i < NG; i++) baked += fs.glass[i].prepared;
    CHECK(baked == 1 && fs.glass[2].prepared == 1, "a new face size bakes that object only (%d baked)", baked);
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    for (i = 0, baked = 0; i < NG; i++) baked += fs.glass[i].prepared;
    CHECK(baked == 0, "and then nothing (%d baked)", baked);
out:
    snell_renderer_destroy(r);
    for (i = 0; i < NM; i++) snell_mesh_destroy(mesh[i]);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_mesh *sphere = NULL;
    snell_env *env = NULL;
    snell_shape_desc sd;
    double qp, qo;
    if (!ctx) SKIP("no GL context");
    qp = max_quant(SNELL_NDCUBE_PLAIN);
    qo = max_quant(SNELL_NDCUBE_OCT);
    printf("normal quantisation (C twin, worst case): plain %.5f rad, oct %.5f rad\n", qp, qo);
    /* Sanity of the twin itself: 8-bit steps are 2/255 wide, so no encoding
     * can be worse than a step's diagonal (sqrt(3)/255 rad) nor exact. */
    CHECK(qp > 0.0 && qp < sqrt(3.0) / 255.0 + 1e-6, "plain quantisation %g", qp);
    /* Octahedral: half a step (1/255 per coordinate) on the octahedron, whose
     * points are at least 1/sqrt(3) from the origin, turns the normal by up to
     * sqrt(2)/255 * sqrt(3) on the upper half; the fold of the lower half can
     * double it (Cigolle et al. 2014 report ~0.9 degrees for 2x8 bits). */
    CHECK(qo > 0.0 && qo < 2.0 * sqrt(6.0) / 255.0, "oct quantisation %g", qo);

    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &sphere));
    env = test_sky(ctx, 128);
    if (!sphere || !env) return test_finish();

    check_bake(ctx, sphere, SNELL_NDCUBE_OCT, 64);
    check_bake(ctx, sphere, SNELL_NDCUBE_PLAIN, 64);
    check_sphere(ctx, sphere, env, SNELL_NDCUBE_OCT, 256, 8);
    check_sphere(ctx, sphere, env, SNELL_NDCUBE_PLAIN, 256, 8);
    check_sphere(ctx, sphere, env, SNELL_NDCUBE_PLAIN, 64, 4);
    check_inverted(ctx, sphere, env);
    check_prepare_cache(ctx, env);

    snell_env_destroy(env);
    snell_mesh_destroy(sphere);
    snell_ctx_destroy(ctx);
    return test_finish();
}
