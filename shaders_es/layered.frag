// SPDX-License-Identifier: MIT
// layered.frag - multi-layer refraction through layered distance cube maps
// (Umenhoffer, Patow and Szirmay-Kalos 2007, GPU Gems 3 ch. 17): the refracted
// ray is marched in SNELL_LINEAR steps through the layers (baked by
// layered_bake.frag, methods/layered.c), SNELL_BINARY bisections find each
// crossing, where it refracts or reflects, re-entries included, up to
// u_max_interfaces; snell_exit past it. STAR: a convex mesh in one layer, Newton
// steps instead. Layers and search in object space about u_centre with a world
// ray parameter. More: docs/methods.md, "Design notes by file".
precision highp float;

#include "common/optics.glsl"
#include "common/env.glsl"
#include "common/output.glsl"
#include "common/surface.glsl"
#include "common/beyond.glsl"
#include "common/dispersion.glsl"

#define MAX_INTERFACES 10    // SNELL_LAYERED_MAX_INTERFACES
// A convex mesh whose layers hold one surface in every direction: no march (next_crossing).
#define STAR (SNELL_LAYERS == 1 && SNELL_REENTRY == 0)
// SNELL_LAYERS (1..8), SNELL_LINEAR (1..64), SNELL_BINARY (1..16),
// SNELL_ABSORB (0/1), SNELL_REENTRY (0/1: the mesh is not convex, so a ray
// that left may meet it again) and SNELL_INNER_FRESNEL (0/1: Fresnel at the
// last exit too, its internal reflection followed one march more) are
// defined by the program's variant (methods/layered.c).

#include "common/view.glsl"
uniform vec3 u_sigma;
uniform vec3 u_tint;
uniform mat3 u_normal_matrix;    // object -> world normals

uniform highp sampler2DArray u_layers;  // RGBA16F: object-space normal, distance / u_radius (4: none);
                                        // slice face * u_stride + layer
uniform int u_stride;            // layers baked a face (SNELL_LAYERS of them hold something)
uniform int u_dist_base;         // the first distance slice: slice u_dist_base + face * u_groups + g holds
uniform int u_groups;            // layers 4g..4g+3's distances (4: none), four layers in one look-up
uniform highp mat4 u_inv_model;  // world -> object
uniform highp mat4 u_model;      // object -> world
uniform highp vec3 u_centre;     // object space
uniform highp float u_radius;    // object units: every vertex lies within it
uniform int u_max_interfaces;    // 1..MAX_INTERFACES

// Where direction q (from the centre) looks its layers up: (s, t) in face
// 0's slice of its face, by the GL cube-map face selection (GLES 3.0 table
// 3.21), which the bake's face cameras render (snell__cube_face_view_proj).
// Looked up filtered (Umenhoffer's distance maps are): the distance is then
// continuous across texels, so the count of surfaces below a point changes
// only where the ray meets the interpolated surface (nearest texels made it
// change wherever a surface runs at a grazing angle to the centre's rays).
// Selected, not branched: a branch's merged values would hold V3D registers
// through the whole march that calls it (bench/notes/device_tuning.md).
highp vec3 layer_coord(highp vec3 q)
{
    highp vec3 a = abs(q);
    bool on_x = a.x >= a.y && a.x >= a.z, on_y = !on_x && a.y >= a.z;
    highp float ma = on_x ? a.x : on_y ? a.y : a.z;
    int face = on_x ? (q.x > 0.0 ? 0 : 1) : on_y ? (q.y > 0.0 ? 2 : 3) : (q.z > 0.0 ? 4 : 5);
    highp float sc = on_x ? (q.x > 0.0 ? -q.z : q.z) : on_y ? q.x : (q.z > 0.0 ? q.x : -q.x);
    highp float tc = on_y ? (q.y > 0.0 ? q.z : -q.z) : -q.y;
    return vec3(vec2(sc, tc) / max(ma, 1e-30) * 0.5 + 0.5, float(face));
}

#define GROUPS ((SNELL_LAYERS + 3) / 4)

