// caustics_receiver.frag - the receiver plane in the view: albedo times its
// light map (direct light where unshadowed plus the caustics), read
// bilinearly by hand (a 32-bit float map need not be filterable), linear.
precision highp float;
precision highp sampler2D;

#include "common/output.glsl"

uniform sampler2D u_light_map;
uniform vec3 u_albedo;
uniform highp vec3 u_eye;
in vec2 v_ndc;
in highp vec3 v_world_pos;

void main()
{
    ivec2 n = textureSize(u_light_map, 0);
    vec2 t = (v_ndc * 0.5 + 0.5) * vec2(n) - 0.5;
    ivec2 b = ivec2(floor(t));
    vec2 f = t - floor(t);
    ivec2 hi = n - 1;
    vec3 e = mix(mix(texelFetch(u_light_map, clamp(b, ivec2(0), hi), 0).rgb,
                     texelFetch(u_light_map, clamp(b + ivec2(1, 0), ivec2(0), hi), 0).rgb, f.x),
                 mix(texelFetch(u_light_map, clamp(b + ivec2(0, 1), ivec2(0), hi), 0).rgb,
                     texelFetch(u_light_map, clamp(b + ivec2(1, 1), ivec2(0), hi), 0).rgb, f.x), f.y);
    snell_write(u_albedo * e, v_world_pos - u_eye);
}
