/* SPDX-License-Identifier: MIT */
/* test_panels — glass panels (snell_panels.h) against the header's model
 * in double: a flat interior is (1 - F0) beneath plus the rim; a bevel or
 * corner pixel reads where the refracted ray lands; the shadow darkens
 * outside; a group merges a gap; dispersion splits the rim; frost is a
 * Gaussian to above 30 dB; a panel over another sees it; TEXTURE, EXTERNAL
 * (or its fallback), snell's own frame, ssaa and msaa, the bound framebuffer
 * with the host's GL state kept; hostile panels refused or drawn, a second
 * frame allocating nothing; the budget drops frost, then dispersion. */
#include "test_util.h"
#include "core/gl.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define W 96
#define H 64
#define N ((size_t)W * H)

static snell_ctx *g_ctx;
static long g_allocs; /* the context's allocations so far */
static EGLDisplay g_dpy;
static EGLContext g_egl;

static void *count_alloc(size_t n, void *u) { (void)u; g_allocs++; return malloc(n); }
static void *count_realloc(void *p, size_t n, void *u) { (void)u; g_allocs++; return realloc(p, n); }
static void count_free(void *p, void *u) { (void)u; free(p); }

enum { RAMP_X, RAMP_XY, STEEP, STEP_X, CHECKER, WAVES, PICTURE };

/* Texel (i, j) of a pattern, bottom row first. */
static void texel(int pattern, int i, int j, uint8_t c[4])
{
    int x = 4 * i > 255 ? 255 : 4 * i, y = 4 * j > 255 ? 255 : 4 * j;
    c[3] = 255;
    if (pattern == RAMP_X) c[0] = c[1] = c[2] = (uint8_t)x;
    else if (pattern == RAMP_XY) c[0] = (uint8_t)x, c[1] = (uint8_t)y, c[2] = 90;
    else if (pattern == STEEP) /* 16 a pixel about (75, 45): a read's move of 0.1 px shows */
        c[0] = (uint8_t)(i < 67 ? 0 : i > 82 ? 255 : 128 + 16 * (i - 75)),
        c[1] = (uint8_t)(j < 37 ? 0 : j > 52 ? 255 : 128 + 16 * (j - 45)), c[2] = 0;
    else if (pattern == STEP_X) c[0] = c[1] = c[2] = i >= 21 ? 255 : 0;
    else if (pattern == WAVES) /* periods of 20 and 14 px: what frost blurs, not erases */
        c[0] = (uint8_t)(128.0 + 120.0 * sin(i * 0.314159)), c[1] = (uint8_t)(128.0 + 120.0 * cos(j * 0.448799)),
        c[2] = (uint8_t)((i / 5 + j / 5) & 1 ? 220 : 40);
    else if (pattern == CHECKER) c[0] = c[1] = c[2] = ((i / 4 + j / 4) & 1) ? 255 : 0;
    else {
        int stripe = ((i + j) / 6) & 1;
        c[0] = (uint8_t)(stripe ? 240 : 30 + 2 * i);
        c[1] = (uint8_t)(stripe ? 200 - 2 * j : 90);
        c[2] = (uint8_t)(stripe ? 60 : 200);
    }
}

static GLuint texture(int pattern)
{
    static uint8_t px[4 * N];
    GLuint t;
    int i, j;
    for (j = 0; j < H; j++)
        for (i = 0; i < W; i++) texel(pattern, i, j, px + 4 * ((size_t)j * W + i));
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, px);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

/* The pattern read as an RGBA8 texture is (bilinear, edges clamped), channel c, 0..1. */
static double under(int pattern, double x, double y, int c)
{
    double fx = x - 0.5, fy = y - 0.5, v = 0.0;
    int i0 = (int)floor(fx), j0 = (int)floor(fy), a, b;
    for (a = 0; a < 2; a++)
        for (b = 0; b < 2; b++) {
            int i = i0 + a < 0 ? 0 : i0 + a >= W ? W - 1 : i0 + a, j = j0 + b < 0 ? 0 : j0 + b >= H ? H - 1 : j0 + b;
            uint8_t t[4];
            double wx = a ? fx - i0 : 1.0 - (fx - i0), wy = b ? fy - j0 : 1.0 - (fy - j0);
            texel(pattern, i, j, t);
            v += wx * wy * t[c] / 255.0;
        }
    return v;
}

static double fresnel(double c, double ior)
{
    double st2 = (1.0 - c * c) / (ior * ior), ct = sqrt(1.0 - st2);
    double rs = (c - ior * ct) / (c + ior * ct), rp = (ior * c - ct) / (ior * c + ct);
    return 0.5 * (rs * rs + rp * rp);
}

/* Where the view ray meets z = 0, relative to p (out[2]), at a point s
 * pixels inside a bevel of width bevel and profile squircle (0: circular),
 * thickness = bevel, where the field's gradient is g (not unit where the
 * corner's exponent is not 2): the header's model in double; returns the
 * Fresnel reflectance. */
