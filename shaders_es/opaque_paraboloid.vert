// SPDX-License-Identifier: MIT
// opaque_paraboloid.vert - an opaque object drawn straight into one map of a
// dynamic environment's dual-paraboloid pair (render/env_dynamic.c): each
// vertex goes to the texel of its direction from the glass centre
// (common/env.glsl's parameterisation, continued past the rim), depth its
// linear distance. The rasteriser joins vertices by straight lines where the
// projection bends them, so a triangle's error grows with the angle it spans
// seen from the centre (measured in bench/BENCHMARKS.md).
precision highp float;

#include "common/env.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;          // object -> world
uniform mat3 u_normal_matrix;  // inverse transpose of u_model's 3x3
uniform vec3 u_centre;         // the glass centre, world space
uniform float u_layer;         // 0: the +Z map, 1: the -Z map
uniform float u_size;          // the maps' side, texels
uniform vec2 u_depth_range;    // near, far distance

out vec3 v_world_pos;
out vec3 v_world_normal;
out float v_hemisphere;        // the direction's z towards the map's own axis

void main()
{
    vec4 wp = u_model * vec4(a_position, 1.0);
    vec3 p = wp.xyz - u_centre;
    float dist = length(p);
    vec3 d = p / max(dist, 1e-20);
    float z = u_layer > 0.5 ? -d.z : d.z;
    float scale = (u_size - 2.0 * SNELL_DP_MARGIN) / u_size; // NDC per unit of st
    // behind the map's hemisphere st grows without bound: held finite so the
    // triangle stays drawable; its fragments there are discarded (opaque.frag)
    vec2 st = d.xy / max(1.0 + z, 0.05);
    v_world_pos = wp.xyz;
    v_world_normal = u_normal_matrix * a_normal;
    v_hemisphere = z;
    gl_Position = vec4(st * scale, 2.0 * (dist - u_depth_range.x) / (u_depth_range.y - u_depth_range.x) - 1.0, 1.0);
}
