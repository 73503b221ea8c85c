// water_surface.vert - the water's height field as a grid of nodes (one vertex
// per node, gl_VertexID = j * n + i, no vertex attributes): the world
// position (x, h, z) and the seed's per-node normal (-dh/dx, 1, -dh/dz) from
// central differences, one-sided at the walls ("CLAMP"), left unnormalised so
// the fragment stage interpolates it per pixel as the reference does.
// Heights come from an R32F texture (CPU simulation) or straight from the
// GPU simulation's RG32UI state (SNELL_WATER_STATE_UINT).
precision highp float;
precision highp int;

#ifdef SNELL_WATER_STATE_UINT
precision highp usampler2D;
uniform usampler2D u_heights;
float height_at(ivec2 p)
{
    return uintBitsToFloat(texelFetch(u_heights, p, 0).r);
}
#else
precision highp sampler2D;
uniform sampler2D u_heights;
float height_at(ivec2 p)
{
    return texelFetch(u_heights, p, 0).r;
}
#endif

uniform int u_n;
uniform float u_half, u_dx;
uniform mat4 u_view_proj;

out vec3 v_world_pos;
out vec3 v_world_normal;

void main()
{
    int i = gl_VertexID % u_n, j = gl_VertexID / u_n;
    int il = max(i - 1, 0), ir = min(i + 1, u_n - 1), jd = max(j - 1, 0), ju = min(j + 1, u_n - 1);
    float dhdx = (height_at(ivec2(ir, j)) - height_at(ivec2(il, j))) / (float(ir - il) * u_dx);
    float dhdz = (height_at(ivec2(i, ju)) - height_at(ivec2(i, jd))) / (float(ju - jd) * u_dx);
    v_world_pos = vec3(-u_half + float(i) * u_dx, height_at(ivec2(i, j)), -u_half + float(j) * u_dx);
    v_world_normal = vec3(-dhdx, 1.0, -dhdz);
    gl_Position = u_view_proj * vec4(v_world_pos, 1.0);
}