static double landing2(double s, double bevel, int squircle, const double g[2], double ior, double out[2])
{
    double u = s / bevel, v = 1.0 - u, p, dp, h, n[3], len, eta = 1.0 / ior, c, k, t[3];
    int a;
    if (squircle) p = pow(1.0 - pow(v, 4.0), 0.25), dp = v * v * v / (p * p * p);
    else p = sqrt(1.0 - v * v), dp = v / p;
    h = bevel * p; /* h'(s) = thickness / bevel P'(u) = P'(u) */
    n[0] = dp * g[0], n[1] = dp * g[1], n[2] = 1.0;
    len = sqrt(n[0] * n[0] + n[1] * n[1] + 1.0);
    for (a = 0; a < 3; a++) n[a] /= len;
    c = n[2], k = 1.0 - eta * eta * (1.0 - c * c);
    for (a = 0; a < 3; a++) t[a] = eta * (a == 2 ? -1.0 : 0.0) + (eta * c - sqrt(k)) * n[a];
    out[0] = h * t[0] / -t[2], out[1] = h * t[1] / -t[2];
    return fresnel(c, ior);
}

/* The same along a straight edge whose outward gradient is -x: the read's
 * move in x (> 0: inwards). */
static double landing(double s, double bevel, double ior, double *f)
{
    const double g[2] = {-1.0, 0.0};
    double o[2];
    *f = landing2(s, bevel, 0, g, ior, o);
    return o[0];
}

static snell_renderer *offscreen(snell_output output)
{
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    memset(&rd, 0, sizeof rd);
    rd.width = W, rd.height = H, rd.output = output;
    CHECK_OK_CTX(g_ctx, snell_renderer_create(g_ctx, &rd, &r));
    return r;
}

/* A panel at (cx, cy) of w x h, corner radius r, bevel b (= thickness), no rim or shadow. */
static snell_panel panel(float cx, float cy, float w, float h, float r, float b)
{
    snell_panel p;
    memset(&p, 0, sizeof p);
    p.center[0] = cx, p.center[1] = cy, p.size[0] = w, p.size[1] = h;
    p.radius[0] = p.radius[1] = p.radius[2] = p.radius[3] = r;
    p.bevel = b, p.thickness = b, p.ior = 1.5f, p.rim = -1.0f, p.shadow[0] = -1.0f;
    return p;
}

static snell_status draw(snell_renderer *r, const snell_panel *p, int n, GLuint tex, uint8_t *img, snell_frame_stats *s)
{
    snell_frame_desc fd;
    snell_panels_under u;
    snell_status st;
    memset(&fd, 0, sizeof fd);
    memset(&u, 0, sizeof u);
    u.source = SNELL_PANELS_UNDER_TEXTURE, u.texture = tex, u.draw = 1;
    fd.draw_background = SNELL_BACKGROUND_NONE;
    fd.panels = p, fd.panel_count = n, fd.panels_under = &u;
    st = snell_render(r, &fd, s);
    if (st == SNELL_OK && img) st = snell_renderer_read_rgba(r, img);
    return st;
}

/* Channel c of pixel (x, y) counted from the bottom-left, 0..255. */
static int at(const uint8_t *img, int x, int y, int c)
{
    return img[4 * ((size_t)(H - 1 - y) * W + x) + c];
}

static int near(int got, double want, double tol)
{
    return fabs(got - want * 255.0) <= tol;
}

