// SPDX-License-Identifier: MIT
// panel.frag - one glass panel, or a merged group, over what lies beneath:
// snell_panels.h's model (field, height, light, edge, shadow) per pixel,
// the normal from the field's analytic gradient (render/panels_stage.c).
// PANEL_SOURCE 0: the frame's capture (frost: its mip level u_lod); 1: an
// app's texture, 2: an external one, through u_uv. PANEL_DISPERSION: a
// ray per colour channel.
#ifndef PANEL_SOURCE
#define PANEL_SOURCE 0
#endif
#ifndef PANEL_DISPERSION
#define PANEL_DISPERSION 0
#endif
#if PANEL_SOURCE == 2
#extension GL_OES_EGL_image_external_essl3 : require
#endif
precision highp float;

#include "common/optics.glsl"

#define PANEL_MEMBERS 8 // SNELL_PANEL_GROUP_MAX

#if PANEL_SOURCE == 2
uniform highp samplerExternalOES u_beneath;
#else
uniform highp sampler2D u_beneath;
#endif
uniform mat4 u_uv;                        // PANEL_SOURCE 1, 2: the texture's uv over the frame's
uniform vec2 u_size;                      // the frame's, pixels
uniform float u_lod;                      // the capture's level: frost
uniform float u_spread;                   // frost: its taps' offset, pixels; 0: one tap
uniform int u_count;                      // members
uniform vec4 u_rect[PANEL_MEMBERS];       // centre, half size
uniform vec4 u_radius[PANEL_MEMBERS];     // bottom-left, bottom-right, top-right, top-left
uniform float u_exponent[PANEL_MEMBERS];
uniform float u_merge;                    // smoothing k; 0: a plain union
uniform vec3 u_slab;                      // thickness, bevel (0: flat), profile (0 circular, 1 squircle)
uniform vec3 u_ior;                       // per channel
uniform vec4 u_tint;
uniform vec4 u_light;                     // unit direction, rim strength
uniform vec4 u_shadow;                    // radius, opacity, offset

out vec4 o_color;

// One member's signed distance and its gradient: q = |p - c| - (b - r),
// d = ||max(q, 0)||_n + min(max(q.x, q.y), 0) - r, the norm taken over
// its largest component so that no power overflows.
float member(int i, vec2 p, out vec2 g)
{
    vec2 rel = p - u_rect[i].xy, side = vec2(rel.x < 0.0 ? -1.0 : 1.0, rel.y < 0.0 ? -1.0 : 1.0);
    vec4 rr = u_radius[i];
    float r = rel.y < 0.0 ? (rel.x < 0.0 ? rr.x : rr.y) : (rel.x < 0.0 ? rr.w : rr.z);
    vec2 q = abs(rel) - (u_rect[i].zw - r);
    if (max(q.x, q.y) <= 0.0) {
        g = side * (q.x > q.y ? vec2(1.0, 0.0) : vec2(0.0, 1.0));
        return max(q.x, q.y) - r;
    }
    float n = u_exponent[i];
    vec2 m = max(q, 0.0);
    if (n == 2.0) { // circular corners, without powers
        float len = length(m);
        g = side * m / len;
        return len - r;
    }
    float big = max(m.x, m.y);
    vec2 t = m / big;
    float sum = pow(t.x, n) + pow(t.y, n);
    g = side * vec2(pow(t.x, n - 1.0), pow(t.y, n - 1.0)) / pow(sum, (n - 1.0) / n);
    return big * pow(sum, 1.0 / n) - r;
}

// The shape's field: its members smooth-unioned in order, smin(a, b) =
// min(a, b) - max(k - |a - b|, 0)^2 / (4 k); its gradient blends the two
// by w = max(k - |a - b|, 0) / (2 k).
float field(vec2 p, out vec2 g)
{
    float d = member(0, p, g);
    for (int i = 1; i < u_count; i++) {
        vec2 gi;
        float di = member(i, p, gi);
        if (u_merge > 0.0) {
            float h = max(u_merge - abs(d - di), 0.0), w = h / (2.0 * u_merge);
            g = d < di ? mix(g, gi, w) : mix(gi, g, w);
            d = min(d, di) - h * h / (4.0 * u_merge);
        } else if (di < d) {
            d = di;
            g = gi;
        }
    }
    return d;
}

