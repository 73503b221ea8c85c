/* SPDX-License-Identifier: MIT */
/* water_draw.h — the water surface as an object of a frame (renderer.c):
 * its kernel's programs, owned by the renderer because they depend on the
 * renderer's output kind, and the draw of one water surface and its
 * container. A sibling of the glass method seam (frame/method.h), not an
 * entry of it: a method serves a mesh and is chosen by the mesh's analysis,
 * prepared once per mesh version; the water has no mesh, changes every
 * frame (its state is the simulation's) and brings its own geometry (the
 * grid and the container). */
#ifndef SNELL_WATER_DRAW_H
#define SNELL_WATER_DRAW_H

#include "frame/method.h"
#include "frame/beyond.h"
#include "water/water.h"

/* Surface program variants: the refracted ray meets only the container,
 * or also the opaque objects searched in a copy of the target
 * (SNELL_WATER_OBJECTS), or every object through the scene layers
 * (SNELL_BEYOND). */
#define SNELL__WATER_MODES 3

typedef struct snell__water_programs {
    unsigned surface[2][SNELL__WATER_MODES]; /* [heights from R32F (CPU simulation) or the RG32UI state (GPU)][mode] */
    snell__samplers surface_samplers[2][SNELL__WATER_MODES], wall_samplers;
    snell__beyond_locs layers[2];  /* the SNELL_BEYOND mode's layer uniforms, per heights format */
    unsigned wall;
    int made;
    /* The opaque objects as the frame drew them (colour and depth), for the
     * search: copied from the target before the water, made on first use at
     * the target's size. */
    unsigned scene_fbo, scene_color, scene_depth;
} snell__water_programs;

/* Copies the bound target's colour and depth (the opaque objects just
 * drawn, read from read_fbo, width x height) for the search; the caller
 * rebinds its target after. */
snell_status snell__water_copy_scene(snell_ctx *ctx, snell__water_programs *p, unsigned read_fbo, int width, int height);

/* Draws the water and its container into the bound target (depth test LESS,
 * depth write); env_texture on unit 0 for snell_env (a cube, or with
 * env_paraboloid dual-paraboloid maps: the renderer's one choice, the programs
 * are built for it on first use).
 * layers: the frame's scene layers are published in v (snell__layers_draw) and the
 * surface's rays march them; else with objects (object_count > 0, after
 * snell__water_copy_scene) their colour and depth and their bounding spheres. Uploads a CPU simulation's heights when they changed
 * since the last draw (stats->water_uploaded): kernels drawn after it may
 * read them (snell__water_uniforms). */
snell_status snell__water_draw(snell_ctx *ctx, snell__water_programs *p, snell__output_kind out, snell_water *w,
                               const snell__view *v, unsigned env_texture, int env_paraboloid,
                               const snell_opaque *objects, int object_count, int layers, snell_frame_stats *stats);
/* Makes the water's grid and container on first use and uploads a CPU
 * simulation's heights when they changed (stats->water_uploaded); the
 * draw and the floor's light map call it. */
snell_status snell__water_upload(snell_water *w, snell_frame_stats *stats);

/* World bounding sphere of an opaque object: the mesh's box centre through
 * the model, its radius times the model's largest axis scale, grown by 0.1% of itself. */
void snell__water_object_sphere(const snell_opaque *o, float s[4]);

/* The container floor's light map (water_caustics.c; the caustics stage
 * calls it in a frame with water and a light): remade when the surface, the
 * light or the opaque objects (which shadow the floor: `objects`, count)
 * moved, kept otherwise; the water's draw and the glass kernels of this
 * frame then see the floor lit by it. Appends what it did to
 * stats->caustics_reason. */
snell_status snell__water_caustics(snell_ctx *ctx, snell_water *w, const snell_light *light,
                                   const snell_opaque *objects, int count, snell_frame_stats *stats);
/* The floor's light map as last made: size x size rgba floats (rgb the
 * irradiance in units of the light's colour), row 0 at z = -width/2, x
 * growing along a row. SNELL_E_INVALID_ARG if none was made. */
snell_status snell__water_caustics_read(snell_ctx *ctx, snell_water *w, float *rgba, int *size);

/* common/water.glsl's uniforms other than its samplers, by name, and
 * their setter for the program in use (locs in the names' order; the
 * glass kernels' hook finds them once per program, render/stages.c). */
#define SNELL__WATER_UNIFORMS 9
extern const char *const snell__water_uniform_names[SNELL__WATER_UNIFORMS];
void snell__water_set_uniforms(const int *locs, const snell_water *w);
/* Publishes the heights (u_water_heights: the GPU simulation's current
 * state or the CPU one's R32F upload) and the floor's light map
 * (u_water_light, 0 where unlit) for the programs drawn after the water. */
void snell__water_publish(const snell_water *w, snell__textures *ts);
/* The water's own programs (its surface, container and floor light map):
 * common/water.glsl's uniforms of prog (in use), found by name, and its
 * heights and light map bound on the units samplers gives them. */
void snell__water_uniforms(unsigned prog, const snell__samplers *samplers, const snell_water *w);
void snell__water_programs_destroy(snell__water_programs *p);

#endif
