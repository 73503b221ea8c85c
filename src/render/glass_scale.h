/* SPDX-License-Identifier: MIT */
/* glass_scale.h — a glass object shaded at a resolution scale
 * (snell_glass_material.scale): its method's passes and kernel drawn on a
 * G-buffer of its own at 1/scale of the frame's sample grid per axis, into
 * this module's target; then the object drawn as its kernel would be at full
 * resolution (forward, or on the frame's G-buffer) taking its colour from
 * that target (glass_scale.frag). */
#ifndef SNELL_GLASS_SCALE_H
#define SNELL_GLASS_SCALE_H

#include "render/gbuffer.h"
#include "frame/glass_program.h"

typedef struct snell__glass_scale {
    unsigned fbo, color_tex, depth_tex;  /* the small target, kept while it fits (a grid uses its corner) */
    int width, height;
    snell__gbuffer gbuffer;              /* the object's front surface at the small grid */
    snell__glass_program prog[SNELL__GLASS_SHADING_MASK + 1]; /* per shading, made on first use */
    int u_ratio[SNELL__GLASS_SHADING_MASK + 1], u_max[SNELL__GLASS_SHADING_MASK + 1];
    int u_thickness[SNELL__GLASS_SHADING_MASK + 1]; /* the fallback's thin wall (glass_scale.frag) */
} snell__glass_scale;

/* The largest scale method m draws at: 1 where it reads the frame's
 * full-resolution back faces, and in a build without the scale
 * (glass_scale_off.c); AUTO by budget keeps the rungs above it off every
 * ladder (budget.c). */
int snell__glass_scale_max(const snell__method *m);

/* The scale the object is drawn at by method m in output `out`: its
 * material's, or 1 where the method reads the frame's full-resolution back
 * faces, or the output is exit directions (an interpolated direction is no
 * path's). */
float snell__glass_scale_of(const snell__method *m, snell__output_kind out, const snell__object *o);

/* What draws the object's method into the bound target (render/stages.c). */
typedef snell_status (*snell__glass_draw_fn)(void *user, const snell__view *v, const snell__object *o,
                                             snell_object_stats *st);

/* Draws object o (o->scale > 1) at its scale: its front surface into the
 * small G-buffer and draw() on it into the small target, over the object's
 * rectangle; then o as it is shaded (o->screen_space: on the frame's
 * G-buffer, as v publishes it) into the bound target coloured from the
 * small one. stats: the frame's, per object index. */
snell_status snell__glass_scale_draw(snell_ctx *ctx, snell__glass_scale *gs,
                                     const snell__view *v, const snell__object *o, snell_object_stats *stats,
                                     snell__glass_draw_fn draw, void *user);
void snell__glass_scale_destroy(snell__glass_scale *gs);

#endif
