/* SPDX-License-Identifier: MIT */
/* method.h — the method seam: a refraction kernel (src/methods/, one file
 * each) is a registry entry (methods/registry.c) with its public
 * description, its parameters, an adequacy test on the analysed mesh, and
 * lazily created GL state that prepares per-mesh resources and draws one
 * glass object of the frame contract (frame/frame.h). The renderer
 * (src/render/) calls methods only through this. Kernels see only resolved values. */
#ifndef SNELL_METHOD_H
#define SNELL_METHOD_H

#include "frame/frame.h"
typedef struct snell__program_cache snell__program_cache; /* frame/glass_program.h */

/* How well a method serves an object. */
typedef enum snell__fit {
    SNELL__FIT_FAILS = 0,           /* preconditions fail: wrong images (explicit use warns) */
    SNELL__FIT_RUNS,                /* correct in kind, approximate: a fallback for AUTO */
    SNELL__FIT_ADEQUATE             /* represents this object's optics: AUTO may pick it */
} snell__fit;

typedef struct snell__method {
    const snell_method_info *info;  /* public: id, name, summary, needs, params */
    int needs_analysis;             /* adequate() reads the mesh analysis */
    /* May be NULL (always ADEQUATE). analysis may be NULL (unanalysable mesh).
     * Writes why into why (a short clause, no method name). */
    snell__fit (*fit)(const snell_mesh_analysis *analysis, const snell_glass_resolved *glass, char *why,
                      size_t why_size);
    /* GL state, made on the first frame that uses the method; its kernel
     * programs live in the renderer's cache `programs`, which outlives it. */
    snell_status (*create)(snell_ctx *ctx, snell__output_kind out, snell__program_cache *programs, void **state);
    void (*destroy)(snell_ctx *ctx, void *state);
    /* Prepared resources per (mesh version, key): prepared_size bytes,
     * zeroed on creation; key() fills the settings they depend on; prepare()
     * builds them (renderer-owned cache, render/prepared.c), release() frees
     * their GL objects. All NULL/0 for a method that prepares nothing. */
    size_t prepared_size;
    void (*key)(const snell__object *o, int key[4]);
    snell_status (*prepare)(snell_ctx *ctx, void *state, const snell__object *o, void *prepared,
                            snell_object_stats *stats);
    void (*release)(void *prepared);
    /* Draws the object into the bound target: depth test LESS with depth
     * write on, the object's env_texture on texture unit 0, unit 1 free for
     * the kernel; forward or in screen space as o->screen_space says (both
     * through glass_program.h, so a kernel writes no code for either). */
    snell_status (*draw)(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                         snell_object_stats *stats);
    /* AUTO shading on software rasterisers: screen space below this many
     * (estimated) pixels per front triangle. Measured per method, because the
     * G-buffer pass pays off sooner the more a kernel costs per pixel
     * (bench/notes/history.md "Screen-space stage"). */
    float software_screen_ppt;
    /* The same for a convex mesh where the method runs a cheaper program of
     * its own there (0: software_screen_ppt): the cheaper a pixel, the larger
     * the triangles forward shading pays on. */
    float software_screen_ppt_convex;
    /* Per-frame inputs beyond the front surface: nonzero = the frame's shared
     * back-face pass (the glass's farthest back faces' normal, depth and id,
     * render/gbuffer.h SNELL__BACK_UNIT_*) is drawn before this method's
     * objects and bound while they draw. */
    int needs_back_faces;
    /* May be NULL (always full detail). The object's snell_back_detail
     * parameter: AUTO lets the back-face pass draw a coarse copy of dense
     * meshes (SNELL__BACK_COARSE_PPT). */
    snell_back_detail (*back_detail)(const snell_glass_resolved *glass);
    /* May be NULL (none). The object's guard band, in percent of the target
     * height, for when it crosses the target's edge. */
    int (*back_guard_percent)(const snell_glass_resolved *glass);
    /* May be NULL. The VAO of the prepared resources (the mesh's attributes
     * plus attribute 2), 0 for none: becomes snell__object.vao. */
    unsigned (*vertex_array)(const void *prepared);
    /* Nonzero: its objects are shaded in screen space whatever the shading
     * rule or snell_renderer_desc.shading says, because the kernel reads the
     * G-buffer at pixels other than its own (oliveira.c). */
    int screen_space_only;
    /* Its configurations on AUTO's budget ladder (render/budget.c): each a
     * parameter setting and a resolution scale with its frame time over
     * single's and its glass PSNR against FULL per mesh class, measured as
     * bench/notes/budget_rungs.md says and corrected on the device by
     * snell_renderer_warm. None: AUTO by budget never picks it. */
    const snell_budget_rung *rungs;
    int rung_count;
} snell__method;

/* Value names of the parameters several methods share (registry.c):
 * snell_back_detail, snell_fresnel_model, snell_inner_fresnel. */
extern const char *const snell__back_detail_names[3];
extern const char *const snell__fresnel_names[3];
extern const char *const snell__inner_fresnel_names[3];
#define SNELL__BACK_DETAIL_HELP "back-face pass detail: auto (a coarse copy of meshes below 8 px per triangle) or full"
#define SNELL__GUARD_HELP "back-face guard band for objects crossing the target's edge, percent of its height (-1 none)"
#define SNELL__GUARD_DEFAULT 10

/* The registry entry of a method id (registry.c), NULL for AUTO or unknown. */
const snell__method *snell__method_get(snell_method id);
/* For a method id that snell__method_get does not know: SNELL_E_UNSUPPORTED
 * naming its option if it is a method built without, else SNELL_E_INVALID_ARG
 * (unknown); the message starts with who (e.g. "glass 2: "). */
snell_status snell__method_unbuilt(snell_method id, const char *who);

/* A glass material resolved whole (snell_glass_defaults with the object's
 * index in messages): frame/material.c's part, then the method it names
 * (built?) and every method's nested parameters (zero = default), range-checked. */
snell_status snell__glass_resolve_all(const snell_glass_material *in, int object, snell_glass_resolved *out);

#endif
