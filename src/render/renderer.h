/* SPDX-License-Identifier: MIT */
/* renderer.h — the renderer object: what its stages may use (their
 * services: its target, caches), the lazily created method states, its
 * stages' slots, and the scratch a frame works in (so a frame allocates
 * nothing). */
#ifndef SNELL_RENDERER_H
#define SNELL_RENDERER_H

#include "render/host_depth.h"
#include "render/host_target.h"
#include "render/stages.h"

struct snell_renderer {
    snell_ctx *ctx;
    snell__services sv;                               /* what its stages may use: its target, caches */
    unsigned color_rb;                                /* the target's colour, where no stage made it */
    int premultiplied;                                /* snell_renderer_desc.premultiplied_alpha */
    void *method_state[SNELL_METHOD_COUNT_];
    snell_status method_status[SNELL_METHOD_COUNT_];  /* creation failed: not retried */
    char method_error[SNELL_METHOD_COUNT_][160];
    snell__paraboloid_gen dp;                         /* makes dual-paraboloid maps, on first use */
    snell__composite comp;
    snell__prepared_cache prepared;
    snell__env_dynamic dyn;
    snell__host_depth host_depth;                     /* the target's depth as the frame's mode asks */
    snell__host_target host_target;                   /* the bound framebuffer, checked, its draw buffers */
    snell_frame_desc frame;                           /* this frame's description, resolved (snell_frame_defaults) */
    snell__scene scene;                               /* this frame's resolved scene */
    void *stage_state[SNELL__STAGES_MAX];             /* each stage's slot (frame/stage.h), by table index */
    snell_frame_stats stats;                          /* filled, then copied to the caller */
    float *readback;                                  /* RGBA32F scratch for exit directions */
    uint8_t *readback8;
};

#endif
