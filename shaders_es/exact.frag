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

// The colour for one IOR, snell_ior (common/dispersion.glsl); g_over
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
    vec3 n = normalize(world_normal);
    if (dot(n, v) > 0.0) n = -n;
    mat3 inv3 = mat3(u_inv_model);

    // the entry: the eye ray's first hit, else (silhouette) the rasterised surface
    vec3 p = (u_inv_model * vec4(world_pos, 1.0)).xyz;
    float t_in = 3.0e38;
    vec3 b;
    int at = closest(make_ray((u_inv_model * vec4(eye, 1.0)).xyz, inv3 * v), 0.0, t_in, -1, b);
    if (at >= 0) surface_at(at, b, v, p, n);

    vec3 r = snell_reflect(v, n);
    vec3 dir;
    bool entered = snell_refract(v, n, 1.0 / snell_ior, dir);
    float fresnel = entered ? snell_fresnel_schlick(-dot(v, n), 1.0, snell_ior) : 1.0;
    dir = entered ? normalize(dir) : r;   // an IOR below 1 at grazing incidence: the mirror, in air
    float path = 0.0;
    // Inside: interface k (k = 1 the first surface after the entry) is
    // refracted or totally reflected while k < u_max_interfaces; at the cap
    // the light leaves through it in its direction (ref_trace.c m_inside).
    for (int k = 1; k <= MAX_INTERFACES; k++) {
        if (!entered) break;
        float t = 3.0e38;
        int h = closest(make_ray(p, inv3 * dir), u_eps, t, at, b);
        if (h < 0) break;                                       // open mesh: leaves in its direction
        path += t;
        at = h;
        vec3 n2;
        surface_at(h, b, dir, p, n2);
        if (k >= u_max_interfaces) break;                      // the cap
        vec3 out_dir;
        bool exited = snell_refract(dir, n2, snell_ior, out_dir);
        dir = normalize(out_dir);                               // refracted out, or totally reflected
        if (exited) break;
    }
    if (g_over) {
        // the budget ran out: single.frag's answer from the rasterised
        // surface (absorption over the bounding-sphere chord)
        n = normalize(world_normal);
        if (dot(n, v) > 0.0) n = -n;
        r = snell_reflect(v, n);
        snell_refract(v, n, 1.0 / snell_ior, dir);
        fresnel = snell_fresnel_schlick(-dot(v, n), 1.0, snell_ior);
        path = snell_sphere_exit(world_pos, dir, u_bsphere);
    }
    highp vec3 exit_p = g_over ? world_pos : (u_model * vec4(p, 1.0)).xyz;
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
    vec3 color = snell_disp_trace(exit_dir);
    snell_write(color, exit_dir);
#ifdef SNELL_OUTPUT_EXIT_DIR_FLOAT
    if (g_over) o_color.a = u_fallback_mark;
#endif
}
