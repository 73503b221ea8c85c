/* SPDX-License-Identifier: MIT */
/* env_paraboloid.h — dual-paraboloid environment maps (Dachsbacher 2002,
 * seed 003; Heidrich and Seidel 1998): two 180-degree maps, +Z and -Z, made
 * on the GPU from a cubemap into the two layers of one RGBA8 2D array
 * texture, looked up by common/env.glsl's SNELL_ENV_DUAL_PARABOLOID variant. */
#ifndef SNELL_ENV_PARABOLOID_H
#define SNELL_ENV_PARABOLOID_H

#include "core/core.h"

/* Texels between the rim circle and the texture edge (common/env.glsl's
 * SNELL_DP_MARGIN): a bilinear look-up on the rim reads only texels that hold
 * their own direction's radiance. */
#define SNELL__DP_MARGIN 2.0

/* The generator: its program and framebuffer, made on first use. */
typedef struct snell__paraboloid_gen {
    unsigned prog, fbo;
    int u_layer, u_size, u_env;
} snell__paraboloid_gen;

void snell__paraboloid_gen_destroy(snell__paraboloid_gen *g);

/* The maps' side for a cube of face size n: 2n (the coarsest paraboloid
 * texel, at the axis, then spans the solid angle of the coarsest cube
 * texel, at a face centre), at most 4096 and GL_MAX_TEXTURE_SIZE. */
int snell__paraboloid_size(int cube_size);

/* Texture coordinate (u, v in [0,1]) and layer (0: +Z, 1: -Z) of a
 * direction in size^2 maps, and its inverse (continued past the rim): the C
 * twins of common/env.glsl's snell_dp_coords and snell_dp_dir. */
void snell__dp_coords(const double dir[3], int size, double *u, double *v, int *layer);
void snell__dp_dir(double u, double v, int layer, int size, double dir[3]);

/* *tex made (if 0, or of another size than *tex_size): a size^2 x 2 RGBA8 2D
 * array, GL_LINEAR, CLAMP_TO_EDGE; left bound to GL_TEXTURE_2D_ARRAY if made. */
void snell__paraboloid_texture(int size, unsigned *tex, int *tex_size);

/* Draws map `layer` (0: +Z, 1: -Z) of size^2 maps from the cubemap cube
 * into the bound framebuffer at the far plane (depth 1: a LEQUAL test keeps
 * what is nearer), binding its program, cube on unit 0 and no vertex array. */
snell_status snell__paraboloid_draw_layer(snell_ctx *ctx, snell__paraboloid_gen *g, unsigned cube, int layer,
                                          int size);

/* Makes *tex (if 0, or its size changed: a size^2 x 2 RGBA8 2D array,
 * GL_LINEAR, CLAMP_TO_EDGE) and renders both layers from the cubemap cube.
 * Leaves the framebuffer, viewport, depth state, vertex array and texture
 * unit 0's cube and array bindings as they were (the program is its own). */
snell_status snell__paraboloid_from_cube(snell_ctx *ctx, snell__paraboloid_gen *g, unsigned cube, int size,
                                         unsigned *tex, int *tex_size);

/* The static environment's maps, made from its cube on first use and kept
 * with it (freed by snell_env_destroy). */
snell_status snell__env_paraboloid(snell_ctx *ctx, snell__paraboloid_gen *g, const snell_env *env, unsigned *tex);

#endif
