/* lm2d_raster_cpu.c — exact length-weighted rasterisation of path segments
 * (eq. 4.2) by a grid walk (Amanatides-Woo) in pixel space. */
#include "lm2d/lm2d_raster_cpu.h"

#include <math.h>

typedef void (*cell_fn)(float *px, const float v[3]);

static void cell_add(float *px, const float v[3])
{
    px[0] += v[0];
    px[1] += v[1];
    px[2] += v[2];
}

static void cell_screen(float *px, const float v[3])
{
    int k;
    for (k = 0; k < 3; k++) px[k] *= 1.0f - (v[k] < 1.0f ? v[k] : 1.0f);
}

static void walk(const lm2d_path *q, const lm2d_raster_view *v, float scale, float *img, cell_fn fn)
{
    float sx = (float)v->width / (v->hi[0] - v->lo[0]), sy = (float)v->height / (v->hi[1] - v->lo[1]);
    double x0 = (q->x0 - v->lo[0]) * sx, y0 = (q->y0 - v->lo[1]) * sy;
    double x1 = (q->x1 - v->lo[0]) * sx, y1 = (q->y1 - v->lo[1]) * sy;
    double dx = x1 - x0, dy = y1 - y0, len = sqrt(dx * dx + dy * dy);
    double t = 0.0, tdx, tdy, tnx, tny;
    int ix, iy, stx, sty, guard;
    if (!(len > 0.0)) return;
    ix = (int)floor(x0);
    iy = (int)floor(y0);
    stx = dx > 0 ? 1 : -1;
    sty = dy > 0 ? 1 : -1;
    tdx = dx != 0.0 ? fabs(1.0 / dx) : INFINITY;
    tdy = dy != 0.0 ? fabs(1.0 / dy) : INFINITY;
    tnx = dx > 0 ? (ix + 1 - x0) / dx : (dx < 0 ? (ix - x0) / dx : INFINITY);
    tny = dy > 0 ? (iy + 1 - y0) / dy : (dy < 0 ? (iy - y0) / dy : INFINITY);
    /* every cell is entered once; the walk cannot take more steps than this */
    guard = (int)(fabs(dx) + fabs(dy)) + 4;
    while (t < 1.0 && guard-- > 0) {
        double tn = tnx < tny ? tnx : tny, mid;
        float val[3];
        int k;
        if (tn > 1.0) tn = 1.0;
        if (ix >= 0 && iy >= 0 && ix < v->width && iy < v->height && tn > t) {
            float *px = img + 3 * ((size_t)iy * (size_t)v->width + (size_t)ix);
            double l = len * (tn - t);
            mid = 0.5 * (t + tn); /* the integral of a linear function = length x midpoint value */
            for (k = 0; k < 3; k++) val[k] = (float)(scale * l * (q->c0[k] + (q->c1[k] - q->c0[k]) * mid));
            fn(px, val);
        }
        t = tn;
        if (tnx < tny) {
            ix += stx;
            tnx += tdx;
        } else {
            iy += sty;
            tny += tdy;
        }
    }
}

void lm2d_raster_exact_add(const lm2d_path *paths, size_t n, const lm2d_raster_view *v, float scale, float *acc)
{
    size_t i;
    for (i = 0; i < n; i++) walk(&paths[i], v, scale, acc, cell_add);
}

void lm2d_raster_exact_screen(const lm2d_path *paths, size_t n, const lm2d_raster_view *v, float scale,
                              float *prod)
{
    size_t i;
    for (i = 0; i < n; i++) walk(&paths[i], v, scale, prod, cell_screen);
}
