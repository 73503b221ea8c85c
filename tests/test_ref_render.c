/* SPDX-License-Identifier: MIT */
/* test_ref_render — image-level properties of the reference tracer on the
 * glmark2 bunny (or, without it, the torus), a glass sphere and scenes of
 * several glass and opaque objects:
 *  (d) determinism: images, exit directions, interface counts, hit masks and
 *      object ids are bitwise equal for 1, 2 and 5 threads, MATCHED and FULL,
 *      for one object and for a scene (solid, thin and opaque objects, with
 *      and without isolate_glass);
 *  (e) energy: with a white environment, no absorption and no tint every
 *      pixel is 1 (F + (1-F) = 1 at each split, rs + ts = 1 at a thin wall,
 *      MATCHED and FULL) within 1e-6, also for a scene of three glass
 *      objects, and no NaN/Inf anywhere; with absorption every pixel is <= 1;
 *  - trace_pixel reproduces the rendered pixel; background pixels carry the
 *    view ray; a model matrix equals pre-transformed geometry;
 *  - object ids: every pixel's id is the box its view ray meets first, found
 *    here by a slab test against the boxes (glass i -> i, opaque j -> -2 - j);
 *  - separation: glass A | opaque wall | glass B renders, pixel for pixel,
 *    as {A, wall} on A's side and {B, wall} on B's (no path can cross the
 *    wall), MATCHED and FULL; with isolate_glass, {A, B} renders as {A} where
 *    A is seen first and as {B} where B is;
 *  - area sampling (samples = S) is the S x S block mean of the S-times image;
 *    sample_var is the block spread in MATCHED mode, 0 in a white world;
 *  - snell_ref_set_material gives the image of a reference created with that
 *    material; bad input gives a status and a message;
 *  - renders of the bunny, a sphere and a scene (MATCHED and FULL) are written
 *    as PNGs with their timings. argv[1] = image size (default 256). */
