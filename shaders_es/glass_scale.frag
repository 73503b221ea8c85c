// SPDX-License-Identifier: MIT
// glass_scale.frag - an object's colour at full resolution from its glass
// shaded at a resolution scale (render/glass_scale.c), drawn as any kernel is,
// so coverage and depth are the full raster's. Reads the small target: bilinear
// among the four nearest covered texels, else the nearest covered of the 4x4,
// else the single-surface answer here (no dispersion). More:
// docs/ARCHITECTURE.md, "Design notes by file".
precision highp float;

#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/surface.glsl"
#include "common/beyond.glsl"

uniform highp sampler2D u_small_color; // the small target's colour (RGBA8), alpha 1 where covered
uniform highp vec2 u_ratio;            // its texels per full-resolution pixel
uniform highp ivec2 u_max;             // its last texel used (the grid's size - 1)
#include "common/view.glsl"
uniform float u_ior;
uniform vec3 u_tint;
uniform vec3 u_sigma;             // Beer-Lambert coefficient per world unit
uniform highp vec4 u_bsphere;     // bounding sphere: world centre, radius
uniform float u_thickness;        // > 0: a thin wall of this thickness (single.frag's SNELL_THIN)

// The single-surface answer at the pixel's own surface point. Its look-ups
// sit in a branch that few pixels take; the environment has no mipmaps
// (frame/env.c), so their implicit derivatives select nothing.
vec3 single_surface(highp vec3 pos, highp vec3 normal)
{
    highp vec3 v = snell_view_ray(pos);
    vec3 n = normalize(normal);
    if (dot(n, v) > 0.0) n = -n;
    vec3 r = snell_reflect(v, n);
    if (u_thickness > 0.0) {
        vec3 rs, ts;
        snell_thin_slab(-dot(v, n), u_ior, u_sigma, u_thickness, rs, ts);
        highp vec3 straight = v;
        return snell_exit(pos, straight) * u_tint * ts + snell_reflection(pos, r) * rs;
    }
    vec3 t;
    snell_refract(v, n, 1.0 / u_ior, t);
    highp vec3 through = t;
    highp float path = snell_sphere_exit(pos, t, u_bsphere);
    float f = snell_fresnel_schlick(-dot(v, n), 1.0, u_ior);
    return mix(snell_exit(pos, through) * u_tint * snell_beer_lambert(u_sigma, path), snell_reflection(pos, r), f);
}

void main()
{
    highp vec3 pos, normal;
    snell_surface(pos, normal); // screen space: other objects' pixels discarded, depth written if needed
    highp vec2 q = gl_FragCoord.xy * u_ratio - 0.5;
    highp vec2 f = fract(q);
    ivec2 b = ivec2(floor(q));
    highp vec4 sum = vec4(0.0);
    for (int j = 0; j < 2; j++) {
        for (int i = 0; i < 2; i++) {
            ivec2 t = clamp(b + ivec2(i, j), ivec2(0), u_max);
            highp float w = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
            vec4 c = texelFetch(u_small_color, t, 0);
            if (c.a > 0.5) sum += w * vec4(c.rgb, 1.0);
        }
    }
    if (sum.a > 0.0) {
        o_color = vec4(sum.rgb / sum.a, 1.0);
        return;
    }
    highp float best = 1e9;
    vec3 c = vec3(0.0);
    for (int j = -1; j < 3; j++) {
        for (int i = -1; i < 3; i++) {
            ivec2 t = clamp(b + ivec2(i, j), ivec2(0), u_max);
            highp vec2 d = vec2(b + ivec2(i, j)) - q;
            vec4 ct = texelFetch(u_small_color, t, 0);
            if (ct.a > 0.5 && dot(d, d) < best) {
                best = dot(d, d);
                c = ct.rgb;
            }
        }
    }
    o_color = vec4(best < 1e9 ? c : single_surface(pos, normal), 1.0);
}
