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
#include "frame/stage.h"
#include "water/water_draw.h"

struct snell_renderer {
    snell_ctx *ctx;
    int width, height;                                /* the frame's size: the output's times ssaa.factor */
    int out_width, out_height;                        /* what snell_renderer_read_* return */
    snell__ssaa ssaa;
    int msaa;                                         /* samples of the colour and depth targets; 0 = off */
    unsigned msaa_fbo, msaa_rb;                       /* the single-sample target it is resolved into */
    snell_target target;
    int premultiplied;                                /* snell_renderer_desc.premultiplied_alpha */
    snell__output_kind out;
    unsigned fbo, color_rb, depth_rb;
    snell__host_depth host_depth;                     /* the target's depth as the frame's mode asks */
    struct snell__program_cache *programs;            /* every method's kernel programs (frame/glass_program.h) */
    void *method_state[SNELL_METHOD_COUNT_];
    snell_status method_status[SNELL_METHOD_COUNT_];  /* creation failed: not retried */
    char method_error[SNELL_METHOD_COUNT_][160];
    snell_env_lookup env_lookup;
    snell__paraboloid_gen dp;                         /* makes dual-paraboloid maps, on first use */
    snell__composite comp;
    snell__prepared_cache prepared;
    snell__env_dynamic dyn;
    snell_shading shading;
    snell__device_class device;                       /* for the AUTO shading rule, found at creation */
    snell_frame_desc frame;                           /* this frame's description, resolved (snell_frame_defaults) */
    snell__scene scene;                               /* this frame's resolved scene */
    void *stage_state[SNELL__STAGES_MAX];             /* each stage's slot (frame/stage.h), by table index */
    snell_frame_stats stats;                          /* filled, then copied to the caller */
    float *readback;                                  /* RGBA32F scratch for exit directions */
    uint8_t *readback8;
};

/* Is the environment looked up in dual-paraboloid maps, for the static
 * environment (dynamic 0) or an object's dynamic one? AUTO: what measured
 * better here (bench/notes/history.md "Environment look-up"). */
int snell__renderer_env_paraboloid(const snell_renderer *r, int dynamic);

#endif
