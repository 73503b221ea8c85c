/* SPDX-License-Identifier: MIT */
/* glass_program.h — a glass kernel's GL program (object.vert + the kernel's
 * fragment shader), the uniforms every kernel shares, and drawing the object. */
#ifndef SNELL_GLASS_PROGRAM_H
#define SNELL_GLASS_PROGRAM_H

#include "frame/method.h"
#include "frame/stage.h"
#include "frame/textures.h"

struct snell__glass_program {
    unsigned prog;
    int screen_space;               /* 0 forward, else SNELL__SCREEN_* (frame/frame.h): screen.vert */
    unsigned variant;               /* what it was built for (snell__glass_variant) */
    int model, normal_matrix, view_proj, eye, view_axis, ior, ior_rgb, sigma, tint, bsphere;
    int inv_view_proj, inv_size, gid;
    int hook_locs[SNELL__HOOK_LOCS]; /* the frame stages' uniforms (frame/stage.h) */
    const snell__kernel_hooks *hooks; /* the stages' kernel hooks it takes (its cache's), NULL none */
    snell__samplers samplers;       /* its texture units, by sampler name (frame/textures.h) */
};

/* Binds texture on the unit of the program's sampler called name (a
 * kernel's own texture: its cube map, BVH, layers); nothing if the variant
 * has no such sampler. */
void snell__glass_program_bind(const snell__glass_program *g, const char *name, unsigned target, unsigned texture,
                               unsigned sampler);

/* A kernel program's variant for an object (what snell__glass_program_build
 * takes): its shading (0 forward or SNELL__SCREEN_*, the low two bits),
 * SNELL__GLASS_ENV_PARABOLOID if it looks its environment up in
 * dual-paraboloid maps (common/env.glsl; its env_texture on unit 0 is then a
 * 2D array, render/env_paraboloid.h), and from SNELL__GLASS_STAGE_SHIFT on
 * the bits the frame's stages add (snell__object.stage_bits), each kernel
 * hook's in the stage table's order (snell__kernel_hooks): a new stage
 * numbers nothing by hand. Kernels key their programs by it. */
#define SNELL__GLASS_SHADING_MASK 3
#define SNELL__GLASS_ENV_PARABOLOID 4
#define SNELL__GLASS_STAGE_SHIFT 3
#define SNELL__GLASS_VARIANT_BITS 16 /* the most bits a variant may take, the stages' with them */
int snell__glass_variant(const snell__object *o);

/* The renderer's one bounded cache of kernel programs, every method's
 * (each method's state keeps the pointer create() was given): a program is
 * keyed by its method and its compile-time constants (the variant among
 * them); when the cache is full the least recently used one is destroyed. */
#define SNELL__PROGRAM_KEY_INTS 10
#define SNELL__PROGRAM_LOCS 12      /* a method's own uniform locations per program */
#define SNELL__PROGRAM_CACHE 48
typedef struct snell__program_slot {
    snell__glass_program g;         /* g.prog == 0: empty */
    int method;                     /* snell_method that built it */
    int key[SNELL__PROGRAM_KEY_INTS];
    int loc[SNELL__PROGRAM_LOCS];   /* the method's uniforms, found once (its own struct of ints overlays them) */
    unsigned long last_use;
    int binary_length;              /* GL_PROGRAM_BINARY_LENGTH, asked once per program; -1 not yet */
} snell__program_slot;

/* A method's uniform locations: its own struct of ints laid over slot p's
 * loc[] (type const-qualified to read); SNELL__PROGRAM_LOCS_FIT(type) at
 * file scope fails to compile where the struct does not fit. */
#define SNELL__PROGRAM_LOCS_OF(type, p) ((type *)(void *)(p)->loc)
#define SNELL__PROGRAM_LOCS_FIT(type) typedef char type##_fits[sizeof(type) <= SNELL__PROGRAM_LOCS * sizeof(int) ? 1 : -1]

struct snell__program_cache {
    snell__program_slot slot[SNELL__PROGRAM_CACHE];
    snell__kernel_hooks hooks;      /* the frame's stages' kernel hooks (snell__program_cache_hooks) */
    unsigned long clock;
    int built;                      /* programs built over its life */
};

/* The slot whose program method built for key (n ints, n <=
 * SNELL__PROGRAM_KEY_INTS): *hit = 1. Else *hit = 0 and the empty or least
 * recently used slot, its program destroyed and its key set: the caller
 * builds into it (a failed build leaves it empty). */
snell__program_slot *snell__program_cache_get(snell__program_cache *c, snell_method method, const int *key, int n,
                                              int *hit);
/* Takes the frame's stages (in frame order) and their state slots, and
 * places each kernel hook's bits in the variant after the previous one's;
 * SNELL_E_LIMIT where they take more than SNELL__GLASS_VARIANT_BITS or
 * declare more than SNELL__HOOK_LOCS uniforms. */
snell_status snell__program_cache_hooks(snell_ctx *ctx, snell__program_cache *c, const snell__stage *const *stages,
                                        void *const *states, int count);
void snell__program_cache_destroy(snell__program_cache *c);
/* Programs it holds; *binary_bytes: their size as the driver reports it
 * (GL_PROGRAM_BINARY_LENGTH, 0 where it reports none), asked once per
 * program, not every frame. */
int snell__program_cache_count(snell__program_cache *c, size_t *binary_bytes);

/* The kernel fs_path with the output kind's defines and extra_defines (may be
 * NULL), for a variant (snell__glass_variant): forward (object.vert) or for
 * the screen-space stage (SNELL__SCREEN_*: screen.vert, common/surface.glsl
 * reads the G-buffer), with or without SNELL_BEYOND. */
snell_status snell__glass_program_build(snell_ctx *ctx, const char *fs_path, snell__output_kind out,
                                        const char *extra_defines, int variant, snell__glass_program *g);
void snell__glass_program_destroy(snell__glass_program *g);
/* The kernel variant a material needs (SNELL_DISPERSION, common/dispersion.glsl):
 * 0 no dispersion, 1 three traces (SNELL_DISPERSION_PER_CHANNEL), 2 one path
 * with the directions per channel (SNELL_DISPERSION_ONE_PATH). */
int snell__dispersion_variant(const snell_glass_resolved *g);
/* The image-space methods' precondition (wyman.c, oliveira.c): their back
 * faces are a solid's, so the mesh must be analysed, closed, and at most
 * max_hidden hidden from its centre (more surfaces along a ray than the
 * farthest back face stands for). 1 if so; else 0 with why written. */
int snell__fit_solid_few_surfaces(const snell_mesh_analysis *an, float max_hidden, char *why, size_t n);
/* glUseProgram, the shared uniforms, the object's environment (u_env) and
 * every texture the frame published that the program samples. */
void snell__glass_program_use(const snell__glass_program *g, const snell__view *v, const snell__object *o);
/* Only surfaces facing the eye start a path (every kernel refracts at the
 * front surface first): for a closed mesh of known winding, cull the others
 * (a mirroring model flips the winding). Returns 1 if culling is on, and
 * marks SNELL_SKIP_BACK_FACES in stats. */
int snell__cull_back_faces(const snell__object *o, snell_object_stats *stats);
/* Draws the object's mesh with the bound program, then turns culling off. */
void snell__draw_object(const snell__object *o);
/* Draws the object with the bound program as it is shaded: its mesh
 * (forward, back faces culled where the mesh allows, except for thin walls)
 * or a full-screen triangle scissored to it (screen space: o->scissor). */
void snell__draw_surface(const snell__object *o, snell_object_stats *stats);

#endif
