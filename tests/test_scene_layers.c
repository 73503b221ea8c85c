/* SPDX-License-Identifier: MIT */
/* test_scene_layers — glass seen through glass, and opaque objects seen
 * through glass where they are (issue 13: render/layers.c,
 * shaders_es/common/beyond.glsl, peel_layer.frag's ids).
 *
 * The scene: three glass objects overlapping on screen at three depths (two
 * spheres and a rotated cube) and two opaque boxes, a small red one between
 * the front sphere and the middle one and a long green one behind them all.
 * Each is compared, glass pixels only (the reference's view ray hits glass
 * first), with the reference tracer over the whole scene (isolate_glass 0):
 *
 * 1. Exit directions against the reference's MATCHED chain with 8
 *    interfaces, which goes on from one glass object into the next (the
 *    kernels' model: Schlick at the entry, no inner Fresnel). Scene layers on
 *    against off (off: each object's exit ray goes straight to the
 *    environment, the pre-#13 renderer). Required: the median error with the
 *    layers at most a third of that without, and below 0.05 rad; measured
 *    at 160x160 (see the printout).
 * 2. Colour against FULL (the Whitted tree, exact Fresnel, whole scene):
 *    glass-pixel PSNR with the layers at least 3 dB above without them.
 * 3. Stats: the stage runs with 3 glass + 2 opaque (peels 2..8, layers
 *    used > 2, no dynamic environment made: SNELL_SKIP_DYNAMIC_ENV), does
 *    not run for one glass object alone, and scene_layers = -1 turns it off;
 *    out-of-range values are refused. A still frame reuses the last frame's
 *    layers (no peel; the image bitwise the same as one peeled afresh); a
 *    moved object, a moved camera or another mesh version peels again.
 * 4. Two spheres on the view axis, one behind the other: through both, the
 *    image is bent twice; the exit directions match MATCHED as in 1.
 * 6. An opaque red box between two spheres side by side, a little behind
 *    them: each sphere shows it (a ball lens turns the view to the other
 *    side). Per sphere, the red pixels of the image (red well above green
 *    and blue) against the reference's FULL image: their overlap
 *    (intersection over union) with the layers at least 0.6 in each sphere
 *    and above that of the dynamic environment (layers off), whose one
 *    centre per sphere misplaces a box this near.
 * 5. A thin-walled, strongly tinted sphere behind a solid one: through the
 *    solid sphere it is seen by the slab model, the whole object one slab as
 *    in the reference (colour against MATCHED over the pixels whose path
 *    crosses both: the mean worst-channel error with the layers below
 *    15/255 and a fifth of that without; measured 7.4 against 144; both
 *    walls as slabs: 25). */
#include "test_util.h"
#include "snell/snell_metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 192
#define H 192

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void translate_scale(float m[16], float x, float y, float z, float s, float rot_y)
{
    float c = cosf(rot_y), sn = sinf(rot_y);
    memset(m, 0, 16 * sizeof *m);
    m[0] = s * c;
    m[2] = -s * sn;
    m[5] = s;
    m[8] = s * sn;
    m[10] = s * c;
    m[12] = x;
    m[13] = y;
    m[14] = z;
    m[15] = 1.0f;
}

typedef struct scene {
    snell_mesh *sphere, *cube;
    snell_glass glass[3];
    snell_opaque opaque[2];
    float gm[3][16], om[2][16];
    snell_frame_desc fd;
} scene;

