/* SPDX-License-Identifier: MIT */
/* test_ref_panels — snell_ref_panels (src/ref/ref_panels.c) against values
 * this test derives itself from snell_panels.h's model: the flat interior,
 * a ray through a circular bevel (Snell's law in angles), dispersion, the
 * shadow's profile, a smooth union's field, frost as a Gaussian, mirror
 * symmetry; and hostile input refused or drawn in bounded time. No GL. */
#include "test_util.h"
#include "snell/snell_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 64

static uint8_t under[W * H * 4], out[W * H * 4];

/* A panel with nothing but what the case asks for: no rim, no shadow. */
static snell_panel plain(float cx, float cy, float w, float h)
{
    snell_panel p;
    memset(&p, 0, sizeof p);
    p.center[0] = cx, p.center[1] = cy, p.size[0] = w, p.size[1] = h;
    p.rim = -1.0f;
    p.shadow[0] = -1.0f;
    return p;
}

/* Each channel of texel x: a + b x (bilinear reproduces it exactly inside). */
static void fill_ramp(double a, double b)
{
    int x, y, c;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            for (c = 0; c < 3; c++) under[4 * (y * W + x) + c] = (uint8_t)(a + b * x);
            under[4 * (y * W + x) + 3] = 255;
        }
}

static void fill_const(int v)
{
    int i;
    for (i = 0; i < W * H; i++) under[4 * i] = under[4 * i + 1] = under[4 * i + 2] = (uint8_t)v, under[4 * i + 3] = 255;
}

static double fresnel(double ci, double n)
{
    double ct = sqrt(1.0 - (1.0 - ci * ci) / (n * n));
    double rs = (ci - n * ct) / (ci + n * ct), rp = (n * ci - ct) / (n * ci + ct);
    return 0.5 * (rs * rs + rp * rp);
}

static int px(int x, int y, int c) { return out[4 * (y * W + x) + c]; }

/* Flat interior: (1 - F0) beneath + F0 rim (l.z)^4 (the mirror direction is +z). */
static void check_flat(void)
{
    snell_panel p = plain(48, 32, 80, 50);
    double f0 = 0.04, lz = 0.70710678 / sqrt(0.25 + 0.25 + 0.70710678 * 0.70710678), spec = pow(lz, 4);
    int x, c, bad = 0;
    p.rim = 2.0f;
    fill_ramp(40, 1.0);
    CHECK_OK(snell_ref_panels(&p, 1, under, W, H, 4, out));
    for (x = 33; x < 64; x++) /* s >= 24, the default bevel, at every sample */
        for (c = 0; c < 3; c++) {
            double want = 255.0 * ((1.0 - f0) * (40 + x) / 255.0 + f0 * 2.0 * spec);
            if (fabs(px(x, 32, c) - want) > 1.0) bad++;
        }
    CHECK(bad == 0, "flat interior: %d channels off (1 - F0) beneath + F0 rim spec", bad);
    CHECK(px(30, 32, 3) == 255, "alpha kept");
}

/* A pixel centre in the left bevel of a circular profile (the edge is
 * straight there, grad d = (-1, 0)): the slope tan(ti) = h'(s), the ray
 * turns by ti - tt towards +x and lands h tan(ti - tt) further on. */
static double bevel_expect(double s, double thick, double bevel, double ior, double x, double a, double b)
{
    double v = 1.0 - s / bevel, h = thick * sqrt(1.0 - v * v), slope = thick / bevel * v / sqrt(1.0 - v * v);
    double ti = atan(slope), tt = asin(sin(ti) / ior), xl = x + h * tan(ti - tt);
    return (1.0 - fresnel(cos(ti), ior)) * (a + b * (xl - 0.5));
}

