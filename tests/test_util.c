/* SPDX-License-Identifier: MIT */
#include "test_util.h"
#include "core/ctx.h"
#include "core/light_map.h"

#include <EGL/eglext.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

int test_passed, test_failed;

int test_finish(void)
{
    printf("%d passed, %d failed\n", test_passed, test_failed);
    return test_failed ? 1 : 0;
}

const char *test_data(const char *name)
{
    static char buf[1024];
    const char *dir = getenv("SNELL_TEST_DATA");
    snprintf(buf, sizeof buf, "%s/%s", dir ? dir : "data", name);
    return buf;
}

const char *test_out(const char *name)
{
    static char buf[1024];
    const char *dir = getenv("SNELL_TEST_OUT");
    snprintf(buf, sizeof buf, "%s/%s", dir ? dir : ".", name);
    return buf;
}

int test_write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(data, 1, n, f) == n;
    if (f && fclose(f) != 0) ok = 0;
    return ok;
}

unsigned char *test_read_file(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    unsigned char *b = NULL;
    long len;
    *n = 0;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (len = ftell(f)) > 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (b = (unsigned char *)malloc((size_t)len)) && fread(b, 1, (size_t)len, f) == (size_t)len)
        *n = (size_t)len;
    else {
        free(b);
        b = NULL;
    }
    fclose(f);
    return b;
}

snell_shading test_shading(void)
{
    const char *s = getenv("SNELL_TEST_SHADING");
    if (s && strcmp(s, "forward") == 0) return SNELL_SHADING_FORWARD;
    if (s && strcmp(s, "screen") == 0) return SNELL_SHADING_SCREEN;
    return SNELL_SHADING_AUTO;
}

double test_time_scale(void)
{
    const char *s = getenv("SNELL_TEST_TIME_SCALE");
    double v = s ? atof(s) : 1.0;
    return v >= 1.0 ? v : 1.0;
}

int test_host_context(EGLDisplay *dpy, EGLContext *ctx)
{
    typedef EGLDisplay (*gpd_fn)(EGLenum, void *, const EGLint *);
    gpd_fn gpd = (gpd_fn)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLint cfg_attrs[] = {EGL_RENDERABLE_TYPE, 0x40 /* ES3 */, EGL_SURFACE_TYPE, 0, EGL_NONE};
    EGLint ctx_attrs[] = {0x3098 /* MAJOR */, 3, EGL_NONE};
    EGLConfig cfg;
    EGLint n = 0;
    if (!gpd) return 0;
    *dpy = gpd(EGL_PLATFORM_SURFACELESS_MESA, NULL, NULL);
    if (*dpy == EGL_NO_DISPLAY || !eglInitialize(*dpy, NULL, NULL)) return 0;
    eglBindAPI(EGL_OPENGL_ES_API);
    if (!eglChooseConfig(*dpy, cfg_attrs, &cfg, 1, &n) || n < 1) return 0;
    *ctx = eglCreateContext(*dpy, cfg, EGL_NO_CONTEXT, ctx_attrs);
    return *ctx != EGL_NO_CONTEXT && eglMakeCurrent(*dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, *ctx);
}

/* SNELL_TEST_GLSL_DUMP=dir: every program's final sources (core/program.c,
 * defines and chunks pasted), a vertex shader and the fragment shader built
 * after it, written once per pair as dir/<hash>.vert and .frag for
 * tests/scripts/glsl_check.py (glslangValidator). */
static char *g_dump_vert;

static unsigned long long fnv64(unsigned long long h, const char *s)
{
    for (; *s; s++) h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return h;
}

static void dump_source(snell_ctx *ctx, unsigned stage, const char *src)
{
    const char *dir = (const char *)ctx->on_source_user;
    char path[1024];
    unsigned long long h;
    FILE *f;
    if (stage == 0x8B31) { /* GL_VERTEX_SHADER: kept until its fragment shader comes */
        free(g_dump_vert);
        if ((g_dump_vert = (char *)malloc(strlen(src) + 1)) != NULL) memcpy(g_dump_vert, src, strlen(src) + 1);
        return;
    }
    if (!g_dump_vert) return;
    h = fnv64(fnv64(14695981039346656037ull, g_dump_vert), src);
    snprintf(path, sizeof path, "%s/%016llx.frag", dir, h);
    if ((f = fopen(path, "r")) != NULL) {
        fclose(f);
        return;
    }
    test_write_file(path, src, strlen(src));
    snprintf(path, sizeof path, "%s/%016llx.vert", dir, h);
    test_write_file(path, g_dump_vert, strlen(g_dump_vert));
}

void test_glsl_dump(snell_ctx *ctx, const char *dir)
{
    ctx->on_source = dump_source;
    ctx->on_source_user = (void *)dir;
}

snell_ctx *test_ctx(void)
{
    snell_ctx *ctx = NULL;
    snell_ctx_desc d = {0};
    const char *dump = getenv("SNELL_TEST_GLSL_DUMP");
    if (snell_ctx_create(&d, &ctx) != SNELL_OK) {
        fprintf(stderr, "no headless GL context: %s\n", snell_last_error(NULL));
        return NULL;
    }
    if (dump && *dump) test_glsl_dump(ctx, dump);
    return ctx;
}

