// SPDX-License-Identifier: MIT
// water_drop.frag - a drop on the GPU water state (snell_water_drop): every
// node within u_drop.z of the point u_drop.xy moves by
// amplitude * (1 + cos(pi r / radius)) / 2 (snell__water_bell).
precision highp float;
precision highp int;
precision highp usampler2D;

uniform usampler2D u_state;
uniform float u_half;     // container half width
uniform float u_dx;       // node spacing
uniform vec4 u_drop;      // x, z, radius, amplitude (world units)

layout(location = 0) out uvec4 o_state;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    uvec2 s = texelFetch(u_state, p, 0).rg;
    float h = uintBitsToFloat(s.r);
    float px = -u_half + float(p.x) * u_dx, pz = -u_half + float(p.y) * u_dx;
    float r = sqrt((px - u_drop.x) * (px - u_drop.x) + (pz - u_drop.y) * (pz - u_drop.y));
    if (r < u_drop.z) h += u_drop.w * 0.5 * (1.0 + cos(3.14159265 * r / u_drop.z));
    o_state = uvec4(floatBitsToUint(h), s.g, 0u, 0u);
}
