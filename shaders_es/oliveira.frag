// SPDX-License-Identifier: MIT
// oliveira.frag - two-sided refraction by a conservative search in image
// space (Oliveira and Brauwers 2007; seed 000 3.4.2, Listing 1): the refracted
// ray is walked in linear, then binary steps against the frame's back-face pass;
// the search ends on a texel with a back face (the invalid-texel rule) or when a
// step spans less than a pixel. E is the bounding sphere's exit, TIR searches
// on; Schlick at the entry, Beer-Lambert inside. SNELL_LINEAR_STEPS and
// SNELL_SEARCH_ITERATIONS are the method's constants (methods/oliveira.c).
// highp throughout. The departures from the seed and why: docs/methods.md,
// "Design notes by file".
precision highp float;

#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/surface.glsl"
#include "common/beyond.glsl"
#include "common/dispersion.glsl"

#ifndef SNELL_SCREEN_SPACE
#error "oliveira.frag shades in screen space only: the search reads the G-buffer's front surface"
#endif

#define MAX_INTERFACES 8

#include "common/view.glsl"
uniform vec3 u_sigma;
uniform vec3 u_tint;
uniform highp mat4 u_view_proj;
uniform highp vec4 u_bsphere;        // world bounding sphere: centre, radius
uniform int u_max_interfaces;        // 2..MAX_INTERFACES

uniform highp sampler2D u_bnormal;   // back-face pass: octahedral 16+16 bits
uniform highp sampler2D u_bdepth_id; // back-face pass: window depth 24 bits, object id 8 bits
uniform int u_back_band;             // the back-face maps' guard band: texel = window pixel + band

highp vec2 g_size;                   // target size in pixels

// Window depth at pixel px of a depth+id map, or -1 where the map holds no
// surface of this object.
highp float map_depth(highp sampler2D depth_id, ivec2 px)
{
    highp uvec4 b = uvec4(texelFetch(depth_id, px, 0) * 255.0 + 0.5);
    highp float z = float((b.r << 16u) | (b.g << 8u) | b.b) / 16777215.0;
    return int(b.a) != u_gid ? -1.0 : z;
}

vec3 map_normal(highp sampler2D normal, ivec2 px)
{
    highp vec4 g = texelFetch(normal, px, 0);
    return snell_oct_decode(vec2(snell_unpack_unorm16(g.xy), snell_unpack_unorm16(g.zw)) * 2.0 - 1.0);
}

// Window position (pixels, depth) of clip coordinates c; w <= 0 maps off-screen.
highp vec3 window(highp vec4 c)
{
    highp vec3 w = vec3((c.xy / c.w * 0.5 + 0.5) * g_size, c.z / c.w * 0.5 + 0.5);
    return c.w <= 0.0 ? vec3(-1.0, -1.0, 2.0) : w;
}

// Is the sample at window position w still inside the object? Against the
// back-face map (away = the ray moves away from the eye) it is while in front
// of the farthest back face; against the G-buffer's front surface while
// behind it. A pixel without this object's surface (off the silhouette or
// off the screen) is outside: the invalid-texel rule.
bool inside(highp vec3 w, bool away)
{
    // the back-face maps reach band pixels past the target's edge, the G-buffer does not
    highp float band = away ? float(u_back_band) : 0.0;
    bool on = all(greaterThanEqual(w.xy, vec2(-band))) && all(lessThan(w.xy, g_size + band));
    // selected, not returned early: one value merged (z, the map read), the
    // texel clamped into the map where the answer is off it anyway
    ivec2 px = clamp(ivec2(floor(w.xy)), ivec2(-int(band)), ivec2(g_size + band) - 1);
    highp float z = away ? map_depth(u_bdepth_id, px + u_back_band) : map_depth(u_gdepth_id, px);
    bool in_front = away ? w.z < z : w.z > z;
    return on && z >= 0.0 && in_front;
}

