// SPDX-License-Identifier: MIT
// peel_depth.glsl - the test of a depth peel (Everitt; Wang 2014 3.4) shared by
// the passes that peel: depth_peel.frag (the peel kernel, the scene layers)
// and layered_bake.frag (the layered method's cube layers). A depth in [0,1]
// is compared as 24 bits, the value the previous pass stored in RGBA8 (r, g, b
// its bytes, a the flag: 0 = empty), so a surface is never kept twice (two
// surfaces closer than 2^-24 of the range merge).

highp uint snell_peel_q(highp float z)
{
    return uint(clamp(z, 0.0, 1.0) * 16777215.0 + 0.5);
}

// Whether a fragment of depth q lies behind the previous layer at its pixel
// (prev: that layer's depth + flag texture): it is peeled only then.
bool snell_peel_behind(highp sampler2D prev, highp uint q)
{
    highp uvec4 p = uvec4(texelFetch(prev, ivec2(gl_FragCoord.xy), 0) * 255.0 + 0.5);
    // an empty previous layer: nothing lies behind it either
    return p.a != 0u && q > ((p.r << 16u) | (p.g << 8u) | p.b);
}

// The texel the next pass tests against: q's bytes and the flag.
highp vec4 snell_peel_texel(highp uint q, highp uint flag)
{
    highp uvec4 b = uvec4(q >> 16u, (q >> 8u) & 255u, q & 255u, flag);
    // (b + 0.25) / 255: stored as b whether the driver rounds or truncates (pack.glsl)
    return (vec4(b) + 0.25) / 255.0;
}
