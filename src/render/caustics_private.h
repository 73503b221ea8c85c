/* SPDX-License-Identifier: MIT */
/* caustics_private.h — what the caustics stage's modules share: caustics.c
 * (the stage), caustics_maps.c (the light frame and its maps),
 * caustics_photons.c (light through the glass), caustics_receiver.c (the
 * receivers in the view, the kernels' hook). */
#ifndef SNELL_CAUSTICS_PRIVATE_H
#define SNELL_CAUSTICS_PRIVATE_H

#include "render/caustics.h"
#include "core/gl.h"

/* The depth bias of the shadow look-ups (plane, opaque objects), shadow map units. */
#define SNELL__CAUSTICS_SHADOW_BIAS 2e-4f

/* The frame's light, resolved: unit direction (directional) or position,
 * unit axis and cone (spot), and its colour (all zero = 1). */
typedef struct snell__caustics_light {
    int spot;
    float d[3], pos[3], cos_cone, col[3];
} snell__caustics_light;

/* The light frame: the one view from the light that the shadow map, the
 * opaque receivers' depth map and their caustic map share (directional:
 * orthographic along the light; spot: a perspective view from it looking
 * straight down), its window holding the receiver plane's corners and the
 * opaque receivers' bounding spheres. */
typedef struct snell__caustics_frame {
    mat4 vp;
    float near_, far_;
    float texel;  /* the larger side of a texel (directional: world; spot: on the plane at distance 1) */
    float area;   /* a texel's area, in the same units */
    float reach;  /* the longest way a photon is marched when no plane ends it */
    int size;
} snell__caustics_frame;

/* What the photons took, for the stage's reason: the casting objects, those
 * that shot any (shot; a spot light inside a bounding sphere shoots none),
 * by a BVH, by the chain path (chained, in groups, chain_shot of them shot),
 * and those left alone as more than SNELL__CAUSTICS_CHAIN overlapped. */
typedef struct snell__caustics_counts {
    int casters, shot, by_bvh, chained, groups, chain_shot, alone_over;
} snell__caustics_counts;

/* caustics.c */
int snell__caustics_casts(const snell__object *o);

/* caustics_maps.c */
snell_status snell__caustics_complete(snell_ctx *ctx, const char *what);
void snell__caustics_resolve_light(const snell_light *l, snell__caustics_light *o);
void snell__caustics_spot_view(const float eye[3], const float target[3], const float lo[2], const float hi[2],
                               float near_, float far_, mat4 vp);
void snell__caustics_light_view(const float d[3], const float centre[3], float back, float lo[2], float hi[2],
                                float near_, float far_, mat4 vp);
void snell__caustics_draw_mesh(GLuint prog, const snell_mesh *m, const float *model, const float vp[16]);
void snell__caustics_plane_uniform(GLuint prog, const snell_receiver *rc);
void snell__caustics_light_uniforms(GLuint prog, const snell__caustics_light *L);
void snell__caustics_frame_uniforms(GLuint prog, const snell__caustics *c);
void snell__caustics_make_frame(const snell_frame_desc *fd, const snell__scene *sc, const snell__caustics_light *L,
                                snell__caustics_frame *F);
snell_status snell__caustics_map_target(snell_ctx *ctx, snell__caustics *c, int size);
snell_status snell__caustics_draw_shadows(snell_ctx *ctx, snell__caustics *c, const snell_frame_desc *fd,
                                          const snell__scene *sc, const snell__caustics_frame *F);
snell_status snell__caustics_draw_receivers(snell_ctx *ctx, snell__caustics *c, const snell_frame_desc *fd,
                                            const snell__caustics_frame *F);
void snell__caustics_draw_direct(snell__caustics *c, const snell_frame_desc *fd, const snell__caustics_light *L,
                                 const snell__caustics_frame *F);

/* caustics_photons.c */
snell_status snell__caustics_glass_targets(snell_ctx *ctx, snell__caustics *c, int size);
snell_status snell__caustics_photons(snell_ctx *ctx, snell__caustics *c, const snell_frame_desc *fd,
                                     const snell__scene *sc, const snell__caustics_light *L,
                                     const snell__caustics_frame *F, snell_frame_stats *s, snell__caustics_counts *n);

/* caustics_receiver.c */
snell_status snell__caustics_draw_view(snell__caustics *c, const snell_frame_desc *fd, const snell__scene *sc);

#endif
