/* SPDX-License-Identifier: MIT */
/* test_lm2d_raster_cpu.c — the exact CPU rasteriser (eq. 4.2, no GL): against an
 * independent reference (each segment clipped to each pixel square), flux
 * conservation, SCREEN, a flipped view; and the threaded lightmap: bitwise the
 * same image for 1, 2, 3 and 8 threads, with and without the band lists, and
 * the rasteriser choice without GL (stats). Prints the measured errors. */
#include "lm2d/lm2d_raster.h"
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint32_t rs = 777u;
static float frand(void)
{
    rs = rs * 1664525u + 1013904223u;
    return (float)(rs >> 8) / 16777216.0f;
}

/* Length (pixel widths) of a..b inside pixel [x, x+1] x [y, y+1], and the
 * segment parameter at the middle of that part. */
static int pixel_part(double ax, double ay, double bx, double by, int x, int y, double *len, double *tm)
{
    double dx = bx - ax, dy = by - ay, t0 = 0.0, t1 = 1.0;
    double p[4] = {-dx, dx, -dy, dy}, q[4] = {ax - x, x + 1 - ax, ay - y, y + 1 - ay};
    int i;
    for (i = 0; i < 4; i++) {
        if (p[i] == 0.0) {
            if (q[i] < 0.0) return 0;
        } else {
            double r = q[i] / p[i];
            if (p[i] < 0.0) {
                if (r > t0) t0 = r;
            } else if (r < t1) {
                t1 = r;
            }
        }
    }
    if (!(t1 > t0)) return 0;
    *len = (t1 - t0) * sqrt(dx * dx + dy * dy);
    *tm = 0.5 * (t0 + t1);
    return 1;
}

/* Reference image (RGBA doubles, rows top first) of paths in a view that maps
 * world = pixels. */
static void reference(const lm2d_path *p, int n, int w, int h, double *ref)
{
    int i, x, y, k;
    for (i = 0; i < n; i++) {
        int x0 = (int)floor(fmin(p[i].x0, p[i].x1)), x1 = (int)floor(fmax(p[i].x0, p[i].x1));
        int y0 = (int)floor(fmin(p[i].y0, p[i].y1)), y1 = (int)floor(fmax(p[i].y0, p[i].y1));
        for (y = y0 < 0 ? 0 : y0; y <= y1 && y < h; y++)
            for (x = x0 < 0 ? 0 : x0; x <= x1 && x < w; x++) {
                double l, t;
                if (!pixel_part(p[i].x0, p[i].y0, p[i].x1, p[i].y1, x, y, &l, &t)) continue;
                for (k = 0; k < 3; k++)
                    ref[4 * (y * w + x) + k] += l * (p[i].c0[k] + (p[i].c1[k] - p[i].c0[k]) * t);
            }
    }
}

/* Random segments in and around a w x h image: general, long, short, nearly
 * and exactly axis-parallel (off the pixel lines, where the reference is
 * unambiguous), 45 degrees, partly and wholly outside, zero length; half with
 * constant flux, half with flux changing along them. */
static int make_paths(lm2d_path *p, int cap, int w, int h)
{
    int n = 0, i, k;
    for (i = 0; i < cap; i++) {
        lm2d_path *q = &p[n];
        float cx = -10.0f + frand() * (float)(w + 20), cy = -10.0f + frand() * (float)(h + 20);
        float len = (i % 4 == 0) ? frand() * 2.0f : frand() * (float)w, a = frand() * 6.2831853f;
        int kind = i % 7;
        if (kind == 1) a = 0.0f;                        /* horizontal */
        if (kind == 2) a = 1.5707963f;                  /* vertical */
        if (kind == 3) a = 0.7853982f;                  /* 45 degrees */
        if (kind == 4) a = 1e-4f * (frand() - 0.5f);    /* nearly horizontal */
        if (kind == 5 && i % 3 == 0) len = 0.0f;        /* zero length */
        if (kind == 1 || kind == 2) {                   /* keep off the pixel lines */
            cx = floorf(cx) + 0.1f + 0.8f * frand();
            cy = floorf(cy) + 0.1f + 0.8f * frand();
        }
        q->x0 = cx;
        q->y0 = cy;
        q->x1 = cx + len * cosf(a);
        q->y1 = cy + len * sinf(a);
        for (k = 0; k < 3; k++) {
            q->c0[k] = 0.1f + frand();
            q->c1[k] = (i & 1) ? q->c0[k] : 0.1f + frand();
        }
        n++;
    }
    return n;
}

