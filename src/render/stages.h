/* SPDX-License-Identifier: MIT */
/* stages.h — the frame that the stages of the stage table (stages.c,
 * frame/stage.h) run on, and the stages themselves, each defined in its own
 * module. */
#ifndef SNELL_STAGES_H
#define SNELL_STAGES_H

#include "frame/stage.h"
#include "render/renderer.h"

struct snell__frame {
    snell_renderer *r;
    const snell_frame_desc *fd;
    snell_frame_stats *s;
    snell__scene *sc;
    void *const *state;             /* each stage's slot, by table index (r->stage_state) */
    /* The caustics stage where it lit the opaque objects this frame (the
     * glass stage's dynamic environments show them lit), NULL none. */
    const struct snell__caustics *lit_opaque;
    /* A stage drew into the target's depth before the glass (the opaque
     * objects, the receiver plane, the water): the G-buffer's depth is not
     * the glass's alone. */
    int depth_drawn;
};

/* The frame's stages in frame order (stages.c), at most SNELL__STAGES_MAX;
 * the renderer hands them to its program cache for the kernels' hooks. */
extern const snell__stage *const snell__stages[];
extern const int snell__stage_count;

/* The stages other modules name (the table, stages.c, declares them all). */
extern const snell__stage snell__stage_budget;     /* budget_stage.c */
extern const snell__stage snell__stage_caustics;   /* caustics_stage.c */
extern const snell__stage snell__stage_gbuffer;    /* gbuffer.c (bench_floor times its pass) */
extern const snell__stage snell__stage_layers;     /* layers.c (the glass stage: who marches them) */

/* A stage's slot in renderer r (NULL: it keeps no state). */
void *snell__renderer_stage_state(const snell_renderer *r, const snell__stage *stage);
/* The caustics stage's maps, for tests and bench_caustics to read. */
struct snell__caustics *snell__renderer_caustics(const snell_renderer *r);

/* A method's GL state, created on first use (renderer.c); a method that
 * failed to build is not retried (its status again). */
snell_status snell__renderer_method_state(void *user, const snell__method *m, void **state);

/* The budget stage (budget_stage.c): after the frame (drawn = its status
 * was SNELL_OK), the GPU timer query ended, a fence to measure it by
 * (budget frames only), or the controller reset when the frame has no
 * budget. */
void snell__budget_frame_end(snell_renderer *r, const snell_frame_desc *fd, double start_ms, int drawn);
/* The GPU is known to be done (after glFinish or a read-back): the frame's end time if still open. */
void snell__budget_gpu_done(snell_renderer *r);

#endif