static void check_bevel(void)
{
    snell_panel p = plain(48, 32, 80, 50); /* left edge at x = 8 */
    const double ior_d = 1.5, disp = 20.0 / 30.0;
    double nr = ior_d + (ior_d - 1.0) * disp / 20.0 * (523655.0 / (656.3 * 656.3) - 1.5168);
    double nb = ior_d + (ior_d - 1.0) * disp / 20.0 * (523655.0 / (486.1 * 486.1) - 1.5168);
    int x, bad = 0, moved = 0;
    p.bevel = 12.0f, p.thickness = 24.0f, p.ior = 1.5f;
    fill_ramp(20, 2.0);
    CHECK_OK(snell_ref_panels(&p, 1, under, W, H, 1, out));
    for (x = 8; x < 20; x++) {
        double want = bevel_expect(x + 0.5 - 8.0, 24, 12, 1.5, x + 0.5, 20, 2.0);
        if (fabs(px(x, 32, 1) - want) > 1.0) {
            printf("  bevel x=%d: %d, want %.2f\n", x, px(x, 32, 1), want);
            bad++;
        }
        if (fabs(want - (20 + 2.0 * x)) > 3.0) moved++;
    }
    CHECK(bad == 0 && moved > 3, "circular bevel: %d pixels off Snell's law (%d moved)", bad, moved);
    /* Dispersion: red and blue at the C and F lines' indices. */
    p.dispersion = (float)disp;
    CHECK_OK(snell_ref_panels(&p, 1, under, W, H, 1, out));
    for (bad = 0, x = 9; x < 20; x++) {
        double r = bevel_expect(x + 0.5 - 8.0, 24, 12, nr, x + 0.5, 20, 2.0);
        double b = bevel_expect(x + 0.5 - 8.0, 24, 12, nb, x + 0.5, 20, 2.0);
        if (fabs(px(x, 32, 0) - r) > 1.0 || fabs(px(x, 32, 2) - b) > 1.0) bad++;
    }
    CHECK(bad == 0, "dispersion: %d pixels off the per-channel indices", bad);
}

/* Below the panel: 200 (1 - o (1 - clamp(d(p - offset) / r, 0, 1))^2),
 * d the distance to the bottom edge (y = 20) of the shape moved by offset. */
static void check_shadow(void)
{
    snell_panel p = plain(48, 40, 60, 40);
    int y, bad = 0;
    p.shadow[0] = 10.0f, p.shadow[1] = 0.5f, p.shadow[2] = 0.0f, p.shadow[3] = -4.0f;
    fill_const(200);
    CHECK_OK(snell_ref_panels(&p, 1, under, W, H, 1, out));
    for (y = 0; y < 20; y++) {
        double d = (20.0 - 4.0) - (y + 0.5), t = d < 0 ? 0 : d / 10.0 > 1 ? 1 : d / 10.0;
        double want = 200.0 * (1.0 - 0.5 * (1.0 - t) * (1.0 - t));
        if (fabs(px(48, y, 0) - want) > 0.6) bad++;
    }
    CHECK(bad == 0 && px(48, 2, 0) == 200 && px(48, 17, 0) == 100, "shadow profile: %d rows off", bad);
    p.shadow[0] = 0.0f; /* a hard edge */
    CHECK_OK(snell_ref_panels(&p, 1, under, W, H, 1, out));
    CHECK(px(48, 16, 0) == 100 && px(48, 19, 0) == 100 && px(48, 15, 0) == 200 && px(10, 30, 0) == 200,
          "hard shadow: %d %d %d %d", px(48, 16, 0), px(48, 19, 0), px(48, 15, 0), px(10, 30, 0));
}

/* Two circles of radius 12 merged with k = 16: the field between them is
 * smin(d1, d2); with tint a = 1 and ior 1 a pixel is the covered share of
 * the tint, so its value is the test's own coverage of smin < 0. */
static double smin(double a, double b, double k)
{
    double h = k - fabs(a - b);
    return (a < b ? a : b) - (h > 0 ? h * h / (4 * k) : 0);
}

static void check_union(void)
{
    snell_panel p[2];
    const double k = 16.0;
    int x, y, bad = 0, i, j, S = 4;
    p[0] = plain(34, 32, 24, 24), p[1] = plain(62, 32, 24, 24);
    for (i = 0; i < 2; i++) {
        p[i].radius[0] = p[i].radius[1] = p[i].radius[2] = p[i].radius[3] = 12.0f;
        p[i].ior = 1.0f, p[i].group = 1, p[i].merge = (float)k;
        p[i].tint[0] = 1.0f, p[i].tint[3] = 1.0f; /* red over grey 100 */
    }
    fill_const(100);
    CHECK_OK(snell_ref_panels(p, 2, under, W, H, S, out));
    for (y = 20; y < 44; y++)
        for (x = 40; x < 56; x++) {
            double cov = 0.0, want;
            for (j = 0; j < S; j++)
                for (i = 0; i < S; i++) {
                    double sx = x + (i + 0.5) / S, sy = y + (j + 0.5) / S;
                    double d1 = hypot(sx - 34, sy - 32) - 12, d2 = hypot(sx - 62, sy - 32) - 12;
                    cov += smin(d1, d2, k) < 0 ? 1.0 : 0.0;
                }
            cov /= S * S;
            want = cov * 255 + (1 - cov) * 100;
            if (fabs(px(x, y, 0) - want) > 0.6 || fabs(px(x, y, 1) - (1 - cov) * 100) > 0.6) bad++;
        }
    CHECK(bad == 0 && px(48, 32, 0) == 255, "union field between two circles: %d pixels off smin", bad);
    p[0].merge = p[1].merge = -1.0f; /* a plain union leaves the gap */
    CHECK_OK(snell_ref_panels(p, 2, under, W, H, S, out));
    CHECK(px(48, 32, 0) == 100, "a plain union: the gap between the circles stays");
}