// Surfaces closer to the centre than q along q's direction: the distance
// slices, four layers a look-up (layers beyond SNELL_LAYERS hold 4 there).
int below(highp vec3 q)
{
    highp vec3 c = layer_coord(q);
    highp float r = length(q) / u_radius;
    c.z = float(u_dist_base) + c.z * float(u_groups);
    int n = 0;
    for (int g = 0; g < GROUPS; g++) {
        highp vec4 d = textureLod(u_layers, c + vec3(0.0, 0.0, float(g)), 0.0);
        n += int(dot(vec4(lessThan(d, vec4(r))), vec4(1.0)));
    }
    return n;
}

// The layer at q's direction whose surface lies nearest q (its index and
// its object-space normal, not normalised).
highp vec3 nearest_normal(highp vec3 q, out int index)
{
    highp vec3 c = layer_coord(q);
#if SNELL_LAYERS == 1
    index = 0;
    return textureLod(u_layers, vec3(c.xy, c.z * float(u_stride)), 0.0).xyz;
#endif
    highp float r = length(q) / u_radius, best = 8.0;
    highp vec3 cd = vec3(c.xy, float(u_dist_base) + c.z * float(u_groups));
    index = 0;
    for (int g = 0; g < GROUPS; g++) {
        highp vec4 e = abs(textureLod(u_layers, cd + vec3(0.0, 0.0, float(g)), 0.0) - r);
        for (int k = 0; k < 4; k++)
            if (4 * g + k < SNELL_LAYERS && e[k] < best) {
                best = e[k];
                index = 4 * g + k;
            }
    }
    return textureLod(u_layers, vec3(c.xy, c.z * float(u_stride) + float(index)), 0.0).xyz;
}

// Distance along p + t d (p about the centre) to the far side of the sphere
// of radius rad about the centre.
highp float sphere_far(highp vec3 p, highp vec3 d, highp float rad)
{
    highp float a2 = dot(d, d), b = dot(p, d), pp = dot(p, p);
    return max((-b + sqrt(max(b * b - a2 * (pp - rad * rad), 0.0))) / a2, 0.0);
}

// ... to the bounding sphere's far side.
highp float sphere_exit(highp vec3 p, highp vec3 d)
{
    return sphere_far(p, d, u_radius);
}

#if STAR
// A convex mesh that one layer holds, the centre inside it (SNELL_REENTRY 0:
// the analysis says convex): every direction from the centre has one
// surface, so the exit of a ray from inside is its one crossing, and a texel
// holds both what the search needs and the normal there. Its own trace below,
// no march: the general one's code is not compiled in (llvmpipe runs a
// branch's code under an empty mask, so dead code costs time;
// bench/notes/code.md, "layered.frag").

// Layer 0 in q's direction: the object-space normal (not normalised) and
// the distance / u_radius, filtered.
highp vec4 texel0(highp vec3 q)
{
    highp vec3 c = layer_coord(q);
    return textureLod(u_layers, vec3(c.xy, c.z * float(u_stride)), 0.0);
}

// The exit of p + t d (p inside, about the centre; d object space per world
// length) and the normal there (object space, not normalised): Newton steps
// on the baked surface's tangent planes. From the bounding sphere's far side,
// each step looks up the layer in the direction of the current point, so the
// surface point x = |q|^-1 q * distance and its normal n, and goes to where
// the ray meets the plane through x normal to n. A convex body lies behind
// each of its tangent planes, so a step never lands inside it; a planar face
// is met exactly once its texel is looked up, a smooth surface converges
// quadratically (a sphere in one step, to within the bake's precision). A
// plane the ray runs along (|n.d| tiny) gives the sphere of the texel's
// distance instead. `steps` steps (a compile-time constant), one look-up
// each; the normal is the last one's. p lies on the surface (the entry, or
// an exit or bounce point), so the first look-up is where the ray meets the
// sphere through p about the centre: on a round mesh that is next to the
// exit, where the bounding sphere's far side is a step away. chord() is in
// closed form (two square roots fewer than sphere_far). That point may lie
// inside the mesh (a cube's entry mid-face); if the plane it looks up is one
// the ray moves away from, the first step goes to the bounding sphere's far
// side instead: any later plane is met outside the mesh or on it (the
// texel-distance sphere there trapped the cube's rays on a wrong face;
// bench/notes/code.md, "layered.frag").
// Where p + t d meets the sphere through p about the centre again (inside
// the bounding sphere: p lies on the mesh).
highp float chord(highp vec3 p, highp vec3 d)
{
    return max(-2.0 * dot(p, d) / dot(d, d), 0.0);
}

