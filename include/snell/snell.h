/* SPDX-License-Identifier: MIT */
/* snell — real-time refractive glass on OpenGL ES 3.0 over EGL. A frame:
 * snell_ctx_create (headless, or your context: SNELL_BACKEND_EXTERNAL),
 * snell_mesh_load, snell_env_create, snell_renderer_create, then fill a
 * snell_frame_desc (env, camera, glass objects, optionally opaque objects,
 * light, water, your depth and backdrop), snell_render, and for an offscreen
 * target snell_renderer_read_rgba. The sections below follow that order; each
 * method's parameters are in snell_methods.h. The rules every call follows
 * (status, zero = default, opaque handles, units, what is undefined) and the
 * longer story of the fields: docs/integrating.md. */
#ifndef SNELL_SNELL_H
#define SNELL_SNELL_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SNELL_VERSION_MAJOR 0
#define SNELL_VERSION_MINOR 1
#define SNELL_VERSION_PATCH 0

/* ------------------------------------------------------------------ status */
typedef enum snell_status {
    SNELL_OK = 0,
    SNELL_E_INVALID_ARG,  /* a parameter is NULL, out of range or inconsistent */
    SNELL_E_IO,           /* a file could not be opened or read/written */
    SNELL_E_PARSE,        /* a file's content is malformed */
    SNELL_E_GL,           /* a GL call, shader compile or link failed */
    SNELL_E_EGL,          /* no EGL display/config/context could be made (EXTERNAL: none current) */
    SNELL_E_UNSUPPORTED,  /* a needed extension or feature is missing */
    SNELL_E_NOMEM,        /* an allocation failed or a size is absurd */
    SNELL_E_LIMIT         /* input exceeds a documented limit */
} snell_status;

/* Name of a status code ("SNELL_E_PARSE"). Never NULL. */
const char *snell_status_str(snell_status s);

/* The components this build of the library holds, by the names of its CMake
 * options (docs/ARCHITECTURE.md "Components"): "ref", "lm2d", "water", "png", "gltf" and
 * each method's name ("peel", ...). 1 if built in; 0 if left out (its API
 * then returns SNELL_E_UNSUPPORTED) or unknown. snell_build_components()
 * lists those built in, separated by spaces. */
int snell_build_has(const char *component);
const char *snell_build_components(void);

typedef struct snell_ctx snell_ctx;
typedef struct snell_mesh snell_mesh;
typedef struct snell_env snell_env;
typedef struct snell_renderer snell_renderer;
typedef struct snell_water snell_water;  /* snell_water.h */

/* Detailed message of the last failure. With ctx == NULL: the last failure on
 * this thread of a call that had no context (or of snell_ctx_create). */
const char *snell_last_error(const snell_ctx *ctx);

/* ------------------------------------------------------------- allocation */
typedef struct snell_allocator {
    void *(*alloc)(size_t size, void *user);               /* NULL: malloc */
    void *(*realloc)(void *ptr, size_t size, void *user);  /* NULL: realloc */
    void (*free)(void *ptr, void *user);                   /* NULL: free */
    void *user;
} snell_allocator;

/* ---------------------------------------------------------------- logging */
typedef enum snell_log_level {
    SNELL_LOG_DEBUG = 0,
    SNELL_LOG_INFO,
    SNELL_LOG_WARN,
    SNELL_LOG_ERROR
} snell_log_level;

typedef void (*snell_log_fn)(snell_log_level level, const char *msg, void *user);

/* ---------------------------------------------------------------- context */
typedef enum snell_backend {
    SNELL_BACKEND_DEFAULT = 0,  /* SURFACELESS, which itself falls back to a pbuffer */
    SNELL_BACKEND_SURFACELESS,  /* EGL_MESA_platform_surfaceless + EGL_KHR_surfaceless_context */
    SNELL_BACKEND_PBUFFER,      /* any EGL display, 1x1 pbuffer surface */
    SNELL_BACKEND_EXTERNAL      /* the caller's current GLES 3.0 context (EGL, GLX or other); GL state is restored */
} snell_backend;

typedef struct snell_ctx_desc {
    snell_backend backend;
    snell_allocator allocator;
    snell_log_fn log;          /* receives library messages and KHR_debug output */
    void *log_user;
    int gl_debug;              /* nonzero: request a debug context, install KHR_debug callback */
    /* bytes one request sized by input data may ask; 0 = SNELL_DEFAULT_MEMORY_BUDGET */
    size_t memory_budget;
    /* a device profile ("rpi-v3d", ...); NULL = $SNELL_DEVICE_PROFILE, else none */
    const char *device_profile;
} snell_ctx_desc;

/* 256 MiB: on a 1 GB board (RAM shared by the OS, the app, and the GPU's
 * copies of what it draws) a request beyond a quarter of it is the point
 * where a load starts pushing the system towards the OOM killer. It holds
 * every accepted image (2^25 pixels, 128 MiB as RGBA8) and meshes of a few
 * million vertices (OBJ parse ~70 bytes per vertex). */
#define SNELL_DEFAULT_MEMORY_BUDGET ((size_t)256 << 20)

/* Owned backends make their context current on the calling thread; all snell
 * calls on a context must come from the thread where it is current.
 * snell_ctx_destroy releases an owned context (no context is current after it
 * if it was current); EXTERNAL leaves the caller's context as it is.
 *
 * One current context per thread: creating a second owned context makes it
 * current, so the first stops being current. Calls that draw or make GL objects
 * (snell_render, snell_renderer_create, snell_env_create with a ctx, the
 * read-backs) check that their context is current and fail with
 * SNELL_E_INVALID_ARG saying so; switch with snell_ctx_make_current.
 * Destroy calls make an owned context current for the moment if needed.
 *
 * Objects may be destroyed before or after their context: after
 * snell_ctx_destroy, destroying a mesh, environment, renderer, reference or
 * 2D object frees its memory only (its GL objects went with an owned GL
 * context; with EXTERNAL they stay in the host's context, so destroy them
 * first to free those). snell_render and the read-backs then fail with
 * SNELL_E_INVALID_ARG, as does creating a mesh, environment or renderer with
 * the destroyed context while such objects keep it alive.
 *
 * A mesh made without a context (ctx NULL) gets its GPU buffers in the
 * context of the first frame that draws it; a frame of another context
 * refuses it (SNELL_E_INVALID_ARG), as it refuses meshes and environments
 * made with another context. */
snell_status snell_ctx_create(const snell_ctx_desc *desc, snell_ctx **out);
void snell_ctx_destroy(snell_ctx *ctx);
/* Makes an owned context current on the calling thread (SNELL_E_EGL if EGL
 * refuses). EXTERNAL: the host makes its context current; this only checks
 * that it is (SNELL_E_INVALID_ARG if not). */
snell_status snell_ctx_make_current(snell_ctx *ctx);
/* The backend actually in use (SURFACELESS may have fallen back to PBUFFER). */
snell_backend snell_ctx_backend(const snell_ctx *ctx);
const char *snell_backend_str(snell_backend b);
/* Nonzero if the current GL context advertises the extension (exact token). */
int snell_ctx_has_gl_extension(const snell_ctx *ctx, const char *name);
/* The shader precision policy chosen for this context, with its reason, e.g.
 * "highp: llvmpipe emulates mediump in software": mediump where the driver has
 * real fp16, highp where mediump is emulated or as precise as highp. */
const char *snell_ctx_precision(snell_ctx *ctx);
/* GL_RENDERER string of the context. */
const char *snell_ctx_gl_renderer(const snell_ctx *ctx);

/* The limits snell checks what it builds against (GLES 3.0's names:
 * GL_MAX_TEXTURE_SIZE, GL_MAX_CUBE_MAP_TEXTURE_SIZE, GL_MAX_ARRAY_TEXTURE_LAYERS,
 * GL_MAX_RENDERBUFFER_SIZE, GL_MAX_SAMPLES, GL_MAX_TEXTURE_IMAGE_UNITS,
 * GL_MAX_FRAGMENT_UNIFORM_VECTORS, GL_MAX_VERTEX_UNIFORM_VECTORS,
 * GL_MAX_VARYING_VECTORS, GL_MAX_DRAW_BUFFERS). */
typedef enum snell_limit {
    SNELL_LIMIT_TEXTURE_SIZE, SNELL_LIMIT_CUBE_SIZE, SNELL_LIMIT_ARRAY_LAYERS, SNELL_LIMIT_RENDERBUFFER_SIZE,
    SNELL_LIMIT_SAMPLES, SNELL_LIMIT_FRAGMENT_UNITS, SNELL_LIMIT_FRAGMENT_VECTORS, SNELL_LIMIT_VERTEX_VECTORS,
    SNELL_LIMIT_VARYINGS, SNELL_LIMIT_DRAW_BUFFERS, SNELL_LIMIT_COUNT
} snell_limit;
typedef struct snell_device_limits {
    const char *profile;            /* the device profile in force, "none" without one */
    int limit[SNELL_LIMIT_COUNT];   /* the GL context's, lowered to the profile's */
    const char *cost_model;         /* the GPU whose method costs AUTO ranks by ("V3D 4.2", "Adreno 630",
                                     * "Mali-G52": bench/devices/COSTS.md), "reference" for any other */
} snell_device_limits;
void snell_ctx_limits(const snell_ctx *ctx, snell_device_limits *out);
/* "texture_size", "cube_size", ...: the limit's name in messages and JSON. */
const char *snell_limit_str(snell_limit which);