// The conservative search from p along unit d: returns the distance to the
// last point known to be inside, px_out its pixel, away_out which map it was
// tested against.
highp float search(highp vec3 p, highp vec3 d, out ivec2 px_out, out bool away_out)
{
    highp float t_end = snell_sphere_exit(p, d, u_bsphere) * 1.001 + 1e-6 * u_bsphere.w;
    // clip coordinates are affine in the world position: c(t) = c0 + t dc
    highp vec4 c0 = u_view_proj * vec4(p, 1.0), dc = u_view_proj * vec4(d, 0.0);
    highp vec3 w0 = window(c0), w_end = window(c0 + t_end * dc);
    bool away = w_end.z > w0.z;
    highp float s = 0.0, step = t_end;
    // (the loops end at their top and select: on V3D every value a loop
    // merges stays live through the interface loop around it)
#if SNELL_LINEAR_STEPS > 0
    step = t_end / float(SNELL_LINEAR_STEPS + 1);
    bool going = true;
    for (int j = 0; j < SNELL_LINEAR_STEPS; j++) {
        if (!going) break;
        going = inside(window(c0 + (s + step) * dc), away);
        highp float s_next = s + step;
        s = going ? s_next : s;
    }
#endif
    // Listing 1: halve the step; advance S only onto samples still inside
    highp vec2 ws = window(c0 + s * dc).xy;
    bool fine = false;
    for (int i = 0; i < SNELL_SEARCH_ITERATIONS; i++) {
        if (fine) break;
        step *= 0.5;
        highp vec3 w = window(c0 + (s + step) * dc);
        highp vec2 span = w.xy - ws;
        bool in_glass = inside(w, away);
        highp float s_next = s + step;
        s = in_glass ? s_next : s;
        ws = in_glass ? w.xy : ws;
        // a step within one pixel: the maps resolve nothing finer
        fine = dot(span, span) < 1.0;
    }
    highp float band = away ? float(u_back_band) : 0.0;
    px_out = ivec2(floor(clamp(ws, vec2(-band), g_size + band - 1.0)));
    away_out = away;
    return s;
}

#if SNELL_DISPERSION == 2
// One-path dispersion: the red or blue ray from q along dir over the green
// ray's length t (updates q), and the normal of the map the green search
// ended in at that point's pixel, facing the ray; where the map holds no
// surface of this object there, n_green's.
vec3 disp_exit_normal(inout highp vec3 q, vec3 dir, highp float t, bool away, vec3 n_green)
{
    q += t * dir;
    highp vec3 w = window(u_view_proj * vec4(q, 1.0));
    highp float band = away ? float(u_back_band) : 0.0;
    ivec2 px = ivec2(floor(clamp(w.xy, vec2(-band), g_size + band - 1.0)));
    ivec2 tex = away ? px + u_back_band : px;
    bool found = (away ? map_depth(u_bdepth_id, tex) : map_depth(u_gdepth_id, tex)) >= 0.0;
    vec3 n = found ? (away ? map_normal(u_bnormal, tex) : map_normal(u_gnormal, tex)) : n_green;
    return dot(n, dir) > 0.0 ? -n : n;
}
#endif

#if SNELL_INNER_FRESNEL
// The branch reflected inside at the exit: one more search from q along d,
// refracted out at the surface found with (1 - F'), its own reflection F'
// leaving along the mirror (the rest of the tree lumped, so no energy is
// lost). Radiance before the tint. v, n: the view ray and entry normal, for
// the fallback normal where no sample was inside.
vec3 inner_branch(highp vec3 q, highp vec3 d, highp float len, highp vec3 v, vec3 n)
{
    ivec2 px;
    bool away;
    highp float t = search(q, d, px, away);
    ivec2 tex = away ? px + u_back_band : px;
    // selected, as the interface loop's normal (snell_glass_trace)
    highp float z_tex = away ? map_depth(u_bdepth_id, tex) : map_depth(u_gdepth_id, tex);
    vec3 n_map = away ? map_normal(u_bnormal, tex) : map_normal(u_gnormal, tex);
    highp vec3 side = d - dot(d, v) * v;
    vec3 n_side = normalize(side);
    vec3 n_fall = dot(side, side) > 1e-12 ? n_side : -n;
    vec3 n3 = z_tex >= 0.0 ? n_map : n_fall;
    n3 = dot(n3, d) > 0.0 ? -n3 : n3;
    highp vec3 out_dir;
    bool exited = snell_refract_sel(d, n3, snell_ior, out_dir);
    float f_out = snell_fresnel_sel(-dot(d, n3), snell_ior, 1.0);
    float f = exited ? f_out : 1.0;
    vec3 l = (1.0 - f) * snell_env(normalize(out_dir)) + f * snell_env(snell_reflect(d, n3));
#if SNELL_ABSORB
    l *= snell_beer_lambert(u_sigma, len + t);
#endif
    return l;
}
#endif

