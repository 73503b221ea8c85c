// SPDX-License-Identifier: MIT
// caustics_receiver.frag - the receiver plane in the view: albedo times its
// light map (direct light where unshadowed plus the caustics,
// common/receiver.glsl, which the glass reads too), linear.
precision highp float;
precision highp sampler2D;

#include "common/output.glsl"
#include "common/receiver.glsl"

#include "common/view.glsl"
in vec2 v_ndc;
in highp vec3 v_world_pos;

void main()
{
    snell_write_path(u_plane_albedo * receiver_irradiance(v_ndc * 0.5 + 0.5), snell_view_vec(v_world_pos), false);
}
