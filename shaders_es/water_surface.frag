// water_surface.frag - the water surface (Dachsbacher 2002, "Refraction
// Mapping"): the view ray refracted at the per-pixel normal meets the
// container exactly - the seed's five ray-wall distances, the nearest
// positive one choosing the floor or a wall - where the tiles are seen,
// attenuated by Beer-Lambert over the path in the water; the mirror ray sees
// the walls' inner side above the water or the environment (the seed: the
// sky box only); Schlick's Fresnel weighs the two (the seed adds them).
// SNELL_WATER_OBJECTS: the frame's opaque objects, drawn before the water,
// are seen through it: their colour and depth (copied from the target) are
// searched along the refracted ray in screen space (the seed has no objects;
// the search is Oliveira's applied to the opaque depth), 24 linear steps and
// 6 binary ones over the part of the ray inside the objects' bounding
// spheres. A step counts as a hit where it lies behind the copied depth by
// less than a twelfth of the way to the container (view depth): a ray
// passing farther behind an object's visible surface goes on; one leaving
// the screen misses. Exit-direction output: the refracted direction.
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
uniform float u_rim;       // top of the walls above the rest level

// What the mirror ray from p sees: the walls' inner side where a rising ray
// meets them below the rim, else the environment (a falling one would meet
// the water again: the environment too, unmodelled).
vec3 reflected(vec3 p, vec3 r)
{
    if (r.y > 0.0) {
        float e = 3.0e38;
        int face = 0;
        if (r.x != 0.0) {
            e = ((r.x > 0.0 ? u_half : -u_half) - p.x) / r.x;
            face = r.x > 0.0 ? 2 : 1;
        }
        if (r.z != 0.0) {
            float s = ((r.z > 0.0 ? u_half : -u_half) - p.z) / r.z;
            if (s < e) {
                e = s;
                face = r.z > 0.0 ? 4 : 3;
            }
        }
        vec3 q = p + max(e, 0.0) * r;
        if (q.y <= u_rim) return water_tile(face, q);
    }
    return snell_env(r);
}

#ifdef SNELL_WATER_OBJECTS
uniform highp sampler2D u_scene_depth; // the opaque objects' window depth (1: none)
uniform sampler2D u_scene_color;
uniform mat4 u_view_proj;
uniform vec2 u_depth_ab;    // proj[2][2], proj[3][2]: view depth = b / (ndc z + a)
// World bounding spheres of the opaque objects (centre, radius; one enclosing
// sphere when there are more than SNELL_WATER_MAX_SPHERES): the search runs
// only over the part of the refracted segment inside them.
#define SNELL_WATER_MAX_SPHERES 16
uniform vec4 u_spheres[SNELL_WATER_MAX_SPHERES];
uniform int u_sphere_count;

// The search runs in clip space, where the refracted segment p .. p + dmax t
// is a straight line (c0 .. c1, clip w = view depth): one matrix product per
// pixel, none per step. 1 if the point at fraction f lies behind an opaque
// surface by less than thickness (view depth).
bool behind_object(vec4 c0, vec4 c1, float f, float thickness, ivec2 size, out ivec2 pix)
{
    vec4 c = mix(c0, c1, f);
    pix = ivec2(floor((c.xy / c.w * 0.5 + 0.5) * vec2(size)));
    if (c.w <= 0.0 || any(lessThan(pix, ivec2(0))) || any(greaterThanEqual(pix, size))) return false;
    float zs = texelFetch(u_scene_depth, pix, 0).r;
    if (zs >= 1.0) return false;
    float ds = u_depth_ab.y / (2.0 * zs - 1.0 + u_depth_ab.x);
    return c.w > ds && c.w - ds < thickness;
}

// Distance along t from p to the first opaque surface before dmax (its colour in col), or -1.
float find_object(vec3 p, vec3 t, float dmax, out vec3 col)
{
    ivec2 pix, size = textureSize(u_scene_depth, 0);
    float a = dmax, b = 0.0;
    for (int k = 0; k < SNELL_WATER_MAX_SPHERES; k++) {
        if (k >= u_sphere_count) break;
        vec3 oc = p - u_spheres[k].xyz;
        float hb = dot(oc, t), c = dot(oc, oc) - u_spheres[k].w * u_spheres[k].w, disc = hb * hb - c;
        if (disc < 0.0) continue;
        float q = sqrt(disc), s0 = max(-hb - q, 0.0), s1 = min(-hb + q, dmax);
        if (s0 < s1) {
            a = min(a, s0);
            b = max(b, s1);
        }
    }
    if (a >= b) return -1.0;
    vec4 c0 = u_view_proj * vec4(p + a * t, 1.0), c1 = u_view_proj * vec4(p + b * t, 1.0);
    // a twelfth of the way to the container: thick enough for a step over the
    // objects' spheres to land inside, thin enough not to stop behind them
    // (measured: 35.0 dB against 32.7 for two steps over the spheres' part)
    float lo = 0.0, hi = -1.0, thickness = 2.0 * dmax / 24.0;
    for (int k = 1; k <= 24; k++) {
        float f = float(k) / 24.0;
        if (behind_object(c0, c1, f, thickness, size, pix)) {
            hi = f;
            break;
        }
        lo = f;
    }
    if (hi < 0.0) return -1.0;
    for (int k = 0; k < 6; k++) {
        float m = 0.5 * (lo + hi);
        if (behind_object(c0, c1, m, thickness, size, pix)) hi = m;
        else lo = m;
    }
    behind_object(c0, c1, hi, thickness, size, pix);
    col = texelFetch(u_scene_color, pix, 0).rgb;
    return a + hi * (b - a);
}
#endif

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
    vec3 seen = water_tile(face, p + d * t);
#ifdef SNELL_WATER_OBJECTS
    vec3 col;
    float e = find_object(p, t, d, col);
    if (e >= 0.0) {
        seen = col;
        d = e;
    }
#endif
    seen *= snell_beer_lambert(u_sigma, d);
    snell_write(mix(seen, reflected(p, r), fresnel), t);
}
