/* SPDX-License-Identifier: MIT */
/* snell_ref.h — the CPU reference ray tracer: ground truth for the GPU methods.
 * Double precision, one BVH over every object of the scene (watertight
 * ray-triangle test), the GPU's smooth normals, camera and environment
 * filtering, so that an image difference measures only a method's
 * approximation. Two optical models: SNELL_REF_MATCHED (the GPU kernels' model)
 * and SNELL_REF_FULL (a Whitted tree with exact Fresnel, as Blender Cycles).
 * What a ray meets, both models in full, dispersion, the interface cap and the
 * conventions: docs/ARCHITECTURE.md, "Design notes by file"; the longer
 * fields: docs/accuracy.md, "The reference's fields in depth". */
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
#define SNELL_REF_MAX_SAMPLES 16   /* snell_ref_params.samples limit (S x S rays a pixel) */

typedef struct snell_ref snell_ref;

/* The scene, as snell_frame_desc gives it to the renderer: glass objects
 * (mesh, model, material; its method and cubemap parameters are validated
 * but not used) and opaque diffuse objects, lit as the GPU lights them
 * (snell_opaque). Paths may leave one glass object and enter another or end
 * on an opaque one. At least one object; at most 2^26 triangles in all
 * (SNELL_E_LIMIT beyond). */
typedef struct snell_ref_desc {
    const snell_glass *glass;     /* glass_count entries, 0..SNELL_MAX_GLASS; triangles copied */
    int glass_count;
    const snell_opaque *opaque;   /* opaque_count entries, 0..SNELL_MAX_OPAQUE; triangles copied;
                                   * colour 0..1 per channel (all zero = 0.8 grey) */
    int opaque_count;
} snell_ref_desc;

/* Builds one BVH (SAH) over all objects' triangles in world space. ctx may be
 * NULL (CPU only, libc allocator, messages via snell_last_error(NULL)).
 * SNELL_E_INVALID_ARG, with a message naming the object ("glass[1].model is
 * not finite", "glass 1: ior ..."), for counts out of range, a NULL list or
 * mesh, a mesh without triangles, a model that is not finite or singular, a
 * material snell_glass_defaults rejects or an opaque colour outside 0..1. */
snell_status snell_ref_create(snell_ctx *ctx, const snell_ref_desc *desc, snell_ref **out);
void snell_ref_destroy(snell_ref *ref);
/* Replaces glass object `index`'s material (no rebuild; NULL = defaults);
 * validated as snell_glass_defaults validates, and on failure the material in
 * use stays. Not while a render or trace of this reference runs. */
snell_status snell_ref_set_material(snell_ref *ref, int index, const snell_glass_material *material);

/* The world-space bounding sphere of glass object `index` that the GPU
 * single-surface method uses for its absorption estimate: centre = model *
 * (object bounding-box centre), radius = max vertex distance from that centre
 * * largest column length of model's 3x3. Zeros for an index out of range. */
void snell_ref_bounding_sphere(const snell_ref *ref, int index, double centre[3], double *radius);

typedef enum snell_ref_mode {
    SNELL_REF_MATCHED = 0,  /* the GPU kernels' optical model (see above) */
    SNELL_REF_FULL          /* Whitted tree, Fresnel at every interface */
} snell_ref_mode;

/* The FULL model's next terms added to MATCHED's chain (bits of
 * snell_ref_params.terms; MATCHED only), as the kernels' options that compute
 * them (snell_exact_params.fresnel, inner_fresnel): */
typedef enum snell_ref_terms {
    SNELL_REF_TERM_EXACT_FRESNEL = 1 << 0,     /* unpolarised Fresnel in place of Schlick's */
    /* the chain's first exit into air transmits 1 - F; its internal
     * reflection F is followed inside (total reflections too) to its own
     * exit, where it all leaves, as the chain does, and does not re-enter */
    SNELL_REF_TERM_INNER_REFLECTION = 1 << 1,
    /* a ray the chain sends out that meets its glass again re-enters it
     * (isolate_glass too), wholly: no Fresnel at the re-entry */
    SNELL_REF_TERM_REENTRY = 1 << 2
} snell_ref_terms;
#define SNELL_REF_TERMS_ALL 7u