static void check_model(snell_renderer *r)
{
    static uint8_t img[4 * N], alone[4 * N];
    GLuint ramp = texture(RAMP_XY), step = texture(STEP_X), steep = texture(STEEP);
    snell_panel p = panel(48, 32, 64, 40, 8, 8), q[2];
    snell_frame_stats s;
    double f, dx, f0 = 0.04, want;
    int c;

    /* Flat interior: (1 - F0) beneath + F0 rim (0.707^4 of the default light straight up). */
    p.rim = 0.0f;
    CHECK_OK_CTX(g_ctx, draw(r, &p, 1, ramp, img, &s));
    for (c = 0; c < 3; c++) {
        want = (1.0 - f0) * under(RAMP_XY, 48.5, 32.5, c) + f0 * 0.25;
        CHECK(near(at(img, 48, 32, c), want, 1.0), "flat interior channel %d: %d, model %.2f", c, at(img, 48, 32, c),
              want * 255.0);
    }
    CHECK(s.panels_drawn == 1 && s.panels_captures == 0 && strstr(s.panels_reason, "texture"),
          "stats: %d drawn, %d captures, %s", s.panels_drawn, s.panels_captures, s.panels_reason);
    CHECK(at(img, 2, 2, 0) == 8 && at(img, 2, 2, 1) == 8, "outside the box: beneath as drawn");

    /* The bevel, 3.5 px inside the left edge: beneath read where the refracted ray lands. */
    p.rim = -1.0f;
    CHECK_OK_CTX(g_ctx, draw(r, &p, 1, ramp, img, &s));
    dx = landing(3.5, 8.0, 1.5, &f);
    CHECK(dx > 1.0, "the model moves the read by %.2f px inwards", dx);
    want = (1.0 - f) * under(RAMP_XY, 19.5 + dx, 32.5, 0);
    CHECK(near(at(img, 19, 32, 0), want, 1.5), "bevel: R %d, model %.2f (unrefracted %.2f)", at(img, 19, 32, 0),
          want * 255.0, (1.0 - f) * under(RAMP_XY, 19.5, 32.5, 0) * 255.0);
    want = (1.0 - f) * under(RAMP_XY, 19.5 + dx, 32.5, 1);
    CHECK(near(at(img, 19, 32, 1), want, 1.5), "bevel: G %d, model %.2f", at(img, 19, 32, 1), want * 255.0);

    /* A superelliptic corner (exponent 4, radius 16): at (76.5, 46.5)
     * q = (12.5, 10.5), d = ||q||_4 - 16, its gradient (q.x^3, q.y^3) /
     * ||q||_4^3, not a unit vector. Then a squircle bevel 1.5 px inside the
     * left edge. */
    {
        double qx = 12.5, qy = 10.5, norm = pow(pow(qx, 4.0) + pow(qy, 4.0), 0.25), g[2], o[2];
        const double left[2] = {-1.0, 0.0};
        snell_panel sq = panel(48, 32, 64, 40, 16, 8);
        sq.exponent = 4.0f;
        g[0] = pow(qx / norm, 3.0), g[1] = pow(qy / norm, 3.0);
        f = landing2(16.0 - norm, 8.0, 0, g, 1.5, o);
        CHECK_OK_CTX(g_ctx, draw(r, &sq, 1, steep, img, &s));
        CHECK(hypot(o[0], o[1]) > 1.0 && fabs(hypot(g[0], g[1]) - 1.0) > 0.1, "the corner's read moves %.2f px",
              hypot(o[0], o[1]));
        for (c = 0; c < 2; c++) {
            want = (1.0 - f) * under(STEEP, 76.5 + o[0], 46.5 + o[1], c);
            CHECK(near(at(img, 76, 46, c), want, 1.5), "superelliptic corner: channel %d %d, model %.2f (unmoved %.2f)",
                  c, at(img, 76, 46, c), want * 255.0, (1.0 - f) * under(STEEP, 76.5, 46.5, c) * 255.0);
        }
        sq.exponent = 2.0f, sq.bevel_profile = SNELL_PANEL_BEVEL_SQUIRCLE;
        f = landing2(1.5, 8.0, 1, left, 1.5, o);
        CHECK_OK_CTX(g_ctx, draw(r, &sq, 1, ramp, img, &s));
        want = (1.0 - f) * under(RAMP_XY, 17.5 + o[0], 32.5, 0);
        CHECK(o[0] > 1.0 && near(at(img, 17, 32, 0), want, 1.5), "squircle bevel: %d, model %.2f (moved %.2f px)",
              at(img, 17, 32, 0), want * 255.0, o[0]);
    }

    /* Dispersion (Abbe 5) over a step between x = 20.5 and 21.5: blue bends
     * more than red at the rim, one read in the interior. */
    p.dispersion = 4.0f;
    CHECK_OK_CTX(g_ctx, draw(r, &p, 1, step, img, &s));
    for (c = 0; c < 3; c += 2) {
        double lambda = c ? 486.1 : 656.3, ior = 1.5 + 0.5 * (4.0 / 20.0) * (523655.0 / (lambda * lambda) - 1.5168);
        double d = landing(3.5, 8.0, ior, &f);
        want = (1.0 - f) * under(STEP_X, 19.5 + d, 32.5, c);
        CHECK(near(at(img, 19, 32, c), want, 1.5), "dispersion: channel %d %d, model %.2f (ior %.4f)", c,
              at(img, 19, 32, c), want * 255.0, ior);
    }
    CHECK(at(img, 19, 32, 2) >= at(img, 19, 32, 0) + 20, "the rim separates blue (%d) from red (%d)", at(img, 19, 32, 2),
          at(img, 19, 32, 0));
    for (c = 0; c < 3; c += 2) {
        double lambda = c ? 486.1 : 656.3, ior = 1.5 + 0.5 * (4.0 / 20.0) * (523655.0 / (lambda * lambda) - 1.5168);
        want = 1.0 - pow((ior - 1.0) / (ior + 1.0), 2.0); /* one read: only each channel's F0 differs */
        CHECK(near(at(img, 48, 32, c), want, 1.0), "dispersion's interior: channel %d %d, model %.2f", c,
              at(img, 48, 32, c), want * 255.0);
    }
    p.dispersion = 0.0f;

    /* Shadow below the panel (radius 16, opacity 0.2, offset (0, -4)): its field at p - offset. */
    memset(p.shadow, 0, sizeof p.shadow);
    CHECK_OK_CTX(g_ctx, draw(r, &p, 1, ramp, img, &s));
    want = 0.8 * under(RAMP_XY, 48.5, 9.5, 0); /* d(p - offset) = 12 - 13.5 < 0 */
    CHECK(near(at(img, 48, 9, 0), want, 1.0), "shadow under the edge: %d, model %.2f", at(img, 48, 9, 0), want * 255.0);
    want = (1.0 - 0.2 * pow(1.0 - 7.5 / 16.0, 2.0)) * under(RAMP_XY, 48.5, 0.5, 0);
    CHECK(near(at(img, 48, 0, 0), want, 1.0), "shadow 7.5 px out: %d, model %.2f", at(img, 48, 0, 0), want * 255.0);

    /* Two panels 6 px apart: alone, the gap is beneath; a group (k = 16) closes it. */
    q[0] = panel(30, 32, 30, 30, 6, 6), q[1] = panel(66, 32, 30, 30, 6, 6);
    CHECK_OK_CTX(g_ctx, draw(r, q, 2, ramp, alone, &s));
    CHECK(s.panels_drawn == 2, "two shapes drawn: %d", s.panels_drawn);
    q[0].group = q[1].group = 3;
    CHECK_OK_CTX(g_ctx, draw(r, q, 2, ramp, img, &s));
    CHECK(s.panels_drawn == 1, "a group is one shape: %d", s.panels_drawn);
    CHECK(at(alone, 48, 32, 0) == at(alone, 48, 30, 0) && near(at(alone, 48, 32, 0), under(RAMP_XY, 48.5, 32.5, 0), 0.5),
          "alone, the gap shows beneath: %d", at(alone, 48, 32, 0));
    CHECK(abs(at(img, 48, 32, 1) - at(alone, 48, 32, 1)) >= 3, "merged, the gap is glass: G %d against %d",
          at(img, 48, 32, 1), at(alone, 48, 32, 1));

    /* A panel over another sees it: B's flat interior over A's tinted glass
     * is (1 - F0) times A's pixel there (the overlap copied again). */
    q[0] = panel(36, 32, 40, 40, 8, 8), q[1] = panel(64, 32, 40, 40, 8, 8);
    q[0].tint[0] = 1.0f, q[0].tint[3] = 0.9f;
    CHECK_OK_CTX(g_ctx, draw(r, q, 1, ramp, alone, &s));
    CHECK_OK_CTX(g_ctx, draw(r, q, 2, ramp, img, &s));
    CHECK(s.panels_captures == 2, "one capture and one copy of the overlap: %d", s.panels_captures);
    for (c = 0; c < 3; c++)
        CHECK(near(at(img, 53, 32, c), (1.0 - f0) * at(alone, 53, 32, c) / 255.0, 1.0),
              "over the first panel, channel %d: %d, model %.2f", c, at(img, 53, 32, c), (1.0 - f0) * at(alone, 53, 32, c));
    glDeleteTextures(1, &ramp);
    glDeleteTextures(1, &step);
    glDeleteTextures(1, &steep);
}

