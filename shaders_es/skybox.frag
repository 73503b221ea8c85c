// SPDX-License-Identifier: MIT
// skybox.frag - the environment drawn as the background (Unger 2.2.2): the
// view direction through each pixel, rotation only, looked up in the cubemap.
precision SNELL_MEDIUMP float; // the context's policy (core/program.c)

#include "common/env.glsl"
#include "common/output.glsl"

in highp vec2 v_ndc;

uniform highp mat4 u_inv_view_proj_rot;  // inverse(proj * view without translation)


void main()
{
    highp vec4 d = u_inv_view_proj_rot * vec4(v_ndc, 1.0, 1.0);
    highp vec3 dir = d.xyz / d.w;
    snell_write_path(snell_env(dir), dir, false);
}
