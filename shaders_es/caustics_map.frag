// SPDX-License-Identifier: MIT
// caustics_map.frag - a glass object seen from the light (render/caustics.c):
// its world normal (unit, packed n * 0.5 + 0.5 into RGB10_A2, alpha 1 where
// covered); the light-space depth goes to the depth texture. Drawn twice:
// the nearest surfaces (where photons enter) and the farthest (where they
// leave a convex object). Used for the shadow map too (colour masked off).
precision highp float;

in highp vec3 v_world_pos;
in highp vec3 v_world_normal;
layout(location = 0) out vec4 o_normal;

void main()
{
    o_normal = vec4(normalize(v_world_normal) * 0.5 + 0.5, 1.0);
}