highp float convex_exit(highp vec3 p, highp vec3 d, out highp vec3 n, const int steps)
{
    highp float t_max = sphere_exit(p, d), t = chord(p, d);
    n = d;
    for (int i = 0; i < steps; i++) {
        highp vec3 q = p + t * d;
        highp vec4 s = texel0(q);
        highp float r = s.w * u_radius;
        highp vec3 x = q * (r / max(length(q), 1e-30 * u_radius));
        highp float dn = dot(s.xyz, d);
        n = s.xyz;
        t = dn > 1e-3 * length(d) ? dot(s.xyz, x - p) / dn : i == 0 ? t_max : sphere_far(p, d, r);
        t = clamp(t, 0.0, t_max);
    }
    return t;
}

#if SNELL_INNER_FRESNEL
// Its light is F of the pixel's: half the steps (at least one) find its exit,
// as accurately as all of them. With iterations 1 no plane step: where it
// meets the sphere through the exit point (chord), with that texel's normal
// (bench/notes/code.md, "layered.frag").
#define INNER_STEPS ((SNELL_BINARY + 1) / 2)
// The branch reflected inside at the exit (weight F there): one more search
// from the exit point q along rdir, refracted out at the next surface with
// (1 - F'), its own reflection F' leaving in the mirror direction (the rest
// of the tree lumped, so that no energy is lost), as cubemap.frag's
// inner_branch. Radiance, before the tint. Its environment look-ups take
// the nearest texel (snell_env_nearest): its light is weak, so filtering it
// costs time for no visible change (bench/notes/code.md, "layered.frag").
vec3 inner_branch(highp vec3 q, vec3 rdir, float path)
{
    highp vec3 d = mat3(u_inv_model) * rdir, n;
#if SNELL_BINARY == 1
    highp float t = chord(q, d);
    n = texel0(q + t * d).xyz;
#else
    highp float t = convex_exit(q, d, n, INNER_STEPS);
#endif
    vec3 n3 = normalize(u_normal_matrix * n);
    if (dot(n3, rdir) > 0.0) n3 = -n3;
    vec3 out_dir;
    vec3 mirror = snell_reflect(rdir, n3);
    bool exited = snell_refract(rdir, n3, snell_ior, out_dir);
    float f = exited ? snell_fresnel(-dot(rdir, n3), snell_ior, 1.0) : 1.0;
    vec3 l = (1.0 - f) * snell_env_nearest(normalize(out_dir)) + f * snell_env_nearest(mirror);
#if SNELL_ABSORB
    l *= snell_beer_lambert(u_sigma, path + t);
#endif
    return l;
}
#endif

#if SNELL_DISPERSION == 2
// One-path dispersion: the red or blue ray from q along d over the green
// ray's length t, and the layer's normal where it got to, facing its ray
// (as cubemap.frag's disp_exit). Updates q.
vec3 disp_normal(inout highp vec3 q, highp vec3 d, highp float t, vec3 dir)
{
    q += t * d;
    vec3 n = normalize(u_normal_matrix * texel0(q).xyz);
    return dot(n, dir) > 0.0 ? -n : n;
}
#endif

