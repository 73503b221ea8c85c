// layered.frag - multi-layer refraction through layered distance cube maps
// (Umenhoffer, Patow and Szirmay-Kalos 2007, "Robust multiple specular
// reflections and refractions", GPU Gems 3 ch. 17). The layers (baked once
// per mesh version by layered_bake.frag, methods/layered.c) hold, per
// direction from the analysed centre, the first SNELL_LAYERS surfaces'
// normals and distances. From the entry, the refracted ray is marched in
// SNELL_LINEAR steps to the bounding sphere's far side; a sample's count of
// surfaces closer to the centre than itself along its direction changes where
// the ray crosses one, and SNELL_BINARY bisections on that count find where.
// There the crossed layer's normal refracts the ray out (or reflects it on
// total internal reflection) and the march goes on, outside too: a concave
// mesh's re-entries are followed (FULL's dominant branch: Schlick at the
// entry, transmission on, TIR bounces), up to u_max_interfaces surfaces. The
// final ray leaves through snell_exit (common/beyond.glsl).
//
// Spaces: layers and search in object space about u_centre, the ray's
// parameter a world length (d = M^-1 * unit world direction, as cubemap.frag),
// so absorption and steps are right for any model matrix.
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
#define STAR_LINEAR 3
// SNELL_LAYERS (1..8), SNELL_LINEAR (1..64), SNELL_BINARY (1..16),
// SNELL_ABSORB (0/1), SNELL_REENTRY (0/1: the mesh is not convex, so a ray
// that left may meet it again) and SNELL_INNER_FRESNEL (0/1: Fresnel at the
// last exit too, its internal reflection followed one march more) are
// defined by the program's variant (methods/layered.c).

uniform highp vec3 u_eye;
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
highp vec3 layer_coord(highp vec3 q)
{
    highp vec3 a = abs(q);
    highp float sc, tc, ma;
    int face;
    if (a.x >= a.y && a.x >= a.z) {
        ma = a.x;
        face = q.x > 0.0 ? 0 : 1;
        sc = q.x > 0.0 ? -q.z : q.z;
        tc = -q.y;
    } else if (a.y >= a.z) {
        ma = a.y;
        face = q.y > 0.0 ? 2 : 3;
        sc = q.x;
        tc = q.y > 0.0 ? q.z : -q.z;
    } else {
        ma = a.z;
        face = q.z > 0.0 ? 4 : 5;
        sc = q.z > 0.0 ? q.x : -q.x;
        tc = -q.y;
    }
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
// Layer 0's distance (/ u_radius) in q's direction.
highp float dist0(highp vec3 q)
{
    highp vec3 c = layer_coord(q);
    return textureLod(u_layers, vec3(c.xy, float(u_dist_base) + c.z * float(u_groups)), 0.0).x;
}
#endif

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
#if STAR
    // A convex mesh that one layer holds (the centre inside it): from inside
    // (c0 0) its one surface ahead, where f = |q| / radius - the layer's
    // distance at q turns positive: STAR_LINEAR steps bracket it, then
    // SNELL_BINARY steps of regula falsi (Illinois) on f, which converge in
    // one or two on a sphere (a cube's faces need the 6 of the default:
    // test_stress' grazing cube, 1.6 degrees mean with 3). The start counts
    // as inside. Measured (snell-bench, sphere 512^2, aa 4, vs FULL, beside
    // single): 1 step 40.69 dB at 3.12x single, 6: 40.95 dB, 4.10x; the
    // 24-step march and 6 bisections before: 40.96 dB at 18.3x. (Layer 0
    // also as a cube map, for the sampler's own face selection: seamless
    // filtering bends the normals across a cube's edges, 1.34 degrees mean
    // on that grazing cube against 0.88.)
    if (c0 == 0) {
        highp float a = 0.0, fa = -1e-3, b = t_max, fb = 1.0;
        for (int j = 1; j <= STAR_LINEAR; j++) {
            highp float t = t_max * float(j) / float(STAR_LINEAR);
            highp vec3 q = p + t * d;
            highp float f = length(q) / u_radius - dist0(q);
            if (f >= 0.0) {
                b = t;
                fb = f;
                break;
            }
            a = t;
            fa = f;
        }
        int side = 0;
        for (int i = 0; i < SNELL_BINARY; i++) {
            highp float t = clamp(a - fa * (b - a) / (fb - fa), a, b);
            highp vec3 q = p + t * d;
            highp float f = length(q) / u_radius - dist0(q);
            if (f < 0.0) {
                a = t;
                fa = f;
                if (side == -1) fb *= 0.5;
                side = -1;
            } else {
                b = t;
                fb = f;
                if (side == 1) fa *= 0.5;
                side = 1;
            }
        }
        lo = a;
        hi = b;
        c_hi = 1;
        return true;
    }
#endif
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
        // measured at 96x96 against FULL (test_layered): the horse's median
        // 18.1 degrees when every change was a surface, 12.7 since
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
// energy is lost), as cubemap.frag's inner_branch. Radiance, before the tint.
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
    highp vec3 v = normalize(world_pos - u_eye);
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
#if STAR
    int c = 0; // inside the one layer
#else
    int c = below(p + 0.02 * u_radius / length(d) * d);
#endif
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
