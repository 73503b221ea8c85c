/* SPDX-License-Identifier: MIT */
/* stages.h — the renderer's per-frame state that the stages of the stage
 * table (stages.c, frame/stage.h) read and write, in frame order. */
#ifndef SNELL_STAGES_H
#define SNELL_STAGES_H

#include "frame/stage.h"
#include "render/renderer.h"

struct snell__frame {
    snell_renderer *r;
    const snell_frame_desc *fd;
    snell_frame_stats *s;
    snell__scene *sc;
    int n_layers;                   /* glass objects in the scene layers, -1: no layers this frame */
    int n_screen, n_back;           /* entries of r->screen_list, r->back_list */
    int band;                       /* the back-face pass's guard band, pixels */
};

/* A method's GL state, created on first use (stages.c); a method that failed
 * to build is not retried (its status again). */
snell_status snell__renderer_method_state(void *user, const snell__method *m, void **state);

/* The budget stage (budget_stage.c): AUTO by frame budget plans every AUTO
 * object's rung before the glass is set up; the frame's fence after it. */
int snell__budget_wanted(const snell__frame *f);
snell_status snell__budget_run(snell__frame *f);
/* After the frame (drawn = its status was SNELL_OK): the GPU timer query
 * ended, a fence to measure it by (budget frames only), or the controller
 * reset when the frame has no budget. */
void snell__budget_frame_end(snell_renderer *r, const snell_frame_desc *fd, double start_ms, int drawn);
/* The GPU is known to be done (after glFinish or a read-back): the frame's end time if still open. */
void snell__budget_gpu_done(snell_renderer *r);
void snell__budget_destroy(snell_renderer *r);

#endif
