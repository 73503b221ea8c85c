// SPDX-License-Identifier: MIT
// ndcube_bake.frag - writes the normal and the distance to the centre of the
// farthest surface (depth test GREATER, no culling; Unger 4.1) packed into
// RGBA8 by common/pack.glsl. Depth is the Euclidean distance / radius, so the
// test keeps exactly the farthest point along each texel's direction with a
// uniform 24-bit precision (a perspective depth would crowd it near the centre).
precision highp float;

#include "common/pack.glsl"

in vec3 v_rel;
in vec3 v_normal;

uniform float u_inv_radius;   // 1 / radius (the largest distance of a vertex)

layout(location = 0) out vec4 o_texel;

void main()
{
    float d = clamp(length(v_rel) * u_inv_radius, 0.0, 1.0);
    vec3 n = normalize(v_normal);
    gl_FragDepth = d;
#ifdef SNELL_NDCUBE_OCT
    o_texel = snell_pack_ndist_oct(n, d);
#else
    o_texel = snell_pack_ndist_plain(n, d);
#endif
}