static int make_scene(snell_ctx *ctx, snell_env *env, scene *s)
{
    snell_shape_desc sd;
    memset(s, 0, sizeof *s);
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &s->sphere));
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &s->cube));
    if (!s->sphere || !s->cube) return 0;
    CHECK_OK(snell_mesh_normalize(s->cube, 1.0f));
    translate_scale(s->gm[0], -0.3f, 0.05f, 1.3f, 0.5f, 0.0f);
    translate_scale(s->gm[1], 0.35f, 0.1f, -0.4f, 0.7f, 0.0f);
    translate_scale(s->gm[2], 1.1f, -0.1f, -2.5f, 0.7f, 0.5f);
    translate_scale(s->om[0], 0.05f, -0.35f, 0.45f, 0.22f, 0.3f);
    translate_scale(s->om[1], -0.2f, 0.5f, -4.0f, 0.6f, 0.2f);
    s->glass[0].mesh = s->sphere;
    s->glass[1].mesh = s->sphere;
    s->glass[2].mesh = s->cube;
    for (int i = 0; i < 3; i++) s->glass[i].model = s->gm[i];
    s->opaque[0].mesh = s->cube;
    s->opaque[0].model = s->om[0];
    s->opaque[0].color[0] = 0.85f;
    s->opaque[0].color[1] = 0.15f;
    s->opaque[0].color[2] = 0.1f;
    s->opaque[1].mesh = s->cube;
    s->opaque[1].model = s->om[1];
    s->opaque[1].color[0] = 0.1f;
    s->opaque[1].color[1] = 0.7f;
    s->opaque[1].color[2] = 0.2f;
    memset(&s->fd, 0, sizeof s->fd);
    s->fd.env = env;
    s->fd.camera.distance = 4.5f;
    s->fd.camera.azimuth = 0.15f;
    s->fd.camera.elevation = 0.1f;
    s->fd.glass = s->glass;
    s->fd.glass_count = 3;
    s->fd.opaque = s->opaque;
    s->fd.opaque_count = 2;
    return 1;
}

static void free_scene(scene *s)
{
    snell_mesh_destroy(s->sphere);
    snell_mesh_destroy(s->cube);
}

/* Exit directions (dirs) or colour (rgba) of the frame. */
static snell_status render(snell_ctx *ctx, const snell_frame_desc *fd, float *dirs, uint8_t *rgba,
                           snell_frame_stats *stats)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_status st;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = rgba ? SNELL_OUTPUT_COLOR : SNELL_OUTPUT_EXIT_DIRECTION;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r) return SNELL_E_GL;
    st = snell_render(r, fd, stats);
    if (st == SNELL_OK && rgba) CHECK_OK(snell_renderer_read_rgba(r, rgba));
    else if (st == SNELL_OK) CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
    snell_renderer_destroy(r);
    return st;
}

/* The reference over the whole scene; interfaces may be NULL. */
static void reference(snell_ctx *ctx, const snell_frame_desc *fd, snell_ref_mode mode, float *rgb, float *dirs,
                      uint8_t *hit, uint8_t *interfaces)
{
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_ref_output out;
    CHECK_OK(test_ref_create(ctx, fd, &ref));
    if (!ref) return;
    test_ref_params(fd, W, H, 8, &p);
    p.mode = mode;
    p.isolate_glass = 0;
    memset(&out, 0, sizeof out);
    out.rgb = rgb;
    out.exit_dir = dirs;
    out.hit = hit;
    out.interfaces = interfaces;
    CHECK_OK(snell_ref_render(ref, &p, &out));
    snell_ref_destroy(ref);
}

/* Median and mean exit-direction error over the glass pixels whose
 * reference path crosses more than min_interfaces surfaces; *count: how many. */
static void dir_error(const float *gpu, const float *ref, const uint8_t *hit, const uint8_t *interfaces,
                      int min_interfaces, double *median, double *mean, int *count)
{
    static double e[W * H];
    int n = 0;
    double sum = 0.0;
    for (int i = 0; i < W * H; i++) {
        if (!hit[i] || interfaces[i] <= min_interfaces) continue;
        e[n] = snell_metrics_angle(gpu + 3 * i, ref + 3 * i);
        if (!(e[n] == e[n])) e[n] = 3.14159;
        sum += e[n++];
    }
    qsort(e, (size_t)n, sizeof *e, cmp_double);
    *median = n ? e[n / 2] : 0.0;
    *mean = n ? sum / n : 0.0;
    *count = n;
}

/* Glass-pixel PSNR of the GPU's 8-bit colour against the reference's. */
static double glass_psnr(const uint8_t *rgba, const float *rgb, const uint8_t *hit)
{
    double se = 0.0;
    long n = 0;
    for (int i = 0; i < W * H; i++) {
        if (!hit[i]) continue;
        for (int c = 0; c < 3; c++) {
            double r = rgb[3 * i + c] > 1.0f ? 1.0 : rgb[3 * i + c], d = rgba[4 * i + c] / 255.0 - r;
            se += d * d;
        }
        n += 3;
    }
    return n && se > 0.0 ? 10.0 * log10((double)n / se) : 99.0;
}