#define _POSIX_C_SOURCE 200809L
#include "test_util.h"
#include "snell/snell_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static void white(const double dir[3], double rgb[3], void *user)
{
    (void)dir;
    (void)user;
    rgb[0] = rgb[1] = rgb[2] = 1.0;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct img {
    int w, h;
    float *rgb, *dir;
    uint8_t *nif, *hit;
    int16_t *obj;
} img;

static img img_new(int w, int h)
{
    img m;
    m.w = w;
    m.h = h;
    m.rgb = (float *)calloc((size_t)w * h * 3, sizeof(float));
    m.dir = (float *)calloc((size_t)w * h * 3, sizeof(float));
    m.nif = (uint8_t *)calloc((size_t)w * h, 1);
    m.hit = (uint8_t *)calloc((size_t)w * h, 1);
    m.obj = (int16_t *)calloc((size_t)w * h, sizeof(int16_t));
    return m;
}

static void img_free(img *m)
{
    free(m->rgb);
    free(m->dir);
    free(m->nif);
    free(m->hit);
    free(m->obj);
}

static snell_status render(const snell_ref *ref, snell_ref_params *p, img *m)
{
    snell_ref_output o;
    memset(&o, 0, sizeof o);
    o.rgb = m->rgb;
    o.exit_dir = m->dir;
    o.interfaces = m->nif;
    o.hit = m->hit;
    o.object = m->obj;
    p->width = m->w;
    p->height = m->h;
    return snell_ref_render(ref, p, &o);
}

static int img_equal(const img *a, const img *b)
{
    size_t n = (size_t)a->w * a->h;
    return !memcmp(a->rgb, b->rgb, n * 3 * sizeof(float)) && !memcmp(a->dir, b->dir, n * 3 * sizeof(float)) &&
           !memcmp(a->nif, b->nif, n) && !memcmp(a->hit, b->hit, n) && !memcmp(a->obj, b->obj, n * sizeof(int16_t));
}

static void write_png(const char *name, const img *m)
{
    uint8_t *px = (uint8_t *)malloc((size_t)m->w * m->h * 4);
    snell_ref_rgb_to_rgba8(m->rgb, m->w, m->h, px);
    CHECK_OK(snell_write_png(test_out(name), m->w, m->h, px));
    printf("wrote %s\n", test_out(name));
    free(px);
}

/* A glass material: ior (0 = default 1.5), per-unit absorption, tint (all
 * zero = white) and thin-wall thickness (0 = solid). */
static snell_glass_material material(float ior, float s0, float s1, float s2, float t0, float t1, float t2,
                                     float thickness)
{
    snell_glass_material m;
    float sig[3];
    memset(&m, 0, sizeof m);
    m.ior = ior;
    sig[0] = s0;
    sig[1] = s1;
    sig[2] = s2;
    snell_glass_set_absorption(&m, sig);
    m.tint[0] = t0;
    m.tint[1] = t1;
    m.tint[2] = t2;
    m.thickness = thickness;
    return m;
}

/* A reference of one glass mesh with a model and material (NULL = defaults). */
static snell_ref *one_glass(const snell_mesh *mesh, const float *model, const snell_glass_material *m)
{
    snell_glass g;
    snell_ref_desc rd;
    snell_ref *ref = NULL;
    memset(&g, 0, sizeof g);
    memset(&rd, 0, sizeof rd);
    g.mesh = mesh;
    g.model = model;
    if (m) g.material = *m;
    rd.glass = &g;
    rd.glass_count = 1;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    return ref;
}

/* Bitwise the same result for 1, 2 and 5 threads, MATCHED and FULL, with
 * and without isolate_glass (with the materials ref has). */
static void determinism(const char *name, const snell_ref *ref, snell_ref_params base)
{
    int mode;
    for (mode = 0; mode < 4; mode++) {
        img a = img_new(96, 80), b = img_new(96, 80), c = img_new(96, 80);
        snell_ref_params p = base;
        p.mode = mode & 1 ? SNELL_REF_FULL : SNELL_REF_MATCHED;
        p.isolate_glass = mode >> 1;
        p.threads = 1;
        CHECK_OK(render(ref, &p, &a));
        p.threads = 2;
        CHECK_OK(render(ref, &p, &b));
        p.threads = 5;
        CHECK_OK(render(ref, &p, &c));
        CHECK(img_equal(&a, &b) && img_equal(&a, &c), "%s, mode %d isolate %d: result depends on the thread count",
              name, mode & 1, mode >> 1);
        img_free(&a);
        img_free(&b);
        img_free(&c);
    }
}

/* White environment: every pixel 1 for the materials given (no absorption,
 * no tint: white[i]) and <= 1 for absorbing ones (absorbing[i]). */
static void energy(const char *name, snell_ref *ref, int count, const snell_glass_material *white_m,
                   const snell_glass_material *absorbing, snell_ref_params base)
{
    int mode, i;
    for (mode = 0; mode < 4; mode++) {
        img a = img_new(64, 64);
        snell_ref_params p = base;
        size_t k, bad = 0, nonfinite = 0, above = 0, hits = 0;
        p.mode = mode & 1 ? SNELL_REF_FULL : SNELL_REF_MATCHED;
        p.isolate_glass = mode >> 1;
        p.env = NULL;
        p.env_fn = white;
        for (i = 0; i < count; i++) CHECK_OK(snell_ref_set_material(ref, i, &white_m[i]));
        CHECK_OK(render(ref, &p, &a));
        for (k = 0; k < (size_t)64 * 64 * 3; k++) {
            if (!isfinite(a.rgb[k]) || !isfinite(a.dir[k])) nonfinite++;
            if (fabs(a.rgb[k] - 1.0) > 1e-6) bad++; /* float output: 1e-6 */
        }
        for (k = 0; k < (size_t)64 * 64; k++) hits += a.hit[k];
        for (i = 0; i < count; i++) CHECK_OK(snell_ref_set_material(ref, i, &absorbing[i]));
        CHECK_OK(render(ref, &p, &a));
        for (k = 0; k < (size_t)64 * 64 * 3; k++) {
            if (!isfinite(a.rgb[k])) nonfinite++;
            if (a.rgb[k] > 1.0f + 1e-6f || a.rgb[k] < 0.0f) above++;
        }
        printf("energy %s, mode %d isolate %d: %zu hit pixels\n", name, mode & 1, mode >> 1, hits);
        CHECK(hits > 200, "%s mode %d: the objects cover only %zu pixels", name, mode, hits);
        CHECK(nonfinite == 0, "%s mode %d: %zu NaN/Inf values", name, mode, nonfinite);
        CHECK(bad == 0, "%s mode %d: %zu channels differ from 1 in a white environment", name, mode, bad);
        CHECK(above == 0, "%s mode %d: %zu channels outside [0, 1] with absorption", name, mode, above);
        img_free(&a);
    }
    for (i = 0; i < count; i++) CHECK_OK(snell_ref_set_material(ref, i, &white_m[i]));
}

static void paths_and_outputs(const char *name, const snell_ref *ref, snell_ref_params p)
{
    img a = img_new(80, 60);
    int x, y, bad_path = 0, bad_bg = 0, bad_dir = 0, mode;
    for (mode = 0; mode < 2; mode++) {
        p.mode = mode ? SNELL_REF_FULL : SNELL_REF_MATCHED;
        CHECK_OK(render(ref, &p, &a));
        for (y = 0; y < a.h; y += 3)
            for (x = 0; x < a.w; x += 3) {
                size_t i = (size_t)y * a.w + x;
                snell_ref_path path;
                int k;
                double l;
                CHECK_OK(snell_ref_trace_pixel(ref, &p, x, y, &path));
                for (k = 0; k < 3; k++)
                    if ((float)path.rgb[k] != a.rgb[3 * i + k] || (float)path.exit_dir[k] != a.dir[3 * i + k])
                        bad_path++;
                if (path.interfaces != a.nif[i] || path.hit != a.hit[i] || (a.hit[i] != 0) != (a.nif[i] > 0) ||
                    path.first_object != a.obj[i] || (a.obj[i] >= 0) != (a.hit[i] != 0) ||
                    a.obj[i] < -1 - SNELL_MAX_OPAQUE)
                    bad_path++;
                l = sqrt((double)a.dir[3 * i] * a.dir[3 * i] + (double)a.dir[3 * i + 1] * a.dir[3 * i + 1] +
                         (double)a.dir[3 * i + 2] * a.dir[3 * i + 2]);
                if (fabs(l - 1.0) > 1e-6) bad_dir++;
                if (path.first_object <= -2) {
                    /* An opaque object first: nothing processed. */
                    if (path.interfaces || path.hit) bad_path++;
                } else if (!path.hit) {
                    /* Background: env of the view ray, which starts at the eye. */
                    double c[3];
                    snell_env_sample_d(p.env, path.exit_dir, c);
                    if (path.interfaces || fabs(c[0] - path.rgb[0]) > 1e-12 || fabs(c[2] - path.rgb[2]) > 1e-12)
                        bad_bg++;
                } else if (path.events[0] != SNELL_REF_EVENT_EYE || path.interfaces < 1) {
                    bad_path++;
                }
            }
    }
    {
        /* FULL with only rgb + hit requested (the path walk is optional there):
         * same colours and mask as with every output. */
        snell_ref_output o;
        float *rgb = (float *)malloc(sizeof(float) * 3 * a.w * a.h);
        uint8_t *hit = (uint8_t *)malloc((size_t)a.w * a.h);
        memset(&o, 0, sizeof o);
        o.rgb = rgb;
        o.hit = hit;
        CHECK_OK(snell_ref_render(ref, &p, &o));
        CHECK(!memcmp(rgb, a.rgb, sizeof(float) * 3 * a.w * a.h) && !memcmp(hit, a.hit, (size_t)a.w * a.h),
              "%s: FULL outputs depend on which outputs are requested", name);
        o.hit = NULL;
        CHECK_OK(snell_ref_render(ref, &p, &o));
        CHECK(!memcmp(rgb, a.rgb, sizeof(float) * 3 * a.w * a.h), "%s: FULL colour depends on the outputs requested",
              name);
        free(rgb);
        free(hit);
    }
    CHECK(bad_path == 0, "%s: %d mismatches between trace_pixel and the rendered image", name, bad_path);
    CHECK(bad_bg == 0, "%s: %d background pixels are not env(view ray)", name, bad_bg);
    CHECK(bad_dir == 0, "%s: %d exit directions are not unit", name, bad_dir);
    img_free(&a);
}

/* A model matrix (rotation, uniform scale, translation) must give the same
 * image as geometry transformed beforehand (and normals rotated). */
static void model_matrix(snell_ref_params p)
{
    snell_shape_desc sd;
    snell_mesh *m = NULL, *m2 = NULL;
    snell_ref *r1 = NULL, *r2 = NULL;
    const double th = 0.6, s = 0.8;
    float model[16] = {0};
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_TORUS;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &m));
    if (!m) return;
    /* rotation about +X by th, scale s, translation (0.1, 0.2, -0.1) */
    model[0] = (float)s;
    model[5] = (float)(s * cos(th));
    model[6] = (float)(s * sin(th));
    model[9] = (float)(-s * sin(th));
    model[10] = (float)(s * cos(th));
    model[12] = 0.1f;
    model[13] = 0.2f;
    model[14] = -0.1f;
    model[15] = 1.0f;
    {
        uint32_t nv = snell_mesh_vertex_count(m), i;
        const float *P = snell_mesh_positions(m), *N = snell_mesh_normals(m);
        float *pos = (float *)malloc(sizeof(float) * 3 * nv), *nrm = (float *)malloc(sizeof(float) * 3 * nv);
        snell_mesh_desc md;
        for (i = 0; i < nv; i++) {
            const float *a = P + 3 * i, *n = N + 3 * i;
            int k;
            for (k = 0; k < 3; k++) {
                pos[3 * i + k] = (float)((double)model[k] * a[0] + (double)model[4 + k] * a[1] +
                                         (double)model[8 + k] * a[2] + (double)model[12 + k]);
                nrm[3 * i + k] = (float)((double)model[k] * n[0] + (double)model[4 + k] * n[1] +
                                         (double)model[8 + k] * n[2]) / (float)s;
            }
        }
        memset(&md, 0, sizeof md);
        md.positions = pos;
        md.normals = nrm;
        md.indices = snell_mesh_indices(m);
        md.vertex_count = nv;
        md.triangle_count = snell_mesh_triangle_count(m);
        CHECK_OK(snell_mesh_create(NULL, &md, &m2));
        free(pos);
        free(nrm);
        r1 = one_glass(m, model, NULL);
        if (m2) r2 = one_glass(m2, NULL, NULL);
    }
    if (r1 && r2) {
        img a = img_new(64, 64), b = img_new(64, 64);
        size_t i, bad = 0;
        double maxd = 0;
        p.mode = SNELL_REF_MATCHED;
        CHECK_OK(render(r1, &p, &a));
        CHECK_OK(render(r2, &p, &b));
        for (i = 0; i < (size_t)64 * 64 * 3; i++) {
            double d = fabs(a.rgb[i] - b.rgb[i]);
            if (d > maxd) maxd = d;
        }
        /* float vertex rounding differs between the two: allow a silhouette pixel or two */
        for (i = 0; i < (size_t)64 * 64; i++)
            if (a.hit[i] != b.hit[i] || fabs(a.rgb[3 * i] - b.rgb[3 * i]) > 1e-3) bad++;
        printf("model matrix vs pre-transformed: %zu differing pixels, max difference %.3g\n", bad, maxd);
        CHECK(bad <= 2, "model matrix: %zu pixels differ from pre-transformed geometry", bad);
        img_free(&a);
        img_free(&b);
    }
    snell_ref_destroy(r1);
    snell_ref_destroy(r2);
    snell_mesh_destroy(m);
    snell_mesh_destroy(m2);
}