static void test_against_reference(void)
{
    enum { W = 97, H = 150, N = 3000 }; /* 150 rows: three bands, one partial */
    lm2d_path *p = (lm2d_path *)malloc(N * sizeof *p);
    float *img = (float *)calloc(4 * W * H, sizeof(float)), *flip = (float *)calloc(4 * W * H, sizeof(float));
    double *ref = (double *)calloc(4 * W * H, sizeof(double)), err = 0.0, peak = 0.0, sum = 0.0, rsum = 0.0;
    lm2d_raster_view v = {W, H, {0, 0}, {W, H}}, vf = {W, H, {0, H}, {W, 0}};
    int n = make_paths(p, N, W, H), i, x, y, k;
    lm2d_raster_exact_add(p, (size_t)n, &v, 1.0f, img);
    reference(p, n, W, H, ref);
    for (i = 0; i < W * H; i++)
        for (k = 0; k < 3; k++) {
            double d = fabs(img[4 * i + k] - ref[4 * i + k]);
            if (d > err) err = d;
            if (ref[4 * i + k] > peak) peak = ref[4 * i + k];
            sum += img[4 * i + k];
            rsum += ref[4 * i + k];
        }
    printf("exact vs reference: %d segments %dx%d, max |diff| %.3g (peak %.3g), total %.9g vs %.9g\n", n, W, H, err,
           peak, sum, rsum);
    /* measured 1.2e-7 of the peak (float sums of ~100 contributions a pixel) */
    CHECK(err < 1e-6 * peak, "max error %.3g > 1e-6 x peak %.3g", err, peak);
    CHECK(fabs(sum - rsum) < 1e-5 * rsum, "total flux %.9g vs %.9g", sum, rsum);
    /* the fourth lane stays 0 */
    for (i = 0, k = 0; i < W * H; i++) k += img[4 * i + 3] != 0.0f;
    CHECK(k == 0, "%d pixels with a nonzero fourth lane", k);
    /* a flipped view (rows bottom first, as the lightmap stores them) is the mirror image */
    lm2d_raster_exact_add(p, (size_t)n, &vf, 1.0f, flip);
    err = 0.0;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++)
            for (k = 0; k < 3; k++) {
                double d = fabs(flip[4 * ((H - 1 - y) * W + x) + k] - img[4 * (y * W + x) + k]);
                if (d > err) err = d;
            }
    CHECK(err < 1e-6 * peak, "flipped view differs by %.3g", err);
    /* SCREEN: prod (1 - min(x, 1)) per contribution; with scale 1e-3 every x is small,
     * so 1 - prod ~ the sum to first order */
    for (i = 0; i < 4 * W * H; i++) flip[i] = 1.0f;
    lm2d_raster_exact_screen(p, (size_t)n, &v, 1e-3f, flip);
    err = 0.0;
    for (i = 0; i < W * H; i++)
        for (k = 0; k < 3; k++) {
            double s = 1.0 - flip[4 * i + k], a = 1e-3 * ref[4 * i + k];
            double d = fabs(s - (1.0 - exp(-a))) / (a + 1e-3);
            if (d > err) err = d;
        }
    printf("screen vs 1 - exp(-sum): max relative diff %.3g\n", err);
    CHECK(err < 0.02, "screen blend off by %.3g", err);
    free(p);
    free(img);
    free(flip);
    free(ref);
}

/* Segments along pixel lines and through pixel corners: whichever cell gets
 * them, no flux is lost or doubled. */
static void test_conservation(void)
{
    enum { W = 64, H = 200 };
    lm2d_path p[6];
    float *img = (float *)calloc(4 * W * H, sizeof(float));
    lm2d_raster_view v = {W, H, {0, 0}, {W, H}};
    double sum = 0.0, want = 0.0;
    int i, k;
    float seg[6][4] = {{3, 10, 60, 10}, {20, 5, 20, 190}, {0, 0, 64, 64}, {10, 70, 50, 190},
                       {0, 199.5f, 64, 199.5f}, {63.5f, 150, 63.5f, 66}};
    memset(p, 0, sizeof p);
    for (i = 0; i < 6; i++) {
        p[i].x0 = seg[i][0];
        p[i].y0 = seg[i][1];
        p[i].x1 = seg[i][2];
        p[i].y1 = seg[i][3];
        for (k = 0; k < 3; k++) p[i].c0[k] = p[i].c1[k] = 1.0f;
        want += 3.0 * hypot(seg[i][2] - seg[i][0], seg[i][3] - seg[i][1]);
    }
    lm2d_raster_exact_add(p, 6, &v, 1.0f, img);
    for (i = 0; i < 4 * W * H; i++) sum += img[i];
    CHECK(fabs(sum - want) < 1e-5 * want, "flux along pixel lines: %.9g, want %.9g", sum, want);
    free(img);
}

