// caustics_direct.frag - the direct light on the receiver's light map: the
// light's irradiance times the cosine, where the shadow map (every glass and
// opaque object seen from the light) leaves a texel's 2 x 2 sample points
// lit; alpha 0 (the photons' alpha counts only the light through glass).
precision highp float;
precision highp sampler2DShadow;

uniform sampler2DShadow u_shadow;
uniform mat4 u_shadow_vp;    // world -> the shadow map's clip space (orthographic)
uniform vec4 u_plane;        // y, centre x, centre z, extent
uniform vec3 u_irradiance;   // light colour * max(0, -dir.y)
uniform float u_texel;       // the light map's texel side / extent (NDC units)
uniform float u_bias;        // depth bias, shadow clip units

layout(location = 0) out vec4 o_color;
in vec2 v_ndc;

void main()
{
    float lit = 0.0;
    for (int k = 0; k < 4; k++) {
        vec2 o = (vec2(float(k & 1), float(k >> 1)) - 0.5) * 0.5 * u_texel;
        vec2 xz = u_plane.yz + (v_ndc + o) * u_plane.w;
        vec4 c = u_shadow_vp * vec4(xz.x, u_plane.x, xz.y, 1.0);
        vec3 s = c.xyz / c.w * 0.5 + 0.5;
        lit += texture(u_shadow, vec3(s.xy, s.z - u_bias));
    }
    o_color = vec4(u_irradiance * lit * 0.25, 0.0);
}
