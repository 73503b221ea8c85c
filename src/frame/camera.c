/* SPDX-License-Identifier: MIT */
/* camera.c — the camera shared by the renderer, the references and the
 * CLI: an orbit (eye on a sphere around the target, +Y up) or the host's
 * matrices, GL clip conventions. */
#include "frame/camera.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

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
        glm_mat4_inv(view, inv);
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

/* ------------------------------------------------ the host's matrices, standardised */

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

/* Already what snell draws with: a rigid view (orthonormal, det +1) and a
 * projection of glm_perspective/glm_frustum/glm_ortho's form (finite far,
 * depth -1 near to 1 far, no oblique or mirrored plane). */
static int standard_pair(const float *v, const float *p)
{
    int i, j;
    int persp = p[11] == -1.0f && p[15] == 0.0f && p[10] < -1.0f && p[14] < 0.0f && p[12] == 0.0f && p[13] == 0.0f;
    int ortho = p[11] == 0.0f && p[15] == 1.0f && p[10] < 0.0f && p[8] == 0.0f && p[9] == 0.0f;
    if (!(persp || ortho) || p[3] != 0.0f || p[7] != 0.0f || !(p[0] > 0.0f) || !(p[5] > 0.0f) || p[1] != 0.0f ||
        p[2] != 0.0f || p[4] != 0.0f || p[6] != 0.0f || v[3] != 0.0f || v[7] != 0.0f || v[11] != 0.0f ||
        v[15] != 1.0f)
        return 0;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            float d = v[i] * v[j] + v[4 + i] * v[4 + j] + v[8 + i] * v[8 + j];
            if (fabsf(d - (i == j)) > 1e-5f) return 0;
        }
    return v[0] * (v[5] * v[10] - v[6] * v[9]) - v[4] * (v[1] * v[10] - v[2] * v[9]) +
               v[8] * (v[1] * v[6] - v[2] * v[5]) > 0.0f;
}

/* A rigid view and a standard projection (glm's forms) with the same pixel
 * of every world point as projection x view, judged by that product alone.
 * Perspective: the eye is where clip x, y and w vanish, the view axis the
 * gradient of w; near and far where the host's depth reaches its near and
 * far values along the axis and the frustum's corner rays (an oblique near
 * plane: the nearest; an infinite far: 1e7 times the near). Orthographic:
 * the axis is where x and y stay put, looking along y x x (a mirrored
 * orthographic view cannot be told from a reversed-Z one turned round).
 * Returns SNELL__CAMERA_* flags, or -1 with *why. */
