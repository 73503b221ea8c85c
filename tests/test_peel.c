/* SPDX-License-Identifier: MIT */
/* test_peel — multi-layer refraction from depth-peeled layers (Wang 2014,
 * methods/peel.c, shaders_es/peel.frag, depth_peel.frag).
 *
 * 1. Depth complexity (mesh analysis): a sphere and a cube cross 2 surfaces
 *    along every line, a torus 4 (a line through both tubes); the peels it
 *    bounds: a sphere asked for 8 layers peels 2; a torus seen from straight
 *    above (view rays cross one tube, 2 surfaces) peels 3 and stops: the
 *    third came out empty (occlusion query), so 2 are used.
 * 2. Two layers on a convex mesh are two-surface refraction: the cube with
 *    layers = 2 and interfaces = 2 against the reference's MATCHED model with
 *    2 interfaces (entry, exit; TIR at the exit reflects and stops, as the
 *    kernel's cap does). The cube's faces are flat, so the layer normals are
 *    exact (16+16-bit octahedral: < 1e-4 rad; the normal filter does not mix
 *    faces across an edge) and the found exit point only matters where it
 *    picks the wrong face: within a few pixels of an edge as seen through
 *    the glass. Required: 97% of the glass pixels within 0.005 rad of the
 *    reference (measured 99.2%) and the mean below 0.02 rad (measured
 *    0.0082: the edge pixels, ~0.5 rad each). (Normals filtered across the
 *    edges: 96.5%, 0.0167.)
 *    The same cube with 8 interfaces against MATCHED(8): inside a cube light
 *    often reflects totally at the second face and goes on (the reference's
 *    direction changes beyond 0.01 rad from MATCHED(2)'s on 65% of the
 *    pixels; required: over 20%), and on a convex mesh MATCHED's chain is
 *    peel's path (no re-entry). Required: 97% within 0.005 rad (measured
 *    98.3%), mean below 0.03 (measured 0.0175: each further face brings its
 *    edges; 3% of the pixels a radian off would be 0.03).
 * 3. Sphere: against the cubemap method, pixels whose incidence is at most
 *    60 degrees (away from the silhouette, where both methods' facets and
 *    quantisation are amplified without bound). Both are exact two-surface
 *    models on a sphere (no TIR inside a sphere); they differ by their
 *    quantisation: the cubemap's normal is its 256-texel face's, filtered in
 *    8 bits per component (up to 0.004 rad), peel's the back layer's
 *    bilinearly filtered at the exit point (160x160: a pixel spans 0.024 rad
 *    of the unit sphere at the back; filtering leaves the facets' error,
 *    interpolated normals within ~2e-3 rad of the sphere's). The exit
 *    refraction multiplies a normal error by at most 1 + 1.5 cos / cos_t ~
 *    3.5 below 60 degrees: the two agree within 3.5 x (0.004 + 0.002) =
 *    0.021 rad per pixel; required: 99% within that and the mean below a
 *    third of it (the mean offset is half the maximum, and the two errors are
 *    independent). Measured: all within, mean 0.0016 rad, worst 0.010.
 *    (Unfiltered pixel-centre normals: worst 0.031, mean 0.0066; a search
 *    range ending exactly on the bounding sphere, on which the tessellated
 *    sphere's vertices lie: 68% within 0.056, mean 0.09.)
 * 4. Torus and goblet against the FULL reference (10 interfaces: the
 *    dominant branch, which goes on through every re-entry, as the kernel
 *    does). The bound is the method's point (the "done means"): the
 *    mean and the median exit-direction error at most half the cubemap's
 *    and half single-surface's. Measured at 160x160 (forward and screen
 *    alike), mean/median rad: torus at 29 degrees elevation peel
 *    0.075/0.0029, cubemap 0.366/0.169, single 0.627/0.404; torus nearly
 *    edge-on (6 degrees, view rays through both tubes) 0.403/0.020 against
 *    1.049/1.000 and 0.956/0.715; goblet 0.115/0.0024 against 0.454/0.180
 *    and 0.470/0.337. Edge-on, the layers beyond two are what it takes:
 *    peel with 2 layers is 0.711/0.349 there (required: the default layers
 *    below 0.75x of that, measured 0.57x/0.06x; at 29 degrees few rays cross
 *    a second tube and 2 layers are within 4%).
 *    The seed's fixes (3.5) earn their keep: without them the mean is
 *    higher (required: with them at most 0.9x; measured 0.76x torus, 0.58x
 *    torus edge-on, 0.80x goblet; BENCHMARKS.md has each fix alone).
 * 5. More surfaces than layers (the goblet, depth complexity 6, with 2
 *    layers): degrades, does not break: every exit direction is a finite unit
 *    vector and no glass pixel of the colour image is black.
 * 6. Two peel objects in one frame share the layer textures: the torus's
 *    exit directions are bitwise those of the torus alone.
 * 7. Colour: Schlick at the entry and Beer-Lambert over the path (the cube,
 *    absorption 1.2/0.5/0.1 per unit, 8 interfaces) against the reference's
 *    MATCHED colour (its model on a convex mesh): the two differ by the 8-bit
 *    target, the environment's filtering and the exit-direction errors of 2.
 *    Required: mean worst-channel difference below 3/255, 95% within 8/255
 *    (measured 1.59/255, 98.3%); absorption itself darkens by 62/255 (required
 *    > 20). (With the path 0.7x too short: 18/255, 3.8%.)
 * 8. Winding: on a closed mesh seen from outside, each peel draws only the
 *    faces its layer can hold (front faces for even layers, back faces for
 *    odd ones; methods/peel.c). A torus built here and the same torus with
 *    every triangle's winding reversed (the mesh analysis finds it inside
 *    out, winding -1) must give the same exit directions: 98% of the glass
 *    pixels within 1e-3 rad. They are not bitwise equal: the rasteriser
 *    sees the same triangles with their corners in another order, and the
 *    last bit of a depth can turn a grazing step of the search; without the
 *    culling 83 of 8923 pixels differ, with it 82 (screen) and 114
 *    (forward). Culling by the wrong winding for the inside-out mesh empties
 *    and swaps its layers (checked by breaking it once: then 8922 of 8923
 *    pixels differ, and 3 layers come out where 4 do).
 *    (A mirroring model matrix is tested by test_mirror, against the
 *    mirrored vertices: mirroring this torus by x -> -x alone maps its
 *    vertices but not its quads' diagonals onto each other, so it is
 *    another mesh.) */
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 160
#define H 160

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static snell_mesh *shape(snell_ctx *ctx, snell_shape s)
{
    snell_shape_desc sd;
    snell_mesh *mesh = NULL;
    memset(&sd, 0, sizeof sd);
    sd.shape = s;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    if (mesh && s != SNELL_SHAPE_SPHERE) CHECK_OK(snell_mesh_normalize(mesh, 1.0f));
    return mesh;
}

