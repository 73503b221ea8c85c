// SPDX-License-Identifier: MIT
// env_paraboloid.frag - one layer of the dual-paraboloid maps made from the
// cubemap (render/env_paraboloid.c): each texel holds the cube's bilinear
// radiance along its own direction (common/env.glsl, snell_dp_dir), also
// the texels past the rim, so look-ups near the rim filter true radiance.
precision highp float;

#include "common/env.glsl"

uniform float u_layer; // 0: the +Z hemisphere, 1: -Z
uniform float u_size;  // the maps' side, texels

layout(location = 0) out vec4 o_color;

void main()
{
    o_color = vec4(snell_env(snell_dp_dir(gl_FragCoord.xy / u_size, u_layer, u_size)), 1.0);
}
