// SPDX-License-Identifier: MIT
// refine_mean.frag - the refine stage's running mean (render/refine.c): the
// mean of n frames from that of n - 1 and frame n, weight 1 / n (1: the
// frame alone, the old mean unread); weight 0 writes the mean out.
precision highp float;

uniform highp sampler2D u_frame;   // this frame, RGBA8
uniform highp sampler2D u_acc;     // the mean so far, RGBA32F
uniform float u_weight;

out vec4 o_color;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 x = texelFetch(u_frame, p, 0), mean = texelFetch(u_acc, p, 0);
    o_color = u_weight >= 1.0 ? x : mean + (x - mean) * u_weight;
}
