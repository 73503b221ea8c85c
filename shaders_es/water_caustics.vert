// SPDX-License-Identifier: MIT
// water_caustics.vert - the container floor's light map (after Evan Wallace's
// webgl-water): one vertex per node of the height field, where the light's ray
// meets the surface, refracted and carried to the floor y = -depth. v_beam: its
// place across the light's beam; v_carry: what a unit of beam brings (Schlick,
// Beer-Lambert); v_surface, v_floor, v_light: for the fragment's shadow tests.
// More: docs/ARCHITECTURE.md, "Design notes by file".
precision highp float;
precision highp int;

#include "common/optics.glsl"

#ifdef SNELL_WATER_STATE_UINT
uniform highp usampler2D u_water_heights;
float height_at(ivec2 p)
{
    return uintBitsToFloat(texelFetch(u_water_heights, p, 0).r);
}
#else
uniform highp sampler2D u_water_heights;
float height_at(ivec2 p)
{
    return texelFetch(u_water_heights, p, 0).r;
}
#endif

uniform int u_water_n;
uniform highp float u_water_half, u_water_dx, u_water_depth, u_water_rim, u_water_ior;
uniform highp vec3 u_water_sigma;
uniform highp int u_spot;    // 1: a spot light at u_pos, axis u_dir
uniform highp vec3 u_dir;    // unit direction the light travels (spot: its axis)
uniform highp vec3 u_pos;
uniform highp vec3 u_beam_u, u_beam_v; // unit, across u_dir

out highp vec2 v_beam;
out vec3 v_carry;
out highp vec3 v_surface, v_floor, v_light;

void main()
{
    int i = gl_VertexID % u_water_n, j = gl_VertexID / u_water_n;
    int il = max(i - 1, 0), ir = min(i + 1, u_water_n - 1), jd = max(j - 1, 0), ju = min(j + 1, u_water_n - 1);
    float dhdx = (height_at(ivec2(ir, j)) - height_at(ivec2(il, j))) / (float(ir - il) * u_water_dx);
    float dhdz = (height_at(ivec2(i, ju)) - height_at(ivec2(i, jd))) / (float(ju - jd) * u_water_dx);
    vec3 p = vec3(-u_water_half + float(i) * u_water_dx, height_at(ivec2(i, j)), -u_water_half + float(j) * u_water_dx);
    vec3 n = normalize(vec3(-dhdx, 1.0, -dhdz));
    vec3 d = u_dir, q = p - u_pos;
    float reach = 3.0e38; // how far the light is, back along the ray
    v_beam = vec2(dot(p, u_beam_u), dot(p, u_beam_v));
    if (u_spot == 1) {
        float along = dot(q, u_dir);
        v_beam = vec2(dot(q, u_beam_u), dot(q, u_beam_v)) / max(along, 1e-6);
        reach = length(q);
        d = q / reach;
        if (along <= 0.0) reach = -1.0; // behind the light: unlit
    }
    v_carry = vec3(0.0);
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    // the rim's shadow: per fragment (water_caustics.frag)
    bool lit = d.y < 0.0 && reach > 0.0;
    if (dot(n, d) > 0.0) n = -n;
    vec3 t;
    snell_refract(d, n, 1.0 / u_water_ior, t);
    t = normalize(t);
    float s = t.y < 0.0 ? (-u_water_depth - p.y) / t.y : 0.0;
    vec3 f = p + s * t;
    if (lit && t.y < 0.0)
        v_carry = (1.0 - snell_fresnel_schlick(-dot(d, n), 1.0, u_water_ior)) * snell_beer_lambert(u_water_sigma, s);
    v_surface = p;
    v_floor = f;
    v_light = -d;
    gl_Position = vec4(f.x / u_water_half, f.z / u_water_half, 0.0, 1.0);
}