static void write_png(const char *name, const uint8_t *rgba)
{
    CHECK_OK(snell_write_png(test_out(name), W, H, rgba));
}

static void test_three_glass_two_opaque(snell_ctx *ctx, snell_env *env)
{
    static float on[W * H * 3], off[W * H * 3], ref[W * H * 3], rgb[W * H * 3];
    static uint8_t hit[W * H], ifs[W * H], c_on[W * H * 4], c_off[W * H * 4], c_ref[W * H * 4];
    scene s;
    snell_frame_stats st;
    double med_on, mean_on, med_off, mean_off, p_on, p_off;
    int n_deep, n_all;
    if (!make_scene(ctx, env, &s)) goto out;

    reference(ctx, &s.fd, SNELL_REF_MATCHED, rgb, ref, hit, ifs);
    CHECK_OK(render(ctx, &s.fd, on, NULL, &st));
    /* up to 7 surfaces along a view ray here: more than the 4 layers first
     * made room for, so the stage grows them and peels again in this frame */
    printf("3 glass + 2 opaque: %d peels, %d layers used\n", st.scene_layer_passes, st.scene_layers);
    CHECK(st.scene_layers > 4 && st.scene_layer_passes > st.scene_layers + 1, "scene layers: %d peels, %d used (%s)",
          st.scene_layer_passes, st.scene_layers, st.scene_layers_reason);
    for (int i = 0; i < 3; i++)
        CHECK(st.glass[i].skipped & SNELL_SKIP_DYNAMIC_ENV, "glass %d made a dynamic environment", i);
    s.fd.scene_layers = -1;
    CHECK_OK(render(ctx, &s.fd, off, NULL, &st));
    CHECK(st.scene_layer_passes == 0 && !(st.glass[0].skipped & SNELL_SKIP_DYNAMIC_ENV),
          "scene_layers -1: %d peels", st.scene_layer_passes);
    s.fd.scene_layers = 0;
    /* the paths that meet more than one object (or bounce inside the cube) */
    dir_error(on, ref, hit, ifs, 2, &med_on, &mean_on, &n_deep);
    dir_error(off, ref, hit, ifs, 2, &med_off, &mean_off, &n_deep);
    printf("3 glass + 2 opaque, %d glass pixels whose MATCHED(8) path crosses > 2 surfaces, exit direction error "
           "median/mean rad: layers %.4f/%.4f, each alone %.4f/%.4f\n", n_deep, med_on, mean_on, med_off, mean_off);
    CHECK(n_deep > W * H / 50, "only %d pixels see glass through glass", n_deep);
    CHECK(med_on <= med_off / 4.0 && med_on < 0.1, "median %.4f with layers, %.4f without", med_on, med_off);
    dir_error(on, ref, hit, ifs, 0, &med_on, &mean_on, &n_all);
    dir_error(off, ref, hit, ifs, 0, &med_off, &mean_off, &n_all);
    printf("3 glass + 2 opaque, all %d glass pixels: layers %.4f/%.4f, each alone %.4f/%.4f\n", n_all, med_on,
           mean_on, med_off, mean_off);
    CHECK(mean_on <= mean_off / 2.0, "mean %.4f with layers, %.4f without", mean_on, mean_off);

    reference(ctx, &s.fd, SNELL_REF_FULL, rgb, NULL, hit, NULL);
    CHECK_OK(render(ctx, &s.fd, NULL, c_on, &st));
    s.fd.scene_layers = -1;
    CHECK_OK(render(ctx, &s.fd, NULL, c_off, &st));
    s.fd.scene_layers = 0;
    p_on = glass_psnr(c_on, rgb, hit);
    p_off = glass_psnr(c_off, rgb, hit);
    printf("3 glass + 2 opaque, glass-pixel PSNR against FULL: layers %.2f dB, each alone %.2f dB\n", p_on, p_off);
    CHECK(p_on >= p_off + 5.0, "PSNR %.2f with layers, %.2f without", p_on, p_off);
    for (int i = 0; i < W * H; i++) {
        for (int c = 0; c < 3; c++) {
            float v = rgb[3 * i + c];
            c_ref[4 * i + c] = (uint8_t)(v >= 1.0f ? 255 : v <= 0.0f ? 0 : (int)(v * 255.0f + 0.5f));
        }
        c_ref[4 * i + 3] = 255;
    }
    write_png("scene_layers_on.png", c_on);
    write_png("scene_layers_off.png", c_off);
    write_png("scene_layers_full.png", c_ref);
out:
    free_scene(&s);
}