static snell_renderer *renderer(snell_ctx *ctx, snell_output out)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = out;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    return r;
}

/* Renders exit directions (or colour, when rgba is given) of the frame with
 * method m: the second of two, whose peels follow the first's occlusion
 * results (so the stats count the layers found). */
static void render(snell_ctx *ctx, snell_frame_desc *fd, snell_glass *g, snell_method m, float *dirs, uint8_t *rgba,
                   snell_frame_stats *stats)
{
    snell_renderer *r = renderer(ctx, rgba ? SNELL_OUTPUT_COLOR : SNELL_OUTPUT_EXIT_DIRECTION);
    if (!r) return;
    g->material.method = m;
    CHECK_OK_CTX(ctx, snell_render(r, fd, stats));
    CHECK_OK_CTX(ctx, snell_render(r, fd, stats));
    if (rgba) CHECK_OK(snell_renderer_read_rgba(r, rgba));
    else CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
    snell_renderer_destroy(r);
}

static void reference(snell_ctx *ctx, const snell_frame_desc *fd, snell_ref_mode mode, int interfaces, float *dirs,
                      uint8_t *hit)
{
    static float rgb[W * H * 3];
    snell_ref *ref = NULL;
    snell_ref_params p;
    CHECK_OK(test_ref_create(ctx, fd, &ref));
    if (!ref) return;
    test_ref_params(fd, W, H, interfaces, &p);
    p.mode = mode;
    p.isolate_glass = 1;
    CHECK_OK(test_ref_render(ref, &p, rgb, dirs, hit));
    snell_ref_destroy(ref);
}

