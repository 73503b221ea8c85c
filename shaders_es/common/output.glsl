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

// SNELL_PREMULTIPLIED (a glass kernel's variant, render/premultiplied.c):
// its colour is linear in the environment it looks up, C = A + W env, so
// two runs of the kernel's main, with the environment 0 and then 1
// (common/env.glsl), give A (what the glass shows of everything else) and
// W (the environment's weight: its transmittance and its reflectance of the
// environment). It writes A premultiplied, alpha 1 - mean(W): composited
// over what lies behind the target, that stands in for the environment.
// The kernel's own main is renamed for the wrapper to call.
#ifdef SNELL_PREMULTIPLIED
void snell_kernel_main();
void main()
{
    snell_env_level = 0.0;
    snell_kernel_main();
    vec4 own = o_color;
    snell_env_level = 1.0;
    snell_kernel_main();
    vec3 w = o_color.rgb - own.rgb;
    o_color = vec4(own.rgb, clamp(1.0 - (w.r + w.g + w.b) / 3.0, 0.0, 1.0));
}
#define main snell_kernel_main
#endif

// glass: whether the light path went through a refracting surface. The exit
// direction cannot tell (an unbent path leaves along the view ray, as the
// background does), so it is written beside it: the float target's alpha
// (0 where not; exact.frag's fallback mark is nonzero too), the packed
// target's coverage bit.
void snell_write_path(vec3 color, highp vec3 exit_dir, bool glass)
{
#if defined(SNELL_OUTPUT_EXIT_DIR_FLOAT)
    o_color = vec4(normalize(exit_dir), glass ? 1.0 : 0.0);
#elif defined(SNELL_OUTPUT_EXIT_DIR_PACKED)
    o_color = snell_pack_exit_rgba8(normalize(exit_dir), glass);
#else
    o_color = vec4(color, 1.0);
#endif
}

// A refracting surface's kernel (glass, the water's surface).
void snell_write(vec3 color, highp vec3 exit_dir)
{
    snell_write_path(color, exit_dir, true);
}
