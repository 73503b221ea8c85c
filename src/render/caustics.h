/* SPDX-License-Identifier: MIT */
/* caustics.h — the caustics stage (render/caustics.c): light refracted
 * through the glass onto a receiver plane as a light map and onto the opaque
 * objects as a light-space caustic map (photons from the light, splatted
 * flux-correct), the direct light shadowed by every object, and the
 * receivers drawn in the view with it; reused while nothing moved. */
#ifndef SNELL_CAUSTICS_H
#define SNELL_CAUSTICS_H

#include "render/prepared.h"
#include "render/scene.h"
#include "frame/beyond.h"
#include "frame/stage.h"

#define SNELL__CAUSTICS_KEY 4096 /* floats of the reuse key */


typedef struct snell__caustics {
    unsigned map_prog, photon_prog, direct_prog, receiver_prog, opaque_prog, vao;
    unsigned photon_bvh_prog[2][2];                /* photons by exact's BVH: [q16 nodes][stack walk] */
    unsigned photon_chain_prog;                    /* photons through the overlapping casters in sequence */
    void *chain_bvh;                               /* their world-space BVH (snell__gpu_bvh_make) */
    float *chain_geo;                              /* its merged mesh: positions then normals (world) */
    uint32_t *chain_idx;                           /* and triangles */
    size_t chain_geo_cap, chain_idx_cap;           /* floats, indices allocated */
    snell_alloc chain_alloc;                       /* they were allocated with */
    unsigned glass_fbo[2], glass_n[2], glass_z[2]; /* nearest and farthest surfaces from the light */
    int glass_size;
    unsigned shadow_fbo, shadow_z;
    int shadow_size;
    unsigned recv_fbo, recv_z;                     /* opaque receivers' nearest depth in the light frame */
    unsigned cm_fbo, cm_tex;                       /* their light-space caustic map (map_format) */
    int recv_size;
    float frame_vp[16];                            /* world -> the light frame (shadow map, receivers) */
    float frame_lin[4];                            /* its near, far, 1 = perspective, texel side */
    unsigned map_fbo, map_tex;                     /* the receiver's light map (float rgba) */
    int map_size;
    int maps_only;                                 /* tests, bench_caustics: every photon takes the depth
                                                    * maps' one crossing (the only path before the BVH's),
                                                    * each caster alone (no chain) */
    unsigned map_format;                           /* snell__light_map_format (core/light_map.h),
                                                    * 0 = not probed yet (tests set it to take a path) */
    int valid;                                     /* the maps hold the frame keyed by key[] */
    int made_plane, made_opaque;                   /* which of them it made (the plane's, the opaque ones') */
    snell_light light;                             /* the light they were made with */
    int frame_plane, frame_opaque;                 /* this frame lit the plane, the opaque objects (the
                                                    * kernels' hook SNELL_RECEIVER; cleared at its plan) */
    float frame_plane_rect[4], frame_albedo[3];    /* the lit plane's y, centre x, z, extent (0 none); albedo */
    unsigned made;                                 /* maps made so far: which lighting a dynamic environment
                                                    * drawn lit by them shows (render/env_dynamic.c) */
    int key_len;
    float key[SNELL__CAUSTICS_KEY];
    float scratch[SNELL__CAUSTICS_KEY];
} snell__caustics;

/* Validates a frame's light and receiver (zero = none); SNELL_E_INVALID_ARG naming the field. */
snell_status snell__caustics_validate(snell_ctx *ctx, const snell_frame_desc *fd);

/* Whether the frame has a light and a receiver (the plane, opaque objects) or water; else why not in why. */
int snell__caustics_wanted(const snell_frame_desc *fd, char *why, size_t n);

/* Makes (or reuses) the light maps and draws the receiver plane (depth-tested,
 * depth written) and the opaque objects lit (over what the opaque stage drew,
 * depth LEQUAL) into the bound framebuffer with the view's view_proj;
 * concave glass's photons walk the mesh's BVH (mesh/bvh_gpu.h). */
snell_status snell__caustics_run(snell_ctx *ctx, snell__caustics *c,
                                 const snell_frame_desc *fd, const snell__scene *sc, snell_frame_stats *s);

/* The light map as last made: size x size texels of rgba floats (rgb the
 * receiver's irradiance, a the mean of the light through glass), row 0 at
 * z = center - extent, x growing along the row. SNELL_E_INVALID_ARG if none. */
snell_status snell__caustics_read(snell_ctx *ctx, snell__caustics *c, float *rgba, int *size);

/* The opaque receivers' light-space caustic map as last made: size x size
 * texels of rgba floats (flux per texel area facing the light).
 * SNELL_E_INVALID_ARG if none. */
snell_status snell__caustics_read_opaque(snell_ctx *ctx, snell__caustics *c, float *rgba, int *size);

/* The glass kernels' hook SNELL_RECEIVER (common/receiver.glsl,
 * common/opaque_lit.glsl): their exit and reflected rays meet the plane lit
 * by the stage, and the opaque objects they meet through the scene layers
 * are lit as the view sees them. snell__receiver_view keeps what the stage
 * lit this frame in c for the hook, after the stage ran (nothing without
 * them, or in a build without the stage: the hook then takes no program),
 * and publishes their maps (u_plane_map; u_shadow, u_recv_z, u_caustic) in
 * v->textures. */
#define SNELL__RECEIVER_UNIFORMS 3
extern const snell__kernel_hook snell__receiver_hook;
void snell__receiver_view(snell__view *v, snell__caustics *c, const snell_receiver *rc);

/* common/opaque_lit.glsl's uniforms (the light, c's shadow and caustic maps
 * on units unit..unit + 2; unit < 0: the program binds the maps itself, as
 * the kernels do from the view's textures) into prog, in use: the opaque
 * objects lit as this frame's caustics stage lit them (caustics_opaque.frag;
 * a dynamic environment's faces, render/composite.c; the kernels' hook). */
void snell__lit_opaque_uniforms(unsigned prog, const snell__caustics *c, int unit);

void snell__caustics_destroy(snell__caustics *c);

#endif
