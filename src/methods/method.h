/* method.h — the seam between the renderer (src/render/) and the refraction
 * kernels (src/methods/, one file each): a method is a registry entry
 * (registry.c) with its public description, its parameters, an adequacy test
 * on the analysed mesh, and lazily created GL state that prepares per-mesh
 * resources and draws one glass object. Kernels see only resolved values. */
#ifndef SNELL_METHOD_H
#define SNELL_METHOD_H

#include "core/core.h"
#include "mesh/mesh.h"

#include <cglm/cglm.h>

/* What the fragment shaders write (common/output.glsl). */
typedef enum snell__output_kind {
    SNELL__OUT_COLOR = 0,
    SNELL__OUT_DIR_FLOAT,           /* RGBA32F target: xyz = exit direction */
    SNELL__OUT_DIR_PACKED,          /* RGBA8 target: octahedral 16+16 bits (pack.h) */
    SNELL__OUT_KINDS
} snell__output_kind;

/* What a program defines to look the environment up in dual-paraboloid
 * maps instead of the cube (common/env.glsl; render/env_paraboloid.h). */
#define SNELL__ENV_PARABOLOID_DEFINE "#define SNELL_ENV_DUAL_PARABOLOID 1\n"

/* The frame's back-face maps (render/gbuffer.h): texel = window pixel +
 * band, valid for window pixels -band .. size + band - 1. */
typedef struct snell__back_maps {
    int band;                       /* guard band on every side, pixels */
    int width, height;              /* map size: the target's + 2 band */
} snell__back_maps;

/* The frame's scene layers (render/layers.h), which the kernels' exit
 * look-ups read when an object's beyond flag is set. */
typedef struct snell__scene_layers {
    int count;                      /* layers peeled that hold something; 0: none this frame */
    int capped;                     /* 1: the peel stopped at its cap with surfaces left behind */
    int glass_ids, opaque_count;     /* ids 1..glass_ids and the opaque ids of opaque_count objects may be in it */
    float fwd[3];                   /* unit view axis */
    float near_, inv_range;         /* depth value 0 at view depth near_, 1 at near_ + 1 / inv_range */
} snell__scene_layers;

/* The frame's camera and target, shared by every object (world space). */
typedef struct snell__view {
    mat4 view, proj, view_proj, inv_view_proj;
    float eye[3];
    int width, height;
    snell__output_kind out;
    snell__back_maps back;          /* this frame's back-face maps (band 0 and the target's size if none) */
    snell__scene_layers layers;     /* this frame's scene layers (count 0 if none) */
    const struct snell_water *water; /* the frame's water surface, NULL none (common/water.glsl) */
} snell__view;

/* One glass object of a frame, resolved by the scene stage (render/scene.c). */
typedef struct snell__object {
    int index;                      /* in the frame's glass list */
    snell_mesh *mesh;               /* uploaded before prepare/draw */
    const snell_glass_resolved *glass;
    mat4 model, inv_model;
    mat3 normal_matrix;             /* inverse transpose of model's 3x3 */
    int mirrored;                   /* model's determinant < 0: winding flips */
    float bsphere[4];               /* world bounding sphere: centre, radius */
    float view_depth;               /* of the sphere's centre, along the view axis */
    const snell_mesh_analysis *analysis; /* NULL: not analysed (not needed, or failed) */
    unsigned env_texture;           /* what it sees: static env or its dynamic one, a cube or (env_paraboloid)
                                     * a 2D array of dual-paraboloid maps */
    int env_paraboloid;             /* env_texture is a 2D array of dual-paraboloid maps (SNELL__GLASS_ENV_PARABOLOID) */
    int screen_space;               /* 0 forward, else shaded on the screen-space stage's G-buffer:
                                     * SNELL__SCREEN_* (render/gbuffer.h) */
    int gid;                        /* its id in the G-buffer (index + 1) */
    float pixels_per_triangle;      /* its projected bounding sphere per front triangle */
    int scissor[4];                 /* that projection in window pixels: x, y, w, h */
    void *prepared;                 /* the method's resources for (mesh version, settings) */
    unsigned vao;                   /* 0: draw the mesh's own VAO; else the method's (vertex_array()):
                                     * the mesh's attributes plus attribute 2, a per-vertex scalar that
                                     * the kernel reads forward and the G-buffer keeps (its aux target) */
    int back_coarse;                /* the back-face pass draws the mesh's coarse copy (render/gbuffer.h) */
    int crosses_edge;               /* its projected bounding sphere reaches past the target's edge */
    int back_guard;                 /* pixels of guard band it asks of the back-face pass (0: none) */
    int beyond;                     /* its exit rays continue through the scene layers (view.layers), not
                                     * straight to the environment: the kernel's SNELL_BEYOND variant */
    int water;                      /* the frame has water for its exit rays to meet (SNELL_WATER):
                                     * 1 heights in R32F (CPU simulation), 2 in the GPU state */
} snell__object;

/* How well a method serves an object. */
typedef enum snell__fit {
    SNELL__FIT_FAILS = 0,           /* preconditions fail: wrong images (explicit use warns) */
    SNELL__FIT_RUNS,                /* correct in kind, approximate: a fallback for AUTO */
    SNELL__FIT_ADEQUATE             /* represents this object's optics: AUTO may pick it */
} snell__fit;

typedef struct snell__method {
    const snell_method_info *info;  /* public: id, name, summary, needs, cost rank, params */
    const size_t *param_offsets;    /* byte offset of each info->params[i] in snell_glass_material */
    int needs_analysis;             /* adequate() reads the mesh analysis */
    /* May be NULL (always ADEQUATE). analysis may be NULL (unanalysable mesh).
     * Writes why into why (a short clause, no method name). */
    snell__fit (*fit)(const snell_mesh_analysis *analysis, const snell_glass_resolved *glass, char *why,
                      size_t why_size);
    /* GL state, made on the first frame that uses the method. */
    snell_status (*create)(snell_ctx *ctx, snell__output_kind out, void **state);
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
     * (bench/BENCHMARKS.md "Screen-space stage"). */
    float software_screen_ppt;
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
} snell__method;

/* Value names of snell_back_detail parameters (registry.c). */
extern const char *const snell__back_detail_names[3];
#define SNELL__BACK_DETAIL_HELP "back-face pass detail: auto (a coarse copy of meshes below 8 px per triangle) or full"
#define SNELL__GUARD_HELP "back-face guard band for objects crossing the target's edge, percent of its height (-1 none)"
#define SNELL__GUARD_DEFAULT 10

/* The registry entry of a method id (registry.c), NULL for AUTO or unknown. */
const snell__method *snell__method_get(snell_method id);
/* For a method id that snell__method_get does not know: SNELL_E_UNSUPPORTED
 * naming its option if it is a method built without, else SNELL_E_INVALID_ARG
 * (unknown); the message starts with who (e.g. "glass 2: "). */
snell_status snell__method_unbuilt(snell_method id, const char *who);

/* Resolves (zero = default) and range-checks the method's nested parameters in m. */
snell_status snell__method_params_resolve(const snell__method *e, snell_glass_material *m, int object);

/* Defines for a program variant of the given output kind ("#define ...\n"). */
const char *snell__output_defines(snell__output_kind out);

/* snprintf that tolerates truncation (reasons are for people). */
void snell__why(char *why, size_t n, const char *fmt, ...) SNELL_PRINTF(3, 4);

#endif
