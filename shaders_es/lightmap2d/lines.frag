// SPDX-License-Identifier: MIT
// lines.frag - additive line fragment. With a fixed-point target (u_quant > 0,
// the fallback without float colour buffers) the value is rounded stochastically
// to a multiple of 1/u_quant so the blended sum stays unbiased (values far below
// one step would otherwise all round to zero: thesis Abb. 6.17).
precision highp float;

in vec3 v_color;
flat in highp uint v_seed;

uniform float u_quant;  // 0: float target; else 2^bits - 1
uniform highp uint u_frame;

out vec4 o_color;

highp uint hash_u(highp uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

void main()
{
    vec3 c = v_color;
    if (u_quant > 0.0) {
        highp uvec2 p = uvec2(gl_FragCoord.xy);
        highp uint h = hash_u(p.x * 0x9e3779b1u ^ hash_u(p.y ^ hash_u(v_seed ^ u_frame * 0x85ebca6bu)));
        float r = float(h >> 8) * (1.0 / 16777216.0);
        c = floor(c * u_quant + r) / u_quant;
    }
    o_color = vec4(c, 0.0);
}
