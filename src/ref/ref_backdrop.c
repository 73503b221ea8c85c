/* SPDX-License-Identifier: MIT */
/* ref_backdrop.c — the host's scene behind the glass in the reference's
 * view (snell_ref_set_backdrop): the host's frame as a depth field, met by
 * the rays in air as common/backdrop.glsl meets it on the GPU, with a far
 * finer search (steps of a quarter texel, 40 halvings), and its sky where a
 * ray's direction vanishes, so the kernels' error against it is measured. */
#include "ref/ref_scene.h"
#include "core/ctx.h"
#include "frame/camera.h"

#include <string.h>

struct ref_backdrop {
    int w, h, has_depth;
    double vp[16];    /* proj * view, column-major */
    double distance;
    float far_;       /* the depth of the host's far plane: 1, 0 reversed-Z */
    float *depth;     /* w * h, bottom row first; NULL none */
    uint8_t rgba[];   /* w * h * 4, bottom row first */
};

void snell__ref_backdrop_free(snell_ref *r)
{
    if (!r->backdrop) return;
    snell__free(&r->alloc, r->backdrop->depth);
    snell__free(&r->alloc, r->backdrop);
    r->backdrop = NULL;
}

snell_status snell_ref_set_backdrop(snell_ref *r, const snell_ref_backdrop *b)
{
    struct ref_backdrop *B;
    float view[16], proj[16], eye[3];
    size_t n, i;
    int row, col, k;
    snell_status st;
    if (!r) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ref_set_backdrop: NULL reference");
    snell__ref_backdrop_free(r);
    if (!b) return SNELL_OK;
    if (!b->rgba || b->width < 1 || b->height < 1 || b->width > 16384 || b->height > 16384 ||
        !(b->distance >= 0.0f) || !isfinite(b->distance))
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "snell_ref_set_backdrop: rgba required, width and height "
                           "1..16384, distance finite >= 0");
    st = snell__camera_validate(r->ctx, &b->camera, (float)b->width / (float)b->height, "snell_ref_set_backdrop");
    if (st != SNELL_OK) return st;
    n = (size_t)b->width * (size_t)b->height;
    for (i = 0; b->depth && i < n; i++)
        if (!(b->depth[i] >= 0.0f && b->depth[i] <= 1.0f))
            return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "snell_ref_set_backdrop: depth[%zu] %g outside 0..1", i,
                               (double)b->depth[i]);
    B = (struct ref_backdrop *)snell__calloc(&r->alloc, 1, sizeof *B + 4 * n);
    if (!B || (b->depth && !(B->depth = (float *)snell__calloc(&r->alloc, n, sizeof(float))))) {
        if (B) snell__free(&r->alloc, B);
        return snell__fail(r->ctx, SNELL_E_NOMEM, "snell_ref_set_backdrop: out of memory");
    }
    memcpy(B->rgba, b->rgba, 4 * n);
    if (b->depth) memcpy(B->depth, b->depth, n * sizeof(float));
    B->w = b->width, B->h = b->height, B->has_depth = b->depth != NULL;
    B->distance = b->distance > 0.0f ? b->distance : 1.0;
    snell_camera_matrices(&b->camera, (float)b->width / (float)b->height, eye, view, proj);
    B->far_ = snell__camera_standard(&b->camera, (float)b->width / (float)b->height, NULL, NULL, NULL) &
                      SNELL__CAMERA_REVERSED ? 0.0f : 1.0f;
    for (col = 0; col < 4; col++)
        for (row = 0; row < 4; row++) {
            double s = 0.0;
            for (k = 0; k < 4; k++) s += (double)proj[4 * k + row] * view[4 * col + k];
            B->vp[4 * col + row] = s;
        }
    r->backdrop = B;
    return SNELL_OK;
}

static void clip_of(const struct ref_backdrop *B, const double p[3], double w, double c[4])
{
    int row;
    for (row = 0; row < 4; row++)
        c[row] = B->vp[row] * p[0] + B->vp[4 + row] * p[1] + B->vp[8 + row] * p[2] + B->vp[12 + row] * w;
}

/* The colour at ndc (x, y), bilinear between texel centres, edges clamped (GL_LINEAR). */
static void color_at(const struct ref_backdrop *B, double x, double y, double rgb[3])
{
    double tx = (0.5 * x + 0.5) * B->w - 0.5, ty = (0.5 * y + 0.5) * B->h - 0.5;
    int q, k;
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    for (q = 0; q < 4; q++) {
        int ix = (int)floor(tx) + (q & 1), iy = (int)floor(ty) + (q >> 1);
        double wgt = fabs(tx - floor(tx) - !(q & 1)) * fabs(ty - floor(ty) - !(q >> 1));
        ix = ix < 0 ? 0 : ix >= B->w ? B->w - 1 : ix;
        iy = iy < 0 ? 0 : iy >= B->h ? B->h - 1 : iy;
        for (k = 0; k < 3; k++) rgb[k] += wgt * B->rgba[4 * ((size_t)iy * (size_t)B->w + (size_t)ix) + k] / 255.0;
    }
}

