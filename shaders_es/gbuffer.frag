// SPDX-License-Identifier: MIT
// gbuffer.frag - the screen-space stage's geometry pass (render/gbuffer.c):
// the glass's front surface with a trivial shader, so that the rasteriser's
// partly filled blocks of tiny triangles cost little; the kernels shade
// later, once per covered pixel. Writes the unit world normal octahedrally in
// 16+16 bits of one RGBA8 target (pack.glsl; quantisation below 2e-3 degrees)
// and the window depth in 24 bits + the object id in 8 of another, so the
// kernels need no depth texture: the depth buffer itself is the target's,
// which then skips the uncovered pixels of the kernels' full-screen pass.
precision highp float;

#include "common/pack.glsl"

in highp vec3 v_world_pos;
in highp vec3 v_world_normal;

uniform int u_gid;

layout(location = 0) out highp vec4 o_normal;
layout(location = 1) out highp vec4 o_depth_id;
#ifdef SNELL_GBUFFER_AUX
// the aux target: a method's per-vertex scalar in [0,1] (snell__object.vao), 16 bits in rg
in highp float v_aux;
layout(location = 2) out highp vec4 o_aux;
#endif

void main()
{
    highp uint d = uint(clamp(gl_FragCoord.z, 0.0, 1.0) * 16777215.0 + 0.5);
    highp uvec4 b = uvec4(d >> 16u, (d >> 8u) & 255u, d & 255u, uint(u_gid));
    o_normal = snell_pack_dir_rgba8(normalize(v_world_normal));
    // (b + 0.25) / 255: stored as b whether the driver rounds or truncates (pack.glsl)
    o_depth_id = (vec4(b) + 0.25) / 255.0;
#ifdef SNELL_GBUFFER_AUX
    o_aux = vec4(snell_pack_unorm16(v_aux), 0.0, 0.0);
#endif
}
