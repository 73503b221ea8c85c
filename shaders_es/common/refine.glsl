// SPDX-License-Identifier: MIT
// refine.glsl - the refine stage's random numbers (render/refine.c): with
// SNELL_REFINE a kernel follows a Fresnel branch at random, one stream of
// numbers a pixel and sample (u_refine_seed), so the frames' mean converges
// to both branches' sum. PCG's hash (Jarzynski and Olano, JCGT 2020).
#ifndef SNELL_REFINE
#define SNELL_REFINE 0
#endif
#if SNELL_REFINE
uniform highp uint u_refine_seed;
highp uint g_refine_rng;

highp uint refine_hash(highp uint v)
{
    highp uint s = v * 747796405u + 2891336453u;
    highp uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (w >> 22u) ^ w;
}

void refine_seed()
{
    g_refine_rng = refine_hash(uint(gl_FragCoord.x) ^ refine_hash(uint(gl_FragCoord.y) ^ refine_hash(u_refine_seed)));
}

// uniform in [0, 1)
float refine_random()
{
    g_refine_rng = refine_hash(g_refine_rng);
    return float(g_refine_rng >> 8u) * (1.0 / 16777216.0);
}
#endif