/* ------------------------------------------------------------------- mesh */
/* Meshes are CPU data (positions, smooth normals, triangle indices) plus GPU
 * buffers created lazily on first draw. ctx may be NULL for CPU-only use
 * (loaders, reference tracer); such a mesh is drawn in the context of the
 * first frame that uses it, and only there (see snell_ctx_destroy). */
typedef struct snell_mesh_desc {
    const float *positions;    /* 3 * vertex_count, object space */
    const float *normals;      /* optional: 3 * vertex_count; NULL = smooth normals computed */
    const uint32_t *indices;   /* 3 * triangle_count; NULL = non-indexed triangles */
    uint32_t vertex_count;
    uint32_t triangle_count;   /* with indices == NULL: vertex_count / 3 */
} snell_mesh_desc;

snell_status snell_mesh_create(snell_ctx *ctx, const snell_mesh_desc *desc, snell_mesh **out);
void snell_mesh_destroy(snell_mesh *mesh);

/* Loaders. snell_mesh_load picks OBJ, glTF (.gltf/.glb), .3ds or .jobj by file extension. */
snell_status snell_mesh_load(snell_ctx *ctx, const char *path, snell_mesh **out);
snell_status snell_mesh_load_obj(snell_ctx *ctx, const char *path, snell_mesh **out);
snell_status snell_mesh_load_obj_mem(snell_ctx *ctx, const char *data, size_t size, snell_mesh **out);
/* glmark2's model formats. Autodesk .3ds: the triangle meshes only (every
 * object's vertex and face lists as stored: Z up, the local frame not applied;
 * materials, lights, cameras and keyframes skipped). glmark2's .jobj text: its
 * v, vn and i lines (vt and vc ignored). Malformed input: SNELL_E_PARSE with
 * the byte offset (3DS) or line (jobj). */
snell_status snell_mesh_load_3ds_mem(snell_ctx *ctx, const void *data, size_t size, snell_mesh **out);
snell_status snell_mesh_load_jobj_mem(snell_ctx *ctx, const char *data, size_t size, snell_mesh **out);
/* glTF 2.0 (.gltf with external/embedded buffers, or .glb): every triangle primitive
 * of the default scene, node transforms applied. SNELL_E_UNSUPPORTED if built without,
 * for glTF 1.0 and for files that require an extension the loader does not handle
 * (named in the message, e.g. KHR_draco_mesh_compression).
 * Files are untrusted (docs/integrating.md "Files are untrusted"): buffer and image URIs are
 * resolved, after percent-decoding, against the model's folder only; an absolute
 * path, a path that leaves the folder (also through a symlink: real paths are
 * compared) or a non-regular file is refused (SNELL_E_IO; the message names the
 * URI, never the refused file's size). data: URIs need no file. Images are not
 * decoded (geometry only); a refused image is skipped. snell_mesh_load_gltf_mem
 * reads no file at all. */
snell_status snell_mesh_load_gltf(snell_ctx *ctx, const char *path, snell_mesh **out);
snell_status snell_mesh_load_gltf_mem(snell_ctx *ctx, const void *data, size_t size, snell_mesh **out);

/* Loader options (bits of the flags of snell_mesh_load_gltf_ex). */
typedef enum snell_load_flags {
    SNELL_LOAD_DEFAULT = 0,
    /* Let glTF URIs name files outside the model's folder (absolute paths, "..",
     * symlinks out of it): only for files the caller trusts. Non-regular
     * files (devices, FIFOs, directories) are refused even so. */
    SNELL_LOAD_ALLOW_OUTSIDE_FOLDER = 1 << 0
} snell_load_flags;
/* snell_mesh_load_gltf with flags (snell_load_flags bits; 0 = the same call). */
snell_status snell_mesh_load_gltf_ex(snell_ctx *ctx, const char *path, unsigned flags, snell_mesh **out);

typedef enum snell_shape {
    SNELL_SHAPE_SPHERE = 0,  /* UV sphere, radius 1 */
    SNELL_SHAPE_CUBE,        /* cube [-1,1]^3, flat faces (24 vertices) */
    SNELL_SHAPE_TORUS,       /* major radius 1, minor radius 0.4, around +Y */
    SNELL_SHAPE_GOBLET,      /* closed lathe goblet (concave bowl, stem, foot), height 2 */
    SNELL_SHAPE_PRISM        /* triangular prism, flat faces (18 vertices): an equilateral
                              * triangle of circumradius 1 in the XZ plane with an edge (the apex)
                              * on +X and the base face towards -X, y from -1 to 1 */
} snell_shape;

typedef struct snell_shape_desc {
    snell_shape shape;
    int segments;            /* around the axis; 0 = 64 */
    int rings;               /* along the profile; 0 = 32 */
} snell_shape_desc;

snell_status snell_mesh_create_shape(snell_ctx *ctx, const snell_shape_desc *desc, snell_mesh **out);

/* Centre the bounding box at the origin and scale so the bounding sphere about
 * that centre has the given radius (0 = 1). Recomputes bounds. Computed in
 * double, so meshes with coordinates up to the float range (1e38) normalise;
 * SNELL_E_INVALID_ARG for a radius above FLT_MAX / 2 or a mesh whose vertices
 * all coincide. (Creating or loading a mesh whose extent or bounding radius
 * exceeds FLT_MAX fails with SNELL_E_LIMIT, giving the size.) */
snell_status snell_mesh_normalize(snell_mesh *mesh, float radius);

/* Deformation: replaces every vertex position (3 * vertex_count floats, same
 * count and triangles) and the normals (NULL = smooth normals recomputed),
 * e.g. each frame of an animated mesh. The mesh gets a new geometry version:
 * its GPU copy is re-uploaded on the next frame that draws it, and what is
 * cached per version (the analysis, a method's prepared resources such as the
 * cubemap's bake or Wyman's thicknesses) is rebuilt when next needed; image-
 * space methods with nothing prepared (OLIVEIRA) redo nothing else. Rejects
 * non-finite values, zero normals and extents beyond the float range
 * (SNELL_E_INVALID_ARG / SNELL_E_LIMIT) and then leaves the mesh unchanged. */
snell_status snell_mesh_set_vertices(snell_mesh *mesh, const float *positions, const float *normals);

uint32_t snell_mesh_vertex_count(const snell_mesh *mesh);
uint32_t snell_mesh_triangle_count(const snell_mesh *mesh);
const float *snell_mesh_positions(const snell_mesh *mesh);   /* 3 * vertex_count */
const float *snell_mesh_normals(const snell_mesh *mesh);     /* 3 * vertex_count, unit */
const uint32_t *snell_mesh_indices(const snell_mesh *mesh);  /* 3 * triangle_count */
void snell_mesh_bounds(const snell_mesh *mesh, float min[3], float max[3]);

/* What a mesh needs (docs/methods.md), found with exact ray casts against
 * a CPU BVH in object space. The centre is the point the normal+distance
 * cubemap (SNELL_METHOD_CUBEMAP) is rendered from: among candidates (vertex
 * average, box centre, surface and volume centroids, an interior grid) the one
 * that is inside and sees the most surface. hidden_fraction is the share of
 * surface area whose line from the centre crosses the surface anywhere else
 * too (hidden behind other surface, or hiding surface farther out): the part
 * the cubemap method, which keeps one surface per direction, cannot represent
 * (0 iff the mesh is star-shaped about the centre, e.g. any convex mesh). */
typedef struct snell_mesh_analysis {
    float centre[3];         /* object space */
    float radius;            /* largest distance of a vertex from centre (object units) */
    float inner_radius;      /* distance from centre to the nearest surface point: the ball of
                              * this radius holds no surface (inside it if the centre is inside) */
    float hidden_fraction;   /* 0..1, area-weighted, +-1/sqrt(samples) sampling error */
    int samples;             /* surface sample points used for hidden_fraction */
    /* Topology below is on vertices welded by position (docs/integrating.md). */
    uint32_t welded_vertices;   /* distinct positions the triangles use, after welding */
    uint32_t boundary_edges;    /* edges with one triangle (holes, open rims) */
    uint32_t nonmanifold_edges; /* edges with three or more triangles (fins, doubled faces) */
    uint32_t flipped_edges;     /* edges whose two triangles run it the same way (inconsistent winding) */
    int closed;              /* none of these three (and some triangle): every edge has two triangles of
                              * opposite orientation (vertices where two sheets touch are not checked) */
    int convex;              /* closed, one piece, every edge locally convex within 4 weld
                              * tolerances, and no sampled line (depth_complexity) crossing
                              * it more than twice: the solid is convex */
    int inside;              /* closed and the centre's crossing parity was odd along 3 rays */
    int winding;             /* closed: +1 counter-clockwise triangles face outward (signed
                              * volume > 0), -1 they face inward; 0 open or zero volume */
    /* Depth complexity: surfaces crossed by lines through the bounding
     * sphere along sampled view directions (16 directions x 12x12 parallel
     * lines), what depth peeling needs (SNELL_METHOD_PEEL): a convex mesh
     * gives 2, a torus 4. */
    int depth_complexity;    /* the most surfaces any sampled line crosses */
    float deep_fraction;     /* of the sampled lines that hit the mesh, the share crossing more than 2 */
    uint32_t pieces;         /* connected pieces: triangles joined through welded corners (two
                              * separate balls: 2); the centre-based methods serve one */
} snell_mesh_analysis;

