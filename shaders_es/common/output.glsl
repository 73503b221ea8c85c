// SPDX-License-Identifier: MIT
// output.glsl - what a glass kernel (and the skybox) writes: the colour, or
// for error measurement the final direction of the light path, either as
// floats (RGBA32F target) or packed octahedrally into RGBA8 (pack.glsl).
#include "common/pack.glsl"

#if defined(SNELL_OUTPUT_EXIT_DIR_FLOAT) || defined(SNELL_OUTPUT_EXIT_DIR_PACKED)
layout(location = 0) out highp vec4 o_color;
#else
layout(location = 0) out vec4 o_color;
#endif

void snell_write(vec3 color, highp vec3 exit_dir)
{
#if defined(SNELL_OUTPUT_EXIT_DIR_FLOAT)
    o_color = vec4(normalize(exit_dir), 1.0);
#elif defined(SNELL_OUTPUT_EXIT_DIR_PACKED)
    o_color = snell_pack_dir_rgba8(normalize(exit_dir));
#else
    o_color = vec4(color, 1.0);
#endif
}
