// water_surface.frag - the water surface (Dachsbacher 2002, "Refraction
// Mapping"): the view ray refracted at the per-pixel normal meets the
// container exactly - the seed's five ray-wall distances, the nearest
// positive one choosing the floor or a wall - where the tiles are seen,
// attenuated by Beer-Lambert over the path in the water; the mirror ray sees
// the environment; Schlick's Fresnel weighs the two (the seed adds them).
// Exit-direction output: the refracted direction.
precision highp float;

#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/water_tiles.glsl"

in vec3 v_world_pos;
in vec3 v_world_normal;

uniform vec3 u_eye;
uniform float u_ior;
uniform vec3 u_sigma;      // Beer-Lambert absorption per world unit

void main()
{
    vec3 p = v_world_pos;
    vec3 v = normalize(p - u_eye);
    vec3 n = normalize(v_world_normal);
    if (dot(n, v) > 0.0) n = -n;
    vec3 r = snell_reflect(v, n), t;
    snell_refract(v, n, 1.0 / u_ior, t);
    float fresnel = snell_fresnel_schlick(-dot(v, n), 1.0, u_ior);
    float d = 3.0e38;
    int face = 0;
    if (t.y < 0.0) d = (-u_depth - p.y) / t.y;
    if (t.x != 0.0) {
        float s = ((t.x > 0.0 ? u_half : -u_half) - p.x) / t.x;
        if (s < d) {
            d = s;
            face = t.x > 0.0 ? 2 : 1;
        }
    }
    if (t.z != 0.0) {
        float s = ((t.z > 0.0 ? u_half : -u_half) - p.z) / t.z;
        if (s < d) {
            d = s;
            face = t.z > 0.0 ? 4 : 3;
        }
    }
    d = max(d, 0.0);
    vec3 seen = water_tile(face, p + d * t) * snell_beer_lambert(u_sigma, d);
    snell_write(mix(seen, snell_env(r), fresnel), t);
}
