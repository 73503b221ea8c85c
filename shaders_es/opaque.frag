// SPDX-License-Identifier: MIT
// opaque.frag - diffuse albedo lit by a sky-like light from +Y (half-Lambert,
// so no side is black). In exit-direction output the view ray is written, as
// for the background: an opaque pixel has no refracted path.
precision SNELL_MEDIUMP float; // the context's policy (core/program.c)

#include "common/output.glsl"
#include "common/paraboloid_view.glsl"

in highp vec3 v_world_pos;
in vec3 v_world_normal;

#include "common/view.glsl"
uniform vec3 u_color;

void main()
{
    snell_paraboloid_clip();
    vec3 n = normalize(v_world_normal);
    float l = 0.5 + 0.5 * dot(n, normalize(vec3(0.3, 1.0, 0.2)));
    snell_write_path(u_color * (0.25 + 0.75 * l), snell_view_vec(v_world_pos), false);
}