/* Analyzes the mesh (O(triangles) memory, O(n log n) time: the BVH build and
 * the weld dominate; docs/integrating.md). The renderer does this itself,
 * once per mesh version (cached on the mesh), for AUTO and the methods that
 * need it; this returns that cached result when there is one, and analyses
 * afresh otherwise; exposed so users can see why a mesh is (not) suited.
 * SNELL_E_INVALID_ARG for a mesh without area, SNELL_E_LIMIT for one whose
 * vertices are too densely clustered to weld (far below the weld tolerance,
 * in their thousands: not seen in real meshes) and for one whose ray casts
 * exceed the analysis's work bound (2^23 + 256 per triangle BVH steps, over
 * 10x what real meshes need: thousands of triangles on top of each other, e.g.
 * one OBJ face of 40,000 repeated corners, which then fails at once). */
snell_status snell_mesh_analyze(const snell_mesh *mesh, snell_mesh_analysis *out);

/* How the renderer lays a mesh out for the GPU: the order of the triangles
 * (the same triangles, each with its winding, either way) that the vertex
 * cache sees. meshoptimizer's vertex-cache optimisation costs about the sum
 * over vertices of (triangle corners on the vertex)^2 steps: a few per
 * corner on real meshes, but billions for one OBJ face of a hundred thousand
 * repeated corners on 3 vertices. Over its bound (2^25 + 64 per corner: at
 * most a small multiple of a real mesh of its size) the optimisation is skipped for
 * meshoptimizer's linear-time FIFO order (order SNELL_GPU_ORDER_LINEAR),
 * copies of a triangle are not drawn twice (copies_hidden), this is
 * logged once a mesh at WARN by the upload, and the coarse copy of the
 * back-face pass (whose simplifier costs the same) is not made (logged
 * when asked for): the full mesh is drawn. snell_mesh_simplify refuses such a
 * mesh (SNELL_E_LIMIT) after removing its duplicate triangles. */
typedef enum snell_gpu_order {
    SNELL_GPU_ORDER_SOURCE = 0, /* the mesh's own order (built without meshoptimizer) */
    SNELL_GPU_ORDER_CACHE,      /* meshoptimizer's vertex-cache optimisation (real meshes) */
    SNELL_GPU_ORDER_LINEAR      /* reorder skipped: order_work > order_work_limit; its FIFO order */
} snell_gpu_order;

typedef struct snell_mesh_gpu_stats {
    snell_gpu_order order;
    double order_work;       /* the reorder's work estimate: sum over vertices of corners^2 */
    double order_work_limit; /* its bound: 2^25 + 64 * 3 * triangle_count */
    uint32_t max_valence;    /* the most triangle corners on one vertex */
    int coarse_allowed;      /* 1: a coarse copy may be made (CACHE order, 4096+ triangles) */
    uint32_t copies_hidden;  /* LINEAR only: same-facing copies of a triangle after its first, made
                              * degenerate in the GPU copy (they would draw the same pixels again) */
    char reason[192];        /* one line: the order and why */
} snell_mesh_gpu_stats;

/* The GPU layout decision for mesh, from its triangles alone (no GL needed;
 * O(vertices + triangles), allocates a count per vertex): the one the
 * renderer's upload makes. SNELL_E_INVALID_ARG for NULL, SNELL_E_NOMEM. */
snell_status snell_mesh_gpu_stats_get(const snell_mesh *mesh, snell_mesh_gpu_stats *out);

/* Level of detail: a simplified copy of a mesh, for meshes whose triangles
 * are far below a pixel (meshoptimizer's edge-collapse simplifier). OFF BY
 * DEFAULT: the renderer never simplifies on its own; a caller who wants LOD
 * creates the copy and draws it instead. snell-bench's lod=R key measures the
 * error it adds against the original mesh, and bench/BENCHMARKS.md states
 * when it pays ("Level of detail"). Zero means the default for every field. */
typedef struct snell_simplify_desc {
    float target_ratio;  /* share of the source's triangles to keep, 0 < r <= 1; 0 = no count
                          * target (as few as target_error allows). The simplifier may stop
                          * short of it (topology, locked border, target_error) */
    float target_error;  /* most a surface point may move, relative to the largest side of the
                          * mesh's bounding box (meshoptimizer's measure), >= 0; 0 = default:
                          * unbounded with a target_ratio (the ratio decides), 0.01 without one */
    int lock_border;     /* nonzero: vertices on boundary edges (an open mesh's rims and holes)
                          * stay, so the boundary is kept edge for edge; 0: rims simplify too */
} snell_simplify_desc;

/* What snell_mesh_simplify did. */
typedef struct snell_simplify_report {
    uint32_t triangles_before, triangles_after;
    uint32_t vertices_before, vertices_after;
    uint32_t welded_vertices;        /* distinct positions of the source (the analysis's weld) */
    float error;                     /* meshoptimizer's resulting error, relative as target_error
                                      * (the repair of non-manifold edges below is not in it) */
    float error_abs;                 /* the same in object units */
    uint32_t degenerate_removed;     /* triangles with two equal (welded) corners removed */
    uint32_t duplicate_pairs_removed; /* opposite-facing pairs on the same three vertices removed */
    uint32_t duplicates_removed;     /* same-facing copies of a triangle removed (one is kept) */
    uint32_t nonmanifold_collapsed;  /* edges where a collapse made two sheets meet (four triangles),
                                      * collapsed in turn so that a closed mesh stays closed */
} snell_simplify_report;

/* *out = a new mesh of ctx (NULL: CPU-only) simplified from src, which is not
 * changed. Vertices are welded by position first (the analysis's weld, so
 * split seams do not block or open), collapses keep source positions, normals
 * are recomputed smooth (hard creases are not kept); then degenerate
 * triangles and opposite-facing duplicate pairs are removed and edges where
 * the simplifier made two sheets meet are collapsed (both make a closed mesh
 * look open): a closed source stays closed (snell_mesh_analyze). report may
 * be NULL. SNELL_E_INVALID_ARG for NULL src/desc/out, a ratio outside [0, 1]
 * or NaN, an error < 0 or not finite, and a result with no triangle left (a
 * tiny ratio can collapse a closed mesh to nothing); SNELL_E_LIMIT beyond the
 * memory budget (scratch estimated at 120 bytes per source triangle and 100 per vertex) and for a mesh
 * the simplifier would take too long on (the cleaning is done before it
 * too; then the work estimate of snell_mesh_gpu_stats over
 * its bound: hundreds of thousands of triangles on one vertex); SNELL_E_UNSUPPORTED
 * when built without SNELL_WITH_MESHOPT. Memory is ctx's allocator's
 * (meshoptimizer's own scratch, freed before the call returns, is its
 * process-wide allocator's). */
snell_status snell_mesh_simplify(snell_ctx *ctx, const snell_mesh *src, const snell_simplify_desc *desc,
                                 snell_mesh **out, snell_simplify_report *report);

/* ------------------------------------------------------------ environment */
typedef enum snell_env_source {
    SNELL_ENV_PROCEDURAL = 0,  /* built in: sky gradient, sun, checkered floor */
    SNELL_ENV_FACES,           /* six square images: +X -X +Y -Y +Z -Z (GL cubemap layout) */
    SNELL_ENV_EQUIRECT,        /* one equirectangular (lat-long) image */
    SNELL_ENV_GL_TEXTURE       /* the host's GL_TEXTURE_CUBE_MAP (gl_texture), sampled where it is: not
                                * copied, so what the host draws into it shows in the next frame; no CPU
                                * copy, so what needs one (the reference tracer) refuses it with
                                * SNELL_E_UNSUPPORTED and snell_env_sample gives black */
} snell_env_source;

typedef struct snell_env_desc {
    snell_env_source source;
    const char *face_paths[6];   /* SNELL_ENV_FACES */
    const char *equirect_path;   /* SNELL_ENV_EQUIRECT */
    int face_size;               /* cubemap face size in texels; 0 = 512 (FACES: the images' size) */
    /* SNELL_ENV_EQUIRECT from memory, used when equirect_path is NULL: RGBA8,
     * top row first, equirect_width x equirect_height (at most 16384 a side and
     * 2^25 pixels, as images), e.g. an asset decoded by snell_image_decode.
     * Copied into the faces: the caller keeps ownership. */
    const uint8_t *equirect_rgba;
    int equirect_width, equirect_height;
    /* SNELL_ENV_GL_TEXTURE: a cube map of ctx's (current) context, face_size required; yours to delete */
    unsigned gl_texture;
} snell_env_desc;

/* Creates the cubemap texture (ctx needed) and keeps a CPU copy of the faces so
 * that references can sample exactly the same texels. ctx may be NULL: CPU only.
 * SNELL_ENV_GL_TEXTURE borrows the host's cube map instead (ctx required). */
