// SPDX-License-Identifier: MIT
// water.glsl - the water and its container as something a ray meets (GLSL
// twin of src/ref/ref_water.c), included by beyond.glsl under SNELL_WATER.
// World space as snell_water.h. water_under (a ray in the water: floor or wall,
// Beer-Lambert), water_walls_above (a ray leaving the surface upwards),
// water_air_hit (what a ray in the air meets first), water_seen (what a ray
// sees of them). What each does: docs/ARCHITECTURE.md, "Design notes by file".
#include "common/water_tiles.glsl"

uniform highp float u_water_rim;       // top of the walls above the rest level
uniform highp float u_water_ior;
uniform highp vec3 u_water_sigma;      // Beer-Lambert absorption per world unit
uniform highp int u_water_n;           // nodes per side
uniform highp float u_water_dx;        // node spacing
#ifdef SNELL_WATER_STATE_UINT
uniform highp usampler2D u_water_heights; // the GPU simulation's state: fp32 bits of height (r), velocity (g)
highp float water_height(ivec2 q)
{
    return uintBitsToFloat(texelFetch(u_water_heights, clamp(q, ivec2(0), ivec2(u_water_n - 1)), 0).r);
}
#else
uniform highp sampler2D u_water_heights;  // R32F, from the CPU simulation
highp float water_height(ivec2 q)
{
    return texelFetch(u_water_heights, clamp(q, ivec2(0), ivec2(u_water_n - 1)), 0).r;
}
#endif

// The floor's light map (the caustics stage, src/water/water_caustics.c):
// its irradiance in units of the light's colour over |x|, |z| <= half, row 0
// at z = -half; read bilinearly by hand (a 32-bit float map need not be
// filterable). u_water_lit 0: a frame without a light, the tiles as they are.
uniform highp sampler2D u_water_light;
uniform int u_water_lit;

vec3 water_floor_light(highp vec2 xz)
{
    ivec2 n = textureSize(u_water_light, 0);
    highp vec2 t = (xz / (2.0 * u_water_half) + 0.5) * vec2(n) - 0.5;
    ivec2 b = ivec2(floor(t)), hi = n - 1;
    highp vec2 f = t - floor(t);
    vec3 e = mix(mix(texelFetch(u_water_light, clamp(b, ivec2(0), hi), 0).rgb,
                     texelFetch(u_water_light, clamp(b + ivec2(1, 0), ivec2(0), hi), 0).rgb, f.x),
                 mix(texelFetch(u_water_light, clamp(b + ivec2(0, 1), ivec2(0), hi), 0).rgb,
                     texelFetch(u_water_light, clamp(b + ivec2(1, 1), ivec2(0), hi), 0).rgb, f.x), f.y);
#ifdef SNELL_LIGHT_RANGE
    e *= SNELL_LIGHT_RANGE; // an RGB10_A2 map holds irradiance / range (core/glstate.h)
#endif
    return e;
}

// A face's tile seen from inside the water: the floor lit by the light map
// in a frame with a light (the walls are not: their light is not traced).
vec3 water_lit_tile(int face, highp vec3 q)
{
    vec3 c = water_tile(face, q);
    if (u_water_lit == 1 && face == 0) c *= water_floor_light(q.xz);
    return c;
}

// Distance from p along t (unit) to the container's floor or a wall seen
// from inside, and which face (0 floor, 1/2 x = -+half, 3/4 z = -+half).
highp float water_box_exit(highp vec3 p, highp vec3 t, out int face)
{
    highp float d = 3.0e38;
    face = 0;
    if (t.y < 0.0) d = (-u_water_depth - p.y) / t.y;
    if (t.x != 0.0) {
        highp float s = ((t.x > 0.0 ? u_water_half : -u_water_half) - p.x) / t.x;
        if (s < d) {
            d = s;
            face = t.x > 0.0 ? 2 : 1;
        }
    }
    if (t.z != 0.0) {
        highp float s = ((t.z > 0.0 ? u_water_half : -u_water_half) - p.z) / t.z;
        if (s < d) {
            d = s;
            face = t.z > 0.0 ? 4 : 3;
        }
    }
    return max(d, 0.0);
}

vec3 water_under(highp vec3 p, highp vec3 t)
{
    int face;
    highp float d = water_box_exit(p, t, face);
    return water_lit_tile(face, p + d * t) * snell_beer_lambert(u_water_sigma, d);
}

vec3 water_walls_above(highp vec3 p, highp vec3 r)
{
    int face;
    highp float e = water_box_exit(p, r, face); // no floor for a rising ray
    highp vec3 q = p + e * r;
    bool wall = r.y > 0.0 && face != 0 && q.y <= u_water_rim;
    vec3 c;
    if (wall) c = water_tile(face, q);
    else c = snell_env(r);
    return c; // at the end only (beyond.glsl, beyond_miss)
}

// The height field at world (x, z) inside the container, bilinear in its cell.
highp float water_height_at(highp vec2 xz, out highp vec2 cell, out ivec2 c0)
{
    highp vec2 g = clamp((xz + u_water_half) / u_water_dx, vec2(0.0), vec2(float(u_water_n - 1)));
    c0 = min(ivec2(floor(g)), ivec2(u_water_n - 2));
    cell = g - vec2(c0);
    highp float h00 = water_height(c0), h10 = water_height(c0 + ivec2(1, 0));
    highp float h01 = water_height(c0 + ivec2(0, 1)), h11 = water_height(c0 + ivec2(1, 1));
    return mix(mix(h00, h10, cell.x), mix(h01, h11, cell.x), cell.y);
}

