/* SPDX-License-Identifier: MIT */
/* pass.h — offscreen passes: begin binds a framebuffer, sets the viewport,
 * depth state and clears; end puts back what begin changed, so kernels that
 * render extra passes (cube bakes, dynamic environments, back faces, peels)
 * write no save/restore code of their own. */
#ifndef SNELL_PASS_H
#define SNELL_PASS_H

typedef struct snell__pass {
    int fbo, viewport[4];
    int depth_func, active_texture;
    unsigned char depth_test, depth_mask, cull_face;
    float clear_color[4], clear_depth;
} snell__pass;

/* clear: GL_COLOR_BUFFER_BIT / GL_DEPTH_BUFFER_BIT mask (colour cleared to 0,
 * depth to clear_depth). Depth test on with depth_func, depth write on, no culling. */
void snell__pass_begin(snell__pass *p, unsigned fbo, int width, int height, unsigned clear, int depth_func,
                       float clear_depth);
void snell__pass_end(const snell__pass *p);

#endif