/* snell_ref_create on desc must fail with SNELL_E_INVALID_ARG, *out NULL and
 * a message containing `words`. */
static void create_fails(const snell_ref_desc *rd, const char *what, const char *words)
{
    snell_ref *r = (snell_ref *)&r;
    CHECK(snell_ref_create(NULL, rd, &r) == SNELL_E_INVALID_ARG && r == NULL, "%s accepted", what);
    CHECK(strstr(snell_last_error(NULL), words) != NULL, "%s: message \"%s\" lacks \"%s\"", what,
          snell_last_error(NULL), words);
}

static void bad_scenes(const snell_mesh *mesh)
{
    snell_glass g[2];
    snell_opaque op[1];
    snell_ref_desc rd;
    snell_ref *r = NULL;
    float nan_model[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
          flat[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
    nan_model[13] = NAN;
    memset(g, 0, sizeof g);
    memset(op, 0, sizeof op);
    memset(&rd, 0, sizeof rd);
    create_fails(&rd, "no objects", "no objects");
    CHECK(snell_ref_create(NULL, NULL, &r) == SNELL_E_INVALID_ARG && !r, "NULL desc");
    CHECK(snell_ref_create(NULL, &rd, NULL) == SNELL_E_INVALID_ARG, "NULL out");
    g[0].mesh = mesh;
    g[1].mesh = mesh;
    op[0].mesh = mesh;
    rd.glass = g;
    rd.glass_count = SNELL_MAX_GLASS + 1;
    create_fails(&rd, "33 glass objects", "glass_count");
    rd.glass_count = -1;
    create_fails(&rd, "negative glass_count", "glass_count");
    rd.glass_count = 2;
    rd.opaque_count = SNELL_MAX_OPAQUE + 1;
    rd.opaque = op;
    create_fails(&rd, "65 opaque objects", "opaque_count");
    rd.opaque_count = 1;
    rd.opaque = NULL;
    create_fails(&rd, "NULL opaque list", "NULL");
    rd.opaque = op;
    rd.glass = NULL;
    create_fails(&rd, "NULL glass list", "NULL");
    rd.glass = g;
    g[1].mesh = NULL;
    create_fails(&rd, "NULL mesh", "glass[1].mesh");
    g[1].mesh = mesh;
    g[0].model = nan_model;
    create_fails(&rd, "NaN glass model", "glass[0].model");
    g[0].model = flat;
    create_fails(&rd, "singular glass model", "singular");
    g[0].model = NULL;
    op[0].model = nan_model;
    create_fails(&rd, "NaN opaque model", "opaque[0].model");
    op[0].model = NULL;
    op[0].color[1] = NAN;
    create_fails(&rd, "NaN opaque colour", "opaque[0].color");
    op[0].color[1] = -0.5f;
    create_fails(&rd, "negative opaque colour", "opaque[0].color");
    op[0].color[1] = 0.0f;
    g[1].material.ior = -1.0f;
    create_fails(&rd, "negative ior", "glass 1");
    g[1].material.ior = 0.0f;
    g[1].material.attenuation_distance = NAN;
    create_fails(&rd, "NaN attenuation distance", "glass 1");
    g[1].material.attenuation_distance = 0.0f;
    g[0].material.thickness = -1.0f;
    create_fails(&rd, "negative thickness", "glass 0");
    g[0].material.thickness = 0.0f;
    CHECK_OK(snell_ref_create(NULL, &rd, &r)); /* and now it is a valid scene */
    snell_ref_destroy(r);
}

static void bad_input(snell_ref *ref, snell_ref_params p)
{
    snell_ref_output o;
    snell_ref_path path;
    float rgb[3 * 4], rgb2[3 * 4];
    double org[3] = {0, 0, 5}, dir[3] = {0, 0, 0}, c[3] = {1, 1, 1}, rad = 1.0;
    snell_glass_material m;
    memset(&o, 0, sizeof o);
    CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "NULL rgb");
    CHECK(snell_ref_render(NULL, &p, &o) == SNELL_E_INVALID_ARG, "NULL ref");
    o.rgb = rgb;
    p.width = 100000;
    p.height = 1;
    CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_LIMIT, "absurd width");
    CHECK(strstr(snell_last_error(NULL), "100000") != NULL, "message: %s", snell_last_error(NULL));
    p.width = -2;
    CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "negative width");
    p.width = 2;
    p.height = 2;
    p.threads = -1;
    CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "negative threads");
    p.threads = 100000; /* clamped: works */
    CHECK_OK(snell_ref_render(ref, &p, &o));
    p.threads = 0;
    p.max_interfaces = SNELL_REF_MAX_INTERFACES + 1;
    CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "max_interfaces too large");
    p.max_interfaces = 0;
    p.mode = (snell_ref_mode)7;
    CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "bad mode");
    p.mode = SNELL_REF_MATCHED;
    p.absorption_model = (snell_ref_absorption)5;
    CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "bad absorption model");
    p.absorption_model = SNELL_REF_ABSORB_PATH;
    /* A rejected material leaves the one in use. */
    CHECK_OK(snell_ref_render(ref, &p, &o));
    memset(&m, 0, sizeof m);
    m.ior = NAN;
    CHECK(snell_ref_set_material(ref, 0, &m) == SNELL_E_INVALID_ARG, "NaN ior");
    CHECK(strstr(snell_last_error(NULL), "ior") != NULL, "message: %s", snell_last_error(NULL));
    m.ior = 0.0f;
    m.attenuation_color[0] = 2.0f;
    CHECK(snell_ref_set_material(ref, 0, &m) == SNELL_E_INVALID_ARG, "attenuation colour 2");
    o.rgb = rgb2;
    CHECK_OK(snell_ref_render(ref, &p, &o));
    CHECK(!memcmp(rgb, rgb2, sizeof rgb), "a rejected material changed the image");
    o.rgb = rgb;
    CHECK(snell_ref_set_material(ref, 1, NULL) == SNELL_E_INVALID_ARG, "material of glass 1 of 1");
    CHECK(snell_ref_set_material(ref, -1, NULL) == SNELL_E_INVALID_ARG, "material of glass -1");
    CHECK(snell_ref_set_material(NULL, 0, NULL) == SNELL_E_INVALID_ARG, "material of no reference");
    snell_ref_bounding_sphere(ref, 1, c, &rad);
    CHECK(c[0] == 0 && c[1] == 0 && c[2] == 0 && rad == 0, "bounding sphere of glass 1 of 1");
    snell_ref_bounding_sphere(NULL, 0, c, &rad);
    {
        float az = p.camera.azimuth;
        p.camera.azimuth = NAN;
        CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "NaN camera");
        p.camera.azimuth = az;
    }
    {
        const snell_env *e = p.env;
        p.env = NULL;
        CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "no environment");
        CHECK(strstr(snell_last_error(NULL), "environment") != NULL, "message: %s", snell_last_error(NULL));
        p.env = e;
    }
    CHECK(snell_ref_trace_pixel(ref, &p, 2, 0, &path) == SNELL_E_INVALID_ARG, "pixel outside");
    CHECK(snell_ref_trace_pixel(ref, &p, 0, -1, &path) == SNELL_E_INVALID_ARG, "pixel outside");
    CHECK(snell_ref_trace_ray(ref, &p, org, dir, &path) == SNELL_E_INVALID_ARG, "zero direction");
    dir[2] = NAN;
    CHECK(snell_ref_trace_ray(ref, &p, org, dir, &path) == SNELL_E_INVALID_ARG, "NaN direction");
    CHECK(snell_ref_trace_ray(ref, &p, org, NULL, &path) == SNELL_E_INVALID_ARG, "NULL direction");
    snell_ref_destroy(NULL);
}

