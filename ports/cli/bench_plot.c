/* SPDX-License-Identifier: MIT */
/* bench_plot.c — the time-vs-error scatter plot of snell-bench as a PNG:
 * log-log axes with decade grid and labels, one colour per scene, one marker
 * per method, the Pareto front of each scene+size group ringed and joined by
 * a dashed line, labels placed clear of the points and of each other, and a
 * legend. Text uses an embedded 6x10 bitmap font. */
#include "bench_plot.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* X11 misc-fixed 6x10 (public domain), ASCII 32..126: 10 rows per glyph, bit 7 = left column. */
static const unsigned char g_font6x10[95][10] = {
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /*   */
    {0x00, 0x20, 0x20, 0x20, 0x20, 0x20, 0x00, 0x20, 0x00, 0x00}, /* ! */
    {0x00, 0x50, 0x50, 0x50, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* " */
    {0x00, 0x50, 0x50, 0xf8, 0x50, 0xf8, 0x50, 0x50, 0x00, 0x00}, /* # */
    {0x00, 0x20, 0x70, 0xa0, 0x70, 0x28, 0x70, 0x20, 0x00, 0x00}, /* $ */
    {0x00, 0x48, 0xa8, 0x50, 0x20, 0x50, 0xa8, 0x90, 0x00, 0x00}, /* % */
    {0x00, 0x40, 0xa0, 0xa0, 0x40, 0xa8, 0x90, 0x68, 0x00, 0x00}, /* & */
    {0x00, 0x20, 0x20, 0x20, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* ' */
    {0x00, 0x10, 0x20, 0x40, 0x40, 0x40, 0x20, 0x10, 0x00, 0x00}, /* ( */
    {0x00, 0x40, 0x20, 0x10, 0x10, 0x10, 0x20, 0x40, 0x00, 0x00}, /* ) */
    {0x00, 0x00, 0x88, 0x50, 0xf8, 0x50, 0x88, 0x00, 0x00, 0x00}, /*   */
    {0x00, 0x00, 0x20, 0x20, 0xf8, 0x20, 0x20, 0x00, 0x00, 0x00}, /* + */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x30, 0x20, 0x40, 0x00}, /* , */
    {0x00, 0x00, 0x00, 0x00, 0xf8, 0x00, 0x00, 0x00, 0x00, 0x00}, /* - */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x20, 0x70, 0x20, 0x00}, /* . */
    {0x00, 0x08, 0x08, 0x10, 0x20, 0x40, 0x80, 0x80, 0x00, 0x00}, /*   */
    {0x00, 0x20, 0x50, 0x88, 0x88, 0x88, 0x50, 0x20, 0x00, 0x00}, /* 0 */
    {0x00, 0x20, 0x60, 0xa0, 0x20, 0x20, 0x20, 0xf8, 0x00, 0x00}, /* 1 */
    {0x00, 0x70, 0x88, 0x08, 0x30, 0x40, 0x80, 0xf8, 0x00, 0x00}, /* 2 */
    {0x00, 0xf8, 0x08, 0x10, 0x30, 0x08, 0x88, 0x70, 0x00, 0x00}, /* 3 */
    {0x00, 0x10, 0x30, 0x50, 0x90, 0xf8, 0x10, 0x10, 0x00, 0x00}, /* 4 */
    {0x00, 0xf8, 0x80, 0xb0, 0xc8, 0x08, 0x88, 0x70, 0x00, 0x00}, /* 5 */
    {0x00, 0x30, 0x40, 0x80, 0xb0, 0xc8, 0x88, 0x70, 0x00, 0x00}, /* 6 */
    {0x00, 0xf8, 0x08, 0x10, 0x10, 0x20, 0x40, 0x40, 0x00, 0x00}, /* 7 */
    {0x00, 0x70, 0x88, 0x88, 0x70, 0x88, 0x88, 0x70, 0x00, 0x00}, /* 8 */
    {0x00, 0x70, 0x88, 0x98, 0x68, 0x08, 0x10, 0x60, 0x00, 0x00}, /* 9 */
    {0x00, 0x00, 0x20, 0x70, 0x20, 0x00, 0x20, 0x70, 0x20, 0x00}, /* : */
    {0x00, 0x00, 0x20, 0x70, 0x20, 0x00, 0x30, 0x20, 0x40, 0x00}, /* ; */
    {0x00, 0x08, 0x10, 0x20, 0x40, 0x20, 0x10, 0x08, 0x00, 0x00}, /* < */
    {0x00, 0x00, 0x00, 0xf8, 0x00, 0xf8, 0x00, 0x00, 0x00, 0x00}, /* = */
    {0x00, 0x40, 0x20, 0x10, 0x08, 0x10, 0x20, 0x40, 0x00, 0x00}, /* > */
    {0x00, 0x70, 0x88, 0x10, 0x20, 0x20, 0x00, 0x20, 0x00, 0x00}, /* ? */
    {0x00, 0x70, 0x88, 0x98, 0xa8, 0xb0, 0x80, 0x70, 0x00, 0x00}, /* @ */
    {0x00, 0x20, 0x50, 0x88, 0x88, 0xf8, 0x88, 0x88, 0x00, 0x00}, /* A */
    {0x00, 0xf0, 0x48, 0x48, 0x70, 0x48, 0x48, 0xf0, 0x00, 0x00}, /* B */
    {0x00, 0x70, 0x88, 0x80, 0x80, 0x80, 0x88, 0x70, 0x00, 0x00}, /* C */
    {0x00, 0xf0, 0x48, 0x48, 0x48, 0x48, 0x48, 0xf0, 0x00, 0x00}, /* D */
    {0x00, 0xf8, 0x80, 0x80, 0xf0, 0x80, 0x80, 0xf8, 0x00, 0x00}, /* E */
    {0x00, 0xf8, 0x80, 0x80, 0xf0, 0x80, 0x80, 0x80, 0x00, 0x00}, /* F */
    {0x00, 0x70, 0x88, 0x80, 0x80, 0x98, 0x88, 0x70, 0x00, 0x00}, /* G */
    {0x00, 0x88, 0x88, 0x88, 0xf8, 0x88, 0x88, 0x88, 0x00, 0x00}, /* H */
    {0x00, 0x70, 0x20, 0x20, 0x20, 0x20, 0x20, 0x70, 0x00, 0x00}, /* I */
    {0x00, 0x38, 0x10, 0x10, 0x10, 0x10, 0x90, 0x60, 0x00, 0x00}, /* J */
    {0x00, 0x88, 0x90, 0xa0, 0xc0, 0xa0, 0x90, 0x88, 0x00, 0x00}, /* K */
    {0x00, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0xf8, 0x00, 0x00}, /* L */
    {0x00, 0x88, 0x88, 0xd8, 0xa8, 0x88, 0x88, 0x88, 0x00, 0x00}, /* M */
    {0x00, 0x88, 0x88, 0xc8, 0xa8, 0x98, 0x88, 0x88, 0x00, 0x00}, /* N */
    {0x00, 0x70, 0x88, 0x88, 0x88, 0x88, 0x88, 0x70, 0x00, 0x00}, /* O */
    {0x00, 0xf0, 0x88, 0x88, 0xf0, 0x80, 0x80, 0x80, 0x00, 0x00}, /* P */
    {0x00, 0x70, 0x88, 0x88, 0x88, 0x88, 0xa8, 0x70, 0x08, 0x00}, /* Q */
    {0x00, 0xf0, 0x88, 0x88, 0xf0, 0xa0, 0x90, 0x88, 0x00, 0x00}, /* R */
    {0x00, 0x70, 0x88, 0x80, 0x70, 0x08, 0x88, 0x70, 0x00, 0x00}, /* S */
    {0x00, 0xf8, 0x20, 0x20, 0x20, 0x20, 0x20, 0x20, 0x00, 0x00}, /* T */
    {0x00, 0x88, 0x88, 0x88, 0x88, 0x88, 0x88, 0x70, 0x00, 0x00}, /* U */
    {0x00, 0x88, 0x88, 0x88, 0x50, 0x50, 0x50, 0x20, 0x00, 0x00}, /* V */
    {0x00, 0x88, 0x88, 0x88, 0xa8, 0xa8, 0xd8, 0x88, 0x00, 0x00}, /* W */
    {0x00, 0x88, 0x88, 0x50, 0x20, 0x50, 0x88, 0x88, 0x00, 0x00}, /* X */
    {0x00, 0x88, 0x88, 0x50, 0x20, 0x20, 0x20, 0x20, 0x00, 0x00}, /* Y */
    {0x00, 0xf8, 0x08, 0x10, 0x20, 0x40, 0x80, 0xf8, 0x00, 0x00}, /* Z */
    {0x00, 0x70, 0x40, 0x40, 0x40, 0x40, 0x40, 0x70, 0x00, 0x00}, /* [ */
    {0x00, 0x80, 0x80, 0x40, 0x20, 0x10, 0x08, 0x08, 0x00, 0x00}, /* \\ */
    {0x00, 0x70, 0x10, 0x10, 0x10, 0x10, 0x10, 0x70, 0x00, 0x00}, /* ] */
    {0x00, 0x20, 0x50, 0x88, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* ^ */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf8, 0x00}, /* _ */
    {0x20, 0x10, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* ` */
    {0x00, 0x00, 0x00, 0x70, 0x08, 0x78, 0x88, 0x78, 0x00, 0x00}, /* a */
    {0x00, 0x80, 0x80, 0xb0, 0xc8, 0x88, 0xc8, 0xb0, 0x00, 0x00}, /* b */
    {0x00, 0x00, 0x00, 0x70, 0x88, 0x80, 0x88, 0x70, 0x00, 0x00}, /* c */
    {0x00, 0x08, 0x08, 0x68, 0x98, 0x88, 0x98, 0x68, 0x00, 0x00}, /* d */
    {0x00, 0x00, 0x00, 0x70, 0x88, 0xf8, 0x80, 0x70, 0x00, 0x00}, /* e */
    {0x00, 0x30, 0x48, 0x40, 0xf0, 0x40, 0x40, 0x40, 0x00, 0x00}, /* f */
    {0x00, 0x00, 0x00, 0x78, 0x88, 0x88, 0x78, 0x08, 0x88, 0x70}, /* g */
    {0x00, 0x80, 0x80, 0xb0, 0xc8, 0x88, 0x88, 0x88, 0x00, 0x00}, /* h */
    {0x00, 0x20, 0x00, 0x60, 0x20, 0x20, 0x20, 0x70, 0x00, 0x00}, /* i */
    {0x00, 0x08, 0x00, 0x18, 0x08, 0x08, 0x08, 0x48, 0x48, 0x30}, /* j */
    {0x00, 0x80, 0x80, 0x88, 0x90, 0xe0, 0x90, 0x88, 0x00, 0x00}, /* k */
    {0x00, 0x60, 0x20, 0x20, 0x20, 0x20, 0x20, 0x70, 0x00, 0x00}, /* l */
    {0x00, 0x00, 0x00, 0xd0, 0xa8, 0xa8, 0xa8, 0x88, 0x00, 0x00}, /* m */
    {0x00, 0x00, 0x00, 0xb0, 0xc8, 0x88, 0x88, 0x88, 0x00, 0x00}, /* n */
    {0x00, 0x00, 0x00, 0x70, 0x88, 0x88, 0x88, 0x70, 0x00, 0x00}, /* o */
    {0x00, 0x00, 0x00, 0xb0, 0xc8, 0x88, 0xc8, 0xb0, 0x80, 0x80}, /* p */
    {0x00, 0x00, 0x00, 0x68, 0x98, 0x88, 0x98, 0x68, 0x08, 0x08}, /* q */
    {0x00, 0x00, 0x00, 0xb0, 0xc8, 0x80, 0x80, 0x80, 0x00, 0x00}, /* r */
    {0x00, 0x00, 0x00, 0x70, 0x80, 0x70, 0x08, 0xf0, 0x00, 0x00}, /* s */
    {0x00, 0x40, 0x40, 0xf0, 0x40, 0x40, 0x48, 0x30, 0x00, 0x00}, /* t */
    {0x00, 0x00, 0x00, 0x88, 0x88, 0x88, 0x98, 0x68, 0x00, 0x00}, /* u */
    {0x00, 0x00, 0x00, 0x88, 0x88, 0x50, 0x50, 0x20, 0x00, 0x00}, /* v */
    {0x00, 0x00, 0x00, 0x88, 0x88, 0xa8, 0xa8, 0x50, 0x00, 0x00}, /* w */
    {0x00, 0x00, 0x00, 0x88, 0x50, 0x20, 0x50, 0x88, 0x00, 0x00}, /* x */
    {0x00, 0x00, 0x00, 0x88, 0x88, 0x98, 0x68, 0x08, 0x88, 0x70}, /* y */
    {0x00, 0x00, 0x00, 0xf8, 0x10, 0x20, 0x40, 0xf8, 0x00, 0x00}, /* z */
    {0x00, 0x18, 0x20, 0x10, 0x60, 0x10, 0x20, 0x18, 0x00, 0x00}, /* { */
    {0x00, 0x20, 0x20, 0x20, 0x20, 0x20, 0x20, 0x20, 0x00, 0x00}, /* | */
    {0x00, 0x60, 0x10, 0x20, 0x18, 0x20, 0x10, 0x60, 0x00, 0x00}, /* } */
    {0x00, 0x48, 0xa8, 0x90, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* ~ */
};

#define PW 1040
#define PH 680
#define LEFT 92
#define RIGHT (PW - 250)
#define TOP 64
#define BOTTOM (PH - 70)

typedef struct canvas {
    uint8_t *px;
} canvas;

/* Okabe-Ito palette (colour-blind safe), without its yellow (poor on white). */
static const uint8_t g_palette[][3] = {{0, 114, 178},  {213, 94, 0},   {0, 158, 115}, {204, 121, 167},
                                       {230, 159, 0},  {86, 180, 233}, {0, 0, 0},     {120, 120, 120}};
#define PALETTE_N ((int)(sizeof g_palette / sizeof *g_palette))

static void put(canvas *c, int x, int y, const uint8_t rgb[3])
{
    uint8_t *p;
    if (x < 0 || y < 0 || x >= PW || y >= PH) return;
    p = c->px + 4 * ((size_t)y * PW + (size_t)x);
    p[0] = rgb[0];
    p[1] = rgb[1];
    p[2] = rgb[2];
    p[3] = 255;
}

static void fill_rect(canvas *c, int x0, int y0, int x1, int y1, const uint8_t rgb[3])
{
    int x, y;
    for (y = y0; y <= y1; y++)
        for (x = x0; x <= x1; x++) put(c, x, y, rgb);
}

/* Bresenham; dash > 0 draws dash pixels on, dash off. */
static void line(canvas *c, int x0, int y0, int x1, int y1, const uint8_t rgb[3], int width, int dash)
{
    int dx, dy, sx, sy, err, n = 0;
    /* Everything drawn lies on the canvas; refuse absurd coordinates. */
    if (abs(x0) > 4 * PW || abs(x1) > 4 * PW || abs(y0) > 4 * PH || abs(y1) > 4 * PH) return;
    dx = abs(x1 - x0), dy = -abs(y1 - y0), sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1, err = dx + dy;
    for (;;) {
        int e2 = 2 * err; /* taken once per step, before either update */
        if (!dash || (n / dash) % 2 == 0) fill_rect(c, x0 - width / 2, y0 - width / 2, x0 + (width - 1) / 2,
                                                   y0 + (width - 1) / 2, rgb);
        n++;
        if (x0 == x1 && y0 == y1) break;
        if (e2 >= dy) { err += dy; x0 += sx; }
        if (e2 <= dx) { err += dx; y0 += sy; }
    }
}

/* Text with its top-left corner at (x, y); vertical = rotated 90 degrees
 * counter-clockwise (reads bottom to top), (x, y) then the bottom-left. */
static int text(canvas *c, int x, int y, const char *s, const uint8_t rgb[3], int scale, int vertical)
{
    int n = 0;
    for (; *s; s++, n++) {
        int ch = (unsigned char)*s, r, b, i, j;
        if (ch < 32 || ch > 126) ch = '?';
        for (r = 0; r < 10; r++)
            for (b = 0; b < 6; b++)
                if (g_font6x10[ch - 32][r] & (0x80 >> b))
                    for (i = 0; i < scale; i++)
                        for (j = 0; j < scale; j++) {
                            int gx = (n * 6 + b) * scale + i, gy = r * scale + j;
                            if (vertical) put(c, x + gy, y - gx, rgb);
                            else put(c, x + gx, y + gy, rgb);
                        }
    }
    return n * 6 * scale;
}

static void marker(canvas *c, int cx, int cy, int kind, const uint8_t rgb[3], int r)
{
    int x, y;
    for (y = -r; y <= r; y++)
        for (x = -r; x <= r; x++) {
            int in;
            /* eight shapes, one per registry method up to eight (a sixth
             * method once took the circle of the first) */
            switch (kind % 8) {
            case 0: in = x * x + y * y <= r * r + r / 2; break;
            case 1: in = 1; break;
            case 2: in = y >= -r && 2 * abs(x) <= y + r; break;
            case 3: in = abs(x) + abs(y) <= r; break;
            case 4: in = abs(x - y) <= 1 || abs(x + y) <= 1; break;
            case 5: in = x * x + y * y <= r * r + r / 2 && x * x + y * y >= (r - 2) * (r - 2); break; /* ring */
            case 6: in = abs(x) >= r - 1 || abs(y) >= r - 1; break;                                  /* box */
            default: in = y <= r && 2 * abs(x) <= r - y; break;                                       /* down */
            }
            if (in) put(c, cx + x, cy + y, rgb);
        }
}

static void ring(canvas *c, int cx, int cy, int r, const uint8_t rgb[3])
{
    int x, y;
    for (y = -r - 1; y <= r + 1; y++)
        for (x = -r - 1; x <= r + 1; x++) {
            double d = sqrt((double)(x * x + y * y));
            if (fabs(d - r) < 0.8) put(c, cx + x, cy + y, rgb);
        }
}

void bench_pareto(const bench_plot_point *p, int n, int *pareto)
{
    int i, j;
    for (i = 0; i < n; i++) {
        pareto[i] = isfinite(p[i].x) && isfinite(p[i].y);
        for (j = 0; j < n && pareto[i]; j++)
            if (j != i && p[j].group == p[i].group && isfinite(p[j].x) && isfinite(p[j].y) && p[j].x <= p[i].x &&
                p[j].y <= p[i].y && (p[j].x < p[i].x || p[j].y < p[i].y))
                pareto[i] = 0;
    }
}

static void decade_label(char *buf, size_t n, int k)
{
    if (k >= -3 && k <= 4) snprintf(buf, n, "%g", pow(10.0, k));
    else snprintf(buf, n, "1e%d", k);
}

typedef struct axis {
    int lo, hi; /* decades */
} axis;

static axis make_axis(double vmin, double vmax)
{
    axis a;
    a.lo = (int)floor(log10(vmin) + 1e-9);
    a.hi = (int)ceil(log10(vmax) - 1e-9);
    if (a.hi <= a.lo) a.hi = a.lo + 1;
    return a;
}

static int map_x(const axis *a, double v) { return LEFT + (int)lround((log10(v) - a->lo) / (a->hi - a->lo) * (RIGHT - LEFT)); }
static int map_y(const axis *a, double v) { return BOTTOM - (int)lround((log10(v) - a->lo) / (a->hi - a->lo) * (BOTTOM - TOP)); }

typedef struct point_px {
    int x, y; /* INT_MIN: not drawn */
} point_px;

typedef struct box {
    int x0, y0, x1, y1;
} box;

static int overlaps(const box *a, const box *b) { return a->x0 <= b->x1 && b->x0 <= a->x1 && a->y0 <= b->y1 && b->y0 <= a->y1; }

/* Draws each point's label where it covers no marker and no label placed
 * before it: beside the point (right, left, above, below, then right or left
 * one and two lines up or down), else in the nearest free line to its right
 * or left; anywhere but right of it, a thin line joins it to its point. If
 * nothing is free, on its right. Labels inside the plot area only. */
static void place_labels(canvas *c, const bench_plot_desc *d, const point_px *pos, const uint8_t rgb[3])
{
    static const uint8_t light[3] = {160, 160, 160};
    static const int beside[][2] = {{12, -4}, {-12, -4}, {0, -20}, {0, 12}, {12, -16}, {12, 8}, {-12, -16},
                                    {-12, 8}, {12, -28}, {12, 20}, {-12, -28}, {-12, 20}};
    box *placed = (box *)malloc(sizeof(box) * (size_t)(d->count > 0 ? d->count : 1));
    int i, j, k, n = 0;
    for (i = 0; i < d->count; i++) {
        const char *label = d->points[i].label;
        int w, found = 0, lead = 0, tries = (int)(sizeof beside / sizeof *beside) + 2 * 24;
        box b;
        if (!label || pos[i].x == INT_MIN) continue;
        w = (int)strlen(label) * 6;
        for (k = 0; k < tries && !found; k++) {
            int dx, dy;
            if (k < (int)(sizeof beside / sizeof *beside)) {
                dx = beside[k][0];
                dy = beside[k][1];
            } else { /* further lines away, alternating down and up, right then left */
                int step = (k - (int)(sizeof beside / sizeof *beside)) / 2 / 2 + 3, up = (k / 2) % 2;
                dx = k % 2 ? -24 : 24;
                dy = -4 + (up ? -12 : 12) * step;
            }
            b.x0 = dx < 0 ? pos[i].x + dx - w : dx == 0 ? pos[i].x - w / 2 : pos[i].x + dx;
            b.y0 = pos[i].y + dy;
            b.x1 = b.x0 + w;
            b.y1 = b.y0 + 10;
            found = b.x0 > LEFT + 2 && b.x1 < RIGHT - 2 && b.y0 > TOP + 2 && b.y1 < BOTTOM - 2;
            for (j = 0; found && j < d->count; j++) { /* every marker with its ring */
                box m = {pos[j].x - 10, pos[j].y - 10, pos[j].x + 10, pos[j].y + 10};
                if (pos[j].x != INT_MIN && overlaps(&b, &m)) found = 0;
            }
            for (j = 0; found && placed && j < n; j++)
                if (overlaps(&b, &placed[j])) found = 0;
            lead = k > 0; /* anywhere but the usual place: a line says whose label it is */
        }
        if (!found) {
            b.x0 = pos[i].x + 12;
            b.y0 = pos[i].y - 4;
            b.x1 = b.x0 + w;
            b.y1 = b.y0 + 10;
            lead = 0;
        }
        if (lead) {
            int lx = b.x1 < pos[i].x ? b.x1 + 2 : b.x0 > pos[i].x ? b.x0 - 2 : pos[i].x;
            int ly = lx == pos[i].x ? (b.y0 > pos[i].y ? b.y0 - 1 : b.y1 + 1) : b.y0 + 5;
            line(c, pos[i].x, pos[i].y, lx, ly, light, 1, 0);
        }
        text(c, b.x0, b.y0, label, rgb, 1, 0);
        if (placed) placed[n++] = b;
    }
    free(placed);
}

snell_status bench_plot_write(const char *path, const bench_plot_desc *d)
{
    static const uint8_t white[3] = {255, 255, 255}, black[3] = {0, 0, 0}, grid[3] = {205, 205, 205},
                         minor[3] = {236, 236, 236}, grey[3] = {90, 90, 90};
    canvas c;
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    int i, k, m, clamped = 0, *pareto;
    point_px *pos;
    axis ax, ay;
    char buf[128];
    snell_status st;
    c.px = (uint8_t *)malloc((size_t)PW * PH * 4);
    pareto = (int *)calloc((size_t)(d->count > 0 ? d->count : 1), sizeof *pareto);
    pos = (point_px *)calloc((size_t)(d->count > 0 ? d->count : 1), sizeof *pos);
    if (!c.px || !pareto || !pos) {
        free(c.px);
        free(pareto);
        free(pos);
        return SNELL_E_NOMEM;
    }
    fill_rect(&c, 0, 0, PW - 1, PH - 1, white);
    for (i = 0; i < d->count; i++) {
        const bench_plot_point *p = &d->points[i];
        if (!(p->x > 0.0) || !isfinite(p->x)) continue;
        if (p->x < xmin) xmin = p->x;
        if (p->x > xmax) xmax = p->x;
        if (p->y > 0.0 && isfinite(p->y)) {
            if (p->y < ymin) ymin = p->y;
            if (p->y > ymax) ymax = p->y;
        }
    }
    if (!(xmin <= xmax)) xmin = 1.0, xmax = 10.0;
    if (!(ymin <= ymax)) ymin = 1e-3, ymax = 1.0;
    ax = make_axis(xmin, xmax);
    ay = make_axis(ymin, ymax);

    /* grid: decades and their 2..9 subdivisions */
    for (k = ax.lo; k < ax.hi; k++)
        for (m = 2; m <= 9; m++) {
            int x = map_x(&ax, m * pow(10.0, k));
            line(&c, x, TOP, x, BOTTOM, minor, 1, 0);
        }
    for (k = ay.lo; k < ay.hi; k++)
        for (m = 2; m <= 9; m++) {
            int y = map_y(&ay, m * pow(10.0, k));
            line(&c, LEFT, y, RIGHT, y, minor, 1, 0);
        }
    for (k = ax.lo; k <= ax.hi; k++) {
        int x = map_x(&ax, pow(10.0, k)), w;
        line(&c, x, TOP, x, BOTTOM, grid, 1, 0);
        line(&c, x, BOTTOM, x, BOTTOM + 5, black, 1, 0);
        decade_label(buf, sizeof buf, k);
        w = (int)strlen(buf) * 6;
        text(&c, x - w / 2, BOTTOM + 9, buf, black, 1, 0);
    }
    for (k = ay.lo; k <= ay.hi; k++) {
        int y = map_y(&ay, pow(10.0, k)), w;
        line(&c, LEFT, y, RIGHT, y, grid, 1, 0);
        line(&c, LEFT - 5, y, LEFT, y, black, 1, 0);
        decade_label(buf, sizeof buf, k);
        w = (int)strlen(buf) * 6;
        text(&c, LEFT - 9 - w, y - 5, buf, black, 1, 0);
    }
    line(&c, LEFT, TOP, RIGHT, TOP, black, 1, 0);
    line(&c, LEFT, BOTTOM, RIGHT, BOTTOM, black, 1, 0);
    line(&c, LEFT, TOP, LEFT, BOTTOM, black, 1, 0);
    line(&c, RIGHT, TOP, RIGHT, BOTTOM, black, 1, 0);

    /* titles and axis labels */
    if (d->title) text(&c, LEFT, 14, d->title, black, 2, 0);
    if (d->subtitle) text(&c, LEFT, 40, d->subtitle, grey, 1, 0);
    if (d->x_label) text(&c, (LEFT + RIGHT) / 2 - (int)strlen(d->x_label) * 3, BOTTOM + 30, d->x_label, black, 1, 0);
    if (d->y_label) text(&c, 18, (TOP + BOTTOM) / 2 + (int)strlen(d->y_label) * 3, d->y_label, black, 1, 1);

    /* Pareto fronts: dashed line through each group's front, sorted by time */
    bench_pareto(d->points, d->count, pareto);
    for (i = 0; i < d->count; i++) {
        int best = -1, j;
        if (!pareto[i]) continue;
        /* the next front point of the same group to the right */
        for (j = 0; j < d->count; j++)
            if (pareto[j] && j != i && d->points[j].group == d->points[i].group && d->points[j].x > d->points[i].x &&
                (best < 0 || d->points[j].x < d->points[best].x))
                best = j;
        if (best >= 0) {
            double y0 = d->points[i].y > 0 ? d->points[i].y : pow(10.0, ay.lo);
            double y1 = d->points[best].y > 0 ? d->points[best].y : pow(10.0, ay.lo);
            if (y0 < pow(10.0, ay.lo)) y0 = pow(10.0, ay.lo);
            if (y1 < pow(10.0, ay.lo)) y1 = pow(10.0, ay.lo);
            line(&c, map_x(&ax, d->points[i].x), map_y(&ay, y0), map_x(&ax, d->points[best].x), map_y(&ay, y1),
                 g_palette[d->points[i].color % PALETTE_N], 2, 6);
        }
    }
    /* points and rings, then the labels placed clear of every point and of each other */
    for (i = 0; i < d->count; i++) {
        const bench_plot_point *p = &d->points[i];
        double y = p->y;
        pos[i].x = INT_MIN;
        if (!(p->x > 0.0) || !isfinite(p->x) || !isfinite(p->y)) continue;
        if (!(y >= pow(10.0, ay.lo))) {
            y = pow(10.0, ay.lo);
            clamped++;
        }
        pos[i].x = map_x(&ax, p->x);
        pos[i].y = map_y(&ay, y);
        marker(&c, pos[i].x, pos[i].y, p->marker, g_palette[p->color % PALETTE_N], 5);
        if (pareto[i]) ring(&c, pos[i].x, pos[i].y, 9, black);
    }
    place_labels(&c, d, pos, grey);
    if (clamped) {
        snprintf(buf, sizeof buf, "%d point(s) below the axis drawn on it", clamped);
        text(&c, LEFT + 6, BOTTOM - 14, buf, grey, 1, 0);
    }

    /* legend */
    {
        int x = RIGHT + 24, y = TOP + 4;
        text(&c, x, y, "scene", black, 1, 0);
        y += 16;
        for (i = 0; i < d->color_count; i++, y += 15) {
            marker(&c, x + 5, y + 4, 1, g_palette[i % PALETTE_N], 5);
            text(&c, x + 18, y, d->color_names[i], black, 1, 0);
        }
        y += 10;
        text(&c, x, y, "method", black, 1, 0);
        y += 16;
        for (i = 0; i < d->marker_count; i++, y += 15) {
            marker(&c, x + 5, y + 4, i, grey, 5);
            text(&c, x + 18, y, d->marker_names[i], black, 1, 0);
        }
        y += 10;
        ring(&c, x + 5, y + 4, 9, black);
        text(&c, x + 20, y, "Pareto-optimal", black, 1, 0);
        text(&c, x + 20, y + 12, "(per scene + size)", grey, 1, 0);
        y += 30;
        line(&c, x - 4, y + 4, x + 14, y + 4, grey, 2, 6);
        text(&c, x + 20, y, "front", black, 1, 0);
    }
    st = snell_write_png(path, PW, PH, c.px);
    free(c.px);
    free(pareto);
    free(pos);
    return st;
}