/* Tiny images and segments ending exactly on (or a rounding error beyond) the
 * image border: nothing written outside the image, no flux lost inside. */
static void test_edges(void)
{
    static const int sizes[][2] = {{1, 1}, {4, 3}, {3, 200}, {130, 2}};
    enum { GUARD = 64, N = 400 };
    int si, i, k, bad = 0;
    for (si = 0; si < 4; si++) {
        int w = sizes[si][0], h = sizes[si][1];
        size_t n = 4 * (size_t)w * (size_t)h;
        float *buf = (float *)malloc((n + 2 * GUARD) * sizeof(float)), *img = buf + GUARD;
        double *ref = (double *)calloc(n, sizeof(double)), sum = 0.0, rsum = 0.0;
        lm2d_path p[N];
        lm2d_raster_view v;
        /* world = pixels (so the reference applies); a second pass below in a
         * scaled, flipped world view, where clipping rounds around the border */
        v.width = w;
        v.height = h;
        v.lo[0] = v.lo[1] = 0.0f;
        v.hi[0] = (float)w;
        v.hi[1] = (float)h;
        for (i = 0; i < (int)(n + 2 * GUARD); i++) buf[i] = 0.0f;
        for (i = 0; i < N; i++) {
            /* endpoints on the border lines, just outside them, or well outside
             * (the segment then crosses the border: clipped there in doubles) */
            float e = (i & 3) == 0 ? 0.0f : ((i & 3) == 1 ? 1e-6f : -1e-6f);
            if (i & 4) e = 3.0f * frand();
            float fx = frand(), fy = frand();
            int side = i % 4;
            p[i].x0 = side == 0 ? -e : side == 1 ? (float)w + e : fx * (float)w;
            p[i].y0 = side == 2 ? -e : side == 3 ? (float)h + e : fy * (float)h;
            p[i].x1 = frand() * (float)w;
            p[i].y1 = frand() * (float)h;
            for (k = 0; k < 3; k++) p[i].c0[k] = p[i].c1[k] = 1.0f;
        }
        lm2d_raster_exact_add(p, N, &v, 1.0f, img);
        for (i = 0; i < GUARD; i++) bad += buf[i] != 0.0f || img[n + (size_t)i] != 0.0f;
        reference(p, N, w, h, ref);
        for (i = 0; i < (int)n; i++) {
            sum += img[i];
            rsum += ref[i];
        }
        CHECK(fabs(sum - rsum) < 1e-4 * rsum, "%dx%d: flux %.9g, want %.9g", w, h, sum, rsum);
        /* the same border points in world units of a 0.3..256.3 x 7..-93 view */
        for (i = 0; i < (int)(n + 2 * GUARD); i++) buf[i] = 0.0f;
        for (i = 0; i < N; i++) {
            p[i].x0 = 0.3f + p[i].x0 / (float)w * 256.0f;
            p[i].x1 = 0.3f + p[i].x1 / (float)w * 256.0f;
            p[i].y0 = 7.0f - p[i].y0 / (float)h * 100.0f;
            p[i].y1 = 7.0f - p[i].y1 / (float)h * 100.0f;
        }
        v.lo[0] = 0.3f;
        v.hi[0] = 256.3f;
        v.lo[1] = 7.0f;
        v.hi[1] = -93.0f;
        lm2d_raster_exact_add(p, N, &v, 1.0f, img);
        for (i = 0; i < GUARD; i++) bad += buf[i] != 0.0f || img[n + (size_t)i] != 0.0f;
        for (i = 0, sum = 0.0; i < (int)n; i++) sum += img[i];
        CHECK(fabs(sum - rsum) < 1e-4 * rsum, "%dx%d scaled view: flux %.9g, want %.9g", w, h, sum, rsum);
        free(buf);
        free(ref);
    }
    CHECK(bad == 0, "%d values written outside the image", bad);
}

