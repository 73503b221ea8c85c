// SPDX-License-Identifier: MIT
// caustics_quad.vert - the receiver plane's square (4 vertices, a triangle
// strip): in the light map, the whole target (v_ndc); in the view, the square
// at y = h under u_view_proj.
precision highp float;

uniform vec4 u_plane;        // y, centre x, centre z, extent
uniform mat4 u_view_proj;    // used with SNELL_RECEIVER_VIEW
out vec2 v_ndc;
#ifdef SNELL_RECEIVER_VIEW
out vec3 v_world_pos;
#endif

void main()
{
    v_ndc = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
#ifdef SNELL_RECEIVER_VIEW
    vec3 p = vec3(u_plane.y + v_ndc.x * u_plane.w, u_plane.x, u_plane.z + v_ndc.y * u_plane.w);
    v_world_pos = p;
    gl_Position = u_view_proj * vec4(p, 1.0);
#else
    gl_Position = vec4(v_ndc, 0.0, 1.0);
#endif
}
