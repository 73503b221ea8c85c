// SPDX-License-Identifier: MIT
// layered_bake.frag - one layer of one face of the layered method's distance
// cube maps (methods/layered.c; Umenhoffer, Patow and Szirmay-Kalos 2007, GPU
// Gems 3 ch. 17): the mesh seen from the analysed centre through a 90 degree
// face camera (ndcube_bake.vert), every face drawn, the nearest fragment
// behind the previous layer kept (depth test LESS on the Euclidean distance /
// radius, peel_depth.glsl's 24-bit test). Writes the object-space normal
// (16+16 bits, octahedral: pack.glsl) and the 24-bit distance + flag, which
// the next layer's pass tests against; layered.c reads both back into the
// filtered half-float layers the kernel reads.
precision highp float;

#include "common/pack.glsl"
#include "common/peel_depth.glsl"

in vec3 v_rel;                  // position relative to the centre, object units
in vec3 v_normal;               // object-space smooth normal

uniform float u_inv_radius;     // 1 / the radius every vertex lies within
uniform int u_first;            // 1: the nearest layer
uniform highp sampler2D u_prev; // the previous layer's depth + flag

layout(location = 0) out highp vec4 o_normal;
layout(location = 1) out highp vec4 o_next;

void main()
{
    highp float d = clamp(length(v_rel) * u_inv_radius, 0.0, 1.0);
    highp uint q = snell_peel_q(d);
    if (u_first == 0 && !snell_peel_behind(u_prev, q)) discard;
    gl_FragDepth = d;
    o_normal = snell_pack_dir_rgba8(normalize(v_normal));
    o_next = snell_peel_texel(q, 1u);
}
