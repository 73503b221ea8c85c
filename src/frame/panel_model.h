/* SPDX-License-Identifier: MIT */
/* panel_model.h — glass panels (snell_panels.h) resolved: defaults applied
 * and every field checked, the same for the panels stage and the reference
 * (snell_ref_panels), so that both draw one slab. */
#ifndef SNELL_PANEL_MODEL_H
#define SNELL_PANEL_MODEL_H

#include "snell/snell.h"

#include <stddef.h>

/* One panel with its defaults applied. */
typedef struct snell__panel {
    float center[2], half[2];       /* half = size / 2 */
    float radius[4];                /* 0..min(half), counter-clockwise from the bottom-left */
    float exponent;                 /* 2..16 */
    float thickness, bevel;         /* bevel 0..min(half); 0: a flat pane */
    snell_panel_bevel profile;
    float ior, dispersion, frost;
    float tint[4];
    float rim;                      /* 0: none */
    float light[3];                 /* unit */
    float shadow[4];                /* radius (0 with opacity: a hard edge), opacity, offset; opacity 0: none */
    int group;
    float merge;                    /* smoothing k, pixels; 0: a plain union */
} snell__panel;

/* Checks panels[0..count) as snell_render does and writes them resolved into
 * out (count entries). Returns 0, or 1 with the reason (naming the panel and
 * the field) in msg. */
int snell__panels_resolve(const snell_panel *panels, int count, snell__panel *out, char *msg, size_t msg_size);

/* The box, in the frame's pixels (x0, y0, x1, y1), outside which panel p
 * alone changes nothing: its shape grown by a group's smoothing and one
 * pixel for the antialiased edge, and its shadow. */
void snell__panel_bounds(const snell__panel *p, float box[4]);

#endif
