/* SPDX-License-Identifier: MIT */
/* composite.h — what is drawn around the glass: the opaque objects (diffuse,
 * lit from above, or in a dynamic environment lit by the caustics stage's
 * light) and the background (the environment through each pixel), in the
 * view or into a cube face; one program per output kind, built on first use. */
#ifndef SNELL_COMPOSITE_H
#define SNELL_COMPOSITE_H

#include "frame/method.h"

struct snell__caustics;

typedef struct snell__opaque_prog {
    unsigned prog;
    int model, normal_matrix, view_proj, eye, view_axis, color;
    int centre, layer, size, depth_range; /* opaque_paraboloid.vert's; -1 in the others */
} snell__opaque_prog;

typedef struct snell__composite {
    snell__opaque_prog opaque[SNELL__OUT_KINDS];
    snell__opaque_prog opaque_dp;   /* into a dual-paraboloid map (opaque_paraboloid.vert), colour only */
    snell__opaque_prog opaque_lit[2]; /* lit (caustics_opaque.frag) into a cube face, a dual-paraboloid map */
    unsigned sky[SNELL__OUT_KINDS][2];  /* [kind][look-up: cube, dual paraboloid] */
    int sky_inv[SNELL__OUT_KINDS][2], sky_env[SNELL__OUT_KINDS][2];
    unsigned empty_vao;             /* the background draws without attributes */
} snell__composite;

void snell__composite_destroy(snell__composite *c);
/* Builds the background program of an output kind now (it is otherwise
 * built on first use); draws nothing. */
snell_status snell__composite_prepare(snell_ctx *ctx, snell__composite *c, snell__output_kind kind);
/* Checks a frame's opaque list (count, meshes, finite models/colours). */
snell_status snell__opaque_validate(snell_ctx *ctx, const snell_opaque *list, int count);
/* Uploads the meshes (first use) and draws them with depth test LESS and
 * depth write. lit (colour output; NULL: lit from above): the caustics
 * stage that lit the opaque objects this frame (snell__frame.lit_opaque, render/stages.h),
 * whose light, shadow and caustic maps light them as the view draws them
 * (its maps on units 1..3, unit 0 left active). */
snell_status snell__composite_opaque(snell_ctx *ctx, snell__composite *c, snell__output_kind kind,
                                     const snell_opaque *list, int count, const float view_proj[16],
                                     const float eye[3], const float view_axis[4], const struct snell__caustics *lit);
/* The same straight into map `layer` (0: +Z, 1: -Z) of size^2 dual-paraboloid
 * maps about centre (render/env_paraboloid.h), depth the distance from it
 * between z_near and z_far; colour output. */
snell_status snell__composite_opaque_paraboloid(snell_ctx *ctx, snell__composite *c, const snell_opaque *list,
                                               int count, const float centre[3], int layer, int size, float z_near,
                                               float z_far, const struct snell__caustics *lit);
/* The environment cubemap bound on unit 0 drawn at the far plane under
 * LEQUAL without depth write (only where nothing was drawn); rot_view_proj
 * is proj * view without the translation. */
snell_status snell__composite_background(snell_ctx *ctx, snell__composite *c, snell__output_kind kind,
                                         const float rot_view_proj[16]);
/* The same with the environment on unit 0 as dual-paraboloid maps (a 2D
 * array, render/env_paraboloid.h) if paraboloid, else the cube; it takes
 * the inverse: a pixel's far-plane point (ndc x, y, 1, 1) through it is the
 * direction it sees. */
snell_status snell__composite_background_lookup(snell_ctx *ctx, snell__composite *c, snell__output_kind kind,
                                                int paraboloid, const float inv_rot_view_proj[16]);

#endif
