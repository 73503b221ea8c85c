// SPDX-License-Identifier: MIT
// hybrid.frag - the cubemap's search (cubemap.frag) with a doubt test per
// pixel, for the hybrid method (methods/hybrid.c), which draws exact where
// the cubemap doubts. The cubemap holds one surface per direction from its
// centre (Unger 4.1); its answer is doubted where the front surface or the
// exit found lies off that surface (hidden from the centre, or the search
// did not converge), or the path did not leave the object (total internal
// reflections past the cap). SNELL_DOUBT_MODE (methods/cubemap.h): 1 a
// doubted pixel is discarded (its depth unwritten); 2 its depth goes to
// the near plane (screen space on the renderer's own depth: exact's pass
// then runs where the depth is 0); 3 a doubted pixel is magenta.
precision highp float;
vec3 snell_doubt(vec3 c, highp vec3 world_pos, highp vec3 p, vec3 dir);
#include "cubemap.frag"

uniform float u_doubt;           // threshold, object units
bool g_doubted = false;

vec3 snell_doubt(vec3 c, highp vec3 world_pos, highp vec3 p, vec3 dir)
{
    highp vec3 p_in = (u_inv_model * vec4(world_pos, 1.0)).xyz - u_centre;
    float off = max(abs(fetch_dist(p_in) - length(p_in)), abs(fetch_dist(p) - length(p)));
    bool leaves = dot(fetch_normal(p), mat3(u_inv_model) * dir) > 0.0;
    bool doubted = off > u_doubt || !leaves;
#if SNELL_DOUBT_MODE == 3
    return doubted ? vec3(1.0, 0.0, 1.0) : c;
#elif SNELL_DOUBT_MODE == 2
    g_doubted = g_doubted || doubted;   // over a pixel's traces (dispersion, premultiplied)
    if (g_doubted) gl_FragDepth = 0.0;
    return c;
#else
    if (doubted) discard;
    return c;
#endif
}
