/* camera.c — the orbit camera shared by the renderer, the references and the
 * CLI: eye on a sphere around the target, +Y up, GL clip conventions. */
#include "core/core.h"

#include <cglm/cglm.h>
#include <math.h>
#include <string.h>

void snell_camera_matrices(const snell_camera *cam, float aspect, float eye_out[3], float view_out[16],
                           float proj_out[16])
{
    snell_camera c;
    vec3 eye, target, up = {0.0f, 1.0f, 0.0f};
    mat4 view, proj;
    float ce, dist, fov, zn, zf;
    memset(&c, 0, sizeof c);
    if (cam) c = *cam;
    dist = c.distance > 0.0f ? c.distance : 3.5f;
    fov = c.fov_y > 0.0f ? c.fov_y : (float)(45.0 * SNELL_PI / 180.0);
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
    /* Near/far default to a 1e4 range around the target, enough for 24-bit depth. */
    zn = c.z_near > 0.0f ? c.z_near : dist * 0.01f;
    zf = c.z_far > zn ? c.z_far : dist * 100.0f;
    glm_lookat(eye, target, up, view);
    glm_perspective(fov, aspect, zn, zf, proj);
    if (eye_out) memcpy(eye_out, eye, sizeof(vec3));
    if (view_out) memcpy(view_out, view, sizeof(mat4));
    if (proj_out) memcpy(proj_out, proj, sizeof(mat4));
}
