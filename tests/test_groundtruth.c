/* SPDX-License-Identifier: MIT */
/* test_groundtruth — snell's FULL reference against an independent path
 * tracer, Blender Cycles (tests/scripts/cycles_render.py), on a glass sphere
 * and a torus (a small closed mesh with internal reflections and TIR): the
 * same triangles and shading normals (Blender's own vertex normals, which the
 * script writes back) with the same rule where a smooth normal faces away
 * from a ray the triangle faces (both bend it: ref_trace.c interface_normal;
 * before FULL had it, the bunny's base was 3.7/255 off), camera, IOR 1.5 and
 * environment image.
 *
 * The environment is snell's procedural one baked into an equirectangular
 * PNG that Cycles loads as non-colour data; the reference looks the same
 * texels up as Cycles' Environment Texture does (its equirectangular mapping
 * in Blender's Z-up frame, bilinear, periodic), so both see one function.
 * Blender's frame is snell's rotated by +90 degrees about X: (x, y, z) ->
 * (x, -z, y). Pixel centres: Cycles' Gaussian filter 0.01 pixels wide (its
 * box filter ignores the width and always covers the pixel; with that
 * mistaken for point sampling the glass scored 32 dB instead of 52).
 *
 * Two assertions over the glass pixels (ray hits glass at the pixel centre),
 * leaving out a band of ERODE pixels along the silhouette, where a
 * pixel-centre comparison measures float against double ray-triangle edge
 * tests (reported apart):
 *
 * 1. The bound from the sample count. Cycles' sharp Glass BSDF samples one
 *    branch per interface (reflection with probability F, the exact Fresnel
 *    reflectance, which FULL uses too), so its N-sample pixel is an unbiased
 *    estimate of the Whitted tree's value, with variance at most sigma^2 / N
 *    (independent samples; Cycles' stratified QMC does better), sigma^2 the
 *    per-sample variance that the reference computes exactly
 *    (snell_ref_output.sample_var: second moment over the tree's leaves).
 *    Over the P glass pixels (3 channels) the expected mean squared
 *    difference is E = mean(sigma^2) / N, and a mean of 3P bounded
 *    independent terms stays within a few percent of it. Asserted:
 *    MSE <= 1.25 E + (0.5/255)^2, i.e. glass-pixel PSNR >= 10 log10(1 /
 *    (1.25 E + (0.5/255)^2)) (36 dB on the sphere at 64 samples).
 * 2. A bias the noise cannot hide. With two renders A, B (seeds 1, 2), E|(A +
 *    B)/2 - R|^2 = bias^2 + s^2/2 and E|A - B|^2 = 2 s^2 for any sampling
 *    pattern, so bias^2 = mean|(A+B)/2 - R|^2 - mean|A - B|^2 / 4. Asserted:
 *    bias <= 1/255. Measured at 96x96, 64 samples: 0.00 (sphere) and 0.29
 *    (torus); with Schlick's approximation in FULL (the former model) 1.47
 *    and 1.79, so this fails if the reference's Fresnel regresses.
 *
 * argv: blender executable, cycles_render.py, image size (default 96),
 * samples per pixel (default 64), BOX (default 1: pixel centres; S > 1: the
 * pixel's area, Cycles' box filter against the reference's S x S grid, which
 * adds the grid's quadrature error, for the BENCHMARKS figure), a mesh file
 * to use instead of the shapes (the bunny: camera as snell-bench's) or "cube"
 * (a smooth-shaded cube of 4 x 4 quads a face, test_smooth_cube). Skipped (77)
 * where Blender is not installed. Writes gt_<mesh>_{cycles,full,diff}.png
 * (diff: grey = equal, differences x8). */
#define _POSIX_C_SOURCE 200809L
#include "test_util.h"
#include "snell/snell_ref.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define GT_PI 3.14159265358979323846
#define ENV_W 1024
#define ENV_H 512
#define BIAS_ALLOW (0.5 / 255.0) /* assertion 1: bias allowed on top of the noise */
#define NOISE_FACTOR 1.25         /* assertion 1: realisation over expectation */
#define ERODE 1                   /* silhouette band left out, pixels */
#define BIAS_PAIR (1.0 / 255.0)   /* assertion 2 */

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* snell -> Blender world frame. */
static void to_blender(const double s[3], double b[3])
{
    b[0] = s[0];
    b[1] = -s[2];
    b[2] = s[1];
}

