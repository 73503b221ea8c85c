/* SPDX-License-Identifier: MIT */
/* gbuffer.h — the screen-space stage (docs/ARCHITECTURE.md "One frame"): the front surface
 * of the glass objects shaded in screen space, drawn once with a trivial
 * shader (gbuffer.frag) into two RGBA8 textures (the normal in 16+16 bits;
 * the depth in 24 bits and the object id in 8) and, for an offscreen target,
 * the target's own depth buffer, so the kernels, which run on a full-screen
 * triangle, scissored to each object (common/surface.glsl). Resources are
 * made on the first frame that uses the stage. */
#ifndef SNELL_GBUFFER_H
#define SNELL_GBUFFER_H

#include "frame/method.h"


/* The back-face pass may draw a mesh's coarse copy (a quarter of its
 * triangles, within 1% of its extent: snell__mesh_coarse) when its front
 * triangles are estimated below this many pixels each and its method's
 * back_detail parameter allows (snell__object.back_coarse): the pass
 * rasterises every back triangle again and is bound by triangle setup on
 * llvmpipe there (bench/notes/history.md "Oliveira"). The same crossover as
 * single-surface's screen-space rule. */
#define SNELL__BACK_COARSE_PPT 8.0f


typedef struct snell__gbuffer {
    unsigned fbo, normal_tex, depth_id_tex;
    unsigned own_depth_rb;          /* for targets whose depth buffer cannot be attached */
    unsigned attached_depth;        /* the renderbuffer attached now */
    int width, height;
    unsigned prog;
    int u_model, u_normal_matrix, u_view_proj, u_gid;
    unsigned aux_tex, prog_aux;     /* the aux target and the program that writes it, made on first use */
    int ua_model, ua_normal_matrix, ua_view_proj, ua_gid;
    int band;                       /* back-face maps: the guard band they were made with (pixels per side) */
} snell__gbuffer;

void snell__gbuffer_destroy(snell__gbuffer *g);
/* Draws the front surfaces of objects[0..count-1] (uploaded) into the
 * G-buffer, with ids o->gid (snell__gbuffer_publish hands its maps on).
 * target_depth: the target's depth renderbuffer, which already holds the
 * opaque objects (tested and written, not cleared), or 0: a depth buffer of
 * the G-buffer's own. */
snell_status snell__gbuffer_draw(snell_ctx *ctx, snell__gbuffer *g, const snell__view *v, snell__object *const *objects,
                                 int count, unsigned target_depth, snell_object_stats *stats);
/* Publishes the maps (frame/textures.h) for the programs that read them:
 * the front G-buffer's as u_gnormal, u_gdepth_id and u_gaux (where drawn),
 * the back-face pass's (back) as u_bnormal and u_bdepth_id. */
void snell__gbuffer_publish(const snell__gbuffer *g, snell__textures *ts, int back);
/* The back-face pass (wyman, oliveira): the
 * farthest surface of objects[0..count-1] (depth GREATER into a depth buffer
 * of its own, cleared to 0, front faces culled where the winding is known;
 * opaque objects are not tested: a back face behind one is still where the
 * light leaves) as the G-buffer stores the front: normal, window depth + id
 * o->gid. Overlapping objects: the farther
 * one's back faces win the texel (the nearer sees another id there). g is a
 * G-buffer of its own (made on first use). band > 0: a guard band of that
 * many pixels on every side is drawn too (the projection widened), for
 * objects whose light leaves past the target's edge; the maps keep the
 * largest band asked for. *maps says how to address them this frame. */
snell_status snell__gbuffer_draw_back(snell_ctx *ctx, snell__gbuffer *g, const snell__view *v,
                                      snell__object *const *objects, int count, int band, snell__back_maps *maps,
                                      snell_object_stats *stats);
/* How a device shades, for the AUTO shading rule; found once per renderer. */
typedef enum snell__device_class {
    SNELL__DEVICE_SOFTWARE = 0,     /* software rasteriser: 4x4 blocks */
    SNELL__DEVICE_TILER,            /* tile-based GPU: an extra pass costs memory bandwidth */
    SNELL__DEVICE_IMMEDIATE         /* other GPUs: 2x2 quads */
} snell__device_class;

snell__device_class snell__device_class_of(const char *gl_renderer);
/* The AUTO shading rule's threshold for a device and a method, on a convex
 * mesh or not: objects whose front triangles cover fewer (estimated) pixels
 * each than this are shaded in screen space. */
float snell__screen_threshold(snell__device_class device, const snell__method *method, int convex);
/* Projects o's bounding sphere once per frame into o->pixels_per_triangle
 * (per front triangle) and o->scissor (window pixels x, y, w, h; the whole
 * target if the sphere reaches the eye's plane). */
void snell__object_project(const snell__view *v, snell__object *o);

#endif
