/* glass_program.h — a glass kernel's GL program (object.vert + the kernel's
 * fragment shader), the uniforms every kernel shares, and drawing the object. */
#ifndef SNELL_GLASS_PROGRAM_H
#define SNELL_GLASS_PROGRAM_H

#include "methods/method.h"

typedef struct snell__glass_program {
    unsigned prog;
    int model, normal_matrix, view_proj, eye, env, ior, sigma, tint, bsphere;
} snell__glass_program;

/* object.vert + fs_path with the output kind's defines and extra_defines (may be NULL). */
snell_status snell__glass_program_build(snell_ctx *ctx, const char *fs_path, snell__output_kind out,
                                        const char *extra_defines, snell__glass_program *g);
void snell__glass_program_destroy(snell__glass_program *g);
/* glUseProgram + the shared uniforms (the object's environment on texture unit 0). */
void snell__glass_program_use(const snell__glass_program *g, const snell__view *v, const snell__object *o);
/* Only surfaces facing the eye start a path (every kernel refracts at the
 * front surface first): for a closed mesh of known winding, cull the others
 * (a mirroring model flips the winding). Returns 1 if culling is on, and
 * marks SNELL_SKIP_BACK_FACES in stats. */
int snell__cull_back_faces(const snell__object *o, snell_object_stats *stats);
/* Draws the object's mesh with the bound program, then turns culling off. */
void snell__draw_object(const snell__object *o);

#endif
