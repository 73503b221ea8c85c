// SPDX-License-Identifier: MIT
// lines.vert - light path segments as GL_LINES (Brueckner 6.5.1). Positions in
// lightmap pixels (x right, y down); colour = flux x flux correction (eq. 6.4),
// already scaled on the CPU.
precision highp float;

layout(location = 0) in vec2 a_pos;
layout(location = 1) in vec3 a_color;

uniform vec2 u_size;  // lightmap size in pixels

out vec3 v_color;
flat out highp uint v_seed;

void main()
{
    vec2 ndc = a_pos / u_size * 2.0 - 1.0;
    gl_Position = vec4(ndc.x, -ndc.y, 0.0, 1.0);  // row 0 at the top
    v_color = a_color;
    v_seed = uint(gl_VertexID >> 1);  // one seed per line, for stochastic rounding
}
