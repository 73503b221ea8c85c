/* SPDX-License-Identifier: MIT */
/* camera.c — the camera shared by the renderer, the references and the
 * CLI: an orbit (eye on a sphere around the target, +Y up) or the host's
 * matrices, GL clip conventions. */
#include "frame/camera.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double *a, const double *b, double *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void unit3(double *a)
{
    double l = sqrt(dot3(a, a));
    a[0] /= l, a[1] /= l, a[2] /= l;
}

/* x with the rows r0, r1, r2 (xyz) . x = y (Cramer). */
static void solve3(const double *r0, const double *r1, const double *r2, const double y[3], double x[3])
{
    double c12[3], c20[3], c01[3], det;
    int k;
    cross3(r1, r2, c12), cross3(r2, r0, c20), cross3(r0, r1, c01);
    det = dot3(r0, c12);
    for (k = 0; k < 3; k++) x[k] = (y[0] * c12[k] + y[1] * c20[k] + y[2] * c01[k]) / det;
}

void snell__camera_defaults(const snell_camera *in, snell_camera *out)
{
    snell_camera c;
    memset(&c, 0, sizeof c);
    if (in) c = *in;
    /* Only zeros are defaults: any other value is the caller's, valid or
     * not (snell__camera_validate checks what this resolves). */
    if (c.kind == SNELL_CAMERA_ORBIT) {
        if (c.distance == 0.0f) c.distance = SNELL_DEFAULT_CAMERA_DISTANCE;
        if (c.fov_y == 0.0f) c.fov_y = SNELL_DEFAULT_FOV_Y;
        /* Near and far span 1e4 around the target, enough for 24-bit depth. */
        if (c.z_near == 0.0f) c.z_near = c.distance * 0.01f;
        if (c.z_far == 0.0f) c.z_far = c.distance * 100.0f;
    }
    *out = c;
}

void snell_camera_matrices(const snell_camera *cam, float aspect, float eye_out[3], float view_out[16],
                           float proj_out[16])
{
    snell_camera c;
    vec3 eye, target, up = {0.0f, 1.0f, 0.0f};
    mat4 view, proj;
    float ce, dist;
    snell__camera_defaults(cam, &c);
    if (c.kind == SNELL_CAMERA_MATRICES) {
        /* The eye is where the view matrix puts the origin of eye space. */
        mat4 inv;
        memcpy(view, c.view, sizeof view);
        snell__mat4_inv((const float *)view, (float *)inv);
        if (eye_out) memcpy(eye_out, inv[3], sizeof(vec3));
        if (view_out) memcpy(view_out, c.view, sizeof(mat4));
        if (proj_out) memcpy(proj_out, c.projection, sizeof(mat4));
        return;
    }
    dist = c.distance;
    if (!(aspect > 0.0f)) aspect = 1.0f;
    ce = cosf(c.elevation);
    target[0] = c.target[0]; target[1] = c.target[1]; target[2] = c.target[2];
    eye[0] = target[0] + dist * ce * sinf(c.azimuth);
    eye[1] = target[1] + dist * sinf(c.elevation);
    eye[2] = target[2] + dist * ce * cosf(c.azimuth);
    if (fabsf(ce) < 1e-5f) {
        /* Looking straight down/up: +Y is parallel to the view, use the azimuth. */
        up[0] = -sinf(c.azimuth) * (c.elevation > 0 ? 1.0f : -1.0f);
        up[1] = 0.0f;
        up[2] = -cosf(c.azimuth) * (c.elevation > 0 ? 1.0f : -1.0f);
    }
    glm_lookat(eye, target, up, view);
    glm_perspective(c.fov_y, aspect, c.z_near, c.z_far, proj);
    if (eye_out) memcpy(eye_out, eye, sizeof(vec3));
    if (view_out) memcpy(view_out, view, sizeof(mat4));
    if (proj_out) memcpy(proj_out, proj, sizeof(mat4));
}