snell_env *test_sky(snell_ctx *ctx, int face_size)
{
    snell_env *env = NULL;
    snell_env_desc d;
    memset(&d, 0, sizeof d);
    d.face_size = face_size;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &d, &env));
    return env;
}

snell_renderer *test_renderer(snell_ctx *ctx, int width, int height)
{
    snell_renderer *r = NULL;
    snell_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.width = width;
    d.height = height;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &d, &r));
    return r;
}

void test_ref_params(const snell_frame_desc *fd, int w, int h, int max_interfaces, snell_ref_params *p)
{
    memset(p, 0, sizeof *p);
    p->mode = SNELL_REF_MATCHED;
    p->max_interfaces = max_interfaces;
    p->env = fd->env;
    p->camera = fd->camera;
    p->width = w;
    p->height = h;
}

snell_status test_ref_create(snell_ctx *ctx, const snell_frame_desc *fd, snell_ref **out)
{
    snell_ref_desc d;
    memset(&d, 0, sizeof d);
    d.glass = fd->glass;
    d.glass_count = fd->glass_count;
    d.opaque = fd->opaque;
    d.opaque_count = fd->opaque_count;
    return snell_ref_create(ctx, &d, out);
}

void test_frame_one(snell_frame_desc *fd, snell_glass *g, const snell_mesh *mesh, const snell_env *env)
{
    memset(fd, 0, sizeof *fd);
    memset(g, 0, sizeof *g);
    g->mesh = mesh;
    fd->env = env;
    fd->glass = g;
    fd->glass_count = 1;
}

snell_status test_ref_render(const snell_ref *ref, const snell_ref_params *p, float *rgb, float *exit_dir,
                             uint8_t *hit)
{
    snell_ref_output o;
    memset(&o, 0, sizeof o);
    o.rgb = rgb;
    o.exit_dir = exit_dir;
    o.hit = hit;
    return snell_ref_render(ref, p, &o);
}

snell_mesh *test_smooth_cube(int quads)
{
    enum { MAXQ = 16, MAXS = MAXQ + 1 };
    static float pos[3 * MAXS * MAXS * MAXS];
    static uint32_t idx[6 * MAXQ * MAXQ * 6];
    static int map[MAXS * MAXS * MAXS];
    snell_mesh_desc md;
    snell_mesh *m = NULL;
    int n = quads, side = quads + 1, i, j, k, axis, s, a, b, t = 0, nv = 0;
    if (quads < 1 || quads > MAXQ) return NULL;
    for (i = 0; i < side; i++)
        for (j = 0; j < side; j++)
            for (k = 0; k < side; k++) {
                int surface = i == 0 || i == n || j == 0 || j == n || k == 0 || k == n;
                map[(i * side + j) * side + k] = surface ? nv : -1;
                if (surface) {
                    pos[3 * nv] = -1.0f + 2.0f * (float)i / (float)n;
                    pos[3 * nv + 1] = -1.0f + 2.0f * (float)j / (float)n;
                    pos[3 * nv + 2] = -1.0f + 2.0f * (float)k / (float)n;
                    nv++;
                }
            }
    for (axis = 0; axis < 3; axis++)
        for (s = 0; s < 2; s++)
            for (a = 0; a < n; a++)
                for (b = 0; b < n; b++) {
                    /* (u, v) span the face with u x v = +axis: the +axis face (s = 1) keeps this order. */
                    static const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
                    int c[3], q, u = (axis + 1) % 3, v = (axis + 2) % 3;
                    uint32_t w[4];
                    for (q = 0; q < 4; q++) {
                        c[axis] = s ? n : 0;
                        c[u] = a + du[q];
                        c[v] = b + dv[q];
                        w[q] = (uint32_t)map[(c[0] * side + c[1]) * side + c[2]];
                    }
                    if (!s) { /* the -axis face: reversed */
                        uint32_t tmp = w[1];
                        w[1] = w[3];
                        w[3] = tmp;
                    }
                    idx[t++] = w[0], idx[t++] = w[1], idx[t++] = w[2];
                    idx[t++] = w[0], idx[t++] = w[2], idx[t++] = w[3];
                }
    memset(&md, 0, sizeof md);
    md.positions = pos;
    md.indices = idx;
    md.vertex_count = (uint32_t)nv;
    md.triangle_count = (uint32_t)(t / 3);
    if (snell_mesh_create(NULL, &md, &m) != SNELL_OK) return NULL;
    return m;
}

