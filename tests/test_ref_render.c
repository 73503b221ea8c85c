/* test_ref_render — image-level properties of the reference tracer on the
 * glmark2 bunny (or, without it, the torus) and a glass sphere:
 *  (d) determinism: images, exit directions, interface counts and hit masks
 *      are bitwise equal for 1, 2 and 5 threads, MATCHED and FULL;
 *  (e) energy: with a white environment, no absorption and no tint every
 *      pixel is 1 (F + (1-F) = 1 at each split, MATCHED and FULL) within 1e-9,
 *      and no NaN/Inf anywhere; with absorption every pixel is <= 1;
 *  - trace_pixel reproduces the rendered pixel; background pixels carry the
 *    view ray; a model matrix equals pre-transformed geometry;
 *  - bad input gives a status and a message;
 *  - renders of the bunny and a sphere (MATCHED and FULL) are written as PNGs
 *    with their timings. argv[1] = image size (default 256). */
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
    return m;
}

static void img_free(img *m)
{
    free(m->rgb);
    free(m->dir);
    free(m->nif);
    free(m->hit);
}

static snell_status render(const snell_ref *ref, snell_ref_params *p, img *m)
{
    snell_ref_output o;
    o.rgb = m->rgb;
    o.exit_dir = m->dir;
    o.interfaces = m->nif;
    o.hit = m->hit;
    p->width = m->w;
    p->height = m->h;
    return snell_ref_render(ref, p, &o);
}

static int img_equal(const img *a, const img *b)
{
    size_t n = (size_t)a->w * a->h;
    return !memcmp(a->rgb, b->rgb, n * 3 * sizeof(float)) && !memcmp(a->dir, b->dir, n * 3 * sizeof(float)) &&
           !memcmp(a->nif, b->nif, n) && !memcmp(a->hit, b->hit, n);
}

static void write_png(const char *name, const img *m)
{
    uint8_t *px = (uint8_t *)malloc((size_t)m->w * m->h * 4);
    snell_ref_rgb_to_rgba8(m->rgb, m->w, m->h, px);
    CHECK_OK(snell_write_png(test_out(name), m->w, m->h, px));
    printf("wrote %s\n", test_out(name));
    free(px);
}

static void determinism(const snell_ref *ref, snell_ref_params base)
{
    int mode;
    for (mode = 0; mode < 2; mode++) {
        img a = img_new(96, 80), b = img_new(96, 80), c = img_new(96, 80);
        snell_ref_params p = base;
        p.mode = mode ? SNELL_REF_FULL : SNELL_REF_MATCHED;
        p.glass.absorption[0] = 0.3f;
        p.glass.tint[0] = 1.0f;
        p.glass.tint[1] = 0.9f;
        p.glass.tint[2] = 0.8f;
        p.threads = 1;
        CHECK_OK(render(ref, &p, &a));
        p.threads = 2;
        CHECK_OK(render(ref, &p, &b));
        p.threads = 5;
        CHECK_OK(render(ref, &p, &c));
        CHECK(img_equal(&a, &b) && img_equal(&a, &c), "mode %d: result depends on the thread count", mode);
        img_free(&a);
        img_free(&b);
        img_free(&c);
    }
}

static void energy(const snell_ref *ref, snell_ref_params base)
{
    int mode;
    for (mode = 0; mode < 2; mode++) {
        img a = img_new(64, 64);
        snell_ref_params p = base;
        size_t i, bad = 0, nonfinite = 0, above = 0, hits = 0;
        p.mode = mode ? SNELL_REF_FULL : SNELL_REF_MATCHED;
        p.env = NULL;
        p.env_fn = white;
        CHECK_OK(render(ref, &p, &a));
        for (i = 0; i < (size_t)64 * 64 * 3; i++) {
            if (!isfinite(a.rgb[i]) || !isfinite(a.dir[i])) nonfinite++;
            if (fabs(a.rgb[i] - 1.0) > 1e-6) bad++; /* float output: 1e-6 */
        }
        for (i = 0; i < (size_t)64 * 64; i++) hits += a.hit[i];
        p.glass.absorption[0] = 0.5f;
        p.glass.absorption[1] = 2.0f;
        p.glass.absorption[2] = 0.0f;
        p.glass.tint[0] = 0.7f;
        p.glass.tint[1] = 1.0f;
        p.glass.tint[2] = 1.0f;
        CHECK_OK(render(ref, &p, &a));
        for (i = 0; i < (size_t)64 * 64 * 3; i++) {
            if (!isfinite(a.rgb[i])) nonfinite++;
            if (a.rgb[i] > 1.0f + 1e-6f || a.rgb[i] < 0.0f) above++;
        }
        printf("energy mode %d: %zu hit pixels\n", mode, hits);
        CHECK(hits > 200, "mode %d: the object covers only %zu pixels", mode, hits);
        CHECK(nonfinite == 0, "mode %d: %zu NaN/Inf values", mode, nonfinite);
        CHECK(bad == 0, "mode %d: %zu channels differ from 1 in a white environment", mode, bad);
        CHECK(above == 0, "mode %d: %zu channels outside [0, 1] with absorption", mode, above);
        img_free(&a);
    }
}

