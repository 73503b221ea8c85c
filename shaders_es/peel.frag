// SPDX-License-Identifier: MIT
// peel.frag - multi-layer refraction from depth-peeled layers (Wang 2014,
// seed 001 3.3-3.6). The object's surfaces along each pixel's view ray are
// in u_layers (methods/peel.c, depth_peel.frag): layer k's normal in array
// slice 2k, its depth (the view-axis distance mapped onto the bounding
// sphere's range, 24 bits) and a flag (0 = empty) in slice 2k + 1; layers
// alternate front and back faces on a closed mesh. Between layer k - 1 and
// layer k lies gap k: gap 0 before the first surface, odd gaps inside the
// glass, even ones in air.
//
// Refract the view ray at the front surface (Schlick Fresnel there, or the
// exact one with SNELL_FRESNEL_EXACT; with SNELL_INNER_FRESNEL the last exit
// into air weights the chain by 1 - F too and adds its internal reflection,
// followed by one more search: inner_branch); the ray
// is then in gap 1. The ray-height-field search (3.3): march along the ray
// from its point in steps of the bounding diameter / SNELL_PEEL_LINEAR (the
// seed's size is 1/50 of the depth range), to where the ray leaves the
// bounding sphere grown by a step (the Z_min/Z_max bound); at each step project the point to
// its pixel and compare its depth with the two layers bounding the ray's gap
// there. Where it leaves the gap, bisect SNELL_PEEL_BINARY times between the
// last point in the gap and the first out of it; the crossed layer (the
// lower bound: upward into gap k - 1, the upper: downward into k + 1) gives
// the normal. Refract, or past the critical angle reflect and stay in the
// gap (3.6), restarting from the last point inside the gap (not the first
// beyond the surface: the seed's false hit on the surface just left), up to
// u_max_interfaces surfaces; then look the direction up in the environment.
// Beer-Lambert over the length inside, tint at every entry (as the FULL
// reference). A ray still inside at the cap leaves in its current direction
// after the next surface (the reference's cap rule); so does an inside ray
// whose gap has no far layer here (more surfaces than layers peeled).
//
// The seed's fixes, compile-time (SNELL_PEEL_FIX_*, to measure each alone):
// DISCONTINUITY (3.5.1): a crossing where the crossed layer's depth jumps
// between the bracket's two pixels by more than one linear step is a layer
// boundary, not necessarily a surface (case 2 against case 3): the gap is
// found afresh from the layers at the far pixel (how many lie in front of
// the point); if the medium is the same there, the search goes on from that
// gap. MERGE (3.5.2): where an inside ray's gap 2k + 1 has no layers at a
// pixel (the far part of a torus is layers 3, 4 where it is behind the near
// part, layers 1, 2 where it is not), gap 2k - 1 there stands in for it.
//
// highp throughout: positions, projections and 24-bit depths.
precision highp float;

#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/surface.glsl"
#include "common/beyond.glsl"
#include "common/dispersion.glsl"

// SNELL_PEEL_LAYERS: the layers peeled for this object (2..SNELL_PEEL_MAX_LAYERS), a
// compile-time bound of the loops over them (u_layer_count of them hold something)
#define MAX_LAYERS SNELL_PEEL_LAYERS
#define MAX_INTERFACES 10     // SNELL_PEEL_MAX_INTERFACES
#define EMPTY 2.0             // depth of an empty texel: behind every stored depth (0..1)
// SNELL_PEEL_LAYERS, SNELL_PEEL_LINEAR, SNELL_PEEL_BINARY, SNELL_PEEL_FIX_DISCONTINUITY,
// SNELL_PEEL_FIX_MERGE, SNELL_ABSORB, SNELL_FRESNEL_EXACT, SNELL_INNER_FRESNEL:
// the program's variant (methods/peel.c).

#include "common/view.glsl"
uniform vec3 u_sigma;
uniform vec3 u_tint;
uniform highp mat4 u_view_proj;
uniform highp vec4 u_bsphere;        // world bounding sphere: centre, radius

uniform highp sampler2DArray u_layers;
uniform int u_layer_count;           // non-empty layers peeled, 1..MAX_LAYERS
uniform highp vec3 u_fwd;            // unit view axis
uniform highp float u_near;          // view depth of depth value 0
uniform highp float u_inv_range;     // depth values per world unit of view depth
uniform highp vec2 u_size;           // target size in pixels
uniform int u_max_interfaces;        // 2..MAX_INTERFACES