/* Frost: with ior 1 and no bevel a pixel's centre reads the Gaussian blur
 * (sigma, cut at 3 sigma, clamped edges) of the image; constant stays constant. */
static void check_frost(void)
{
    const double sigma = 2.5;
    snell_panel p = plain(48, 32, 120, 90); /* over the whole image */
    int i, x, y, c, bad = 0, K = (int)floor(3 * sigma);
    srand(7);
    for (i = 0; i < W * H * 4; i++) under[i] = (uint8_t)(rand() & 255);
    p.ior = 1.0f, p.bevel = -1.0f, p.frost = (float)sigma;
    CHECK_OK(snell_ref_panels(&p, 1, under, W, H, 1, out));
    for (y = 0; y < H; y += 7)
        for (x = 0; x < W; x += 5)
            for (c = 0; c < 3; c++) {
                double v = 0, wsum = 0;
                int a, b;
                for (b = -K; b <= K; b++)
                    for (a = -K; a <= K; a++) {
                        int xs = x + a < 0 ? 0 : x + a >= W ? W - 1 : x + a;
                        int ys = y + b < 0 ? 0 : y + b >= H ? H - 1 : y + b;
                        double w = exp(-(a * a + b * b) / (2 * sigma * sigma));
                        v += w * under[4 * (ys * W + xs) + c], wsum += w;
                    }
                if (fabs(px(x, y, c) - v / wsum) > 0.6) bad++;
            }
    CHECK(bad == 0, "frost: %d channels off the Gaussian", bad);
    fill_const(123);
    p = plain(48, 32, 400, 400); /* its bevel off the image: flat glass, (1 - F0) 123 */
    p.frost = 9.0f;
    CHECK_OK(snell_ref_panels(&p, 1, under, W, H, 2, out));
    for (bad = 0, i = 0; i < W * H; i++)
        if (abs(out[4 * i] - 118) > 0) bad++;
    CHECK(bad == 0, "frost of a constant image is (1 - F0) of it: %d pixels differ", bad);
}

/* A circle centred on a mirror-symmetric image, light from straight above:
 * the result is mirror-symmetric in x and y. */
static void check_symmetry(void)
{
    snell_panel p = plain(48, 32, 50, 50);
    int x, y, c, bad = 0;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int dx = x < W / 2 ? W / 2 - 1 - x : x - W / 2, dy = y < H / 2 ? H / 2 - 1 - y : y - H / 2;
            under[4 * (y * W + x)] = (uint8_t)(dx * 5), under[4 * (y * W + x) + 1] = (uint8_t)(dy * 7);
            under[4 * (y * W + x) + 2] = (uint8_t)(((dx / 4 + dy / 4) & 1) * 200), under[4 * (y * W + x) + 3] = 255;
        }
    p.radius[0] = p.radius[1] = p.radius[2] = p.radius[3] = 25.0f;
    p.thickness = 14.0f, p.dispersion = 1.0f, p.rim = 3.0f, p.light[2] = 1.0f;
    p.shadow[0] = 8.0f, p.shadow[1] = 0.3f, p.shadow[2] = 0.0f, p.shadow[3] = 0.0f;
    CHECK_OK(snell_ref_panels(&p, 1, under, W, H, 3, out));
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++)
            for (c = 0; c < 3; c++)
                if (abs(px(x, y, c) - px(W - 1 - x, y, c)) > 1 || abs(px(x, y, c) - px(x, H - 1 - y, c)) > 1) bad++;
    CHECK(bad == 0 && memcmp(out, under, sizeof out) != 0, "mirror symmetry: %d channels differ", bad);
}