// Whether p lies in the water: inside the container, under the surface.
bool water_contains(highp vec3 p)
{
    highp vec2 cell;
    ivec2 c0;
    return all(lessThan(abs(p.xz), vec2(u_water_half))) && p.y > -u_water_depth && p.y < water_height_at(p.xz, cell, c0);
}

// The vertex shader's per-node normal (unnormalised): central differences,
// one-sided at the walls (water_surface.vert).
highp vec3 water_node_normal(ivec2 q)
{
    ivec2 l = max(q - ivec2(1, 0), ivec2(0)), r = min(q + ivec2(1, 0), ivec2(u_water_n - 1));
    ivec2 d = max(q - ivec2(0, 1), ivec2(0)), u = min(q + ivec2(0, 1), ivec2(u_water_n - 1));
    highp float dhdx = (water_height(r) - water_height(l)) / (float(r.x - l.x) * u_water_dx);
    highp float dhdz = (water_height(u) - water_height(d)) / (float(u.y - d.y) * u_water_dx);
    return vec3(-dhdx, 1.0, -dhdz);
}

// What a ray in the air from o along unit d meets first: -1
// nothing, WATER_IN (it starts in the water), a face of the container
// (0..4) or WATER_SURFACE, at distance dist (the surface: unit normal n).
#define WATER_SURFACE 5
#define WATER_IN 6
int water_air_hit(highp vec3 o, highp vec3 d, out highp float dist, out highp vec3 n)
{
    dist = 3.0e38;
    n = vec3(0.0, 1.0, 0.0);
    // a ray leaving a glass object under the water is in the water (refracted as into air by the kernel)
    bool in_water = water_contains(o);
    int what = -1;
    // the container's faces: the floor and the four walls up to the rim, either side
    if (!in_water && d.y != 0.0) {
        highp float s = (-u_water_depth - o.y) / d.y;
        highp vec3 q = o + s * d;
        if (s > 0.0 && s < dist && abs(q.x) <= u_water_half && abs(q.z) <= u_water_half) {
            dist = s;
            what = 0;
        }
    }
    for (int k = 0; k < 4; k++) {
        highp float dk = k < 2 ? d.x : d.z, ok = k < 2 ? o.x : o.z;
        if (in_water || dk == 0.0) continue;
        highp float s = ((k % 2 == 0 ? -u_water_half : u_water_half) - ok) / dk;
        highp vec3 q = o + s * d;
        highp float other = k < 2 ? q.z : q.x;
        if (s > 0.0 && s < dist && abs(other) <= u_water_half && q.y >= -u_water_depth && q.y <= u_water_rim) {
            dist = s;
            what = k + 1;
        }
    }
    // the surface, from above: the rest plane, refined by the heights
    if (!in_water && d.y < 0.0) {
        highp vec2 cell;
        ivec2 c0;
        highp float s = -o.y / d.y;
        for (int k = 0; k < 3; k++) s = (water_height_at((o + s * d).xz, cell, c0) - o.y) / d.y;
        highp vec3 q = o + s * d;
        if (s > 0.0 && s < dist && abs(q.x) <= u_water_half && abs(q.z) <= u_water_half) {
            water_height_at(q.xz, cell, c0);
            n = normalize(mix(mix(water_node_normal(c0), water_node_normal(c0 + ivec2(1, 0)), cell.x),
                              mix(water_node_normal(c0 + ivec2(0, 1)), water_node_normal(c0 + ivec2(1, 1)), cell.x),
                              cell.y));
            dist = s;
            what = WATER_SURFACE;
        }
    }
    dist = in_water ? 0.0 : dist;
    return in_water ? WATER_IN : what; // at the end only (beyond.glsl, beyond_miss)
}

// What a ray from o along unit d sees of the water and its container, in
// col: false where it meets neither. in_water: o lies in the water. A ray in
// the water, one starting in it and one refracted into it at the surface
// share one look-up of the water's inside (water_under): GPU compilers
// inline every call, so each call site is a copy of the code.
bool water_seen(highp vec3 o, highp vec3 d, bool in_water, out vec3 col)
{
    highp vec3 uo = o, ud = d;
    vec3 above = vec3(0.0);
    float f = 0.0;
    highp float dist = 0.0;
    highp vec3 n = vec3(0.0, 1.0, 0.0);
    int what = WATER_IN;
    if (!in_water) what = water_air_hit(o, d, dist, n);
    if (what == WATER_SURFACE) {
        // reflected off the surface, refracted into the water
        uo = o + dist * d;
        n = dot(n, d) > 0.0 ? -n : n;
        highp vec3 t;
        snell_refract_sel(d, n, 1.0 / u_water_ior, t);
        f = snell_fresnel_schlick_sel(-dot(d, n), 1.0, u_water_ior);
        above = water_walls_above(uo, snell_reflect(d, n));
        ud = normalize(t);
    }
    if (what == WATER_IN || what == WATER_SURFACE) col = mix(water_under(uo, ud), above, f);
    else col = water_tile(max(what, 0), o + dist * d);
    return what >= 0; // at the end only (beyond.glsl, beyond_miss)
}