highp float depth_of(highp vec3 p)
{
    return (dot(p - u_eye, u_fwd) - u_near) * u_inv_range;
}

// The pixel of clip-space position c; (-1, -1) outside the target or behind the eye.
ivec2 pixel_at(highp vec4 c)
{
    if (c.w <= 0.0) return ivec2(-1);
    highp vec2 w = (c.xy / c.w * 0.5 + 0.5) * u_size;
    if (any(lessThan(w, vec2(0.0))) || any(greaterThanEqual(w, u_size))) return ivec2(-1);
    return ivec2(w);
}

// The pixel p projects to.
ivec2 pixel_of(highp vec3 p)
{
    return pixel_at(u_view_proj * vec4(p, 1.0));
}

highp float layer_depth(ivec2 px, int k)
{
    if (px.x < 0 || k < 0 || k >= u_layer_count) return EMPTY;
    highp uvec4 b = uvec4(texelFetch(u_layers, ivec3(px, 2 * k + 1), 0) * 255.0 + 0.5);
    if (b.a == 0u) return EMPTY;
    return float((b.r << 16u) | (b.g << 8u) | b.b) / 16777215.0;
}

vec3 layer_normal(ivec2 px, int k)
{
    highp vec4 g = texelFetch(u_layers, ivec3(px, 2 * k), 0);
    return snell_oct_decode(vec2(snell_unpack_unorm16(g.xy), snell_unpack_unorm16(g.zw)) * 2.0 - 1.0);
}

// Layer k's normal at point q: the four texels around q's position,
// bilinearly, those of the same smooth surface as the texel q projects to
// (depth within a linear step of q's, normal within 18 degrees of that
// texel's: not across a depth jump or a crease, e.g. a cube's edge); that
// texel's alone if none is. Pixel-centre normals alone gave a larger error
// against FULL on every mesh measured (bench/notes/code.md, "peel.frag").
vec3 layer_normal_at(highp vec3 q, int k)
{
    highp vec4 c = u_view_proj * vec4(q, 1.0);
    highp vec2 w = (c.xy / c.w * 0.5 + 0.5) * u_size - 0.5;
    ivec2 base = ivec2(floor(w));
    highp vec2 f = w - floor(w);
    highp float z = depth_of(q);
    ivec2 own = pixel_of(q);
    vec3 n0 = layer_normal(own, k), sum = vec3(0.0);
    for (int i = 0; i < 4; i++) {
        ivec2 px = base + ivec2(i & 1, i >> 1);
        if (any(lessThan(px, ivec2(0))) || any(greaterThanEqual(px, ivec2(u_size)))) continue;
        if (abs(layer_depth(px, k) - z) > 1.0 / float(SNELL_PEEL_LINEAR)) continue;
        vec3 n = layer_normal(px, k);
        if (dot(n, n0) < 0.95) continue;
        float wt = ((i & 1) == 1 ? f.x : 1.0 - f.x) * ((i >> 1) == 1 ? f.y : 1.0 - f.y);
        sum += wt * n;
    }
    return dot(sum, sum) > 1e-12 ? sum : n0;
}

// How many layers at px lie in front of depth z: the gap z is in there.
int gap_at(ivec2 px, highp float z)
{
    int n = 0;
    for (int k = 0; k < MAX_LAYERS; k++)
        if (layer_depth(px, k) < z) n = k + 1;
    return n;
}

// The depths bounding gap j at px: lo = layer j - 1 (none for gap 0 or an
// empty layer: -1), hi = layer j (EMPTY if absent). m: the gap whose layers
// stand for it there (MERGE). False for an inside gap with no layers at px:
// the ray has left through the silhouette.
bool gap_bounds(ivec2 px, int j, out int m, out highp float lo, out highp float hi)
{
    m = j;
    lo = layer_depth(px, j - 1);
#if SNELL_PEEL_FIX_MERGE && MAX_LAYERS > 2
    for (int i = 0; i < MAX_LAYERS / 2; i++) {
        if ((m & 1) == 0 || m < 3 || lo != EMPTY) break;
        m -= 2;
        lo = layer_depth(px, m - 1);
    }
#endif
    hi = layer_depth(px, m);
    if ((m & 1) == 1 && lo == EMPTY) return false;
    if (lo == EMPTY) lo = -1.0;
    return true;
}

