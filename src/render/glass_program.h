/* glass_program.h — a glass kernel's GL program (glass.vert + the kernel's
 * fragment shader) and the uniforms every kernel shares. */
#ifndef SNELL_GLASS_PROGRAM_H
#define SNELL_GLASS_PROGRAM_H

#include "render/method.h"

typedef struct snell__glass_program {
    unsigned prog;
    int model, normal_matrix, view_proj, eye, env, ior, sigma, tint, bsphere;
} snell__glass_program;

/* glass.vert + fs_path with the output kind's defines and extra_defines (may be NULL). */
snell_status snell__glass_program_build(snell_ctx *ctx, const char *fs_path, snell__output_kind out,
                                        const char *extra_defines, snell__glass_program *g);
void snell__glass_program_destroy(snell__glass_program *g);
/* glUseProgram + the shared uniforms (environment on texture unit 0). */
void snell__glass_program_use(const snell__glass_program *g, const snell__frame *f);
/* Only surfaces facing the eye start a path (both kernels refract at the
 * front surface): for a closed mesh of known winding, enable culling of the
 * others (a model with negative determinant mirrors the winding). Returns
 * whether culling was enabled; the caller disables GL_CULL_FACE after drawing. */
int snell__cull_back_faces(const snell__frame *f);
/* Draws the frame's mesh with the currently bound program. */
void snell__draw_mesh(const snell__frame *f);

#endif
