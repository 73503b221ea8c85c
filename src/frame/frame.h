/* SPDX-License-Identifier: MIT */
/* frame.h — the frame contract every pass of a frame reads: what the
 * shaders write, the frame's view (camera, target, back-face maps, scene
 * layers, the textures the stages published) and one glass object
 * as the scene stage resolved it (render/scene.c). Methods, stages and the
 * renderer share it; it imports only core/ and mesh/. */
#ifndef SNELL_FRAME_H
#define SNELL_FRAME_H

#include "core/core.h"
#include "frame/textures.h"
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

/* How a screen-space kernel gets its depth into the target (snell__object.screen_space). */
#define SNELL__SCREEN_SHARED_DEPTH 1  /* the G-buffer pass wrote the target's own depth buffer */
#define SNELL__SCREEN_WRITES_DEPTH 2  /* the G-buffer had its own; the kernel writes gl_FragDepth */

/* Light through glass in sequence (the caustics' chain, render/caustics_photons.c,
 * and its reference, ref_caustics.c chain): at most this many glass objects
 * a photon crosses, and the most casters with overlapping beams the stage
 * takes together. */
#define SNELL__CAUSTICS_CHAIN 4

/* The frame's back-face maps (render/gbuffer.h): texel = window pixel +
 * band, valid for window pixels -band .. size + band - 1. */
typedef struct snell__back_maps {
    int band;                       /* guard band on every side, pixels */
    int width, height;              /* map size: the target's + 2 band */
} snell__back_maps;

/* The frame's scene layers (render/layers.h), which the kernels' exit
 * look-ups read when an object's beyond flag is set. */
typedef struct snell__scene_layers {
    int active;                     /* 1: the layers stage ran this frame (the water's rays march them too) */
    int count;                      /* layers peeled that hold something; 0: none this frame */
    int capped;                     /* 1: the peel stopped at its cap with surfaces left behind */
    int glass_ids, opaque_count;     /* ids 1..glass_ids and the opaque ids of opaque_count objects may be in it */
    float fwd[3];                   /* unit view axis */
    float near_, inv_range;         /* depth value 0 at view depth near_, 1 at near_ + 1 / inv_range */
    int width, height;              /* the grid they were peeled at: the frame's (an object shaded at a
                                     * resolution scale, render/glass_scale.h, draws at a smaller one) */
} snell__scene_layers;

/* The frame's camera and target, shared by every object (world space). */
typedef struct snell__view {
    mat4 view, proj, view_proj, inv_view_proj;
    float eye[3];                   /* the camera's position (orthographic: a point on its axis) */
    float view_axis[4];             /* the direction it looks along; w 1: orthographic (common/view.glsl) */
    int mirrored;                   /* the camera flips the image in x (frame/camera.h): windings flip */
    int width, height;
    snell__output_kind out;
    snell__back_maps back;          /* this frame's back-face maps (band 0 and the target's size if none) */
    snell__scene_layers layers;     /* this frame's scene layers (count 0 if none) */
    /* What the stages made for the programs after them, by sampler name
     * (frame/textures.h): the G-buffer's and back faces' maps, the scene
     * layers, the water's heights, the receiver's and the lit opaque
     * objects' maps. Emptied with the view each frame. */
    snell__textures textures;
} snell__view;

/* One glass object of a frame, resolved by the scene stage (render/scene.c). */
typedef struct snell__object {
    int index;                      /* in the frame's glass list */
    snell_mesh *mesh;               /* uploaded before prepare/draw */
    const snell_glass_resolved *glass;
    mat4 model, inv_model;
    mat3 normal_matrix;             /* inverse transpose of model's 3x3 */
    int mirrored;                   /* model's determinant < 0 or a mirrored camera (not both): winding flips */
    float bsphere[4];               /* world bounding sphere: centre, radius */
    float view_depth;               /* of the sphere's centre, along the view axis */
    const snell_mesh_analysis *analysis; /* NULL: not analysed (not needed, or failed) */
    unsigned env_texture;           /* what it sees: static env or its dynamic one, a cube or (env_paraboloid)
                                     * a 2D array of dual-paraboloid maps */
    int env_paraboloid;             /* env_texture is a 2D array of dual-paraboloid maps (SNELL__GLASS_ENV_PARABOLOID) */
    int screen_space;               /* 0 forward, else shaded on the screen-space stage's G-buffer:
                                     * SNELL__SCREEN_* (above) */
    int gid;                        /* its id in the G-buffer (index + 1) */
    float pixels_per_triangle;      /* its projected bounding sphere per front triangle */
    int scissor[4];                 /* that projection in window pixels: x, y, w, h */
    int front_whole;                /* screen space: the G-buffer holds its whole front surface (nothing
                                     * else in the G-buffer's depth over its scissor; render/stages.c) */
    const struct snell__method *method; /* this frame's method (frame/method.h), chosen by the glass stage */
    void *method_state;             /* its GL state (the renderer's, made on first use) */
    void *prepared;                 /* the method's resources for (mesh version, settings) */
    unsigned vao;                   /* 0: draw the mesh's own VAO; else the method's (vertex_array()):
                                     * the mesh's attributes plus attribute 2, a per-vertex scalar that
                                     * the kernel reads forward and the G-buffer keeps (its aux target) */
    int back_coarse;                /* the back-face pass draws the mesh's coarse copy (render/gbuffer.h) */
    int crosses_edge;               /* its projected bounding sphere reaches past the target's edge */
    int back_guard;                 /* pixels of guard band it asks of the back-face pass (0: none) */
    float scale;                    /* the resolution scale it is drawn at (render/glass_scale.h): 1 full;
                                     * s > 1: its method draws at 1/s of the grid per axis, in screen space */
    const char *budget_note;        /* AUTO by budget: the rung it was given and why (render/budget.c), else NULL */
    unsigned stage_bits;            /* what the frame's stages' kernel hooks add to its program's variant
                                     * (frame/stage.h; e.g. the layers stage's: its exit rays march the
                                     * scene layers, view.layers, not straight to the environment) */
} snell__object;

/* Defines for a program variant of the given output kind ("#define ...\n"). */
const char *snell__output_defines(snell__output_kind out);

#endif
