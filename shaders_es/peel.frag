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
// followed by one more search, the interface loop's last iteration); the
// ray is then in gap 1. The ray-height-field search (3.3): march along the ray
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
// The helpers below select rather than branch: every value a branch merges
// inside the interface loop is one more register through all of it on V3D
// (its conditional writes do not end a value's life).
ivec2 pixel_at(highp vec4 c)
{
    highp vec2 w = (c.xy / c.w * 0.5 + 0.5) * u_size;
    bool in_target = c.w > 0.0 && all(greaterThanEqual(w, vec2(0.0))) && all(lessThan(w, u_size));
    return in_target ? ivec2(w) : ivec2(-1);
}

// The pixel p projects to.
ivec2 pixel_of(highp vec3 p)
{
    return pixel_at(u_view_proj * vec4(p, 1.0));
}

highp float layer_depth(ivec2 px, int k)
{
    bool valid = px.x >= 0 && k >= 0 && k < u_layer_count;
    highp uvec4 b = uvec4(texelFetch(u_layers, ivec3(max(px, ivec2(0)), 2 * clamp(k, 0, MAX_LAYERS - 1) + 1), 0) * 255.0 + 0.5);
    return valid && b.a != 0u ? float((b.r << 16u) | (b.g << 8u) | b.b) / 16777215.0 : EMPTY;
}

// Layer k's normal at px: common/pack.glsl's octahedral decode, selected
// rather than branched (the same operations, so the same bits).
vec3 layer_normal(ivec2 px, int k)
{
    highp vec4 g = texelFetch(u_layers, ivec3(px, 2 * k), 0);
    highp vec2 e = vec2(snell_unpack_unorm16(g.xy), snell_unpack_unorm16(g.zw)) * 2.0 - 1.0;
    highp vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    highp vec2 s = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    n.xy = n.z < 0.0 ? (1.0 - abs(n.yx)) * s : n.xy;
    return normalize(n);
}

// Layer k's normal at point q: the four texels around q's position,
// bilinearly, those of the same smooth surface as the texel q projects to
// (depth within a linear step of q's, normal within 18 degrees of that
// texel's: not across a depth jump or a crease, e.g. a cube's edge); that
// texel's alone if none is. Pixel-centre normals alone gave a larger error
// against FULL on every mesh measured (bench/notes/code.md, "peel.frag").
vec3 layer_normal_at(highp vec3 q, int k, out vec3 n0)
{
    highp vec4 c = u_view_proj * vec4(q, 1.0);
    highp vec2 w = (c.xy / c.w * 0.5 + 0.5) * u_size - 0.5;
    ivec2 base = ivec2(floor(w));
    highp vec2 f = w - floor(w);
    highp float z = depth_of(q);
    ivec2 own = pixel_of(q);
    n0 = layer_normal(own, k);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 4; i++) {
        ivec2 px = base + ivec2(i & 1, i >> 1);
        bool use = all(greaterThanEqual(px, ivec2(0))) && all(lessThan(px, ivec2(u_size)));
        px = clamp(px, ivec2(0), ivec2(u_size) - 1);
        highp float dk = layer_depth(px, k);     // before the &&: no short-circuit branch
        use = use && !(abs(dk - z) > 1.0 / float(SNELL_PEEL_LINEAR));
        vec3 n = layer_normal(px, k);
        float wt = ((i & 1) == 1 ? f.x : 1.0 - f.x) * ((i >> 1) == 1 ? f.y : 1.0 - f.y);
        sum += use && dot(n, n0) >= 0.95 ? wt * n : vec3(0.0);
    }
    return dot(sum, sum) > 1e-12 ? sum : n0;
}

// How many layers at px lie in front of depth z: the gap z is in there.
int gap_at(ivec2 px, highp float z)
{
    // written out, not a loop (a loop's count is one more value live
    // through the interface loop on V3D)
    int n = layer_depth(px, 0) < z ? 1 : 0;
    n = layer_depth(px, 1) < z ? 2 : n;
#if MAX_LAYERS > 2
    n = layer_depth(px, 2) < z ? 3 : n;
#endif
#if MAX_LAYERS > 3
    n = layer_depth(px, 3) < z ? 4 : n;
#endif
#if MAX_LAYERS > 4
    n = layer_depth(px, 4) < z ? 5 : n;
#endif
#if MAX_LAYERS > 5
    n = layer_depth(px, 5) < z ? 6 : n;
#endif
#if MAX_LAYERS > 6
    n = layer_depth(px, 6) < z ? 7 : n;
#endif
#if MAX_LAYERS > 7
    n = layer_depth(px, 7) < z ? 8 : n;
#endif
    return n;
}

