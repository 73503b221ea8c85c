// SPDX-License-Identifier: MIT
// exact.frag - exact refraction by BVH ray traversal (methods/exact.c): the
// MATCHED reference's model (src/ref/ref_trace.c, m_air and m_inside) in
// float. Per pixel: the eye ray through the pixel is traced against the
// mesh's BVH (the entry the reference finds, with its smooth normal; the
// rasterised surface only where the ray misses, at the silhouette); Schlick
// Fresnel at the entry; inside, the closest surface ahead (skipping the
// triangle the ray starts on), total internal reflection there or
// refraction out, up to u_max_interfaces surfaces; at the cap the light
// leaves through the next surface in its direction, and with no surface
// ahead (an open mesh) in its direction; Beer-Lambert over the whole path
// inside. Past SNELL_NODE_BUDGET node visits the pixel takes the
// single-surface answer (single.frag's model) and is marked.
//
// The traversal (the BVH texture's layout, watertight triangles, the
// stackless and short-stack walks, the node budget) is common/bvh.glsl,
// shared with the caustics' photons (caustics_photon.vert).
//
// Spaces: traversal in object space with the world ray parameter (d = M^-1 *
// unit world direction), so t and the path are world lengths for any model
// matrix; normals go to world space by the normal matrix. highp throughout.
precision highp float;
precision highp int;

#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/surface.glsl"
#include "common/beyond.glsl"
#define SNELL_KERNEL_MAIN 1 // main below: the fallback mark goes after the write
#include "common/dispersion.glsl"

// SNELL_ABSORB (0/1) and the traversal's defines (common/bvh.glsl) are the
// program's variant (methods/exact.c).
#include "common/bvh.glsl"

#include "common/view.glsl"
uniform vec3 u_sigma;
uniform vec3 u_tint;
uniform highp vec4 u_bsphere;    // world bounding sphere: the fallback's absorption chord
uniform mat4 u_inv_model;        // world -> object
uniform highp mat4 u_model;      // object -> world (object.vert's; the exit point for snell_exit)
uniform int u_max_interfaces;    // 1..MAX_INTERFACES
uniform float u_eps;             // minimum distance of a secondary hit, world units
uniform float u_fallback_mark;   // alpha of a fallback pixel in the RGBA32F exit-direction target
uniform mat3 u_cam_basis;        // view -> world rotation (the view matrix's 3x3, transposed)
uniform vec4 u_cam_proj;         // the projection's P00, P11, P20, P21 (orthographic: P00, P11, -P30, -P31)
uniform vec2 u_pixel_to_ndc;     // 2 / target size in pixels