static double spread(const uint8_t *img, int x0, int y0, int x1, int y1)
{
    double sum = 0.0, sq = 0.0, n = 0.0;
    int x, y;
    for (y = y0; y < y1; y++)
        for (x = x0; x < x1; x++) {
            double v = at(img, x, y, 0);
            sum += v, sq += v * v, n += 1.0;
        }
    return sqrt(sq / n - (sum / n) * (sum / n));
}

static void check_frost(snell_renderer *r)
{
    static uint8_t img[4 * N];
    GLuint checker = texture(CHECKER);
    snell_panel p = panel(48, 32, 60, 44, 8, 8);
    snell_frame_stats s;
    double clear, frosted;
    int k;
    CHECK_OK_CTX(g_ctx, draw(r, &p, 1, checker, img, &s));
    clear = spread(img, 36, 24, 60, 40);
    p.frost = 4.0f;
    CHECK_OK_CTX(g_ctx, draw(r, &p, 1, checker, img, &s));
    frosted = spread(img, 36, 24, 60, 40);
    CHECK(clear > 100.0 && frosted < 0.4 * clear, "frost 4 px blurs a 4 px checker: spread %.1f, clear %.1f",
          frosted, clear);
    CHECK(s.panels_captures == 1, "frost over a texture copies it once: %d", s.panels_captures);
    glDeleteTextures(1, &checker);

    /* Against the header's Gaussian of sigma frost (cut at 3 sigma, edges
     * clamped) over the flat interior: (1 - F0) times the blur. */
    for (k = 0; k < 3; k++) {
        static const float sigma[3] = {1.5f, 3.0f, 6.0f};
        GLuint waves = texture(WAVES);
        double se = 0.0, n = 0.0, psnr;
        int x, y, c;
        p = panel(48, 32, 80, 56, 6, 6), p.frost = sigma[k];
        CHECK_OK_CTX(g_ctx, draw(r, &p, 1, waves, img, &s));
        for (y = 10; y < 54; y++)
            for (x = 14; x < 82; x++)
                for (c = 0; c < 3; c++) {
                    double sum = 0.0, wsum = 0.0, e;
                    int i, j, reach = (int)ceil(3.0 * sigma[k]);
                    for (j = y - reach; j <= y + reach; j++)
                        for (i = x - reach; i <= x + reach; i++) {
                            double w = exp(-((i - x) * (i - x) + (j - y) * (j - y)) / (2.0 * sigma[k] * sigma[k]));
                            uint8_t t[4];
                            texel(WAVES, i < 0 ? 0 : i >= W ? W - 1 : i, j < 0 ? 0 : j >= H ? H - 1 : j, t);
                            sum += w * t[c], wsum += w;
                        }
                    e = at(img, x, y, c) - 0.96 * sum / wsum;
                    se += e * e, n += 1.0;
                }
        psnr = 10.0 * log10(255.0 * 255.0 / (se / n));
        printf("frost %.1f px against a Gaussian: %.1f dB\n", sigma[k], psnr);
        CHECK(psnr > 30.0, "frost %.1f px against a Gaussian: %.1f dB", sigma[k], psnr);
        glDeleteTextures(1, &waves);
    }
}

/* EXTERNAL: an EGLImage of a GL texture bound as GL_TEXTURE_EXTERNAL_OES
 * draws what TEXTURE draws; without the extension, TARGET and the reason. */
