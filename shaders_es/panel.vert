// SPDX-License-Identifier: MIT
// panel.vert - one quad over a glass panel's box (render/panels_stage.c):
// u_box in the frame's pixels, u_size the frame's size.
precision highp float;

uniform vec4 u_box;  // x0, y0, x1, y1
uniform vec2 u_size;

void main()
{
    vec2 c = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
    vec2 p = mix(u_box.xy, u_box.zw, c);
    gl_Position = vec4(2.0 * p / u_size - 1.0, 0.0, 1.0);
}