// The colour for one IOR, snell_ior (common/dispersion.glsl); g_visits
// accumulates over the calls, as the budget counts all of a pixel's rays.
vec3 snell_glass_trace(out highp vec3 exit_dir)
{
    highp vec3 world_pos, world_normal;
    snell_surface(world_pos, world_normal);
    // The eye ray through the pixel centre from the camera's basis, as the
    // reference's camera rays (the line through the unprojected near and far
    // points): neither the interpolated position nor one reconstructed from
    // the G-buffer's depth through a float inverse of view_proj (off by up
    // to 5e-4 rad here) is on it to float precision.
    vec2 ndc = gl_FragCoord.xy * u_pixel_to_ndc - 1.0;
    highp vec3 lens = vec3((ndc + u_cam_proj.zw) / u_cam_proj.xy, -1.0), v, eye = u_eye;
    if (u_view_axis.w > 0.5) { // orthographic: parallel rays from the lens plane's point
        v = u_view_axis.xyz;
        eye += u_cam_basis * vec3(lens.xy, 0.0);
    } else {
        v = normalize(u_cam_basis * lens);
    }
    vec3 n_raster = normalize(world_normal);
    if (dot(n_raster, v) > 0.0) n_raster = -n_raster;
    mat3 inv3 = mat3(u_inv_model);

    // One traversal call site for all the pixel's rays (each call site is a
    // copy of the walk): ray 0 is the eye ray to the entry, its first hit,
    // else (silhouette) the rasterised surface; ray k >= 1 goes inside to
    // interface k, refracted or totally reflected while k <
    // u_max_interfaces; at the cap the light leaves through it in its
    // direction (ref_trace.c m_inside).
    vec3 p = (u_inv_model * vec4(eye, 1.0)).xyz, dir = v, n_entry = vec3(0.0);
    float path = 0.0;
    int at = RAY_FIRST;
    for (int k = 0; k <= MAX_INTERFACES; k++) {
        Ray ray = make_ray(p, inv3 * dir);
        float t = 3.0e38;
        int h = closest(ray, u_eps, t, at);
        if (h < 0 && k > 0) break;                              // open mesh: leaves in its direction
        vec3 ps, ns;
        surface_at(max(h, 0), ray, dir, ps, ns);
        p = h >= 0 ? ps : (u_inv_model * vec4(world_pos, 1.0)).xyz;
        vec3 n2 = h >= 0 ? ns : n_raster;
        at = h >= 0 ? h : RAY_AFTER_MISS;
        path += k > 0 ? t : 0.0;
        if (k > 0 && k >= u_max_interfaces) break;             // the cap
        vec3 out_dir;
        bool through = snell_refract(dir, n2, k == 0 ? 1.0 / snell_ior : snell_ior, out_dir);
        n_entry = k == 0 ? n2 : n_entry;                        // its reflection after the loop
        // the entry with an IOR below 1 at grazing incidence: the mirror, in
        // air; inside: refracted out, or totally reflected
        dir = k == 0 && !through ? snell_reflect(v, n2) : normalize(out_dir);
        if (through != (k == 0)) break;                        // not entered, or out
    }
    // The entry's reflection and Fresnel from its normal, recomputed here
    // rather than carried through the loop: fewer values live across it.
    vec3 r = snell_reflect(v, n_entry), in_dir;
    float fresnel = snell_refract(v, n_entry, 1.0 / snell_ior, in_dir) ?
                        snell_fresnel_schlick(-dot(v, n_entry), 1.0, snell_ior) : 1.0;
    if (bvh_over()) {
        // the budget ran out: single.frag's answer from the rasterised
        // surface (absorption over the bounding-sphere chord)
        r = snell_reflect(v, n_raster);
        snell_refract(v, n_raster, 1.0 / snell_ior, dir);
        fresnel = snell_fresnel_schlick(-dot(v, n_raster), 1.0, snell_ior);
        path = snell_sphere_exit(world_pos, dir, u_bsphere);
    }
    highp vec3 exit_p = bvh_over() ? world_pos : (u_model * vec4(p, 1.0)).xyz;
    // The look-ups after the branches: their implicit derivatives are
    // undefined in non-uniform control flow (GLSL ES 3.00, 8.9).
#if SNELL_ABSORB
    vec3 transmitted = snell_exit(exit_p, dir) * u_tint * snell_beer_lambert(u_sigma, path);
#else
    vec3 transmitted = snell_exit(exit_p, dir) * u_tint;
#endif
    vec3 reflected = snell_reflection(world_pos, r);
    exit_dir = dir;
    return mix(transmitted, reflected, fresnel);
}

void main()
{
    highp vec3 exit_dir;
#if SNELL_DISPERSION == 1
    // Per channel: the three traces in one loop, not three inlined copies of
    // the walk; red, blue, then green, whose exit direction is written (the
    // order of dispersion.glsl's snell_disp_trace).
    vec3 color = vec3(0.0);
    for (int c = 0; c < 3; c++) {
        vec3 m = c == 0 ? vec3(1.0, 0.0, 0.0) : (c == 1 ? vec3(0.0, 0.0, 1.0) : vec3(0.0, 1.0, 0.0));
        snell_ior = dot(u_ior_rgb, m);
        color += m * snell_glass_trace(exit_dir);
    }
#else
    vec3 color = snell_disp_trace(exit_dir);
#endif
    snell_write(color, exit_dir);
#ifdef SNELL_OUTPUT_EXIT_DIR_FLOAT
    if (bvh_over()) o_color.a = u_fallback_mark;
#endif
}
