/* SPDX-License-Identifier: MIT */
/* test_twin.h — double-precision twins for the image-space kernels' tests
 * (test_wyman.c, test_oliveira.c): angles between directions, optics.h's
 * refraction, the analytic unit sphere, and the renderer's camera and pixel
 * rays. */
#ifndef SNELL_TEST_TWIN_H
#define SNELL_TEST_TWIN_H

#include <snell/snell.h>

#include <math.h>

static inline double angle(const float a[3], const double b[3])
{
    double c0 = a[1] * b[2] - a[2] * b[1], c1 = a[2] * b[0] - a[0] * b[2], c2 = a[0] * b[1] - a[1] * b[0];
    return atan2(sqrt(c0 * c0 + c1 * c1 + c2 * c2), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

static inline double anglef(const float a[3], const float b[3])
{
    double d[3] = {b[0], b[1], b[2]};
    return angle(a, d);
}

static inline double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static inline void normalize3(double *a)
{
    double l = sqrt(dot3(a, a));
    a[0] /= l;
    a[1] /= l;
    a[2] /= l;
}

/* optics.h's model in double: n faces the incoming ray; 0 and the mirror on TIR */
static inline int refract(const double i[3], const double n[3], double eta, double t[3])
{
    double c = -dot3(n, i), k = 1.0 - eta * eta * (1.0 - c * c);
    int j;
    if (k < 0.0) {
        for (j = 0; j < 3; j++) t[j] = i[j] + 2.0 * c * n[j];
        return 0;
    }
    for (j = 0; j < 3; j++) t[j] = eta * i[j] + (eta * c - sqrt(k)) * n[j];
    return 1;
}

/* Unit sphere at the origin: near and far ray parameters, 0 on a miss. */
static inline int sphere_hits(const double o[3], const double d[3], double *t0, double *t1)
{
    double b = dot3(o, d), c = dot3(o, o) - 1.0, disc = b * b - c;
    if (disc <= 0.0) return 0;
    *t0 = -b - sqrt(disc);
    *t1 = -b + sqrt(disc);
    return *t0 > 0.0;
}

typedef struct camera_d {
    double eye[3], right[3], up[3], fwd[3], tan_half;
    int w, h;
    float view_proj[16];
} camera_d;

static inline void camera_setup(const snell_camera *cam, int w, int h, camera_d *c)
{
    float eye[3], view[16], proj[16];
    int k, i, j;
    snell_camera_matrices(cam, (float)w / (float)h, eye, view, proj);
    c->w = w;
    c->h = h;
    for (k = 0; k < 3; k++) {
        c->eye[k] = eye[k];
        c->right[k] = view[4 * k + 0];
        c->up[k] = view[4 * k + 1];
        c->fwd[k] = -view[4 * k + 2];
    }
    c->tan_half = tan(0.5 * (cam->fov_y > 0.0f ? cam->fov_y : 45.0 * 3.14159265358979 / 180.0));
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            double s = 0.0;
            for (k = 0; k < 4; k++) s += (double)proj[4 * k + j] * view[4 * i + k];
            c->view_proj[4 * i + j] = (float)s;
        }
}

/* The ray through the centre of pixel (x, y), y = 0 the top row. */
static inline void pixel_ray(const camera_d *c, double x, double y, double d[3])
{
    double nx = (x + 0.5) / c->w * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / c->h * 2.0;
    int k;
    for (k = 0; k < 3; k++) d[k] = c->fwd[k] + nx * c->tan_half * ((double)c->w / c->h) * c->right[k] + ny * c->tan_half * c->up[k];
    normalize3(d);
}

#endif