vec4 beneath(vec2 p)
{
#if PANEL_SOURCE == 0
    if (u_spread <= 0.0) return textureLod(u_beneath, p / u_size, u_lod);
    // Frost: four taps of level u_lod at (+-a, +-a) add a^2 to its variance per axis.
    vec2 a = vec2(u_spread) / u_size, uv = p / u_size;
    return 0.25 * (textureLod(u_beneath, uv + a, u_lod) + textureLod(u_beneath, uv - a, u_lod) +
                   textureLod(u_beneath, uv + vec2(a.x, -a.y), u_lod) + textureLod(u_beneath, uv + vec2(-a.x, a.y), u_lod));
#else
    return texture(u_beneath, (u_uv * vec4(p / u_size, 0.0, 1.0)).xy);
#endif
}

// The height h(s) and its slope h'(s) at s pixels inside.
vec2 height(float s)
{
    float thick = u_slab.x, bevel = u_slab.y;
    if (bevel <= 0.0 || s >= bevel) return vec2(thick, 0.0);
    float u = max(s, 0.0) / bevel, v = 1.0 - u, p, dp;
    if (u_slab.z < 0.5) {
        p = sqrt(u * (2.0 - u)); // sqrt(1 - (1 - u)^2)
        dp = v / p;
    } else {
        p = sqrt(sqrt(u * (2.0 - u) * (1.0 + v * v))); // (1 - (1 - u)^4)^(1/4)
        dp = v * v * v / (p * p * p);
    }
    return vec2(thick * p, thick / bevel * dp);
}

// The glass at p, s pixels inside, its field's gradient g: the view ray
// (0, 0, -1) refracted at the top, read where it meets z = 0.
vec3 glass(vec2 p, float s, vec2 g)
{
    vec2 h = height(s);
    vec3 n = normalize(vec3(h.y * g, 1.0)), view = vec3(0.0, 0.0, -1.0), t;
#if PANEL_DISPERSION
    vec3 under, f;
    for (int c = 0; c < 3; c++) {
        snell_refract(view, n, 1.0 / u_ior[c], t);
        under[c] = beneath(p + h.x * t.xy / -t.z)[c];
        f[c] = snell_fresnel_exact(n.z, 1.0, u_ior[c]);
    }
#else
    snell_refract(view, n, 1.0 / u_ior.g, t);
    vec3 under = beneath(p + h.x * t.xy / -t.z).rgb;
    vec3 f = vec3(snell_fresnel_exact(n.z, 1.0, u_ior.g));
#endif
    float rim = u_light.w * pow(max(dot(snell_reflect(view, n), u_light.xyz), 0.0), 4.0);
    return (1.0 - f) * mix(under, u_tint.rgb, u_tint.a) + f * rim;
}

// The area of the pixel (a unit square about its centre) on the inside of
// a straight edge at signed distance de along the unit normal nrm.
float coverage(float de, vec2 nrm)
{
    float a = max(abs(nrm.x), abs(nrm.y)), b = max(min(abs(nrm.x), abs(nrm.y)), 1e-4);
    float t = -de, lo = 0.5 * (a - b), hi = 0.5 * (a + b);
    if (t <= -hi) return 0.0;
    if (t >= hi) return 1.0;
    if (abs(t) <= lo) return 0.5 + t / a;
    float e = hi - abs(t), corner = e * e / (2.0 * a * b);
    return t < 0.0 ? corner : 1.0 - corner;
}

void main()
{
    vec2 p = gl_FragCoord.xy, g;
    float d = field(p, g), len = max(length(g), 1e-6), de = d / len;
    float cover = coverage(de, g / len), shade = 1.0;
    if (u_shadow.y > 0.0 && cover < 1.0) {
        vec2 gs;
        float ds = field(p - u_shadow.zw, gs);
        float x = u_shadow.x > 0.0 ? clamp(ds / u_shadow.x, 0.0, 1.0) : (ds > 0.0 ? 1.0 : 0.0);
        shade = 1.0 - u_shadow.y * (1.0 - x) * (1.0 - x);
    }
    if (cover <= 0.0 && shade >= 1.0) discard;
#if PANEL_SOURCE == 0
    vec4 here = texelFetch(u_beneath, ivec2(p), 0); // unblurred
#else
    vec4 here = beneath(p);
#endif
    vec3 outside = here.rgb * shade, inside = outside;
    if (cover > 0.0) {
        // An edge pixel's glass at the centroid of its inside part (for an
        // edge across it, half way between the edge and the far side).
        float s = -de, s_in = s < 0.5 ? 0.5 * (s + 0.5) : s;
        inside = glass(p - (s_in - s) * g / len, s_in * len, g);
    }
    o_color = vec4(mix(outside, inside, cover), here.a);
}