static void test_depth_complexity(snell_ctx *ctx, snell_env *env)
{
    static float dirs[W * H * 3];
    snell_shape shapes[3] = {SNELL_SHAPE_SPHERE, SNELL_SHAPE_CUBE, SNELL_SHAPE_TORUS};
    int want[3] = {2, 2, 4}, i;
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    for (i = 0; i < 3; i++) {
        snell_mesh *mesh = shape(ctx, shapes[i]);
        snell_mesh_analysis an;
        if (!mesh) continue;
        CHECK_OK(snell_mesh_analyze(mesh, &an));
        printf("shape %d: depth complexity %d, %.3f of lines cross more than 2 surfaces\n", i, an.depth_complexity,
               an.deep_fraction);
        CHECK(an.depth_complexity == want[i], "shape %d: depth complexity %d, want %d", i, an.depth_complexity,
              want[i]);
        CHECK((an.deep_fraction > 0.0f) == (want[i] > 2), "shape %d: deep fraction %g", i, an.deep_fraction);
        test_frame_one(&fd, &g, mesh, env);
        if (i == 0) {
            g.material.peel.layers = 8;
            render(ctx, &fd, &g, SNELL_METHOD_PEEL, dirs, NULL, &st);
            CHECK(snell_object_counter(&st.glass[0], "layers_peeled") == 2 && snell_object_counter(&st.glass[0], "layers_found") == 2, "sphere: %d peeled, %d found",
                  snell_object_counter(&st.glass[0], "layers_peeled"), snell_object_counter(&st.glass[0], "layers_found"));
        }
        if (i == 2) {
            fd.camera.elevation = 1.5707f; /* from straight above: one tube per view ray */
            render(ctx, &fd, &g, SNELL_METHOD_PEEL, dirs, NULL, &st);
            CHECK(snell_object_counter(&st.glass[0], "layers_peeled") == 3 && snell_object_counter(&st.glass[0], "layers_found") == 2,
                  "torus from above: %d peeled, %d found", snell_object_counter(&st.glass[0], "layers_peeled"), snell_object_counter(&st.glass[0], "layers_found"));
            fd.camera.elevation = 0.1f; /* nearly edge-on: both tubes */
            render(ctx, &fd, &g, SNELL_METHOD_PEEL, dirs, NULL, &st);
            CHECK(snell_object_counter(&st.glass[0], "layers_peeled") == 4 && snell_object_counter(&st.glass[0], "layers_found") == 4, "torus edge-on: %d peeled, %d found",
                  snell_object_counter(&st.glass[0], "layers_peeled"), snell_object_counter(&st.glass[0], "layers_found"));
        }
        snell_mesh_destroy(mesh);
    }
}

static void test_two_layers(snell_ctx *ctx, snell_env *env)
{
    static float gpu[W * H * 3], ref[W * H * 3];
    static uint8_t hit[W * H];
    snell_mesh *mesh = shape(ctx, SNELL_SHAPE_CUBE);
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    int i, glass = 0, close = 0;
    double sum = 0.0;
    if (!mesh) return;
    test_frame_one(&fd, &g, mesh, env);
    fd.camera.azimuth = 0.5f;
    fd.camera.elevation = 0.4f;
    g.material.peel.layers = 2;
    g.material.peel.max_interfaces = 2;
    render(ctx, &fd, &g, SNELL_METHOD_PEEL, gpu, NULL, &st);
    CHECK(snell_object_counter(&st.glass[0], "layers_peeled") == 2, "%d layers peeled", snell_object_counter(&st.glass[0], "layers_peeled"));
    reference(ctx, &fd, SNELL_REF_MATCHED, 2, ref, hit);
    for (i = 0; i < W * H; i++) {
        double e;
        if (!hit[i]) continue;
        glass++;
        e = test_dir_angle(gpu + 3 * i, ref + 3 * i);
        sum += e;
        close += e < 0.005;
    }
    printf("cube, 2 layers vs MATCHED(2): %d glass px, %.1f%% within 0.005 rad, mean %.4f rad\n", glass,
           100.0 * close / (glass ? glass : 1), sum / (glass ? glass : 1));
    CHECK(glass > W * H / 10, "cube covers %d px", glass);
    CHECK(close >= 0.97 * glass, "only %d of %d pixels within 0.005 rad", close, glass);
    CHECK(sum < 0.02 * glass, "mean %g rad", sum / glass);

    /* TIR: inside a cube light often reflects totally at the second face and
     * goes on; with 8 interfaces against MATCHED(8) (a convex mesh: no
     * re-entry, so MATCHED's chain is peel's path) */
    {
        static float ref8[W * H * 3];
        int tir = 0;
        g.material.peel.layers = 0;
        g.material.peel.max_interfaces = 8;
        render(ctx, &fd, &g, SNELL_METHOD_PEEL, gpu, NULL, &st);
        reference(ctx, &fd, SNELL_REF_MATCHED, 8, ref8, hit);
        glass = close = 0;
        sum = 0.0;
        for (i = 0; i < W * H; i++) {
            double e;
            if (!hit[i]) continue;
            glass++;
            tir += test_dir_angle(ref8 + 3 * i, ref + 3 * i) > 0.01;
            e = test_dir_angle(gpu + 3 * i, ref8 + 3 * i);
            sum += e;
            close += e < 0.005;
        }
        printf("cube, 8 interfaces vs MATCHED(8): %.1f%% of the pixels where TIR goes on; %.1f%% within 0.005 rad, "
               "mean %.4f rad\n", 100.0 * tir / (glass ? glass : 1), 100.0 * close / (glass ? glass : 1),
               sum / (glass ? glass : 1));
        CHECK(tir > glass / 5, "only %d of %d pixels reach a third interface", tir, glass);
        CHECK(close >= 0.97 * glass, "only %d of %d pixels within 0.005 rad", close, glass);
        CHECK(sum < 0.03 * glass, "mean %g rad", sum / glass);
    }
    snell_mesh_destroy(mesh);
}

