/* SPDX-License-Identifier: MIT */
/* stages.h — the frame that the stages of the stage table (stages.c,
 * frame/stage.h) run on, and the stages themselves, each defined in its own
 * module. */
#ifndef SNELL_STAGES_H
#define SNELL_STAGES_H

#include "frame/glass_program.h"
#include "frame/stage.h"
#include "render/composite.h"
#include "render/env_dynamic.h"
#include "render/env_paraboloid.h"
#include "render/gbuffer.h"
#include "render/prepared.h"
#include "render/scene.h"

/* What a stage may use of its renderer: its context, its target, the
 * settings the stages read, and the passes and caches they share; not the
 * renderer. At creation the stages set the target up (create()): the ssaa
 * stage its size and colour texture, the msaa stage its samples; fixed
 * from then on. */
struct snell__services {
    snell_ctx *ctx;
    snell_target target;
    snell__output_kind out;
    int width, height;              /* the frame's size: the output's times the ssaa stage's factor */
    int out_width, out_height;      /* the output's: what snell_renderer_read_* return */
    int samples;                    /* of the target's colour and depth (the msaa stage); 0: one */
    unsigned color_texture;         /* the target's colour attachment where a stage made it (ssaa), 0 none */
    unsigned fbo, depth_rb;         /* the offscreen target (0 with the bound framebuffer) */
    unsigned read_fbo;              /* where the finished image is read: a resolve's, 0: fbo */
    snell_shading shading;
    snell_env_lookup env_lookup;
    snell__device_class device;     /* for the AUTO shading rule, found at creation */
    snell__composite *comp;
    snell__paraboloid_gen *dp;      /* makes dual-paraboloid maps, on first use */
    snell__env_dynamic *dyn;
    snell__prepared_cache *prepared;
    snell__program_cache *programs; /* every method's kernel programs (frame/glass_program.h) */
    /* A method's GL state, made on first use; one that failed to build is
     * not retried (its status again). user: this struct's owner. */
    snell_status (*method_state)(void *user, const snell__method *m, void **state);
    void *user;
};

struct snell__frame {
    const snell__services *sv;
    const snell_frame_desc *fd;
    snell_frame_stats *s;
    snell__scene *sc;
    void *const *state;             /* each stage's slot, by table index */
    /* The caustics stage where it lit the opaque objects this frame (the
     * glass stage's dynamic environments show them lit), NULL none. */
    const struct snell__caustics *lit_opaque;
    double start_ms;                /* when snell_render began (snell__now_ms) */
    /* A stage drew into the target's depth before the glass (the opaque
     * objects, the receiver plane, the water): the G-buffer's depth is not
     * the glass's alone. */
    int depth_drawn;
};

/* The frame's stages in frame order (stages.c), at most SNELL__STAGES_MAX;
 * the renderer hands them to its program cache for the kernels' hooks. */
extern const snell__stage *const snell__stages[];
extern const int snell__stage_count;

/* The stages other modules name (the table, stages.c, declares them all). */
extern const snell__stage snell__stage_budget;     /* budget_stage.c */
extern const snell__stage snell__stage_caustics;   /* caustics_stage.c */
extern const snell__stage snell__stage_gbuffer;    /* gbuffer.c (bench_floor times its pass) */
extern const snell__stage snell__stage_layers;     /* layers.c (the glass stage: who marches them) */

/* A stage's slot in renderer r (NULL: it keeps no state). */
void *snell__renderer_stage_state(const snell_renderer *r, const snell__stage *stage);
/* The caustics stage's maps, for tests and bench_caustics to read. */
struct snell__caustics *snell__renderer_caustics(const snell_renderer *r);

/* Is the environment looked up in dual-paraboloid maps, for the static
 * environment (dynamic 0) or an object's dynamic one? AUTO: what measured
 * better here (bench/notes/history.md "Environment look-up"). */
int snell__env_lookup_paraboloid(snell_env_lookup lookup, int dynamic);

#endif