/* ------------------------------------------------------------ scenes */

static void box_model(float m[16], double sx, double sy, double sz, double tx, double ty, double tz)
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = (float)sx;
    m[5] = (float)sy;
    m[10] = (float)sz;
    m[12] = (float)tx;
    m[13] = (float)ty;
    m[14] = (float)tz;
    m[15] = 1.0f;
}

/* Entry parameter of the ray o + t d into the box centre c, half sizes h (slab
 * test), or HUGE_VAL; grown by g (negative: shrunk). */
static double box_t(const double o[3], const double d[3], const float m[16], double g)
{
    double t0 = 0.0, t1 = HUGE_VAL;
    int k;
    for (k = 0; k < 3; k++) {
        double c = m[12 + k], h = m[5 * k] + g, a, b;
        if (d[k] == 0.0) {
            if (fabs(o[k] - c) > h) return HUGE_VAL;
            continue;
        }
        a = (c - h - o[k]) / d[k];
        b = (c + h - o[k]) / d[k];
        if (a > b) {
            double tmp = a;
            a = b;
            b = tmp;
        }
        if (a > t0) t0 = a;
        if (b < t1) t1 = b;
    }
    return t0 <= t1 ? t0 : HUGE_VAL;
}

/* Object ids: two glass boxes (one thin) and two opaque ones (the second a
 * floor); per pixel the first box along the view ray, by slab tests here
 * (pixels within 1e-4 of a box's edge or with two boxes within 1e-6 of
 * each other skipped), is the id in snell_ref_output.object; hit is id >= 0. */
