/* SPDX-License-Identifier: MIT */
/* scene.h — the frame's scene, resolved once (docs/ARCHITECTURE.md "One frame"): camera
 * matrices, every glass object's material (the one resolve step), model
 * matrices and bounding sphere, what is skipped (outside the view,
 * passthrough), the back-to-front order, and per object the method: the
 * requested one or AUTO's walk of the registry, with the reason. */
#ifndef SNELL_SCENE_H
#define SNELL_SCENE_H

#include "frame/method.h"
#include "core/device_cost.h"

typedef struct snell__scene {
    snell__view view;
    int count;                                  /* glass objects in the frame */
    snell__object obj[SNELL_MAX_GLASS];
    snell_glass_resolved glass[SNELL_MAX_GLASS];
    int order[SNELL_MAX_GLASS], drawn;          /* objects to draw, farthest first */
} snell__scene;

/* Validates and resolves fd's glass list into sc and fills stats->glass[]
 * (view depth, skips, draw order). Allocates nothing. */
/* World-space bounding sphere of a mesh under model: centre of the
 * object-space box, radius = farthest vertex, scaled by the model's largest
 * axis scale. */
void snell__bounding_sphere(const snell_mesh *m, mat4 model, float out[4]);

snell_status snell__scene_build(snell_ctx *ctx, const snell_frame_desc *fd, int width, int height,
                                snell__output_kind out, snell__scene *sc, snell_frame_stats *stats);

/* The method state for m, created on first use (renderer.c). */
typedef snell_status (*snell__method_state_fn)(void *user, const snell__method *m, void **state);

/* The built methods in the order AUTO tries them for a mesh class
 * (render/budget.h): the registry's, its cost order on the reference
 * device; on a device with a cost model (NULL: none), by the model's cost,
 * those it does not model after, in the registry's order. Returns their count. */
int snell__auto_order(const snell__device_cost *dev, int cls, const snell__method *order[]);

/* Chooses the object's method (analysing its mesh if a candidate needs it):
 * an explicit request is honoured, with a warning if the mesh fails the
 * method's preconditions; AUTO takes the cheapest adequate method the device
 * can run (snell__auto_order), else the cheapest one that runs. Writes method_used, reason,
 * warning, hidden_fraction and SNELL_SKIP_ANALYSIS into st. */
snell_status snell__scene_choose(snell_ctx *ctx, snell__object *o, snell__method_state_fn get_state, void *user,
                                 const snell__method **method, void **state, snell_object_stats *st);

#endif