/* The equirectangular image, RGBA8, top row first (as the PNG holds it). */
typedef struct equirect {
    uint8_t *px;
    int w, h;
} equirect;

/* Cycles' direction_to_equirectangular (range (-2pi, pi, -pi, pi)) of a
 * Blender-frame direction: u = 0.5 - atan2(y, x) / 2pi, v = 1 - acos(z) / pi,
 * v = 0 the image's bottom row; then its linear interpolation, x = u W - 0.5,
 * y = v H - 0.5, periodic in both. */
static void env_cycles(const double dir[3], double rgb[3], void *user)
{
    const equirect *e = (const equirect *)user;
    double b[3], len, u, v, x, y, fx, fy;
    int ix, iy, k, dx, dy;
    to_blender(dir, b);
    len = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    u = 0.5 - atan2(b[1], b[0]) / (2.0 * GT_PI);
    v = 1.0 - acos(fmax(-1.0, fmin(1.0, b[2] / len))) / GT_PI;
    x = u * e->w - 0.5;
    y = v * e->h - 0.5;
    ix = (int)floor(x);
    iy = (int)floor(y);
    fx = x - ix;
    fy = y - iy;
    for (k = 0; k < 3; k++) rgb[k] = 0.0;
    for (dy = 0; dy < 2; dy++)
        for (dx = 0; dx < 2; dx++) {
            int tx = ((ix + dx) % e->w + e->w) % e->w, ty = ((iy + dy) % e->h + e->h) % e->h;
            const uint8_t *p = e->px + 4 * ((size_t)(e->h - 1 - ty) * e->w + tx); /* bottom-up row ty */
            double wgt = (dx ? fx : 1.0 - fx) * (dy ? fy : 1.0 - fy);
            for (k = 0; k < 3; k++) rgb[k] += wgt * p[k] / 255.0;
        }
}

/* snell's procedural environment at each texel centre of the equirect image
 * (the inverse of env_cycles' mapping). */
static int bake_env(equirect *e, const char *path)
{
    snell_env *env = NULL;
    snell_env_desc ed;
    int x, y, k, ok;
    memset(&ed, 0, sizeof ed);
    if (snell_env_create(NULL, &ed, &env) != SNELL_OK) return 0;
    e->w = ENV_W;
    e->h = ENV_H;
    e->px = (uint8_t *)malloc((size_t)ENV_W * ENV_H * 4);
    for (y = 0; y < ENV_H; y++)
        for (x = 0; x < ENV_W; x++) {
            double u = (x + 0.5) / ENV_W, v = 1.0 - (y + 0.5) / ENV_H; /* y: top row 0 */
            double phi = -2.0 * GT_PI * u + GT_PI, th = GT_PI * (1.0 - v);
            double b[3] = {sin(th) * cos(phi), sin(th) * sin(phi), cos(th)}, s[3] = {b[0], b[2], -b[1]}, rgb[3];
            uint8_t *p = e->px + 4 * ((size_t)y * ENV_W + x);
            snell_env_sample_d(env, s, rgb);
            for (k = 0; k < 3; k++) p[k] = (uint8_t)(fmin(fmax(rgb[k], 0.0), 1.0) * 255.0 + 0.5);
            p[3] = 255;
        }
    snell_env_destroy(env);
    ok = snell_write_png(path, ENV_W, ENV_H, e->px) == SNELL_OK;
    return ok;
}

/* Camera-to-world in Blender's frame, row-major: C * inverse(view), with
 * view rigid (inverse = [R^T | -R^T t]) and C the frame change. */
