/* glstate.h — snapshot and restore of the GL state the renderer touches, so
 * the library can draw inside a host application's context (EXTERNAL backend). */
#ifndef SNELL_GLSTATE_H
#define SNELL_GLSTATE_H

#define SNELL_GLSTATE_UNITS 4 /* texture units the library may bind (0..3) */

typedef struct snell_glstate {
    int draw_fbo, read_fbo, renderbuffer, program, vao, array_buffer, active_texture;
    int tex_2d[SNELL_GLSTATE_UNITS], tex_cube[SNELL_GLSTATE_UNITS];
    int viewport[4], scissor_box[4];
    unsigned char depth_test, cull_face, blend, scissor_test, stencil_test, polygon_offset, dither;
    unsigned char color_mask[4], depth_mask;
    int depth_func, cull_mode, front_face;
    int blend_src_rgb, blend_dst_rgb, blend_src_a, blend_dst_a, blend_eq_rgb, blend_eq_a;
    float clear_color[4], clear_depth;
    int pack_alignment, unpack_alignment;
} snell_glstate;

void snell__glstate_save(snell_glstate *s);
void snell__glstate_restore(const snell_glstate *s);

#endif
