/* SPDX-License-Identifier: MIT */
/* lm2d_trace.h — the CPU light tracer (Brückner 6.4): rays from lights through
 * mirror/diffuse BRDF, Fresnel refraction and attenuated interior paths, into
 * preallocated path segments; plus the small pthread pool that runs it. */
#ifndef SNELL_LM2D_TRACE_H
#define SNELL_LM2D_TRACE_H

#include "lm2d/lm2d_scene.h"

/* One rasterisable light path segment (world units) with the flux at both
 * ends (rgb); the flux varies linearly in between (thesis 6.5.1). 40 bytes. */
typedef struct lm2d_path {
    float x0, y0, x1, y1;
    float c0[3], c1[3];
} lm2d_path;

/* Per-trace bookkeeping: flux (summed over rgb) by fate, and the bounds of
 * every ray vertex (unclipped) so the lightmap knows which object changes can
 * affect these paths; unbounded = some ray escaped to infinity. */
typedef struct lm2d_energy {
    double emitted, absorbed, escaped, capped, rr_killed, rr_gained;
    float lo[2], hi[2];
    int unbounded;
} lm2d_energy;

typedef struct lm2d_trace_params {
    const snell_scene2d *scene;   /* prepared (edges + BVH current) */
    float view_lo[2], view_hi[2]; /* paths are clipped to this rectangle (6.4.1.3) */
    int max_bounces;              /* >= 0 */
    uint64_t seed;
    uint32_t pass;
} lm2d_trace_params;

/* Traces rays [r0, r1) of light `li`. Writes at most `cap` segments to out and
 * returns how many; energy is added to *e. Every ray yields at most
 * max_bounces + 1 segments, so cap = (r1 - r0) * (max_bounces + 1) never drops. */
size_t lm2d_trace_rays(const lm2d_trace_params *p, int li, int r0, int r1, lm2d_path *out, size_t cap,
                       lm2d_energy *e);

/* Clips segment o + t d, t in [0, t_end] (t_end may be INFINITY) to the box;
 * returns 0 when nothing is left, else the clipped parameter range. */
int lm2d_clip(const float lo[2], const float hi[2], const float o[2], const float d[2], float t_end, float *ta,
              float *tb);

/* Fixed worker pool: run() calls fn(i, n, arg) for i in [0, n) on n threads
 * (the caller is thread 0) and returns when all are done. No allocation per run. */
typedef struct lm2d_pool lm2d_pool;
typedef void (*lm2d_pool_fn)(int i, int n, void *arg);
snell_status lm2d_pool_create(const snell_ctx *ctx, const snell_alloc *al, int threads, lm2d_pool **out);
void lm2d_pool_destroy(lm2d_pool *pool);
int lm2d_pool_size(const lm2d_pool *pool);
void lm2d_pool_run(lm2d_pool *pool, lm2d_pool_fn fn, void *arg);

#endif