static void object_ids(const snell_mesh *cube, snell_ref_params p)
{
    float mg[2][16], mo[2][16];
    const float *models[4];
    const int ids[4] = {0, 1, -2, -3};
    snell_glass g[2];
    snell_opaque op[2];
    snell_ref_desc rd;
    snell_ref *ref = NULL;
    img a = img_new(120, 90);
    int x, y, i, checked = 0, bad = 0, seen[4] = {0, 0, 0, 0}, bg = 0;
    box_model(mg[0], 0.5, 0.5, 0.5, -1.2, 0.0, 0.0);
    box_model(mg[1], 0.6, 0.4, 0.3, 0.2, 0.3, -0.5);
    box_model(mo[0], 0.4, 0.4, 0.4, 1.3, -0.2, 0.3);
    box_model(mo[1], 4.0, 0.1, 4.0, 0.0, -1.5, 0.0);
    memset(g, 0, sizeof g);
    memset(op, 0, sizeof op);
    for (i = 0; i < 2; i++) {
        g[i].mesh = cube;
        g[i].model = mg[i];
        op[i].mesh = cube;
        op[i].model = mo[i];
    }
    g[1].material.thickness = 0.02f;
    op[0].color[0] = 0.9f;
    models[0] = mg[0];
    models[1] = mg[1];
    models[2] = mo[0];
    models[3] = mo[1];
    memset(&rd, 0, sizeof rd);
    rd.glass = g;
    rd.glass_count = 2;
    rd.opaque = op;
    rd.opaque_count = 2;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    if (!ref) {
        img_free(&a);
        return;
    }
    p.camera.azimuth = 0.3f;
    p.camera.elevation = 0.35f;
    p.camera.distance = 5.0f;
    p.camera.target[0] = p.camera.target[1] = p.camera.target[2] = 0.0f;
    CHECK_OK(render(ref, &p, &a));
    for (y = 0; y < a.h; y++)
        for (x = 0; x < a.w; x++) {
            size_t px = (size_t)y * a.w + x;
            snell_ref_path path;
            double o[3], d[3], best = HUGE_VAL, second = HUGE_VAL;
            int want = -1, ambiguous = 0, k;
            CHECK_OK(snell_ref_trace_pixel(ref, &p, x, y, &path));
            for (k = 0; k < 3; k++) {
                o[k] = path.points[0][k];
                d[k] = path.interfaces ? path.points[1][k] - o[k] : path.exit_dir[k];
            }
            for (i = 0; i < 4; i++) {
                double t = box_t(o, d, models[i], 0.0);
                if ((box_t(o, d, models[i], 1e-4) == HUGE_VAL) != (box_t(o, d, models[i], -1e-4) == HUGE_VAL))
                    ambiguous = 1;
                if (t < best) {
                    second = best;
                    best = t;
                    want = ids[i];
                } else if (t < second) {
                    second = t;
                }
            }
            if (ambiguous || (second < HUGE_VAL && second - best < 1e-6 * (1 + best))) continue;
            checked++;
            if (want == -1)
                bg++;
            else
                seen[want >= 0 ? want : -want]++; /* glass 0, 1; opaque -2, -3 -> 2, 3 */
            if (a.obj[px] != want || (a.hit[px] != 0) != (want >= 0) || path.first_object != want) {
                if (bad < 5) fprintf(stderr, "pixel (%d, %d): object %d, want %d\n", x, y, a.obj[px], want);
                bad++;
            }
        }
    printf("object ids: %d pixels checked (%d / %d glass, %d / %d opaque, %d background)\n", checked, seen[0], seen[1],
           seen[2], seen[3], bg);
    CHECK(checked > 9000 && seen[0] > 200 && seen[1] > 200 && seen[2] > 200 && seen[3] > 200 && bg > 200,
          "too few pixels of some object");
    CHECK(bad == 0, "%d pixels with the wrong object id", bad);
    determinism("box scene", ref, p);
    paths_and_outputs("box scene", ref, p);
    snell_ref_destroy(ref);
    img_free(&a);
}

/* Largest channel difference of two images over pixels where pick(x) holds. */
static double diff_where(const img *a, const img *b, int left)
{
    double worst = 0.0;
    int x, y, k;
    for (y = 0; y < a->h; y++)
        for (x = 0; x < a->w; x++) {
            size_t i = (size_t)y * a->w + x;
            if ((x < a->w / 2) != left) continue;
            for (k = 0; k < 3; k++) {
                double d = fabs(a->rgb[3 * i + k] - b->rgb[3 * i + k]);
                if (d > worst) worst = d;
            }
        }
    return worst;
}

/* Glass A (sphere, x < 0) | opaque wall x in [-0.02, 0.02] | glass B (torus,
 * x > 0), eye on the wall's plane: a path that starts left stays left (it
 * would have to cross the wall to meet B), so the scene renders on the left
 * as {A, wall} and on the right as {B, wall} (ids there: B is 0), MATCHED
 * and FULL, to 1e-6 (the BVHs differ, so hits on shared edges may pick the
 * other triangle). */
static void separation(const snell_mesh *sphere, const snell_mesh *torus, const snell_mesh *cube, snell_ref_params p)
{
    float ma[16], mb[16], mw[16];
    snell_glass g[2];
    snell_opaque wall;
    snell_ref_desc rd;
    snell_ref *both = NULL, *left = NULL, *right = NULL;
    int mode;
    box_model(ma, 0.8, 0.8, 0.8, -1.5, 0.1, 0.0);
    box_model(mb, 0.6, 0.6, 0.6, 1.5, -0.1, 0.2);
    mb[5] = 0.0f; /* torus axis +Y turned to +Z: a ring facing the eye */
    mb[6] = 0.6f;
    mb[9] = -0.6f;
    mb[10] = 0.0f;
    box_model(mw, 0.02, 20.0, 12.75, 0.0, 0.0, -7.25); /* z from -20 to 5.5, the eye at z = 6 */
    memset(g, 0, sizeof g);
    memset(&wall, 0, sizeof wall);
    g[0].mesh = sphere;
    g[0].model = ma;
    g[0].material = material(1.5f, 0.4f, 0.1f, 0.2f, 1, 0.9f, 0.8f, 0);
    g[1].mesh = torus;
    g[1].model = mb;
    g[1].material = material(1.6f, 0.1f, 0.5f, 0.2f, 0.8f, 1, 0.9f, 0);
    wall.mesh = cube;
    wall.model = mw;
    wall.color[0] = 0.3f;
    wall.color[1] = 0.6f;
    wall.color[2] = 0.9f;
    memset(&rd, 0, sizeof rd);
    rd.opaque = &wall;
    rd.opaque_count = 1;
    rd.glass = g;
    rd.glass_count = 2;
    CHECK_OK(snell_ref_create(NULL, &rd, &both));
    rd.glass_count = 1;
    CHECK_OK(snell_ref_create(NULL, &rd, &left));
    rd.glass = g + 1;
    CHECK_OK(snell_ref_create(NULL, &rd, &right));
    p.camera.azimuth = 0.0f;
    p.camera.elevation = 0.0f;
    p.camera.distance = 6.0f;
    p.camera.target[0] = p.camera.target[1] = p.camera.target[2] = 0.0f;
    for (mode = 0; both && left && right && mode < 2; mode++) {
        img a = img_new(128, 72), l = img_new(128, 72), r = img_new(128, 72);
        double dl, dr;
        int x, y, bad_id = 0, seen_a = 0, seen_b = 0;
        p.mode = mode ? SNELL_REF_FULL : SNELL_REF_MATCHED;
        CHECK_OK(render(both, &p, &a));
        CHECK_OK(render(left, &p, &l));
        CHECK_OK(render(right, &p, &r));
        dl = diff_where(&a, &l, 1);
        dr = diff_where(&a, &r, 0);
        for (y = 0; y < a.h; y++)
            for (x = 0; x < a.w; x++) {
                size_t i = (size_t)y * a.w + x;
                int want = x < a.w / 2 ? l.obj[i] : (r.obj[i] == 0 ? 1 : r.obj[i]);
                seen_a += a.obj[i] == 0;
                seen_b += a.obj[i] == 1;
                if (a.obj[i] != want || (x < a.w / 2 ? a.obj[i] == 1 : a.obj[i] == 0)) bad_id++;
            }
        printf("separation, mode %d: left differs by %.3g, right by %.3g (%d / %d pixels of A / B)\n", mode, dl, dr,
               seen_a, seen_b);
        CHECK(seen_a > 300 && seen_b > 300, "the objects cover %d / %d pixels", seen_a, seen_b);
        CHECK(dl < 1e-6 && dr < 1e-6, "mode %d: the scene differs from its separate halves (%.3g, %.3g)", mode, dl, dr);
        CHECK(bad_id == 0, "mode %d: %d object ids differ from the separate halves", mode, bad_id);
        img_free(&a);
        img_free(&l);
        img_free(&r);
    }
    snell_ref_destroy(both);
    snell_ref_destroy(left);
    snell_ref_destroy(right);
}

