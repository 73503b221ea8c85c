/* snell_ref.h — the CPU reference ray tracer: ground truth for the GPU methods.
 *
 * Double precision, a BVH over the mesh (watertight ray-triangle test), the
 * GPU's smooth shading normals, camera and environment filtering, so that an
 * image difference measures only a method's approximation. Two optical models:
 *
 *  SNELL_REF_MATCHED — the model of the GPU kernels (Unger 4.1): at the first
 *    surface C = F*env(R) + (1-F) * tint * T * L, F = Schlick(cos_i, 1, ior),
 *    R the mirror direction, L the radiance of the refracted chain: the
 *    refracted ray continues inside; at each further interface it is reflected
 *    if totally internally reflected (no Fresnel split inside), else refracted
 *    out and L = env(exit direction). T = exp(-absorption * d), d the path
 *    length inside (or see SNELL_REF_ABSORB_BOUNDING_SPHERE).
 *  SNELL_REF_FULL — a Whitted tree: reflection and refraction at every
 *    interface weighted by Schlick's F (n1/n2 of the side the ray is on),
 *    Beer-Lambert on every inner segment, tint on every entering refraction
 *    (once for a convex object); what a glass object really looks like. A
 *    branch whose throughput drops below 1e-5 ends with an env lookup in its
 *    direction instead of being traced on (error < 1e-5, far below 1/255).
 *
 * Interface cap (both modes): an "interface" is one ray-surface hit that is
 * processed (refracted and/or reflected); the first surface is interface 1.
 * At most max_interfaces are processed along any path. A ray that has gone
 * through max_interfaces interfaces and is still inside leaves in its current
 * direction: the environment is looked up in that direction, and absorption
 * (PATH model) runs on to the next surface along it. The same holds for a ray
 * inside that finds no surface (open mesh). max_interfaces = 1 in MATCHED mode
 * is the single-surface method (Unger 3.3): env(T1) after the front refraction.
 *
 * Conventions are those of the renderer: pixel (x, y), y = 0 the top row, ray
 * through the pixel centre of snell_camera_matrices(camera, width/height);
 * smooth normal = normalize(barycentric interpolation of the world-space vertex
 * normals, inverse-transpose(model) * n), flipped to face the incoming ray;
 * environment = snell_env_sample_d (GL_LINEAR model). All directions are world
 * space, unit length. Results do not depend on the thread count (bitwise). */
#ifndef SNELL_SNELL_REF_H
#define SNELL_SNELL_REF_H

#include "snell.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Upper bound of max_interfaces; also the size of a traced path. */
#define SNELL_REF_MAX_INTERFACES 64
#define SNELL_REF_MAX_SIZE 16384   /* width, height limit */
#define SNELL_REF_MAX_THREADS 256  /* more are clamped */

typedef struct snell_ref snell_ref;

typedef struct snell_ref_desc {
    const snell_mesh *mesh;  /* required; its triangles are copied (world space) */
    const float *model;      /* float[16] object-to-world, column-major; NULL = identity */
} snell_ref_desc;

/* Builds the BVH (SAH) over the mesh in world space. ctx may be NULL (CPU only,
 * libc allocator, messages via snell_last_error(NULL)). */
snell_status snell_ref_create(snell_ctx *ctx, const snell_ref_desc *desc, snell_ref **out);
void snell_ref_destroy(snell_ref *ref);

/* The world-space bounding sphere the GPU single-surface method uses for its
 * absorption estimate: centre = model * (object bounding-box centre), radius =
 * max vertex distance from that centre * largest column length of model's 3x3. */
void snell_ref_bounding_sphere(const snell_ref *ref, double centre[3], double *radius);

typedef enum snell_ref_mode {
    SNELL_REF_MATCHED = 0,  /* the GPU kernels' optical model (see above) */
    SNELL_REF_FULL          /* Whitted tree, Fresnel at every interface */
} snell_ref_mode;

typedef enum snell_ref_absorption {
    SNELL_REF_ABSORB_PATH = 0,         /* the real path length inside the glass */
    /* MATCHED only: d = distance from the entry point along the first refracted
     * direction to the exit of snell_ref_bounding_sphere(), whatever the chain
     * does; with max_interfaces = 1 this is exactly SNELL_METHOD_SINGLE. */
    SNELL_REF_ABSORB_BOUNDING_SPHERE
} snell_ref_absorption;

