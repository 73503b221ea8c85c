// SPDX-License-Identifier: MIT
// water_wall.frag - the container's tiles where the view sees them directly
// (outside, and inside above the water); exit-direction output: the view ray.
precision highp float;

#include "common/output.glsl"
#include "common/water_tiles.glsl"

in vec3 v_world_pos;
flat in int v_face;

#include "common/view.glsl"

void main()
{
    snell_write_path(water_tile(v_face, v_world_pos), snell_view_vec(v_world_pos), false);
}