/* isolate_glass: glass A (sphere) and B (a smaller sphere in front of it,
 * overlapping it in the image): the scene renders as {A} alone where A is
 * seen first, as {B} alone where B is, and as the background elsewhere,
 * MATCHED and FULL, to 1e-6; without isolate_glass B's pixels do differ
 * (they see A through B). */
static void isolation(const snell_mesh *sphere, snell_ref_params p)
{
    float ma[16], mb[16];
    snell_glass g[2];
    snell_ref_desc rd;
    snell_ref *both = NULL, *ra = NULL, *rb = NULL;
    int mode;
    box_model(ma, 0.8, 0.8, 0.8, 0.0, 0.0, -0.5);
    box_model(mb, 0.4, 0.4, 0.4, 0.45, 0.2, 1.0);
    memset(g, 0, sizeof g);
    g[0].mesh = sphere;
    g[0].model = ma;
    g[0].material = material(1.5f, 0.4f, 0.1f, 0.2f, 1, 0.9f, 0.8f, 0);
    g[1].mesh = sphere;
    g[1].model = mb;
    g[1].material = material(1.7f, 0, 0, 0, 0.8f, 1, 0.9f, 0);
    memset(&rd, 0, sizeof rd);
    rd.glass = g;
    rd.glass_count = 2;
    CHECK_OK(snell_ref_create(NULL, &rd, &both));
    rd.glass_count = 1;
    CHECK_OK(snell_ref_create(NULL, &rd, &ra));
    rd.glass = g + 1;
    CHECK_OK(snell_ref_create(NULL, &rd, &rb));
    p.camera.azimuth = 0.0f;
    p.camera.elevation = 0.1f;
    p.camera.distance = 4.0f;
    p.camera.target[0] = p.camera.target[1] = p.camera.target[2] = 0.0f;
    for (mode = 0; both && ra && rb && mode < 2; mode++) {
        img s = img_new(96, 96), a = img_new(96, 96), b = img_new(96, 96), n = img_new(96, 96);
        size_t i, k, seen_a = 0, seen_b = 0, bad = 0, differ = 0;
        double worst = 0.0;
        p.mode = mode ? SNELL_REF_FULL : SNELL_REF_MATCHED;
        p.isolate_glass = 1;
        CHECK_OK(render(both, &p, &s));
        CHECK_OK(render(ra, &p, &a));
        CHECK_OK(render(rb, &p, &b));
        p.isolate_glass = 0;
        CHECK_OK(render(both, &p, &n));
        for (i = 0; i < (size_t)96 * 96; i++) {
            const img *want = s.obj[i] == 1 ? &b : &a;
            seen_a += s.obj[i] == 0;
            seen_b += s.obj[i] == 1;
            if (s.obj[i] == 1 && fabs(n.rgb[3 * i + 1] - s.rgb[3 * i + 1]) > 1e-3) differ++;
            if (s.obj[i] == 0 ? a.obj[i] != 0 : s.obj[i] == 1 ? b.obj[i] != 0 : a.obj[i] != -1 || b.obj[i] != -1) bad++;
            for (k = 0; k < 3; k++) {
                double d = fabs(s.rgb[3 * i + k] - want->rgb[3 * i + k]);
                if (d > worst) worst = d;
            }
        }
        printf("isolation, mode %d: %zu / %zu pixels of A / B, differs from the single objects by %.3g; %zu of B's "
               "pixels change without isolate_glass\n",
               mode, seen_a, seen_b, worst, differ);
        CHECK(seen_a > 600 && seen_b > 400, "too few pixels (%zu / %zu)", seen_a, seen_b);
        CHECK(worst < 1e-6, "mode %d: isolate_glass image differs from the single objects by %.3g", mode, worst);
        CHECK(bad == 0, "mode %d: %zu object ids inconsistent with the single objects", mode, bad);
        CHECK(differ > 50, "mode %d: without isolate_glass only %zu of B's pixels see A", mode, differ);
        img_free(&s);
        img_free(&a);
        img_free(&b);
        img_free(&n);
    }
    snell_ref_destroy(both);
    snell_ref_destroy(ra);
    snell_ref_destroy(rb);
}

/* A scene of a solid sphere, a solid torus and a thin-walled cube: energy
 * (white env) and determinism; set_material equals creating with that material. */