snell_status snell_env_create(snell_ctx *ctx, const snell_env_desc *desc, snell_env **out);
void snell_env_destroy(snell_env *env);
int snell_env_face_size(const snell_env *env);
/* Bilinear sample in direction dir (need not be unit), as GL samples the cube
 * with GL_LINEAR: rgb in [0,1]. Edge texels are clamped per face (GL filters
 * across faces; the difference is confined to a one-texel seam). Black (0)
 * for a NULL env or dir and for a direction that is not finite. */
void snell_env_sample(const snell_env *env, const float dir[3], float rgb[3]);
/* Double-precision variant for the reference tracer. */
void snell_env_sample_d(const snell_env *env, const double dir[3], double rgb[3]);
/* The built-in procedural environment's exact radiance along dir (need not be
 * unit), rgb in [0,1]: what its faces sample (3x3 per texel) before they are
 * quantised and filtered, for measuring a look-up's error. Black for a NULL,
 * zero or non-finite dir. */
void snell_env_procedural_radiance(const double dir[3], double rgb[3]);

/* ------------------------------------------------------------------ glass */
/* How the exit of a light path through the glass is found. Methods are the
 * entries of a registry (snell_method_info); AUTO picks, per object, the
 * cheapest method whose preconditions the object's mesh and material meet
 * and says why in the frame statistics. */
typedef enum snell_method {
    SNELL_METHOD_AUTO = 0,     /* the cheapest method adequate for the object */
    SNELL_METHOD_SINGLE,       /* refraction at the front surface only (Unger 3.3); needs nothing */
    SNELL_METHOD_CUBEMAP,      /* two-sided: exit found in a normal+distance cubemap (Unger 4.1, Li et al.);
                                * needs a closed mesh with its centre inside */
    SNELL_METHOD_WYMAN,        /* two-sided in image space (Wyman 2005): exit point interpolated between the
                                * view-ray and inward-normal thicknesses, normal from a per-frame back-face
                                * pass; needs no bake, so works for any closed mesh */
    SNELL_METHOD_OLIVEIRA,     /* two-sided in image space (Oliveira and Brauwers 2007): the exit found by a
                                * conservative linear + binary search along the refracted ray against the
                                * back-face pass, TIR bounces; always shaded in screen space */
    SNELL_METHOD_PEEL,         /* multi-layer in image space (Wang 2014): depth-peeled layers of normal and
                                * depth, a ray-height-field search between them, up to N interfaces with TIR;
                                * for concave meshes (a view ray crossing more than two surfaces) */
    SNELL_METHOD_EXACT,        /* exact: the mesh's BVH ray-traced per pixel, the MATCHED reference's model;
                                * the dearest; AUTO only where exact.auto_pick allows */
    SNELL_METHOD_LAYERED,      /* multi-layer, view-independent (Umenhoffer et al. 2007): layered distance
                                * cube maps baked once per mesh version, re-entries included */
    SNELL_METHOD_HYBRID,       /* the cubemap where it trusts its answer, exact on the pixels it doubts, in
                                * one frame (material.hybrid); needs what the cubemap needs */
    SNELL_METHOD_COUNT_        /* number of values, not a method */
} snell_method;

/* Each method's parameters (snell_cubemap_params, ...): snell_methods.h. */
#include "snell_methods.h"
#include "snell_panels.h"

/* How a kernel renders a dispersive material (snell_glass_material.dispersion > 0).
 * SNELL_METHOD_EXACT always traces per channel (its traversal finds each
 * channel's true exits). */
typedef enum snell_dispersion_model {
    SNELL_DISPERSION_AUTO = 0,        /* the measured better trade: ONE_PATH (bench/BENCHMARKS.md,
                                       * "Dispersion") */
    SNELL_DISPERSION_PER_CHANNEL,     /* the kernel's whole trace three times, once with each channel's
                                       * IOR, each giving its own channel: 3x the cost */
    SNELL_DISPERSION_ONE_PATH         /* one trace with the green IOR; the red and blue directions are
                                       * refracted with their own IORs at the entry and at every
                                       * interface of that path (its normals, its events), and looked
                                       * up per channel at the end */
} snell_dispersion_model;

/* A glass material, named as glTF 2.0 names it so that a glTF material maps
 * onto it field by field. Zero means the default (snell_glass_defaults). */
typedef struct snell_glass_material {
    float ior;                     /* KHR_materials_ior "ior": 0 = 1.5; outside is 1 (0.05..100) */
    float attenuation_color[3];    /* KHR_materials_volume: the colour white light turns after
                                    * attenuation_distance inside; 0..1, all zero = white (none) */
    float attenuation_distance;    /* KHR_materials_volume, world units; 0 = infinite (no absorption) */
    /* 0: the mesh bounds a solid volume of glass. > 0: a thin wall of this
     * thickness (world units), e.g. a window pane or a bubble: light leaves in
     * the direction it entered, reflected and absorbed as by a slab (glTF's
     * thin-walled case; KHR_materials_volume's thicknessFactor 0). */
    float thickness;
    float tint[3];                 /* multiplies transmitted light (glTF baseColorFactor under
                                    * KHR_materials_transmission); all zero = white */
    /* KHR_materials_dispersion: 20 / Abbe number, 0..20; 0 = none; solids only */
    float dispersion;
    snell_dispersion_model dispersion_model; /* used when dispersion > 0 */
    snell_method method;           /* SNELL_METHOD_AUTO = chosen per object and frame */
    snell_cubemap_params cubemap;  /* used when the method (or AUTO's choice) is CUBEMAP */
    snell_wyman_params wyman;      /* used when it is WYMAN */
    snell_oliveira_params oliveira; /* used when it is OLIVEIRA */
    snell_peel_params peel;        /* used when the method (or AUTO's choice) is PEEL */
    snell_exact_params exact;      /* used when it is EXACT (which AUTO picks only if exact.auto_pick allows) */
    snell_layered_params layered;  /* used when it is LAYERED */
    snell_hybrid_params hybrid;    /* used when it is HYBRID (with cubemap's and exact's) */
    /* shaded at 1/scale per axis, silhouette at full; 0 = 1, 1..SNELL_MAX_GLASS_SCALE */
    float scale;
} snell_glass_material;

#define SNELL_MAX_GLASS_SCALE 8

/* A material with every default applied, and the per-unit absorption derived
 * from it (Beer-Lambert: sigma = -ln(attenuation_color) / attenuation_distance;
 * a colour channel of 0 counts as 1e-6). This is what the renderer and the
 * reference tracer use; CLIs print it instead of keeping their own copies. */
typedef struct snell_glass_resolved {
    snell_glass_material material; /* ior, tint, cubemap.* resolved; attenuation_distance
                                    * HUGE_VALF when there is no absorption */
    float absorption[3];           /* per world unit, rgb; 0 = none */
    int absorbs;                   /* any absorption > 0 */
    float ior_rgb[3];              /* the IOR of each colour channel (dispersion); all ior without */
    int disperses;                 /* a solid with dispersion > 0: the channels' IORs differ */
} snell_glass_resolved;

/* Resolves and validates `in` (NULL = all defaults) into *out. SNELL_E_INVALID_ARG
 * with a message naming the field when a value is out of range or not finite. */
snell_status snell_glass_defaults(const snell_glass_material *in, snell_glass_resolved *out);

/* Per-unit absorption -> the glTF form (distance 1, colour exp(-sigma)); for
 * callers that think in Beer-Lambert coefficients. */
void snell_glass_set_absorption(snell_glass_material *m, const float sigma[3]);

/* Dispersion from an Abbe number V_d (> 0; e.g. 64.2 for BK7, 55 for
 * diamond): m->dispersion = 20 / V_d. SNELL_E_INVALID_ARG for V_d <= 1 or
 * not finite (dispersion above 20), leaving m unchanged. */
snell_status snell_glass_set_abbe(snell_glass_material *m, float abbe);

/* ------------------------------------------------------- method registry */
/* One integer parameter of a method (enums are integers with value names). */
typedef struct snell_param_info {
    const char *name;              /* "max_interfaces": the name of the field it sets (the last part of
                                    * snell_glass_material.cubemap.max_interfaces), what CLIs accept as
                                    * name=value and snell_glass_set_param / get_param take */
    const char *help;
    int min, max;                  /* valid range of explicit values */
    int def;                       /* the resolved default */
    const char *const *value_names; /* enum parameters: name of each value min..max, else NULL */
    size_t offset;                 /* where it lives in snell_glass_material (offsetof; an int or an enum) */
} snell_param_info;

/* A number a method reports per object and frame (snell_object_stats.counters). */
typedef struct snell_counter_info {
    const char *name;              /* "layers_peeled" */
    const char *help;              /* what it counts, one line */
} snell_counter_info;
#define SNELL_MAX_METHOD_COUNTERS 4

typedef struct snell_method_info {
    snell_method method;
    const char *name;              /* "single", "cubemap" */
    const char *summary;           /* one line */
    const char *needs;             /* its preconditions, in words */
    int param_count;
    const snell_param_info *params;
    int counter_count;             /* 0..SNELL_MAX_METHOD_COUNTERS */
    const snell_counter_info *counters;
    /* The MATCHED reference model it approximates (snell_ref.h): surfaces per
     * path, a fixed count, or 0 for its "max_interfaces" parameter's value; 1 if
     * absorption runs over the bounding-sphere chord (the single-surface
     * model), 0 over the traced path. */
    int ref_interfaces;
    int ref_chord_absorption;
    const char *default_sweep;     /* the parameter sweep snell-bench runs by default ("" none) */
} snell_method_info;