// The colour for one IOR, snell_ior (common/dispersion.glsl calls it).
vec3 snell_glass_trace(out highp vec3 exit_dir)
{
    g_size = 1.0 / u_inv_size;
    highp vec3 p1, n1;
    snell_surface(p1, n1);
    highp vec3 v = snell_view_ray(p1);
    vec3 n = normalize(n1);
    n = dot(n, v) > 0.0 ? -n : n;
    highp vec3 dir;
    snell_refract(v, n, 1.0 / snell_ior, dir);
    dir = normalize(dir);
    snell_disp_enter(v, n);
    float fresnel = snell_fresnel(-dot(v, n), 1.0, snell_ior);

    highp vec3 p = p1;
    highp float length_inside = 0.0;
#if SNELL_DISPERSION == 2
    highp vec3 p_red = p1, p_blue = p1; // where the red and blue rays are, after the green ray's lengths
#endif
#if SNELL_INNER_FRESNEL
    // the loop ends at the exit: its point and length are the loop's last
    float exit_fresnel = 0.0;   // F at the exit the path refracted out of (0: capped, no exit)
    highp vec3 exit_in = dir;
    vec3 exit_n = n;
#endif
    // selects, not branches, and the loop ends at its top: on V3D every
    // value the loop merges stays live through all of it
    bool done = false;
    for (int k = 2; k <= MAX_INTERFACES; k++) {
        if (done) break;
        ivec2 px;
        bool away;
        highp float t = search(p, dir, px, away);
        // the exit point: the bracket's far end is outside, so the surface is
        // within a pixel of the last inside sample; its normal is the map's there
        p += t * dir;
        length_inside += t;
        ivec2 tex = away ? px + u_back_band : px;
        highp float z_tex = away ? map_depth(u_bdepth_id, tex) : map_depth(u_gdepth_id, tex);
        vec3 n_map = away ? map_normal(u_bnormal, tex) : map_normal(u_gnormal, tex);
        // not one sample was inside (the first step already left the
        // silhouette): Wyman's fallback, a normal perpendicular to the
        // view vector, in the plane of V and the ray
        highp vec3 side = dir - dot(dir, v) * v;
        vec3 n_side = normalize(side);
        vec3 n_fall = dot(side, side) > 1e-12 ? n_side : -n;
        vec3 n2 = z_tex >= 0.0 ? n_map : n_fall;
        n2 = dot(n2, dir) > 0.0 ? -n2 : n2; // face the ray (it comes from inside)
        highp vec3 next;
        bool out_of_glass = snell_refract_sel(dir, n2, snell_ior, next); // on TIR: the mirror direction
#if SNELL_DISPERSION == 2
        // red and blue meet the surface near where their own rays are after
        // the green ray's length: the map's normal there (a curved exit bends
        // them by its change of normal as much as by their IORs)
        snell_disp_cross3(mat3(disp_exit_normal(p_red, snell_disp_dirs[0], t, away, n2), n2,
                               disp_exit_normal(p_blue, snell_disp_dirs[2], t, away, n2)), out_of_glass, true);
#else
        snell_disp_cross(n2, out_of_glass, true);
#endif
#if SNELL_INNER_FRESNEL
        float f_exit = snell_fresnel_sel(-dot(dir, n2), snell_ior, 1.0);
        exit_fresnel = out_of_glass ? f_exit : exit_fresnel;
        exit_in = out_of_glass ? dir : exit_in;
        exit_n = out_of_glass ? n2 : exit_n;
#endif
        dir = normalize(next);
        done = out_of_glass || k >= u_max_interfaces;
    }

#if SNELL_ABSORB
    vec3 transmitted = snell_disp_exit(p, dir) * u_tint * snell_beer_lambert(u_sigma, length_inside);
#else
    vec3 transmitted = snell_disp_exit(p, dir) * u_tint;
#endif
#if SNELL_INNER_FRESNEL
    // Fresnel at the exit too: it transmits 1 - F and reflects F back in,
    // which one more search follows (inner_branch). Computed for every pixel
    // and selected: its look-ups take implicit derivatives, undefined in
    // non-uniform control flow (GLSL ES 3.0, 8.9).
    vec3 inner = inner_branch(p, snell_reflect(exit_in, exit_n), length_inside, v, n);
    transmitted = exit_fresnel > 0.0 ? (1.0 - exit_fresnel) * transmitted + exit_fresnel * u_tint * inner : transmitted;
#endif
    // the reflected direction from v and n, which the loop keeps anyway:
    // three values fewer live through it
    vec3 reflected = snell_reflection(p1, snell_reflect(v, n));
    exit_dir = dir;
    return mix(transmitted, reflected, fresnel);
}
