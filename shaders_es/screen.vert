// SPDX-License-Identifier: MIT
// screen.vert - one full-screen triangle for the screen-space stage: a glass
// kernel then runs once per pixel the scissor and the G-buffer leave it
// (common/surface.glsl).
precision highp float;

void main()
{
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 1.0, 1.0); // at the far plane: GREATER passes where anything was drawn
}
