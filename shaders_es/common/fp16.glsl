// SPDX-License-Identifier: MIT
// fp16.glsl - mediump study. SNELL_MEDIUMP marks what a GPU with real fp16
// holds at mediump; the precision policy makes it highp on llvmpipe
// (core/program.c). SNELL_FP16_EMULATION rounds what crosses snell_h() to IEEE
// half (packHalf2x16), whatever the driver; without it snell_h(x) is x. Only
// those values are rounded, so this is a lower bound on the real fp16 error.
// More: docs/ARCHITECTURE.md, "Design notes by file".
#ifdef SNELL_FP16_EMULATION
float snell_h(float x)
{
    return unpackHalf2x16(packHalf2x16(vec2(x, 0.0))).x;
}
vec2 snell_h(vec2 v)
{
    return unpackHalf2x16(packHalf2x16(v));
}
vec3 snell_h(vec3 v)
{
    return vec3(snell_h(v.xy), snell_h(v.z));
}
vec4 snell_h(vec4 v)
{
    return vec4(snell_h(v.xy), snell_h(v.zw));
}
#else
#define snell_h(x) (x)
#endif