/* An environment given as a function (radiance, linear, 0..1 scale); dir is unit. */
typedef void (*snell_ref_env_fn)(const double dir[3], double rgb[3], void *user);

typedef struct snell_ref_params {
    snell_ref_mode mode;
    int max_interfaces;                  /* 1..SNELL_REF_MAX_INTERFACES; 0 = 10 */
    snell_ref_absorption absorption_model;
    snell_glass_desc glass;              /* ior (0 = 1.5), absorption, tint; method ignored */
    const snell_env *env;                /* environment, or: */
    snell_ref_env_fn env_fn;             /* used instead of env when non-NULL */
    void *env_user;
    snell_camera camera;                 /* as snell_frame_desc.camera */
    int width, height;                   /* pixels; 0 = 512 */
    int threads;                         /* 0 = online CPUs; > SNELL_REF_MAX_THREADS clamped */
} snell_ref_params;

/* Caller-owned output buffers, width*height pixels each, top row first. */
typedef struct snell_ref_output {
    float *rgb;           /* required: 3 per pixel, linear radiance (0..1 scale of the 8-bit env) */
    float *exit_dir;      /* optional: 3 per pixel, the direction of the final env lookup of the
                           * path (MATCHED: the chain; FULL: the dominant branch, see
                           * snell_ref_trace_pixel); background pixels: the view ray */
    uint8_t *interfaces;  /* optional: interfaces processed along that path (0 = background) */
    uint8_t *hit;         /* optional: 1 if the view ray hits the mesh, else 0 */
} snell_ref_output;

/* Renders the whole image with params->threads worker threads (pthreads). */
snell_status snell_ref_render(const snell_ref *ref, const snell_ref_params *params, const snell_ref_output *out);

/* GL's float->unorm8 conversion: round-to-nearest of clamp(v, 0, 1) * 255;
 * alpha = 255. rgba: 4 * width * height bytes. */
void snell_ref_rgb_to_rgba8(const float *rgb, int width, int height, uint8_t *rgba);

/* ---------------------------------------------------- light path (Unger 4.2.2) */
typedef enum snell_ref_event {
    SNELL_REF_EVENT_EYE = 0,   /* points[0]: the ray origin (camera) */
    SNELL_REF_EVENT_REFRACT,   /* refracted through the surface (into or out of the glass) */
    SNELL_REF_EVENT_REFLECT,   /* Fresnel-dominant reflection (FULL only) */
    SNELL_REF_EVENT_TIR        /* total internal reflection */
} snell_ref_event;

/* One light path as a polyline: points[0] is the origin, points[1..interfaces]
 * the interface points (world space) with what happened there; after the last
 * point the ray travels along exit_dir (unit). MATCHED: the refracted chain of
 * the GPU model (points[1] is the entry; its Fresnel reflection is a side
 * branch with weight `fresnel`). FULL: the dominant branch of the Whitted tree
 * (at every interface the branch of larger weight, refraction on a tie). */
typedef struct snell_ref_path {
    int hit;                   /* 0: the ray missed the mesh (points[0] only) */
    int interfaces;            /* number of interface points; point count = interfaces + 1 */
    double points[SNELL_REF_MAX_INTERFACES + 1][3];
    snell_ref_event events[SNELL_REF_MAX_INTERFACES + 1];
    double exit_dir[3];
    int ended_inside;          /* 1 if the path stopped inside the glass (cap or open mesh) */
    double fresnel;            /* F at the first surface (0 if missed) */
    double inside_length;      /* path length inside the glass, world units (PATH model) */
    double rgb[3];             /* the pixel's colour as snell_ref_render computes it */
} snell_ref_path;

/* The path of pixel (x, y) of the image params describes (ray through the
 * pixel centre). x, y must lie inside width x height. */
snell_status snell_ref_trace_pixel(const snell_ref *ref, const snell_ref_params *params, int x, int y,
                                   snell_ref_path *path);
/* The same for an arbitrary ray (world space; dir need not be unit);
 * params->camera/width/height/threads are ignored. */
snell_status snell_ref_trace_ray(const snell_ref *ref, const snell_ref_params *params, const double org[3],
                                 const double dir[3], snell_ref_path *path);

#ifdef __cplusplus
}
#endif
#endif
