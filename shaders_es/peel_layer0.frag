// SPDX-License-Identifier: MIT
// peel_layer0.frag - the peel kernel's first layer (methods/peel.c) from the
// screen-space stage's G-buffer, which already holds the object's front
// surface there: a full-screen triangle over the object's scissor writes, at
// the texels of the object's id, the G-buffer's normal texel as it is and the
// view-axis depth of its surface point (common/surface.glsl: from the 24-bit
// window depth) quantised as depth_peel.frag quantises it, to layer 0 and to
// the ping-pong texture peel 1 reads. Other texels keep the clear (empty).
// Where the G-buffer's front surface differs from what a peel would keep
// (another object nearer, a mesh without known winding) peel.c peels instead.
precision highp float;

#define SNELL_SCREEN_SPACE 1
#include "common/pack.glsl"
#include "common/surface.glsl"
#include "common/peel_depth.glsl"

uniform highp vec3 u_eye;
uniform highp vec3 u_fwd;           // unit view axis, world space
uniform highp float u_near;         // view depth of the bounding sphere's near side
uniform highp float u_inv_range;    // 1 / the sphere's diameter

layout(location = 0) out highp vec4 o_normal;
layout(location = 1) out highp vec4 o_depth;
layout(location = 2) out highp vec4 o_next;

void main()
{
    highp vec3 pos, n;
    snell_surface(pos, n); // discards other objects' texels
    highp uint q = snell_peel_q((dot(pos - u_eye, u_fwd) - u_near) * u_inv_range);
    // the normal's bytes unchanged ((b + 0.25) / 255: stored as b, pack.glsl)
    o_normal = (floor(texelFetch(u_gnormal, ivec2(gl_FragCoord.xy), 0) * 255.0 + 0.5) + 0.25) / 255.0;
    o_depth = snell_peel_texel(q, 1u);
    o_next = o_depth;
}