/* A superelliptic corner (n = 4): the test's own field, its gradient by a
 * central difference, the vector form of Snell's law; red ramps in x and
 * green in y, so both components of the landing point show. */
static double corner_field(double x, double y)
{
    double qx = fabs(x - 48) - (40 - 20), qy = fabs(y - 32) - (28 - 20);
    double mx = qx > 0 ? qx : 0, my = qy > 0 ? qy : 0, in = qx > qy ? qx : qy;
    return pow(pow(mx, 4) + pow(my, 4), 0.25) + (in < 0 ? in : 0) - 20;
}

static void check_corner(void)
{
    snell_panel p = plain(48, 32, 80, 56);
    int x, y, k, bad = 0, n = 0;
    p.exponent = 4.0f, p.bevel = 16.0f, p.thickness = 24.0f;
    for (k = 0; k < 4; k++) p.radius[k] = 20.0f;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            uint8_t *t = under + 4 * (y * W + x);
            t[0] = (uint8_t)(20 + 2 * x), t[1] = (uint8_t)(20 + 3 * y), t[2] = 0, t[3] = 255;
        }
    CHECK_OK(snell_ref_panels(&p, 1, under, W, H, 1, out));
    for (y = 44; y < 60; y++)
        for (x = 70; x < 88; x++) {
            double px_ = x + 0.5, py_ = y + 0.5, d = corner_field(px_, py_), e = 1e-5, g[2], v, h, slope, nn[3];
            double len, c, eta = 1 / 1.5, k2, tt[3], xl, yl, F;
            if (!(d < -0.05 && d > -15.95)) continue; /* in the bevel */
            g[0] = (corner_field(px_ + e, py_) - corner_field(px_ - e, py_)) / (2 * e);
            g[1] = (corner_field(px_, py_ + e) - corner_field(px_, py_ - e)) / (2 * e);
            v = 1 + d / 16, h = 24 * sqrt(1 - v * v), slope = 24.0 / 16 * v / sqrt(1 - v * v);
            nn[0] = slope * g[0], nn[1] = slope * g[1], nn[2] = 1;
            len = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + 1);
            nn[0] /= len, nn[1] /= len, nn[2] /= len;
            c = nn[2], k2 = 1 - eta * eta * (1 - c * c);
            tt[0] = (eta * c - sqrt(k2)) * nn[0], tt[1] = (eta * c - sqrt(k2)) * nn[1];
            tt[2] = -eta + (eta * c - sqrt(k2)) * nn[2];
            xl = px_ + h * tt[0] / -tt[2], yl = py_ + h * tt[1] / -tt[2];
            F = fresnel(c, 1.5);
            if (xl > W - 1 || yl > H - 1) continue; /* past the ramp's clamped edge */
            n++;
            if (fabs(px(x, y, 0) - (1 - F) * (20 + 2 * (xl - 0.5))) > 1.0 ||
                fabs(px(x, y, 1) - (1 - F) * (20 + 3 * (yl - 0.5))) > 1.0)
                bad++;
        }
    CHECK(n > 40 && bad == 0, "superelliptic corner: %d of %d bevel pixels off the field's gradient", bad, n);
}

/* Panels in order: the second reads the first's result where they overlap. */
static void check_order(void)
{
    snell_panel p[2];
    p[0] = plain(30, 32, 40, 40), p[1] = plain(60, 32, 40, 40);
    p[0].ior = p[1].ior = 1.0f;
    p[0].tint[0] = 1.0f, p[0].tint[3] = 1.0f;              /* red */
    p[1].tint[2] = 1.0f, p[1].tint[3] = 0.5f;              /* half blue */
    fill_const(100);
    CHECK_OK(snell_ref_panels(p, 2, under, W, H, 1, out));
    CHECK(px(45, 32, 0) == 128 && px(45, 32, 2) == 128 && px(70, 32, 0) == 50 && px(20, 32, 0) == 255,
          "the later panel over the earlier one's result: %d %d, %d, %d", px(45, 32, 0), px(45, 32, 2),
          px(70, 32, 0), px(20, 32, 0));
}