static int all_finite(const float *v, int n)
{
    int i;
    for (i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

int snell__projection_orthographic(const float p[16])
{
    return p[3] == 0.0f && p[7] == 0.0f && p[11] == 0.0f && p[15] != 0.0f;
}

/* o = a x b, column-major. */
static void mul4(const double *a, const double *b, double *o)
{
    int i, j, k;
    for (j = 0; j < 4; j++)
        for (i = 0; i < 4; i++)
            for (o[4 * j + i] = 0.0, k = 0; k < 4; k++) o[4 * j + i] += a[4 * k + i] * b[4 * j + k];
}

/* A rigid view and a standard projection (glm's forms: depth -1 near to 1
 * far, finite far, no oblique plane) with the same pixel of every world
 * point as projection x view, judged by that product alone. Perspective: the
 * eye is where clip x, y and w vanish, the view axis the gradient of w; near
 * and far where the host's depth reaches its near and far values along the
 * axis and the frustum's corner rays (an oblique near plane: the nearest; an
 * infinite far: 1e7 times the near). Orthographic: the axis is where x and y
 * stay put, looking along y x x (a mirrored orthographic view cannot be told
 * from a reversed-Z one turned round). Returns SNELL__CAMERA_* flags, or -1
 * with *why. */
static int standardize(const float *view, const float *proj, float eye[3], float v[16], float p[16], double *near_out,
                       char *why, size_t n)
{
    double a[16], b[16], m[16], q[16], row[4][4], e[3], y[3], fwd[3], up[3], right[3], z0, near_ = HUGE_VAL,
        far_ = 0.0;
    int i, k, flags = 0, ortho, infinite = 0;
    for (k = 0; k < 16; k++) a[k] = proj[k], b[k] = view[k];
    mul4(a, b, m);
    for (i = 0; i < 16; i++) row[i & 3][i >> 2] = m[i];
    ortho = row[3][0] == 0.0 && row[3][1] == 0.0 && row[3][2] == 0.0;
    if (ortho && !(row[3][3] > 0.0)) {
        snprintf(why, n, "is orthographic with clip w %g <= 0: every point is clipped (a negated matrix?)", row[3][3]);
        return -1;
    }
    if (ortho) {
        cross3(row[1], row[0], fwd); /* x right, y up: it looks along y x x */
        if (dot3(fwd, row[2]) < 0.0) flags |= SNELL__CAMERA_REVERSED;
        y[0] = -row[0][3], y[1] = -row[1][3], y[2] = (flags ? row[3][3] : -row[3][3]) - row[2][3];
        solve3(row[0], row[1], row[2], y, e); /* the near plane's centre */
    } else {
        y[0] = -row[0][3], y[1] = -row[1][3], y[2] = -row[3][3];
        solve3(row[0], row[1], row[3], y, e);
        memcpy(fwd, row[3], sizeof fwd);
    }
    unit3(fwd);
    for (k = 0; k < 3; k++) up[k] = row[1][k] - dot3(row[1], fwd) * fwd[k];
    unit3(up);
    cross3(fwd, up, right);
    if (!isfinite(dot3(e, e) + dot3(right, right))) {
        snprintf(why, n, "has no pinhole or parallel camera with its pixels (degenerate rows)");
        return -1;
    }
    /* b: the rigid view's inverse (columns right, up, back, eye); q: the
     * host's clip coordinates of its points, scaled to clip w = depth */
    memset(b, 0, sizeof b);
    for (k = 0; k < 3; k++) b[k] = right[k], b[4 + k] = up[k], b[8 + k] = -fwd[k], b[12 + k] = e[k];
    b[15] = 1.0;
    mul4(m, b, q);
    z0 = ortho ? q[15] : -q[11];
    for (k = 0; k < 16; k++) q[k] /= z0;
    z0 = q[14]; /* ndc z along eye direction (x, y, -1) at depth D: z0 / D + q2 x + q6 y - q10 */
    if (ortho) {
        q[10] = -fabs(q[10]), q[14] = -1.0;
    } else {
        if (z0 > 0.0) flags |= SNELL__CAMERA_REVERSED;
        for (k = 0; k < 5; k++) {
            double cx = k ? ((k & 1) ? 1.0 : -1.0) : 0.0, cy = k ? ((k & 2) ? 1.0 : -1.0) : 0.0;
            double ye = (cy + q[9]) / q[5], xe = (cx + q[8] - q[4] * ye) / q[0], al = q[2] * xe + q[6] * ye - q[10];
            double dn = z0 / ((z0 > 0.0 ? 1.0 : -1.0) - al), df = z0 / ((z0 > 0.0 ? -1.0 : 1.0) - al);
            if (dn > 0.0) near_ = fmin(near_, dn);
            if (df > 0.0) far_ = fmax(far_, df);
            else infinite = 1;
        }
        if (!(near_ < HUGE_VAL)) {
            snprintf(why, n, "has no near plane in front of the eye");
            return -1;
        }
        if (infinite || far_ > 1e7 * near_) far_ = 1e7 * near_;
        q[10] = -(far_ + near_) / (far_ - near_), q[14] = -2.0 * far_ * near_ / (far_ - near_);
    }
    *near_out = near_;
    if (fabs(q[2]) + fabs(q[6]) > 1e-6 * fabs(q[10])) flags |= SNELL__CAMERA_OBLIQUE;
    q[2] = q[6] = 0.0;
    if (q[0] < 0.0) flags |= SNELL__CAMERA_MIRRORED;
    for (k = 0; k < 16; k++) p[k] = (float)q[k];
    for (k = 0; k < 3; k++) {
        v[4 * k] = (float)right[k], v[4 * k + 1] = (float)up[k], v[4 * k + 2] = (float)-fwd[k], v[4 * k + 3] = 0.0f;
        eye[k] = (float)e[k];
    }
    v[12] = (float)-dot3(right, e), v[13] = (float)-dot3(up, e), v[14] = (float)dot3(fwd, e), v[15] = 1.0f;
    return flags;
}

int snell__camera_standard(const snell_camera *cam, float aspect, float eye[3], float view[16], float proj[16])
{
    float v[16], p[16], e[3];
    double near_;
    char why[8];
    int flags, k, same = cam && cam->projection[10] != cam->projection[11]; /* equal: an infinite far */
    snell_camera_matrices(cam, aspect, eye, view, proj);
    if (!cam || cam->kind != SNELL_CAMERA_MATRICES) return 0;
    flags = standardize(cam->view, cam->projection, e, v, p, &near_, why, sizeof why);
    /* The host's own where they are standard already, to float rounding. */
    for (k = 0; k < 16; k++)
        same &= fabsf(v[k] - cam->view[k]) <= 1e-5f * fmaxf(1.0f, fabsf(v[k])) &&
                fabsf(p[k] - cam->projection[k]) <= 1e-5f * fmaxf(1.0f, fabsf(p[k]));
    if (flags < 0) return 0; /* refused by snell__camera_validate */
    if (same) return flags;  /* a mirrored projection may be standard otherwise */
    if (eye) memcpy(eye, e, sizeof e);
    if (view) memcpy(view, v, sizeof v);
    if (proj) memcpy(proj, p, sizeof p);
    return flags | SNELL__CAMERA_CHANGED;
}

/* Window depth of world point x under projection p x view v (column-major). */
static double window_depth(const float *p, const float *v, const double x[3])
{
    double e[4], c[2];
    int i, k;
    for (i = 0; i < 4; i++) e[i] = v[12 + i] + v[i] * x[0] + v[4 + i] * x[1] + v[8 + i] * x[2];
    for (k = 0; k < 2; k++) {
        int row = k ? 3 : 2;
        c[k] = p[row] * e[0] + p[4 + row] * e[1] + p[8 + row] * e[2] + p[12 + row] * e[3];
    }
    return 0.5 * c[0] / c[1] + 0.5;
}

int snell__camera_depth_map(const snell_camera *cam, float aspect, double map[2])
{
    float e[3], v[16], p[16];
    double x[2][3], near_, far_, z[2], dh[2], ds[2];
    int i, k, flags = snell__camera_standard(cam, aspect, e, v, p);
    map[0] = 1.0, map[1] = 0.0;
    if (!(flags & SNELL__CAMERA_CHANGED) || (flags & SNELL__CAMERA_OBLIQUE)) return 0;
    if (snell__projection_orthographic(p)) {
        near_ = ((double)p[14] + 1.0) / p[10], far_ = ((double)p[14] - 1.0) / p[10];
    } else {
        near_ = (double)p[14] / (p[10] - 1.0), far_ = (double)p[14] / (p[10] + 1.0);
    }
    z[0] = near_ + 0.25 * (far_ - near_), z[1] = near_ + 0.5 * (far_ - near_);
    if (!snell__projection_orthographic(p) && far_ > 4.0 * near_) z[0] = 2.0 * near_, z[1] = 4.0 * near_;
    for (i = 0; i < 2; i++) {
        for (k = 0; k < 3; k++) x[i][k] = e[k] - z[i] * v[4 * k + 2]; /* along -z of the view */
        dh[i] = window_depth(cam->projection, cam->view, x[i]);
        ds[i] = window_depth(p, v, x[i]);
    }
    if (!(fabs(dh[1] - dh[0]) > 0.0)) return 0;
    map[0] = (ds[1] - ds[0]) / (dh[1] - dh[0]);
    map[1] = ds[0] - map[0] * dh[0];
    return fabs(map[0] - 1.0) > 1e-6 || fabs(map[1]) > 1e-6;
}

/* The host's matrices: finite, invertible, and a perspective projection
 * (bottom row 0 0 -w 0: the view rays start at the eye) or an orthographic
 * one (0 0 0 w: they run along the axis, common/view.glsl). */
static snell_status validate_matrices(const snell_ctx *ctx, const snell_camera *cam, const char *who)
{
    const float *p = cam->projection;
    mat4 vp, a, b;
    char why[96];
    if (!all_finite(cam->view, 16))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.view is not finite", who);
    if (!all_finite(p, 16))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.projection is not finite", who);
    if (!snell__matrix_invertible(cam->view, why, sizeof why))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.view %s", who, why);
    if (!snell__matrix_invertible(p, why, sizeof why))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.projection %s", who, why);
    if (!snell__projection_orthographic(p) && (p[3] != 0.0f || p[7] != 0.0f || !(p[11] < 0.0f) || p[15] != 0.0f))
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "%s: camera.projection's bottom row (%g %g %g %g) is neither a "
                           "perspective one (0 0 -w 0) nor an orthographic one (0 0 0 w)",
                           who, p[3], p[7], p[11], p[15]);
    memcpy(a, cam->projection, sizeof a);
    memcpy(b, cam->view, sizeof b);
    snell__mat4_mul((const float *)a, (const float *)b, (float *)vp);
    if (!snell__matrix_invertible((const float *)vp, why, sizeof why))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.projection x camera.view %s", who, why);
    {
        /* Depth precision: a near plane closer than a millionth of the
         * scene's scale (as an orbit's, snell__camera_validate) rounds every
         * depth beyond it to the far plane's. */
        float e[3], v[16], q[16];
        double near_;
        if (standardize(cam->view, p, e, v, q, &near_, why, sizeof why) < 0)
            return snell__fail(ctx, SNELL_E_UNSUPPORTED, "%s: camera.projection x camera.view %s", who, why);
        if (near_ < 1e-6 * fmax(1.0, sqrt((double)e[0] * e[0] + (double)e[1] * e[1] + (double)e[2] * e[2])))
            return snell__fail(ctx, SNELL_E_UNSUPPORTED, "%s: camera.projection's near plane at %g from the eye is "
                               "too close for depth precision (at least a millionth of the scene's scale, 1 or the "
                               "eye's distance from the origin)", who, near_);
    }
    return SNELL_OK;
}

/* Resolves the camera first, then checks the resolved copy (sokol_gfx's
 * order): a message names the value the frame would have used. */
snell_status snell__camera_validate(const snell_ctx *ctx, const snell_camera *cam, float aspect, const char *who)
{
    float eye[3], view[16], proj[16], scale;
    snell_camera c;
    int k;
    if (!cam) return SNELL_OK;
    if (cam->kind == SNELL_CAMERA_MATRICES) return validate_matrices(ctx, cam, who);
    if (cam->kind != SNELL_CAMERA_ORBIT)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.kind %d is not a snell_camera_kind", who, (int)cam->kind);
    snell__camera_defaults(cam, &c);
    if (!isfinite(c.azimuth))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.azimuth %g is not finite", who, c.azimuth);
    if (!isfinite(c.elevation))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.elevation %g is not finite", who, c.elevation);
    for (k = 0; k < 3; k++)
        if (!isfinite(c.target[k]))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.target[%d] %g is not finite", who, k,
                               c.target[k]);
    if (!(c.distance > 0.0f) || !isfinite(c.distance))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.distance %g: a finite distance > 0", who,
                           c.distance);
    if (!(c.fov_y > 0.0f && c.fov_y < (float)SNELL_PI))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.fov_y %g rad outside (0, pi)", who, c.fov_y);
    /* An eye closer to the target than a millionth of the scene's scale
     * (1, or the target's distance from the origin) derives near and far
     * planes that clip the whole scene: the frame would be background. */
    scale = fmaxf(1.0f, fmaxf(fabsf(c.target[0]), fmaxf(fabsf(c.target[1]), fabsf(c.target[2]))));
    if (c.distance < 1e-6f * scale)
        return snell__fail(ctx, SNELL_E_INVALID_ARG,
                           "%s: camera.distance %g is too small (at least %g: a millionth of the scene's scale)",
                           who, c.distance, 1e-6f * scale);
    if (!(c.z_near > 0.0f) || !isfinite(c.z_near))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.z_near %g%s: a finite distance > 0", who, c.z_near,
                           cam->z_near == 0.0f ? " (derived from the distance)" : "");
    if (!isfinite(c.z_far) && cam->z_far == 0.0f)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.distance %g is too large (the derived far plane "
                           "overflows; set z_far)", who, c.distance);
    if (!(c.z_far > 0.0f) || !isfinite(c.z_far))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.z_far %g: a finite distance > 0", who, c.z_far);
    if (!(c.z_near < c.z_far))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera.z_near %g%s is not before camera.z_far %g%s", who,
                           c.z_near, cam->z_near == 0.0f ? " (derived from the distance)" : "", c.z_far,
                           cam->z_far == 0.0f ? " (derived from the distance)" : "");
    snell_camera_matrices(&c, aspect, eye, view, proj);
    if (!all_finite(eye, 3) || !all_finite(view, 16) || !all_finite(proj, 16))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: camera (distance %g, z_near %g, z_far %g) gives matrices "
                           "that are not finite", who, c.distance, c.z_near, c.z_far);
    return SNELL_OK;
}
