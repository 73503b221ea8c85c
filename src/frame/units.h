/* units.h — the one table of texture units a frame binds while kernels draw,
 * so no module finds a free unit by reading others' headers. A new stage
 * takes the next free unit here and raises SNELL__UNIT_COUNT (the EXTERNAL
 * backend saves and restores SNELL_GLSTATE_UNITS units, core/glstate.h: the
 * check below fails the build if the table outgrows it). */
#ifndef SNELL_UNITS_H
#define SNELL_UNITS_H

#define SNELL__UNIT_ENV 0             /* the object's environment (cube, or paraboloid 2D array) */
#define SNELL__UNIT_KERNEL 1          /* the kernel's own texture (cubemap, layers, BVH, ...) */
#define SNELL__GBUFFER_UNIT_NORMAL 2  /* the screen-space stage's G-buffer (render/gbuffer.h) */
#define SNELL__GBUFFER_UNIT_DEPTH_ID 3
/* The G-buffer's aux target (RGBA8, rg: 16 bits of a per-vertex scalar of
 * objects drawn with a method VAO, snell__object.vao), made and drawn only in
 * frames where a screen-space object has one. */
#define SNELL__GBUFFER_UNIT_AUX 4
/* The back-face pass (snell__gbuffer_draw_back): the same two textures for
 * the farthest surface. */
#define SNELL__BACK_UNIT_NORMAL 5
#define SNELL__BACK_UNIT_DEPTH_ID 6
#define SNELL__LAYERS_UNIT 7          /* the scene layers (render/layers.h) */
#define SNELL__LAYERS_TABLE_UNIT 8    /* ... and their object table */
#define SNELL__WATER_HEIGHTS_UNIT 9   /* the water's heights (water/water_draw.h) */
#define SNELL__WATER_LIGHT_UNIT 10    /* ... and its floor's light map (water/water_caustics.c) */
#define SNELL__RECEIVER_UNIT 11       /* the receiver plane's light map (render/caustics.c) */
#define SNELL__UNIT_ENV_NEAREST 12   /* unit 0's environment again, through a nearest sampler (common/env.glsl
                                       * snell_env_nearest; methods/layered.c) */
/* The caustics stage's light frame, for kernels that see opaque objects lit
 * through the scene layers (common/opaque_lit.glsl; render/caustics.c's
 * hook): the shadow map, the opaque receivers' depth, their caustic map,
 * consecutive (the hook binds them from the first on). */
#define SNELL__LIT_SHADOW_UNIT 13
#define SNELL__LIT_RECV_Z_UNIT 14
#define SNELL__LIT_CAUSTIC_UNIT 15
#define SNELL__UNIT_COUNT 16 /* GLES 3.0 guarantees 16 fragment texture units */

#include "core/glstate.h"
/* The EXTERNAL backend's snapshot must cover every unit of the table. */
typedef char snell__units_fit_glstate[SNELL__UNIT_COUNT <= SNELL_GLSTATE_UNITS ? 1 : -1];

#endif
