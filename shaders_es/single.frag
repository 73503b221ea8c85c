// SPDX-License-Identifier: MIT
// single.frag - single-surface refraction (Unger 3.3): refract the view ray at
// the front surface, look the refracted direction up in the environment, mix
// with the reflection by Schlick's Fresnel term. Absorption uses the distance
// from the entry point to where the refracted ray leaves the mesh's bounding
// sphere (exact for a sphere, an estimate otherwise).
// SNELL_THIN: a thin wall (material thickness > 0) is a slab: light leaves in
// the direction it came, reflected and attenuated by all of its inner bounces
// (snell_thin_slab, common/optics.glsl).
precision SNELL_MEDIUMP float; // the context's policy (core/program.c)

#include "common/fp16.glsl"
#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/surface.glsl"
#include "common/beyond.glsl"
#include "common/dispersion.glsl"


#include "common/view.glsl"
uniform vec3 u_sigma;            // Beer-Lambert coefficient per world unit
uniform vec3 u_tint;
uniform highp vec4 u_bsphere;    // bounding sphere: world centre, radius
uniform float u_thickness;       // SNELL_THIN: wall thickness, world units


// The colour for one IOR, snell_ior (outside is 1; common/dispersion.glsl calls it).
vec3 snell_glass_trace(out highp vec3 exit_dir)
{
    highp vec3 world_pos, world_normal;
    snell_surface(world_pos, world_normal);
    // snell_h(): fp16 rounding of what is mediump on real hardware (the
    // arguments of the mediump optics functions included) under
    // SNELL_FP16_EMULATION; the identity otherwise (common/fp16.glsl).
    highp vec3 v = snell_view_ray(world_pos);
    vec3 n = snell_h(normalize(world_normal)); // normalised at highp, then mediump
    // Interpolated normals can face away from the eye at the silhouette.
    if (dot(n, v) > 0.0) n = -n;
    vec3 r = snell_h(snell_reflect(snell_h(v), n));
#ifdef SNELL_THIN
    vec3 rs, ts;
    snell_thin_slab(-dot(v, n), snell_ior, u_sigma, u_thickness, rs, ts);
    highp vec3 through = v; // straight on through the wall (snell_exit: to what lies beyond)
    vec3 color = snell_exit(world_pos, through) * u_tint * ts + snell_reflection(world_pos, r) * rs;
    exit_dir = through;
    return color;
#else
    vec3 t;
    snell_refract(snell_h(v), n, snell_h(1.0 / snell_ior), t);
    t = snell_h(t);
    snell_disp_enter(v, n);
    float fresnel = snell_h(snell_fresnel_schlick(snell_h(-dot(v, n)), 1.0, snell_ior));

#ifdef SNELL_ABSORB
    // Only in the variant with absorption: exp per lane costs even with
    // sigma = 0 (bench/notes/code.md, "single.frag").
    highp float path = snell_sphere_exit(world_pos, t, u_bsphere);

    vec3 transmitted = snell_h(snell_disp_exit(world_pos, t) * u_tint * snell_beer_lambert(u_sigma, snell_h(path)));
#else
    vec3 transmitted = snell_h(snell_disp_exit(world_pos, t) * u_tint);
#endif
    vec3 reflected = snell_h(snell_reflection(world_pos, r));
    exit_dir = t;
    return mix(transmitted, reflected, fresnel);
#endif
}
