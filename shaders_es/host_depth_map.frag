// SPDX-License-Identifier: MIT
// host_depth_map.frag - the host's window depth to snell's, or back where
// the frame changed it (render/host_depth_map.c): the two cameras share eye
// and axis, so one depth is an affine function of the other.
precision highp float;

uniform highp sampler2D u_depth;  // the depth to map, at the pixel (minus u_offset)
uniform vec2 u_map;               // out = u_map.x * in + u_map.y
uniform vec2 u_far;               // the far plane's depth: in, out (kept exactly)
uniform ivec2 u_offset;
#ifdef SNELL_DEPTH_BACK
uniform highp sampler2D u_before; // snell's depth before the frame: unchanged pixels keep the host's own
#endif

out vec4 o_color;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy) - u_offset;
    float d = texelFetch(u_depth, p, 0).r;
#ifdef SNELL_DEPTH_BACK
    if (d == texelFetch(u_before, p, 0).r) discard;
#endif
    gl_FragDepth = d == u_far.x ? u_far.y : clamp(u_map.x * d + u_map.y, 0.0, 1.0);
    o_color = vec4(0.0);
}