static void refused(const char *what, snell_status st, const char *needle)
{
    CHECK(st == SNELL_E_INVALID_ARG && strstr(snell_last_error(NULL), needle), "%s: %s \"%s\"", what,
          snell_status_str(st), snell_last_error(NULL));
}

static void check_hostile(void)
{
    static snell_panel many[1000];
    snell_panel p = plain(48, 32, 40, 30), bad;
    int i;
    fill_ramp(10, 2.0);
    refused("NULL under", snell_ref_panels(&p, 1, NULL, W, H, 1, out), "under");
    refused("NULL out", snell_ref_panels(&p, 1, under, W, H, 1, NULL), "out");
    refused("width 0", snell_ref_panels(&p, 1, under, 0, H, 1, out), "width");
    refused("height 16385", snell_ref_panels(&p, 1, under, W, 16385, 1, out), "height");
    refused("samples 17", snell_ref_panels(&p, 1, under, W, H, 17, out), "samples");
    refused("samples -1", snell_ref_panels(&p, 1, under, W, H, -1, out), "samples");
    refused("out is under", snell_ref_panels(&p, 1, under, W, H, 1, under), "overlaps");
    refused("count -1", snell_ref_panels(&p, -1, under, W, H, 1, out), "panels");
    refused("count 4097", snell_ref_panels(&p, 4097, under, W, H, 1, out), "panels");
    refused("NULL panels", snell_ref_panels(NULL, 2, under, W, H, 1, out), "panels");
    bad = p, bad.center[0] = NAN;
    refused("NaN centre", snell_ref_panels(&bad, 1, under, W, H, 1, out), "center");
    bad = p, bad.size[1] = 0.0f;
    refused("size 0", snell_ref_panels(&bad, 1, under, W, H, 1, out), "size");
    bad = p, bad.exponent = 1.0f;
    refused("exponent 1", snell_ref_panels(&bad, 1, under, W, H, 1, out), "exponent");
    bad = p, bad.ior = INFINITY;
    refused("ior inf", snell_ref_panels(&bad, 1, under, W, H, 1, out), "ior");
    bad = p, bad.frost = 65.0f;
    refused("frost 65", snell_ref_panels(&bad, 1, under, W, H, 1, out), "frost");
    bad = p, bad.tint[1] = NAN;
    refused("tint NaN", snell_ref_panels(&bad, 1, under, W, H, 1, out), "tint");
    for (i = 0; i < 9; i++) many[i] = p, many[i].group = 3;
    refused("9 in a group", snell_ref_panels(many, 9, under, W, H, 1, out), "group");

    /* Drawn: none, off the frame, larger than it, zero and huge radii, 1,000. */
    CHECK_OK(snell_ref_panels(NULL, 0, under, W, H, 0, out));
    CHECK(memcmp(out, under, sizeof out) == 0, "no panels: the image unchanged");
    bad = p, bad.center[0] = -500.0f;
    CHECK_OK(snell_ref_panels(&bad, 1, under, W, H, 0, out));
    CHECK(memcmp(out, under, sizeof out) == 0, "a panel off the frame changes nothing");
    bad = p, bad.size[0] = 1e6f, bad.size[1] = 1e6f, bad.thickness = 1e6f, bad.radius[0] = 1e9f, bad.frost = 64.0f;
    CHECK_OK(snell_ref_panels(&bad, 1, under, W, H, 1, out));
    bad = p, bad.radius[0] = -1.0f, bad.radius[2] = 1e30f, bad.bevel = 1e5f, bad.exponent = 16.0f;
    CHECK_OK(snell_ref_panels(&bad, 1, under, W, H, 2, out));
    for (i = 0; i < 1000; i++) {
        many[i] = plain((float)(i * 37 % W), (float)(i * 53 % H), 4.0f + i % 20, 3.0f + i % 11);
        many[i].frost = (float)(i % 3), many[i].dispersion = (float)(i % 2), many[i].group = i % 50 ? 0 : 1 + i / 50 % 4;
        many[i].shadow[0] = 0.0f;
    }
    CHECK_OK(snell_ref_panels(many, 1000, under, W, H, 1, out));
    CHECK(memcmp(out, under, sizeof out) != 0, "1,000 panels drawn");
}

int main(void)
{
    check_flat();
    check_bevel();
    check_shadow();
    check_union();
    check_frost();
    check_symmetry();
    check_corner();
    check_order();
    check_hostile();
    return test_finish();
}
