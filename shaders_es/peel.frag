// SPDX-License-Identifier: MIT
// peel.frag - multi-layer refraction from depth-peeled layers (Wang 2014,
// seed 001 3.3-3.6): refract at the front surface, then march the refracted
// ray through the layers (u_layers, methods/peel.c) with a linear search and
// bisection, refracting or totally reflecting at each crossed layer, up to
// u_max_interfaces surfaces; the seed's fixes (SNELL_PEEL_FIX_*) compile-time.
// The design notes (gaps, the search, the fixes, precision): docs/methods.md,
// "shaders_es/peel.frag".
precision highp float;
precision highp int;

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
    highp vec2 folded = (1.0 - abs(n.yx)) * s;
    n.xy = n.z < 0.0 ? folded : n.xy;
    return normalize(n);
}

// Layer k's normal at point q: the four texels around q's position,
// bilinearly, those of the same smooth surface as the texel q projects to
// (depth within a linear step of q's, normal within 18 degrees of that
// texel's: not across a depth jump or a crease, e.g. a cube's edge); that
// texel's alone if none is. Pixel-centre normals alone gave a larger error
// against FULL on every mesh measured (bench/notes/code.md, "peel.frag").
// One texel's share: its weighted normal, or none.
vec3 normal_tap(ivec2 px, int k, highp float z, vec3 n0, float wt)
{
    bool use = all(greaterThanEqual(px, ivec2(0))) && all(lessThan(px, ivec2(u_size)));
    px = clamp(px, ivec2(0), ivec2(u_size) - 1);
    highp float dk = layer_depth(px, k);     // before the &&: no short-circuit branch
    use = use && !(abs(dk - z) > 1.0 / float(SNELL_PEEL_LINEAR));
    vec3 n = layer_normal(px, k);
    return use && dot(n, n0) >= 0.95 ? wt * n : vec3(0.0);
}

