/* env_dynamic.h — the dynamic environment (Unger 4.1): the static environment
 * plus the opaque scene objects rendered into a cubemap from the glass's
 * centre, re-rendered only when something in it changed; and the opaque
 * objects' own drawing in the view. */
#ifndef SNELL_ENV_DYNAMIC_H
#define SNELL_ENV_DYNAMIC_H

#include "core/core.h"
#include "render/method.h"

typedef struct snell__opaque_prog {
    unsigned prog;
    int model, normal_matrix, view_proj, eye, color;
} snell__opaque_prog;

typedef struct snell__env_dynamic {
    snell__opaque_prog view_prog;     /* renderer's output kind (view pass) */
    snell__opaque_prog cube_prog;     /* colour (cube faces) */
    unsigned sky_prog;                /* colour skybox for the faces */
    int sky_inv, sky_env;
    unsigned texture, fbo, depth_rb;
    int size;                         /* face size of texture, 0 = none yet */
    /* what the current texture shows (for the "nothing moved" skip) */
    int valid;
    const snell_env *env;
    float centre[3];
    int count;
    const snell_mesh *mesh[SNELL_MAX_OPAQUE];
    unsigned version[SNELL_MAX_OPAQUE];
    float model[SNELL_MAX_OPAQUE][16];
    float color[SNELL_MAX_OPAQUE][3];
} snell__env_dynamic;

snell_status snell__env_dynamic_create(snell_ctx *ctx, snell__output_kind out, snell__env_dynamic *d);
void snell__env_dynamic_destroy(snell__env_dynamic *d);

/* Checks a frame's opaque list (count, meshes, finite models/colours, size). */
snell_status snell__env_dynamic_validate(snell_ctx *ctx, const snell_frame_desc *fd);

/* Uploads the opaque meshes and draws them in the view (depth test on). */
snell_status snell__opaque_draw_view(snell__env_dynamic *d, const snell__frame *f, snell_frame_stats *stats);

/* Re-renders the cubemap if anything changed since it was last rendered
 * (stats->env_updated) or reuses it (stats->env_skipped). Leaves the draw
 * framebuffer and viewport changed when it renders: the caller restores. */
snell_status snell__env_dynamic_update(snell_ctx *ctx, snell__env_dynamic *d, const snell__frame *f,
                                       snell_frame_stats *stats);

#endif
