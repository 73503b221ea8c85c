// cubemap.frag - two-sided refraction with a normal+distance cubemap (Li et
// al. 2007 as in Unger 4.1, Listing 2). Refract at the front surface, find the
// exit point along the refracted ray by a binary search against the distance
// stored per direction from the centre, refract out there (or reflect on total
// internal reflection and search again, up to u_max_interfaces surfaces), look
// the final direction up in the environment; Schlick Fresnel at the entry,
// Beer-Lambert over the path length inside.
//
// Spaces: the cubemap is in object space about u_centre; the search runs in
// object space with the world ray parameter (d = M^-1 * unit world direction),
// so t is a world length for any model matrix, non-uniform scale included.
// highp throughout: this shader is the search (DESIGN.md, highp for search
// parameters).
precision highp float;

#include "common/optics.glsl"
#include "common/output.glsl"

#define MAX_ITER 32          // SNELL_CUBEMAP_MAX_ITERATIONS
#define MAX_LINEAR 32        // SNELL_CUBEMAP_MAX_LINEAR_STEPS
#define MAX_INTERFACES 8     // SNELL_CUBEMAP_MAX_INTERFACES

in highp vec3 v_world_pos;
in highp vec3 v_world_normal; // highp: scaled by 1/scale, overflows fp16 at tiny scales (see single.frag)

uniform highp vec3 u_eye;
uniform samplerCube u_env;
uniform float u_ior;
uniform vec3 u_sigma;
uniform vec3 u_tint;
uniform mat3 u_normal_matrix;    // object -> world normals

uniform highp samplerCube u_ndcube;
uniform mat4 u_inv_model;        // world -> object
uniform vec3 u_centre;           // cubemap centre, object space
uniform float u_radius;          // distance scale of the cubemap, object units
uniform int u_iterations;        // binary search steps, 1..MAX_ITER
uniform int u_linear_steps;      // 0..MAX_LINEAR
uniform int u_max_interfaces;    // 1..MAX_INTERFACES
uniform float u_texel_angle;     // smallest angle of a cubemap texel, radians
uniform int u_absorb;            // 1 if any sigma > 0: the capped path still needs its length

// Normal (object space, unit) and distance from the centre of the farthest
// surface in direction q (object space, relative to the centre).
vec4 fetch(vec3 q)
{
    vec4 t = textureLod(u_ndcube, q, 0.0);
#ifdef SNELL_NDCUBE_OCT
    return snell_unpack_ndist_oct(t);
#else
    return snell_unpack_ndist_plain(t);
#endif
}

// Distance only (the search needs no normal).
float fetch_dist(vec3 q)
{
    vec4 t = textureLod(u_ndcube, q, 0.0);
#ifdef SNELL_NDCUBE_OCT
    return snell_unpack_unorm16(t.ba) * u_radius;
#else
    return t.a * u_radius;
#endif
}

// Signed "insideness" of point q: stored distance - |q| (> 0 inside).
float inside_f(vec3 q)
{
    return fetch_dist(q) - length(q);
}

// Exit of the ray p + t d (p relative to the centre, object space; t world
// length) from the surface held in the cubemap. Bounds from the bounding
// sphere of radius u_radius about the centre: t = 0 is on the surface (the
// ray starts there), t_max is where the ray leaves that sphere, surely
// outside (Unger uses fixed 0.01..250 for objects scaled to radius 100; this
// is the same idea without the scaling). Optional linear pre-search finds the
// first crossing at a coarse step; the binary search (Listing 2) halves the
// bracket until u_iterations steps or the bracket is below one texel at the
// current distance; a final secant step between the bracket's ends uses the
// insideness values already fetched.
float search_exit(vec3 p, vec3 d)
{
    float a2 = dot(d, d);
    float b = dot(p, d);
    float c = dot(p, p) - u_radius * u_radius;
    float t_max = (-b + sqrt(max(b * b - a2 * c, 0.0))) / a2;
    float lo = 0.0, hi = max(t_max, 0.0);
    float f_lo = 0.0, f_hi = 0.0;
    bool have_lo = false, have_hi = false;
    float dlen = sqrt(a2);
    for (int j = 1; j <= MAX_LINEAR; j++) {
        if (j > u_linear_steps) break;
        float t = t_max * float(j) / float(u_linear_steps + 1);
        float f = inside_f(p + t * d);
        if (f < 0.0) {
            hi = t;
            f_hi = f;
            have_hi = true;
            break;
        }
        lo = t;
        f_lo = f;
        have_lo = true;
    }
    for (int i = 0; i < MAX_ITER; i++) {
        if (i >= u_iterations) break;
        float m = 0.5 * (lo + hi);
        vec3 q = p + m * d;
        if ((hi - lo) * dlen < length(q) * u_texel_angle) break;
        float f = inside_f(q);
        if (f > 0.0) {
            lo = m;
            f_lo = f;
            have_lo = true;
        } else {
            hi = m;
            f_hi = f;
            have_hi = true;
        }
    }
    if (have_lo && have_hi && f_lo - f_hi > 0.0) return lo + (hi - lo) * f_lo / (f_lo - f_hi);
    return 0.5 * (lo + hi);
}

void main()
{
    highp vec3 v = normalize(v_world_pos - u_eye);
    vec3 n = normalize(v_world_normal);
    if (dot(n, v) > 0.0) n = -n;
    vec3 r = snell_reflect(v, n);
    vec3 dir;
    snell_refract(v, n, 1.0 / u_ior, dir);
    float fresnel = snell_fresnel_schlick(-dot(v, n), 1.0, u_ior);

    mat3 inv3 = mat3(u_inv_model);
    vec3 pos = v_world_pos;                                     // world
    vec3 p = (u_inv_model * vec4(pos, 1.0)).xyz - u_centre;    // object, about the centre
    float path = 0.0;
    bool inside = true;
    // Interface 1 was the entry; each further one is an exit attempt.
    for (int k = 2; k <= MAX_INTERFACES; k++) {
        if (k > u_max_interfaces) break;
        vec3 d = inv3 * dir;
        float t = search_exit(p, d);
        p += t * d;
        pos += t * dir;
        path += t;
        vec3 n2 = normalize(u_normal_matrix * fetch(p).xyz);
        if (dot(n2, dir) > 0.0) n2 = -n2;                      // face the ray (it comes from inside)
        vec3 out_dir;
        if (snell_refract(dir, n2, u_ior, out_dir)) {
            dir = normalize(out_dir);
            inside = false;
            break;
        }
        dir = normalize(out_dir);                               // total internal reflection
    }
    // Capped while inside: the light leaves along its current direction and
    // absorption runs on to the next surface (the reference's MATCHED model).
    if (inside && u_absorb != 0) path += search_exit(p, inv3 * dir);

    vec3 transmitted = texture(u_env, dir).rgb * u_tint * snell_beer_lambert(u_sigma, path);
    vec3 reflected = texture(u_env, r).rgb;
    snell_write(mix(transmitted, reflected, fresnel), dir);
}
