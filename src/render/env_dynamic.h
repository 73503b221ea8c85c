/* SPDX-License-Identifier: MIT */
/* env_dynamic.h — dynamic environments (Unger 4.1): per glass object, the
 * static environment plus the opaque objects rendered into a cubemap from
 * the object's bounding-sphere centre, re-rendered only when something it
 * shows changed. One slot per position in the frame's glass list. */
#ifndef SNELL_ENV_DYNAMIC_H
#define SNELL_ENV_DYNAMIC_H

#include "render/composite.h"
#include "render/env_paraboloid.h"

typedef struct snell__env_view {
    unsigned texture;                 /* GL cubemap, 0 = none yet */
    int size;
    unsigned paraboloid;              /* its dual-paraboloid maps, made from it when asked for; 0 = none yet */
    int paraboloid_size, paraboloid_valid;
    /* what the texture shows (for the "nothing moved" skip) */
    int valid;
    const snell_env *env;
    float centre[3];
    int count;
    const snell_mesh *mesh[SNELL_MAX_OPAQUE];
    unsigned version[SNELL_MAX_OPAQUE];
    float model[SNELL_MAX_OPAQUE][16];
    float color[SNELL_MAX_OPAQUE][3];
    unsigned lit;                     /* their lighting: 0 from above, else the caustics stage's maps' `made` */
} snell__env_view;

typedef struct snell__env_dynamic {
    snell__env_view *views;           /* SNELL_MAX_GLASS, allocated on first use */
    unsigned fbo, depth_rb;
    int depth_size;
    unsigned dp_depth_rb;             /* for maps rendered directly (direct = 1) */
    int dp_depth_size;
} snell__env_dynamic;

void snell__env_dynamic_destroy(snell_ctx *ctx, snell__env_dynamic *d);

/* The cubemap glass object `slot` sees from centre: re-rendered when
 * anything changed (stats->env_updated, passes) or reused
 * (SNELL_SKIP_ENV_UPDATE). size: face size, 0 = half of env's, 16..256.
 * lit: the caustics stage that lit the opaque objects this frame (NULL:
 * none), whose lighting they are drawn with (snell__composite_opaque).
 * With dp (not NULL) *texture is instead its dual-paraboloid maps
 * (snell__paraboloid_size(size)): made from the cube after each re-render,
 * or with direct rendered straight (2 views, no cube: opaque objects projected
 * per vertex, opaque_paraboloid.vert). */
snell_status snell__env_dynamic_update(snell_ctx *ctx, snell__env_dynamic *d, snell__composite *comp, int slot,
                                       const snell_env *env, const snell_opaque *list, int count,
                                       const float centre[3], float radius, int size, snell__paraboloid_gen *dp,
                                       int direct, const struct snell__caustics *lit, unsigned *texture,
                                       snell_object_stats *stats);

#endif