// 0: z lies in gap j at px; 1: above it (crossed layer m - 1); 2: below it
// (crossed layer m); 3: no such gap here (silhouette).
int classify(ivec2 px, int j, highp float z, out int m)
{
    highp float lo, hi;
    if (!gap_bounds(px, j, m, lo, hi)) return 3;
    return z < lo ? 1 : z > hi ? 2 : 0;
}

// The search (3.3) from p along dir in gap j, out to the bounding sphere
// grown by a step (t_max). Returns the crossing's kind (classify; 0: none
// before t_max); ta: the last ray parameter in the gap, tb: the first out of
// it; m: the gap whose layers stood for j there. DISCONTINUITY may move the
// ray to another gap of the same medium (j).
int search_gap(highp vec3 p, vec3 dir, highp float step, inout int j, out int m, out highp float ta,
               out highp float tb, out highp float t_max)
{
    // the search range: to the far side of the bounding sphere grown by
    // one step, so that the last sample lies clearly beyond a surface on
    // the sphere (a tessellated sphere's vertices are on it): a point just
    // beyond it can still test as in front of it, against the depth at its
    // pixel's centre
    highp vec3 oc = p - u_bsphere.xyz;
    highp float b = dot(oc, dir), rs = u_bsphere.w + step;
    t_max = max(-b + sqrt(max(b * b - dot(oc, oc) + rs * rs, 0.0)), 0.0);
    ta = 0.0;
    tb = -1.0;
    m = j;
    int kind = 0;
    // The linear scan stops at the first step out of the gap; the bisection
    // follows it, outside the scan's loop: a software rasteriser runs a
    // branch's body for the whole block whenever any pixel of it takes it
    // (llvmpipe masks, it does not jump), so a bisection inside the scan
    // was paid at every step. A DISCONTINUITY restart scans on from the
    // next step (the outer loop), as the single loop did.
    // clip position and depth are linear along the ray: one projection per search
    highp vec4 c0 = u_view_proj * vec4(p, 1.0), cd = u_view_proj * vec4(dir, 0.0);
    highp float z0 = depth_of(p), dz = dot(dir, u_fwd) * u_inv_range;
    int i = 1;
    for (int restart = 0; restart <= SNELL_PEEL_LINEAR; restart++) {
        highp float t = 0.0;
        for (; i <= SNELL_PEEL_LINEAR + 1; i++) {
            t = min(float(i) * step, t_max);
            kind = classify(pixel_at(c0 + t * cd), j, z0 + t * dz, m);
            if (kind != 0) break;
            ta = t;
            if (t >= t_max) break;
        }
        if (kind == 0) break;
        // bisect [ta, t]: ta in the gap, tb out of it
        tb = t;
        for (int s = 0; s < SNELL_PEEL_BINARY; s++) {
            highp float tm = 0.5 * (ta + tb);
            int mm;
            int km = classify(pixel_at(c0 + tm * cd), j, z0 + tm * dz, mm);
            if (km == 0) ta = tm;
            else {
                tb = tm;
                kind = km;
                m = mm;
            }
        }
#if SNELL_PEEL_FIX_DISCONTINUITY
        highp vec3 qa = p + ta * dir, qb = p + tb * dir;
        ivec2 pa = pixel_of(qa), pb = pixel_of(qb);
        int crossed = kind == 1 ? m - 1 : m;
        if (kind != 3 && abs(layer_depth(pa, crossed) - layer_depth(pb, crossed)) > 1.0 / float(SNELL_PEEL_LINEAR)) {
            int g = gap_at(pb, depth_of(qb));
            if ((g & 1) == (j & 1)) {
                // case 2: a layer boundary, not a surface; go on in the gap found there
                j = g;
                ta = tb;
                tb = -1.0;
                kind = 0;
                i++;
                continue;
            }
        }
#endif
        break;
    }
    return kind;
}