static void camera_to_world(const snell_camera *cam, float aspect, double out[16])
{
    float eye[3], view[16], proj[16];
    double inv[4][4], c[3][3] = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
    int i, j, k;
    snell_camera_matrices(cam, aspect, eye, view, proj);
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) inv[i][j] = view[4 * i + j]; /* (R^T)[i][j] = R[j][i] = view[col i, row j] */
        inv[i][3] = eye[i];
        inv[3][i] = 0.0;
    }
    inv[3][3] = 1.0;
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            double s = 0.0;
            if (i == 3) {
                out[4 * i + j] = inv[3][j];
                continue;
            }
            for (k = 0; k < 3; k++) s += c[i][k] * inv[k][j];
            out[4 * i + j] = s;
        }
}

static float *read_floats(const char *path, size_t n)
{
    FILE *f = fopen(path, "rb");
    float *v = (float *)malloc(n * sizeof(float));
    int ok = f && v && fread(v, sizeof(float), n, f) == n;
    if (f) fclose(f);
    if (!ok) {
        free(v);
        return NULL;
    }
    return v;
}

static float *read_raw(const char *path, int w, int h)
{
    FILE *f = fopen(path, "rb");
    int32_t dim[2];
    float *rgb = NULL;
    size_t n = (size_t)w * h * 3;
    if (!f) return NULL;
    if (fread(dim, 4, 2, f) == 2 && dim[0] == w && dim[1] == h) {
        rgb = (float *)malloc(n * sizeof(float));
        if (rgb && fread(rgb, sizeof(float), n, f) != n) {
            free(rgb);
            rgb = NULL;
        }
    }
    fclose(f);
    return rgb;
}

static void write_images(const char *name, const float *cy, const float *rf, int w, int h)
{
    size_t n = (size_t)w * h, i;
    float *d = (float *)malloc(n * 3 * sizeof(float));
    uint8_t *px = (uint8_t *)malloc(n * 4);
    char file[128];
    snell_ref_rgb_to_rgba8(cy, w, h, px);
    snprintf(file, sizeof file, "gt_%s_cycles.png", name);
    snell_write_png(test_out(file), w, h, px);
    snell_ref_rgb_to_rgba8(rf, w, h, px);
    snprintf(file, sizeof file, "gt_%s_full.png", name);
    snell_write_png(test_out(file), w, h, px);
    for (i = 0; i < 3 * n; i++) d[i] = 0.5f + 8.0f * (cy[i] - rf[i]); /* grey = equal, x8 */
    snell_ref_rgb_to_rgba8(d, w, h, px);
    snprintf(file, sizeof file, "gt_%s_diff.png", name);
    snell_write_png(test_out(file), w, h, px);
    free(d);
    free(px);
}

typedef struct gt_case {
    const char *name;
    const char *path; /* a mesh file (normalised to the unit sphere), else the shape: */
    snell_shape shape;
    int segments, rings; /* segments 0: test_smooth_cube(rings) instead of a shape */
    float azimuth, elevation, distance;
} gt_case;

/* box: 1 = pixel centres (Cycles' 0.01-pixel Gaussian filter); S > 1 = the
 * pixel's area (Cycles' box filter, the reference's S x S grid). */
