// SPDX-License-Identifier: MIT
// hybrid.frag - the cubemap's search (cubemap.frag, unchanged) with a doubt
// test per pixel, for the hybrid method (methods/hybrid.c). The cube holds
// one surface per direction from its centre (Unger 4.1); its answer is
// doubted where the front surface or the exit found lies off that surface
// by more than u_doubt (hidden from the centre, or the search did not
// converge), or the path leaves inward (total reflections past the cap).
// The test sits on the trace's call of snell_disp_exit (renamed below).
// SNELL_DOUBT_MODE (methods/cubemap.h): 1 a doubted pixel is discarded;
// 2 its depth goes to the near plane; 3 it is magenta.
precision highp float;
#define SNELL_KERNEL_MAIN 1 // main below
#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/surface.glsl"
#include "common/beyond.glsl"
#include "common/dispersion.glsl"

bool g_doubted = false;         // over a pixel's traces (dispersion, premultiplied)
vec3 hybrid_exit(highp vec3 exit_p, inout highp vec3 dir);
#define snell_disp_exit(p, d) hybrid_exit(p, d)
#include "cubemap.frag"
#undef snell_disp_exit

uniform float u_doubt;          // threshold, object units

vec3 hybrid_exit(highp vec3 exit_p, inout highp vec3 dir)
{
    highp vec3 world_pos, world_normal;
    snell_surface(world_pos, world_normal);
    highp vec3 p_in = (u_inv_model * vec4(world_pos, 1.0)).xyz - u_centre;
    highp vec3 p = (u_inv_model * vec4(exit_p, 1.0)).xyz - u_centre;
    float off = max(abs(fetch_dist(p_in) - length(p_in)), abs(fetch_dist(p) - length(p)));
    bool leaves = dot(fetch_normal(p), mat3(u_inv_model) * dir) > 0.0;
    g_doubted = g_doubted || off > u_doubt || !leaves;
#if SNELL_DOUBT_MODE == 1
    if (g_doubted) discard;
#endif
    return snell_disp_exit(exit_p, dir);
}

void main()
{
    highp vec3 exit_dir;
    vec3 color = snell_disp_trace(exit_dir);
#if SNELL_DOUBT_MODE == 2
    // written on every path: where it is not, a fragment's depth is undefined (GLSL ES 3.00 7.2)
    gl_FragDepth = g_doubted ? 0.0 : gl_FragCoord.z;
#endif
#if SNELL_DOUBT_MODE == 3
    color = g_doubted ? vec3(1.0, 0.0, 1.0) : color;
#endif
    snell_write(color, exit_dir);
}
