/* SPDX-License-Identifier: MIT */
/* water.h — the water surface object (snell_water.h): its resolved
 * description, the CPU simulation's arrays (water_sim.c), the GPU
 * simulation's ping-pong targets (water_gpu.c) and what drawing it needs
 * (water_draw.c: the grid's index buffer and the heights texture). */
#ifndef SNELL_WATER_INTERNAL_H
#define SNELL_WATER_INTERNAL_H

#include "core/core.h"
#include "frame/textures.h"
#include "snell/snell_water.h"

#define SNELL__WATER_INV_SQRT2 0.70710678118654752440f

struct snell_water {
    snell_ctx *ctx;                /* NULL: CPU only, not drawable */
    snell_alloc alloc;
    snell_water_desc d;            /* resolved */
    int n;                         /* grid nodes per side */
    float dx, dt_limit;
    float sigma[3];                /* Beer-Lambert absorption per world unit */
    float *h, *v;                  /* CPU simulation (also a GPU water's read-back scratch: h) */
    double mean;                   /* mean height: 0 + every drop's added height / nodes */
    int settled;
    float cpu_dev[2];              /* CPU: max |h - mean|, max |v| dx / c after the last call ... */
    int cpu_dev_known;             /* ... if a call ran since the last drop (the GPU's one-call-late rule) */
    unsigned version;              /* bumped whenever the heights change (draw re-uploads) */
    /* GPU simulation (water_gpu.c) */
    unsigned state_tex[2], state_fbo[2];
    int cur;                       /* state_tex[cur] holds the current state */
    unsigned prog_step, prog_drop, prog_reduce, reduce_tex, reduce_fbo, empty_vao;
    int reduce_size;               /* reduce target side: grid / 16 rounded up */
    uint32_t *reduce_px;           /* read-back scratch (the whole state for snell_water_read_heights) */
    unsigned reduce_pbo;           /* the settle check's reduction, read asynchronously into it */
    void *reduce_fence;            /* GLsync of that read-back; NULL: none pending */
    /* drawing (water_draw.c) */
    unsigned grid_ibo, grid_vao, height_tex, wall_vbo, wall_vao;
    unsigned uploaded_version;     /* version the CPU heights texture holds */
    int uploaded;                  /* height_tex was filled at least once */
    /* the floor's light map (water_caustics.c, made by the caustics stage) */
    unsigned light_prog, light_fbo, light_tex;
    snell__samplers light_samplers; /* light_prog's units */
    unsigned light_format;         /* snell__light_map_format (core/light_map.h), 0 = not probed yet */
    int light_size, light_valid;   /* light_valid: the map holds the surface of light_version under light_key */
    unsigned light_version;
    snell_light light_key;
    int lit_pending;               /* the caustics stage made or kept the map for this frame ... */
    int lit;                       /* ... which the water's draw takes into lit: this frame's floor reads the map */
    /* the opaque objects as columns seen from above (water_caustics.c): their highest and lowest
     * surfaces' depths, [0] and [1]; depth 0 at y = column_top, 1 at column_top - column_range */
    unsigned column_prog, column_fbo[2], column_tex[2];
    int column_size;
    float column_top, column_range;
    uint64_t column_key;           /* the objects the map was made with (meshes, versions, models) */
};


/* One CPU step of dt (<= the stability limit, unchecked: tests step past it
 * on purpose) with the velocity factor damp; k = (c dt / dx)^2 / dt. */
void snell__water_cpu_step(float *h, float *v, int n, float k, float dt, float damp);

/* max |h - mean| and max |v| * dx / c over the CPU arrays. */
void snell__water_cpu_deviation(const snell_water *w, float *dev_h, float *dev_v);

/* The drop profile at distance r (water_sim.c; the GPU drop pass computes the same). */
float snell__water_bell(float r, float radius, float amplitude);

/* GPU simulation (water_gpu.c): targets and programs, one step pass per step,
 * one drop pass, the settle reduction, the read-back of heights. */
snell_status snell__water_gpu_create(snell_water *w);
void snell__water_gpu_destroy(snell_water *w);
snell_status snell__water_gpu_step(snell_water *w, float k, float dt, float damp, int steps);
snell_status snell__water_gpu_drop(snell_water *w, float x, float z, float radius, float amplitude);
/* The settle check without stalling: the reduction of the state after this
 * call is read into a pixel buffer, and the one of the previous call (if
 * any, and no drop came since) is evaluated: *known = 0 when there is none. */
snell_status snell__water_gpu_deviation(snell_water *w, float *dev_h, float *dev_v, int *known);
snell_status snell__water_gpu_read(snell_water *w, float *h, float *v);

/* Drawing resources owned by the water (water_draw.c). */
void snell__water_draw_release(snell_water *w);

/* Tile colour in double (the reference's and snell_water_tile_color's). */
void snell__water_tile(const snell_water_desc *d, int face, const double p[3], double rgb[3]);

#endif