/* Reuse of the layers across frames by one renderer. */
static void test_reuse(snell_ctx *ctx, snell_env *env)
{
    static uint8_t a[W * H * 4], b[W * H * 4];
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_stats st;
    scene s;
    if (!make_scene(ctx, env, &s)) goto out;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r) goto out;
    CHECK_OK_CTX(ctx, snell_render(r, &s.fd, &st));
    CHECK(!st.scene_layers_reused && st.scene_layer_passes >= 2, "first frame: reused %d, %d peels",
          st.scene_layers_reused, st.scene_layer_passes);
    CHECK_OK(snell_renderer_read_rgba(r, a));
    CHECK_OK_CTX(ctx, snell_render(r, &s.fd, &st));
    CHECK(st.scene_layers_reused && st.scene_layer_passes == 0, "still frame: reused %d, %d peels",
          st.scene_layers_reused, st.scene_layer_passes);
    CHECK_OK(snell_renderer_read_rgba(r, b));
    CHECK(!memcmp(a, b, sizeof a), "the still frame's image differs from the peeled one");
    s.om[0][12] += 0.05f;
    CHECK_OK_CTX(ctx, snell_render(r, &s.fd, &st));
    CHECK(!st.scene_layers_reused && st.scene_layer_passes >= 2, "moved opaque object: reused %d",
          st.scene_layers_reused);
    s.fd.camera.azimuth += 0.01f;
    CHECK_OK_CTX(ctx, snell_render(r, &s.fd, &st));
    CHECK(!st.scene_layers_reused, "moved camera: layers reused");
    CHECK_OK(snell_mesh_normalize(s.cube, 1.0f)); /* a new geometry version */
    CHECK_OK_CTX(ctx, snell_render(r, &s.fd, &st));
    CHECK(!st.scene_layers_reused, "new mesh version: layers reused");
    s.glass[0].material.ior = 1.33f; /* materials are the table's, rewritten every frame */
    CHECK_OK_CTX(ctx, snell_render(r, &s.fd, &st));
    CHECK(st.scene_layers_reused, "a material change re-peeled");
    snell_renderer_destroy(r);
out:
    free_scene(&s);
}

static void test_stage_rule(snell_ctx *ctx, snell_env *env)
{
    static float d[W * H * 3];
    scene s;
    snell_frame_stats st;
    if (!make_scene(ctx, env, &s)) goto out;
    s.fd.glass_count = 1;
    s.fd.opaque_count = 0;
    CHECK_OK(render(ctx, &s.fd, d, NULL, &st));
    CHECK(st.scene_layer_passes == 0 && strstr(st.scene_layers_reason, "not needed"), "one glass: %d peels (%s)",
          st.scene_layer_passes, st.scene_layers_reason);
    s.fd.opaque_count = 1;
    CHECK_OK(render(ctx, &s.fd, d, NULL, &st));
    CHECK(st.scene_layer_passes >= 2, "one glass + one opaque: %d peels (%s)", st.scene_layer_passes,
          st.scene_layers_reason);
    s.fd.scene_layers = 2;
    CHECK_OK(render(ctx, &s.fd, d, NULL, &st));
    CHECK(st.scene_layer_passes == 2, "scene_layers 2: %d peels", st.scene_layer_passes);
    s.fd.scene_layers = 1;
    CHECK(render(ctx, &s.fd, d, NULL, &st) == SNELL_E_INVALID_ARG, "scene_layers 1 accepted");
    s.fd.scene_layers = SNELL_MAX_SCENE_LAYERS + 1;
    CHECK(render(ctx, &s.fd, d, NULL, &st) == SNELL_E_INVALID_ARG, "scene_layers %d accepted",
          SNELL_MAX_SCENE_LAYERS + 1);
out:
    free_scene(&s);
}