// The normal (not normalised) of the surface a search from p along dir
// crossed (kind != 0), and the gap beyond it (next).
vec3 crossing_normal(highp vec3 p, vec3 dir, int kind, int j, int m, highp float ta, highp float tb, out int next)
{
    highp vec3 qb = p + tb * dir, qa = p + ta * dir;
    if (kind == 3) {
        // out through the silhouette: its normal is the last pixel's
        // layer nearest the point (the side wall there)
        ivec2 pa = pixel_of(qa);
        highp float za = depth_of(qa);
        int near_k = abs(layer_depth(pa, m - 1) - za) < abs(layer_depth(pa, m) - za) ? m - 1 : m;
        next = j + 1;
        return pa.x >= 0 && layer_depth(pa, near_k) != EMPTY ? layer_normal(pa, near_k) : -dir;
    }
    next = kind == 1 ? j - 1 : j + 1;
    return layer_normal_at(qb, kind == 1 ? m - 1 : m);
}

#if SNELL_DISPERSION == 2
// One-path dispersion: the red or blue ray from q along dir over the green
// ray's length t towards layer k, then one Newton step on its depth against
// the layer's at its pixel: near where that ray crosses the layer, without a
// search of its own. Updates q; returns the layer's normal there, facing the
// ray; n_green (green's, facing green's ray) where that normal is more than
// 18 degrees off it: across a crease (a prism's edge) the texel is another
// face's, not the one green crossed.
vec3 disp_crossing(inout highp vec3 q, vec3 dir, highp float t, int k, vec3 n_green)
{
    q += t * dir;
    highp float rate = dot(dir, u_fwd) * u_inv_range; // depth per unit of t
    highp float z = layer_depth(pixel_of(q), k);
    if (z != EMPTY && abs(rate) > 1e-6) q += clamp((z - depth_of(q)) / rate, -t, t) * dir;
    vec3 n = normalize(layer_normal_at(q, k));
    n = dot(n, dir) > 0.0 ? -n : n;
    return dot(n, n_green) < 0.95 ? n_green : n;
}
#endif

#if SNELL_INNER_FRESNEL
// The branch reflected inside at the last exit (weight F there): one more
// search from q (in inside gap j) along rdir, refracted out at the surface
// it finds with (1 - F'), whose own reflection F' leaves in its mirror
// direction (the rest of the tree, lumped so that no energy is lost); no
// surface found (no far layer): it leaves along rdir, as the chain does.
// Radiance, before the tint.
vec3 inner_branch(highp vec3 q, vec3 rdir, int j, highp float step, highp float path)
{
    int m, next;
    highp float ta, tb, t_max;
    int kind = search_gap(q, rdir, step, j, m, ta, tb, t_max);
    vec3 n2 = normalize(crossing_normal(q, rdir, kind == 0 ? 2 : kind, j, m, ta, tb, next));
    if (dot(n2, rdir) > 0.0) n2 = -n2;
    vec3 out_dir;
    bool exited = snell_refract(rdir, n2, snell_ior, out_dir);
    float f = kind == 0 ? 0.0 : exited ? snell_fresnel(-dot(rdir, n2), snell_ior, 1.0) : 1.0;
    out_dir = kind == 0 ? rdir : normalize(out_dir);
    vec3 l = (1.0 - f) * snell_env(out_dir) + f * snell_env(snell_reflect(rdir, n2));
#if SNELL_ABSORB
    l *= snell_beer_lambert(u_sigma, path + (kind == 0 ? t_max : tb));
#endif
    return l;
}
#endif

