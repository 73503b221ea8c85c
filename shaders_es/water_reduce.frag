// SPDX-License-Identifier: MIT
// water_reduce.frag - the settle check of the GPU water simulation: each
// texel holds max |height - mean| and max |velocity| over a 16 x 16 block of
// nodes, read back by snell__water_gpu_deviation (a 32 x 32 read for 512^2).
precision highp float;
precision highp int;
precision highp usampler2D;

uniform usampler2D u_state;
uniform int u_n;
uniform float u_mean;

layout(location = 0) out uvec4 o_max;

void main()
{
    ivec2 base = ivec2(gl_FragCoord.xy) * 16;
    float mh = 0.0, mv = 0.0;
    for (int j = 0; j < 16; j++)
        for (int i = 0; i < 16; i++) {
            ivec2 p = base + ivec2(i, j);
            if (p.x < u_n && p.y < u_n) {
                uvec2 s = texelFetch(u_state, p, 0).rg;
                mh = max(mh, abs(uintBitsToFloat(s.r) - u_mean));
                mv = max(mv, abs(uintBitsToFloat(s.g)));
            }
        }
    o_max = uvec4(floatBitsToUint(mh), floatBitsToUint(mv), 0u, 0u);
}