/* Registry entries in cost order (i = 0 .. snell_method_count()-1), NULL past the end. */
int snell_method_count(void);
const snell_method_info *snell_method_info_at(int i);
/* The entry of a method (NULL for AUTO or an unknown value). */
const snell_method_info *snell_method_info_of(snell_method m);
/* "auto", "single", "cubemap"; "unknown" for other values. Never NULL. */
const char *snell_method_str(snell_method m);
/* By name ("auto" included); SNELL_E_INVALID_ARG for an unknown one,
 * SNELL_E_UNSUPPORTED for one this build left out (snell_build_has). */
snell_status snell_method_from_str(const char *name, snell_method *out);
/* A method parameter's value in m by name (as snell_glass_set_param names
 * it), 0 = the default; SNELL_E_INVALID_ARG if the method has no such one. */
snell_status snell_glass_get_param(const snell_glass_material *m, snell_method method, const char *name, int *value);
/* Copies every method's nested parameters (material.cubemap, .peel, ...)
 * from src to dst, leaving dst's optics and method choice. */
void snell_glass_copy_method_params(snell_glass_material *dst, const snell_glass_material *src);
/* Sets a method parameter of the material by name ("iterations", "encoding"
 * also by value name, e.g. "oct"), range-checked. */
snell_status snell_glass_set_param(snell_glass_material *m, snell_method method, const char *name,
                                   const char *value);

/* How a camera is given: an orbit around a target (the fields azimuth ..
 * z_far), or the host's own view and projection matrices. */
typedef enum snell_camera_kind {
    SNELL_CAMERA_ORBIT = 0,
    SNELL_CAMERA_MATRICES
} snell_camera_kind;

typedef struct snell_camera {
    float azimuth;             /* radians, around +Y, 0 = camera on +Z */
    float elevation;           /* radians above the XZ plane */
    float distance;            /* from target; 0 = SNELL_DEFAULT_CAMERA_DISTANCE (3.5) */
    float fov_y;               /* vertical field of view, radians; 0 = 45 degrees */
    float target[3];           /* orbit centre, world space */
    float z_near, z_far;       /* 0 = derived from the distance (0.01 and 100 times it) */
    snell_camera_kind kind;
    /* SNELL_CAMERA_MATRICES: world to eye, eye to clip; column-major, GL conventions */
    float view[16], projection[16];
} snell_camera;
/* snell_render and the reference tracer refuse, with SNELL_E_INVALID_ARG
 * naming the field: a value that is not finite, distance, z_near or z_far < 0,
 * fov_y outside [0, pi), a near plane (given or derived) not before the far
 * plane, and a distance so large that the derived far plane overflows; for
 * SNELL_CAMERA_MATRICES, a matrix that is not finite or not invertible, and
 * (SNELL_E_UNSUPPORTED) a projection neither perspective nor orthographic, a
 * near plane closer than a millionth of the scene's scale (depth precision),
 * an orthographic projection x view whose clip w is negative (a negated
 * matrix), and a reversed-Z or oblique camera with the target's depth
 * tested (snell's depth is a standard projection's).
 * Matrices are judged by projection x view alone: reversed-Z, an infinite
 * far plane, an oblique near plane, a mirrored or scaled view draw what the
 * standard camera with the same rays draws (a mirrored view: flipped in x). */

#define SNELL_DEFAULT_CAMERA_DISTANCE 3.5f
#define SNELL_DEFAULT_FOV_Y 0.78539816339744831f /* 45 degrees */

/* Eye position and view/projection matrices (column-major) of a camera:
 * the orbit's, or the matrices given (then aspect is unused). */
void snell_camera_matrices(const snell_camera *cam, float aspect, float eye[3],
                           float view[16], float proj[16]);

/* ---------------------------------------------------------------- render */
typedef enum snell_target {
    SNELL_TARGET_OFFSCREEN = 0,     /* renderer-owned RGBA8 framebuffer, read back with snell_renderer_read_rgba */
    SNELL_TARGET_BOUND_FRAMEBUFFER  /* whatever draw framebuffer is bound when snell_render is called */
} snell_target;

/* What a frame writes. EXIT_DIRECTION is for error measurement: each pixel
 * holds the world direction in which its light path finally leaves (the view
 * ray for background pixels). It uses an RGBA32F target when
 * GL_EXT_color_buffer_float is present, else RGBA8 with the direction packed
 * octahedrally in 16+15 bits (quantisation error below 1e-4 rad; see
 * snell_renderer_exit_dir_encoding) and a coverage bit. Whether a pixel's
 * path went through glass: snell_renderer_read_coverage. Offscreen targets
 * only. */
typedef enum snell_output {
    SNELL_OUTPUT_COLOR = 0,
    SNELL_OUTPUT_EXIT_DIRECTION,
    SNELL_OUTPUT_EXIT_DIRECTION_PACKED  /* force the RGBA8 fallback encoding */
} snell_output;

/* Where the glass kernels run. Forward shading runs a kernel on the glass
 * triangles; a rasteriser that shades pixels in blocks (llvmpipe: 4x4, GPUs:
 * 2x2 quads) then wastes most lanes on meshes whose triangles cover a pixel
 * or two. The screen-space stage draws the glass's front surface once with a
 * trivial shader into a G-buffer (two RGBA8 textures: the normal, the depth and
 * object id; GLES 3.0, no extension) and runs each kernel once per covered pixel, at the
 * cost of one more pass and a G-buffer's memory (8 bytes per pixel). */
typedef enum snell_shading {
    SNELL_SHADING_AUTO = 0,         /* per object: screen space when its projected triangles are
                                     * smaller than the renderer's threshold (snell_frame_stats says) */
    SNELL_SHADING_FORWARD,          /* every object whose method can: OLIVEIRA's are always in screen space */
    SNELL_SHADING_SCREEN
} snell_shading;

/* How the kernels and the background look the environment up
 * (shaders_es/common/env.glsl): the GL cube texture, or dual-paraboloid maps
 * (Heidrich and Seidel 1998, Dachsbacher 2002): two 180-degree maps of the
 * +Z and -Z hemispheres, made on the GPU from the cube (the static
 * environment's once, kept with it; a dynamic one's each time it is
 * re-rendered) at twice its face size, RGBA8, in one 2D array texture. */
typedef enum snell_env_lookup {
    SNELL_ENV_LOOKUP_AUTO = 0,      /* per use, what measured better (bench/BENCHMARKS.md "Environment
                                     * look-up"): the cube for the static and dynamic environments alike */
    SNELL_ENV_LOOKUP_CUBE,
    SNELL_ENV_LOOKUP_DUAL_PARABOLOID,
    /* the same, but a dynamic environment's maps are rendered straight from
     * the glass centre (2 views instead of 6 cube faces): opaque objects are
     * projected per vertex, which bends no edge, so they come out right only
     * where their triangles are small as seen from the centre */
    SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT
} snell_env_lookup;

typedef struct snell_renderer_desc {
    /* pixels; 0 = 512. At most 16384 (SNELL_E_LIMIT); offscreen (times ssaa)
     * at most the device's texture and renderbuffer size, lowered to its
     * profile's (SNELL_E_UNSUPPORTED, naming the limit and the profile) */
    int width, height;
    snell_target target;
    snell_output output;
    snell_shading shading;
    /* supersampling S x S, box-filtered; 0 or 1 = off, up to SNELL_MAX_SSAA */
    int ssaa;
    /* multisample count; 0 or 1 = off, up to GL_MAX_SAMPLES; not with ssaa */
    int msaa;
    snell_env_lookup env_lookup;    /* for every glass object and the background */
    /* 1: premultiplied alpha for compositing; colour output only; 0 = off */
    int premultiplied_alpha;
    /* Progressive refinement of still frames: while nothing a frame depends
     * on changes (camera, objects, meshes, materials, methods, environment,
     * backdrop, the frame's settings), each frame adds a sample, its
     * projection moved within the pixel and, in exact with inner_fresnel,
     * every exit's reflection followed at random, and the image read back is
     * the mean of up to `refine` such frames; any change restarts it
     * (snell_frame_stats.refine_samples, refine_reason). Offscreen colour
     * renderers without msaa; needs GL_EXT_color_buffer_float (the mean is
     * kept in RGBA32F; without it each frame is drawn unrefined, the reason
     * says so). 0 = off, 1..SNELL_MAX_REFINE. */
    int refine;
} snell_renderer_desc;

#define SNELL_MAX_REFINE 4096

#define SNELL_MAX_SSAA 8

/* A glass object of the scene. */
typedef struct snell_glass {
    const snell_mesh *mesh;         /* required; GPU buffers made on first draw */
    const float *model;             /* float[16] object-to-world; NULL = identity; finite and
                                     * invertible (else SNELL_E_INVALID_ARG) */
    snell_glass_material material;
} snell_glass;

/* An opaque object of the scene (diffuse, lit from above: colour *
 * (0.25 + 0.75 * (0.5 + 0.5 * dot(n, normalize(0.3, 1, 0.2))))), drawn in the
 * view and, seen from each glass object, into its dynamic environment. In a
 * frame with a light (snell_frame_desc.light) it is drawn lit by that light
 * instead: colour * irradiance, as the receiver plane, in the view and as the
 * glass sees it (through the scene layers or its dynamic environment). */
