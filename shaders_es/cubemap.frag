// SPDX-License-Identifier: MIT
// cubemap.frag - two-sided refraction with a normal+distance cubemap (Li et
// al. 2007 as in Unger 4.1, Listing 2): refract at the front, binary-search the
// exit against the distance per direction, refract out (or reflect on TIR and
// search again, up to u_max_interfaces), look the environment up; Schlick or
// exact Fresnel, SNELL_INNER_FRESNEL at the exit too; Beer-Lambert inside.
// Object space about u_centre with the world ray parameter (any model matrix).
// highp throughout: a search's parameters lose their steps in mediump.
precision highp float;

#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/surface.glsl"
#include "common/beyond.glsl"
#include "common/dispersion.glsl"

#define MAX_INTERFACES 8     // SNELL_CUBEMAP_MAX_INTERFACES
// SNELL_SEARCH_ITERATIONS (1..32), SNELL_LINEAR_STEPS (0..32),
// SNELL_FRESNEL_EXACT (0/1) and SNELL_INNER_FRESNEL (0/1) are defined by the
// program's variant (methods/cubemap.c).


#include "common/view.glsl"
uniform vec3 u_sigma;
uniform vec3 u_tint;
uniform mat3 u_normal_matrix;    // object -> world normals

uniform highp samplerCube u_ndcube;
uniform mat4 u_inv_model;        // world -> object
uniform highp mat4 u_model;      // object -> world (object.vert's; the exit point for snell_exit)
uniform vec3 u_centre;           // cubemap centre, object space
uniform float u_radius;          // distance scale of the cubemap, object units
uniform float u_inner_radius;    // no surface closer to the centre, object units
uniform int u_max_interfaces;    // 1..MAX_INTERFACES
uniform float u_texel_angle;     // smallest angle of a cubemap texel, radians
// SNELL_ABSORB (0/1, compile-time): any sigma > 0, so the capped path still
// needs its length and the Beer-Lambert exp runs; without it neither does.

// Distance only (the search needs no normal): one channel of the texel.
float fetch_dist(vec3 q)
{
    vec4 t = textureLod(u_ndcube, q, 0.0);
#ifdef SNELL_NDCUBE_OCT
    return snell_unpack_unorm16(t.ba) * u_radius;
#else
    return t.a * u_radius;
#endif
}

// Normal at q (object space, not normalised: the caller normalises after the
// normal matrix anyway).
vec3 fetch_normal(vec3 q)
{
    vec4 t = textureLod(u_ndcube, q, 0.0);
#ifdef SNELL_NDCUBE_OCT
    return snell_oct_decode(t.rg * 2.0 - 1.0);
#else
    return t.rgb * 2.0 - 1.0;
#endif
}

// Exit of the ray p + t d (p relative to the centre, object space; t world
// length) from the surface held in the cubemap. The bracket comes from two
// spheres about the centre: the ray surely is inside while within the inner
// one (u_inner_radius: no surface there) and surely outside once it leaves
// the bounding one (u_radius); Unger uses fixed 0.01..250 for objects scaled
// to radius 100, this is the same idea without the scaling, and for a convex,
// nearly round mesh the bracket is already short. An optional linear
// pre-search finds the first crossing at a coarse step; the binary search
// (Listing 2) halves the bracket SNELL_SEARCH_ITERATIONS times or until it is
// below one texel at the current distance; a final secant step between the
// bracket's ends uses the insideness f = stored distance - |q| (> 0 inside)
// already fetched there (an end never sampled counts as f = 0: the estimate
// stays inside the final bracket either way).
//
// The step counts are compile-time constants (one program per setting,
// built on first use, methods/cubemap.c): a loop bounded by uniforms, or one
// left in the program but disabled, costs llvmpipe time by itself
// (bench/notes/code.md, "cubemap.frag"). On GPUs a constant bound lets the
// compiler unroll.
float search_exit(vec3 p, vec3 d)
{
    float a2 = dot(d, d);
    float b = dot(p, d);
    float pp = dot(p, p);
    float t_max = max((-b + sqrt(max(b * b - a2 * (pp - u_radius * u_radius), 0.0))) / a2, 0.0);
    float disc_in = b * b - a2 * (pp - u_inner_radius * u_inner_radius);
    float lo = disc_in > 0.0 ? clamp((-b + sqrt(disc_in)) / a2, 0.0, t_max) : 0.0;
    float hi = t_max;
    float dlen = sqrt(a2);
    float f_lo = 0.0, f_hi = 0.0;
#if SNELL_LINEAR_STEPS > 0
    float step = (hi - lo) / float(SNELL_LINEAR_STEPS + 1);
    float t0 = lo;
    for (int j = 1; j <= SNELL_LINEAR_STEPS; j++) {
        float m = t0 + float(j) * step;
        vec3 q = p + m * d;
        float f = fetch_dist(q) - length(q);
        if (f > 0.0) {
            lo = m;
            f_lo = f;
        } else {
            hi = m;
            f_hi = f;
            break;
        }
    }
#endif
    for (int i = 0; i < SNELL_SEARCH_ITERATIONS; i++) {
        float m = 0.5 * (lo + hi);
        vec3 q = p + m * d;
        float lq = length(q);
        float f = fetch_dist(q) - lq;
        if (f > 0.0) {
            lo = m;
            f_lo = f;
        } else {
            hi = m;
            f_hi = f;
        }
        if ((hi - lo) * dlen < lq * u_texel_angle) break;
    }
    if (f_lo - f_hi > 0.0) return lo + (hi - lo) * f_lo / (f_lo - f_hi);
    return 0.5 * (lo + hi);
}