/* incidence cosine of pixel i's view ray on the unit sphere at the origin (0: a miss) */
static double sphere_cos(const snell_camera *cam, int i)
{
    float eye[3], view[16], proj[16];
    double d[3], len = 0.0, b = 0.0, c = 0.0, nx, ny, tan_half, disc, t;
    int k;
    snell_camera_matrices(cam, (float)W / H, eye, view, proj);
    tan_half = 1.0 / proj[5];
    nx = ((i % W) + 0.5) / W * 2.0 - 1.0;
    ny = 1.0 - ((i / W) + 0.5) / H * 2.0;
    for (k = 0; k < 3; k++) {
        d[k] = -view[4 * k + 2] + nx * tan_half * view[4 * k + 0] + ny * tan_half * view[4 * k + 1];
        len += d[k] * d[k];
    }
    for (k = 0; k < 3; k++) {
        d[k] /= sqrt(len);
        b += eye[k] * d[k];
        c += (double)eye[k] * eye[k];
    }
    disc = b * b - (c - 1.0);
    if (disc <= 0.0) return 0.0;
    t = -b - sqrt(disc);
    /* the normal at the hit is the hit point itself */
    return -((eye[0] + t * d[0]) * d[0] + (eye[1] + t * d[1]) * d[1] + (eye[2] + t * d[2]) * d[2]);
}

static void test_sphere_vs_cubemap(snell_ctx *ctx, snell_env *env)
{
    static float peel[W * H * 3], cube[W * H * 3];
    snell_mesh *mesh = shape(ctx, SNELL_SHAPE_SPHERE);
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    const double bound = 0.021;
    int i, n = 0, within = 0;
    double sum = 0.0, worst = 0.0;
    if (!mesh) return;
    test_frame_one(&fd, &g, mesh, env);
    fd.camera.azimuth = 0.4f;
    fd.camera.elevation = 0.3f;
    render(ctx, &fd, &g, SNELL_METHOD_PEEL, peel, NULL, &st);
    render(ctx, &fd, &g, SNELL_METHOD_CUBEMAP, cube, NULL, &st);
    for (i = 0; i < W * H; i++) {
        double e;
        if (sphere_cos(&fd.camera, i) < 0.5) continue; /* incidence above 60 degrees, or a miss */
        e = test_dir_angle(peel + 3 * i, cube + 3 * i);
        n++;
        sum += e;
        within += e <= bound;
        worst = fmax(worst, e);
    }
    printf("sphere, incidence <= 60 deg: %d px, peel vs cubemap mean %.4f rad, %.2f%% within %.3f, worst %.3f\n", n,
           sum / (n ? n : 1), 100.0 * within / (n ? n : 1), bound, worst);
    CHECK(n > W * H / 10, "%d central pixels", n);
    CHECK(within >= 0.99 * n, "only %d of %d within %g rad", within, n, bound);
    CHECK(sum < bound / 3.0 * n, "mean %g rad", sum / n);
    snell_mesh_destroy(mesh);
}