// The colour for one IOR, snell_ior (common/dispersion.glsl calls it): the
// entry, the exit (or, on total internal reflection, the next one, up to
// u_max_interfaces surfaces), and with SNELL_INNER_FRESNEL the exit's
// internal reflection.
vec3 snell_glass_trace(out highp vec3 exit_dir)
{
    highp vec3 world_pos, world_normal;
    snell_surface(world_pos, world_normal);
    highp vec3 v = snell_view_ray(world_pos);
    vec3 n = normalize(world_normal);
    if (dot(n, v) > 0.0) n = -n;
    vec3 r = snell_reflect(v, n);
    highp vec3 dir;
    snell_refract(v, n, 1.0 / snell_ior, dir);
    dir = normalize(dir);
    snell_disp_enter(v, n);
    float fresnel = snell_fresnel(-dot(v, n), 1.0, snell_ior);

    mat3 inv3 = mat3(u_inv_model);
    highp vec3 p = (u_inv_model * vec4(world_pos, 1.0)).xyz - u_centre;
    highp float path = 0.0;
#if SNELL_DISPERSION == 2
    highp vec3 p_red = p, p_blue = p;
#endif
#if SNELL_INNER_FRESNEL
    float exit_fresnel = 0.0; // F at the exit into air (0: none)
    vec3 exit_in = dir;       // the direction that reached it from inside
    vec3 exit_n = n;
    float exit_path = 0.0;
#endif
    // interface 1 was the entry; pass k looks for interface k; past
    // u_max_interfaces (inside: capped) the length to the next surface only
    for (int k = 2; k <= MAX_INTERFACES + 1; k++) {
        if (k > u_max_interfaces && SNELL_ABSORB == 0) break;
        highp vec3 d = inv3 * dir, on;
        highp float t = convex_exit(p, d, on, SNELL_BINARY);
        p += t * d;
        path += t;
        if (k > u_max_interfaces) break;
        vec3 n2 = normalize(u_normal_matrix * on);
        if (dot(n2, dir) > 0.0) n2 = -n2; // face the ray (it comes from inside)
        highp vec3 out_dir;
        bool through = snell_refract(dir, n2, snell_ior, out_dir);
#if SNELL_DISPERSION == 2
        vec3 n_red = disp_normal(p_red, inv3 * snell_disp_dirs[0], t, snell_disp_dirs[0]);
        vec3 n_blue = disp_normal(p_blue, inv3 * snell_disp_dirs[2], t, snell_disp_dirs[2]);
        snell_disp_cross3(mat3(n_red, n2, n_blue), through, true);
#else
        snell_disp_cross(n2, through, true);
#endif
#if SNELL_INNER_FRESNEL
        if (through) {
            exit_fresnel = snell_fresnel(-dot(dir, n2), snell_ior, 1.0);
            exit_in = dir;
            exit_n = n2;
            exit_path = path;
        }
#endif
        dir = normalize(out_dir);
        if (through || (k == u_max_interfaces && SNELL_ABSORB == 0)) break;
    }
    highp vec3 exit_p = (u_model * vec4(p + u_centre, 1.0)).xyz;
#if SNELL_ABSORB
    vec3 transmitted = snell_disp_exit(exit_p, dir) * u_tint * snell_beer_lambert(u_sigma, path);
#else
    vec3 transmitted = snell_disp_exit(exit_p, dir) * u_tint;
#endif
#if SNELL_INNER_FRESNEL
    // called for every pixel and selected, not branched on (GLSL ES 3.0 8.9:
    // its environment look-ups take implicit derivatives)
    vec3 inner = inner_branch(p, snell_reflect(exit_in, exit_n), exit_path);
    transmitted = exit_fresnel > 0.0 ? (1.0 - exit_fresnel) * transmitted + exit_fresnel * u_tint * inner
                                     : transmitted;
#endif
    vec3 reflected = snell_reflection(world_pos, r);
    exit_dir = dir;
    return mix(transmitted, reflected, fresnel);
}

