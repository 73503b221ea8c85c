// SPDX-License-Identifier: MIT
// pack.glsl - GLSL twin of src/core/pack.h: octahedral unit vectors and 16-bit
// values split over two 8-bit channels of an RGBA8 target. Needs highp for
// the 16-bit split.

highp vec2 snell_oct_encode(highp vec3 n)
{
    highp vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    if (n.z < 0.0) {
        highp vec2 s = vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
        p = (1.0 - abs(p.yx)) * s;
    }
    return p;
}

highp vec3 snell_oct_decode(highp vec2 e)
{
    highp vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) {
        highp vec2 s = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
        n.xy = (1.0 - abs(n.yx)) * s;
    }
    return normalize(n);
}

// v in [0,1] -> (high byte, low byte) for two UNORM8 channels. Each byte b is
// written as (b + 0.25) / 255 so that it is stored as b whether the driver
// rounds or truncates in the float -> UNORM8 conversion (llvmpipe truncates
// b / 255 * 255 = b - ulp to b - 1, which would corrupt the high byte).
highp vec2 snell_pack_unorm16(highp float v)
{
    highp float q = floor(clamp(v, 0.0, 1.0) * 65535.0 + 0.5);
    highp float hi = floor(q / 256.0);
    return (vec2(hi, q - hi * 256.0) + 0.25) / 255.0;
}

highp float snell_unpack_unorm16(highp vec2 hl)
{
    return (floor(hl.x * 255.0 + 0.5) * 256.0 + floor(hl.y * 255.0 + 0.5)) / 65535.0;
}

highp vec4 snell_pack_dir_rgba8(highp vec3 n)
{
    highp vec2 e = snell_oct_encode(n) * 0.5 + 0.5;
    return vec4(snell_pack_unorm16(e.x), snell_pack_unorm16(e.y));
}

// An exit direction with a coverage bit (pack.h twin): octahedral x in 16
// bits, y in 15 and the low bit of y's word set where the path went through
// glass, since an unbent path's direction is the background's own.
highp vec4 snell_pack_exit_rgba8(highp vec3 n, bool glass)
{
    highp vec2 e = snell_oct_encode(n) * 0.5 + 0.5;
    highp float q = floor(clamp(e.y, 0.0, 1.0) * 32767.0 + 0.5) * 2.0 + (glass ? 1.0 : 0.0);
    highp float hi = floor(q / 256.0);
    return vec4(snell_pack_unorm16(e.x), (vec2(hi, q - hi * 256.0) + 0.25) / 255.0);
}

// Normal + distance texels of the cubemap method (src/core/pack.h twin, ndcube.c).
// d = distance from the cubemap centre / mesh radius, in [0,1].
highp vec4 snell_pack_ndist_plain(highp vec3 n, highp float d)
{
    return vec4(n * 0.5 + 0.5, clamp(d, 0.0, 1.0));
}

highp vec4 snell_pack_ndist_oct(highp vec3 n, highp float d)
{
    return vec4(snell_oct_encode(n) * 0.5 + 0.5, snell_pack_unorm16(d));
}

// Decoders return the unit normal in xyz and d in w.
highp vec4 snell_unpack_ndist_plain(highp vec4 t)
{
    return vec4(normalize(t.rgb * 2.0 - 1.0), t.a);
}

highp vec4 snell_unpack_ndist_oct(highp vec4 t)
{
    return vec4(snell_oct_decode(t.rg * 2.0 - 1.0), snell_unpack_unorm16(t.ba));
}
