/* caustics.h — the caustics stage (render/caustics.c): light refracted
 * through the glass onto a receiver plane as a light map (photons from the
 * light, splatted flux-correct), the direct light shadowed by every object,
 * and the receiver drawn in the view with it; reused while nothing moved. */
#ifndef SNELL_CAUSTICS_H
#define SNELL_CAUSTICS_H

#include "render/scene.h"

#define SNELL__CAUSTICS_KEY 4096 /* floats of the reuse key */
#define SNELL__CAUSTICS_NO_FLOAT 1u /* map_format: probed, no float target (the stage is skipped) */

typedef struct snell__caustics {
    unsigned map_prog, photon_prog, direct_prog, receiver_prog, vao;
    unsigned glass_fbo[2], glass_n[2], glass_z[2]; /* nearest and farthest surfaces from the light */
    int glass_size;
    unsigned shadow_fbo, shadow_z;
    int shadow_size;
    unsigned map_fbo, map_tex;                     /* the receiver's light map (float rgba) */
    int map_size;
    unsigned map_format;                           /* GL_RGBA32F or GL_RGBA16F, SNELL__CAUSTICS_NO_FLOAT,
                                                    * 0 = not probed yet (tests set it to take a path) */
    int valid;                                     /* the map holds the frame keyed by key[] */
    int key_len;
    float key[SNELL__CAUSTICS_KEY];
    float scratch[SNELL__CAUSTICS_KEY];
} snell__caustics;

/* Validates a frame's light and receiver (zero = none); SNELL_E_INVALID_ARG naming the field. */
snell_status snell__caustics_validate(snell_ctx *ctx, const snell_frame_desc *fd);

/* Whether the frame has a light and a receiver or water; else why not in why. */
int snell__caustics_wanted(const snell_frame_desc *fd, char *why, size_t n);

/* Makes (or reuses) the light map and draws the receiver into the bound
 * framebuffer with view_proj (depth-tested, depth written). */
snell_status snell__caustics_run(snell_ctx *ctx, snell__caustics *c, const snell_frame_desc *fd,
                                 const snell__scene *sc, snell_frame_stats *s);

/* The light map as last made: size x size texels of rgba floats (rgb the
 * receiver's irradiance, a the mean of the light through glass), row 0 at
 * z = center - extent, x growing along the row. SNELL_E_INVALID_ARG if none. */
snell_status snell__caustics_read(snell_ctx *ctx, snell__caustics *c, float *rgba, int *size);

void snell__caustics_destroy(snell__caustics *c);

#endif
