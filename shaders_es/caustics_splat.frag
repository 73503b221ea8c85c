// SPDX-License-Identifier: MIT
// caustics_splat.frag - a photon's share for this texel of its 4 x 4 point
// (caustics_photon.vert): a tent of half-width 2 texels along each axis,
// (1 - |dx| / 2) (1 - |dz| / 2) / 4 at the texel centres within 2 texels of
// the photon, which sum to 1, added into the receiver's light map. Wider
// than a 2 x 2 bilinear share so that the regular photon grid leaves no moire
// where photons are sparse, at the price of a focus one texel wider
// (bench/notes/code.md, "caustics_splat.frag").
precision highp float;

in vec4 v_flux;
layout(location = 0) out vec4 o_color;

void main()
{
    vec2 d = abs(gl_PointCoord * 2.0 - 1.0); // 0..1 = 0..2 texels from the photon
    o_color = v_flux * (1.0 - d.x) * (1.0 - d.y) * 0.25;
#ifdef SNELL_LIGHT_RANGE
    // An RGB10_A2 map (no float target, core/glstate.h): the share in steps
    // of 1/1023 of the range, rounded up with the probability of its
    // fraction (hashed from the photon's place in its point and the texel),
    // so that the blend's many rounded additions sum right on average
    // (+ 0.25 step: the same whole step whether the GL rounds or truncates;
    // highp: a fragment shader's ints are mediump, 16 bits, by default).
    highp uvec2 k = floatBitsToUint(gl_PointCoord) ^ uvec2(gl_FragCoord.xy) * 2654435761u;
    highp uint h = (k.x ^ k.y * 2246822519u) * 3266489917u;
    h ^= h >> 15;
    o_color = (floor(o_color * (1023.0 / SNELL_LIGHT_RANGE) + float(h >> 8) / 16777216.0) + 0.25) / 1023.0;
#endif
}