typedef struct snell_opaque {
    const snell_mesh *mesh;         /* required; GPU buffers made on first draw */
    const float *model;             /* float[16] object-to-world; NULL = identity; finite and
                                     * invertible (else SNELL_E_INVALID_ARG) */
    float color[3];                 /* diffuse albedo 0..1; all zero = SNELL_DEFAULT_OPAQUE_ALBEDO grey */
} snell_opaque;
#define SNELL_DEFAULT_OPAQUE_ALBEDO 0.8f

/* A light for the caustics stage (snell_frame_desc.light): zero = none. */
typedef enum snell_light_type {
    SNELL_LIGHT_NONE = 0,
    SNELL_LIGHT_DIRECTIONAL,        /* parallel light travelling along direction (a sun) */
    SNELL_LIGHT_SPOT                /* a point light at position shining along direction within spot_angle */
} snell_light_type;

typedef struct snell_light {
    snell_light_type type;
    float direction[3];             /* world direction the light travels (need not be unit; not zero) */
    float position[3];              /* SPOT: world position */
    /* Linear rgb. DIRECTIONAL: the irradiance on a surface facing the light;
     * SPOT: the intensity (irradiance at distance 1 facing it). All zero = 1. */
    float color[3];
    float spot_angle;               /* SPOT: half angle of its cone, radians (0..1.5); 0 = 0.5 */
    int photons;                    /* photons per glass object: a photons x photons grid over its bounding
                                     * sphere seen from the light; 0 = 256, 16..1024 */
} snell_light;

/* A receiver plane y = height for the caustics stage (snell_frame_desc.receiver):
 * the square |x - center[0]|, |z - center[1]| <= extent, lit from above by
 * the light (direct light where nothing casts a shadow, plus the light that
 * passed through the glass: caustics and coloured shadows), diffuse:
 * colour = albedo * irradiance (in units of the light's colour). extent 0 = none. */
typedef struct snell_receiver {
    float height;                   /* y of the plane, world */
    float center[2];                /* x, z of the square's centre */
    float extent;                   /* half its side, world units; 0 = no receiver */
    float albedo[3];                /* 0..1; all zero = 0.8 grey */
    int map_size;                   /* texels per side of its light map; 0 = 256, 16..2048 */
} snell_receiver;

#define SNELL_DEFAULT_PHOTONS 256
#define SNELL_DEFAULT_SPOT_ANGLE 0.5f
#define SNELL_DEFAULT_RECEIVER_MAP 256
#define SNELL_DEFAULT_RECEIVER_ALBEDO 0.8f


#define SNELL_MAX_GLASS 32
#define SNELL_MAX_OPAQUE 64

/* One frame's scene. Drawn as Franke's transparency notes order it: opaque
 * objects first (depth write), then the glass objects back to front by the
 * view depth of their bounding-sphere centres, then the background where
 * nothing was drawn. A glass object sees the environment and, when there are
 * opaque objects, a dynamic environment rendered from its bounding-sphere
 * centre with them in it (Unger 4.1), re-rendered only in frames where
 * something it shows moved or the light on them changed; with the scene
 * layers (scene_layers below) it sees the other glass and opaque objects
 * through them instead. */
/* The target's depth at the start of a frame. snell draws its opaque
 * objects and its glass with the depth test on; the glass writes its front
 * surface's depth, so what a host draws after sorts against it. */
typedef enum snell_depth_mode {
    SNELL_DEPTH_DEFAULT = 0,        /* CLEAR for SNELL_TARGET_OFFSCREEN, TEST for a bound framebuffer */
    SNELL_DEPTH_CLEAR,              /* cleared to 1 first */
    SNELL_DEPTH_TEST,               /* kept: what the host drew hides the glass and opaque objects behind it */
    SNELL_DEPTH_TEST_NO_WRITE       /* kept and tested as TEST, and the same values again after the frame:
                                     * snell copies the depth first and back after (a single-sample target
                                     * whose depth buffer can be blitted) */
} snell_depth_mode;

/* What the frame draws where nothing else is. */
typedef enum snell_background {
    SNELL_BACKGROUND_NONE = -1,     /* leave the target's pixels as they are (a host's scene, alpha 0) */
    SNELL_BACKGROUND_DRAW = 0       /* default: the environment */
} snell_background;

/* scene_layers' modes; 2..SNELL_MAX_SCENE_LAYERS is a cap on the layers. */
#define SNELL_SCENE_LAYERS_OFF (-1)
#define SNELL_SCENE_LAYERS_AUTO 0

/* The host's scene behind the glass (snell_frame_desc.backdrop): what the
 * host drew before calling snell_render, as textures. The glass's exit and
 * reflected rays that leave it (every method, the scene layers' march:
 * common/beyond.glsl) look for it in screen space before the environment.
 * With a depth texture, each ray is searched against it as a depth field
 * (32 steps across the screen, then 6 halvings): a texel of depth d
 * stands for everything behind its surface (a ray passing behind a thin
 * object is stopped by it), and the far plane's depth (1; 0 for a
 * reversed-Z camera) for the host's sky. The colour where the ray goes
 * behind the field is taken, bilinearly; a ray that finds nothing reaches
 * the far plane where its direction vanishes: on the view, over the host's
 * sky, it takes the host's colour there; off the view, or over something
 * the host drew, it sees the environment. Without
 * depth, the colour where the ray is `distance` past the glass (one look-up,
 * as Filament's and three.js's screen-space refraction). The backdrop is
 * met after the frame's own objects, water and receiver plane. */
typedef enum snell_backdrop_source {
    SNELL_BACKDROP_TEXTURES = 0,    /* color_texture and depth_texture as given */
    SNELL_BACKDROP_COPY_BOUND       /* snell copies the bound framebuffer's colour at the frame's start, and
                                     * its depth where a blit can (a depth buffer of 16, 24 or 32F bits; else
                                     * the colour at distance); SNELL_TARGET_BOUND_FRAMEBUFFER only */
} snell_backdrop_source;

typedef struct snell_backdrop {
    snell_backdrop_source source;
    unsigned color_texture;         /* TEXTURES: a GL_TEXTURE_2D of the renderer's context, required; rows
                                     * bottom first, as GL draws them; not the frame's target */
    unsigned depth_texture;         /* TEXTURES: its window depths (a depth-format GL_TEXTURE_2D, drawn with
                                     * glDepthRangef(0, 1)); 0 = none */
    int width, height;              /* TEXTURES: the textures' size in texels (GLES 3.0 cannot ask), required */
    int region[4];                  /* x, y (from the bottom), w, h: the texels that hold the view; all 0 =
                                     * the whole texture (COPY_BOUND: the frame's size) */
    const snell_camera *camera;     /* the camera it was drawn with (ORBIT: aspect of the region); NULL =
                                     * the frame's */
    float distance;                 /* without depth: how far past the glass a ray takes the colour,
                                     * world units; 0 = SNELL_DEFAULT_BACKDROP_DISTANCE (1) */
} snell_backdrop;
#define SNELL_DEFAULT_BACKDROP_DISTANCE 1.0f

typedef struct snell_frame_desc {
    const snell_env *env;           /* required */
    snell_camera camera;
    const snell_glass *glass;       /* glass_count entries (0..SNELL_MAX_GLASS) */
    int glass_count;
    const snell_opaque *opaque;     /* opaque_count entries (0..SNELL_MAX_OPAQUE) */
    int opaque_count;
    snell_background draw_background; /* SNELL_BACKGROUND_DRAW (0) or SNELL_BACKGROUND_NONE (-1) */
    int dynamic_env_size;           /* dynamic environment face size, 16..2048; 0 = half of env's, at most 256 */
    int scene_layers;               /* 0 = auto, -1 = off, 2..SNELL_MAX_SCENE_LAYERS: layers seen through glass */
    /* water in its container (snell_water.h), same context; NULL = none */
    snell_water *water;
    /* AUTO by frame budget: frame time to hold, ms, finite, <= 1e6; 0 = none */
    float budget_ms;
    /* With budget_ms: no object below the rung whose predicted glass PSNR
     * reaches this many dB (its best rung if none does), whatever the
     * budget; 0 = none. 0..100. */
    float quality_floor_db;
    /* caustics and shadows of glass, with the receiver below; zero = none */
    snell_light light;
    snell_receiver receiver;
    /* What the frame does with the target's depth buffer (snell_depth_mode). */
    snell_depth_mode depth;
    const snell_backdrop *backdrop; /* the host's scene behind the glass; NULL = none */
    /* Glass panels over the frame, drawn last, in this order (snell_panels.h);
     * NULL or 0 = none. A frame of panels only needs no environment (env
     * NULL with no glass, opaque objects or water and draw_background NONE). */
    const snell_panel *panels;
    int panel_count;                /* 0..SNELL_MAX_PANELS */
    const snell_panels_under *panels_under; /* what lies beneath them; NULL = the frame's rectangle as drawn */
} snell_frame_desc;

#define SNELL_MAX_SCENE_LAYERS 8
#define SNELL_DEFAULT_SCENE_LAYERS 8