int test_write_blender_mesh(const snell_mesh *m, const double t[3], const char *path, int flip)
{
    static const double zero[3] = {0.0, 0.0, 0.0};
    uint32_t nv = snell_mesh_vertex_count(m), nt = snell_mesh_triangle_count(m), i;
    const float *p = snell_mesh_positions(m), *n = snell_mesh_normals(m);
    FILE *f = fopen(path, "wb");
    int ok;
    if (!f) return 0;
    if (!t) t = zero;
    ok = fwrite(&nv, 4, 1, f) == 1 && fwrite(&nt, 4, 1, f) == 1;
    for (i = 0; i < nv && ok; i++) {
        float b[3] = {(float)(p[3 * i] + t[0]), (float)(-(p[3 * i + 2] + t[2])), (float)(p[3 * i + 1] + t[1])};
        ok = fwrite(b, 4, 3, f) == 3;
    }
    for (i = 0; i < nv && ok; i++) {
        float b[3] = {n[3 * i], -n[3 * i + 2], n[3 * i + 1]};
        ok = fwrite(b, 4, 3, f) == 3;
    }
    for (i = 0; i < nt && ok; i++) {
        const uint32_t *tr = snell_mesh_indices(m) + 3 * i;
        uint32_t tri[3] = {tr[0], flip ? tr[2] : tr[1], flip ? tr[1] : tr[2]};
        ok = fwrite(tri, 4, 3, f) == 3;
    }
    return (fclose(f) == 0) && ok;
}

double test_light_map_flux(const float *v, int stride, int n, double texel)
{
    double e = 0;
    int i;
    for (i = 0; i < n; i++) e += v[i * stride + 1] * texel * texel;
    return e;
}

double test_light_map_excess(snell_ctx *ctx, const float *ref_rgb, int n, double texel)
{
    double e = 0;
    int i;
    if (!ctx || !snell__light_fixed(ctx)) return 0.0;
    for (i = 0; i < n; i++) e += fmax(0.0, ref_rgb[3 * i + 1] - SNELL__LIGHT_RANGE) * texel * texel;
    return e;
}

double test_light_map_psnr(const float *a, int stride_a, const float *b, int n, float albedo)
{
    double se = 0;
    int i, c;
    for (i = 0; i < n; i++)
        for (c = 0; c < 3; c++) {
            double x = fmin(1.0, albedo * a[i * stride_a + c]), y = fmin(1.0, albedo * b[i * 3 + c]);
            se += (x - y) * (x - y);
        }
    se /= 3.0 * n;
    return se > 0 ? 10.0 * log10(1.0 / se) : 999.0;
}

void test_write_light_map(const char *name, const float *v, int stride, int n, float albedo)
{
    uint8_t *px = (uint8_t *)malloc((size_t)n * n * 4);
    int i, j, c;
    if (!px) return;
    for (j = 0; j < n; j++) /* row 0 of the image: the far edge (z largest) */
        for (i = 0; i < n; i++)
            for (c = 0; c < 4; c++) {
                double x = c == 3 ? 1.0 : fmin(1.0, albedo * v[((n - 1 - j) * n + i) * stride + c]);
                px[4 * (j * n + i) + c] = (uint8_t)lround(x * 255.0);
            }
    snell_write_png(test_out(name), n, n, px);
    free(px);
}

double test_dir_angle(const float a[3], const float b[3])
{
    double c0 = (double)a[1] * b[2] - (double)a[2] * b[1], c1 = (double)a[2] * b[0] - (double)a[0] * b[2],
           c2 = (double)a[0] * b[1] - (double)a[1] * b[0];
    return atan2(sqrt(c0 * c0 + c1 * c1 + c2 * c2), (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2]);
}

double test_psnr_mask(const uint8_t *a, const uint8_t *b, const uint8_t *mask, int n, int *count)
{
    double se = 0.0;
    int i, c, m = 0;
    for (i = 0; i < n; i++) {
        if (!mask[i]) continue;
        m++;
        for (c = 0; c < 3; c++) se += pow((a[4 * i + c] - b[4 * i + c]) / 255.0, 2.0);
    }
    *count = m;
    se /= 3.0 * (m ? m : 1);
    return se > 0.0 ? 10.0 * log10(1.0 / se) : 999.0;
}

snell_dir_error test_dir_error(const float *test, const float *ref, const uint8_t *mask, int w, int h)
{
    snell_dir_error_desc d;
    snell_dir_error e;
    memset(&d, 0, sizeof d);
    memset(&e, 0, sizeof e);
    d.test = test;
    d.ref = ref;
    d.ref_mask = mask;
    d.width = w;
    d.height = h;
    CHECK_OK(snell_metrics_dir_error(&d, &e));
    CHECK(e.nan_inf == 0, "%ld non-finite exit directions", e.nan_inf);
    return e;
}

int test_ref_dirs(snell_ctx *ctx, const snell_frame_desc *fd, int w, int h, snell_ref_mode mode, int interfaces,
                  float *dirs, uint8_t *hit)
{
    float *rgb = (float *)malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    snell_ref *ref = NULL;
    snell_ref_params p;
    int traced = 0;
    CHECK(rgb != NULL, "out of memory for a %dx%d reference", w, h);
    if (rgb) CHECK_OK(test_ref_create(ctx, fd, &ref));
    if (ref) {
        test_ref_params(fd, w, h, interfaces, &p);
        p.mode = mode;
        p.isolate_glass = 1;
        snell_status st = test_ref_render(ref, &p, rgb, dirs, hit);
        CHECK_OK(st);
        traced = st == SNELL_OK;
        snell_ref_destroy(ref);
    }
    free(rgb);
    return traced;
}
