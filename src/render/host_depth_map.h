/* SPDX-License-Identifier: MIT */
/* host_depth_map.h — a host depth buffer of another convention than snell's
 * (reversed-Z): mapped into the depth of snell's copy of the frame's
 * rectangle before the frame, and back into the host's where the frame
 * changed it (snell__camera_depth_map gives the affine map). With
 * SNELL_WITH_HOST_FRAMEBUFFERS. */
#ifndef SNELL_HOST_DEPTH_MAP_H
#define SNELL_HOST_DEPTH_MAP_H

#include "core/core.h"

typedef struct snell__depth_map {
    unsigned host_tex, host_fbo, host_format; /* the host's depth, blitted as it is */
    unsigned before_tex, before_fbo;          /* snell's depth before the frame */
    unsigned prog[2], vao;                    /* in, back */
    int size[2];
    double map[2];                            /* snell's depth = map[0] x the host's + map[1] */
} snell__depth_map;

/* Before the frame: the host framebuffer host_fbo's depth in rect (x, y, w,
 * h) into copy_fbo's depth (DEPTH_COMPONENT32F, w x h), mapped; copy_fbo
 * stays bound. */
snell_status snell__depth_map_in(snell_ctx *ctx, snell__depth_map *m, unsigned host_fbo, const int rect[4],
                                 unsigned copy_fbo);
/* After it: where copy_depth changed, its depth mapped back into the host's. */
snell_status snell__depth_map_back(snell_ctx *ctx, snell__depth_map *m, unsigned host_fbo, const int rect[4],
                                   unsigned copy_depth);
void snell__depth_map_destroy(snell__depth_map *m);

#endif
