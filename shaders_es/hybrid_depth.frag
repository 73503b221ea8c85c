// SPDX-License-Identifier: MIT
// hybrid_depth.frag - writes an object's front depth back from the G-buffer
// (common/surface.glsl) after the hybrid's screen-space passes moved its
// trusted pixels' depth to the far plane (methods/hybrid.c).
precision highp float;
#define SNELL_SCREEN_SPACE 1
#define SNELL_SCREEN_WRITES_DEPTH 1
#include "common/pack.glsl"
#include "common/surface.glsl"

void main()
{
    highp vec3 pos, normal;
    snell_surface(pos, normal);
}
