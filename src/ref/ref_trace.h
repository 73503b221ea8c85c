/* ref_trace.h — internals of the reference tracer shared with its tests: a
 * scene of exact spheres that runs the very same optics code (ref_trace.c)
 * on analytic geometry, so closed-form checks are not blurred by
 * tessellation. */
#ifndef SNELL_REF_TRACE_H
#define SNELL_REF_TRACE_H

#include "core/core.h"
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

#endif
