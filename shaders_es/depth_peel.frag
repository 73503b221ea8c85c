// SPDX-License-Identifier: MIT
// depth_peel.frag - one depth peel (methods/peel.c, render/layers.c; Wang 2014
// 3.4, after Everitt): every face drawn with depth test LESS, a fragment no
// deeper than the previous layer discarded. Depth is view-axis distance mapped
// onto the bounding-sphere range in 24 bits, compared quantised, so no surface is
// kept twice. Writes the octahedral normal, depth + flag to the layer and to the
// ping-pong texture. More: docs/ARCHITECTURE.md, "Design notes by file".
precision highp float;

#include "common/pack.glsl"
#include "common/peel_depth.glsl"

in highp vec3 v_world_pos;
in highp vec3 v_world_normal;

uniform highp vec3 u_eye;
uniform highp vec3 u_fwd;           // unit view axis, world space
uniform highp float u_near;         // view depth of the bounding sphere's near side
uniform highp float u_inv_range;    // 1 / the sphere's diameter
uniform int u_first;                // 1: the nearest layer (nothing to peel yet)
uniform highp sampler2D u_prev;     // the previous layer's depth + flag
uniform int u_id;                   // the flag: 1 for the peel kernel, the object's id for the
                                    // scene layers (render/layers.c), 1..255

layout(location = 0) out highp vec4 o_normal;
layout(location = 1) out highp vec4 o_depth;
layout(location = 2) out highp vec4 o_next;

void main()
{
    highp uint q = snell_peel_q((dot(v_world_pos - u_eye, u_fwd) - u_near) * u_inv_range);
    if (u_first == 0 && !snell_peel_behind(u_prev, q)) discard;
    o_normal = snell_pack_dir_rgba8(normalize(v_world_normal));
    o_depth = snell_peel_texel(q, uint(u_id));
    o_next = o_depth;
}