static void check_external(snell_renderer *r)
{
    static uint8_t img[4 * N], want[4 * N];
    typedef EGLImageKHR (*create_fn)(EGLDisplay, EGLContext, EGLenum, EGLClientBuffer, const EGLint *);
    typedef EGLBoolean (*destroy_fn)(EGLDisplay, EGLImageKHR);
    typedef void (*target_fn)(GLenum, GLeglImageOES);
    create_fn create = (create_fn)eglGetProcAddress("eglCreateImageKHR");
    destroy_fn destroy = (destroy_fn)eglGetProcAddress("eglDestroyImageKHR");
    target_fn target = (target_fn)eglGetProcAddress("glEGLImageTargetTexture2DOES");
    const char *egl_ext = eglQueryString(g_dpy, EGL_EXTENSIONS);
    GLuint ramp = texture(RAMP_XY), ext = 0;
    snell_panel p = panel(48, 32, 64, 40, 8, 8);
    snell_frame_desc fd;
    snell_panels_under u;
    snell_frame_stats s;
    EGLImageKHR image = EGL_NO_IMAGE_KHR;
    CHECK_OK_CTX(g_ctx, draw(r, &p, 1, ramp, want, &s));
    if (!snell_ctx_has_gl_extension(g_ctx, "GL_OES_EGL_image_external_essl3")) {
        /* the fallback: what the target holds (the same picture, drawn by the frame before) */
        memset(&fd, 0, sizeof fd);
        memset(&u, 0, sizeof u);
        u.source = SNELL_PANELS_UNDER_EXTERNAL, u.texture = 1234;
        fd.draw_background = SNELL_BACKGROUND_NONE, fd.panels = &p, fd.panel_count = 1, fd.panels_under = &u;
        CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
        CHECK(strstr(s.panels_reason, "EXTERNAL without GL_OES_EGL_image_external_essl3") && s.panels_captures == 1,
              "EXTERNAL falls back to the target: %s", s.panels_reason);
        printf("EXTERNAL: no GL_OES_EGL_image_external_essl3 here: the fallback checked\n");
        glDeleteTextures(1, &ramp);
        return;
    }
    CHECK(create && destroy && target && egl_ext && strstr(egl_ext, "EGL_KHR_gl_texture_2D_image"),
          "EGL_KHR_gl_texture_2D_image and OES_EGL_image");
    if (create && target && egl_ext && strstr(egl_ext, "EGL_KHR_gl_texture_2D_image"))
        image = create(g_dpy, g_egl, EGL_GL_TEXTURE_2D_KHR, (EGLClientBuffer)(uintptr_t)ramp, NULL);
    CHECK(image != EGL_NO_IMAGE_KHR, "an EGLImage of the texture");
    if (image == EGL_NO_IMAGE_KHR) return;
    glGenTextures(1, &ext);
    glBindTexture(GL_TEXTURE_EXTERNAL_OES, ext);
    target(GL_TEXTURE_EXTERNAL_OES, (GLeglImageOES)image);
    glBindTexture(GL_TEXTURE_EXTERNAL_OES, 0);
    memset(&fd, 0, sizeof fd);
    memset(&u, 0, sizeof u);
    u.source = SNELL_PANELS_UNDER_EXTERNAL, u.texture = ext, u.draw = 1;
    fd.draw_background = SNELL_BACKGROUND_NONE, fd.panels = &p, fd.panel_count = 1, fd.panels_under = &u;
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
    CHECK_OK_CTX(g_ctx, snell_renderer_read_rgba(r, img));
    CHECK(strstr(s.panels_reason, "external"), "reason: %s", s.panels_reason);
    CHECK(memcmp(img, want, sizeof img) == 0, "EXTERNAL draws what TEXTURE draws");
    p.frost = 2.0f; /* copied into the capture first, as a 2D texture is */
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
    CHECK_OK_CTX(g_ctx, snell_renderer_read_rgba(r, img));
    CHECK_OK_CTX(g_ctx, draw(r, &p, 1, ramp, want, NULL));
    CHECK(s.panels_captures == 1 && memcmp(img, want, sizeof img) == 0, "frosted, EXTERNAL draws what TEXTURE draws");
    p.frost = 0.0f;
    u.texture = ramp; /* a GL_TEXTURE_2D is not an external one */
    CHECK(snell_render(r, &fd, &s) == SNELL_E_INVALID_ARG, "a 2D texture as EXTERNAL is refused: %s",
          snell_last_error(g_ctx));
    glDeleteTextures(1, &ext);
    destroy(g_dpy, image);
    glDeleteTextures(1, &ramp);
}

/* TARGET in a host's framebuffer (the bound one): the flat interior over
 * what it held, and the host's GL state as it was. */