// MERGE: an inside gap m >= 3 with no layer m - 1 at px: gap m - 2 stands
// for it (its lower layer lo fetched only then).
void merge_step(ivec2 px, inout int m, inout highp float lo)
{
    if ((m & 1) == 1 && m >= 3 && lo == EMPTY) {
        m -= 2;
        lo = layer_depth(px, m - 1);
    }
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
    // at most (MAX_LAYERS - 1) / 2 steps down (gap j <= MAX_LAYERS), written
    // out: no loop whose values stay live through the interface loop on V3D
    merge_step(px, m, lo);
#if MAX_LAYERS > 4
    merge_step(px, m, lo);
#endif
#if MAX_LAYERS > 6
    merge_step(px, m, lo);
#endif
#endif
    hi = layer_depth(px, m);
    bool seen = !((m & 1) == 1 && lo == EMPTY);
    lo = lo == EMPTY ? -1.0 : lo;
    return seen;
}

// 0: z lies in gap j at px; 1: above it (crossed layer m - 1); 2: below it
// (crossed layer m); 3: no such gap here (silhouette).
int classify(ivec2 px, int j, highp float z, out int m)
{
    highp float lo, hi;
    bool seen = gap_bounds(px, j, m, lo, hi);
    return !seen ? 3 : z < lo ? 1 : z > hi ? 2 : 0;
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
    // One loop, one sample (one classify) an iteration: the linear scan's
    // steps until the first one out of the gap, then the bisection's
    // SNELL_PEEL_BINARY halvings of [ta, tb], then (DISCONTINUITY) the
    // scan goes on from the next step. One copy of the classification
    // (texture fetches and all) instead of one for the scan and one per
    // unrolled bisection step; and no branch whose body a software
    // rasteriser runs for the whole block at every step (llvmpipe masks,
    // it does not jump): every pixel takes one sample an iteration.
    // clip position and depth are linear along the ray: one projection per search
    highp vec4 c0 = u_view_proj * vec4(p, 1.0), cd = u_view_proj * vec4(dir, 0.0);
    highp float z0 = depth_of(p), dz = dot(dir, u_fwd) * u_inv_range;
    int i = 1;      // the scan's next step (it stays while bisecting)
    int s = -1;     // bisection steps done; -1: scanning
    while (i <= SNELL_PEEL_LINEAR + 1) {
        highp float t = s < 0 ? min(float(i) * step, t_max) : 0.5 * (ta + tb);
        int mt;
        int kt = classify(pixel_at(c0 + t * cd), j, z0 + t * dz, mt);
        if (s < 0) {
            kind = kt;
            m = mt;
            if (kt == 0) {
                ta = t;
                if (t >= t_max) break;
                i++;
            } else {
                tb = t;      // bisect [ta, tb]: ta in the gap, tb out of it
                s = 0;
            }
            continue;
        }
        if (kt == 0) ta = t;
        else {
            tb = t;
            kind = kt;
            m = mt;
        }
        if (++s < SNELL_PEEL_BINARY) continue;
#if SNELL_PEEL_FIX_DISCONTINUITY
        highp vec3 qa = p + ta * dir, qb = p + tb * dir;
        ivec2 pa = pixel_of(qa), pb = pixel_of(qb);
        int crossed = kind == 1 ? m - 1 : m;
        highp float da = layer_depth(pa, crossed), db = layer_depth(pb, crossed);
        if (kind != 3 && abs(da - db) > 1.0 / float(SNELL_PEEL_LINEAR)) {
            int g = gap_at(pb, depth_of(qb));
            if ((g & 1) == (j & 1)) {
                // case 2: a layer boundary, not a surface; go on in the gap found there
                j = g;
                ta = tb;
                tb = -1.0;
                kind = 0;
                i++;
                s = -1;
                continue;
            }
        }
#endif
        break;
    }
    return kind;
}