vec3 layer_normal_at(highp vec3 q, int k, out vec3 n0)
{
    highp vec4 c = u_view_proj * vec4(q, 1.0);
    highp vec2 w = (c.xy / c.w * 0.5 + 0.5) * u_size - 0.5;
    ivec2 base = ivec2(floor(w));
    highp vec2 f = w - floor(w);
    highp float z = depth_of(q);
    ivec2 own = pixel_of(q);
    n0 = layer_normal(own, k);
    // A loop, not written out (four taps at once hold more values than the
    // registers of V3D and Mali-G52 have beside the interface loop's), and
    // one the compiler does not unroll: its count is not a constant to it
    // (u_max_interfaces >> 8 is 0: at most MAX_INTERFACES; not the opaque
    // zero the interface loop starts from, which would be one value live
    // through that loop).
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 4 + (u_max_interfaces >> 8); i++) {
        ivec2 px = base + ivec2(i & 1, i >> 1);
        float wt = ((i & 1) == 1 ? f.x : 1.0 - f.x) * ((i >> 1) == 1 ? f.y : 1.0 - f.y);
        sum += normal_tap(px, k, z, n0, wt);
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
// for it (its lower layer lo fetched only then). Only lo is written in the
// branch (m is selected): one value merged, one register through the
// interface loop on V3D.
void merge_step(ivec2 px, inout int m, inout highp float lo)
{
    bool merge = (m & 1) == 1 && m >= 3 && lo == EMPTY;
    m = merge ? m - 2 : m;
    if (merge) lo = layer_depth(px, m - 1);
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

// The search's state through its loop, packed in one int (one register
// through the interface loop on V3D, not five): bits 0-7 i (the scan's
// next step), 8-12 s + 1 (bisection steps done; 0: scanning), 13-14 the
// crossing's kind, 15: done, 16-19 m, 20-23 j (the top: read without a
// mask). The loop ends at its top, where its values are those it carries:
// no copies of them for its exit.
#define SEARCH_PACK(i, s, kind, m, j) ((i) | ((s) + 1) << 8 | (kind) << 13 | (m) << 16 | (j) << 20)

// The search (3.3) from p along dir in gap j, out to the bounding sphere
// grown by a step (t_max). Returns the crossing's kind (classify; 0: none
// before t_max); ta: the last ray parameter in the gap, tb: the first out of
// it; m: the gap whose layers stood for j there. DISCONTINUITY may move the
// ray to another gap of the same medium (j).
int search_gap(highp vec3 p, vec3 dir, inout int j, out int m, out highp float ta,
               out highp float tb, out highp float t_max)
{
    // the search range: to the far side of the bounding sphere grown by
    // one step, so that the last sample lies clearly beyond a surface on
    // the sphere (a tessellated sphere's vertices are on it): a point just
    // beyond it can still test as in front of it, against the depth at its
    // pixel's centre
    // the step: the bounding diameter / SNELL_PEEL_LINEAR (from the uniform
    // here, in the loop: not a value live through it)
    highp float step = 2.0 * u_bsphere.w / float(SNELL_PEEL_LINEAR);
    highp vec3 oc = p - u_bsphere.xyz;
    highp float b = dot(oc, dir), rs = u_bsphere.w + step;
    t_max = max(-b + sqrt(max(b * b - dot(oc, oc) + rs * rs, 0.0)), 0.0);
    // tb: none yet; the range's end, not a constant (from a constant
    // start NIR makes ta + tb a loop value of its own, see marks below)
    ta = 0.0;
    tb = t_max;
    // One loop, one sample (one classify) an iteration: the linear scan's
    // steps until the first one out of the gap, then the bisection's
    // SNELL_PEEL_BINARY halvings of [ta, tb], then (DISCONTINUITY) the
    // scan goes on from the next step. One copy of the classification
    // (texture fetches and all) instead of one for the scan and one per
    // unrolled bisection step; and no branch whose body a software
    // rasteriser runs for the whole block at every step (llvmpipe masks,
    // it does not jump): every pixel takes one sample an iteration. The
    // state is selected, not assigned in branches, and packed (st): on V3D
    // every value the loop merges stays live through the interface loop.
    // clip position and depth are linear along the ray: one projection per search
    highp vec4 c0 = u_view_proj * vec4(p, 1.0), cd = u_view_proj * vec4(dir, 0.0);
    highp float z0 = depth_of(p), dz = dot(dir, u_fwd) * u_inv_range;
    int st = SEARCH_PACK(1, -1, 0, j, j);
    for (;;) {
        if ((st & 1 << 15) != 0) break;
        int i = st & 255, s = (st >> 8 & 31) - 1, kind = st >> 13 & 3, g = st >> 20;
        int m = st >> 16 & 15;
        bool scan = s < 0;
        highp float t_scan = min(float(i) * step, t_max);
        highp float t = scan ? t_scan : 0.5 * (ta + tb);
        int mt;
        int kt = classify(pixel_at(c0 + t * cd), g, z0 + t * dz, mt);
        bool in_gap = kt == 0;
        // the scan: in the gap, on to the next step; out of it, bisect [ta,
        // tb] (ta in the gap, tb out of it). The bisection: in the gap, ta
        // moves; out of it, tb and the crossing (kind, m)
        ta = in_gap ? t : ta;
        tb = in_gap ? tb : t;
        kind = scan || !in_gap ? kt : kind;
        m = scan || !in_gap ? mt : m;
        bool done = scan && in_gap && t >= t_max;
        i += scan && in_gap ? 1 : 0;
        s = scan ? (in_gap ? -1 : 0) : s + 1;
        bool bisected = !scan && s >= SNELL_PEEL_BINARY;
#if SNELL_PEEL_FIX_DISCONTINUITY
        // the gap found afresh at the far pixel, where a crossing's layer
        // jumps there (case 2: a layer boundary, not a surface) and the
        // medium is the same: the search goes on from it (-1: not). The
        // only value written in a branch.
        int moved = -1;
        if (bisected && kind != 3) {
            highp vec3 qa = p + ta * dir, qb = p + tb * dir;
            ivec2 pa = pixel_of(qa), pb = pixel_of(qb);
            int crossed = kind == 1 ? m - 1 : m;
            highp float da = layer_depth(pa, crossed), db = layer_depth(pb, crossed);
            if (abs(da - db) > 1.0 / float(SNELL_PEEL_LINEAR)) {
                int ng = gap_at(pb, depth_of(qb));
                moved = (ng & 1) == (g & 1) ? ng : -1;
            }
        }
        bool restart = moved >= 0;
        g = restart ? moved : g;
        ta = restart ? tb : ta;
        tb = restart ? -1.0 : tb;
        kind = restart ? 0 : kind;
        i += restart ? 1 : 0;
        s = restart ? -1 : s;
        done = done || (bisected && !restart);
#else
        done = done || bisected;
#endif
        st = SEARCH_PACK(i, s, kind, m, g) | (done || i > SNELL_PEEL_LINEAR + 1 ? 1 << 15 : 0);
    }
    m = st >> 16 & 15;
    j = st >> 20;
    return st >> 13 & 3;
}

// The normal (not normalised) of the surface a search from p along dir
// crossed (kind != 0; 0 gives layer m's). Out through the
// silhouette (kind 3) its normal is the last pixel's layer nearest the
// point (the side wall there): the texel layer_normal_at reads at qa.
vec3 crossing_normal(highp vec3 p, vec3 dir, int kind, int m, highp float ta, highp float tb)
{
    highp vec3 qb = p + tb * dir, qa = p + ta * dir;
    bool sil = kind == 3;
    ivec2 pa = pixel_of(qa);
    highp float za = depth_of(qa), d0 = layer_depth(pa, m - 1), d1 = layer_depth(pa, m);
    bool near0 = abs(d0 - za) < abs(d1 - za);
    int layer = sil ? (near0 ? m - 1 : m) : (kind == 1 ? m - 1 : m);
    // decided before the taps: one value live through them, not three
    bool own = pa.x >= 0 && (near0 ? d0 : d1) != EMPTY;
    vec3 n0, n = layer_normal_at(sil ? qa : qb, layer, n0);
    return !sil ? n : own ? n0 : -dir;
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
    // the entry's Fresnel after the loop, from its cosine: its constants
    // (1 / (1 + ior), ...) would be shared with the loop's exit Fresnel and
    // live through the loop
    float fresnel = snell_fresnel(-dot(v, n), 1.0, snell_ior);
    // the reflection before the loop: three values through it, not six
    // (its direction and origin)
    vec3 reflected = snell_reflection(p1, r);

    highp vec3 p = p1;
    highp float path = 0.0;
#if SNELL_DISPERSION == 2
    highp vec3 p_red = p, p_blue = p; // where the red and blue rays are, after the green ray's lengths
#endif
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
    // The last exit: its F (0: none), the direction reflected back in
    // (exit_r), the last point inside before it (exit_q), the path up to it,
    // its gap and entries (marks). When the chain ends (at the end of an
    // iteration) the two change places: the inner search is from p along
    // dir as every search, the chain's end waits in exit_q, exit_r and
    // exit_path, and the inner search leaves its two directions in dir and
    // p. No register more through the loop: on V3D every value it carries
    // is live through all of it, and so is any value derived from one at
    // the top of an iteration and read at its end (a copy of p or dir).
    float exit_fresnel = 0.0, inner_fresnel = 0.0;
    vec3 exit_r = snell_reflect(dir, n);
    highp vec3 exit_q = p;
    highp float exit_path = 0.0;
#endif
    // The loop's counts, packed in one int (one value live through the
    // loop, not five): bits 0-3 the entries after the first; with
    // SNELL_INNER_FRESNEL 4-7 those up to the last exit, 8-11 its gap, 12:
    // the chain ended (this iteration is the inner search); 14: done (the loop ends at its top, where its values
    // are those it carries: no copies of them for its exit); 16-19 the gap
    // the ray is in (j), 20-23 the interfaces processed (the entry and one
    // an iteration before this one). Not a constant to the compiler (u_max_interfaces & 256 is 0:
    // at most MAX_INTERFACES): from a constant start NIR's
    // opt_split_alu_of_phi (nir_opt_if) makes each field the loop reads a
    // loop value of its own, undoing the packing.
    int marks = (1 << 8 | 1 << 16) + (u_max_interfaces & 256);
    // Values that change in the loop are selected, not assigned in branches
    // (each such value would stay live through the whole loop on V3D).
    for (;;) {
        if ((marks & 0x4000) != 0) break;
#if !SNELL_INNER_FRESNEL
        int it = marks >> 20, j = marks >> 16 & 15;
        if (it == MAX_INTERFACES || (it + 1 >= u_max_interfaces && ((j & 1) == 0 || SNELL_ABSORB == 0))) break;
#endif
        // (what the iteration reads from marks is read where it is needed:
        // not a value live through the search and the normal's taps)
        int g = marks >> 16 & 15, m;
        highp float ta, tb, t_max;
        int kind = search_gap(p, dir, g, m, ta, tb, t_max);
        // the crossed layer's normal where the ray crossed it (kind 0, none:
        // taken as 2, its value unused); what else the iteration reads of the
        // search's results is read after it
        vec3 n2 = normalize(crossing_normal(p, dir, kind, m, ta, tb));
        n2 = dot(n2, dir) > 0.0 ? -n2 : n2;   // face the ray
        bool inside = (g & 1) == 1;
        // no surface before the bounding sphere's far side: the length to it
        path += inside ? (kind == 0 ? t_max : tb) : 0.0;
        bool capped = (marks >> 20) + 1 >= u_max_interfaces;  // inside at the cap: this search gives the length only
#if SNELL_INNER_FRESNEL
        // the chain ends here (no surface, or the cap): the next iteration is
        // the inner search, this one changes nothing more (advance: the
        // chain goes on)
        bool inner = (marks & 0x1000) != 0;
        bool advance = !inner && !(kind == 0 || capped);
#else
        bool advance = !(kind == 0 || capped);
#endif
        vec3 out_dir;
        bool through = snell_refract_sel(dir, n2, inside ? snell_ior : 1.0 / snell_ior, out_dir);
        vec3 out_n = normalize(out_dir);
#if SNELL_DISPERSION == 2
        if (advance) {
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
        }
#else
        snell_disp_cross(n2, through, inside);
#endif
        // through: just beyond the surface, in the next gap (entering again:
        // one more tint); TIR: from the last point inside the gap (3.6)
        highp vec3 p_next = advance ? p + (through ? tb : ta) * dir : p;
        vec3 dir_next = advance ? out_n : dir;
        marks += advance && through && !inside ? 1 : 0;
        // the gap beyond the surface, or g again (the search may have moved on
        // to another gap)
        int nj = through ? (kind == 1 ? g - 1 : g + 1) : g;
#if SNELL_INNER_FRESNEL
        // an exit into air: the last exit so far
        bool leaves = advance && through && inside;
        float f_out = snell_fresnel_sel(-dot(dir, n2), snell_ior, 1.0);
        vec3 back = snell_reflect(dir, n2);
        exit_fresnel = leaves ? f_out : exit_fresnel;
        vec3 exit_r_next = leaves ? back : exit_r;
        // qa, not the value crossing_normal had (which would be live through
        // the taps): ta plus an opaque zero (u_max_interfaces >> 8: at most
        // MAX_INTERFACES), so that the compiler cannot merge the two
        highp vec3 exit_q_next = leaves ? p + (ta + float(u_max_interfaces >> 8)) * dir : exit_q;
        highp float exit_path_next = leaves ? path : exit_path;
        marks = leaves ? (marks & ~0xfff) | (marks & 15) * 17 | g << 8 : marks;
        marks = (advance ? (marks & ~0xf0000) | nj << 16 : marks) + (1 << 20);
        // the inner search's way out: its two directions go to dir and p
        // (inner read again from marks: a new value of it, not one live
        // through the taps)
        inner = (marks & 0x1000) != 0;
        inner_fresnel = inner ? (kind == 0 ? 0.0 : through ? f_out : 1.0) : inner_fresnel;
        vec3 dir_inner = kind == 0 ? dir : out_n;
        // the chain ends here, or at the cap at the next iteration's start:
        // the last exit and the chain's end change places, the next
        // iteration is the inner search (from the last exit's gap)
        int it_next = marks >> 20, j_next = marks >> 16 & 15;
        bool ended = it_next == MAX_INTERFACES ||
                     (it_next + 1 >= u_max_interfaces && ((j_next & 1) == 0 || SNELL_ABSORB == 0));
        bool swap = !inner && (!advance || ended);
        p = inner ? back : swap ? exit_q_next : p_next;
        exit_q = swap ? p_next : exit_q_next;
        dir = inner ? dir_inner : swap ? exit_r_next : dir_next;
        exit_r = swap ? dir_next : exit_r_next;
        highp float path_next = path;
        path = swap ? exit_path_next : path_next;
        exit_path = swap ? path_next : exit_path_next;
        marks = swap ? (marks & ~0xf0000) | (marks >> 8 & 15) << 16 | 0x1000 : marks;
        marks |= inner ? 0x4000 : 0;
#else
        p = p_next;
        dir = dir_next;
        marks = (advance ? (marks & ~0xf0000) | nj << 16 : marks | 0x4000) + (1 << 20);
#endif
    }
#if SNELL_INNER_FRESNEL
#define CHAIN_P exit_q
#define CHAIN_DIR exit_r
#define CHAIN_PATH exit_path
#else
#define CHAIN_P p
#define CHAIN_DIR dir
#define CHAIN_PATH path
#endif
    // the tints: u_tint at the entry and at each entry after it (the same
    // products, in the same order, as multiplying at each)
    vec3 tint = u_tint;
    int entries = marks & 15;
#if SNELL_INNER_FRESNEL
    int exit_entries = (marks >> 4) & 15;
    vec3 exit_tint = u_tint;
#endif
    for (int e = 1; e <= entries; e++) {
        tint *= u_tint;
#if SNELL_INNER_FRESNEL
        exit_tint = e == exit_entries ? tint : exit_tint;
#endif
    }

#if SNELL_INNER_FRESNEL
    // the inner branch's two directions are in dir and p now, its length in
    // path
    vec3 inner_l = (1.0 - inner_fresnel) * snell_env(dir) + inner_fresnel * snell_env(p);
#if SNELL_ABSORB
    inner_l *= snell_beer_lambert(u_sigma, path);
#endif
#endif
#if SNELL_ABSORB
    vec3 transmitted = snell_disp_exit(CHAIN_P, CHAIN_DIR) * tint * snell_beer_lambert(u_sigma, CHAIN_PATH);
#else
    vec3 transmitted = snell_disp_exit(CHAIN_P, CHAIN_DIR) * tint;
#endif
#if SNELL_INNER_FRESNEL
    transmitted = exit_fresnel > 0.0 ? (1.0 - exit_fresnel) * transmitted + exit_fresnel * exit_tint * inner_l
                                     : transmitted;
#endif
    exit_dir = CHAIN_DIR;
#undef CHAIN_P
#undef CHAIN_DIR
#undef CHAIN_PATH
    return mix(transmitted, reflected, fresnel);
}
