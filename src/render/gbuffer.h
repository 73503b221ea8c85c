/* gbuffer.h — the screen-space stage (DESIGN.md "frame"): the front surface
 * of the glass objects shaded in screen space, drawn once with a trivial
 * shader (gbuffer.frag) into two RGBA8 textures (the normal in 16+16 bits;
 * the depth in 24 bits and the object id in 8) and, for an offscreen target,
 * the target's own depth buffer, so the kernels, which run on a full-screen
 * triangle, scissored to each object (common/surface.glsl). Resources are
 * made on the first frame that uses the stage. */
#ifndef SNELL_GBUFFER_H
#define SNELL_GBUFFER_H

#include "methods/method.h"

/* Texture units the G-buffer is bound to while kernels shade (0: env, 1: a
 * kernel's own texture). */
#define SNELL__GBUFFER_UNIT_NORMAL 2
#define SNELL__GBUFFER_UNIT_DEPTH_ID 3

/* How a screen-space kernel gets its depth into the target (snell__object.screen_space). */
#define SNELL__SCREEN_SHARED_DEPTH 1  /* the G-buffer pass wrote the target's own depth buffer */
#define SNELL__SCREEN_WRITES_DEPTH 2  /* the G-buffer had its own; the kernel writes gl_FragDepth */

typedef struct snell__gbuffer {
    unsigned fbo, normal_tex, depth_id_tex;
    unsigned own_depth_rb;          /* for targets whose depth buffer cannot be attached */
    unsigned attached_depth;        /* the renderbuffer attached now */
    int width, height;
    unsigned prog;
    int u_model, u_normal_matrix, u_view_proj, u_gid;
} snell__gbuffer;

void snell__gbuffer_destroy(snell__gbuffer *g);
/* Draws the front surfaces of objects[0..count-1] (uploaded) into the
 * G-buffer, with ids o->gid, and binds its textures on the units above.
 * target_depth: the target's depth renderbuffer, which already holds the
 * opaque objects (tested and written, not cleared), or 0: a depth buffer of
 * the G-buffer's own. */
snell_status snell__gbuffer_draw(snell_ctx *ctx, snell__gbuffer *g, const snell__view *v, snell__object *const *objects,
                                 int count, unsigned target_depth, snell_object_stats *stats);
/* The AUTO shading rule's threshold for a GL_RENDERER string and a method:
 * objects whose front triangles cover fewer (estimated) pixels each than
 * this are shaded in screen space. */
float snell__screen_threshold(const char *gl_renderer, const snell__method *method);
/* Pixels per front triangle of o seen in v (projected bounding sphere). */
float snell__pixels_per_triangle(const snell__view *v, const snell__object *o);
/* The object's scissor rectangle in window pixels (x, y, w, h): its
 * bounding sphere's projection, the whole target if it reaches the eye's plane. */
void snell__object_scissor(const snell__view *v, const snell__object *o, int rect[4]);

#endif