static int standardize(const float *view, const float *proj, float eye[3], float v[16], float p[16], double *near_out,
                       char *why, size_t n)
{
    double m[4][4], e[3], y[3], fwd[3], up[3], right[3], s = 1.0, z0, near_ = HUGE_VAL, far_ = 0.0;
    int i, j, k, flags = 0, ortho, infinite = 0;
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++)
            for (m[i][j] = 0.0, k = 0; k < 4; k++) m[i][j] += (double)proj[4 * k + i] * view[4 * j + k];
    ortho = m[3][0] == 0.0 && m[3][1] == 0.0 && m[3][2] == 0.0;
    if (ortho) {
        if (!(m[3][3] > 0.0)) {
            snprintf(why, n, "is orthographic with clip w %g <= 0: every point is clipped (a negated matrix?)", m[3][3]);
            return -1;
        }
        for (i = 0; i < 3; i++)
            for (j = 0; j < 4; j++) m[i][j] /= m[3][3];
        cross3(m[1], m[0], fwd); /* x right, y up: it looks along y x x */
        if (dot3(fwd, m[2]) < 0.0) flags |= SNELL__CAMERA_REVERSED;
        y[0] = -m[0][3], y[1] = -m[1][3], y[2] = (flags ? 1.0 : -1.0) - m[2][3];
        solve3(m[0], m[1], m[2], y, e); /* the near plane's centre */
    } else {
        y[0] = -m[0][3], y[1] = -m[1][3], y[2] = -m[3][3];
        solve3(m[0], m[1], m[3], y, e);
        memcpy(fwd, m[3], sizeof fwd);
        s = sqrt(dot3(fwd, fwd));
    }
    unit3(fwd);
    for (k = 0; k < 3; k++) up[k] = m[1][k] - dot3(m[1], fwd) * fwd[k];
    unit3(up);
    cross3(fwd, up, right);
    memset(v, 0, 16 * sizeof *v);
    memset(p, 0, 16 * sizeof *p);
    for (k = 0; k < 3; k++) {
        v[4 * k] = (float)right[k], v[4 * k + 1] = (float)up[k], v[4 * k + 2] = (float)-fwd[k];
        eye[k] = (float)e[k];
    }
    v[12] = (float)-dot3(right, e), v[13] = (float)-dot3(up, e), v[14] = (float)dot3(fwd, e), v[15] = 1.0f;
    p[0] = (float)(dot3(m[0], right) / s), p[4] = (float)(dot3(m[0], up) / s), p[8] = (float)(-dot3(m[0], fwd) / s);
    p[5] = (float)(dot3(m[1], up) / s), p[9] = (float)(-dot3(m[1], fwd) / s);
    if (p[0] < 0.0f) flags |= SNELL__CAMERA_MIRRORED;
    if (ortho) {
        far_ = 2.0 / fabs(dot3(m[2], fwd));
        p[10] = (float)(-2.0 / far_), p[14] = -1.0f, p[15] = 1.0f;
        *near_out = HUGE_VAL;
        return flags;
    }
    /* Along the eye ray of depth 1 through ndc (cx, cy): ndc z = z0 / (s D) + a. */
    z0 = m[2][0] * e[0] + m[2][1] * e[1] + m[2][2] * e[2] + m[2][3];
    if (z0 == 0.0) {
        snprintf(why, n, "puts the near plane through the eye");
        return -1;
    }
    if (z0 > 0.0) flags |= SNELL__CAMERA_REVERSED;
    for (k = 0; k < 5; k++) {
        double cx = k ? ((k & 1) ? 1.0 : -1.0) : 0.0, cy = k ? ((k & 2) ? 1.0 : -1.0) : 0.0, d[3], a, dn, df;
        double ye = (cy + p[9]) / p[5], xe = (cx + p[8] - p[4] * ye) / p[0];
        for (j = 0; j < 3; j++) d[j] = xe * right[j] + ye * up[j] + fwd[j];
        a = dot3(m[2], d) / s;
        dn = z0 / (s * ((z0 > 0.0 ? 1.0 : -1.0) - a));
        df = z0 / (s * ((z0 > 0.0 ? -1.0 : 1.0) - a));
        if (dn > 0.0) near_ = fmin(near_, dn);
        if (df > 0.0) far_ = fmax(far_, df);
        else infinite = 1;
    }
    *near_out = near_;
    if (!(near_ < HUGE_VAL)) {
        snprintf(why, n, "has no near plane in front of the eye");
        return -1;
    }
    if (infinite || far_ > 1e7 * near_) far_ = 1e7 * near_;
    p[10] = (float)(-(far_ + near_) / (far_ - near_));
    p[14] = (float)(-2.0 * far_ * near_ / (far_ - near_));
    p[11] = -1.0f;
    return flags;
}

int snell__camera_standard(const snell_camera *cam, float aspect, float eye[3], float view[16], float proj[16])
{
    snell_camera c;
    float v[16], p[16], e[3];
    double near_;
    char why[8];
    int flags;
    snell__camera_defaults(cam, &c);
    snell_camera_matrices(&c, aspect, eye, view, proj);
    if (c.kind != SNELL_CAMERA_MATRICES || standard_pair(c.view, c.projection)) return 0;
    flags = standardize(c.view, c.projection, e, v, p, &near_, why, sizeof why);
    if (flags < 0) return 0; /* refused by snell__camera_validate */
    if (eye) memcpy(eye, e, sizeof e);
    if (view) memcpy(view, v, sizeof v);
    if (proj) memcpy(proj, p, sizeof p);
    return flags;
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
    glm_mat4_mul(a, b, vp);
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