#if SNELL_DISPERSION == 2
// One-path dispersion: the red or blue ray from q along d (object space per
// world length) over the green ray's length t, then one Newton step on the
// insideness f = stored distance - |q| with the stored distance taken as
// constant (exact for a sphere about the centre): where that ray meets the
// surface, without a search of its own. Updates q; returns the world normal
// there, facing the ray.
vec3 disp_exit(inout vec3 q, vec3 d, float t, vec3 dir)
{
    q += t * d;
    float lq = length(q);
    float rate = dot(q, d) / lq; // d|q|/dt
    if (rate > 1e-3) q += clamp((fetch_dist(q) - lq) / rate, -t, t) * d;
    vec3 n = normalize(u_normal_matrix * fetch_normal(q));
    return dot(n, dir) > 0.0 ? -n : n;
}
#endif

#if SNELL_INNER_FRESNEL
// The branch reflected inside at the exit (weight F there): one more search
// from the exit point q along rdir, refracted out at the next surface with
// (1 - F'), whose own reflection F' leaves in its mirror direction (the rest
// of the tree, lumped so that no energy is lost). Radiance, before the tint.
vec3 inner_branch(vec3 q, vec3 rdir, float path)
{
    vec3 d = mat3(u_inv_model) * rdir;
    float t = search_exit(q, d);
    q += t * d;
    vec3 n3 = normalize(u_normal_matrix * fetch_normal(q));
    if (dot(n3, rdir) > 0.0) n3 = -n3;
    vec3 out_dir;
    vec3 mirror = snell_reflect(rdir, n3);
    bool exited = snell_refract(rdir, n3, snell_ior, out_dir);
    float f = exited ? snell_fresnel(-dot(rdir, n3), snell_ior, 1.0) : 1.0;
    vec3 l = (1.0 - f) * snell_env(normalize(out_dir)) + f * snell_env(mirror);
#if SNELL_ABSORB
    l *= snell_beer_lambert(u_sigma, path + t);
#endif
    return l;
}
#endif