/* Two spheres on the view axis: through both, bent twice. */
static void test_two_on_axis(snell_ctx *ctx, snell_env *env)
{
    static float on[W * H * 3], off[W * H * 3], ref[W * H * 3], rgb[W * H * 3];
    static uint8_t hit[W * H], ifs[W * H], c[W * H * 4];
    scene s;
    snell_frame_stats st;
    double med_on, mean_on, med_off, mean_off;
    int n;
    if (!make_scene(ctx, env, &s)) goto out;
    translate_scale(s.gm[0], 0.0f, 0.0f, 1.0f, 0.6f, 0.0f);
    translate_scale(s.gm[1], 0.0f, 0.0f, -1.5f, 0.9f, 0.0f);
    s.fd.glass_count = 2;
    s.fd.opaque_count = 0;
    s.fd.camera.azimuth = 0.0f;
    s.fd.camera.elevation = 0.0f;
    reference(ctx, &s.fd, SNELL_REF_MATCHED, rgb, ref, hit, ifs);
    CHECK_OK(render(ctx, &s.fd, on, NULL, &st));
    s.fd.scene_layers = -1;
    CHECK_OK(render(ctx, &s.fd, off, NULL, &st));
    s.fd.scene_layers = 0;
    dir_error(on, ref, hit, ifs, 2, &med_on, &mean_on, &n);
    dir_error(off, ref, hit, ifs, 2, &med_off, &mean_off, &n);
    printf("two spheres on the axis, %d pixels through both, exit direction error against MATCHED(8) median/mean "
           "rad: layers %.4f/%.4f, each alone %.4f/%.4f\n", n, med_on, mean_on, med_off, mean_off);
    CHECK(n > W * H / 50, "only %d pixels see the far sphere through the near one", n);
    CHECK(med_on <= med_off / 10.0 && med_on < 0.02, "median %.4f with layers, %.4f without", med_on, med_off);
    CHECK_OK(render(ctx, &s.fd, NULL, c, &st));
    write_png("two_on_axis.png", c);
out:
    free_scene(&s);
}

/* A tinted thin wall seen through a solid sphere. */
static void test_thin_behind(snell_ctx *ctx, snell_env *env)
{
    static float ref[W * H * 3], rgb[W * H * 3];
    static uint8_t hit[W * H], ifs[W * H], c_on[W * H * 4], c_off[W * H * 4];
    scene s;
    snell_frame_stats st;
    double e_on = 0.0, e_off = 0.0;
    int n = 0;
    if (!make_scene(ctx, env, &s)) goto out;
    translate_scale(s.gm[0], 0.0f, 0.0f, 1.0f, 0.6f, 0.0f);
    translate_scale(s.gm[1], 0.0f, 0.0f, -1.5f, 1.2f, 0.0f);
    s.glass[1].material.thickness = 0.02f;
    s.glass[1].material.tint[0] = 1.0f;
    s.glass[1].material.tint[1] = 0.3f;
    s.glass[1].material.tint[2] = 0.2f;
    s.fd.glass_count = 2;
    s.fd.opaque_count = 0;
    s.fd.camera.azimuth = 0.0f;
    s.fd.camera.elevation = 0.0f;
    reference(ctx, &s.fd, SNELL_REF_MATCHED, rgb, ref, hit, ifs);
    CHECK_OK(render(ctx, &s.fd, NULL, c_on, &st));
    CHECK(st.scene_layer_passes >= 2 && strstr(st.scene_layers_reason, "1 thin"), "thin wall: %d peels (%s)",
          st.scene_layer_passes, st.scene_layers_reason);
    s.fd.scene_layers = -1;
    CHECK_OK(render(ctx, &s.fd, NULL, c_off, &st));
    for (int i = 0; i < W * H; i++) {
        double w_on = 0.0, w_off = 0.0;
        if (!hit[i] || ifs[i] <= 2) continue;
        for (int c = 0; c < 3; c++) {
            double r = rgb[3 * i + c] > 1.0f ? 1.0 : rgb[3 * i + c];
            w_on = fmax(w_on, fabs(c_on[4 * i + c] / 255.0 - r));
            w_off = fmax(w_off, fabs(c_off[4 * i + c] / 255.0 - r));
        }
        e_on += w_on;
        e_off += w_off;
        n++;
    }
    e_on = n ? 255.0 * e_on / n : 0.0;
    e_off = n ? 255.0 * e_off / n : 0.0;
    printf("thin wall behind a sphere, %d pixels through both: mean worst-channel error against MATCHED %.2f/255 "
           "with layers, %.2f/255 without\n", n, e_on, e_off);
    CHECK(n > W * H / 50, "only %d pixels see the thin wall through the sphere", n);
    CHECK(e_on <= 0.2 * e_off && e_on < 15.0, "error %.2f/255 with layers, %.2f without", e_on, e_off);
    write_png("thin_behind.png", c_on);
out:
    free_scene(&s);
}

