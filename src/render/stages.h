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

#endif