/* What a frame did not do for an object, and why (bits of snell_object_stats.skipped). */
typedef enum snell_skip {
    SNELL_SKIP_PASSTHROUGH = 1 << 0,  /* IOR 1, no absorption, no tint: the glass changes nothing */
    SNELL_SKIP_OUTSIDE_VIEW = 1 << 1, /* its bounding sphere is outside the view frustum */
    SNELL_SKIP_PREPARE = 1 << 2,      /* prepared resources (e.g. the baked cubemap) reused */
    SNELL_SKIP_ENV_UPDATE = 1 << 3,   /* its dynamic environment reused: nothing in it moved, and the light
                                       * on its opaque objects is unchanged (the caustics stage's maps reused) */
    SNELL_SKIP_BACK_FACES = 1 << 4,   /* back faces culled (closed mesh of known winding) */
    SNELL_SKIP_ANALYSIS = 1 << 5,     /* no mesh analysis: an explicit method that needs none */
    SNELL_SKIP_SEARCH = 1 << 6,       /* CUBEMAP with one interface and no absorption: no exit search */
    SNELL_SKIP_BACK_DETAIL = 1 << 7,  /* the back-face pass drew its mesh's coarse copy (a quarter of the
                                       * triangles, within 1% of its extent): its triangles are below
                                       * 8 px each, finer than the per-pixel map holds */
    SNELL_SKIP_DYNAMIC_ENV = 1 << 8   /* no dynamic environment although the frame has opaque objects: its
                                       * exit rays meet them in the scene layers (snell_frame_desc.scene_layers) */
} snell_skip;

/* The size of every reason text in the stats, its terminating NUL included;
 * a reason longer than that is cut at a character and ends in "...". */
#define SNELL_REASON_SIZE 160

typedef struct snell_object_stats {
    snell_method method_used;       /* SINGLE, CUBEMAP, WYMAN, OLIVEIRA (what drew it, or would have) */
    char reason[SNELL_REASON_SIZE]; /* why this method: AUTO's choice or the explicit request,
                                     * with the mesh facts it rests on */
    int warning;                    /* 1: an explicit method whose preconditions the mesh fails
                                     * (drawn anyway; the reason says what fails; logged at WARN) */
    unsigned skipped;               /* SNELL_SKIP_* bits */
    int passes;                     /* GL draw passes for this object (bake, environment, kernel) */
    int prepared;                   /* 1: its method's resources were built this frame */
    int env_updated;                /* 1: its dynamic environment was re-rendered this frame */
    int draw_order;                 /* 0 = drawn first (farthest); -1 = not drawn */
    float view_depth;               /* distance of its bounding-sphere centre along the view axis */
    float hidden_fraction;          /* the mesh's hidden_fraction if analysed, else 0 */
    int screen_space;               /* 1: shaded in screen space (G-buffer), 0: forward */
    float pixels_per_triangle;      /* estimate AUTO shading decided on: projected bounding-sphere
                                     * area / front triangles (half the mesh's) */
    /* The counters of the method that drew it, in the order its
     * snell_method_info.counters names them (e.g. PEEL: layers_peeled,
     * layers_found; EXACT: fallback_pixels); -1 where not counted this frame.
     * snell_object_counter() reads one by name. */
    int counters[SNELL_MAX_METHOD_COUNTERS];
    int env_paraboloid;             /* 1: it looked its environment up in dual-paraboloid maps, 0: the cube */
    int sees_water;                 /* 1: its exit rays meet the frame's water and container before the
                                     * environment (common/water.glsl), and those leaving under the water
                                     * are bent for its index (the scene layers hold the exit normal) */
    float scale;                    /* the resolution scale it was shaded at (snell_glass_material.scale):
                                     * 1 full resolution, s: 1/s of the frame's samples per axis; 0 not drawn */
} snell_object_stats;

/* The counter name of the method that drew the object (snell_object_stats.counters), -1 if it has none. */
int snell_object_counter(const snell_object_stats *st, const char *name);

typedef struct snell_frame_stats {
    int passes;                     /* GL draw passes issued in all */
    double cpu_ms;                  /* CPU time spent issuing the frame */
    char stages[SNELL_REASON_SIZE]; /* the frame's stages that ran, in frame order, by name ("opaque caustics
                                     * glass layers water back_faces gbuffer kernels background ssaa msaa");
                                     * one a frame does not need is left out (the fields below say why) */
    int glass_count;                /* entries of glass[] filled, = the frame's glass_count */
    snell_object_stats glass[SNELL_MAX_GLASS]; /* in the order of the frame's glass list */
    int opaque_drawn;               /* opaque objects drawn in the view */
    int background_drawn;           /* 1 if the background pass ran */
    int back_face_pass;             /* 1 if the shared back-face pass ran (a method of the frame needs the
                                     * glass's back faces: WYMAN, OLIVEIRA); one pass for all objects that need it */
    int back_face_guard;            /* pixels of guard band it drew around the target (an object crossing the
                                     * target's edge asked for it: guard_band), 0 if none */
    int fragment_mediump;           /* 1: kernels ran at mediump, 0: highp (snell_ctx_precision says why) */
    /* kernel program cache: held, built since creation, bytes the driver reports */
    int programs, programs_built;
    size_t program_bytes;
    int texture_units;              /* texture units the frame bound on; inside a host's context (EXTERNAL)
                                     * only these were saved and restored */
    int scene_layer_passes;         /* depth peels of the scene layers drawn (0: the stage did not run) */
    int scene_layers;               /* of those, the layers that hold something */
    int scene_layers_reused;        /* 1: the last frame's layers, nothing they depend on having changed
                                     * (camera, models, geometry, which objects, size): no peel drawn */
    char scene_layers_reason[SNELL_REASON_SIZE]; /* why the stage ran or did not */
    int water_drawn;                /* 1: the frame's water surface and container were drawn */
    int water_uploaded;             /* 1: its CPU-simulated heights changed and were uploaded this frame */
    int water_objects;              /* 1: objects in the water are seen through it (along its refracted rays:
                                     * the scene layers, or with opaque objects only the screen-space search of
                                     * an offscreen single-sample colour renderer); 0: only the container */
    int water_layers;               /* 1: the water's rays marched the scene layers (glass in the frame) */
    int background_paraboloid;      /* 1: the background looked the environment up in dual-paraboloid maps */
    /* AUTO by budget (snell_frame_desc.budget_ms; all 0 without one): */
    float budget_ms;                /* the budget this frame was planned for */
    double budget_measured_ms;      /* the last frame measured, -1 none yet: by budget_clock */
    int budget_clock;               /* that measurement's clock: 2 the GPU's timer query (EXT_disjoint_timer_query;
                                     * snell_render's CPU time where longer), 1 the CPU's from snell_render's start
                                     * to the frame's fence seen passed, 0 none this frame */
    double budget_predicted_ms;     /* this frame's plan at the learned ms per unit, -1 before a measurement */
    int budget_changed;             /* 1: the plan changed this frame */
    int budget_first_use;           /* 1: the plan draws a configuration for the first time on this renderer:
                                     * the frame may build its programs and per-mesh resources (a bake), so
                                     * its time is neither learned from nor judged over the budget */
    char budget_reason[SNELL_REASON_SIZE]; /* what the controller did and why */
    int caustics_photons;           /* photons splatted onto the receiver this frame (0: none or reused) */
    int caustics_reused;            /* 1: the last frame's light map (light, glass and receiver still) */
    char caustics_reason[SNELL_REASON_SIZE]; /* why the caustics stage ran or did not */
    int backdrop;                   /* 0 none; 1 the backdrop's colour at its distance; 2 searched against its depth */
    /* Progressive refinement (snell_renderer_desc.refine; 0 without): the
     * frames averaged in the image read back, 1 after a restart */
    int refine_samples;
    char refine_reason[SNELL_REASON_SIZE]; /* what the last change was, or why nothing is refined */
    /* Glass panels (snell_frame_desc.panels; all 0 without): */
    int panels_drawn;               /* shapes drawn (a merged group counts once; culled ones do not) */
    int panels_captures;            /* copies of what lies beneath made this frame: 1, more where a panel
                                     * lies over one drawn before it */
    unsigned panels_dropped;        /* SNELL_PANELS_DROPPED_* bits: what the budget took away */
    char panels_reason[SNELL_REASON_SIZE]; /* what lay beneath, what was dropped and why */
} snell_frame_stats;

/* ------------------------------------------------------------ scene files */
/* A glTF 2.0 scene (.gltf/.glb) as frame lists: every node instance of every
 * triangle primitive of the default scene becomes a glass object when its
 * material has KHR_materials_transmission with transmissionFactor > 0, else
 * an opaque object (base colour; glTF's default material is opaque white).
 * Glass: KHR_materials_ior's ior (default 1.5), baseColorFactor as the tint,
 * KHR_materials_volume with thicknessFactor > 0 a solid with its attenuation
 * colour and distance and KHR_materials_dispersion's dispersion (0..20, else
 * SNELL_E_PARSE), without it a thin wall (glTF's "infinitely thin"; a
 * 1e-4 wall here). Geometry stays in each node's local space, the node's
 * world transform is the object's model matrix; primitives instanced by
 * several nodes share one mesh. The first camera met in the node tree, if
 * any, becomes snell_scene_file_camera (eye and view direction kept, roll
 * dropped: snell's camera keeps +Y up). Other extensions are ignored with
 * one INFO log line; a file that requires a KHR_materials_* extension other
 * than those four is SNELL_E_UNSUPPORTED, beyond that the rules and trust
 * model of snell_mesh_load_gltf_ex apply (flags likewise). More than
 * SNELL_MAX_GLASS glass objects is SNELL_E_LIMIT (the message names both
 * counts); more than SNELL_MAX_OPAQUE opaque ones are merged, one object per
 * base colour with the node transforms baked into its mesh (SNELL_E_LIMIT if
 * there are more colours than that). */
