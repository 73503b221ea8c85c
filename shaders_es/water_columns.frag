// SPDX-License-Identifier: MIT
// water_columns.frag - the opaque objects seen from above the water's box
// (water/water_caustics.c draw_columns): only their depth is kept, the
// highest and the lowest surface over each texel of the floor.
precision mediump float;

layout(location = 0) out vec4 o_color;

void main()
{
    o_color = vec4(1.0);
}