/* A scene whose paths cover a tall image (11 bands) in every direction. */
static snell_scene2d *scene(void)
{
    snell_scene2d *s;
    snell_object2d_desc o;
    snell_light2d_desc L;
    float box[8] = {30, 100, 170, 100, 170, 140, 30, 140}, tri[6] = {60, 400, 150, 420, 90, 520};
    CHECK_OK(snell_scene2d_create(NULL, &s));
    memset(&o, 0, sizeof o);
    o.points = box;
    o.point_count = 4;
    o.material.diffuse = 0.5f;
    o.material.absorption = 0.3f;
    CHECK_OK(snell_scene2d_add_object(s, &o, NULL));
    o.points = tri;
    o.point_count = 3;
    o.material.transmission = 0.9f;
    o.material.ior = 1.5f;
    o.material.opaqueness = 0.02f; /* paths inside have a flux slope */
    CHECK_OK(snell_scene2d_add_object(s, &o, NULL));
    memset(&L, 0, sizeof L);
    L.position[0] = 100;
    L.position[1] = 300;
    L.power = 1;
    L.rays = 6000;
    CHECK_OK(snell_scene2d_add_light(s, &L, NULL));
    L.type = SNELL_LIGHT2D_BAR;
    L.position[0] = 20;
    L.position[1] = 690;
    L.end[0] = 180;
    L.end[1] = 690;
    CHECK_OK(snell_scene2d_add_light(s, &L, NULL));
    return s;
}

static void image(snell_scene2d *s, int threads, snell_blend2d blend, float *rgb, snell_lightmap2d_stats *st)
{
    snell_lightmap2d_desc d;
    snell_lightmap2d *lm = NULL;
    memset(&d, 0, sizeof d);
    d.width = 200;
    d.height = 700;
    d.threads = threads;
    d.seed = 3;
    d.max_bounces = 4;
    d.blend = blend;
    d.exposure = blend == SNELL_BLEND2D_SCREEN ? 20.0f : 1.0f;
    CHECK_OK(snell_lightmap2d_create(NULL, &d, &lm));
    if (!lm) return;
    CHECK_OK(snell_lightmap2d_frame(lm, s, st));
    CHECK_OK(snell_lightmap2d_read_rgb(lm, rgb));
    snell_lightmap2d_destroy(lm);
}

static void test_threads(void)
{
    static const int counts[] = {2, 3, 8};
    size_t n = 3 * 200 * 700, i;
    float *one = (float *)malloc(n * sizeof(float)), *many = (float *)malloc(n * sizeof(float));
    snell_scene2d *s = scene();
    snell_lightmap2d_stats st;
    int b, c, lit = 0;
    for (b = 0; b < 2; b++) {
        snell_blend2d blend = b ? SNELL_BLEND2D_SCREEN : SNELL_BLEND2D_ADD;
        image(s, 1, blend, one, &st);
        CHECK(st.raster == SNELL_RASTER2D_CPU && st.raster_threads == 1, "1 thread: raster %d on %d threads",
              (int)st.raster, st.raster_threads);
        for (i = 0; i < n; i++) lit += one[i] > 0.0f;
        for (c = 0; c < 3; c++) {
            image(s, counts[c], blend, many, &st);
            CHECK(st.raster_threads == counts[c], "raster threads %d, want %d", st.raster_threads, counts[c]);
            CHECK(memcmp(one, many, n * sizeof(float)) == 0, "%s: %d threads give another image than 1",
                  b ? "screen" : "add", counts[c]);
        }
    }
    CHECK(lit > (int)n / 4, "scene lights only %d of %zu values", lit, n);
    free(one);
    free(many);
    snell_scene2d_destroy(s);
}

