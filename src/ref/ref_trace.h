/* ref_trace.h — internals of the reference tracer (ref_trace.c) shared with
 * its tests: an analytic-sphere scene that runs the very same optics code on
 * an exact sphere, so closed-form checks are not blurred by tessellation. */
#ifndef SNELL_REF_TRACE_H
#define SNELL_REF_TRACE_H

#include "core/core.h"
#include "snell/snell_ref.h"

/* A reference whose geometry is the exact sphere |p - centre| = radius (world
 * space, outward normal (p - centre) / radius) instead of a mesh. Everything
 * else (cameras, modes, outputs) behaves as for a mesh reference. */
snell_status snell__ref_create_sphere(snell_ctx *ctx, const double centre[3], double radius, snell_ref **out);

#endif
