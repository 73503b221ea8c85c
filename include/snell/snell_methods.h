/* SPDX-License-Identifier: MIT */
/* snell_methods.h — each refraction method's parameters (snell_glass_material's
 * cubemap, wyman, oliveira, peel, exact, layered) and their enums. Included by
 * snell.h; zero is every field's default. docs/methods.md explains the methods
 * and, under "Parameters in depth", the parameters a line does not hold. */
#ifndef SNELL_SNELL_METHODS_H
#define SNELL_SNELL_METHODS_H

#ifdef __cplusplus
extern "C" {
#endif

/* How SNELL_METHOD_CUBEMAP packs normal and distance into one RGBA8 texel. */
typedef enum snell_ndcube_encoding {
    SNELL_NDCUBE_DEFAULT = 0,  /* SNELL_NDCUBE_PLAIN (lower error; OCT is cheaper, bench/BENCHMARKS.md) */
    SNELL_NDCUBE_PLAIN,        /* Unger 4.1: normal*0.5+0.5 in RGB, distance/radius in A (8 bits), filtered */
    SNELL_NDCUBE_OCT           /* octahedral normal in RG (8+8 bits), distance in BA (16 bits), nearest */
} snell_ndcube_encoding;

/* How a kernel computes reflectance at an interface. */
typedef enum snell_fresnel_model {
    SNELL_FRESNEL_DEFAULT = 0, /* the method's default (cubemap: SCHLICK) */
    SNELL_FRESNEL_SCHLICK,     /* Schlick's approximation, the MATCHED reference's model */
    SNELL_FRESNEL_EXACT        /* unpolarised dielectric Fresnel (mean of s and p), the FULL reference's */
} snell_fresnel_model;

typedef enum snell_inner_fresnel {
    SNELL_INNER_FRESNEL_AUTO = 0, /* on where it pays (cubemap: convex meshes; bench/BENCHMARKS.md) */
    SNELL_INNER_FRESNEL_OFF,
    SNELL_INNER_FRESNEL_ON
} snell_inner_fresnel;

/* SNELL_METHOD_CUBEMAP's parameters (material.cubemap); zero = the default
 * snell_glass_defaults() reports. All changeable per frame: the first frame
 * with a new (iterations, linear_steps, encoding, max_interfaces == 1 without
 * absorption or not) builds that search program (step counts are compile-time
 * constants of the shader; 8 programs are kept) and a new face_size or
 * encoding bakes that mesh's cubemap; frames with settings already used
 * allocate nothing. */
typedef struct snell_cubemap_params {
    int iterations;            /* binary-search steps per interface, 1..32 (default 6) */
    int linear_steps;          /* linear pre-search steps before the binary search, 0..32 (default 0) */
    int max_interfaces;        /* surfaces processed per path, 1..8 (1 = single surface, 2 = entry +
                                * exit, more = internal reflections; default 2) */
    int face_size;             /* normal+distance cubemap face, 16..2048 texels (default 256) */
    snell_ndcube_encoding encoding;
    snell_fresnel_model fresnel; /* reflectance at the interfaces (default Schlick, the MATCHED model) */
    /* Fresnel at the exit too; AUTO (default) on for convex meshes */
    snell_inner_fresnel inner_fresnel;
} snell_cubemap_params;

#define SNELL_CUBEMAP_MAX_ITERATIONS 32
#define SNELL_CUBEMAP_MAX_LINEAR_STEPS 32
#define SNELL_CUBEMAP_MAX_INTERFACES 8

/* How finely the image-space methods' back-face pass draws the mesh. */
typedef enum snell_back_detail {
    SNELL_BACK_DETAIL_DEFAULT = 0, /* SNELL_BACK_DETAIL_AUTO */
    SNELL_BACK_DETAIL_AUTO,        /* a coarse copy (a quarter of the triangles, within 1% of the extent,
                                    * made once per mesh) when the mesh's triangles are below 8 px each:
                                    * cheaper, slightly less accurate (bench/BENCHMARKS.md) */
    SNELL_BACK_DETAIL_FULL         /* always the mesh itself */
} snell_back_detail;

/* SNELL_METHOD_WYMAN's parameters (material.wyman); zero = the default. */
typedef struct snell_wyman_params {
    snell_back_detail back_detail;
    int guard_band;            /* percent of the target height drawn around it in the back-face pass for an
                                * object that crosses the target's edge (its light may leave off-screen);
                                * -1 none, 1..25, default 10 */
} snell_wyman_params;

#define SNELL_MAX_GUARD_BAND 25

/* SNELL_METHOD_OLIVEIRA's parameters (material.oliveira); zero = the default.
 * Step counts are compile-time constants of its shader, as for the cubemap
 * (one program per (linear_steps, iterations) pair, 8 kept). */
typedef struct snell_oliveira_params {
    int linear_steps;          /* linear steps along the refracted ray before the binary search, 0..32
                                * (default 8) */
    int iterations;            /* binary-search steps per interface, 1..32 (default 6); the search also
                                * stops when a step spans less than a pixel */
    int max_interfaces;        /* surfaces processed per path, 2..8 (2 = entry + exit, more = internal
                                * reflections; default 2) */
    snell_back_detail back_detail;
    int guard_band;            /* as snell_wyman_params.guard_band */
    snell_fresnel_model fresnel; /* reflectance at the interfaces (default Schlick, the MATCHED model) */
    snell_inner_fresnel inner_fresnel; /* as the cubemap's: the exit transmits 1 - F and the internal
                                        * reflection is searched once more and refracted out; AUTO
                                        * (default) on for convex meshes (bench/BENCHMARKS.md) */
} snell_oliveira_params;

#define SNELL_OLIVEIRA_MAX_LINEAR_STEPS 32
#define SNELL_OLIVEIRA_MAX_ITERATIONS 32
#define SNELL_OLIVEIRA_MAX_INTERFACES 8
/* Which of the seed's fixes for the layer search (Wang 2014, 3.5) run in
 * SNELL_METHOD_PEEL; the others are for measuring each fix's effect. */
typedef enum snell_peel_fixes {
    SNELL_PEEL_FIXES_DEFAULT = 0, /* SNELL_PEEL_FIXES_BOTH */
    SNELL_PEEL_FIXES_NONE,        /* the plain layer-pair search */
    SNELL_PEEL_FIXES_DISCONTINUITY, /* 3.5.1: a crossing at a depth jump larger than the linear step is
                                     * re-checked against the layers there and skipped if the medium is
                                     * unchanged (case 2) */
    SNELL_PEEL_FIXES_MERGE,       /* 3.5.2: where layers 2k, 2k+1 are empty, an inside ray uses 2k-2, 2k-1 */
    SNELL_PEEL_FIXES_BOTH
} snell_peel_fixes;

/* Where SNELL_METHOD_PEEL's first layer (the front surface) comes from. */
typedef enum snell_peel_layer0 {
    SNELL_PEEL_LAYER0_GBUFFER = 0, /* default: from the screen-space G-buffer where that pays, else peeled */
    SNELL_PEEL_LAYER0_PEEL         /* always peeled (one more pass of the mesh) */
} snell_peel_layer0;

/* SNELL_METHOD_PEEL's parameters (material.peel); zero = the default. Step
 * counts are compile-time constants of the search program (one per setting,
 * built on first use). */
typedef struct snell_peel_params {
    int layers;                /* depth layers peeled, 2..8 (default 4, as the seed argues; fewer are
                                * peeled where the mesh's depth_complexity or the object's last
                                * peels (one past the layers they found non-empty) allow) */
    int linear_steps;          /* linear search steps over the bounding diameter, 1..128 (default 16; the
                                * seed's 50 cost more for little less error, bench/BENCHMARKS.md) */
    int binary_steps;          /* binary refinement steps after a linear crossing, 1..16 (default 6) */
    int max_interfaces;        /* surfaces processed per path, 1..10 (1 = single surface; then exits,
                                * re-entries, TIR bounces; default 8) */
    snell_peel_fixes fixes;
    snell_fresnel_model fresnel; /* reflectance at the interfaces (default Schlick, the MATCHED model) */
    /* Fresnel at the last exit too; AUTO (default) on for every mesh */
    snell_inner_fresnel inner_fresnel;
    snell_peel_layer0 layer0;
} snell_peel_params;

#define SNELL_PEEL_MAX_LAYERS 8
#define SNELL_PEEL_MAX_INTERFACES 10

/* Whether AUTO may choose SNELL_METHOD_EXACT. */
typedef enum snell_exact_auto {
    SNELL_EXACT_AUTO_DEFAULT = 0, /* SNELL_EXACT_AUTO_NEVER */
    SNELL_EXACT_AUTO_NEVER,       /* only an explicit material.method = EXACT uses it */
    SNELL_EXACT_AUTO_ALLOW        /* AUTO may pick it where no cheaper method is adequate (open or
                                   * non-manifold meshes, which AUTO otherwise draws with single); on a mesh a
                                   * cheaper method represents AUTO still picks that one */
} snell_exact_auto;

/* How exact's BVH nodes store their bounds. */
typedef enum snell_exact_nodes {
    SNELL_EXACT_NODES_DEFAULT = 0,  /* F32 */
    SNELL_EXACT_NODES_F32,          /* RGBA32F, two texels a node */
    SNELL_EXACT_NODES_Q16           /* 16 bits a coordinate relative to the root box, rounded outward, one
                                     * RGBA32UI texel a node (bench/BENCHMARKS.md, "Exact") */
} snell_exact_nodes;

/* How exact walks its tree. */
typedef enum snell_exact_walk {
    SNELL_EXACT_WALK_DEFAULT = 0,   /* STACK, but STACKLESS on GPUs whose compiler keeps the stack in registers
                                     * (Mali Bifrost: it spills there; bench/notes/device_tuning.md) */
    SNELL_EXACT_WALK_STACKLESS,     /* escape indices: no per-pixel array, no depth bound (GPUs where the
                                     * stack spills) */
    SNELL_EXACT_WALK_STACK          /* near-first with a 32-entry stack a pixel; pixels whose walk would
                                     * overflow it (a tree deeper than 32) fall back as past the budget */
} snell_exact_walk;

/* Whether exact's chain re-enters the object it left (a concave mesh: the
 * bunny's ear seen through its head). */
typedef enum snell_exact_reentry {
    SNELL_EXACT_REENTRY_DEFAULT = 0, /* OFF */
    SNELL_EXACT_REENTRY_OFF,         /* the MATCHED model: light that left sees the object no more */
    SNELL_EXACT_REENTRY_ON           /* it enters again, wholly (no Fresnel there), the cap counting on */
} snell_exact_reentry;

/* SNELL_METHOD_EXACT's parameters (material.exact); zero = the default. The
 * budget is a compile-time constant of the traversal program (one program per
 * (budget, node format, absorption, shading), built on first use, 8 kept); the
 * BVH is the mesh's, built once per node format (the reference tracer's SAH
 * build) and refitted, not rebuilt, when snell_mesh_set_vertices moves the
 * vertices. */
typedef struct snell_exact_params {
    int max_interfaces;        /* surfaces processed per path, 1..10 (1 = single surface with the exact path
                                * length for absorption; default 8); the MATCHED reference's cap */
    /* BVH nodes a pixel may visit, 64..65536 (default 4096); past it: single */
    int node_budget;
    snell_exact_nodes node_format;
    snell_exact_auto auto_pick;
    snell_exact_walk walk;
    /* The FULL model's next terms (snell_ref_terms: the MATCHED reference with
     * the same terms is what they compute; docs/methods.md, "exact"). */
    snell_fresnel_model fresnel;       /* default Schlick */
    snell_inner_fresnel inner_fresnel; /* the first exit transmits 1 - F, its reflection followed to its exit;
                                        * AUTO: off */
    snell_exact_reentry reentry;
} snell_exact_params;

#define SNELL_EXACT_MAX_INTERFACES 10
#define SNELL_EXACT_DEFAULT_INTERFACES 8
#define SNELL_EXACT_DEFAULT_BUDGET 4096

/* SNELL_METHOD_LAYERED's parameters (material.layered); zero = the default.
 * The layers are baked once per (mesh version, face size, layers) and kept
 * in the renderer's prepared cache: face_size^2 * 6 * (layers + one slice
 * per four) * 8 bytes of RGBA16F (128, 4: 3.75 MiB; a convex mesh, one
 * layer: 1.5 MiB; snell_object_stats.counters reports the layers used,
 * whether they were capped, and the KiB). */
typedef struct snell_layered_params {
    int layers;                /* distance-map layers, 1..8 (default 4): the first `layers` surfaces along each
                                * direction from the centre; the bake stops at the first empty layer. A
                                * convex mesh is baked into one (it holds every surface) */
    int face_size;             /* texels a cube face side, 16..1024 (default 128) */
    int linear_steps;          /* linear march steps from a point to the bounding sphere's far side,
                                * 1..64 (default 24) */
    int binary_steps;          /* binary refinement steps after a crossing, 1..16 (default 6) */
    int convex_steps;          /* on a convex mesh that one layer holds (no march): the tangent-plane steps
                                * to each exit, 1..16 (default 2; half as many, at least one, for the inner
                                * Fresnel's internal reflection) */
    int max_interfaces;        /* surfaces processed per path, 1..10 (default 8: exits, re-entries, TIR) */
    /* Fresnel at the last exit too (1 - F out; the internal reflection F
     * followed one march more): AUTO on convex meshes (as the cubemap's). */
    snell_inner_fresnel inner_fresnel;
} snell_layered_params;

/* SNELL_METHOD_HYBRID's parameters (material.hybrid); zero = the default.
 * The hybrid draws the cubemap method (material.cubemap's parameters) with a
 * doubt test per pixel, and the exact method (material.exact's) on the
 * pixels it doubts, in the same frame: the cubemap pass leaves those pixels'
 * depth unwritten (or at the far plane), and exact's pass, depth-tested
 * LESS, shades only them. A pixel is doubted when the front surface or the
 * exit found lies off the surface the cubemap holds by more than `doubt`
 * thousandths of its radius (hidden from its centre, or the search did not
 * converge), or the path did not leave the object within
 * hybrid.max_interfaces (total internal reflections past the cap). */
typedef enum snell_hybrid_doubted {
    SNELL_HYBRID_DOUBTED_DEFAULT = 0, /* SNELL_HYBRID_DOUBTED_EXACT */
    SNELL_HYBRID_DOUBTED_EXACT,       /* exact on the doubted pixels */
    SNELL_HYBRID_DOUBTED_SHOW         /* the doubted pixels magenta, no exact pass (to see the mask) */
} snell_hybrid_doubted;

typedef struct snell_hybrid_params {
    int doubt;                 /* threshold, thousandths of the cubemap's radius, 1..1000 (default 20) */
    snell_hybrid_doubted doubted;
    int max_interfaces;        /* the cubemap pass's cap on surfaces per path, 1..8 (default 4); its
                                * paths still inside at the cap are doubted */
} snell_hybrid_params;

#define SNELL_HYBRID_DEFAULT_DOUBT 20

#define SNELL_LAYERED_MAX_LAYERS 8
#define SNELL_LAYERED_MAX_INTERFACES 10
#define SNELL_EXACT_MIN_BUDGET 64
#define SNELL_EXACT_MAX_BUDGET 65536

#ifdef __cplusplus
}
#endif
#endif
