/* water_draw.h — the water surface as an object of a frame (renderer.c):
 * its kernel's programs, owned by the renderer because they depend on the
 * renderer's output kind, and the draw of one water surface and its
 * container. A sibling of the glass method seam (methods/method.h), not an
 * entry of it: a method serves a mesh and is chosen by the mesh's analysis,
 * prepared once per mesh version; the water has no mesh, changes every
 * frame (its state is the simulation's) and brings its own geometry (the
 * grid and the container). */
#ifndef SNELL_WATER_DRAW_H
#define SNELL_WATER_DRAW_H

#include "methods/method.h"
#include "water/water.h"

typedef struct snell__water_programs {
    unsigned surface[2];           /* heights from R32F (CPU simulation) or from the RG32UI state (GPU) */
    unsigned wall;
    int made;
} snell__water_programs;

/* Draws the water and its container into the bound target (depth test LESS,
 * depth write); env_texture on unit 0 for snell_env, the heights on unit 1.
 * Uploads a CPU simulation's heights when they changed since the last draw
 * (stats->water_uploaded). */
snell_status snell__water_draw(snell_ctx *ctx, snell__water_programs *p, snell__output_kind out, snell_water *w,
                               const snell__view *v, unsigned env_texture, snell_frame_stats *stats);
void snell__water_programs_destroy(snell__water_programs *p);

#endif