/* Mean and median of peel's, the cubemap's and single's error against FULL (10 interfaces). */
static void test_concave(snell_ctx *ctx, snell_env *env, snell_shape s, const char *name, float elevation)
{
    static float ref[W * H * 3], dirs[5][W * H * 3];
    static double err[5][W * H];
    static uint8_t hit[W * H];
    static const snell_method methods[3] = {SNELL_METHOD_PEEL, SNELL_METHOD_CUBEMAP, SNELL_METHOD_SINGLE};
    snell_mesh *mesh = shape(ctx, s);
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    double mean[5] = {0, 0, 0, 0, 0}, median[5];
    int i, m, n = 0;
    if (!mesh) return;
    test_frame_one(&fd, &g, mesh, env);
    fd.camera.azimuth = 0.3f;
    fd.camera.elevation = elevation;
    for (m = 0; m < 3; m++) render(ctx, &fd, &g, methods[m], dirs[m], NULL, &st);
    g.material.peel.layers = 2; /* [3]: what the two layers of a two-surface method see */
    render(ctx, &fd, &g, SNELL_METHOD_PEEL, dirs[3], NULL, &st);
    g.material.peel.layers = 0;
    g.material.peel.fixes = SNELL_PEEL_FIXES_NONE; /* [4]: the plain layer search */
    render(ctx, &fd, &g, SNELL_METHOD_PEEL, dirs[4], NULL, &st);
    g.material.peel.fixes = SNELL_PEEL_FIXES_DEFAULT;
    g.material.method = SNELL_METHOD_PEEL;
    reference(ctx, &fd, SNELL_REF_FULL, 10, ref, hit);
    for (i = 0; i < W * H; i++) {
        if (!hit[i]) continue;
        for (m = 0; m < 5; m++) {
            err[m][n] = test_dir_angle(dirs[m] + 3 * i, ref + 3 * i);
            mean[m] += err[m][n];
        }
        n++;
    }
    CHECK(n > W * H / 20, "%s covers %d px", name, n);
    if (n == 0) goto out;
    for (m = 0; m < 5; m++) {
        mean[m] /= n;
        qsort(err[m], (size_t)n, sizeof(double), cmp_double);
        median[m] = err[m][n / 2];
    }
    printf("%s (elevation %.2f) vs FULL(10), %d px: mean/median rad: peel %.4f/%.4f, cubemap %.4f/%.4f, single "
           "%.4f/%.4f, peel with 2 layers %.4f/%.4f, without the fixes %.4f/%.4f\n", name, elevation, n, mean[0],
           median[0], mean[1], median[1], mean[2], median[2], mean[3], median[3], mean[4], median[4]);
    CHECK(mean[0] <= 0.9 * mean[4], "%s: the seed's fixes %g, without them %g: not 0.9x", name, mean[0], mean[4]);
    for (m = 1; m < 3; m++) {
        CHECK(mean[0] <= 0.5 * mean[m], "%s: peel mean %g not at most half of %s's %g", name, mean[0],
              m == 1 ? "cubemap" : "single", mean[m]);
        CHECK(median[0] <= 0.5 * median[m], "%s: peel median %g not at most half of %s's %g", name, median[0],
              m == 1 ? "cubemap" : "single", median[m]);
    }
    if (elevation < 0.2f)
        CHECK(mean[0] < 0.75 * mean[3] && median[0] < 0.75 * median[3],
              "%s edge-on: the default layers' %g/%g not below 0.75x two layers' %g/%g", name, mean[0],
              median[0], mean[3], median[3]);
out:
    snell_mesh_destroy(mesh);
}

static void test_over_cap(snell_ctx *ctx, snell_env *env)
{
    static float dirs[W * H * 3], ref[W * H * 3];
    static uint8_t rgba[W * H * 4], hit[W * H];
    snell_mesh *mesh = shape(ctx, SNELL_SHAPE_GOBLET);
    snell_mesh_analysis an;
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    int i, glass = 0, bad = 0, black = 0;
    if (!mesh) return;
    CHECK_OK(snell_mesh_analyze(mesh, &an));
    CHECK(an.depth_complexity > 4, "goblet depth complexity %d", an.depth_complexity);
    test_frame_one(&fd, &g, mesh, env);
    fd.camera.elevation = 0.2f;
    g.material.peel.layers = 2;
    render(ctx, &fd, &g, SNELL_METHOD_PEEL, dirs, NULL, &st);
    CHECK(snell_object_counter(&st.glass[0], "layers_peeled") == 2, "%d layers peeled", snell_object_counter(&st.glass[0], "layers_peeled"));
    render(ctx, &fd, &g, SNELL_METHOD_PEEL, NULL, rgba, &st);
    reference(ctx, &fd, SNELL_REF_MATCHED, 2, ref, hit);
    for (i = 0; i < W * H; i++) {
        const float *d = dirs + 3 * i;
        double len = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
        if (!hit[i]) continue;
        glass++;
        bad += !(isfinite(d[0]) && isfinite(d[1]) && isfinite(d[2]) && fabs(len - 1.0) < 1e-3);
        black += rgba[4 * i] == 0 && rgba[4 * i + 1] == 0 && rgba[4 * i + 2] == 0;
    }
    printf("goblet, 2 layers of depth complexity %d: %d glass px, %d not unit, %d black\n", an.depth_complexity,
           glass, bad, black);
    CHECK(glass > W * H / 20, "goblet covers %d px", glass);
    CHECK(bad == 0 && black == 0, "%d directions not finite unit vectors, %d black pixels", bad, black);
    snell_mesh_destroy(mesh);
}

/* Beer-Lambert over the path, Schlick at the entry: the cube's colour with
 * absorption against the reference's (MATCHED, 8 interfaces, path
 * absorption: on a convex mesh peel's optical model). */