static void check_bound(void)
{
    static uint8_t img[4 * N];
    GLuint ramp = texture(RAMP_XY), fbo, depth, vao, prog_tex = texture(CHECKER), sampler;
    GLint v[4], box[4] = {3, 4, 20, 30};
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    snell_panel p = panel(48, 32, 64, 40, 8, 8);
    snell_frame_desc fd;
    snell_frame_stats s;
    int c;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, ramp, 0);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
    glViewport(0, 0, W, H);
    memset(&rd, 0, sizeof rd);
    rd.width = W, rd.height = H, rd.target = SNELL_TARGET_BOUND_FRAMEBUFFER;
    CHECK_OK_CTX(g_ctx, snell_renderer_create(g_ctx, &rd, &r));
    /* the host's state */
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenSamplers(1, &sampler);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, prog_tex);
    glBindSampler(0, sampler);
    glActiveTexture(GL_TEXTURE3);
    glEnable(GL_BLEND);
    glEnable(GL_SCISSOR_TEST);
    glScissor(box[0], box[1], box[2], box[3]);
    memset(&fd, 0, sizeof fd);
    p.rim = 0.0f;
    fd.draw_background = SNELL_BACKGROUND_NONE, fd.panels = &p, fd.panel_count = 1;
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
    CHECK(s.panels_captures == 1 && strstr(s.panels_reason, "frame's rectangle"), "TARGET: %d captures, %s",
          s.panels_captures, s.panels_reason);
    glGetIntegerv(GL_ACTIVE_TEXTURE, v);
    CHECK(v[0] == GL_TEXTURE3, "the host's active unit kept");
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, v);
    CHECK(v[0] == (GLint)vao, "the host's vertex array kept");
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, v);
    CHECK(v[0] == (GLint)fbo, "the host's framebuffer kept");
    glGetIntegerv(GL_SCISSOR_BOX, v);
    CHECK(glIsEnabled(GL_BLEND) && glIsEnabled(GL_SCISSOR_TEST) && !memcmp(v, box, sizeof box),
          "blend and scissor kept");
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, v);
    glGetIntegerv(GL_SAMPLER_BINDING, v + 1);
    CHECK(v[0] == (GLint)prog_tex && v[1] == (GLint)sampler, "unit 0's texture and sampler kept");
    CHECK(glGetError() == GL_NO_ERROR, "no GL error left");
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, img);
    for (c = 0; c < 3; c++) {
        double want = 0.96 * under(RAMP_XY, 48.5, 32.5, c) + 0.04 * 0.25;
        int got = img[4 * ((size_t)32 * W + 48) + c];
        CHECK(near(got, want, 1.0), "TARGET flat interior channel %d: %d, model %.2f", c, got, want * 255.0);
    }
    snell_renderer_destroy(r);
    glBindSampler(0, 0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteSamplers(1, &sampler);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &depth);
    glDeleteTextures(1, &ramp);
    glDeleteTextures(1, &prog_tex);
}

/* Over snell's own frame (a glass sphere and the environment, offscreen):
 * the flat interior is (1 - F0) times that frame's pixel plus the rim. */
static void check_scene(snell_renderer *r)
{
    static uint8_t plain[4 * N], img[4 * N];
    snell_shape_desc sd;
    snell_env_desc ed;
    snell_mesh *mesh = NULL;
    snell_env *env = NULL;
    snell_glass g;
    snell_frame_desc fd;
    snell_frame_stats s;
    snell_panel p = panel(40, 30, 50, 40, 8, 8);
    int c, x, y;
    memset(&sd, 0, sizeof sd);
    memset(&ed, 0, sizeof ed);
    memset(&g, 0, sizeof g);
    memset(&fd, 0, sizeof fd);
    ed.face_size = 16;
    CHECK_OK_CTX(g_ctx, snell_mesh_create_shape(g_ctx, &sd, &mesh));
    CHECK_OK_CTX(g_ctx, snell_env_create(g_ctx, &ed, &env));
    g.mesh = mesh;
    fd.env = env, fd.glass = &g, fd.glass_count = 1;
    if (mesh && env) {
        CHECK_OK_CTX(g_ctx, snell_render(r, &fd, NULL));
        CHECK_OK_CTX(g_ctx, snell_renderer_read_rgba(r, plain));
        p.rim = 0.0f, fd.panels = &p, fd.panel_count = 1;
        CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
        CHECK_OK_CTX(g_ctx, snell_renderer_read_rgba(r, img));
        CHECK(s.panels_captures == 1 && strstr(s.stages, "kernels") && strstr(s.stages, "panels"),
              "panels over the frame: %d captures, stages %s", s.panels_captures, s.stages);
        for (y = 20; y < 40; y += 9)
            for (x = 30; x < 50; x += 9)
                for (c = 0; c < 3; c++)
                    CHECK(near(at(img, x, y, c), 0.96 * at(plain, x, y, c) / 255.0 + 0.01, 1.0),
                          "over the frame at (%d, %d) channel %d: %d, model %.2f", x, y, c, at(img, x, y, c),
                          0.96 * at(plain, x, y, c) + 2.55);
        for (c = 0, y = 0; y < H; y++) /* right of the panel's box (its shadow's reach included) */
            c += memcmp(img + 4 * ((size_t)y * W + 84), plain + 4 * ((size_t)y * W + 84), 4 * (W - 84)) != 0;
        CHECK(c == 0, "right of the box the frame is as it was (%d rows differ)", c);
    }
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
}

/* Renderers that resolve (ssaa 2, msaa 4): the panels are drawn over the
 * image read back, at its size, as without. */
static void check_resolves(void)
{
    static uint8_t img[4 * N];
    GLuint ramp = texture(RAMP_XY);
    snell_panel p = panel(48, 32, 64, 40, 8, 8);
    int k, c;
    p.rim = 0.0f;
    for (k = 0; k < 2; k++) {
        snell_renderer_desc rd;
        snell_renderer *r = NULL;
        snell_frame_stats s;
        memset(&rd, 0, sizeof rd);
        rd.width = W, rd.height = H, rd.ssaa = k ? 0 : 2, rd.msaa = k ? 4 : 0;
        CHECK_OK_CTX(g_ctx, snell_renderer_create(g_ctx, &rd, &r));
        if (!r) continue;
        CHECK_OK_CTX(g_ctx, draw(r, &p, 1, ramp, img, &s));
        for (c = 0; c < 3; c++)
            CHECK(near(at(img, 48, 32, c), 0.96 * under(RAMP_XY, 48.5, 32.5, c) + 0.01, 1.0),
                  "%s: flat interior channel %d: %d", k ? "msaa 4" : "ssaa 2", c, at(img, 48, 32, c));
        CHECK(at(img, 2, 2, 0) == 8, "%s: beneath outside the box", k ? "msaa 4" : "ssaa 2");
        snell_renderer_destroy(r);
    }
    glDeleteTextures(1, &ramp);
}

