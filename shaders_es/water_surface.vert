// SPDX-License-Identifier: MIT
// water_surface.vert - the water's height field as a grid of nodes (one vertex
// per node, gl_VertexID = j * n + i, no vertex attributes): the world
// position (x, h, z) and the seed's per-node normal (-dh/dx, 1, -dh/dz) from
// central differences, one-sided at the walls ("CLAMP"), left unnormalised so
// the fragment stage interpolates it per pixel as the reference does.
// Heights come from an R32F texture (CPU simulation) or straight from the
// GPU simulation's RG32UI state (SNELL_WATER_STATE_UINT).
precision highp float;
precision highp int;

// (the uniforms as common/water.glsl declares them: one program, one set)
#ifdef SNELL_WATER_STATE_UINT
uniform highp usampler2D u_water_heights;
float height_at(ivec2 p)
{
    return uintBitsToFloat(texelFetch(u_water_heights, p, 0).r);
}
#else
uniform highp sampler2D u_water_heights;
float height_at(ivec2 p)
{
    return texelFetch(u_water_heights, p, 0).r;
}
#endif

uniform int u_water_n;
uniform highp float u_water_half, u_water_dx;
uniform mat4 u_view_proj;

out vec3 v_world_pos;
out vec3 v_world_normal;

void main()
{
    int i = gl_VertexID % u_water_n, j = gl_VertexID / u_water_n;
    int il = max(i - 1, 0), ir = min(i + 1, u_water_n - 1), jd = max(j - 1, 0), ju = min(j + 1, u_water_n - 1);
    float dhdx = (height_at(ivec2(ir, j)) - height_at(ivec2(il, j))) / (float(ir - il) * u_water_dx);
    float dhdz = (height_at(ivec2(i, ju)) - height_at(ivec2(i, jd))) / (float(ju - jd) * u_water_dx);
    v_world_pos = vec3(-u_water_half + float(i) * u_water_dx, height_at(ivec2(i, j)), -u_water_half + float(j) * u_water_dx);
    v_world_normal = vec3(-dhdx, 1.0, -dhdz);
    gl_Position = u_view_proj * vec4(v_world_pos, 1.0);
}
