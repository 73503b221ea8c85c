/* SPDX-License-Identifier: MIT */
/* exact.h — what the exact method's prepared resource (methods/exact.c, one
 * per mesh version in the prepared cache) lends to a stage that walks the
 * same BVH with common/bvh.glsl: the caustics' photons (render/caustics.c). */
#ifndef SNELL_EXACT_H
#define SNELL_EXACT_H

#include "snell/snell.h"

typedef struct snell__exact_bvh {
    unsigned texture;       /* the BVH texture: RGBA32F (f32 nodes) or RGBA32UI (q16 nodes) */
    int q16;                /* SNELL_NODES_Q16 */
    int node_count, tri_base;
    const float *qlo, *qstep; /* q16: bound = qlo + q * qstep (object space) */
    int stack;              /* SNELL_STACK_WALK: the material's exact.walk is the short stack */
} snell__exact_bvh;

/* The least distance a secondary ray travels before it may hit again, for an
 * object of bounding radius r: exact's kernel's and the caustics' photons'
 * (through one object or a chain of them) alike. */
#define SNELL__EXACT_EPS(r) (1e-5f * (r))

/* The BVH of exact's prepared resource `prepared` for material m. */
void snell__exact_bvh_of(const void *prepared, const snell_glass_material *m, snell__exact_bvh *out);

/* exact's BVH (f32 nodes, the stack walk) of a mesh outside the prepared
 * cache (render/caustics.c: the casters of a chain merged in world space),
 * in *prepared (made on the first call, NULL before; built again, or refitted
 * for the same triangle count, on each); its triangle entries carry their
 * mesh triangle's index in v0's w. SNELL_WITH_CAUSTICS builds only. */
snell_status snell__exact_bvh_make(snell_ctx *ctx, const snell_mesh *mesh, void **prepared, snell__exact_bvh *out);
void snell__exact_bvh_free(void *prepared);

#endif
