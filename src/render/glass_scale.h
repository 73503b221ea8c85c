/* glass_scale.h — a glass object shaded at a resolution scale
 * (snell_glass_material.scale): its method's passes and kernel drawn at
 * 1/scale of the frame's sample grid per axis into a target of this
 * module's, then its faces at full resolution taking their colour from it
 * (glass_scale.frag), depth-tested as any forward object. */
#ifndef SNELL_GLASS_SCALE_H
#define SNELL_GLASS_SCALE_H

#include "frame/method.h"

typedef struct snell__glass_scale {
    unsigned fbo, color_tex, depth_tex; /* the small target, kept while it fits (a grid uses its corner) */
    int width, height;
    unsigned prog;                      /* glass_scale.frag, made on first use */
    int u_model, u_normal_matrix, u_view_proj, u_color, u_depth, u_ratio, u_max, u_inv_proj_z;
} snell__glass_scale;

/* The scale the object is drawn at by method m in output `out`: its
 * material's, or 1 where the method reads the frame's full-resolution back
 * faces or screen-space G-buffer, or the output is exit directions (an
 * interpolated direction is no path's). */
float snell__glass_scale_of(const snell__method *m, snell__output_kind out, const snell__object *o);

/* What draws the object's method into the bound target (render/stages.c). */
typedef snell_status (*snell__glass_draw_fn)(void *user, const snell__view *v, const snell__object *o,
                                             snell_object_stats *st);

/* Draws forward object o (o->scale > 1) at its scale: draw() at the small
 * grid into this module's target over the object's rectangle, then its
 * faces into the bound target (depth test LESS, depth write) coloured
 * from it. */
snell_status snell__glass_scale_draw(snell_ctx *ctx, snell__glass_scale *gs, const snell__view *v,
                                     const snell__object *o, snell_object_stats *st, snell__glass_draw_fn draw,
                                     void *user);
void snell__glass_scale_destroy(snell__glass_scale *gs);

#endif