// The colour for one IOR, snell_ior (common/dispersion.glsl calls it).
vec3 snell_glass_trace(out highp vec3 exit_dir)
{
    highp vec3 p1, n1;
    snell_surface(p1, n1);
    highp vec3 v = snell_view_ray(p1);
    vec3 n = normalize(n1);
    if (dot(n, v) > 0.0) n = -n;
    vec3 r = snell_reflect(v, n);
    vec3 dir;
    snell_refract(v, n, 1.0 / snell_ior, dir);
    dir = normalize(dir);
    snell_disp_enter(v, n);
    float fresnel = snell_fresnel(-dot(v, n), 1.0, snell_ior);

    highp vec3 p = p1;
    highp float step = 2.0 * u_bsphere.w / float(SNELL_PEEL_LINEAR);
    highp float path = 0.0;
    vec3 tint = u_tint;
#if SNELL_DISPERSION == 2
    highp vec3 p_red = p, p_blue = p; // where the red and blue rays are, after the green ray's lengths
#endif
    int j = 1;             // the gap the ray is in
    int done = 1;          // interfaces processed (the entry)
#if SNELL_INNER_FRESNEL
    float exit_fresnel = 0.0;   // F at the last exit into air (0: none)
    vec3 exit_in = dir;         // the direction that reached it from inside
    vec3 exit_n = n;
    highp vec3 exit_q = p;      // the last point inside before it
    int exit_gap = 1;
    highp float exit_path = 0.0;
    vec3 exit_tint = tint;
#endif
    for (int it = 0; it < MAX_INTERFACES; it++) {
        bool capped = done >= u_max_interfaces;  // inside at the cap: this search gives the length only
        if (capped && ((j & 1) == 0 || SNELL_ABSORB == 0)) break;
        int m;
        highp float ta, tb, t_max;
        int kind = search_gap(p, dir, step, j, m, ta, tb, t_max);
        if (kind == 0) {
            // no surface before the bounding sphere's far side
            if ((j & 1) == 1) path += t_max;
            break;
        }
        if ((j & 1) == 1) path += tb;
        if (capped) break;
        // the crossed layer's normal where the ray crossed it
        int next;
        vec3 n2 = normalize(crossing_normal(p, dir, kind, j, m, ta, tb, next));
        if (dot(n2, dir) > 0.0) n2 = -n2;   // face the ray
        vec3 out_dir;
        bool inside = (j & 1) == 1;
        bool through = snell_refract(dir, n2, inside ? snell_ior : 1.0 / snell_ior, out_dir);
#if SNELL_DISPERSION == 2
        // red and blue cross the layer near where their own rays are after
        // the green ray's length: its normal there (a curved surface bends
        // them by its change of normal as much as by their IORs); through
        // the silhouette, green's
        mat3 n_rgb = mat3(n2, n2, n2);
        if (kind != 3) {
            int layer = kind == 1 ? m - 1 : m;
            n_rgb[0] = disp_crossing(p_red, snell_disp_dirs[0], tb, layer, n2);
            n_rgb[2] = disp_crossing(p_blue, snell_disp_dirs[2], tb, layer, n2);
        } else {
            p_red += tb * snell_disp_dirs[0];
            p_blue += tb * snell_disp_dirs[2];
        }
        snell_disp_cross3(n_rgb, through, inside);
#else
        snell_disp_cross(n2, through, inside);
#endif
#if SNELL_INNER_FRESNEL
        if (through && inside) {
            exit_fresnel = snell_fresnel(-dot(dir, n2), snell_ior, 1.0);
            exit_in = dir;
            exit_n = n2;
            exit_q = p + ta * dir;       // qa
            exit_gap = j;
            exit_path = path;
            exit_tint = tint;
        }
#endif
        highp vec3 qb = p + tb * dir, qa = p + ta * dir;
        dir = normalize(out_dir);
        done++;
        if (through) {
            j = next;
            p = qb;                          // just beyond the surface
            if (!inside) tint *= u_tint;     // entering again
        } else {
            p = qa;                          // TIR: from the last point inside the gap (3.6)
        }
    }

#if SNELL_ABSORB
    vec3 transmitted = snell_disp_exit(p, dir) * tint * snell_beer_lambert(u_sigma, path);
#else
    vec3 transmitted = snell_disp_exit(p, dir) * tint;
#endif
#if SNELL_INNER_FRESNEL
    // Fresnel inside too (peel param inner_fresnel=on): the last exit transmits
    // 1 - F of the chain and reflects F back in, the strongest branch the
    // chain drops (the first internal reflection at the exit: the ghost);
    // one more search through the layers follows it (inner_branch). Called
    // for every pixel and selected, not branched on: its environment
    // look-ups take implicit derivatives, which GLSL ES 3.0 leaves
    // undefined in non-uniform control flow (8.9).
    vec3 inner = inner_branch(exit_q, snell_reflect(exit_in, exit_n), exit_gap, step, exit_path);
    transmitted = exit_fresnel > 0.0 ? (1.0 - exit_fresnel) * transmitted + exit_fresnel * exit_tint * inner
                                     : transmitted;
#endif
    vec3 reflected = snell_reflection(p1, r);
    exit_dir = dir;
    return mix(transmitted, reflected, fresnel);
}