typedef enum snell_ref_absorption {
    SNELL_REF_ABSORB_PATH = 0,         /* the real path length inside the glass */
    /* MATCHED only: absorption over the bounding-sphere chord, as SINGLE */
    SNELL_REF_ABSORB_BOUNDING_SPHERE
} snell_ref_absorption;

/* An environment given as a function (radiance, linear, 0..1 scale); dir is unit. */
typedef void (*snell_ref_env_fn)(const double dir[3], double rgb[3], void *user);

/* Progress of a long render: done is the fraction of the image's rows
 * finished, 0..1, never decreasing; called at most about 10 times a second
 * while rows are done and exactly once with 1.0 when the image is complete
 * (not on an early error). Calls never overlap, but they may come from any of
 * the render's threads: keep it short (the rows wait for it). The library
 * prints nothing; the caller shows what it likes. */
typedef void (*snell_ref_progress_fn)(double done, void *user);

typedef struct snell_ref_params {
    snell_ref_mode mode;
    int max_interfaces;                  /* 1..SNELL_REF_MAX_INTERFACES; 0 = 10 */
    snell_ref_absorption absorption_model;
    unsigned terms;                      /* MATCHED: snell_ref_terms bits (0: the kernels' default model) */
    /* 1: glass sees no other glass object (a method's error apart from the scene layers') */
    int isolate_glass;                   /* nonzero = 1 */
    const snell_env *env;                /* environment, or: */
    snell_ref_env_fn env_fn;             /* used instead of env when non-NULL */
    void *env_user;
    snell_camera camera;                 /* as snell_frame_desc.camera */
    int width, height;                   /* pixels; 0 = 512 */
    int threads;                         /* 0 = online CPUs; > SNELL_REF_MAX_THREADS clamped */
    /* S x S rays a pixel, box-filtered (as ssaa = S); 0 or 1 = the centre ray; 0..SNELL_REF_MAX_SAMPLES */
    int samples;
    snell_ref_progress_fn progress;      /* NULL = none (snell_ref_render, snell_ref_water_render) */
    void *progress_user;
} snell_ref_params;

/* Caller-owned output buffers, width*height pixels each, top row first. */
typedef struct snell_ref_output {
    float *rgb;           /* required: 3 per pixel, linear radiance (0..1 scale of the 8-bit env) */
    float *exit_dir;      /* optional: 3 per pixel, the direction of the final env lookup of the
                           * path (MATCHED: the chain; FULL: the dominant branch, see
                           * snell_ref_trace_pixel), or of the ray that hit the opaque
                           * object it ends on; background and opaque pixels: the view ray */
    uint8_t *interfaces;  /* optional: interfaces processed along that path (0 = background) */
    uint8_t *hit;         /* optional: 1 if the view ray hits a glass object first, else 0 */
    int16_t *object;      /* optional: what the view ray hits first: glass i -> i, opaque j ->
                           * -2 - j, nothing -> -1 */
    /* optional: 3 per pixel, a path tracer's per-sample variance: N samples, sample_var / N */
    float *sample_var;
} snell_ref_output;

/* Renders the whole image with params->threads worker threads (pthreads). */
snell_status snell_ref_render(const snell_ref *ref, const snell_ref_params *params, const snell_ref_output *out);

/* GL's float->unorm8 conversion: round-to-nearest of clamp(v, 0, 1) * 255;
 * alpha = 255. rgba: 4 * width * height bytes. */
void snell_ref_rgb_to_rgba8(const float *rgb, int width, int height, uint8_t *rgba);