static void test_absorption(snell_ctx *ctx, snell_env *env)
{
    static float rgb[W * H * 3], dirs[W * H * 3];
    static uint8_t gpu[W * H * 4], clear[W * H * 4], hit[W * H];
    snell_mesh *mesh = shape(ctx, SNELL_SHAPE_CUBE);
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    snell_ref *ref = NULL;
    snell_ref_params p;
    const float sigma[3] = {1.2f, 0.5f, 0.1f};
    int i, k, glass = 0, close = 0;
    double sum = 0.0, dark = 0.0;
    if (!mesh) return;
    test_frame_one(&fd, &g, mesh, env);
    g.material.peel.inner_fresnel = SNELL_INNER_FRESNEL_OFF; /* the MATCHED model: no exit Fresnel */
    fd.camera.azimuth = 0.5f;
    fd.camera.elevation = 0.4f;
    render(ctx, &fd, &g, SNELL_METHOD_PEEL, NULL, clear, &st);
    snell_glass_set_absorption(&g.material, sigma);
    render(ctx, &fd, &g, SNELL_METHOD_PEEL, NULL, gpu, &st);
    CHECK_OK(test_ref_create(ctx, &fd, &ref));
    if (!ref) goto out;
    test_ref_params(&fd, W, H, 8, &p);
    p.isolate_glass = 1;
    CHECK_OK(test_ref_render(ref, &p, rgb, dirs, hit));
    for (i = 0; i < W * H; i++) {
        double d = 0.0;
        if (!hit[i]) continue;
        glass++;
        for (k = 0; k < 3; k++) {
            double want = 255.0 * fmin(fmax(rgb[3 * i + k], 0.0), 1.0);
            d = fmax(d, fabs(gpu[4 * i + k] - want));
            dark += (double)clear[4 * i + k] - gpu[4 * i + k];
        }
        sum += d;
        close += d <= 8.0;
    }
    printf("cube, absorption (1.2, 0.5, 0.1): vs MATCHED(8) colour mean %.2f/255 (worst channel), %.1f%% within "
           "8/255; absorption darkens by %.1f/255 a channel\n", sum / (glass ? glass : 1),
           100.0 * close / (glass ? glass : 1), dark / (3.0 * (glass ? glass : 1)));
    CHECK(glass > W * H / 10, "cube covers %d px", glass);
    CHECK(dark > 20.0 * 3.0 * glass, "absorption darkened by only %g/255", dark / (3.0 * glass));
    CHECK(sum < 3.0 * glass, "mean colour difference %g/255", sum / glass);
    CHECK(close >= 0.95 * glass, "only %d of %d within 8/255", close, glass);
out:
    snell_ref_destroy(ref);
    snell_mesh_destroy(mesh);
}

/* Two peel objects in a frame share the layer textures, peeling one after
 * the other: the torus's pixels are the same with the goblet beside it as
 * alone (the left half of the image holds only the torus). */
static void test_two_objects(snell_ctx *ctx, snell_env *env)
{
    static float both[W * H * 3], alone[W * H * 3], none[W * H * 3];
    snell_mesh *torus = shape(ctx, SNELL_SHAPE_TORUS), *goblet = shape(ctx, SNELL_SHAPE_GOBLET);
    float m0[16] = {0.45f, 0, 0, 0, 0, 0.45f, 0, 0, 0, 0, 0.45f, 0, -0.55f, 0, 0, 1};
    float m1[16] = {0.45f, 0, 0, 0, 0, 0.45f, 0, 0, 0, 0, 0.45f, 0, 0.6f, 0, 0, 1};
    snell_frame_desc fd;
    snell_glass g[2];
    snell_frame_stats st;
    int x, y, differ = 0, glass = 0;
    if (!torus || !goblet) goto out;
    memset(g, 0, sizeof g);
    test_frame_one(&fd, &g[0], torus, env);
    fd.camera.azimuth = 0.0f;
    fd.camera.elevation = 0.3f;
    g[0].model = m0;
    g[1].mesh = goblet;
    g[1].model = m1;
    g[1].material.method = SNELL_METHOD_PEEL;
    fd.glass = g;
    fd.glass_count = 2;
    fd.scene_layers = -1; /* the kernel's own layer textures are the point, not what the torus sees of the goblet */
    render(ctx, &fd, &g[0], SNELL_METHOD_PEEL, both, NULL, &st);
    CHECK(st.glass[0].method_used == SNELL_METHOD_PEEL && st.glass[1].method_used == SNELL_METHOD_PEEL &&
              snell_object_counter(&st.glass[0], "layers_found") >= 2 && snell_object_counter(&st.glass[1], "layers_found") >= 2,
          "methods %d %d, layers found %d %d", (int)st.glass[0].method_used, (int)st.glass[1].method_used,
          snell_object_counter(&st.glass[0], "layers_found"), snell_object_counter(&st.glass[1], "layers_found"));
    fd.glass_count = 1;
    render(ctx, &fd, &g[0], SNELL_METHOD_PEEL, alone, NULL, &st);
    fd.glass_count = 0; /* the background's directions: where the torus is not */
    render(ctx, &fd, &g[0], SNELL_METHOD_PEEL, none, NULL, &st);
    for (y = 0; y < H; y++)
        for (x = 0; x < W / 2; x++) {
            size_t i = 3 * ((size_t)y * W + x);
            differ += memcmp(both + i, alone + i, 3 * sizeof(float)) != 0;
            glass += memcmp(alone + i, none + i, 3 * sizeof(float)) != 0;
        }
    printf("two peel objects: %d of the torus's %d pixels differ from the torus alone\n", differ, glass);
    CHECK(glass > W * H / 40, "the torus covers %d px of the left half", glass);
    CHECK(differ == 0, "%d pixels of the torus changed with the goblet beside it", differ);
out:
    snell_mesh_destroy(torus);
    snell_mesh_destroy(goblet);
}