// The normal (not normalised) of the surface a search from p along dir
// crossed (kind != 0), and the gap beyond it (next). Out through the
// silhouette (kind 3) its normal is the last pixel's layer nearest the
// point (the side wall there): the texel layer_normal_at reads at qa.
vec3 crossing_normal(highp vec3 p, vec3 dir, int kind, int j, int m, highp float ta, highp float tb, out int next)
{
    highp vec3 qb = p + tb * dir, qa = p + ta * dir;
    bool sil = kind == 3;
    ivec2 pa = pixel_of(qa);
    highp float za = depth_of(qa), d0 = layer_depth(pa, m - 1), d1 = layer_depth(pa, m);
    bool near0 = abs(d0 - za) < abs(d1 - za);
    int layer = sil ? (near0 ? m - 1 : m) : (kind == 1 ? m - 1 : m);
    next = kind == 1 ? j - 1 : j + 1;
    vec3 n0, n = layer_normal_at(sil ? qa : qb, layer, n0);
    return !sil ? n : pa.x >= 0 && (near0 ? d0 : d1) != EMPTY ? n0 : -dir;
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
    vec3 n0, n = normalize(layer_normal_at(q, k, n0));
    n = dot(n, dir) > 0.0 ? -n : n;
    return dot(n, n_green) < 0.95 ? n_green : n;
}
#endif

// common/optics.glsl's snell_refract, selected rather than branched (the
// same operations, so the same bits).
bool refract_sel(vec3 i, vec3 n, float eta, out vec3 t)
{
    float c = -dot(n, i);
    float k = 1.0 - eta * eta * (1.0 - c * c);
    t = k < 0.0 ? snell_reflect(i, n) : eta * i + (eta * c - sqrt(k)) * n;
    return !(k < 0.0);
}

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
    // the reflection before the loop: three values through it, not six
    // (its direction and origin)
    vec3 reflected = snell_reflection(p1, r);

    highp vec3 p = p1;
    highp float step = 2.0 * u_bsphere.w / float(SNELL_PEEL_LINEAR);
    highp float path = 0.0;
#if SNELL_DISPERSION == 2
    highp vec3 p_red = p, p_blue = p; // where the red and blue rays are, after the green ray's lengths
#endif
    int j = 1;             // the gap the ray is in
#if SNELL_INNER_FRESNEL
    // Fresnel inside too (peel param inner_fresnel=on): the last exit into
    // air transmits 1 - F of the chain and reflects F back in, the
    // strongest branch the chain drops (the first internal reflection at
    // the exit: the ghost); one more search follows it from the last point
    // inside before the exit, in the loop's last iteration (inner): its
    // surface refracts it out with 1 - F', its own reflection F' leaves in
    // its mirror direction (the rest of the tree, lumped so that no energy
    // is lost); no surface found (no far layer): it leaves along its way,
    // as the chain does. Searched for every pixel and selected, not
    // branched on: its environment look-ups (after the loop) take implicit
    // derivatives, which GLSL ES 3.0 leaves undefined in non-uniform
    // control flow (8.9).
    // The last exit: its F (0: none), the direction reflected back in, the
    // last point inside before it, its gap, the path and entries up to it;
    // the inner search starts from them and leaves its own end in them
    // (exit_r and exit_q its two directions, exit_path its length): no
    // register more through the loop. The counts are packed in one int (one
    // value live through the loop, not five): bits 0-3 the entries after the
    // first, 4-7 those up to the last exit, 8-11 its gap, 12: the chain
    // ended, 13: the inner search.
    float exit_fresnel = 0.0, inner_fresnel = 0.0;
    vec3 exit_r = snell_reflect(dir, n);
    highp vec3 exit_q = p;
    highp float exit_path = 0.0;
    int marks = 1 << 8;
#define M_ENTRIES (marks & 15)
#define M_INNER ((marks & 0x2000) != 0)
#else
    int entries = 0;
