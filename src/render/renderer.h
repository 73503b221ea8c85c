/* SPDX-License-Identifier: MIT */
/* renderer.h — the renderer object: its target, the lazily created method
 * states, the prepared-resource cache, dynamic environments, and the scratch
 * a frame works in (so a frame allocates nothing). */
#ifndef SNELL_RENDERER_H
#define SNELL_RENDERER_H

#include "render/budget.h"
#include "render/caustics.h"
#include "render/composite.h"
#include "render/env_dynamic.h"
#include "render/env_paraboloid.h"
#include "render/gbuffer.h"
#include "render/glass_scale.h"
#include "render/host_depth.h"
#include "render/layers.h"
#include "render/prepared.h"
#include "render/scene.h"
#include "render/ssaa.h"
#include "water/water_draw.h"

struct snell_renderer {
    snell_ctx *ctx;
    int width, height;                                /* the frame's size: the output's times ssaa.factor */
    int out_width, out_height;                        /* what snell_renderer_read_* return */
    snell__ssaa ssaa;
    int msaa;                                         /* samples of the colour and depth targets; 0 = off */
    unsigned msaa_fbo, msaa_rb;                       /* the single-sample target it is resolved into */
    snell_target target;
    snell__output_kind out;
    unsigned fbo, color_rb, depth_rb;
    snell__host_depth host_depth;                     /* the target's depth as the frame's mode asks */
    void *method_state[SNELL_METHOD_COUNT_];
    snell_status method_status[SNELL_METHOD_COUNT_];  /* creation failed: not retried */
    char method_error[SNELL_METHOD_COUNT_][160];
    snell_env_lookup env_lookup;
    snell__paraboloid_gen dp;                         /* makes dual-paraboloid maps, on first use */
    unsigned warned[SNELL_MAX_GLASS];                 /* warn_once keys */
    snell__composite comp;
    snell__prepared_cache prepared;
    snell__env_dynamic dyn;
    snell_shading shading;
    snell__device_class device;                       /* for the AUTO shading rule, found at creation */
    snell__gbuffer gbuffer;                           /* the screen-space stage, made on first use */
    snell__scene scene;                               /* this frame's resolved scene */
    const snell__method *object_method[SNELL_MAX_GLASS]; /* this frame's choice per object */
    void *object_state[SNELL_MAX_GLASS];
    snell__object *screen_list[SNELL_MAX_GLASS];      /* objects shaded in screen space */
    snell__gbuffer backfaces;                         /* the shared back-face pass, made on first use */
    snell__object *back_list[SNELL_MAX_GLASS];        /* objects whose method needs it */
    snell__water_programs water;                      /* the water kernel's programs, made on first use */
    snell__layers layers;                             /* the scene layers, made on first use */
    snell__object *layer_list[SNELL_MAX_GLASS];       /* the glass objects peeled into them */
    snell__budget budget;                             /* AUTO by budget's controller (budget.h) */
    snell__budget_object budget_obj[SNELL_MAX_GLASS]; /* this frame's ladders */
    char budget_note[SNELL_MAX_GLASS][128];            /* each object's rung and why (snell__object.budget_note) */
    void *budget_fence;                               /* GLsync after the last budget frame, NULL none */
    double budget_start_ms, budget_done_ms;           /* that frame's start; its completion seen (-1 not yet) */
    double budget_cpu_ms;                             /* that frame's time inside snell_render */
    unsigned budget_query;                            /* its GL_TIME_ELAPSED_EXT query (0: none made yet) */
    int budget_timer;                                 /* EXT_disjoint_timer_query: 0 not probed, 1 yes, -1 no */
    int budget_query_state;                           /* 1 running in this frame, 2 ended (read next frame), 0 */
    const int *budget_force;                          /* snell_renderer_warm: the plan to draw (ladder index per
                                                       * object), NULL: the controller's */
    snell__glass_scale glass_scale;                   /* objects at a resolution scale, made on first use */
    snell__caustics caustics;                         /* the caustics stage's light map, made on first use */
    snell_frame_stats stats;                          /* filled, then copied to the caller */
    float *readback;                                  /* RGBA32F scratch for exit directions */
    uint8_t *readback8;
};

/* Is the environment looked up in dual-paraboloid maps, for the static
 * environment (dynamic 0) or an object's dynamic one? AUTO: what measured
 * better here (bench/BENCHMARKS.md "Environment look-up"). */
int snell__renderer_env_paraboloid(const snell_renderer *r, int dynamic);

#endif