static void run_case(const gt_case *gc, const char *blender, const char *script, const equirect *env,
                     const char *env_path, int size, int samples, int box)
{
    snell_mesh *mesh = NULL, *shaded = NULL;
    snell_shape_desc sd;
    snell_glass g;
    snell_ref_desc rd;
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_ref_output o;
    snell_camera cam;
    double c2w[16], t0, t_cycles, t_ref, sum2 = 0.0, var = 0.0, bg2 = 0.0, bg_max = 0.0, edge2 = 0.0, mean2 = 0.0, pair2 = 0.0, bias, mse, expect, bound;
    size_t n = (size_t)size * size, i;
    float *rf = (float *)malloc(n * 3 * sizeof(float)), *sv = (float *)malloc(n * 3 * sizeof(float)), *cy;
    float *cys[2] = {NULL, NULL};
    uint8_t *hit = (uint8_t *)malloc(n);
    char mesh_path[256], normals_path[256], json_path[256], out_path[256], cmd[1600];
    long glass = 0, n_edge = 0;
    FILE *f;
    int k, seed;

    memset(&sd, 0, sizeof sd);
    sd.shape = gc->shape;
    sd.segments = gc->segments;
    sd.rings = gc->rings;
    if (gc->path) {
        CHECK_OK(snell_mesh_load(NULL, gc->path, &mesh));
        if (mesh) CHECK_OK(snell_mesh_normalize(mesh, 1.0f));
    } else if (gc->segments == 0) {
        mesh = test_smooth_cube(gc->rings);
        CHECK(mesh != NULL, "%s: the smooth cube", gc->name);
    } else {
        CHECK_OK(snell_mesh_create_shape(NULL, &sd, &mesh));
    }
    if (!mesh) return;
    memset(&cam, 0, sizeof cam);
    cam.azimuth = gc->azimuth;
    cam.elevation = gc->elevation;
    cam.distance = gc->distance;
    cam.fov_y = (float)(45.0 * GT_PI / 180.0);
    camera_to_world(&cam, 1.0f, c2w);

    snprintf(mesh_path, sizeof mesh_path, "%s", test_out("gt_mesh.bin"));
    snprintf(normals_path, sizeof normals_path, "%s", test_out("gt_normals.bin"));
    snprintf(json_path, sizeof json_path, "%s", test_out("gt_scene.json"));
    snprintf(out_path, sizeof out_path, "%s", test_out("gt_cycles.raw"));
    {
        snell_mesh_analysis an;
        CHECK_OK(snell_mesh_analyze(mesh, &an));
        CHECK(an.closed, "%s: the mesh must be closed for Cycles to tell inside from outside", gc->name);
        CHECK(test_write_blender_mesh(mesh, NULL, mesh_path, an.winding < 0), "write %s", mesh_path);
    }
    /* Two renders, seeds 1 and 2: the first for the bound, the pair for the
     * bias estimate. */
    t0 = now();
    for (seed = 1; seed <= 2; seed++) {
        f = fopen(json_path, "w");
        CHECK(f != NULL, "write %s", json_path);
        if (!f) return;
        fprintf(f, "{\"mesh\": \"%s\", \"normals_out\": \"%s\", \"env\": \"%s\", \"out\": \"%s\", \"camera\": [",
                mesh_path, normals_path, env_path, out_path);
        for (k = 0; k < 16; k++) fprintf(f, "%s%.17g", k ? ", " : "", c2w[k]);
        fprintf(f, "], \"fov_y\": %.17g, \"width\": %d, \"height\": %d, \"samples\": %d, \"seed\": %d, \"ior\": 1.5, "
                   "\"threads\": %ld, \"filter\": \"%s\"}\n",
                (double)cam.fov_y, size, size, samples, seed,
                sysconf(_SC_NPROCESSORS_ONLN) > 0 ? sysconf(_SC_NPROCESSORS_ONLN) : 1, box > 1 ? "box" : "point");
        fclose(f);
        remove(out_path);
        remove(normals_path);
        snprintf(cmd, sizeof cmd, "'%s' -b --factory-startup -noaudio -P '%s' -- '%s' > '%s' 2>&1", blender, script,
                 json_path, test_out("gt_blender.log"));
        k = system(cmd);
        cys[seed - 1] = read_raw(out_path, size, size);
        CHECK(k == 0 && cys[seed - 1] != NULL, "%s: Blender failed (status %d), see %s", gc->name, k,
              test_out("gt_blender.log"));
        if (!cys[seed - 1]) {
            free(cys[0]);
            snell_mesh_destroy(mesh);
            return;
        }
    }
    t_cycles = (now() - t0) / 2;
    cy = cys[0];

    /* The reference shades with the normals Cycles uses (Blender's own,
     * written by the script), turned back into snell's frame. */
    {
        float *nb = read_floats(normals_path, (size_t)snell_mesh_vertex_count(mesh) * 3), *ns;
        snell_mesh_desc md;
        uint32_t v, nv = snell_mesh_vertex_count(mesh);
        CHECK(nb != NULL, "%s: Blender's normals %s", gc->name, normals_path);
        if (!nb) return;
        ns = (float *)malloc((size_t)nv * 3 * sizeof(float));
        for (v = 0; v < nv; v++) {
            ns[3 * v] = nb[3 * v];
            ns[3 * v + 1] = nb[3 * v + 2];
            ns[3 * v + 2] = -nb[3 * v + 1];
        }
        memset(&md, 0, sizeof md);
        md.positions = snell_mesh_positions(mesh);
        md.normals = ns;
        md.indices = snell_mesh_indices(mesh);
        md.vertex_count = nv;
        md.triangle_count = snell_mesh_triangle_count(mesh);
        CHECK_OK(snell_mesh_create(NULL, &md, &shaded));
        free(nb);
        free(ns);
        if (!shaded) return;
    }
    memset(&g, 0, sizeof g);
    g.mesh = shaded;
    g.material.ior = 1.5f;
    memset(&rd, 0, sizeof rd);
    rd.glass = &g;
    rd.glass_count = 1;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    memset(&p, 0, sizeof p);
    p.mode = SNELL_REF_FULL;
    p.max_interfaces = SNELL_REF_MAX_INTERFACES; /* Cycles: 64 bounces */
    p.env_fn = env_cycles;
    p.env_user = (void *)env;
    p.camera = cam;
    p.width = p.height = size;
    p.samples = box;
    memset(&o, 0, sizeof o);
    o.rgb = rf;
    o.hit = hit;
    o.sample_var = sv;
    t0 = now();
    CHECK_OK(snell_ref_render(ref, &p, &o));
    t_ref = now() - t0;

    for (i = 0; i < n; i++) {
        int x = (int)(i % size), y = (int)(i / size), dx, dy, edge = 0;
        for (dy = -ERODE; dy <= ERODE; dy++)
            for (dx = -ERODE; dx <= ERODE; dx++) {
                int xx = x + dx, yy = y + dy;
                edge |= xx < 0 || yy < 0 || xx >= size || yy >= size || hit[(size_t)yy * size + xx] != hit[i];
            }
        if (edge) {
            for (k = 0; k < 3; k++) {
                double d = (double)cy[3 * i + k] - rf[3 * i + k];
                edge2 += d * d;
            }
            n_edge++;
            continue;
        }
        if (!hit[i]) {
            for (k = 0; k < 3; k++) {
                double d = (double)cy[3 * i + k] - rf[3 * i + k];
                bg2 += d * d;
                bg_max = fmax(bg_max, fabs(d));
            }
            continue;
        }
        glass++;
        for (k = 0; k < 3; k++) {
            double d = (double)cy[3 * i + k] - rf[3 * i + k];
            double m = 0.5 * ((double)cys[0][3 * i + k] + cys[1][3 * i + k]) - rf[3 * i + k];
            double ab = (double)cys[0][3 * i + k] - cys[1][3 * i + k];
            sum2 += d * d;
            var += sv[3 * i + k];
            mean2 += m * m;
            pair2 += ab * ab;
        }
    }
    CHECK(glass > (long)(n / 10), "%s: only %ld glass pixels", gc->name, glass);
    mse = sum2 / (3.0 * (double)glass);
    expect = var / (3.0 * (double)glass) / samples;
    bound = NOISE_FACTOR * expect + BIAS_ALLOW * BIAS_ALLOW;
    printf("%s %dx%d, %d samples, %s: Cycles %.1f s, FULL %.2f s; glass pixels %ld: PSNR %.2f dB (independent "
           "samples' noise alone %.2f dB, bound %.2f dB)\n",
           gc->name, size, size, samples, box > 1 ? "area" : "pixel centres", t_cycles, t_ref, glass,
           -10.0 * log10(mse), -10.0 * log10(expect), -10.0 * log10(bound));
    printf("%s background (%ld pixels, no noise there): PSNR %.2f dB, largest difference %.2f/255; silhouette "
           "band (%ld pixels): PSNR %.2f dB\n",
           gc->name, (long)n - glass - n_edge, -10.0 * log10(bg2 / (3.0 * (double)((long)n - glass - n_edge))),
           255.0 * bg_max, n_edge, -10.0 * log10(edge2 / (3.0 * (double)n_edge)));
    /* E|(A+B)/2 - R|^2 = bias^2 + s^2/2 and E|A - B|^2 = 2 s^2 whatever
     * Cycles' sampling pattern makes s^2 (its QMC beats independent sampling
     * by several dB): bias^2 = mean2 - pair2/4. */
    bias = sqrt(fmax(mean2 - 0.25 * pair2, 0.0) / (3.0 * (double)glass));
    printf("%s: bias from the seed pair %.2f/255 (allowed %.2f/255); Cycles' measured noise %.2f dB\n", gc->name,
           255.0 * bias, 255.0 * BIAS_PAIR, -10.0 * log10(0.5 * pair2 / (3.0 * (double)glass)));
    CHECK(bias <= BIAS_PAIR, "%s: systematic difference %.2f/255 from Cycles beyond %.2f/255", gc->name,
          255.0 * bias, 255.0 * BIAS_PAIR);
    CHECK(mse <= bound, "%s: glass-pixel PSNR %.2f dB below the bound %.2f dB from %d samples", gc->name,
          -10.0 * log10(mse), -10.0 * log10(bound), samples);
    write_images(gc->name, cy, rf, size, size);
    snell_ref_destroy(ref);
    snell_mesh_destroy(mesh);
    snell_mesh_destroy(shaded);
    free(cys[0]);
    free(cys[1]);
    free(rf);
    free(sv);
    free(hit);
}

