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

/* The BVH of exact's prepared resource `prepared` for material m. */
void snell__exact_bvh_of(const void *prepared, const snell_glass_material *m, snell__exact_bvh *out);

#endif