/* A torus (major radius 1, minor 0.4, around +Y; even segment count, so
 * x -> -x maps its vertices onto each other), triangles wound outward, or
 * inward with reversed = 1. */
static snell_mesh *torus_mesh(snell_ctx *ctx, int reversed)
{
    enum { NU = 48, NV = 24 };
    static float pos[NU * NV * 3], nrm[NU * NV * 3];
    static uint32_t idx[NU * NV * 6];
    snell_mesh_desc d;
    snell_mesh *mesh = NULL;
    int i, j, t = 0;
    for (i = 0; i < NU; i++)
        for (j = 0; j < NV; j++) {
            double u = 2.0 * 3.14159265358979 * i / NU, v = 2.0 * 3.14159265358979 * j / NV;
            float *p = pos + 3 * (i * NV + j), *n = nrm + 3 * (i * NV + j);
            n[0] = (float)(cos(v) * cos(u));
            n[1] = (float)sin(v);
            n[2] = (float)(cos(v) * sin(u));
            p[0] = (float)((1.0 + 0.4 * cos(v)) * cos(u));
            p[1] = (float)(0.4 * sin(v));
            p[2] = (float)((1.0 + 0.4 * cos(v)) * sin(u));
        }
    for (i = 0; i < NU; i++)
        for (j = 0; j < NV; j++) {
            uint32_t a = (uint32_t)(i * NV + j), b = (uint32_t)(((i + 1) % NU) * NV + j),
                     c = (uint32_t)(((i + 1) % NU) * NV + (j + 1) % NV), e = (uint32_t)(i * NV + (j + 1) % NV);
            uint32_t q[6] = {a, e, c, a, c, b};
            int k;
            for (k = 0; k < 6; k++) idx[t + k] = q[reversed ? k - k % 3 + (3 - k % 3) % 3 : k];
            t += 6;
        }
    memset(&d, 0, sizeof d);
    d.positions = pos;
    d.normals = nrm;
    d.indices = idx;
    d.vertex_count = NU * NV;
    d.triangle_count = 2 * NU * NV;
    CHECK_OK(snell_mesh_create(ctx, &d, &mesh));
    return mesh;
}

static void test_winding(snell_ctx *ctx, snell_env *env)
{
    static float dirs[2][W * H * 3], none[W * H * 3];
    snell_mesh *mesh[2] = {torus_mesh(ctx, 0), torus_mesh(ctx, 1)};
    snell_mesh_analysis an[2];
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    int c, i, glass = 0, off = 0;
    if (!mesh[0] || !mesh[1]) goto out;
    for (c = 0; c < 2; c++) {
        CHECK_OK(snell_mesh_analyze(mesh[c], &an[c]));
        CHECK(an[c].closed && an[c].winding == (c ? -1 : 1), "torus %d: closed %d, winding %d", c, an[c].closed,
              an[c].winding);
        test_frame_one(&fd, &g, mesh[c], env);
        fd.camera.azimuth = 0.3f;
        fd.camera.elevation = 0.1f; /* nearly edge-on: rays through both tubes, 4 layers */
        render(ctx, &fd, &g, SNELL_METHOD_PEEL, dirs[c], NULL, &st);
        CHECK(snell_object_counter(&st.glass[0], "layers_found") == 4, "torus %d: %d layers found", c,
              snell_object_counter(&st.glass[0], "layers_found"));
    }
    fd.glass_count = 0;
    render(ctx, &fd, &g, SNELL_METHOD_PEEL, none, NULL, &st);
    for (i = 0; i < W * H; i++) {
        if (!memcmp(dirs[0] + 3 * i, none + 3 * i, 3 * sizeof(float))) continue;
        glass++;
        off += test_dir_angle(dirs[0] + 3 * i, dirs[1] + 3 * i) > 1e-3;
    }
    printf("winding: %d of %d glass pixels of the inside-out torus differ by more than 1e-3 rad\n", off, glass);
    CHECK(glass > W * H / 20, "the torus covers %d px", glass);
    CHECK(off <= glass / 50, "%d of %d pixels differ", off, glass);
out:
    snell_mesh_destroy(mesh[0]);
    snell_mesh_destroy(mesh[1]);
}

