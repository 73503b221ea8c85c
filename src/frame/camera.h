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

/* What snell__camera_standard found in the host's matrices. */
#define SNELL__CAMERA_MIRRORED 1 /* the image is a standard camera's flipped in x: the winding flips */
#define SNELL__CAMERA_REVERSED 2 /* reversed-Z: the host's depth runs from 1 near to 0 far */
#define SNELL__CAMERA_CHANGED 4  /* the matrices are snell's standard ones, not the host's */
#define SNELL__CAMERA_OBLIQUE 8  /* the host's depth is tilted (an oblique near plane): not snell's */

/* The camera as snell draws it: snell_camera_matrices, except that host
 * matrices (a validated SNELL_CAMERA_MATRICES camera) not of glm's standard
 * forms become a rigid view and a standard projection with the same pixel of
 * every point, judged by projection x view alone: reversed-Z, an infinite far
 * plane, an oblique near plane, a scaled or mirrored view. Returns
 * SNELL__CAMERA_* flags. */
int snell__camera_standard(const snell_camera *cam, float aspect, float eye[3], float view[16], float proj[16]);

/* Where snell__camera_standard changed a host camera that is not oblique,
 * its window depth and the host's are affine functions of each other (both
 * of 1/z along the same axis; of z orthographic): snell's = map[0] x the
 * host's + map[1]. Returns 0 when the depths agree already (to 1e-6). */
int snell__camera_depth_map(const snell_camera *cam, float aspect, double map[2]);

/* 1 if the column-major projection p is orthographic (bottom row 0 0 0 w):
 * every view ray runs along the camera's axis. */
int snell__projection_orthographic(const float p[16]);

#endif
