// SPDX-License-Identifier: MIT
// water_surface.frag - the water surface (Dachsbacher 2002, "Refraction
// Mapping"): the view ray refracted at the per-pixel normal meets the container
// exactly (the seed's five ray-wall distances); the mirror ray sees the walls
// or the environment; Schlick weighs the two, Beer-Lambert in the water.
// Objects in the water: SNELL_BEYOND marches the refracted ray through the scene
// layers; SNELL_WATER_OBJECTS (opaque objects only) searches their copied depth
// in screen space. Exit-direction output: the refracted direction. Details:
// docs/ARCHITECTURE.md, "Design notes by file".
precision highp float;

#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/beyond.glsl"

in vec3 v_world_pos;
in vec3 v_world_normal;

#include "common/view.glsl"

#ifdef SNELL_WATER_OBJECTS
uniform highp sampler2D u_scene_depth; // the opaque objects' window depth (1: none)
uniform sampler2D u_scene_color;
uniform mat4 u_view_proj;
uniform vec2 u_depth_ab;    // proj[2][2], proj[3][2]: view depth = b / (ndc z + a)
// World bounding spheres of the opaque objects (centre, radius; one enclosing
// sphere when there are more than SNELL_WATER_MAX_SPHERES): the search runs
// only over the part of the refracted segment inside them.
#define SNELL_WATER_MAX_SPHERES 16
uniform vec4 u_spheres[SNELL_WATER_MAX_SPHERES];
uniform int u_sphere_count;

// The search runs in clip space, where the refracted segment p .. p + dmax t
// is a straight line (c0 .. c1, clip w = view depth): one matrix product per
// pixel, none per step. 1 if the point at fraction f lies behind an opaque
// surface by less than thickness (view depth).
bool behind_object(vec4 c0, vec4 c1, float f, float thickness, ivec2 size, out ivec2 pix)
{
    vec4 c = mix(c0, c1, f);
    pix = ivec2(floor((c.xy / c.w * 0.5 + 0.5) * vec2(size)));
    if (c.w <= 0.0 || any(lessThan(pix, ivec2(0))) || any(greaterThanEqual(pix, size))) return false;
    float zs = texelFetch(u_scene_depth, pix, 0).r;
    if (zs >= 1.0) return false;
    float ds = u_depth_ab.y / (2.0 * zs - 1.0 + u_depth_ab.x);
    return c.w > ds && c.w - ds < thickness;
}

// Distance along t from p to the first opaque surface before dmax (its colour in col), or -1.
float find_object(vec3 p, vec3 t, float dmax, out vec3 col)
{
    ivec2 pix, size = textureSize(u_scene_depth, 0);
    float a = dmax, b = 0.0;
    for (int k = 0; k < SNELL_WATER_MAX_SPHERES; k++) {
        if (k >= u_sphere_count) break;
        vec3 oc = p - u_spheres[k].xyz;
        float hb = dot(oc, t), c = dot(oc, oc) - u_spheres[k].w * u_spheres[k].w, disc = hb * hb - c;
        if (disc < 0.0) continue;
        float q = sqrt(disc), s0 = max(-hb - q, 0.0), s1 = min(-hb + q, dmax);
        if (s0 < s1) {
            a = min(a, s0);
            b = max(b, s1);
        }
    }
    if (a >= b) return -1.0;
    vec4 c0 = u_view_proj * vec4(p + a * t, 1.0), c1 = u_view_proj * vec4(p + b * t, 1.0);
    // a twelfth of the way to the container: thick enough for a step over the
    // objects' spheres to land inside, thin enough not to stop behind them
    // (bench/notes/code.md, "water_surface.frag")
    float lo = 0.0, hi = -1.0, thickness = 2.0 * dmax / 24.0;
    for (int k = 1; k <= 24; k++) {
        float f = float(k) / 24.0;
        if (behind_object(c0, c1, f, thickness, size, pix)) {
            hi = f;
            break;
        }
        lo = f;
    }
    if (hi < 0.0) return -1.0;
    for (int k = 0; k < 6; k++) {
        float m = 0.5 * (lo + hi);
        if (behind_object(c0, c1, m, thickness, size, pix)) hi = m;
        else lo = m;
    }
    behind_object(c0, c1, hi, thickness, size, pix);
    col = texelFetch(u_scene_color, pix, 0).rgb;
    return a + hi * (b - a);
}
#endif

void main()
{
    highp vec3 p = v_world_pos;
    highp vec3 v = snell_view_ray(p);
    highp vec3 n = normalize(v_world_normal);
    if (dot(n, v) > 0.0) n = -n;
    highp vec3 r = snell_reflect(v, n), t;
    snell_refract(v, n, 1.0 / u_water_ior, t);
    t = normalize(t);
    float fresnel = snell_fresnel_schlick(-dot(v, n), 1.0, u_water_ior);
#ifdef SNELL_BEYOND
    highp vec3 dir = t;
    beyond_start_in_water = true;
    vec3 seen = snell_exit(p, dir);
#else
    int face;
    highp float d = water_box_exit(p, t, face);
    vec3 seen = water_lit_tile(face, p + d * t);
#ifdef SNELL_WATER_OBJECTS
    vec3 col;
    float e = find_object(p, t, d, col);
    if (e >= 0.0) {
        seen = col;
        d = e;
    }
#endif
    seen *= snell_beer_lambert(u_water_sigma, d);
#endif
    snell_write(mix(seen, water_walls_above(p, r), fresnel), t);
}
