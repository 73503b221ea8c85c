/* SPDX-License-Identifier: MIT */
/* camera.h — validation of an orbit camera (snell_camera), shared by the
 * renderer and the reference tracer so both refuse the same values, and of
 * model matrices. */
#ifndef SNELL_CAMERA_H
#define SNELL_CAMERA_H

#include "core/core.h"

/* An orbit camera with every default applied where it is 0: distance,
 * fov_y, and z_near and z_far derived from the distance (0.01 and 100 times
 * it); a SNELL_CAMERA_MATRICES camera as given. in NULL: the default camera. */
void snell__camera_defaults(const snell_camera *in, snell_camera *out);

/* Checks the camera as snell__camera_defaults resolves it: SNELL_OK, or
 * SNELL_E_INVALID_ARG with a message "who: camera.FIELD ..." naming the
 * field and its resolved value: every value finite, distance > 0,
 * 0 < fov_y < pi, z_near and z_far > 0 with the near plane (given or
 * derived) before the far one, and finite matrices for the given aspect (a
 * distance so large that the derived far plane overflows is refused). cam
 * NULL = all defaults. */
snell_status snell__camera_validate(const snell_ctx *ctx, const snell_camera *cam, float aspect, const char *who);

/* 1 if the column-major projection p is orthographic (bottom row 0 0 0 w):
 * every view ray runs along the camera's axis. */
int snell__projection_orthographic(const float p[16]);

#endif