static void refused(snell_renderer *r, snell_frame_desc *fd, const char *part)
{
    snell_status st = snell_render(r, fd, NULL);
    CHECK(st == SNELL_E_INVALID_ARG && strstr(snell_last_error(g_ctx), part), "refused naming %s: %s (%s)", part,
          snell_status_str(st), snell_last_error(g_ctx));
}

static void check_hostile(snell_renderer *r)
{
    static snell_panel many[SNELL_MAX_PANELS + 1];
    static uint8_t img[4 * N];
    GLuint ramp = texture(RAMP_XY);
    snell_renderer *dirs = offscreen(SNELL_OUTPUT_EXIT_DIRECTION);
    snell_panel p = panel(48, 32, 64, 40, 8, 8);
    snell_panels_under u;
    snell_frame_desc fd;
    snell_frame_stats s;
    double t0, ms;
    int i;
    memset(&fd, 0, sizeof fd);
    memset(&u, 0, sizeof u);
    u.source = SNELL_PANELS_UNDER_TEXTURE, u.texture = ramp, u.draw = 1;
    fd.draw_background = SNELL_BACKGROUND_NONE, fd.panels = &p, fd.panel_count = 1, fd.panels_under = &u;
    p.center[0] = NAN;
    refused(r, &fd, "panels[0].center");
    p.center[0] = 48.0f, p.ior = INFINITY;
    refused(r, &fd, "panels[0].ior");
    p.ior = 1.5f;
    fd.panel_count = SNELL_MAX_PANELS + 1, fd.panels = many;
    refused(r, &fd, "panel_count");
    fd.panel_count = 1, fd.panels = &p;
    u.texture = 9999;
    refused(r, &fd, "panels_under.texture");
    u.texture = ramp, u.uv_transform[5] = NAN;
    refused(r, &fd, "uv_transform");
    u.uv_transform[5] = 0.0f, u.source = SNELL_PANELS_UNDER_EXTERNAL, u.texture = 0;
    refused(r, &fd, "panels_under.texture");
    u.source = SNELL_PANELS_UNDER_TEXTURE, u.texture = ramp;
    fd.draw_background = SNELL_BACKGROUND_DRAW;
    refused(r, &fd, "environment");
    fd.draw_background = SNELL_BACKGROUND_NONE;
    if (dirs) refused(dirs, &fd, "SNELL_OUTPUT_COLOR");
    snell_renderer_destroy(dirs);
    for (i = 0; i < 9; i++) many[i] = panel(10.0f * (float)i, 20, 8, 8, 2, 2), many[i].group = 1;
    fd.panels = many, fd.panel_count = 9;
    refused(r, &fd, "group 1");

    /* Drawn: sharp and huge radii, off the frame, larger than the frame. */
    fd.panels = &p, fd.panel_count = 1;
    p.radius[0] = p.radius[1] = p.radius[2] = p.radius[3] = -1.0f;
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
    p.radius[0] = p.radius[1] = p.radius[2] = p.radius[3] = 1e5f;
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
    p.center[0] = -5000.0f;
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
    CHECK(s.panels_drawn == 0, "a panel off the frame is culled");
    p = panel(48, 32, 1e6f, 1e6f, 0, 0);
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
    CHECK_OK_CTX(g_ctx, snell_renderer_read_rgba(r, img));
    CHECK(s.panels_drawn == 1 && near(at(img, 50, 30, 0), 0.96 * under(RAMP_XY, 50.5, 30.5, 0), 1.0),
          "a panel larger than the frame: flat at (50, 30): %d", at(img, 50, 30, 0));

    /* 1,000 panels of every kind, some in groups. */
    srand(7);
    for (i = 0; i < 1000; i++) {
        snell_panel *q = &many[i];
        *q = panel((float)(rand() % (W + 40)) - 20.0f, (float)(rand() % (H + 40)) - 20.0f, 4.0f + (float)(rand() % 30),
                   4.0f + (float)(rand() % 30), (float)(rand() % 8), (float)(rand() % 6));
        q->frost = (float)(rand() % 3), q->dispersion = (float)(rand() % 2), q->group = i % 5 == 0 ? 1 + (i / 5) % 100 : 0;
        q->exponent = (float)(2 + rand() % 6), q->bevel_profile = (snell_panel_bevel)(rand() % 2);
    }
    fd.panels = many, fd.panel_count = 1000;
    t0 = (double)clock();
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
    CHECK_OK_CTX(g_ctx, snell_renderer_read_rgba(r, img));
    ms = ((double)clock() - t0) * 1000.0 / CLOCKS_PER_SEC;
    CHECK(s.panels_drawn > 300 && ms < 20000.0 * test_time_scale(), "1,000 panels: %d shapes, %d captures, %.0f ms CPU",
          s.panels_drawn, s.panels_captures, ms);
    printf("1,000 panels: %d shapes drawn, %d captures, %.0f ms CPU\n", s.panels_drawn, s.panels_captures, ms);
    {
        long before = g_allocs;
        CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
        CHECK(g_allocs == before, "a frame of panels after the first allocates nothing: %ld", g_allocs - before);
    }
    glDeleteTextures(1, &ramp);
}

