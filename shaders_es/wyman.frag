// SPDX-License-Identifier: MIT
// wyman.frag - two-sided refraction in image space (Wyman 2005; seed 000
// 3.4.1): the exit point P2 = P1 + d T1 interpolates the view-ray and
// inward-normal thicknesses (the seed's equation 10); the exit normal is the
// back-face map's at P2, or the paper's fallback off the back faces; TIR
// reflects and stops. Schlick at the entry, Beer-Lambert over d. World space;
// window depth 24 bits; highp throughout. More: docs/methods.md, "Design notes
// by file".
precision highp float;

#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/surface.glsl"
#include "common/beyond.glsl"
#include "common/dispersion.glsl"

#include "common/view.glsl"
uniform vec3 u_sigma;
uniform vec3 u_tint;
uniform mat4 u_model;                // object -> world
uniform mat4 u_view_proj;

uniform highp sampler2D u_bnormal;   // back-face pass: octahedral 16+16 bits
uniform highp sampler2D u_bdepth_id; // back-face pass: window depth 24 bits, object id 8 bits
uniform float u_dn_scale;            // object units of a d_N value of 1 (the mesh's bounding diameter)
uniform int u_back_band;             // the back-face maps' guard band: texel = window pixel + band

#ifdef SNELL_SCREEN_SPACE
uniform highp sampler2D u_gaux;      // the G-buffer's aux target: d_N / u_dn_scale in 16 bits

float wyman_dn()
{
    return snell_unpack_unorm16(texelFetch(u_gaux, ivec2(gl_FragCoord.xy), 0).rg);
}
#else
// surface.glsl declares these for the screen-space stage; forward needs them for the back-face map
uniform highp mat4 u_inv_view_proj;
uniform highp vec2 u_inv_size;
uniform int u_gid;
in highp float v_aux;

float wyman_dn()
{
    return v_aux;
}
#endif

// The back face at window pixel px (-band .. size + band - 1), if it is this
// object's: world position and outward normal.
bool back_face(ivec2 px, out highp vec3 pos, out highp vec3 normal)
{
    ivec2 t = px + u_back_band;
    highp uvec4 b = uvec4(texelFetch(u_bdepth_id, t, 0) * 255.0 + 0.5);
    if (int(b.a) != u_gid) return false;
    highp float depth = float((b.r << 16u) | (b.g << 8u) | b.b) / 16777215.0;
    highp vec4 ndc = vec4((vec2(px) + 0.5) * u_inv_size * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    highp vec4 w = u_inv_view_proj * ndc;
    pos = w.xyz / w.w;
    highp vec4 g = texelFetch(u_bnormal, t, 0);
    normal = snell_oct_decode(vec2(snell_unpack_unorm16(g.xy), snell_unpack_unorm16(g.zw)) * 2.0 - 1.0);
    return true;
}

#if SNELL_DISPERSION == 2
// One-path dispersion: the back-face map's normal at the projection of q, a
// red or blue ray's exit estimate, facing that ray's direction dir; n_green
// where the map holds no back face of this object there.
vec3 disp_exit_normal(highp vec3 q, vec3 dir, ivec2 size, vec3 n_green)
{
    highp vec3 pb, n;
    highp vec4 c = u_view_proj * vec4(q, 1.0);
    ivec2 px = ivec2(floor((c.xy / c.w * 0.5 + 0.5) * vec2(size)));
    bool inside = c.w > 0.0 && all(greaterThanEqual(px, ivec2(-u_back_band))) && all(lessThan(px, size + u_back_band));
    if (!(inside && back_face(px, pb, n))) n = n_green;
    return dot(n, dir) > 0.0 ? -n : n;
}
#endif

// The colour for one IOR, snell_ior (common/dispersion.glsl calls it).
vec3 snell_glass_trace(out highp vec3 exit_dir)
{
    highp vec3 p1, n1;
    snell_surface(p1, n1);
    highp vec3 v = snell_view_ray(p1);
    vec3 n = normalize(n1);
    if (dot(n, v) > 0.0) n = -n;
    vec3 r = snell_reflect(v, n);
    vec3 t1;
    snell_refract(v, n, 1.0 / snell_ior, t1);
    t1 = normalize(t1);
    snell_disp_enter(v, n);
    float fresnel = snell_fresnel_schlick(-dot(v, n), 1.0, snell_ior);

    // d_N in world units: the object-space thickness along the inward normal,
    // scaled as the model matrix stretches the normal's object direction.
    mat3 m3 = mat3(u_model);
    float d_n = wyman_dn() * u_dn_scale * length(m3 * normalize(transpose(m3) * n));
    highp vec3 pb, nb;
    ivec2 size = ivec2(1.0 / u_inv_size + 0.5);
    float d_v = back_face(ivec2(gl_FragCoord.xy), pb, nb) ? max(dot(pb - p1, v), 0.0) : d_n;
    float th_i = acos(clamp(-dot(v, n), 0.0, 1.0));
    float th_t = acos(clamp(-dot(t1, n), 0.0, 1.0));
    float w = th_i > 1e-3 ? th_t / th_i : 1.0 / snell_ior; // the ratio's limit at normal incidence
    float d = w * d_v + (1.0 - w) * d_n;
    highp vec3 p2 = p1 + d * t1;

    highp vec4 c = u_view_proj * vec4(p2, 1.0);
    ivec2 q = ivec2(floor((c.xy / c.w * 0.5 + 0.5) * vec2(size)));
    vec3 n2;
    bool inside = c.w > 0.0 && all(greaterThanEqual(q, ivec2(-u_back_band))) && all(lessThan(q, size + u_back_band));
    if (!(inside && back_face(q, pb, n2))) {
        // Wyman's fallback: a normal perpendicular to the view vector (in the plane of V and T1)
        vec3 side = t1 - dot(t1, v) * v;
        n2 = dot(side, side) > 1e-12 ? normalize(side) : -n;
    }
    if (dot(n2, t1) > 0.0) n2 = -n2; // face the ray (it comes from inside)
    vec3 dir;
    bool exited = snell_refract(t1, n2, snell_ior, dir); // refracted out, or on TIR reflected: the capped direction
    dir = normalize(dir);
#if SNELL_DISPERSION == 2
    // red and blue leave near where their own rays are after the green ray's
    // length d: the back-face map's normal there (a curved exit bends them by
    // its change of normal as much as by their IORs), else green's
    snell_disp_cross3(mat3(disp_exit_normal(p1 + d * snell_disp_dirs[0], snell_disp_dirs[0], size, n2), n2,
                           disp_exit_normal(p1 + d * snell_disp_dirs[2], snell_disp_dirs[2], size, n2)), exited, true);
#else
    snell_disp_cross(n2, exited, true);
#endif

#if SNELL_ABSORB
    vec3 transmitted = snell_disp_exit(p2, dir) * u_tint * snell_beer_lambert(u_sigma, d);
#else
    vec3 transmitted = snell_disp_exit(p2, dir) * u_tint;
#endif
    vec3 reflected = snell_reflection(p1, r);
    exit_dir = dir;
    return mix(transmitted, reflected, fresnel);
}