/* The water scene (snell_water.h): the container's floor and walls, the
 * water surface, whose heights are read from the water (a GPU simulation's
 * context must be current), and the glass and opaque objects of `objects`
 * (or NULL for none), standing in the water or above it. The surface is the
 * triangles the GPU draws (two per grid cell), intersected exactly; its
 * normal the barycentric blend of the nodes' (-dh/dx, 1, -dh/dz),
 * normalised. A ray meeting the surface from the air gives
 * F * L(R) + (1 - F) * L_water(T): F Schlick's (1 -> ior), R the mirror
 * direction, T the refracted one. Rays are traced by the MATCHED model
 * (snell_ref_render's, Schlick at each entry, TIR inside) through every
 * medium: in the air, the objects, the container's faces (either side,
 * walls up to the rim) and the surface, else the environment; in the water
 * (the water's index around the glass: a glass object below the surface
 * refracts against it, one through the surface against the air above and
 * the water below), the objects, else the floor or the wall the seed's five
 * distances choose (a rising ray meets the walls, not the surface from
 * below), Beer-Lambert with the water's absorption over every stretch in
 * it; a mirror ray off the surface leaves the surface out. Opaque objects
 * lit as snell_ref_render lights them. Uses params' env (or env_fn),
 * camera, width, height, threads, samples and max_interfaces (as
 * snell_ref_render); mode, absorption_model and isolate_glass do not apply.
 * Outputs rgb, exit_dir (water pixels: the refracted direction; others the
 * view ray) and hit (1: the view ray meets the water surface before any
 * object or face); the other outputs are not written. */
snell_status snell_ref_water_render(snell_water *water, const snell_ref *objects, const snell_ref_params *params,
                                    const snell_ref_output *out);

/* The water container's floor irradiance under a light (the caustics
 * stage's floor light map, snell_water.h), traced in double precision from
 * the light: size x size texels over the floor (0 = the water's light_map),
 * row 0 at z = -width/2, x growing along a row, 3 floats each, in units of
 * the light's colour. A photons x photons grid of rays (cell centres):
 * directional, parallel rays over a square across the light holding the
 * container's top, each the flux through its cell; spot, directions on the
 * plane at distance 1 along its axis within tan(spot_angle), each the flux
 * of its solid angle cell^2 cos^3, none outside the cone. A ray that meets a
 * wall first (the rim's shadow) is dropped; at the height field (its
 * triangles, met exactly) it is refracted at the blended node normal
 * (Schlick transmission), and where it meets the floor before a wall its
 * flux times Beer-Lambert over the path in the water is shared by the texel
 * centres within 2 texels with the caustics stage's tent weights
 * (1 - |dx|/2)(1 - |dz|/2)/4. objects (NULL: none): its opaque objects
 * stop a ray anywhere on its way, before the surface or in the water (its
 * glass objects are not met: the light through them is not traced).
 * photons 1..16384, threads 0 = online CPUs. */
snell_status snell_ref_water_floor_render(snell_water *water, const snell_ref *objects, const snell_light *light,
                                          int size, int photons, int threads, float *rgb);

/* ------------------------------------------------------ light on a receiver */
/* The receiver plane's irradiance as the caustics stage
 * (snell_frame_desc.light / .receiver) defines it, traced in double
 * precision from the light: size x size texels (receiver->map_size, 0 =
 * 256), row 0 at z = center[1] - extent, x growing along a row, 3 floats
 * each, in units of the light's colour. Direct light: the mean over
 * samples x samples points of the texel of the light's irradiance there
 * (directional: colour * max(0, -dir.y); spot: colour * cosine / distance^2
 * inside its cone) where a ray towards the light (up to it) meets no
 * object (glass or opaque). Through glass: per glass object a photons x
 * photons grid of rays (cell centres) over its bounding sphere (directional:
 * parallel rays, each the flux through its cell; spot: a square of
 * directions from the light on the plane at distance 1, each the flux of its
 * solid angle cell^2 cos^3, none outside the cone nor from a light inside
 * the sphere) that meets it first, refracted in (Schlick, Snell) and out at its next surface
 * (Schlick; TIR drops it), tint and Beer-Lambert over the chord (a thin
 * wall, material thickness > 0: straight on through each of its walls, each
 * a slab of the kernels' thin-wall model times the tint), carrying
 * the light's flux through its cell, then, unless an object stops it, its
 * flux shared by the texel centres within 2 texels of where it meets the
 * plane with tent weights (1 - |dx|/2)(1 - |dz|/2)/4 (the stage's splat). caustic (optional, 3 floats a texel) receives
 * that part alone. photons 1..4096, samples 1..16. */
