// SPDX-License-Identifier: MIT
// exact.frag - exact refraction by BVH ray traversal (methods/exact.c), the
// MATCHED reference's model (src/ref/ref_trace.c) in float: the eye ray
// traced against the mesh's BVH (common/bvh.glsl), Schlick at the entry, TIR
// or refraction at each surface up to u_max_interfaces, Beer-Lambert inside;
// past SNELL_NODE_BUDGET node visits the single-surface answer, marked.
// The design notes (the cap, spaces, the walks): docs/methods.md,
// "shaders_es/exact.frag".
precision highp float;
precision highp int;

#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/surface.glsl"
#include "common/beyond.glsl"
#define SNELL_KERNEL_MAIN 1 // main below: the fallback mark goes after the write
#include "common/dispersion.glsl"

// SNELL_ABSORB (0/1), SNELL_FRESNEL_EXACT, SNELL_EXACT_INNER,
// SNELL_EXACT_REENTRY and the traversal's defines (common/bvh.glsl) are the
// program's variant (methods/exact.c).
#include "common/bvh.glsl"
#ifndef SNELL_EXACT_INNER
#define SNELL_EXACT_INNER 0
#endif
#ifndef SNELL_EXACT_REENTRY
#define SNELL_EXACT_REENTRY 0
#endif
#define SNELL_EXACT_TERMS (SNELL_EXACT_INNER || SNELL_EXACT_REENTRY)
// The three channels' traces in one loop (dispersion) read the G-buffer
// again where they need the surface (snell_surface_frag) rather than keep
// it in registers through the loops.
#if SNELL_DISPERSION == 1 && defined(SNELL_SCREEN_SPACE)
#define EXACT_READS_AGAIN 1
#else
#define EXACT_READS_AGAIN 0
#endif

#include "common/view.glsl"
#include "common/refine.glsl"
uniform vec3 u_sigma;
uniform vec3 u_tint;
uniform highp vec4 u_bsphere;    // world bounding sphere: the fallback's absorption chord
uniform mat4 u_inv_model;        // world -> object
uniform highp mat4 u_model;      // object -> world (object.vert's; the exit point for snell_exit)
uniform int u_max_interfaces;    // 1..MAX_INTERFACES
uniform float u_eps;             // minimum distance of a secondary hit, world units
uniform float u_fallback_mark;   // alpha of a fallback pixel in the RGBA32F exit-direction target
uniform mat3 u_cam_basis;        // view -> world rotation (the view matrix's 3x3, transposed)
uniform vec4 u_cam_proj;         // the projection's P00, P11, P20, P21 (orthographic: P00, P11, -P30, -P31)
uniform vec2 u_pixel_to_ndc;     // 2 / target size in pixels

// The front surface (common/surface.glsl), read once by main before the
// traces: its discard is then outside the loop over the channels.
highp vec3 g_world_pos, g_world_normal;