/* The band lists (lightmap path) and the plain scan give the same bits. */
static void test_bins(void)
{
    enum { W = 120, H = 333, N = 2000 };
    lm2d_path *p = (lm2d_path *)malloc(N * sizeof *p);
    float *a = (float *)calloc(4 * W * H, sizeof(float)), *b = (float *)calloc(4 * W * H, sizeof(float));
    lm2d_raster_view v = {W, H, {0, 0}, {W, H}};
    lm2d_raster_bins *bins = NULL;
    lm2d_pool *pool = NULL;
    lm2d_raster_src src[2];
    int n = make_paths(p, N, W, H);
    CHECK_OK(lm2d_raster_bins_create(NULL, snell__ctx_alloc(NULL), &bins));
    CHECK_OK(lm2d_pool_create(NULL, snell__ctx_alloc(NULL), 3, &pool));
    src[0].paths = p;
    src[0].n = (size_t)n / 3;
    src[1].paths = p + n / 3;
    src[1].n = (size_t)(n - n / 3);
    lm2d_raster_exact(bins, pool, src, 2, &v, 0.5f, LM2D_RASTER_ADD, 1, a);
    lm2d_raster_exact_add(p, (size_t)n, &v, 0.5f, b);
    CHECK(memcmp(a, b, 4 * W * H * sizeof(float)) == 0, "band lists on 3 threads differ from the plain scan");
    /* again with fewer paths: the lists shrink without stale entries */
    src[1].n = 10;
    lm2d_raster_exact(bins, pool, src, 2, &v, 0.5f, LM2D_RASTER_ADD, 1, a);
    memset(b, 0, 4 * W * H * sizeof(float));
    lm2d_raster_exact_add(p, (size_t)n / 3 + 10, &v, 0.5f, b);
    CHECK(memcmp(a, b, 4 * W * H * sizeof(float)) == 0, "second frame with fewer paths differs");
    lm2d_pool_destroy(pool);
    lm2d_raster_bins_destroy(bins);
    free(p);
    free(a);
    free(b);
}

/* The rule without GL, and the errors of an impossible request. */
static void test_choice(void)
{
    char why[SNELL_REASON_SIZE];
    snell_lightmap2d_desc d;
    snell_lightmap2d *lm = NULL;
    CHECK(lm2d_raster_pick(SNELL_RASTER2D_AUTO, 0, NULL, why, sizeof why) == SNELL_RASTER2D_CPU, "no GL -> CPU");
    CHECK(lm2d_raster_pick(SNELL_RASTER2D_AUTO, 1, "llvmpipe (LLVM 15.0.6, 256 bits)", why, sizeof why) ==
              SNELL_RASTER2D_CPU && strstr(why, "llvmpipe"),
          "llvmpipe -> CPU (%s)", why);
    CHECK(lm2d_raster_pick(SNELL_RASTER2D_AUTO, 1, "softpipe", why, sizeof why) == SNELL_RASTER2D_CPU, "softpipe");
    CHECK(lm2d_raster_pick(SNELL_RASTER2D_AUTO, 1, "Mesa DRI swrast", why, sizeof why) == SNELL_RASTER2D_CPU,
          "swrast");
    CHECK(lm2d_raster_pick(SNELL_RASTER2D_AUTO, 1, "Mali-G78", why, sizeof why) == SNELL_RASTER2D_GL &&
              strstr(why, "Mali-G78"),
          "a GPU -> GL lines (%s)", why);
    CHECK(lm2d_raster_pick(SNELL_RASTER2D_AUTO, 1, "NVIDIA H200/PCIe/SSE2", why, sizeof why) == SNELL_RASTER2D_GL,
          "NVIDIA -> GL lines");
    CHECK(lm2d_raster_pick(SNELL_RASTER2D_GL, 1, "llvmpipe", why, sizeof why) == SNELL_RASTER2D_GL &&
              strstr(why, "requested"),
          "forced GL kept on llvmpipe");
    CHECK(lm2d_raster_pick(SNELL_RASTER2D_CPU, 1, "Adreno (TM) 640", why, sizeof why) == SNELL_RASTER2D_CPU,
          "forced CPU kept on a GPU");
    memset(&d, 0, sizeof d);
    d.width = d.height = 8;
    d.raster = SNELL_RASTER2D_GL;
    CHECK(snell_lightmap2d_create(NULL, &d, &lm) == SNELL_E_INVALID_ARG && !lm, "GL lines without a ctx accepted");
    d.raster = (snell_raster2d)7;
    CHECK(snell_lightmap2d_create(NULL, &d, &lm) == SNELL_E_INVALID_ARG && !lm, "unknown raster accepted");
}

int main(void)
{
    test_against_reference();
    test_conservation();
    test_edges();
    test_threads();
    test_bins();
    test_choice();
    return test_finish();
}
