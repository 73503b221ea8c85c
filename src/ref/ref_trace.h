/* SPDX-License-Identifier: MIT */
/* ref_trace.h — internals of the reference tracer shared with its tests: a
 * scene of exact spheres that runs the very same optics code (ref_trace.c)
 * on analytic geometry, so closed-form checks are not blurred by
 * tessellation. */
#ifndef SNELL_REF_TRACE_H
#define SNELL_REF_TRACE_H

#include "core/core.h"
#include "ref/ref_scene.h"
#include "snell/snell_ref.h"

/* A reference whose glass objects are the exact spheres |p - centres[i]| =
 * radii[i] (world space, outward normal (p - c) / r; centres: 3 * count),
 * count 1..SNELL_MAX_GLASS, each with the default material (change it with
 * snell_ref_set_material); no opaque objects. Everything else (cameras,
 * modes, outputs, bounding spheres = the spheres) behaves as for meshes. */
snell_status snell__ref_create_spheres(snell_ctx *ctx, int count, const double *centres, const double *radii,
                                       snell_ref **out);
/* One sphere. */
snell_status snell__ref_create_sphere(snell_ctx *ctx, const double centre[3], double radius, snell_ref **out);

/* Camera rays of an image as the renderer rasterises it (snell_camera_matrices,
 * inverted in double): shared by the mesh tracer and the water's (ref_water.c). */
typedef struct camera_rays {
    double eye[3], inv[16]; /* inverse of proj * view, column-major */
    int w, h;
    int ortho;              /* orthographic: each ray starts on the near plane, all parallel */
} camera_rays;
/* Validates params' camera and size (width/height 0 = 512) and fills cr. */
snell_status snell__ref_camera_setup(snell_ctx *ctx, const snell_ref_params *p, camera_rays *cr);
/* The ray through the point (fx, fy) of pixel (x, y) (0.5, 0.5: its centre), y = 0 the top row:
 * its origin (the eye; orthographic: the near plane's point) and unit direction. */
void snell__ref_camera_ray(const camera_rays *cr, int x, int y, double fx, double fy, double org[3], double dir[3]);

/* snell_ref_params.progress for an image loop of `rows` rows handed out under
 * one lock: snell__ref_progress_row() is called under that lock after each
 * finished row (it reports at most ten times a second), snell__ref_progress_end()
 * once by the calling thread after the workers are joined (reports 1.0). */
typedef struct snell__ref_progress {
    snell_ref_progress_fn fn;
    void *user;
    int rows, done;
    double last_ms;
} snell__ref_progress;
void snell__ref_progress_init(snell__ref_progress *p, const snell_ref_params *params, int rows);
void snell__ref_progress_row(snell__ref_progress *p);
void snell__ref_progress_end(snell__ref_progress *p);

/* What surrounds the objects when it is not the air and the environment
 * alone (the water scene, ref_water.c). The rays between objects travel in
 * a medium: its index, its Beer-Lambert absorption sigma, and meet(), asked
 * first along each ray: 1 with rgb if the ray o + t d (unit d) meets the
 * surroundings before t_limit (the nearest object surface ahead, HUGE_VAL
 * none), rgb then the radiance arriving along it, its absorption included;
 * 0 passes it on to the object (or, with none ahead, the environment).
 * at() is the medium at a point of an object's surface (where a ray leaves
 * an object, or is reflected off it). */
typedef struct snell__ref_medium {
    int (*meet)(const void *user, const double o[3], const double d[3], double t_limit, double rgb[3]);
    double ior;
    double sigma[3];
} snell__ref_medium;

typedef struct snell__ref_surroundings {
    const void *user;
    const snell__ref_medium *(*at)(const void *user, const double p[3]);
} snell__ref_surroundings;

/* The MATCHED model's radiance along o + t d (unit d) through ref's objects,
 * starting in medium first of the surroundings sur (sur NULL: air and the
 * environment), with params' environment (env or env_fn) and
 * max_interfaces; no path recorded. params are valid (not checked again). */
void snell__ref_trace_matched(const snell_ref *ref, const snell_ref_params *params, const snell__ref_surroundings *sur,
                              const snell__ref_medium *first, const double o[3], const double d[3], double rgb[3]);

/* The walk inside solid glass object j (the MATCHED chain's, m_inside; the
 * caustics' photons take it too, ref_caustics.c): from pos along unit dir
 * (prim: the triangle it starts on; *depth: interfaces already processed),
 * the closest surface ahead, totally internally reflected there (no Fresnel
 * split inside) while it must be, until the ray is refracted out
 * (SNELL__REF_OUT: dir the refracted direction, *cos_out the incidence
 * cosine there, refl the internal reflection there where not NULL), reaches the cap max_if at a surface (SNELL__REF_CAP: dir
 * unchanged), finds no surface ahead (SNELL__REF_OPEN: an open mesh), or
 * meets an opaque object (SNELL__REF_OPAQUE: *s it). pos, prim and *depth
 * follow the ray, *len adds its length inside. ior: j's index (its channel's);
 * outside, sur's medium at the surface (NULL: air). path: the points of its
 * events are recorded (NULL: none). */
enum { SNELL__REF_OPEN, SNELL__REF_OUT, SNELL__REF_CAP, SNELL__REF_OPAQUE };
int snell__ref_inside(const snell_ref *r, int j, double ior, const snell__ref_surroundings *sur, int max_if,
                      double pos[3], double dir[3], uint32_t *prim, int *depth, double *len, ref_surf *s,
                      double *cos_out, double refl[3], snell_ref_path *path);

#endif
