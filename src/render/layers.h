/* SPDX-License-Identifier: MIT */
/* layers.h — the scene layers (docs/ARCHITECTURE.md "One frame"): what a ray
 * sees after it leaves a glass object, when the frame has other objects for it to
 * meet. Every drawn solid glass and opaque object is depth peeled together into
 * one RGBA8 texture array (normal in slice 2k, depth and object id in 2k + 1)
 * with a small RGBA32F table of each id's optics; common/beyond.glsl marches
 * exit rays through them. At most SNELL_MAX_SCENE_LAYERS peels, whatever the
 * number of objects. More: docs/ARCHITECTURE.md, "Design notes by file". */
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
    snell__peel_targets t;      /* the layers (frame/peel_targets.h) */
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
