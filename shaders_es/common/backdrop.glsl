// SPDX-License-Identifier: MIT
// backdrop.glsl - the host's scene behind the glass (snell_frame_desc.backdrop,
// render/backdrop.c): what a ray leaving the glass sees of what the host drew,
// before the environment. With the host's depth, a screen-space search as peel's
// (Wang 2014, seed 001 3.4): BACKDROP_LINEAR steps, BACKDROP_BINARY halvings;
// without it, the colour u_backdrop_distance along the ray. A ray that meets
// nothing reaches the host's far plane where its direction vanishes: on the
// view, where the host's depth holds its far plane (its sky), the host's colour
// there. Off the view, or not found: false. More: docs/ARCHITECTURE.md,
// "Design notes by file".
uniform highp mat4 u_backdrop_view_proj;
uniform highp vec4 u_backdrop_region;   // x, y, w, h of the texels that hold the view
uniform highp vec2 u_backdrop_size;     // the textures' size in texels
uniform highp float u_backdrop_distance; // > 0: no depth, the one look-up's distance
uniform highp float u_backdrop_far;      // the depth of the host's far plane: 1, or 0 (reversed-Z)
uniform mediump sampler2D u_backdrop_color;
uniform highp sampler2D u_backdrop_depth;

#define BACKDROP_LINEAR 32 // steps across the screen
#define BACKDROP_BINARY 6

highp vec2 backdrop_texel(highp vec2 ndc)
{
    return u_backdrop_region.xy + (ndc * 0.5 + 0.5) * u_backdrop_region.zw;
}

vec3 backdrop_color(highp vec2 ndc)
{
    return textureLod(u_backdrop_color, backdrop_texel(ndc) / u_backdrop_size, 0.0).rgb;
}

// Whether the point of ndc xy and window depth z lies behind the field.
bool backdrop_behind(highp vec3 p)
{
    highp vec2 t = clamp(backdrop_texel(p.xy), u_backdrop_region.xy, u_backdrop_region.xy + u_backdrop_region.zw - 1.0);
    highp float d = texelFetch(u_backdrop_depth, ivec2(t), 0).r;
    return d != u_backdrop_far && (u_backdrop_far > 0.5 ? p.z >= d : p.z <= d);
}

// The host's sky where the direction of clip coordinates cd vanishes, if on the view.
bool backdrop_sky(highp vec4 cd, out vec3 col)
{
    col = vec3(0.0);
    if (cd.w <= 0.0 || any(greaterThan(abs(cd.xy), vec2(cd.w)))) return false;
    highp vec2 t = clamp(backdrop_texel(cd.xy / cd.w), u_backdrop_region.xy,
                         u_backdrop_region.xy + u_backdrop_region.zw - 1.0);
    if (texelFetch(u_backdrop_depth, ivec2(t), 0).r != u_backdrop_far) return false;
    col = backdrop_color(cd.xy / cd.w);
    return true;
}

bool backdrop_seen(highp vec3 o, highp vec3 dir, out vec3 col)
{
    highp vec4 c0 = u_backdrop_view_proj * vec4(o, 1.0), cd = u_backdrop_view_proj * vec4(dir, 0.0);
    col = vec3(0.0);
    if (u_backdrop_distance > 0.0) {
        highp vec4 c = c0 + u_backdrop_distance * cd;
        if (c.w <= 0.0 || any(greaterThan(abs(c.xy), vec2(c.w)))) return false;
        col = backdrop_color(c.xy / c.w);
        return true;
    }
    // the part of o + t dir, t >= 0, inside -w <= x, y, z <= w (Liang-Barsky)
    highp float t0 = 0.0, t1 = 1e6;
    for (int k = 0; k < 6; k++) {
        highp float s = (k & 1) == 0 ? 1.0 : -1.0;
        int a = k / 2;
        highp float f = c0.w + s * c0[a], g = cd.w + s * cd[a];
        if (g < 0.0) t1 = min(t1, -f / g);
        else if (g > 0.0) t0 = max(t0, -f / g);
        else if (f < 0.0) return backdrop_sky(cd, col);
    }
    if (t0 > t1) return backdrop_sky(cd, col);
    highp vec4 ca = c0 + t0 * cd, cb = c0 + t1 * cd;
    highp vec3 a = ca.xyz / ca.w, b = cb.xyz / cb.w;
    a.z = a.z * 0.5 + 0.5;
    b.z = b.z * 0.5 + 0.5;
    highp float ua = 0.0, ub = -1.0;
    for (int i = 0; i <= BACKDROP_LINEAR; i++) {
        highp float u = float(i) / float(BACKDROP_LINEAR);
        if (backdrop_behind(mix(a, b, u))) {
            ub = u;
            break;
        }
        ua = u;
    }
    if (ub < 0.0) return backdrop_sky(cd, col);
    if (ub > 0.0) {
        for (int s = 0; s < BACKDROP_BINARY; s++) {
            highp float um = 0.5 * (ua + ub);
            if (backdrop_behind(mix(a, b, um))) ub = um;
            else ua = um;
        }
    }
    col = backdrop_color(mix(a.xy, b.xy, ub));
    return true;
}
