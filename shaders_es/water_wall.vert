// SPDX-License-Identifier: MIT
// water_wall.vert - the container's floor and walls (zero thickness, both
// sides drawn): world positions and the face each belongs to.
precision highp float;

layout(location = 0) in vec3 a_position;
layout(location = 1) in float a_face;

uniform mat4 u_view_proj;

out vec3 v_world_pos;
flat out int v_face;

void main()
{
    v_world_pos = a_position;
    v_face = int(a_face + 0.5);
    gl_Position = u_view_proj * vec4(a_position, 1.0);
}
