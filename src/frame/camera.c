/* SPDX-License-Identifier: MIT */
/* camera.c — the camera shared by the renderer, the references and the
 * CLI: an orbit (eye on a sphere around the target, +Y up) or the host's
 * matrices, GL clip conventions. */
#include "frame/camera.h"

#include <cglm/cglm.h>
#include <math.h>
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