/* The budget: a tiny one drops frost, then dispersion, and says so; a large one drops nothing. */
static void check_budget(snell_renderer *r)
{
    GLuint ramp = texture(RAMP_XY);
    snell_panel p = panel(48, 32, 64, 40, 8, 8);
    snell_panels_under u;
    snell_frame_desc fd;
    snell_frame_stats s;
    p.frost = 3.0f, p.dispersion = 1.0f;
    memset(&fd, 0, sizeof fd);
    memset(&u, 0, sizeof u);
    u.source = SNELL_PANELS_UNDER_TEXTURE, u.texture = ramp, u.draw = 1;
    fd.draw_background = SNELL_BACKGROUND_NONE, fd.panels = &p, fd.panel_count = 1, fd.panels_under = &u;
    fd.budget_ms = 1e-4f;
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
    CHECK(s.panels_dropped == (SNELL_PANELS_DROPPED_FROST | SNELL_PANELS_DROPPED_DISPERSION) &&
              strstr(s.panels_reason, "frost and dispersion dropped"),
          "a tiny budget drops both: %u, %s", s.panels_dropped, s.panels_reason);
    fd.budget_ms = 1e5f;
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
    CHECK(s.panels_dropped == 0 && !strstr(s.panels_reason, "dropped"), "a large budget drops nothing: %s",
          s.panels_reason);
    /* Budgets growing by 1.5: both dropped, then frost alone, then nothing; never dispersion alone. */
    {
        unsigned last = SNELL_PANELS_DROPPED_FROST | SNELL_PANELS_DROPPED_DISPERSION;
        int frost_alone = 0, order = 1;
        for (fd.budget_ms = 1e-3f; fd.budget_ms < 1e3f; fd.budget_ms *= 1.5f) {
            CHECK_OK_CTX(g_ctx, snell_render(r, &fd, &s));
            order &= (s.panels_dropped & ~last) == 0 && s.panels_dropped != SNELL_PANELS_DROPPED_DISPERSION;
            frost_alone |= s.panels_dropped == SNELL_PANELS_DROPPED_FROST;
            last = s.panels_dropped;
        }
        CHECK(order && frost_alone && last == 0, "frost goes first, then dispersion (%d, %d, %u)", order, frost_alone,
              last);
    }
    glDeleteTextures(1, &ramp);
}

/* A picture to look at (test_out panels.png, 4 x the frame): two panels
 * merging, a frosted one and a dispersive superellipse over stripes. */
static void picture(void)
{
    enum { S = 4 };
    static uint8_t px[4 * N * S * S];
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    snell_panel p[4];
    GLuint tex;
    int i, j, k;
    for (j = 0; j < H * S; j++)
        for (i = 0; i < W * S; i++) texel(PICTURE, i / S, j / S, px + 4 * ((size_t)j * W * S + i));
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W * S, H * S, 0, GL_RGBA, GL_UNSIGNED_BYTE, px);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glBindTexture(GL_TEXTURE_2D, 0);
    memset(&rd, 0, sizeof rd);
    rd.width = W * S, rd.height = H * S;
    CHECK_OK_CTX(g_ctx, snell_renderer_create(g_ctx, &rd, &r));
    p[0] = panel(96, 144, 120, 120, 60, 24), p[1] = panel(200, 152, 144, 88, 44, 24);
    p[0].group = p[1].group = 1;
    p[2] = panel(312, 160, 112, 136, 24, 24), p[2].frost = 6.0f;
    p[2].tint[0] = p[2].tint[1] = p[2].tint[2] = 1.0f, p[2].tint[3] = 0.15f;
    p[3] = panel(192, 48, 320, 64, 32, 32), p[3].dispersion = 2.0f, p[3].exponent = 4.0f;
    for (k = 0; k < 4; k++) p[k].rim = 0.0f, memset(p[k].shadow, 0, sizeof p[k].shadow), p[k].thickness = 0.0f;
    if (r) {
        CHECK_OK_CTX(g_ctx, draw(r, p, 4, tex, NULL, NULL));
        CHECK_OK_CTX(g_ctx, snell_renderer_read_rgba(r, px));
        if (snell_build_has("png")) snell_write_png(test_out("panels.png"), W * S, H * S, px);
    }
    snell_renderer_destroy(r);
    glDeleteTextures(1, &tex);
}

int main(void)
{
    snell_ctx_desc d;
    snell_renderer *r;
    if (!test_host_context(&g_dpy, &g_egl)) SKIP("cannot make a host context here");
    memset(&d, 0, sizeof d);
    d.backend = SNELL_BACKEND_EXTERNAL;
    d.allocator.alloc = count_alloc, d.allocator.realloc = count_realloc, d.allocator.free = count_free;
    CHECK_OK(snell_ctx_create(&d, &g_ctx));
    if (!g_ctx) return test_finish();
    r = offscreen(SNELL_OUTPUT_COLOR);
    if (r) {
        check_model(r);
        check_frost(r);
        check_scene(r);
        check_external(r);
        check_hostile(r);
        check_budget(r);
    }
    check_bound();
    check_resolves();
    picture();
    snell_renderer_destroy(r);
    snell_ctx_destroy(g_ctx);
    return test_finish();
}
