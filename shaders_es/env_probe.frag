// SPDX-License-Identifier: MIT
// env_probe.frag - snell_env (common/env.glsl, as the kernels and the skybox
// build it) evaluated for a list of directions, one per pixel, read from a
// float texture: how snell_renderer_env_probe measures a look-up's error.
precision highp float;

#include "common/env.glsl"

uniform highp sampler2D u_dirs; // RGBA32F, xyz = direction, one per pixel

layout(location = 0) out vec4 o_color;

void main()
{
    o_color = vec4(snell_env(texelFetch(u_dirs, ivec2(gl_FragCoord.xy), 0).xyz), 1.0);
}
