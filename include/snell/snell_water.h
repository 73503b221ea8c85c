/* SPDX-License-Identifier: MIT */
/* snell_water.h — animated water in a box container (Dachsbacher 2002,
 * "Wasser-Spiegel", PC Magazin 1/2002). A height field on a square grid,
 * simulated by the seed's eight-neighbour scheme on the CPU or the GPU, drawn as
 * one object of a frame (snell_frame_desc.water): refraction into the container,
 * the sky reflected, Schlick between the two, Beer-Lambert in the water; with a
 * light, the floor's caustics. World space: the inner box is |x|, |z| <= width/2,
 * -depth <= y <= rim; the water rests at y = 0; node (i, j) sits at
 * x = -width/2 + i dx, z = -width/2 + j dx, dx = width / (grid - 1), height
 * y = h[j * grid + i]. The longer story: docs/ARCHITECTURE.md, "Design notes by file". */
#ifndef SNELL_SNELL_WATER_H
#define SNELL_SNELL_WATER_H

#include "snell.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SNELL_WATER_MIN_GRID 64
#define SNELL_WATER_MAX_GRID 512

/* The explicit integrator's stability limit on the Courant number c dt / dx
 * (derivation in src/water/water_sim.c): 1 / sqrt(1 + sqrt 2) = 0.64359. */
#define SNELL_WATER_COURANT_LIMIT 0.6435942529055826
/* snell_water_step clamps dt to this share of the limit (exactly at the
 * limit the highest mode is marginal and grows linearly). */
#define SNELL_WATER_COURANT_SAFETY 0.99

typedef enum snell_water_sim {
    SNELL_WATER_SIM_AUTO = 0,  /* GPU when the water has a context on a hardware GPU; CPU without a
                                * context or on a software rasteriser (llvmpipe: a GPU step costs
                                * 10-25x a CPU step, bench/notes/history.md "Water") */
    SNELL_WATER_SIM_CPU,       /* C, deterministic (bitwise the same on every run and thread) */
    SNELL_WATER_SIM_GPU        /* fragment passes into ping-pong RG32UI targets (GLES 3.0, no extension) */
} snell_water_sim;

/* Zero means the documented default for every field. */
typedef struct snell_water_desc {
    int grid;                      /* nodes per side, 64..512; 0 = 128 */
    float width;                   /* inner width of the container in x and z, world units; 0 = 2 */
    float depth;                   /* depth of the floor below the rest level; 0 = 0.8 */
    float rim;                     /* height of the walls above the rest level, >= 0; 0 = 0.1 * depth */
    float wave_speed;              /* c, world units per second; 0 = 0.6 */
    float damping;                 /* velocity decay per second (v *= exp(-damping dt)); 0 = 0.4, < 0 = none */
    float ior;                     /* of the water, outside is 1; 0 = 1.333 */
    /* Beer-Lambert, named as glTF's KHR_materials_volume: the colour white
     * light turns after attenuation_distance in the water. Zero colour =
     * (0.55, 0.80, 0.85), zero distance = 1.5 world units. */
    float attenuation_color[3];
    float attenuation_distance;
    float tile_size;               /* side of the floor and wall tiles, world units; 0 = width / 8 */
    /* The surface counts as settled when every node's height is within this
     * of the mean and every |velocity| * dx / c is too (world units);
     * 0 = 1e-5 * width. A settled surface with no new drop skips its steps. */
    float settle_threshold;
    snell_water_sim sim;
    /* Texels per side of the floor's light map (a frame with a light,
     * snell_frame_desc.light: the caustics stage refracts the light through
     * the surface onto the floor); 0 = 256, 16..2048. */
    int light_map;
} snell_water_desc;

/* ctx may be NULL (CPU simulation only, not drawable: for the reference
 * tracer and tests). SIM_GPU needs ctx, current on this thread.
 * SNELL_E_INVALID_ARG naming the field for a value out of range or not finite. */
snell_status snell_water_create(snell_ctx *ctx, const snell_water_desc *desc, snell_water **out);
void snell_water_destroy(snell_water *w);

/* The resolved description (every default applied) and the simulation in use. */
void snell_water_get_desc(const snell_water *w, snell_water_desc *out);
/* Node spacing dx and the largest time step snell_water_step takes:
 * SNELL_WATER_COURANT_SAFETY * SNELL_WATER_COURANT_LIMIT * dx / c, seconds. */
float snell_water_dx(const snell_water *w);
float snell_water_dt_limit(const snell_water *w);

/* A drop (or, with amplitude > 0, a lift) at world (x, z): every node within
 * radius of it moves by amplitude * (1 + cos(pi r / radius)) / 2, r its
 * distance; the water it adds (or removes) is part of the volume from then
 * on. radius >= dx (one node) and <= width; |amplitude| <= depth / 2; the
 * point inside the container. Applied at once; wakes a settled surface. */
snell_status snell_water_drop(snell_water *w, float x, float z, float radius, float amplitude);

typedef struct snell_water_stats {
    int steps_run;                 /* steps integrated by this call */
    int skipped_settled;           /* 1: the surface was settled and undisturbed: no step ran */
    int settled;                   /* 1: settled (the next undisturbed call skips), judged on the state after
                                    * the previous call: the GPU's check is read back one call late (so it never
                                    * waits for the GPU) and the CPU follows the same rule, so that the twins
                                    * settle on the same call; a drop in between cancels it */
    float dt;                      /* the step used, seconds */
    int dt_clamped;                /* 1: the requested dt was above snell_water_dt_limit */
    float max_deviation;           /* largest |height - mean| (world units) after the previous call, -1
                                    * where that is not known (the first call after a drop) */
    double ms;                     /* wall time of the call (GPU: the passes issued, not finished) */
} snell_water_stats;

/* Advances the surface by `steps` steps of dt seconds (dt <= 0: 1/60;
 * clamped to snell_water_dt_limit). Each step: per node the force
 * f = sum over axial neighbours (h_n - h) + 1/sqrt2 * sum over diagonal ones
 * (h_n - h), neighbours beyond the walls left out (no flux: reflecting
 * walls); v = (v + (c dt / dx)^2 / dt * f) * exp(-damping dt); h += dt v.
 * The settle check runs once at the end of the call (GPU: a reduction pass
 * and a small asynchronous read-back, evaluated on the next call). stats may
 * be NULL. steps 0..100000. */
snell_status snell_water_step(snell_water *w, float dt, int steps, snell_water_stats *stats);

/* Heights, grid * grid floats (row j = z index, column i = x index). GPU
 * simulation: read back from the current target (its context current). */
snell_status snell_water_read_heights(snell_water *w, float *heights);
/* The water volume above the floor, world units^3: (depth + mean height) * width^2. */
snell_status snell_water_volume(snell_water *w, double *volume);

/* The procedural tiles of the floor (face 0) and the walls (1: x = -w/2,
 * 2: x = +w/2, 3: z = -w/2, 4: z = +w/2) at world point p, as the GPU and
 * the reference shade them (rgb 0..1); for tests and tools. */
void snell_water_tile_color(const snell_water *w, int face, const double p[3], double rgb[3]);

#ifdef __cplusplus
}
#endif
#endif