#else // !STAR: the march through the layers
// The first crossing along p + t d, 0 < t <= t_max, of a surface, starting
// with c0 surfaces below: the bracket [lo, hi] around it (lo on the start's
// side, with c0 surfaces below there on return, hi beyond, with c_hi
// surfaces below there); false if none. A change of the count by an even
// number is no surface: it is where the ray crosses the edge of the cone
// that a fold (two surfaces that begin together, seen from the centre)
// hides, so the march goes on from there.
bool next_crossing(highp vec3 p, highp vec3 d, inout int c0, highp float t_max, out highp float lo,
                   out highp float hi, out int c_hi)
{
    highp float step = t_max / float(SNELL_LINEAR);
    lo = 0.0;
    hi = t_max;
    c_hi = c0;
    for (int j = 1; j <= SNELL_LINEAR; j++) {
        highp float t = float(j) * step;
        int c = below(p + t * d);
        if (c == c0) {
            lo = t;
            continue;
        }
        hi = t;
        c_hi = c;
        for (int i = 0; i < SNELL_BINARY; i++) {
            highp float m = 0.5 * (lo + hi);
            int cm = below(p + m * d);
            if (cm == c0) {
                lo = m;
            } else {
                hi = m;
                c_hi = cm;
            }
        }
        // a surface crossed changes the count's parity (inside to outside); an
        // even change is a fold's rim swept past from the centre, not a crossing
        if ((abs(c_hi - c0) & 1) == 1) return true;
        c0 = c;
        lo = t;
    }
    return false;
}

#if SNELL_DISPERSION == 2
// One-path dispersion: the red or blue ray from q along d (object space per
// world length) over the green ray's length t, and the normal of the layer
// nearest where it got to, facing its ray: where that channel meets the
// surface, without a march of its own (as cubemap.frag's disp_exit). Updates q.
vec3 disp_normal(inout highp vec3 q, highp vec3 d, highp float t, vec3 dir)
{
    int layer;
    q += t * d;
    vec3 n = normalize(u_normal_matrix * nearest_normal(q, layer));
    return dot(n, dir) > 0.0 ? -n : n;
}
#endif

