/* SPDX-License-Identifier: MIT */
/* stage.h — the stage seam: a frame is the entries of one table
 * (render/stages.c) run in order, each with whether this frame wants it,
 * what it draws, and what it adds to every glass kernel's program (the
 * kernel hook: bits of the program variant, their #defines, uniforms found
 * once per program and set at each draw). Kernels (frame/glass_program.c)
 * read the hooks from the table, so a new stage is one table entry, its
 * files, its shader chunk and its tests: no kernel changes. */
#ifndef SNELL_STAGE_H
#define SNELL_STAGE_H

#include "frame/frame.h"

/* The renderer's per-frame state and what its stages may use of it
 * (render/stages.h); the floor only passes them on. */
typedef struct snell__frame snell__frame;
typedef struct snell__services snell__services;

/* Uniform locations the hooks of one kernel program may keep, in all
 * (render/stages.c checks that the hooks' names fit). */
#define SNELL__HOOK_LOCS 48

typedef struct snell__glass_program snell__glass_program; /* frame/glass_program.h */

/* What a stage adds to every kernel program. Its textures it publishes in
 * the frame's view by sampler name (frame/textures.h) when it runs: each
 * program binds those it samples, on units of its own. Its bits of the
 * program variant are its own, counted from 1: where they sit in the
 * variant follows from the table's order (snell__kernel_hooks). */
typedef struct snell__kernel_hook {
    int variant_bits;               /* how many bits of the variant it takes (1 or more) */
    /* The #defines for its bits (nonzero) a program is built with. */
    const char *(*defines)(unsigned bits);
    /* The uniforms it sets, by name: found once per program, handed to
     * uniforms() in this order (-1 where the variant has none). */
    const char *const *uniform_names;
    int uniform_count;
    /* Sets its uniforms of the program in use for object o of the frame,
     * from its stage's state (NULL where the stage keeps none). */
    void (*uniforms)(const snell__glass_program *g, const int *locs, const void *state, const snell__view *v,
                     const snell__object *o);
} snell__kernel_hook;

/* A stage is a module: its own files hold its state, its validation of its
 * part of the frame description and its passes; the renderer keeps one
 * opaque slot of state_size bytes per stage (zeroed at creation, freed with
 * it) and hands it to every call. What one stage makes for another it
 * publishes through the frame: textures by sampler name in the view
 * (frame/textures.h), its per-object choices in the objects. */
typedef struct snell__stage {
    const char *name;               /* as snell_frame_stats.stages lists it */
    size_t state_size;              /* its slot's bytes, 0: none */
    /* All may be NULL. validate_renderer: its part of the renderer's
     * description (resolved), checked before the renderer makes anything,
     * and the target's shape it asks for set in sv (the ssaa stage the
     * frame's size, the msaa stage its samples), which the renderer's
     * memory check counts. create: at the renderer's creation, its state
     * zeroed: its first values and GL objects (the target's colour texture
     * and the image read back, in sv, are its to set before the target is
     * made); a failure fails the creation. destroy: its GL objects and
     * memory, in the renderer's context (also after a failed create). */
    snell_status (*validate_renderer)(snell__services *sv, const snell_renderer_desc *d);
    snell_status (*create)(snell__services *sv, const snell_renderer_desc *d, void *state);
    void (*destroy)(snell_ctx *ctx, void *state);
    /* Its part of the frame description, checked before anything is drawn. */
    snell_status (*validate)(const snell__services *sv, const snell_frame_desc *fd);
    /* Its part of the frame description with its defaults applied, kept in
     * its state, before the frame is validated (sokol_gfx's order): fd is
     * the renderer's copy, which it points at them, so that validate() and
     * every stage see only resolved values. It fills zeros only and must
     * not trust the rest, which validate() judges. */
    void (*resolve)(const snell__services *sv, snell_frame_desc *fd, void *state);
    /* Before any stage runs: what it will do this frame, which earlier
     * stages' set-up may depend on (the scene layers: every glass kernel's
     * variant). */
    void (*plan)(snell__frame *f, void *state);
    int (*wanted)(const snell__frame *f, const void *state); /* NULL: every frame */
    snell_status (*run)(snell__frame *f, void *state);
    /* Which of its kernel hook's bits (its own, from 1) object o's program
     * needs this frame, before any kernel draws (the glass stage places
     * them in o->stage_bits). */
    unsigned (*kernel_variant)(const snell__frame *f, const void *state, const snell__object *o);
    const snell__kernel_hook *kernel; /* NULL: it adds nothing to the kernels */
    /* After the frame, the host's GL state restored (st: how the frame went). */
    void (*frame_end)(snell__frame *f, void *state, snell_status st);
    /* The GPU finished what the renderer issued (snell_renderer_finish, a read-back). */
    void (*gpu_done)(void *state);
} snell__stage;

/* The frame has at most this many stages (its table: render/stages.h). */
#define SNELL__STAGES_MAX 16

/* The stages' kernel hooks as the programs of one renderer see them: the
 * table in frame order, each stage's state slot, and where each hook's bits
 * sit in a program's variant: after the variant's own bits
 * (frame/glass_program.h), each hook's after the previous hook's. */
typedef struct snell__kernel_hooks {
    const snell__stage *const *stages;
    void *const *states;
    int count;
    unsigned shift[SNELL__STAGES_MAX];
} snell__kernel_hooks;

/* Stage i's hook bits (its own, from 1) in variant, 0 where it has none. */
unsigned snell__kernel_hook_bits(const snell__kernel_hooks *h, int i, unsigned variant);

#endif