/* Whether the point of ndc (x, y) and window depth z lies behind the field. */
static int behind(const struct ref_backdrop *B, const double p[3])
{
    int ix = (int)floor((0.5 * p[0] + 0.5) * B->w), iy = (int)floor((0.5 * p[1] + 0.5) * B->h);
    float d;
    ix = ix < 0 ? 0 : ix >= B->w ? B->w - 1 : ix;
    iy = iy < 0 ? 0 : iy >= B->h ? B->h - 1 : iy;
    d = B->depth[(size_t)iy * (size_t)B->w + (size_t)ix];
    return d != B->far_ && (B->far_ > 0.5f ? p[2] >= d : p[2] <= d);
}

/* A ray that meets nothing (tmax infinite) reaches the host's far plane where
 * its direction (clip cd) vanishes: on the view, where the host's depth holds
 * its far plane (its sky), it sees the host's colour there. */
static int sky(const struct ref_backdrop *B, const double cd[4], double tmax, double rgb[3])
{
    double x, y;
    int ix, iy;
    if (tmax < HUGE_VAL || !(cd[3] > 0.0) || fabs(cd[0]) > cd[3] || fabs(cd[1]) > cd[3]) return 0;
    x = cd[0] / cd[3], y = cd[1] / cd[3];
    ix = (int)floor((0.5 * x + 0.5) * B->w), iy = (int)floor((0.5 * y + 0.5) * B->h);
    ix = ix < 0 ? 0 : ix >= B->w ? B->w - 1 : ix;
    iy = iy < 0 ? 0 : iy >= B->h ? B->h - 1 : iy;
    if (B->depth[(size_t)iy * (size_t)B->w + (size_t)ix] != B->far_) return 0;
    if (rgb) color_at(B, x, y, rgb);
    return 1;
}

static void lerp3(const double a[3], const double b[3], double u, double p[3])
{
    int k;
    for (k = 0; k < 3; k++) p[k] = a[k] + u * (b[k] - a[k]);
}

int snell__ref_backdrop_hit(const snell_ref *r, const double o[3], const double d[3], double tmax, double rgb[3])
{
    const struct ref_backdrop *B = r->backdrop;
    double c0[4], cd[4], ca[4], cb[4], a[3], b[3], p[3], t0 = 0.0, t1 = 1e6, ua = 0.0, ub = -1.0, len, t;
    int k, i, steps;
    if (!B) return 0;
    clip_of(B, o, 1.0, c0);
    clip_of(B, d, 0.0, cd);
    if (!B->has_depth) {
        for (k = 0; k < 4; k++) ca[k] = c0[k] + B->distance * cd[k];
        if (!(ca[3] > 0.0) || fabs(ca[0]) > ca[3] || fabs(ca[1]) > ca[3] || B->distance >= tmax) return 0;
        if (rgb) color_at(B, ca[0] / ca[3], ca[1] / ca[3], rgb);
        return 1;
    }
    for (k = 0; k < 6; k++) { /* Liang-Barsky against -w <= x, y, z <= w */
        double s = (k & 1) == 0 ? 1.0 : -1.0, f = c0[3] + s * c0[k / 2], g = cd[3] + s * cd[k / 2];
        if (g < 0.0) t1 = fmin(t1, -f / g);
        else if (g > 0.0) t0 = fmax(t0, -f / g);
        else if (f < 0.0) return sky(B, cd, tmax, rgb);
    }
    if (t1 > tmax) t1 = tmax; /* what lies past the nearest object is hidden by it */
    if (!(t0 <= t1)) return sky(B, cd, tmax, rgb);
    for (k = 0; k < 4; k++) ca[k] = c0[k] + t0 * cd[k], cb[k] = c0[k] + t1 * cd[k];
    for (k = 0; k < 3; k++) a[k] = ca[k] / ca[3], b[k] = cb[k] / cb[3];
    a[2] = 0.5 * a[2] + 0.5, b[2] = 0.5 * b[2] + 0.5;
    len = hypot((b[0] - a[0]) * 0.5 * B->w, (b[1] - a[1]) * 0.5 * B->h);
    steps = 1 + (int)ceil(4.0 * len);
    for (i = 0; i <= steps; i++) {
        double u = (double)i / steps;
        lerp3(a, b, u, p);
        if (behind(B, p)) {
            ub = u;
            break;
        }
        ua = u;
    }
    if (ub < 0.0) return sky(B, cd, tmax, rgb);
    for (i = 0; ub > 0.0 && i < 40; i++) {
        double um = 0.5 * (ua + ub);
        lerp3(a, b, um, p);
        if (behind(B, p)) ub = um;
        else ua = um;
    }
    /* t at the crossing, from 1/w and t/w, both affine in screen position */
    t = ((1.0 - ub) * t0 / ca[3] + ub * t1 / cb[3]) / ((1.0 - ub) / ca[3] + ub / cb[3]);
    if (!(t < tmax)) return 0;
    lerp3(a, b, ub, p);
    if (rgb) color_at(B, p[0], p[1], rgb);
    return 1;
}