static int red(const uint8_t *c) { return c[0] > 120 && c[0] > 2 * c[1] + 20 && c[0] > 2 * c[2] + 20; }

/* An opaque box between two glass spheres. */
static void test_opaque_between(snell_ctx *ctx, snell_env *env)
{
    static float rgb[W * H * 3];
    static uint8_t c_on[W * H * 4], c_off[W * H * 4], c_ref[W * H * 4];
    static int16_t object[W * H];
    scene s;
    snell_frame_stats st;
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_ref_output out;
    if (!make_scene(ctx, env, &s)) goto out;
    translate_scale(s.gm[0], -0.7f, 0.0f, 0.0f, 0.6f, 0.0f);
    translate_scale(s.gm[1], 0.7f, 0.0f, 0.0f, 0.6f, 0.0f);
    translate_scale(s.om[0], 0.0f, 0.0f, -1.6f, 0.55f, 0.4f);
    s.fd.glass_count = 2;
    s.fd.opaque_count = 1;
    s.fd.camera.azimuth = 0.0f;
    s.fd.camera.elevation = 0.0f;
    s.fd.camera.distance = 4.0f;
    CHECK_OK(test_ref_create(ctx, &s.fd, &ref));
    if (!ref) goto out;
    test_ref_params(&s.fd, W, H, 8, &p);
    p.mode = SNELL_REF_FULL;
    memset(&out, 0, sizeof out);
    out.rgb = rgb;
    out.object = object;
    CHECK_OK(snell_ref_render(ref, &p, &out));
    snell_ref_destroy(ref);
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 4; c++)
            c_ref[4 * i + c] = c == 3 ? 255 : (uint8_t)(rgb[3 * i + c] >= 1.0f ? 255 : (int)(rgb[3 * i + c] * 255.0f + 0.5f));
    CHECK_OK(render(ctx, &s.fd, NULL, c_on, &st));
    s.fd.scene_layers = -1;
    CHECK_OK(render(ctx, &s.fd, NULL, c_off, &st));
    for (int g = 0; g < 2; g++) {
        int in_ref = 0, both_on = 0, any_on = 0, both_off = 0, any_off = 0;
        for (int i = 0; i < W * H; i++) {
            int r = red(c_ref + 4 * i), a = red(c_on + 4 * i), b = red(c_off + 4 * i);
            if (object[i] != g) continue;
            in_ref += r;
            both_on += r && a;
            any_on += r || a;
            both_off += r && b;
            any_off += r || b;
        }
        double iou_on = any_on ? (double)both_on / any_on : 0.0, iou_off = any_off ? (double)both_off / any_off : 0.0;
        printf("opaque box between two spheres, sphere %d: %d red pixels in FULL, overlap with it %.3f with layers, "
               "%.3f with the dynamic environment\n", g, in_ref, iou_on, iou_off);
        CHECK(in_ref > W * H / 400, "sphere %d shows the box in only %d pixels of FULL", g, in_ref);
        CHECK(iou_on >= 0.6 && iou_on > iou_off, "sphere %d: overlap %.3f with layers, %.3f without", g, iou_on,
              iou_off);
    }
    write_png("opaque_between.png", c_on);
    write_png("opaque_between_full.png", c_ref);
    write_png("opaque_between_dynamic.png", c_off);
out:
    free_scene(&s);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 128);
    if (!env) return test_finish();
    test_three_glass_two_opaque(ctx, env);
    test_stage_rule(ctx, env);
    test_reuse(ctx, env);
    test_two_on_axis(ctx, env);
    test_thin_behind(ctx, env);
    test_opaque_between(ctx, env);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
