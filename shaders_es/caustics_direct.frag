// SPDX-License-Identifier: MIT
// caustics_direct.frag - the direct light on the receiver's light map: at
// each of a texel's 2 x 2 sample points the light's irradiance (directional:
// colour * cosine; spot: intensity * cosine / distance^2 inside its cone)
// where the shadow map (every glass and opaque object seen from the light)
// leaves it lit; alpha 0 (the photons' alpha counts only the light through glass).
precision highp float;
precision highp sampler2DShadow;

uniform sampler2DShadow u_shadow;
uniform mat4 u_shadow_vp;    // world -> the shadow map's clip space (orthographic)
uniform vec4 u_plane;        // y, centre x, centre z, extent
uniform vec3 u_color;        // the light's colour (directional: irradiance; spot: intensity)
uniform vec3 u_dir;          // directional: the unit direction it travels
uniform int u_spot;          // 1: a spot light at u_pos, axis u_axis, cone cosine u_cos_cone
uniform vec3 u_pos, u_axis;
uniform float u_cos_cone;
uniform float u_texel;       // the light map's texel side / extent (NDC units)
uniform float u_bias;        // depth bias, shadow clip units

layout(location = 0) out vec4 o_color;
in vec2 v_ndc;

void main()
{
    vec3 e = vec3(0.0);
    for (int k = 0; k < 4; k++) {
        vec2 o = (vec2(float(k & 1), float(k >> 1)) - 0.5) * 0.5 * u_texel;
        vec2 xz = u_plane.yz + (v_ndc + o) * u_plane.w;
        vec3 q = vec3(xz.x, u_plane.x, xz.y);
        vec3 ek = u_color * max(0.0, -u_dir.y);
        if (u_spot == 1) {
            vec3 l = q - u_pos;
            float d2 = dot(l, l);
            l *= inversesqrt(d2);
            ek = dot(l, u_axis) >= u_cos_cone ? u_color * max(0.0, -l.y) / d2 : vec3(0.0);
        }
        vec4 c = u_shadow_vp * vec4(q, 1.0);
        vec3 s = c.xyz / c.w * 0.5 + 0.5;
        e += ek * texture(u_shadow, vec3(s.xy, s.z - u_bias));
    }
    o_color = vec4(e * 0.25, 0.0);
#ifdef SNELL_LIGHT_RANGE
    // An RGB10_A2 map (core/glstate.h): in 1/1023 steps of the range, rounded
    // up with the probability of the fraction, as caustics_splat.frag's
    // photons are (rounding a region's one value the same way everywhere
    // would bias its mean by up to half a step)
    highp uint h = (uint(gl_FragCoord.x) * 2654435761u ^ uint(gl_FragCoord.y) * 2246822519u) * 3266489917u;
    h ^= h >> 15;
    o_color = (floor(o_color * (1023.0 / SNELL_LIGHT_RANGE) + float(h >> 8) / 16777216.0) + 0.25) / 1023.0;
#endif
}
