// SPDX-License-Identifier: MIT
// ndcube_bake.vert - the mesh seen from the cubemap centre, one cube face per
// pass (Unger 4.1). Object space: the cubemap is baked once per mesh version,
// independent of the model matrix.
precision highp float;

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_view_proj;   // cube face camera at u_centre (object space)
uniform vec3 u_centre;

out vec3 v_rel;             // position relative to the centre, object units
out vec3 v_normal;          // object-space smooth normal

void main()
{
    v_rel = a_position - u_centre;
    v_normal = a_normal;
    gl_Position = u_view_proj * vec4(a_position, 1.0);
}