#ifdef SNELL_SCREEN_OURS
// The hybrid's pass (methods/hybrid.c): its depth test alone passes only
// this object's doubted pixels, so the G-buffer is read as surface.glsl
// reads it but without the object test, whose discard would turn early
// depth tests off (llvmpipe).
void snell_surface_ours(highp vec2 frag, out highp vec3 pos, out highp vec3 normal)
{
    ivec2 px = ivec2(frag);
    highp uvec4 b = uvec4(texelFetch(u_gdepth_id, px, 0) * 255.0 + 0.5);
    highp float depth = float((b.r << 16u) | (b.g << 8u) | b.b) / 16777215.0;
    highp vec4 w = u_inv_view_proj * vec4(frag * u_inv_size * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    highp vec4 g = texelFetch(u_gnormal, px, 0);
    pos = w.xyz / w.w;
    normal = snell_oct_decode(vec2(snell_unpack_unorm16(g.xy), snell_unpack_unorm16(g.zw)) * 2.0 - 1.0);
}
#define snell_surface_frag snell_surface_ours
#define snell_surface(pos, normal) snell_surface_ours(gl_FragCoord.xy, pos, normal)
#endif

#if SNELL_EXACT_TERMS
// What exact_terms_walk leaves for the colour: the chain's entries after the
// first (a tint each), and with SNELL_EXACT_INNER the split's Fresnel (0:
// no split) and the inner branch's end point, direction and length.
int g_entries;
#if SNELL_EXACT_INNER
int g_entry_tri; // the eye ray's triangle (-1: none), its normal made again after the walk
float g_split_fresnel, g_inner_path;
highp vec3 g_inner_p, g_inner_dir;
#endif

// The FULL model's next terms (SNELL_REF_TERM_* in snell_ref.h, whose
// MATCHED reference with the same terms this walk equals): with
// SNELL_EXACT_REENTRY a ray the chain sends out that meets the object again
// re-enters it, wholly; with SNELL_EXACT_INNER the chain's first exit into
// air transmits 1 - F, and its internal reflection F is followed inside
// (total reflections too) to its own exit once the chain has ended, the cap
// counted on from the split. One traversal call site for every ray, as the
// chain's walk. Out: the chain's last point (object space) and direction,
// the entry's normal, the chain's length inside.
void exact_terms_walk(highp vec3 eye, highp vec3 v, highp vec3 world_pos, vec3 n_raster, mat3 inv3,
                      out highp vec3 p, out highp vec3 dir, out vec3 n_entry, out highp float path)
{
    p = (u_inv_model * vec4(eye, 1.0)).xyz;
    dir = v;
    n_entry = vec3(0.0);
    path = 0.0;
    int at = RAY_FIRST;
    // The loop's counts and flags packed in one int (one value live through
    // the loop, as peel.frag's marks): bits 0-3 the interfaces processed on
    // this branch, 4-7 the entries after the first, 8-11 the split's
    // interfaces, 12 inside, 13 split, 14 the inner branch runs, 15 done,
    // 16 on the rays traced (the loop's counter). Not a constant to the compiler (u_max_interfaces & 256 is 0), so that
    // NIR does not split the fields into loop values of their own.
    int marks = u_max_interfaces & 256;
#if SNELL_EXACT_INNER
    // The split: its point, reflected direction, length and triangle. When
    // the chain ends the two change places: the inner branch goes on from
    // them, and they keep the chain's end (its entries in bits 4-7 then).
    // Until the split they hold the rasterised surface's point (object space)
    // and normal, which only the eye ray's miss reads: fewer values live.
    highp vec3 q = (u_inv_model * vec4(world_pos, 1.0)).xyz, rq = n_raster;
    highp float q_path = 0.0;
    int q_at = 0;
    g_split_fresnel = 0.0;
    g_entry_tri = -1;
#define TERMS_LOOP (2 * MAX_INTERFACES + 1)
#else
#define TERMS_LOOP (MAX_INTERFACES + 1)
#endif
    while ((marks & 0x8000) == 0 && marks < TERMS_LOOP << 16) {
        Ray ray = make_ray(p, inv3 * dir);
        float t = 3.0e38;
        int h = closest(ray, u_eps, t, at);
        bool first = marks < 0x10000, hit = h >= 0, inside = (marks & 0x1000) != 0;
        marks += 0x10000;
        // at the cap: inside, the light leaves through the surface ahead in
        // its direction; outside, it sees the object no more
        bool capped = !first && (marks & 15) >= u_max_interfaces;
        bool ends = !first && (!hit || capped);
        vec3 ps, ns;
        surface_at(max(h, 0), ray, dir, ps, ns);
        bool moves = first || (hit && (inside || !capped));
#if SNELL_EXACT_INNER
        p = moves ? (hit ? ps : q) : p;
        path += inside && hit ? t : 0.0;
        vec3 n2 = hit ? ns : rq;
#else
        p = moves ? (hit ? ps : (u_inv_model * vec4(world_pos, 1.0)).xyz) : p;
        path += inside && hit ? t : 0.0;
        vec3 n2 = hit ? ns : n_raster;
#endif
        at = moves ? (hit ? h : RAY_AFTER_MISS) : at;
        vec3 out_dir;
        bool through = snell_refract_sel(dir, n2, inside ? snell_ior : 1.0 / snell_ior, out_dir);
#if SNELL_EXACT_INNER
        g_entry_tri = first ? h : g_entry_tri;
#else
        n_entry = first ? n2 : n_entry;
#endif
        vec3 mirror = snell_reflect(dir, n2);
#if SNELL_EXACT_INNER && SNELL_REFINE
        // refinement (common/refine.glsl): an exit after the split reflects
        // with probability F, else transmits, so that the frames' mean adds
        // the reflections the split drops (the Whitted tree inside)
        bool reflects = !ends && inside && through && (marks & 0x6000) != 0 &&
                        refine_random() < snell_fresnel_sel(-dot(dir, n2), snell_ior, 1.0);
        through = through && !reflects;
        out_dir = reflects ? mirror : out_dir;
#endif
        bool exits = !ends && inside && through;
#if SNELL_EXACT_INNER
        bool splits = exits && (marks & 0x6000) == 0;
        q = splits ? p : q;
        rq = splits ? normalize(mirror) : rq;
        q_path = splits ? path : q_path;
        q_at = splits ? at : q_at;
        g_split_fresnel = splits ? snell_fresnel_sel(-dot(dir, n2), snell_ior, 1.0) : g_split_fresnel;
        marks = splits ? (marks & ~0xf00) | ((marks & 15) + 1) << 8 | 0x2000 : marks;
#endif
        marks += !ends && !first && !inside && through ? 16 : 0;
        dir = ends ? dir : (first && !through ? mirror : normalize(out_dir));
        marks += ends ? 0 : 1;
        marks ^= !ends && through ? 0x1000 : 0;
        // not entered at the eye, out (without re-entry; the inner branch
        // never re-enters), or left for good
#if SNELL_EXACT_REENTRY
        bool stops = ends || (first && !through);
#else
        bool stops = ends || (first && !through) || exits;
#endif
#if SNELL_EXACT_INNER
        stops = stops || ((marks & 0x4000) != 0 && exits);
        // the chain has ended: its end and the split change places
        bool swap = stops && (marks & 0x6000) == 0x2000;
        highp vec3 p_chain = p, dir_chain = dir;
        highp float path_chain = path;
        p = swap ? q : p;
        q = swap ? p_chain : q;
        dir = swap ? rq : dir;
        rq = swap ? dir_chain : rq;
        path = swap ? q_path : path;
        q_path = swap ? path_chain : q_path;
        at = swap ? q_at : at;
        // inside, the inner branch, its interfaces from the split's; the
        // chain's entries stay in bits 4-7
        marks = swap ? (marks & ~0x100f) | (marks >> 8 & 15) | 0x5000 : marks;
        marks |= stops && !swap ? 0x8000 : 0;
#else
        marks |= stops ? 0x8000 : 0;
#endif
    }
    g_entries = marks >> 4 & 15;
#if SNELL_EXACT_INNER
    bool inner = (marks & 0x4000) != 0;
    g_inner_p = p;
    g_inner_dir = dir;
    g_inner_path = path;
    p = inner ? q : p;
    dir = inner ? rq : dir;
    path = inner ? q_path : path;
    g_split_fresnel = inner ? g_split_fresnel : 0.0;
#endif
}
#endif

// The eye ray's point on the lens plane (view space) for the pixel at frag
// (gl_FragCoord.xy).
highp vec3 exact_lens(highp vec2 frag)
{
    vec2 ndc = frag * u_pixel_to_ndc - 1.0;
    return vec3((ndc + u_cam_proj.zw) / u_cam_proj.xy, -1.0);
}

// The colour for one IOR, snell_ior (common/dispersion.glsl); g_visits
// accumulates over the calls, as the budget counts all of a pixel's rays.
// Selects rather than branches throughout (common/optics.glsl: snell_refract_sel).
vec3 snell_glass_trace(out highp vec3 exit_dir)
{
#if EXACT_READS_AGAIN
    // each channel's trace reads the surface again (as after the terms' walk
    // below), so that main's read is not live through the channels' loop
    highp vec3 world_pos, world_normal;
    snell_surface_frag(gl_FragCoord.xy + float(u_max_interfaces >> 11), world_pos, world_normal);
#else
    highp vec3 world_pos = g_world_pos, world_normal = g_world_normal;
#endif
    // The eye ray through the pixel centre from the camera's basis, as the
    // reference's camera rays (the line through the unprojected near and far
    // points): neither the interpolated position nor one reconstructed from
    // the G-buffer's depth through a float inverse of view_proj (off by up
    // to 5e-4 rad here) is on it to float precision.
    highp vec3 lens = exact_lens(gl_FragCoord.xy);
    // orthographic: parallel rays from the lens plane's point
    bool ortho = u_view_axis.w > 0.5;
    // (the orthographic point's products apart from the perspective
    // direction's: lens.xy plus an opaque zero, u_max_interfaces >> 8, at
    // most MAX_INTERFACES; shared, they would round the direction
    // differently from the branches this replaces)
    highp vec3 v_persp = normalize(u_cam_basis * lens);
    highp vec3 eye_ortho = u_eye + u_cam_basis * vec3(lens.xy + float(u_max_interfaces >> 8), 0.0);
    highp vec3 v = ortho ? u_view_axis.xyz : v_persp, eye = ortho ? eye_ortho : u_eye;
    vec3 n_raster = normalize(world_normal);
    n_raster = dot(n_raster, v) > 0.0 ? -n_raster : n_raster;
    mat3 inv3 = mat3(u_inv_model);
#if SNELL_EXACT_TERMS
    vec3 p, dir, n_entry;
    float path;
    exact_terms_walk(eye, v, world_pos, n_raster, inv3, p, dir, n_entry, path);
#if SNELL_EXACT_INNER
    // The front surface, the eye ray, the raster normal and the entry's
    // normal (from its triangle) made again for what follows, with an opaque
    // zero (u_max_interfaces >> 8) so that the compiler does not keep the
    // first ones live through the walk's loop, past V3D's registers: the
    // same operations on the same values, so the same bits.
    highp vec2 frag = gl_FragCoord.xy + float(u_max_interfaces >> 8);
    snell_surface_frag(frag, world_pos, world_normal);
    lens = exact_lens(frag);
    v_persp = normalize(u_cam_basis * lens);
    v = ortho ? u_view_axis.xyz : v_persp;
    n_raster = normalize(world_normal);
    n_raster = dot(n_raster, v) > 0.0 ? -n_raster : n_raster;
    eye_ortho = u_eye + u_cam_basis * vec3(lens.xy + float(u_max_interfaces >> 8), 0.0);
    eye = ortho ? eye_ortho : u_eye;
    vec3 entry_p;
    surface_at(max(g_entry_tri, 0), make_ray((u_inv_model * vec4(eye, 1.0)).xyz, inv3 * v), v, entry_p, n_entry);
    n_entry = g_entry_tri >= 0 ? n_entry : n_raster;
#endif
#else

    // One traversal call site for all the pixel's rays (each call site is a
    // copy of the walk): ray 0 is the eye ray to the entry, its first hit,
    // else (silhouette) the rasterised surface; ray k >= 1 goes inside to
    // interface k, refracted or totally reflected while k <
    // u_max_interfaces; at the cap the light leaves through it in its
    // direction (ref_trace.c m_inside).
    vec3 p = (u_inv_model * vec4(eye, 1.0)).xyz, dir = v, n_entry = vec3(0.0);
    float path = 0.0;
    int at = RAY_FIRST;
    for (int k = 0; k <= MAX_INTERFACES; k++) {
        Ray ray = make_ray(p, inv3 * dir);
        float t = 3.0e38;
        int h = closest(ray, u_eps, t, at);
        if (h < 0 && k > 0) break;                              // open mesh: leaves in its direction
        vec3 ps, ns;
        surface_at(max(h, 0), ray, dir, ps, ns);
#if EXACT_READS_AGAIN
        // the rasterised surface, which the eye ray's miss reads, read here
        // and again after the loop (other opaque zeros: not the values above)
        // rather than kept through the walk's and the channels' loops
        highp vec3 wp, wn;
        snell_surface_frag(gl_FragCoord.xy + float(u_max_interfaces >> 9), wp, wn);
        vec3 nr = normalize(wn);
        nr = dot(nr, dir) > 0.0 ? -nr : nr;
        p = h >= 0 ? ps : (u_inv_model * vec4(wp, 1.0)).xyz;
        vec3 n2 = h >= 0 ? ns : nr;
#else
        p = h >= 0 ? ps : (u_inv_model * vec4(world_pos, 1.0)).xyz;
        vec3 n2 = h >= 0 ? ns : n_raster;
#endif
        at = h >= 0 ? h : RAY_AFTER_MISS;
        path += k > 0 ? t : 0.0;
        if (k > 0 && k >= u_max_interfaces) break;             // the cap
        vec3 out_dir;
        bool through = snell_refract_sel(dir, n2, k == 0 ? 1.0 / snell_ior : snell_ior, out_dir);
        n_entry = k == 0 ? n2 : n_entry;                        // its reflection after the loop
        // the entry with an IOR below 1 at grazing incidence: the mirror, in
        // air; inside: refracted out, or totally reflected
#if EXACT_READS_AGAIN
        vec3 mirror = snell_reflect(dir, n2), out_n = normalize(out_dir); // dir: v at k = 0
#else
        vec3 mirror = snell_reflect(v, n2), out_n = normalize(out_dir);
#endif
        dir = k == 0 && !through ? mirror : out_n;
        if (through != (k == 0)) break;                        // not entered, or out
    }
#if EXACT_READS_AGAIN
    highp vec2 frag = gl_FragCoord.xy + float(u_max_interfaces >> 10);
    snell_surface_frag(frag, world_pos, world_normal);
    lens = exact_lens(frag);
    v_persp = normalize(u_cam_basis * lens);
    v = ortho ? u_view_axis.xyz : v_persp;
    n_raster = normalize(world_normal);
    n_raster = dot(n_raster, v) > 0.0 ? -n_raster : n_raster;
#endif
#endif
    // The entry's reflection and Fresnel from its normal, recomputed here
    // rather than carried through the loop: fewer values live across it.
    vec3 r = snell_reflect(v, n_entry), in_dir;
    bool entered = snell_refract_sel(v, n_entry, 1.0 / snell_ior, in_dir);
    float f_entry = snell_fresnel_sel(-dot(v, n_entry), 1.0, snell_ior);
    float fresnel = entered ? f_entry : 1.0;
    // the budget ran out: single.frag's answer from the rasterised surface
    // (absorption over the bounding-sphere chord); its Fresnel and exit
    // point selected, not branched (fewer values merged: V3D keeps each
    // through the channels' loop), its directions and path in the branch
    // (selected, they would share their products with the entry's and
    // round differently)
    bool over = bvh_over();
    if (over) {
        r = snell_reflect(v, n_raster);
        snell_refract(v, n_raster, 1.0 / snell_ior, dir);
        path = snell_sphere_exit(world_pos, dir, u_bsphere);
    }
    float f_raster = snell_fresnel_sel(-dot(v, n_raster), 1.0, snell_ior);
    fresnel = over ? f_raster : fresnel;
    highp vec3 exit_obj = (u_model * vec4(p, 1.0)).xyz;
    highp vec3 exit_p = over ? world_pos : exit_obj;
    // The look-ups after the branches: their implicit derivatives are
    // undefined in non-uniform control flow (GLSL ES 3.00, 8.9).
#if SNELL_EXACT_TERMS
    vec3 tint = u_tint;
    for (int e = 0; e < MAX_INTERFACES; e++) tint *= e < g_entries ? u_tint : vec3(1.0);
#else
    vec3 tint = u_tint;
#endif
#if SNELL_ABSORB
    vec3 transmitted = snell_exit(exit_p, dir) * tint * snell_beer_lambert(u_sigma, path);
#else
    vec3 transmitted = snell_exit(exit_p, dir) * tint;
#endif
#if SNELL_EXACT_INNER
    // the first exit's internal reflection, followed to its own exit
    // (exact_terms_walk): what it sees past the object, the entry's tint
    vec3 inner_l = beyond_miss((u_model * vec4(g_inner_p, 1.0)).xyz, g_inner_dir) * u_tint;
#if SNELL_ABSORB
    inner_l *= snell_beer_lambert(u_sigma, g_inner_path);
#endif
    float f_split = over ? 0.0 : g_split_fresnel;
    transmitted = (1.0 - f_split) * transmitted + f_split * inner_l;
#endif
    vec3 reflected = snell_reflection(world_pos, r);
    exit_dir = dir;
    return mix(transmitted, reflected, fresnel);
}

void main()
{
    highp vec3 exit_dir;
    snell_surface(g_world_pos, g_world_normal);
#if SNELL_REFINE
    refine_seed();
#endif
#if SNELL_DISPERSION == 1
    // Per channel: the three traces in one loop, not three inlined copies of
    // the walk; red, blue, then green, whose exit direction is written (the
    // order of dispersion.glsl's snell_disp_trace).
    vec3 color = vec3(0.0);
    for (int c = 0; c < 3; c++) {
        // the channel's IOR and colour selected, not masked: no mask live
        // through the trace
        snell_ior = c == 0 ? u_ior_rgb.r : (c == 1 ? u_ior_rgb.b : u_ior_rgb.g);
        vec3 rgb = snell_glass_trace(exit_dir);
        color = vec3(c == 0 ? rgb.r : color.r, c == 2 ? rgb.g : color.g, c == 1 ? rgb.b : color.b);
    }
#else
    vec3 color = snell_disp_trace(exit_dir);
#endif
    snell_write(color, exit_dir);
#ifdef SNELL_OUTPUT_EXIT_DIR_FLOAT
    if (bvh_over()) o_color.a = u_fallback_mark;
#endif
}