snell_status snell_ref_receiver_render(const snell_ref *ref, const snell_light *light, const snell_receiver *receiver,
                                       int photons, int samples, float *rgb, float *caustic);

/* Lights the opaque objects (in snell_ref_render and snell_ref_water_render)
 * as the caustics stage lights them in a frame with `light` (and the
 * receiver plane `receiver`, extent 0 = none): colour = albedo *
 * irradiance, in units of the light's colour, instead of opaque.frag's sky
 * light. Irradiance = the direct light (directional: colour * cosine; spot:
 * colour * cosine / distance^2 inside its cone) where a ray towards the
 * light (up to it) meets no object, plus the light through glass: photons
 * traced as snell_ref_receiver_render traces them (photons x photons per
 * solid glass object) that first meet an opaque object (before the plane)
 * on a surface the light sees there, splatted with the stage's tent into
 * the stage's light frame (the view from the light whose window holds the
 * receiver square's corners and the opaque objects' bounding spheres: an
 * orthographic one along a directional light, a perspective one looking
 * straight down from a spot light; 2 * map_size texels a side, at most
 * 2048), flux per texel area facing the light (a spot's: solid angle); at
 * a surface point read bilinearly over the texels whose nearest opaque
 * surface seen from the light is within 3 texels of the point's depth,
 * times the cosine (spot: / distance^2). light NULL or SNELL_LIGHT_NONE:
 * back to the sky light. photons 1..4096; not while a render runs. */
snell_status snell_ref_set_light(snell_ref *ref, const snell_light *light, const snell_receiver *receiver,
                                 int photons);

/* Shows the receiver plane to the view rays of snell_ref_render and
 * snell_ref_trace_pixel / _ray (not snell_ref_water_render's) as the GPU
 * shows it in a frame with `light` and `receiver`, drawn and seen by the
 * glass (common/receiver.glsl): a ray in air (a view ray, or one that has
 * left glass, reflected or refracted; MATCHED and FULL) that meets the
 * square from above before any object ends there with albedo (all zero =
 * 0.8 grey) * irradiance, in units of the light's colour, read bilinearly
 * between texel centres (the edge texels held beyond them) from the map
 * snell_ref_receiver_render(ref, light, receiver, photons, 2, ...) traces
 * once here (its direct light at the stage's 2 x 2 points a texel;
 * photons 1..4096 a side). It casts no shadow and stops no photon of the
 * reference's own light tracing; it is not an object
 * (snell_ref_output.object -1, hit 0; the path ends there, exit_dir the
 * ray's direction). The opaque objects keep their light
 * (snell_ref_set_light lights them). light NULL or
 * SNELL_LIGHT_NONE, receiver NULL or extent 0: no plane, the images as
 * without the call. SNELL_E_INVALID_ARG for a receiver whose height or
 * centre is not finite, albedo outside 0..1, map_size outside 0..4096, or
 * what snell_ref_receiver_render refuses (then no plane). Not while a
 * render runs. */
snell_status snell_ref_set_receiver(snell_ref *ref, const snell_light *light, const snell_receiver *receiver,
                                    int photons);

/* ------------------------------------------- the host's scene behind the glass */
/* A backdrop as snell_frame_desc.backdrop gives the renderer one: the
 * host's frame and its window depths, here from memory. */
typedef struct snell_ref_backdrop {
    const uint8_t *rgba;            /* width x height RGBA8, bottom row first (as glReadPixels reads them) */
    const float *depth;             /* width x height window depths 0..1, bottom row first; NULL = none */
    int width, height;              /* 1..16384 */
    snell_camera camera;            /* the camera it was drawn with (aspect width / height) */
    float distance;                 /* without depth, as snell_backdrop.distance; 0 = 1 */
} snell_ref_backdrop;

