// SPDX-License-Identifier: MIT
// depth_peel.frag - one depth peel (the peel kernel, methods/peel.c, and the scene layers, render/layers.c; Wang
// 2014 3.4, after Everitt's depth peeling): every face, front and back, is
// drawn with depth test LESS, and a fragment no deeper than the previous
// layer at its pixel is discarded, so the pass keeps the next surface behind
// it. Depth is the view-axis distance mapped linearly onto the object's
// bounding-sphere range [u_near, u_near + 1 / u_inv_range] in 24 bits; the
// test compares the same quantised value the previous pass stored, so a
// surface is never kept twice (two surfaces closer than 2r / 2^24 merge).
// Writes the unit world normal octahedrally in 16+16 bits (as gbuffer.frag),
// the depth + a flag (1; 0, the clear, marks an empty texel) to the layer,
// and the depth + flag again to the ping-pong texture the next peel reads.
// On a closed mesh the layers alternate front and back faces by
// construction (every face is drawn, nearest first); the kernel takes the
// gap's parity for inside or outside.
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