static void paths_and_outputs(const snell_ref *ref, snell_ref_params p)
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
                if (path.interfaces != a.nif[i] || path.hit != a.hit[i] || (a.hit[i] != 0) != (a.nif[i] > 0))
                    bad_path++;
                l = sqrt((double)a.dir[3 * i] * a.dir[3 * i] + (double)a.dir[3 * i + 1] * a.dir[3 * i + 1] +
                         (double)a.dir[3 * i + 2] * a.dir[3 * i + 2]);
                if (fabs(l - 1.0) > 1e-6) bad_dir++;
                if (!path.hit) {
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
              "FULL outputs depend on which outputs are requested");
        o.hit = NULL;
        CHECK_OK(snell_ref_render(ref, &p, &o));
        CHECK(!memcmp(rgb, a.rgb, sizeof(float) * 3 * a.w * a.h), "FULL colour depends on the outputs requested");
        free(rgb);
        free(hit);
    }
    CHECK(bad_path == 0, "%d mismatches between trace_pixel and the rendered image", bad_path);
    CHECK(bad_bg == 0, "%d background pixels are not env(view ray)", bad_bg);
    CHECK(bad_dir == 0, "%d exit directions are not unit", bad_dir);
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
        snell_ref_desc rd;
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
        memset(&rd, 0, sizeof rd);
        rd.mesh = m;
        rd.model = model;
        CHECK_OK(snell_ref_create(NULL, &rd, &r1));
        rd.mesh = m2;
        rd.model = NULL;
        if (m2) CHECK_OK(snell_ref_create(NULL, &rd, &r2));
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

static void bad_input(const snell_ref *ref, snell_ref_params p)
{
    snell_ref *r = (snell_ref *)&r;
    snell_ref_desc rd;
    snell_ref_output o;
    snell_ref_path path;
    float rgb[3 * 4];
    double org[3] = {0, 0, 5}, dir[3] = {0, 0, 0};
    memset(&rd, 0, sizeof rd);
    memset(&o, 0, sizeof o);
    CHECK(snell_ref_create(NULL, &rd, &r) == SNELL_E_INVALID_ARG && r == NULL, "NULL mesh");
    CHECK(strstr(snell_last_error(NULL), "mesh") != NULL, "message: %s", snell_last_error(NULL));
    CHECK(snell_ref_create(NULL, NULL, &r) == SNELL_E_INVALID_ARG, "NULL desc");
    CHECK(snell_ref_create(NULL, &rd, NULL) == SNELL_E_INVALID_ARG, "NULL out");
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
    p.glass.ior = -1.0f;
    CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "negative ior");
    p.glass.ior = NAN;
    CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "NaN ior");
    p.glass.ior = 0.0f;
    p.glass.absorption[1] = -1.0f;
    CHECK(snell_ref_render(ref, &p, &o) == SNELL_E_INVALID_ARG, "negative absorption");
    p.glass.absorption[1] = 0.0f;
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
    snell_mesh *mesh = NULL, *sphere = NULL;
    snell_shape_desc sd;
    snell_ref *ref = NULL, *sref = NULL;
    snell_ref_desc rd;
    snell_ref_params p;
    int size = argc > 1 ? atoi(argv[1]) : 256;
    double t0;
    memset(&ed, 0, sizeof ed);
    CHECK_OK(snell_env_create(NULL, &ed, &env));
    if (!env) return test_finish();
    if (snell_mesh_load_obj(NULL, "/usr/share/glmark2/models/bunny.obj", &mesh) != SNELL_OK) {
        printf("bunny not available (%s): using the torus\n", snell_last_error(NULL));
        memset(&sd, 0, sizeof sd);
        sd.shape = SNELL_SHAPE_TORUS;
        CHECK_OK(snell_mesh_create_shape(NULL, &sd, &mesh));
    }
    if (!mesh) return test_finish();
    CHECK_OK(snell_mesh_normalize(mesh, 1.0f));
    memset(&rd, 0, sizeof rd);
    rd.mesh = mesh;
    t0 = now();
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    printf("reference of %u triangles built in %.3f s\n", snell_mesh_triangle_count(mesh), now() - t0);
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    sd.segments = 128;
    sd.rings = 64;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &sphere));
    rd.mesh = sphere;
    if (sphere) CHECK_OK(snell_ref_create(NULL, &rd, &sref));
    if (!ref || !sref) return test_finish();

    memset(&p, 0, sizeof p);
    p.env = env;
    p.camera.azimuth = 0.5f;
    p.camera.elevation = 0.25f;
    p.camera.distance = 3.0f;

    determinism(ref, p);
    energy(ref, p);
    paths_and_outputs(ref, p);
    model_matrix(p);
    bad_input(ref, p);

    p.threads = 0;
    p.glass.absorption[0] = 0.25f;
    p.glass.absorption[1] = 0.08f;
    p.glass.absorption[2] = 0.05f;
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

    snell_ref_destroy(ref);
    snell_ref_destroy(sref);
    snell_mesh_destroy(mesh);
    snell_mesh_destroy(sphere);
    snell_env_destroy(env);
    return test_finish();
}
