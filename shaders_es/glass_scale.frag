// glass_scale.frag - an object's colour at full resolution from its glass
// shaded at a resolution scale (render/glass_scale.c): drawn on the object's
// own faces, so the silhouette is the full raster's, reading the small
// target's colour and depth (1.0 where the object did not cover the texel).
// Bilinear among the four nearest texels, but only those the object covers
// and whose surface is the fragment's own (view distance within DEPTH_TOL of
// it; joint bilateral upsampling, Kopf et al. 2007, with a depth weight of 0
// or 1): no background from outside the silhouette, no ear blended into the
// body behind it. Where none of the four qualifies (a sliver thinner than a
// texel, an edge over another part of the object), the covered texel of the
// 4x4 around with the nearest view distance.
precision highp float;

uniform highp sampler2D u_color;     // the small target's colour (RGBA8)
uniform highp sampler2D u_depth;     // ... and window depth, 1.0 = not covered
uniform highp vec2 u_ratio;          // its texels per full-resolution pixel
uniform highp ivec2 u_max;           // its last texel used (the grid's size - 1)
uniform highp vec4 u_inv_proj_z;     // the inverse projection's [2][2], [3][2], [2][3], [3][3]: view z from NDC z

layout(location = 0) out vec4 o_color;

// Relative view-distance difference above which two samples are different surfaces.
#define DEPTH_TOL 0.02

highp float view_distance(highp float window_depth)
{
    highp float n = window_depth * 2.0 - 1.0;
    return -(u_inv_proj_z.x * n + u_inv_proj_z.y) / (u_inv_proj_z.z * n + u_inv_proj_z.w);
}

void main()
{
    highp vec2 q = gl_FragCoord.xy * u_ratio - 0.5;
    highp vec2 f = fract(q);
    ivec2 b = ivec2(floor(q));
    highp float z = view_distance(gl_FragCoord.z);
    highp vec4 sum = vec4(0.0);
    for (int j = 0; j < 2; j++) {
        for (int i = 0; i < 2; i++) {
            ivec2 t = clamp(b + ivec2(i, j), ivec2(0), u_max);
            highp float d = texelFetch(u_depth, t, 0).r;
            highp float w = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
            if (d < 1.0 && abs(view_distance(d) - z) <= DEPTH_TOL * z)
                sum += w * vec4(texelFetch(u_color, t, 0).rgb, 1.0);
        }
    }
    if (sum.a > 0.0) {
        o_color = vec4(sum.rgb / sum.a, 1.0);
        return;
    }
    highp float best = 1e30;
    vec3 c = vec3(0.0);
    for (int j = -1; j < 3; j++) {
        for (int i = -1; i < 3; i++) {
            ivec2 t = clamp(b + ivec2(i, j), ivec2(0), u_max);
            highp float d = texelFetch(u_depth, t, 0).r;
            highp float e = abs(view_distance(d) - z);
            if (d < 1.0 && e < best) {
                best = e;
                c = texelFetch(u_color, t, 0).rgb;
            }
        }
    }
    // Nothing of the object within two texels: a feature the small grid
    // missed; its fragment is left to what lies behind.
    if (best == 1e30) discard;
    o_color = vec4(c, 1.0);
}
