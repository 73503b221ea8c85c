/* SPDX-License-Identifier: MIT */
/* device_cost.h — what each method costs on the GPU the context reports
 * (GL_RENDERER), from the compile-based model of bench/devices/COSTS.md.
 * AUTO and the budget rank methods by it; unknown GPUs keep the rung tables'. */
#ifndef SNELL_DEVICE_COST_H
#define SNELL_DEVICE_COST_H

#include "core/core.h"

#define SNELL__COST_CLASSES 4 /* the budget's mesh classes (render/budget.h) */

typedef struct snell__device_cost {
    char name[12];                                   /* "V3D 4.2", said in AUTO's reasons */
    float cost[SNELL_METHOD_COUNT_][SNELL__COST_CLASSES]; /* frame time over single's; 0 = not modelled */
    int arrays_in_registers; /* its compiler keeps a shader's local arrays in registers: exact's
                              * 32-entry stack is half of Mali-G52's file and spills there */
} snell__device_cost;

/* The model of the GPU a GL_RENDERER string names, NULL when none. */
const snell__device_cost *snell__device_cost_find(const char *gl_renderer);

/* Whether the BVH walk (exact, the photons' BVH path) takes the stack for
 * material.exact.walk = walk on this GPU (dev: its model, NULL: none):
 * SNELL_EXACT_WALK_DEFAULT is the stack, but the stackless walk where the
 * compiler keeps local arrays in registers. The two give the same image. */
int snell__exact_walk_stack(const snell__device_cost *dev, int walk);

#endif
