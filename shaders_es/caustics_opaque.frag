// SPDX-License-Identifier: MIT
// caustics_opaque.frag - an opaque object lit by the frame's light (the
// caustics stage, render/caustics.c; used instead of opaque.frag only in a
// frame with a light): colour = albedo * irradiance (common/opaque_lit.glsl),
// as the receiver plane (caustics_receiver.frag); in the view and in the
// dynamic environments (render/composite.c: with opaque_paraboloid.vert
// under SNELL_PARABOLOID_VIEW).
precision highp float;
precision highp sampler2D;
precision highp sampler2DShadow;

#include "common/output.glsl"
#include "common/opaque_lit.glsl"
#include "common/paraboloid_view.glsl"

in highp vec3 v_world_pos;
in vec3 v_world_normal;

#include "common/view.glsl"
uniform vec3 u_color;        // albedo

void main()
{
    snell_paraboloid_clip();
    highp vec3 p = v_world_pos;
    snell_write_path(u_color * snell_lit_irradiance(p, normalize(v_world_normal)), snell_view_vec(p), false);
}