// The colour for one IOR, snell_ior (common/dispersion.glsl calls it).
vec3 snell_glass_trace(out highp vec3 exit_dir)
{
    highp vec3 world_pos, world_normal;
    snell_surface(world_pos, world_normal);
    highp vec3 v = snell_view_ray(world_pos);
    vec3 n = normalize(world_normal);
    if (dot(n, v) > 0.0) n = -n;
    vec3 r = snell_reflect(v, n);
    vec3 dir;
    snell_refract(v, n, 1.0 / snell_ior, dir);
    snell_disp_enter(v, n);
    float fresnel = snell_fresnel(-dot(v, n), 1.0, snell_ior);
#if SNELL_INNER_FRESNEL
    float exit_fresnel = 0.0;   // F at the exit the chain refracted out of (0: capped, no exit)
    vec3 exit_in = dir;         // the direction that reached it from inside
    vec3 exit_n = n;
    float exit_path = 0.0;
#endif

    mat3 inv3 = mat3(u_inv_model);
    vec3 p = (u_inv_model * vec4(world_pos, 1.0)).xyz - u_centre;    // object, about the centre
    float path = 0.0;
#if SNELL_DISPERSION == 2
    vec3 p_red = p, p_blue = p; // where the red and blue rays are, after the green ray's lengths
#endif
    // Interface 1 was the entry; pass k searches for interface k. After
    // u_max_interfaces the light is capped while inside: it leaves along its
    // current direction and absorption runs on to the next surface (the
    // reference's MATCHED model), so with absorption one more search gives
    // that length. The exit tests are at the end of the pass (see
    // search_exit: no fully masked pass). SNELL_NO_SEARCH (one interface, no
    // absorption: the single-surface model) compiles the loop out, as
    // llvmpipe would run its body under an empty mask.
#if !SNELL_NO_SEARCH
    for (int k = 2; k <= MAX_INTERFACES + 1; k++) {
        if (k > u_max_interfaces && SNELL_ABSORB == 0) break;      // max_interfaces 1: no search
        vec3 d = inv3 * dir;
        float t = search_exit(p, d);
        p += t * d;
        path += t;
        if (k > u_max_interfaces) break;                        // the capped pass: length only
        vec3 n2 = normalize(u_normal_matrix * fetch_normal(p));
        if (dot(n2, dir) > 0.0) n2 = -n2;                      // face the ray (it comes from inside)
        vec3 out_dir;
        bool exited = snell_refract(dir, n2, snell_ior, out_dir);
#if SNELL_DISPERSION == 2
        // red and blue meet the surface near where their own rays are after
        // the green ray's length: the cubemap's normal there (a curved exit
        // bends them by its change of normal as much as by their IORs)
        vec3 n_red = disp_exit(p_red, inv3 * snell_disp_dirs[0], t, snell_disp_dirs[0]);
        vec3 n_blue = disp_exit(p_blue, inv3 * snell_disp_dirs[2], t, snell_disp_dirs[2]);
        snell_disp_cross3(mat3(n_red, n2, n_blue), exited, true);
#else
        snell_disp_cross(n2, exited, true);
#endif
#if SNELL_INNER_FRESNEL
        if (exited) {
            exit_fresnel = snell_fresnel(-dot(dir, n2), snell_ior, 1.0);
            exit_in = dir;
            exit_n = n2;
            exit_path = path;
        }
#endif
        dir = normalize(out_dir);                               // refracted out, or totally reflected
        if (exited || (k == u_max_interfaces && SNELL_ABSORB == 0)) break;
    }
#endif

    highp vec3 exit_p = (u_model * vec4(p + u_centre, 1.0)).xyz;
#if SNELL_ABSORB
    vec3 transmitted = snell_disp_exit(exit_p, dir) * u_tint * snell_beer_lambert(u_sigma, path);
#else
    vec3 transmitted = snell_disp_exit(exit_p, dir) * u_tint;
#endif
#if SNELL_INNER_FRESNEL && !SNELL_NO_SEARCH
    // Fresnel inside too (cubemap param inner_fresnel=1): the exit transmits 1 - F
    // of the chain and reflects F back in, the strongest of the branches the
    // two-interface model drops (the first internal reflection: the ghost);
    // one more search follows it (inner_branch). Called for every pixel and
    // selected, not branched on: its environment look-ups take implicit
    // derivatives, which GLSL ES 3.0 leaves undefined in non-uniform control
    // flow (8.9); on llvmpipe the whole 4x4 block runs the branch anyway.
    vec3 inner = inner_branch(p, snell_reflect(exit_in, exit_n), exit_path);
    transmitted = exit_fresnel > 0.0 ? (1.0 - exit_fresnel) * transmitted + exit_fresnel * u_tint * inner
                                     : transmitted;
#endif
    vec3 reflected = snell_reflection(world_pos, r);
    exit_dir = dir;
    return mix(transmitted, reflected, fresnel);
}