static void scene_properties(const snell_mesh *sphere, const snell_mesh *torus, const snell_mesh *cube,
                             snell_ref_params p)
{
    float ms[16], mt[16], mc[16];
    snell_glass g[3];
    snell_opaque floor_;
    snell_ref_desc rd;
    snell_ref *ref = NULL, *ref2 = NULL;
    snell_glass_material white_m[3], absorbing[3];
    int i;
    box_model(ms, 0.6, 0.6, 0.6, -0.8, 0.0, 0.3);
    box_model(mt, 0.5, 0.5, 0.5, 0.7, 0.2, -0.2);
    box_model(mc, 0.5, 0.6, 0.4, 0.1, -0.4, -1.2);
    memset(g, 0, sizeof g);
    g[0].mesh = sphere;
    g[0].model = ms;
    g[1].mesh = torus;
    g[1].model = mt;
    g[2].mesh = cube;
    g[2].model = mc;
    for (i = 0; i < 3; i++) {
        white_m[i] = material(i == 1 ? 1.33f : 1.5f, 0, 0, 0, 0, 0, 0, i == 2 ? 0.03f : 0.0f);
        absorbing[i] = material(i == 1 ? 1.33f : 1.5f, 0.5f, 2.0f * (float)i, 0.1f, 0.7f, 1, 1, i == 2 ? 0.03f : 0.0f);
    }
    memset(&rd, 0, sizeof rd);
    rd.glass = g;
    rd.glass_count = 3;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    if (!ref) return;
    p.camera.azimuth = 0.4f;
    p.camera.elevation = 0.3f;
    p.camera.distance = 4.0f;
    energy("scene", ref, 3, white_m, absorbing, p);
    for (i = 0; i < 3; i++) CHECK_OK(snell_ref_set_material(ref, i, &absorbing[i]));
    determinism("scene", ref, p);
    /* set_material = created with the material; an opaque floor added. */
    for (i = 0; i < 3; i++) g[i].material = absorbing[i];
    CHECK_OK(snell_ref_create(NULL, &rd, &ref2));
    if (ref2) {
        img a = img_new(64, 48), b = img_new(64, 48);
        CHECK_OK(render(ref, &p, &a));
        CHECK_OK(render(ref2, &p, &b));
        CHECK(img_equal(&a, &b), "snell_ref_set_material differs from creating with the material");
        img_free(&a);
        img_free(&b);
    }
    snell_ref_destroy(ref);
    snell_ref_destroy(ref2);
    {
        float mf[16];
        box_model(mf, 3.0, 0.1, 3.0, 0.0, -1.2, 0.0);
        memset(&floor_, 0, sizeof floor_);
        floor_.mesh = cube;
        floor_.model = mf;
        rd.opaque = &floor_;
        rd.opaque_count = 1;
        ref = NULL;
        CHECK_OK(snell_ref_create(NULL, &rd, &ref));
        if (ref) {
            determinism("scene with a floor", ref, p);
            paths_and_outputs("scene with a floor", ref, p);
        }
        snell_ref_destroy(ref);
    }
}

/* Area sampling: with samples = S the pixel is the mean of an S x S grid of
 * rays, whose sub-pixel centres are exactly the pixel centres of the image S
 * times as large, so the S x S block means of that image are the result (up
 * to the rounding of the two NDC computations, 1e-5 allowed); path outputs
 * stay the centre ray's (the S = 1 image's); sample_var is 0 where the box
 * sees one colour (white environment, no absorption: every ray is 1) and
 * equals the block's spread in MATCHED mode (deterministic rays). */
static void area_sampling(const snell_ref *ref, snell_ref_params p)
{
    enum { W = 24, H = 20, S = 3 };
    int mode;
    for (mode = 0; mode < 2; mode++) {
        img big = img_new(W * S, H * S), small = img_new(W, H), centre = img_new(W, H);
        float *var = (float *)calloc((size_t)W * H * 3, sizeof(float));
        snell_ref_output o;
        int x, y, k, a, b, bad = 0, bad_var = 0;
        p.mode = mode ? SNELL_REF_FULL : SNELL_REF_MATCHED;
        p.samples = 1;
        CHECK_OK(render(ref, &p, &big));
        CHECK_OK(render(ref, &p, &centre));
        p.samples = S;
        memset(&o, 0, sizeof o);
        o.rgb = small.rgb;
        o.exit_dir = small.dir;
        o.hit = small.hit;
        o.sample_var = var;
        p.width = W;
        p.height = H;
        CHECK_OK(snell_ref_render(ref, &p, &o));
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x++) {
                size_t i = (size_t)y * W + x;
                for (k = 0; k < 3; k++) {
                    double m = 0.0, m2 = 0.0, v;
                    for (b = 0; b < S; b++)
                        for (a = 0; a < S; a++) {
                            double c = big.rgb[3 * ((size_t)(y * S + b) * W * S + x * S + a) + k];
                            m += c / (S * S);
                            m2 += c * c / (S * S);
                        }
                    v = m2 - m * m;
                    bad += fabs(small.rgb[3 * i + k] - m) > 1e-5;
                    if (!mode) bad_var += fabs(var[3 * i + k] - v) > 1e-5;
                    bad += memcmp(small.dir + 3 * i, centre.dir + 3 * i, 3 * sizeof(float)) != 0 ||
                           small.hit[i] != centre.hit[i];
                }
            }
        CHECK(bad == 0, "mode %d: %d area-sampled values differ from the %dx block means or the centre ray", mode, bad,
              S);
        CHECK(bad_var == 0, "MATCHED: %d sample variances differ from the block spread", bad_var);
        img_free(&big);
        img_free(&small);
        img_free(&centre);
        free(var);
    }
    {
        float rgb[3 * 16], var[3 * 16];
        snell_ref_output o;
        int i, bad = 0;
        p.env = NULL;
        p.env_fn = white;
        p.mode = SNELL_REF_FULL;
        p.samples = 2;
        p.width = p.height = 4;
        memset(&o, 0, sizeof o);
        o.rgb = rgb;
        o.sample_var = var;
        CHECK_OK(snell_ref_render(ref, &p, &o));
        for (i = 0; i < 3 * 16; i++) bad += fabs(rgb[i] - 1.0) > 1e-6 || var[i] > 1e-6;
        CHECK(bad == 0, "white environment: %d values with colour != 1 or variance != 0", bad);
        p.samples = SNELL_REF_MAX_SAMPLES + 1;
        CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG && strstr(snell_last_error(NULL), "samples"),
              "samples beyond the limit are refused with a message");
    }
}