#if SNELL_INNER_FRESNEL
// The branch reflected inside at the last exit (weight F there): one more
// march from the last point inside, q (c surfaces below it), along rdir,
// refracted out at the next surface with (1 - F'), its own reflection F'
// leaving in the mirror direction (the rest of the tree lumped, so that no
// energy is lost), as cubemap.frag's inner_branch, its environment nearest
// as the convex program's. Radiance, before the tint.
vec3 inner_branch(highp vec3 q, vec3 rdir, int c, float path)
{
    highp vec3 d = mat3(u_inv_model) * rdir;
    highp float t_max = sphere_exit(q, d), lo, hi;
    int c_hi, layer;
    float t = t_max;
    vec3 n3 = rdir;
    if (next_crossing(q, d, c, t_max, lo, hi, c_hi)) {
        t = 0.5 * (lo + hi);
        n3 = normalize(u_normal_matrix * nearest_normal(q + t * d, layer));
    }
    if (dot(n3, rdir) > 0.0) n3 = -n3;
    vec3 out_dir;
    vec3 mirror = snell_reflect(rdir, n3);
    bool exited = snell_refract(rdir, n3, snell_ior, out_dir);
    float f = exited ? snell_fresnel(-dot(rdir, n3), snell_ior, 1.0) : 1.0;
    vec3 l = (1.0 - f) * snell_env_nearest(normalize(out_dir)) + f * snell_env_nearest(mirror);
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
    highp vec3 dir;
    snell_refract(v, n, 1.0 / snell_ior, dir);
    dir = normalize(dir);
    snell_disp_enter(v, n);
    float fresnel = snell_fresnel(-dot(v, n), 1.0, snell_ior);

    mat3 inv3 = mat3(u_inv_model);
    highp vec3 p = (u_inv_model * vec4(world_pos, 1.0)).xyz - u_centre;
    highp vec3 d = inv3 * dir;
    // The count just inside the entry, sampled a little way in (2% of the
    // radius): the entry surface's own texel distance is not reliable as
    // close to it as the surface point itself. Measured at 96x96 against
    // FULL (test_layered), mean degrees: torus 11.5, goblet 6.4, open sphere
    // 2.75; the count inferred from the layer nearest the entry and the
    // ray's heading gave 14.1, 10.1, 2.7; the offset capped at half the first
    // march step (for walls thinner than it) 11.7, 7.0, 3.4.
    int c = below(p + 0.02 * u_radius / length(d) * d);
    bool inside = true;
    highp float path = 0.0;
    vec3 tint = u_tint;
    int done = 1; // interfaces processed: the entry
#if SNELL_DISPERSION == 2
    highp vec3 p_red = p, p_blue = p; // where the red and blue rays are, after the green ray's lengths
#endif
#if SNELL_INNER_FRESNEL
    float exit_fresnel = 0.0;   // F at the last exit into air (0: none)
    vec3 exit_in = dir;         // the direction that reached it from inside
    vec3 exit_n = n;
    highp vec3 exit_q = p;      // the last point inside before it
    int exit_c = c;
    float exit_path = 0.0;
    vec3 exit_tint = tint;
#endif
    for (int k = 0; k < MAX_INTERFACES; k++) {
        bool capped = done >= u_max_interfaces; // inside at the cap: the length to the next surface only
        if (capped && (!inside || SNELL_ABSORB == 0)) break;
        highp float t_max = sphere_exit(p, d), lo, hi;
        int c_hi;
        if (!next_crossing(p, d, c, t_max, lo, hi, c_hi)) {
            // nothing before the bounding sphere's far side: out in the air,
            // the ray leaves from its last exit; inside, through an open
            // mesh's hole
            if (inside) {
                path += t_max;
                p += t_max * d;
            }
            break;
        }
        highp float t = 0.5 * (lo + hi);
        if (inside) path += t;
        if (capped) {
            p += t * d;
            break;
        }
        int layer;
        vec3 n2 = normalize(u_normal_matrix * nearest_normal(p + t * d, layer));
        if (dot(n2, dir) > 0.0) n2 = -n2; // face the ray
        highp vec3 out_dir;
        bool through = snell_refract(dir, n2, inside ? snell_ior : 1.0 / snell_ior, out_dir);
#if SNELL_DISPERSION == 2
        // red and blue meet the surface near where their own rays are after
        // the green ray's length: the layers' normal there (a curved surface
        // bends them by its change of normal as much as by their IORs)
        vec3 n_red = disp_normal(p_red, inv3 * snell_disp_dirs[0], t, snell_disp_dirs[0]);
        vec3 n_blue = disp_normal(p_blue, inv3 * snell_disp_dirs[2], t, snell_disp_dirs[2]);
        snell_disp_cross3(mat3(n_red, n2, n_blue), through, inside);
#else
        snell_disp_cross(n2, through, inside);
#endif
#if SNELL_INNER_FRESNEL
        if (through && inside) {
            exit_fresnel = snell_fresnel(-dot(dir, n2), snell_ior, 1.0);
            exit_in = dir;
            exit_n = n2;
            exit_q = p + lo * d;
            exit_c = c;
            exit_path = path;
            exit_tint = tint;
        }
#endif
        // the next march starts on the side the ray goes on in: just beyond
        // the surface (refracted through), or just before it (reflected)
        if (through) {
            p += hi * d;
            c = c_hi;
            inside = !inside;
            if (inside) tint *= u_tint; // entering again
        } else {
            p += lo * d;
        }
        dir = normalize(out_dir);
        d = inv3 * dir;
        done++;
        // out in the air: a convex mesh is not met again (SNELL_REENTRY 0),
        // nor anything after the last interface
        if (!inside && (SNELL_REENTRY == 0 || done >= u_max_interfaces)) break;
    }
    highp vec3 exit_p = (u_model * vec4(p + u_centre, 1.0)).xyz;
#if SNELL_ABSORB
    vec3 transmitted = snell_disp_exit(exit_p, dir) * tint * snell_beer_lambert(u_sigma, path);
#else
    vec3 transmitted = snell_disp_exit(exit_p, dir) * tint;
#endif
#if SNELL_INNER_FRESNEL
    // Called for every pixel and selected, not branched on: its environment
    // look-ups take implicit derivatives, which GLSL ES 3.0 leaves undefined
    // in non-uniform control flow (8.9).
    vec3 inner = inner_branch(exit_q, snell_reflect(exit_in, exit_n), exit_c, exit_path);
    transmitted = exit_fresnel > 0.0 ? (1.0 - exit_fresnel) * transmitted + exit_fresnel * exit_tint * inner
                                     : transmitted;
#endif
    vec3 reflected = snell_reflection(world_pos, r);
    exit_dir = dir;
    return mix(transmitted, reflected, fresnel);
}
#endif // STAR
