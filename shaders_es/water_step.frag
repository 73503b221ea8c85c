// SPDX-License-Identifier: MIT
// water_step.frag - one step of the water simulation on the GPU (Dachsbacher
// 2002; src/water/water_sim.c derives the scheme and its stability limit):
// per node the force from the eight neighbours (diagonals times 1/sqrt 2,
// neighbours beyond the walls left out), into velocity, then into height.
// The state is an RG32UI texture holding the fp32 bits of (height, velocity):
// GLES 3.0 renders to 32-bit integer targets without extensions, float
// targets need GL_EXT_color_buffer_float, and RGBA8 packing would round the
// state every step. Term for term in the order of snell__water_cpu_step.
precision highp float;
precision highp int;
precision highp usampler2D;

uniform usampler2D u_state;
uniform int u_n;          // nodes per side
uniform float u_k;        // (c dt / dx)^2 / dt
uniform float u_dt;
uniform float u_damp;     // exp(-damping dt)

layout(location = 0) out uvec4 o_state;

float height_at(ivec2 p)
{
    return uintBitsToFloat(texelFetch(u_state, p, 0).r);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    uvec2 s = texelFetch(u_state, p, 0).rg;
    float c = uintBitsToFloat(s.r), v = uintBitsToFloat(s.g), fa = 0.0, fd = 0.0;
    bool l = p.x > 0, r = p.x + 1 < u_n, up = p.y > 0, dn = p.y + 1 < u_n;
    if (l) fa += height_at(p + ivec2(-1, 0)) - c;
    if (r) fa += height_at(p + ivec2(1, 0)) - c;
    if (up) fa += height_at(p + ivec2(0, -1)) - c;
    if (dn) fa += height_at(p + ivec2(0, 1)) - c;
    if (up && l) fd += height_at(p + ivec2(-1, -1)) - c;
    if (up && r) fd += height_at(p + ivec2(1, -1)) - c;
    if (dn && l) fd += height_at(p + ivec2(-1, 1)) - c;
    if (dn && r) fd += height_at(p + ivec2(1, 1)) - c;
    v = (v + u_k * (fa + 0.70710678118654752440 * fd)) * u_damp;
    c = c + u_dt * v;
    o_state = uvec4(floatBitsToUint(c), floatBitsToUint(v), 0u, 0u);
}