#endif
    // Values that change in the loop are selected, not assigned in branches
    // (each such value would stay live through the whole loop on V3D).
    for (int it = 0; it < MAX_INTERFACES + SNELL_INNER_FRESNEL; it++) {
        // interfaces processed: the entry and one an iteration before this one
        bool capped = it + 1 >= u_max_interfaces;  // inside at the cap: this search gives the length only
        bool ended = it == MAX_INTERFACES || (capped && ((j & 1) == 0 || SNELL_ABSORB == 0));
#if SNELL_INNER_FRESNEL
        // the chain ended: the inner search from the last exit (in exit_q,
        // exit_r, exit_path and its gap; where it ends goes there too)
        marks |= (ended || (marks & 0x1000) != 0) && !M_INNER ? 0x2000 : 0;
        bool inner = M_INNER;
        capped = capped && !inner;
        highp vec3 q = inner ? exit_q : p;
        vec3 d = inner ? exit_r : dir;
        int g = inner ? (marks >> 8) & 15 : j;
#else
        if (ended) break;
        highp vec3 q = p;
        vec3 d = dir;
        int g = j;
#endif
        int m;
        highp float ta, tb, t_max;
        int kind = search_gap(q, d, step, g, m, ta, tb, t_max);
        bool inside = (g & 1) == 1;
        // no surface before the bounding sphere's far side: the length to it
        highp float len = inside ? (kind == 0 ? t_max : tb) : 0.0;
#if SNELL_INNER_FRESNEL
        exit_path += inner ? len : 0.0;
        path += inner ? 0.0 : len;
        if (!inner && (kind == 0 || capped)) {
            marks |= 0x1000;
            continue;  // the next iteration is the inner search
        }
#else
        path += len;
        if (kind == 0 || capped) break;
#endif
        // the crossed layer's normal where the ray crossed it
        int next;
        vec3 n2 = normalize(crossing_normal(q, d, kind == 0 ? 2 : kind, g, m, ta, tb, next));
        n2 = dot(n2, d) > 0.0 ? -n2 : n2;   // face the ray
        vec3 out_dir;
        bool through = refract_sel(d, n2, inside ? snell_ior : 1.0 / snell_ior, out_dir);
#if SNELL_INNER_FRESNEL
        if (inner) {
            // the inner branch's way out: exit_r and exit_q take its two
            // directions
            inner_fresnel = kind == 0 ? 0.0 : through ? snell_fresnel(-dot(d, n2), snell_ior, 1.0) : 1.0;
            exit_q = snell_reflect(d, n2);
            exit_r = kind == 0 ? d : normalize(out_dir);
            break;
        }
#endif
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
        bool leaves = through && inside;
        exit_fresnel = leaves ? snell_fresnel(-dot(dir, n2), snell_ior, 1.0) : exit_fresnel;
        exit_r = leaves ? snell_reflect(dir, n2) : exit_r;
        exit_q = leaves ? p + ta * dir : exit_q;   // qa
        exit_path = leaves ? path : exit_path;
        marks = leaves ? (marks & 15) * 17 | g << 8 : marks;
#endif
        // through: just beyond the surface, in the next gap (entering again:
        // one more tint); TIR: from the last point inside the gap (3.6)
        p += (through ? tb : ta) * dir;
        dir = normalize(out_dir);
#if SNELL_INNER_FRESNEL
        marks += through && !inside ? 1 : 0;
#else
        entries += through && !inside ? 1 : 0;
#endif
        j = through ? next : g;                  // (g: the search may have moved on to another gap)
    }
    // the tints: u_tint at the entry and at each entry after it (the same
    // products, in the same order, as multiplying at each)
    vec3 tint = u_tint;
#if SNELL_INNER_FRESNEL
    int entries = M_ENTRIES, exit_entries = (marks >> 4) & 15;
    vec3 exit_tint = u_tint;
#endif
    for (int e = 1; e <= entries; e++) {
        tint *= u_tint;
#if SNELL_INNER_FRESNEL
        exit_tint = e == exit_entries ? tint : exit_tint;
#endif
    }

#if SNELL_INNER_FRESNEL
    // the inner branch's two directions are in exit_r and exit_q now, its
    // length in exit_path
    vec3 inner_l = (1.0 - inner_fresnel) * snell_env(exit_r) + inner_fresnel * snell_env(exit_q);
#if SNELL_ABSORB
    inner_l *= snell_beer_lambert(u_sigma, exit_path);
#endif
#endif
#if SNELL_ABSORB
    vec3 transmitted = snell_disp_exit(p, dir) * tint * snell_beer_lambert(u_sigma, path);
#else
    vec3 transmitted = snell_disp_exit(p, dir) * tint;
#endif
#if SNELL_INNER_FRESNEL
    transmitted = exit_fresnel > 0.0 ? (1.0 - exit_fresnel) * transmitted + exit_fresnel * exit_tint * inner_l
                                     : transmitted;
#undef M_ENTRIES
#undef M_INNER
#endif
    exit_dir = dir;
    return mix(transmitted, reflected, fresnel);
}