static void timed_render(const char *label, const char *png, const snell_ref *ref, snell_ref_params p, int size)
{
    img a = img_new(size, size);
    double t0 = now(), t;
    CHECK_OK(render(ref, &p, &a));
    t = now() - t0;
    printf("%s: %dx%d, %s, max_interfaces %d, %d threads: %.3f s\n", label, size, size,
           p.mode == SNELL_REF_FULL ? "FULL" : "MATCHED", p.max_interfaces ? p.max_interfaces : 10, p.threads, t);
    write_png(png, &a);
    img_free(&a);
}

int main(int argc, char **argv)
{
    snell_env *env = NULL;
    snell_env_desc ed;
    snell_mesh *mesh = NULL, *sphere = NULL, *torus = NULL, *cube = NULL;
    snell_shape_desc sd;
    snell_ref *ref = NULL, *sref = NULL, *scene = NULL;
    snell_glass_material m;
    snell_ref_params p;
    int size = argc > 1 ? atoi(argv[1]) : 256;
    double t0;
    memset(&ed, 0, sizeof ed);
    CHECK_OK(snell_env_create(NULL, &ed, &env));
    if (!env) return test_finish();
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_TORUS;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &torus));
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &cube));
    sd.shape = SNELL_SHAPE_SPHERE;
    sd.segments = 128;
    sd.rings = 64;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &sphere));
    if (!torus || !cube || !sphere) return test_finish();
    if (snell_mesh_load_obj(NULL, "/usr/share/glmark2/models/bunny.obj", &mesh) != SNELL_OK) {
        printf("bunny not available (%s): using the torus\n", snell_last_error(NULL));
        sd.shape = SNELL_SHAPE_TORUS;
        sd.segments = sd.rings = 0;
        CHECK_OK(snell_mesh_create_shape(NULL, &sd, &mesh));
    }
    if (!mesh) return test_finish();
    CHECK_OK(snell_mesh_normalize(mesh, 1.0f));
    t0 = now();
    ref = one_glass(mesh, NULL, NULL);
    printf("reference of %u triangles built in %.3f s\n", snell_mesh_triangle_count(mesh), now() - t0);
    sref = one_glass(sphere, NULL, NULL);
    if (!ref || !sref) return test_finish();

    memset(&p, 0, sizeof p);
    p.env = env;
    p.camera.azimuth = 0.5f;
    p.camera.elevation = 0.25f;
    p.camera.distance = 3.0f;

    m = material(0, 0.3f, 0, 0, 1.0f, 0.9f, 0.8f, 0);
    CHECK_OK(snell_ref_set_material(ref, 0, &m));
    determinism("bunny", ref, p);
    {
        snell_glass_material w = material(0, 0, 0, 0, 0, 0, 0, 0), a = material(0, 0.5f, 2.0f, 0, 0.7f, 1, 1, 0);
        energy("bunny", ref, 1, &w, &a, p);
    }
    paths_and_outputs("bunny", ref, p);
    model_matrix(p);
    bad_scenes(mesh);
    bad_input(ref, p);
    object_ids(cube, p);
    separation(sphere, torus, cube, p);
    isolation(sphere, p);
    scene_properties(sphere, torus, cube, p);
    {
        snell_glass_material w = material(0, 0, 0, 0, 0, 0, 0, 0);
        CHECK_OK(snell_ref_set_material(ref, 0, &w));
        area_sampling(ref, p);
    }

    p.threads = 0;
    m = material(0, 0.25f, 0.08f, 0.05f, 0, 0, 0, 0);
    CHECK_OK(snell_ref_set_material(ref, 0, &m));
    CHECK_OK(snell_ref_set_material(sref, 0, &m));
    timed_render("bunny", "ref_bunny_matched.png", ref, p, size);
    p.mode = SNELL_REF_FULL;
    timed_render("bunny", "ref_bunny_full.png", ref, p, size);
    p.mode = SNELL_REF_MATCHED;
    p.max_interfaces = 1;
    p.absorption_model = SNELL_REF_ABSORB_BOUNDING_SPHERE;
    timed_render("bunny", "ref_bunny_single.png", ref, p, size);
    p.max_interfaces = 0;
    p.absorption_model = SNELL_REF_ABSORB_PATH;
    timed_render("sphere", "ref_sphere_matched.png", sref, p, size);
    p.mode = SNELL_REF_FULL;
    timed_render("sphere", "ref_sphere_full.png", sref, p, size);
    {
        /* A scene: the bunny, a thin-walled cube, a sphere and an opaque floor. */
        float mb[16], mc[16], ms[16], mf[16];
        snell_glass g[3];
        snell_opaque fl;
        snell_ref_desc rd;
        box_model(mb, 0.7, 0.7, 0.7, -0.6, 0.0, 0.0);
        box_model(mc, 0.45, 0.45, 0.45, 0.8, -0.25, 0.6);
        box_model(ms, 0.4, 0.4, 0.4, 0.5, -0.3, -0.8);
        box_model(mf, 3.0, 0.05, 3.0, 0.0, -0.75, 0.0);
        memset(g, 0, sizeof g);
        memset(&fl, 0, sizeof fl);
        g[0].mesh = mesh;
        g[0].model = mb;
        g[0].material = m;
        g[1].mesh = cube;
        g[1].model = mc;
        g[1].material = material(1.5f, 0, 0, 0, 0.6f, 0.9f, 1.0f, 0.02f);
        g[2].mesh = sphere;
        g[2].model = ms;
        g[2].material = material(1.7f, 0.1f, 0.8f, 1.2f, 0, 0, 0, 0);
        fl.mesh = cube;
        fl.model = mf;
        fl.color[0] = 0.8f;
        fl.color[1] = 0.6f;
        fl.color[2] = 0.3f;
        memset(&rd, 0, sizeof rd);
        rd.glass = g;
        rd.glass_count = 3;
        rd.opaque = &fl;
        rd.opaque_count = 1;
        CHECK_OK(snell_ref_create(NULL, &rd, &scene));
        if (scene) {
            p.camera.elevation = 0.35f;
            p.camera.distance = 3.5f;
            p.mode = SNELL_REF_MATCHED;
            timed_render("scene", "ref_scene_matched.png", scene, p, size);
            p.mode = SNELL_REF_FULL;
            timed_render("scene", "ref_scene_full.png", scene, p, size);
        }
    }

    snell_ref_destroy(ref);
    snell_ref_destroy(sref);
    snell_ref_destroy(scene);
    snell_mesh_destroy(mesh);
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(torus);
    snell_mesh_destroy(cube);
    snell_env_destroy(env);
    return test_finish();
}