/* Shows the backdrop (copied) to every ray in air of snell_ref_render and
 * snell_ref_trace_pixel / _ray (MATCHED and FULL), before the environment,
 * as a depth field: the ray, clipped to the camera's frustum, meets it
 * where its window depth first reaches the depth of the texel it is over
 * (depth 1, 0 for a reversed-Z camera: the host's sky), searched in steps
 * of at most a quarter texel and halved 40 times; that point must come
 * before the nearest object surface ahead. It shows the colour there,
 * bilinear as GL_LINEAR with clamped edges (radiance = byte / 255). A ray
 * that meets nothing takes the colour where its direction vanishes, if
 * that is on the view and over the host's sky. Without depth: the colour where
 * the ray is `distance` past its start, if that point is in view. A view
 * ray that meets it first ends there (hit 0, object -1). NULL: none.
 * SNELL_E_INVALID_ARG for a NULL rgba, a size out of range, a camera
 * snell_render would refuse, a depth not in 0..1 or a distance below 0.
 * Not while a render runs. */
snell_status snell_ref_set_backdrop(snell_ref *ref, const snell_ref_backdrop *backdrop);

/* ------------------------------------------------------------ glass panels */
/* The panels of snell_panels.h's model drawn over an image in double
 * precision, each pixel the mean of samples x samples rays on a regular grid
 * within it (0 = 8): under and out are width x height RGBA8, bottom row
 * first (as glReadPixels reads them); what lies beneath is read from under's
 * stored values as the GPU reads an RGBA8 texture (bilinear, edges clamped;
 * frost: a Gaussian of sigma frost pixels, cut at 3 sigma). out may not be
 * under. SNELL_E_INVALID_ARG for what snell_render refuses in the panels. */
snell_status snell_ref_panels(const snell_panel *panels, int count, const uint8_t *under, int width, int height,
                              int samples, uint8_t *out);

/* ---------------------------------------------------- light path (Unger 4.2.2) */
typedef enum snell_ref_event {
    SNELL_REF_EVENT_EYE = 0,   /* points[0]: the ray origin (camera) */
    SNELL_REF_EVENT_REFRACT,   /* refracted through the surface (into or out of the glass; FULL:
                                * leaving about a bent normal it can stay inside) */
    SNELL_REF_EVENT_REFLECT,   /* Fresnel-dominant reflection (FULL only) */
    SNELL_REF_EVENT_TIR        /* total internal reflection */
} snell_ref_event;

/* One light path as a polyline: points[0] is the origin, points[1..interfaces]
 * the interface points (world space) with what happened there (a thin wall
 * crossed is REFRACT); after the last point the ray travels along exit_dir
 * (unit) to the environment or to the opaque object the path ends on.
 * MATCHED: the refracted (thin: transmitted) chain of the GPU model through
 * every glass object it meets (points[1] is the entry; its Fresnel reflection
 * is a side branch with weight `fresnel`). FULL: the dominant branch of the
 * Whitted tree (at every interface the branch of larger weight, refraction on
 * a tie; at a thin wall rs against ts summed over rgb). */
typedef struct snell_ref_path {
    int hit;                   /* 1: the ray meets a glass object first; 0: nothing or an opaque
                                * object (points[0] only) */
    int first_object;          /* as snell_ref_output.object for the first hit */
    int objects[SNELL_REF_MAX_INTERFACES + 1]; /* glass object of each interface point (-1 at points[0]) */
    int interfaces;            /* number of interface points; point count = interfaces + 1 */
    double points[SNELL_REF_MAX_INTERFACES + 1][3];
    snell_ref_event events[SNELL_REF_MAX_INTERFACES + 1];
    double exit_dir[3];
    int ended_inside;          /* 1 if the path stopped inside glass (cap, open mesh, or an opaque
                                * object inside it) */
    double fresnel;            /* F at the first surface (a thin wall: its rs, mean of rgb; 0 if missed) */
    double inside_length;      /* path length inside glass over all objects, world units (PATH
                                * model; a thin wall crossed counts thickness / cos_t) */
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
