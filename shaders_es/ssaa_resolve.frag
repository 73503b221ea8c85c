// SPDX-License-Identifier: MIT
// ssaa_resolve.frag - supersampling resolve (render/ssaa.c): each output
// pixel is the mean of its SNELL_SSAA x SNELL_SSAA block of the frame rendered
// that many times larger, a box filter over the pixel's area, which is what
// the reference tracer's samples = S computes (snell_ref_params). The block
// size is a compile-time constant (docs/ARCHITECTURE.md "Conventions").
precision highp float;

uniform highp sampler2D u_frame;

out vec4 o_color;

void main()
{
    ivec2 base = ivec2(gl_FragCoord.xy) * SNELL_SSAA;
    vec4 sum = vec4(0.0);
    for (int j = 0; j < SNELL_SSAA; j++)
        for (int i = 0; i < SNELL_SSAA; i++) sum += texelFetch(u_frame, base + ivec2(i, j), 0);
    o_color = sum / float(SNELL_SSAA * SNELL_SSAA);
}
