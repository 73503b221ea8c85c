// SPDX-License-Identifier: MIT
// receiver.glsl - the receiver plane (snell_frame_desc.receiver)
// lit by the caustics stage's light map, as the view sees it
// (caustics_receiver.frag) and as the glass sees it along its exit and
// reflected rays (common/beyond.glsl, SNELL_RECEIVER): albedo times the
// map's irradiance, one function for both so that the plane seen through
// glass of index 1 is the plane seen directly.
uniform highp sampler2D u_plane_map; // the light map: rgb irradiance (float rgba, render/caustics.c)
uniform highp vec4 u_plane;          // y, centre x, centre z, extent (half side; 0: no plane this frame)
uniform vec3 u_plane_albedo;

// The map at uv (0..1 over the square), bilinear by hand: a 32-bit float
// map need not be filterable.
vec3 receiver_irradiance(highp vec2 uv)
{
    ivec2 n = textureSize(u_plane_map, 0);
    highp vec2 t = uv * vec2(n) - 0.5;
    ivec2 b = ivec2(floor(t));
    vec2 f = t - floor(t);
    ivec2 hi = n - 1;
    vec3 e = mix(mix(texelFetch(u_plane_map, clamp(b, ivec2(0), hi), 0).rgb,
                     texelFetch(u_plane_map, clamp(b + ivec2(1, 0), ivec2(0), hi), 0).rgb, f.x),
                 mix(texelFetch(u_plane_map, clamp(b + ivec2(0, 1), ivec2(0), hi), 0).rgb,
                     texelFetch(u_plane_map, clamp(b + ivec2(1, 1), ivec2(0), hi), 0).rgb, f.x), f.y);
#ifdef SNELL_LIGHT_RANGE
    e *= SNELL_LIGHT_RANGE; // an RGB10_A2 map holds irradiance / range (core/glstate.h)
#endif
    return e;
}

// What the ray o + t dir (t > 0) sees of the plane: its lit colour where it
// meets the square from above, false elsewhere (the plane has no underside).
bool receiver_seen(highp vec3 o, highp vec3 dir, out vec3 col)
{
    highp vec2 xz = o.xz + dir.xz * ((u_plane.x - o.y) / dir.y);
    highp vec2 uv = (xz - u_plane.yz) / u_plane.w;
    // at the end only (common/beyond.glsl, beyond_miss)
    bool seen = !(u_plane.w <= 0.0 || dir.y >= 0.0 || o.y <= u_plane.x) && !any(greaterThan(abs(uv), vec2(1.0)));
    col = vec3(0.0);
    if (seen) col = u_plane_albedo * receiver_irradiance(uv * 0.5 + 0.5);
    return seen;
}
