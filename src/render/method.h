/* method.h — the interface between the renderer (frame setup, targets,
 * background) and the refraction kernels (one module each: method_*.c).
 * A kernel builds its programs at renderer creation and draws the glass of
 * one frame; shared uniforms are set by glass_program.c. */
#ifndef SNELL_METHOD_H
#define SNELL_METHOD_H

#include "core/core.h"
#include "mesh/mesh.h"
#include "render/env.h"

#include <cglm/cglm.h>

/* Everything about a frame that kernels need, resolved once by the renderer
 * (defaults applied, matrices built). World space throughout. */
typedef struct snell__frame {
    const snell_frame_desc *desc;
    snell_mesh *mesh;               /* uploaded; never NULL when a kernel draws */
    const snell_env *env;
    float ior;                      /* default applied */
    float tint[3];                  /* default applied (white) */
    mat4 model, view, proj, view_proj;
    mat3 normal_matrix;             /* inverse transpose of model's 3x3 */
    float eye[3];
    float bsphere[4];               /* world bounding sphere: centre, radius */
    int width, height;
} snell__frame;

/* What the fragment shaders write (common/output.glsl). */
typedef enum snell__output_kind {
    SNELL__OUT_COLOR = 0,
    SNELL__OUT_DIR_FLOAT,           /* RGBA32F target: xyz = exit direction */
    SNELL__OUT_DIR_PACKED           /* RGBA8 target: octahedral 16+16 bits (pack.h) */
} snell__output_kind;

typedef struct snell__method {
    snell_method id;
    const char *name;
    /* Builds programs for the renderer's output kind; *state is the kernel's own. */
    snell_status (*create)(snell_ctx *ctx, snell__output_kind out, void **state);
    void (*destroy)(snell_ctx *ctx, void *state);
    /* Draws the glass over the background already in the target; depth test
     * is on (LESS), depth cleared, the environment bound on texture unit 0. */
    snell_status (*draw)(snell_ctx *ctx, void *state, const snell__frame *f, snell_frame_stats *stats);
} snell__method;

extern const snell__method snell__method_single;
extern const snell__method snell__method_cubemap;

/* Defines for a program variant of the given output kind ("#define ...\n"). */
const char *snell__output_defines(snell__output_kind out);

#endif
