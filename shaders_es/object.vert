// SPDX-License-Identifier: MIT
// object.vert - world-space position and normal of a mesh, for every glass
// kernel and for opaque objects (in the view and in dynamic environments).
// Positions are highp (depth, search parameters).
precision highp float;

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;          // object -> world
uniform mat3 u_normal_matrix;  // inverse transpose of u_model's 3x3
uniform mat4 u_view_proj;

out vec3 v_world_pos;
out vec3 v_world_normal;
#ifdef SNELL_VERTEX_AUX
// a method's per-vertex scalar (snell__object.vao, attribute 2), passed through
layout(location = 2) in float a_aux;
out float v_aux;
#endif

void main()
{
#ifdef SNELL_VERTEX_AUX
    v_aux = a_aux;
#endif
    vec4 wp = u_model * vec4(a_position, 1.0);
    v_world_pos = wp.xyz;
    v_world_normal = u_normal_matrix * a_normal;
    gl_Position = u_view_proj * wp;
}