typedef struct snell_scene_file snell_scene_file;
snell_status snell_scene_load_gltf(snell_ctx *ctx, const char *path, unsigned flags, snell_scene_file **out);
snell_status snell_scene_load_gltf_mem(snell_ctx *ctx, const void *data, size_t size, snell_scene_file **out);
void snell_scene_file_destroy(snell_scene_file *scene);
/* The objects (valid until the scene is destroyed), for snell_frame_desc.glass / .opaque. */
const snell_glass *snell_scene_file_glass(const snell_scene_file *scene, int *count);
const snell_opaque *snell_scene_file_opaque(const snell_scene_file *scene, int *count);
/* 1 and *camera set if the file has a camera, else 0. */
int snell_scene_file_camera(const snell_scene_file *scene, snell_camera *camera);
/* For a file without a camera (snell_scene_file_camera 0): frames the scene.
 * *camera's azimuth, elevation and fov_y (0 = 45 degrees) are kept; its target
 * becomes the centre of every glass and opaque object's world bounds, its
 * distance the one at which their bounding sphere fits the vertical and the
 * horizontal field of view (aspect = width / height) with 5% to spare, z_near
 * and z_far 0 (derived). SNELL_E_INVALID_ARG for NULL, aspect not > 0 or
 * fov_y outside [0, pi). */
snell_status snell_scene_file_frame(const snell_scene_file *scene, float aspect, snell_camera *camera);
/* Object i's glTF node name ("node N" if it has none; a merged opaque object:
 * "K nodes of 'material'"), NULL if i is out of range. Valid with the scene. */
const char *snell_scene_file_glass_name(const snell_scene_file *scene, int i);
const char *snell_scene_file_opaque_name(const snell_scene_file *scene, int i);

/* AUTO by budget's rung table (snell_frame_desc.budget_ms): the
 * configurations it chooses among, each with its frame time relative to
 * single's and its glass PSNR against FULL per mesh class, as measured on
 * the project's reference device (bench/BENCHMARKS.md "AUTO by frame budget").
 * An object's ladder is the rungs its mesh does not fail, cut to their
 * Pareto front; the controller replaces the costs by what it measures. */
typedef struct snell_budget_rung {
    snell_method method;
    const char *param;              /* a parameter of the method set to value, or NULL (its defaults) */
    int value;
    float cost[4];                  /* frame time over single's, same scene and size, per mesh class:
                                     * convex; closed concave whose centre the cubemap serves (AUTO's
                                     * cubemap: the bunny); closed concave it does not (the torus); open
                                     * or non-manifold */
    float db[4];                    /* glass PSNR vs FULL per class; 0 = not on that class's ladder */
    int scale;                      /* the resolution scale it draws at (snell_glass_material.scale); 0 = 1,
                                     * full resolution. Such rungs are on no ladder where the scale does not
                                     * apply (a method reading full-resolution back faces; a build without
                                     * the scale) */
    const char *more;               /* further parameters of the method, "name=value" joined by ':' (as
                                     * snell_glass_set_param takes them), or NULL; only beside param: a
                                     * rung without param is the method's defaults */
} snell_budget_rung;
int snell_budget_rung_count(void);
const snell_budget_rung *snell_budget_rung_at(int i); /* NULL outside 0..count-1 */

#define SNELL_DEFAULT_RENDER_SIZE 512

/* The descriptions with every default applied: what snell_renderer_create
 * and snell_render use (zero fields to their defaults, sokol-style). The
 * frame's camera (an orbit's distance, fov_y, and z_near and z_far at 0.01
 * and 100 times the distance; matrices as given), light (colour all zero =
 * 1, spot angle, photons) and receiver (albedo all zero = 0.8, map size) are
 * resolved too; scene_layers 0 (auto) becomes its cap,
 * SNELL_DEFAULT_SCENE_LAYERS (on only where the frame needs the layers, as
 * for any cap); dynamic_env_size needs the frame's env. Nothing is
 * validated here (snell_render does that). */
void snell_renderer_defaults(const snell_renderer_desc *in, snell_renderer_desc *out);
void snell_frame_defaults(const snell_frame_desc *in, snell_frame_desc *out);

snell_status snell_renderer_create(snell_ctx *ctx, const snell_renderer_desc *desc, snell_renderer **out);
void snell_renderer_destroy(snell_renderer *r);
snell_status snell_render(snell_renderer *r, const snell_frame_desc *frame, snell_frame_stats *stats);
/* Read the offscreen target as tightly packed RGBA8, top row first. */
snell_status snell_renderer_read_rgba(snell_renderer *r, uint8_t *pixels);
/* Read an EXIT_DIRECTION target: 3 floats (unit world direction) per pixel,
 * top row first. */
snell_status snell_renderer_read_exit_dirs(snell_renderer *r, float *xyz);
/* Read an EXIT_DIRECTION target's coverage: 1 byte per pixel, top row first,
 * 1 where the pixel's light path went through glass (or the water's
 * surface), 0 for the background and opaque objects. The direction alone
 * cannot say so: a path that leaves unbent (a slab, IOR 1) has the view
 * ray's direction, as the background has. */
snell_status snell_renderer_read_coverage(snell_renderer *r, uint8_t *mask);
/* "float" or "packed-rgba8": how an EXIT_DIRECTION renderer stores directions. */
const char *snell_renderer_exit_dir_encoding(const snell_renderer *r);
/* The environment look-up the kernels and the background use
 * (snell_env_lookup: CUBE or DUAL_PARABOLOID, which DUAL_PARABOLOID_DIRECT
 * is for a static environment; AUTO is the renderer's choice for one), evaluated on the GPU for n directions (xyz, need not
 * be unit) into n rgb triples: for measuring a look-up's error. Read from an
 * RGBA32F target where GL_EXT_color_buffer_float allows, else RGBA8 (to
 * 1/255). Makes and deletes its GL objects; GL state is left as it was.
 * n in 1..2^20. */
snell_status snell_renderer_env_probe(snell_renderer *r, const snell_env *env, snell_env_lookup lookup,
                                      const float *dirs, int n, float *rgb);
/* Blocks until the GPU finished the frame (glFinish); for timing. */
void snell_renderer_finish(snell_renderer *r);
/* What snell_renderer_warm did. */
typedef struct snell_warm_stats {
    int frames;                     /* frames drawn */
    double ms;                      /* wall time it took */
    int rungs;                      /* with a budget: configurations of the rung table timed on this device */
    double base_ms;                 /* with a budget: the frame without its glass objects, as measured */
} snell_warm_stats;
/* Draws the frame ahead of time so that the frames after it build nothing:
 * programs and per-mesh resources (bakes, BVHs) are made now. With a budget
 * (budget_ms > 0) it draws every rung of each AUTO object's ladder and times
 * them on this device (glFinish before and after; the median of three draws):
 * the frame without its glass, every object on its lowest rung, then one
 * object at a time on each rung above. AUTO by budget then plans its first
 * frame from this device's own costs rather than the table's, draws no
 * configuration for the first time later, and tries a step up only where it
 * is predicted within 105% of the budget. Without a budget: the frame drawn once.
 * Takes about 4 x (2 + the ladders' rungs above the lowest) frames, each
 * drawn into the target (which holds the last one). stats may be NULL. */
snell_status snell_renderer_warm(snell_renderer *r, const snell_frame_desc *frame, snell_warm_stats *stats);

/* ------------------------------------------------------------------ image */
/* Writes RGBA8 (top row first) as PNG. */
snell_status snell_write_png(const char *path, int width, int height, const uint8_t *rgba);
/* Reads a PNG or Radiance HDR file (HDR clamped to [0,1]) as RGBA8, top row
 * first; at most 16384 pixels per side and 2^25 pixels in all (SNELL_E_LIMIT
 * beyond, checked before decoding), and within the default memory budget
 * (SNELL_DEFAULT_MEMORY_BUDGET for the decode's peak: 8 bytes a pixel for an
 * RGBA8 PNG, 20 for an HDR, so an 8192x4096 HDR needs a context with a larger
 * budget, snell_env_create). A truncated HDR is SNELL_E_PARSE; a directory or
 * other non-regular file SNELL_E_IO. JPEG gives SNELL_E_UNSUPPORTED: the
 * bundled decoder is not safe on malformed files. Free *rgba with snell_image_free. */
snell_status snell_image_read(const char *path, int *width, int *height, uint8_t **rgba);
/* The same from an encoded image in memory (e.g. an Android asset). */
snell_status snell_image_decode(const void *data, size_t size, int *width, int *height, uint8_t **rgba);
void snell_image_free(uint8_t *rgba);

#ifdef __cplusplus
}
#endif
#endif
