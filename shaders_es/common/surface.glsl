// SPDX-License-Identifier: MIT
// surface.glsl - the front surface a glass kernel shades: world position and
// (unnormalised) normal. Forward: the interpolated vertex outputs of
// object.vert. SNELL_SCREEN_SPACE: fetched from the G-buffer that the
// renderer's screen-space stage drew (render/gbuffer.c: RGBA8 with the normal
// octahedral in 16+16 bits, RGBA8 with the depth in 24 bits and the object id
// in 8), on a full-screen triangle at the far plane, scissored to the object,
// that the depth test (GREATER) limits to covered pixels; pixels of other
// objects are discarded.
#ifdef SNELL_SCREEN_SPACE
uniform highp sampler2D u_gnormal;   // octahedral 16+16 bits
uniform highp sampler2D u_gdepth_id; // window depth 24 bits, object id 8 bits
uniform highp mat4 u_inv_view_proj;
uniform highp vec2 u_inv_size;       // 1 / target size in pixels
uniform int u_gid;                   // this object's id in the G-buffer (1..255)

// frag: gl_FragCoord.xy (snell_surface), or it plus an opaque zero, which
// makes the compiler read and decode again rather than keep the first
// read's values live (exact.frag after its walk).
void snell_surface_frag(highp vec2 frag, out highp vec3 pos, out highp vec3 normal)
{
    ivec2 px = ivec2(frag);
    highp uvec4 b = uvec4(texelFetch(u_gdepth_id, px, 0) * 255.0 + 0.5);
    if (int(b.a) != u_gid) discard;
    highp float depth = float((b.r << 16u) | (b.g << 8u) | b.b) / 16777215.0;
    highp vec4 ndc = vec4(frag * u_inv_size * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    highp vec4 w = u_inv_view_proj * ndc;
    highp vec4 g = texelFetch(u_gnormal, px, 0);
    pos = w.xyz / w.w;
    normal = snell_oct_decode(vec2(snell_unpack_unorm16(g.xy), snell_unpack_unorm16(g.zw)) * 2.0 - 1.0);
#ifdef SNELL_SCREEN_WRITES_DEPTH
    // the G-buffer had a depth buffer of its own (a target whose depth buffer
    // the renderer cannot attach): the surface's depth goes to the target here
    gl_FragDepth = depth;
#endif
}
void snell_surface(out highp vec3 pos, out highp vec3 normal)
{
    snell_surface_frag(gl_FragCoord.xy, pos, normal);
}
#else
in highp vec3 v_world_pos;
// highp: the normal matrix scales normals by 1/scale; at mediump (fp16 on llvmpipe)
// |n|^2 overflows above 256 (mesh scale 1e-3) and is subnormal at scale 1e3.
in highp vec3 v_world_normal;

void snell_surface(out highp vec3 pos, out highp vec3 normal)
{
    pos = v_world_pos;
    normal = v_world_normal;
}
#define snell_surface_frag(frag, pos, normal) snell_surface(pos, normal)
#endif

// Distance along unit d from p, inside sphere (world centre, radius: the
// object's u_bsphere), to where it leaves the sphere; 0 from outside it. The
// path length inside the glass where the kernel does not trace the exit
// (Beer-Lambert's estimate: single.frag, glass_scale.frag's fallback, exact's
// fallback pixels) and oliveira's search range.
highp float snell_sphere_exit(highp vec3 p, highp vec3 d, highp vec4 sphere)
{
    highp vec3 oc = p - sphere.xyz;
    highp float b = dot(oc, d), c = dot(oc, oc) - sphere.w * sphere.w;
    return max(-b + sqrt(max(b * b - c, 0.0)), 0.0);
}