/* One frame of r (exit directions) into dirs; its stats' peel counters. */
static void history_frame(snell_ctx *ctx, snell_renderer *r, const snell_frame_desc *fd, float *dirs, int *peeled,
                          int *found)
{
    snell_frame_stats st;
    *peeled = *found = -2;
    if (!r) return;
    CHECK_OK_CTX(ctx, snell_render(r, fd, &st));
    CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
    *peeled = snell_object_counter(&st.glass[0], "layers_peeled");
    *found = snell_object_counter(&st.glass[0], "layers_found");
}

static int dirs_differ(const float *a, const float *b)
{
    int i, n = 0;
    for (i = 0; i < W * H; i++) n += memcmp(a + 3 * i, b + 3 * i, 3 * sizeof(float)) != 0;
    return n;
}

static void test_history(snell_ctx *ctx, snell_env *env)
{
    static float all[W * H * 3], dirs[W * H * 3];
    snell_mesh *mesh = shape(ctx, SNELL_SHAPE_TORUS);
    snell_renderer *r = renderer(ctx, SNELL_OUTPUT_EXIT_DIRECTION), *fresh = NULL;
    snell_frame_desc fd;
    snell_glass g;
    int f, peeled, found, n;
    if (!mesh || !r) goto out;
    test_frame_one(&fd, &g, mesh, env);
    g.material.method = SNELL_METHOD_PEEL;
    fd.camera.elevation = 1.5707f; /* from straight above: one tube per view ray, 2 layers */
    history_frame(ctx, r, &fd, all, &peeled, &found);
    CHECK(peeled == 4 && found == -1, "first frame: %d peeled (want all 4), %d found (want -1: no result)", peeled, found);
    for (f = 2; f <= 4; f++) {
        history_frame(ctx, r, &fd, dirs, &peeled, &found);
        n = dirs_differ(dirs, all);
        CHECK(peeled == 3 && found == 2, "still frame %d: %d peeled, %d found (want 3, 2)", f, peeled, found);
        CHECK(n == 0, "still frame %d: %d pixels differ from the first frame's, which peeled every layer", f, n);
    }
    /* edge-on: both tubes, 4 layers; what every layer gives, from a renderer without history */
    fd.camera.elevation = 0.1f;
    fresh = renderer(ctx, SNELL_OUTPUT_EXIT_DIRECTION);
    history_frame(ctx, fresh, &fd, all, &peeled, &found);
    CHECK(peeled == 4, "edge-on without history: %d peeled", peeled);
    history_frame(ctx, r, &fd, dirs, &peeled, &found);
    n = dirs_differ(dirs, all);
    printf("history: the first edge-on frame peels %d layers (found %d): %d pixels differ from every layer's\n",
           peeled, found, n);
    CHECK(peeled == 3 && found == 2, "first edge-on frame: %d peeled, %d found (want 3: the spare, 2)", peeled, found);
    CHECK(n > 0, "the first edge-on frame lacks layer 4 but no pixel differs (the view does not test growth)");
    history_frame(ctx, r, &fd, dirs, &peeled, &found);
    n = dirs_differ(dirs, all);
    CHECK(peeled == 4 && found == 3, "second edge-on frame: %d peeled, %d found (want 4, 3: the spare was full)",
          peeled, found);
    CHECK(n == 0, "second edge-on frame: %d pixels differ from every layer's", n);
    history_frame(ctx, r, &fd, dirs, &peeled, &found);
    CHECK(peeled == 4 && found == 4, "third edge-on frame: %d peeled, %d found (want 4, 4)", peeled, found);
out:
    snell_renderer_destroy(fresh);
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
    test_depth_complexity(ctx, env);
    test_two_layers(ctx, env);
    test_sphere_vs_cubemap(ctx, env);
    test_concave(ctx, env, SNELL_SHAPE_TORUS, "torus", 0.5f);
    test_concave(ctx, env, SNELL_SHAPE_TORUS, "torus", 0.1f);
    test_concave(ctx, env, SNELL_SHAPE_GOBLET, "goblet", 0.5f);
    test_over_cap(ctx, env);
    test_two_objects(ctx, env);
    test_absorption(ctx, env);
    test_winding(ctx, env);
    test_history(ctx, env);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
