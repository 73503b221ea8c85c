// SPDX-License-Identifier: MIT
// fp16.glsl - mediump study. Shaders declare what a GPU with real
// fp16 holds at mediump as SNELL_MEDIUMP, which the context's precision policy
// makes highp on llvmpipe (it emulates fp16 mediump in software, slower than
// highp; core/program.c). A build with SNELL_FP16_EMULATION sets the policy
// to mediump and also rounds chosen intermediates to IEEE half precision
// (10-bit mantissa, max 65504) through packHalf2x16 / unpackHalf2x16, as a
// GPU with true fp16 mediump would hold them, whatever the driver. Kernels
// wrap values that are mediump on such hardware with snell_h(); without the
// flag snell_h(x) is x and the shader is unchanged. Only what crosses a
// snell_h() is rounded: arithmetic inside a function (e.g. the optics chunk)
// stays fp32, so this is a lower bound on the real fp16 error.
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
