/* SPDX-License-Identifier: MIT */
/* layers.h — the scene layers (docs/ARCHITECTURE.md "One frame"): what a ray sees
 * after it leaves a glass object, when the frame has other objects for it
 * to meet. Every drawn solid glass object and every opaque object is depth
 * peeled together (depth_peel.frag, the peel kernel's pass) into one RGBA8
 * texture array: layer k's normal (octahedral 16+16 bits) in slice 2k, its
 * depth (24 bits over the view-depth range of all their bounding spheres)
 * and its object's id (8 bits, 0 = empty) in slice 2k + 1; a small RGBA32F
 * table holds each id's optics (IOR, tint, absorption, bounding sphere;
 * opaque: IOR 0 and its albedo). The kernels' exit look-up
 * (common/beyond.glsl, SNELL_BEYOND) marches the exit ray through these
 * layers: the medium at a point is the innermost object with an odd number
 * of its surfaces in front of the point at its pixel, so a change of medium
 * along the ray is a surface crossed; it refracts into and out of the other
 * glass objects (TIR inside them), stops at an opaque one (shaded as
 * opaque.frag shades it), crosses thin walls by the slab model, and looks
 * the environment up when it leaves them all. Passes per frame: the peels, at most SNELL_MAX_SCENE_LAYERS, each
 * drawing every object once, whatever the number of objects; nothing is
 * copied per object. */
#ifndef SNELL_LAYERS_H
#define SNELL_LAYERS_H

#include "frame/method.h"
#include "frame/peel_targets.h"

#include "frame/beyond.h" /* the ids, units and uniforms its readers share */
#define SNELL__LAYERS_OPAQUE_ID0 (SNELL_MAX_GLASS + 1)
#define SNELL__LAYERS_IDS (SNELL_MAX_GLASS + SNELL_MAX_OPAQUE)
#define SNELL__LAYERS_TABLE_ROWS 4
/* Layers first made room for (snell__layers_draw grows them when full). */
#define SNELL__LAYERS_START 4

/* What the peels depend on: a frame whose key equals the last one's reuses
 * them (a still scene, a kiosk's idle frames). */
typedef struct snell__layers_key_item {
    float model[16];
    unsigned mesh_version;      /* process-unique per geometry (mesh.h) */
    int id;
} snell__layers_key_item;

typedef struct snell__layers_key {
    float view_proj[16];
    int width, height, max_layers, count;
    snell__layers_key_item item[SNELL_MAX_GLASS + SNELL_MAX_OPAQUE];
} snell__layers_key;

typedef struct snell__layers {
    unsigned prog;
    int u_model, u_normal_matrix, u_view_proj, u_eye, u_fwd, u_near, u_inv_range, u_first, u_prev, u_id;
    snell__peel_targets t;      /* the layers (render/peel_targets.h) */
    unsigned table_tex;         /* the object table, RGBA32F, made on first use */
    int grown;                  /* layers the scenes so far have needed (0: SNELL__LAYERS_START) */
    float table[SNELL__LAYERS_TABLE_ROWS][SNELL__LAYERS_IDS][4]; /* the frame's object table, uploaded */
    snell__layers_key key, last;  /* this frame's and the last peeled one's (last.count < 0: none) */
    snell__scene_layers last_layers;
} snell__layers;

void snell__layers_destroy(snell__layers *l);

/* Peels glass[0..glass_count-1] (drawn, uploaded; solid or thin walls) and
 * opaque[0..opaque_count-1] (uploaded) into up to max_layers layers, unless
 * nothing they depend on changed since the last frame (camera, models,
 * geometry versions, ids, size: *reused = 1), and binds them and the table
 * (always rewritten: materials) on the units above; fills v->layers for the
 * kernels. *passes: peels drawn. */
snell_status snell__layers_draw(snell_ctx *ctx, snell__layers *l, snell__view *v, snell__object *const *glass,
                                int glass_count, const snell_opaque *opaque, int opaque_count, int max_layers,
                                int *passes, int *reused);


#endif