int main(int argc, char **argv)
{
    static const gt_case cases[] = {
        {"sphere", NULL, SNELL_SHAPE_SPHERE, 256, 128, 0.5f, 0.25f, 3.5f},
        {"torus", NULL, SNELL_SHAPE_TORUS, 192, 96, 0.3f, 0.6f, 3.2f},
    };
    gt_case file_case = {"mesh", NULL, SNELL_SHAPE_SPHERE, 0, 0, 0.5235988f, 0.3490659f, 3.5f}; /* 30, 20 degrees */
    /* A smooth-shaded cube, whose rounded creases met the old FULL's rule for
     * smooth normals that face away (BENCHMARKS.md); not in CI: pixel centres
     * of its chaotic inner paths speckle beyond the bias assertion. */
    static const gt_case cube_case = {"cube", NULL, SNELL_SHAPE_CUBE, 0, 4, 0.6f, 0.45f, 5.0f};
    const char *blender = argc > 1 ? argv[1] : "blender", *script = argc > 2 ? argv[2] : "cycles_render.py";
    int size = argc > 3 ? atoi(argv[3]) : 96, samples = argc > 4 ? atoi(argv[4]) : 64;
    int box = argc > 5 ? atoi(argv[5]) : 1;
    char env_path[256], probe[600];
    equirect env;
    size_t c;
    if (size < 8 || size > 4096 || samples < 1 || box < 1 || box > SNELL_REF_MAX_SAMPLES) {
        fprintf(stderr, "usage: test_groundtruth BLENDER SCRIPT [SIZE 8..4096] [SAMPLES >= 1] [BOX 1..16]\n");
        return 2;
    }
    snprintf(probe, sizeof probe, "'%s' --version > /dev/null 2>&1", blender);
    if (system(probe) != 0) SKIP("Blender (%s) is not installed: apt-get install blender", blender);
    snprintf(env_path, sizeof env_path, "%s", test_out("gt_env.png"));
    CHECK(bake_env(&env, env_path), "bake the environment into %s", env_path);
    if (argc > 6 && !strcmp(argv[6], "cube")) {
        run_case(&cube_case, blender, script, &env, env_path, size, samples, box);
    } else if (argc > 6) { /* a mesh file instead of the shapes, e.g. the bunny for BENCHMARKS.md */
        file_case.path = argv[6];
        run_case(&file_case, blender, script, &env, env_path, size, samples, box);
    } else {
        for (c = 0; c < sizeof cases / sizeof *cases; c++)
            run_case(&cases[c], blender, script, &env, env_path, size, samples, box);
    }
    free(env.px);
    return test_finish();
}
