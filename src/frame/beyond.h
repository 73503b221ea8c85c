/* SPDX-License-Identifier: MIT */
/* beyond.h — the GPU side of the seam "what a ray sees past its object":
 * the uniforms of common/beyond.glsl's march through the frame's scene
 * layers (drawn by render/layers.c), which every kernel's exit rays and the
 * water's rays read. Found once per program, set every frame. */
#ifndef SNELL_BEYOND_H
#define SNELL_BEYOND_H

#include "frame/frame.h"

/* Ids: glass object i is i + 1, opaque object j is SNELL__LAYERS_OPAQUE_ID0 + j;
 * a thin-walled glass object's layers carry SNELL__LAYERS_THIN_ID more (the
 * shader tells them without a table look-up); its table column is i's. */
#define SNELL__LAYERS_THIN_ID 128

/* common/beyond.glsl's uniform locations in a program: found once, when
 * the program is built (snell__beyond_locate), set every frame. Its
 * samplers, u_scene_layers and u_scene_table, are published in the view by
 * the layers stage (render/layers.c) and bound by each program. */
typedef struct snell__beyond_locs {
    int layer_count, capped, glass_ids, opaque_count, self, view_proj, eye, fwd, near_, inv_range, size;
} snell__beyond_locs;
/* The names of those uniforms, in the struct's order. */
#define SNELL__BEYOND_UNIFORMS ((int)(sizeof(snell__beyond_locs) / sizeof(int)))
extern const char *const snell__beyond_uniform_names[SNELL__BEYOND_UNIFORMS];
void snell__beyond_locate(unsigned prog, snell__beyond_locs *l);

/* Sets those uniforms of the program in use for this frame's layers
 * (v->layers), skipping the object of layer id self (0: none). */
void snell__beyond_uniforms(const snell__beyond_locs *l, const snell__view *v, int self);

#endif
