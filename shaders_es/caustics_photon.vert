// SPDX-License-Identifier: MIT
// caustics_photon.vert - one photon per texel of the light's view of a glass
// object (Wyman & Davis 2006, caustic maps): it enters where the nearest-
// surface map says and leaves by the depth maps, the mesh's BVH or the chain
// of casters (SNELL_PHOTON_BVH, SNELL_PHOTON_CHAIN), then lands on the
// receiver plane or an opaque receiver (u_target) as a 4 x 4 tent splat.
// Its reference is ref_caustics.c. The design notes (the three paths, thin
// walls, receivers, flux): docs/ARCHITECTURE.md, "shaders_es/caustics_photon.vert".
precision highp float;
precision highp sampler2D;

#include "common/optics.glsl"

uniform sampler2D u_front_n, u_front_z, u_back_n, u_back_z;
uniform mat4 u_light_vp;      // world -> the light's clip space (orthographic)
uniform mat4 u_light_inv;     // its inverse
uniform int u_size;           // the maps' texels per side = photons per side
uniform vec3 u_dir;           // unit direction the light travels (directional)
uniform int u_spot;           // 1: a spot light at u_pos, its photons leaving it
uniform vec3 u_pos;           // the spot's position
uniform vec3 u_axis;          // the spot's unit axis
uniform float u_cos_cone;     // cosine of its half angle
uniform float u_tan;          // tangent of the half angle of the light's view of the object
uniform float u_ior;
uniform vec3 u_sigma;         // Beer-Lambert absorption per world unit
uniform float u_thickness;    // > 0: a thin wall of this thickness (world units); 0: solid
uniform vec3 u_tint;
uniform vec3 u_flux;          // light colour * photon area / texel area (irradiance one photon adds);
                              // spot: the area on the view's image plane at distance 1
uniform vec4 u_plane;         // y, centre x, centre z, extent (half side)
uniform float u_reach;        // the longest chord: the bounding sphere's diameter
uniform int u_target;         // 0: the receiver plane's light map; 1: the opaque receivers' caustic map
uniform int u_has_plane;      // 1: the receiver plane u_plane ends the photons' way
uniform int u_recv;           // 1: opaque receivers in u_recv_z stop the photons
uniform sampler2D u_recv_z;   // their nearest depth per texel of the light frame (1: none)
uniform mat4 u_recv_vp;       // world -> the light frame's clip space
uniform vec4 u_recv_lin;      // near, far, 1 = perspective (spot), texel side (world; spot: at distance 1)
uniform float u_recv_reach;   // the longest way marched when no plane ends it
uniform vec3 u_flux_recv;     // u_flux's share per light-frame texel (u_target 1)
#if SNELL_PHOTON_BVH
// the exact method's BVH of the mesh (common/bvh.glsl, one texture per mesh
// version from the prepared cache) and the path's parameters
#define SNELL_NODE_BUDGET u_node_budget
uniform int u_node_budget;    // node visits of all a photon's rays (material.exact.budget)
uniform mat4 u_model, u_inv_model;
uniform int u_max_interfaces; // 1..MAX_INTERFACES (material.exact.interfaces)
uniform float u_eps;          // minimum distance of a secondary hit, world units
#include "common/bvh.glsl"
#endif
#ifdef SNELL_PHOTON_CHAIN
// the casters whose beams overlap, in sequence (render/caustics_photons.c chain):
// their world-space BVH (identity matrices), a triangle entry's mesh
// triangle in its v0's w, object k's triangles u_chain_first[k] ..
// u_chain_first[k + 1] - 1; their materials
uniform int u_chain_self;                      // this photon's caster among them
uniform int u_chain_first[SNELL_PHOTON_CHAIN + 1];
uniform float u_chain_ior[SNELL_PHOTON_CHAIN], u_chain_thick[SNELL_PHOTON_CHAIN], u_chain_eps[SNELL_PHOTON_CHAIN];
uniform vec3 u_chain_sigma[SNELL_PHOTON_CHAIN], u_chain_tint[SNELL_PHOTON_CHAIN];
uniform int u_chain_maxif[SNELL_PHOTON_CHAIN]; // their exact.max_interfaces
uniform vec4 u_chain_sphere;                   // holding them all: directional photons start before it
#endif

out vec4 v_flux;

// The exit: a few linear steps bracket the first point past the far
// surface (one crossing for a convex object), bisection refines it.
const int LINEAR_STEPS = 8;
const int BISECT_STEPS = 14;

// Covered-texel bilinear look-up of a map at light uv: rgb of the normals,
// or r of the depth; w = summed weight of covered texels (0: none).
vec4 fetch4(sampler2D cov, sampler2D tex, vec2 uv, out float w)
{
    vec2 t = uv * float(u_size) - 0.5;
    ivec2 b = ivec2(floor(t));
    vec2 f = t - floor(t);
    vec4 acc = vec4(0.0);
    w = 0.0;
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 q = clamp(b + o, ivec2(0), ivec2(u_size - 1));
        float wk = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        if (texelFetch(cov, q, 0).a > 0.5) {
            acc += wk * texelFetch(tex, q, 0);
            w += wk;
        }
    }
    return w > 0.0 ? acc / w : acc;
}

// Light-space depth of the ray point minus the far surface's there (> 0:
// past it), the far depths read bilinearly over covered texels (the far map
// is cleared to depth 0, which no surface has).
float past_back(vec3 p)
{
    vec4 c = u_light_vp * vec4(p, 1.0);
    vec3 s = c.xyz / c.w * 0.5 + 0.5;
    vec2 t = s.xy * float(u_size) - 0.5;
    ivec2 b = ivec2(floor(t));
    vec2 f = t - floor(t);
    float z = 0.0, w = 0.0;
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float zk = texelFetch(u_back_z, clamp(b + o, ivec2(0), ivec2(u_size - 1)), 0).r;
        float wk = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y) * (zk > 0.0 ? 1.0 : 0.0);
        z += wk * zk;
        w += wk;
    }
    if (w <= 0.0) return 1.0; // off the object: out
    return s.z - z / w;
}

// The light frame's linear depth (world units along its axis) of a depth-buffer value.
float recv_lin(float z01)
{
    float n = u_recv_lin.x, f = u_recv_lin.y;
    return u_recv_lin.z > 0.5 ? n * f / (f - z01 * (f - n)) : n + z01 * (f - n);
}

// x: the linear depth of p past the nearest opaque receiver at its texel (> 0:
// behind it; -1: no receiver there), y: that receiver's linear depth.
vec2 recv_gap(vec3 p)
{
    vec4 c = u_recv_vp * vec4(p, 1.0);
    if (c.w <= 0.0) return vec2(-1.0, 0.0);
    vec3 s = c.xyz / c.w * 0.5 + 0.5;
    if (s.x < 0.0 || s.y < 0.0 || s.x >= 1.0 || s.y >= 1.0) return vec2(-1.0, 0.0);
    ivec2 n = textureSize(u_recv_z, 0);
    float z = texelFetch(u_recv_z, ivec2(s.xy * vec2(n)), 0).r;
    if (z >= 1.0) return vec2(-1.0, 0.0);
    float b = recv_lin(z);
    return vec2(recv_lin(s.z) - b, b);
}

// The first point of q + d l, 0 <= l <= lmax, behind the opaque receivers
// (linear steps, then bisection): l, or -1 if none. on: whether it is their
// surface (the depths meet there within 3 texels), not a step behind an
// edge into a face the light does not see (where the photon stops unseen).
const int RECV_STEPS = 32;
const int RECV_BISECT = 12;
float recv_march(vec3 q, vec3 d, float lmax, out bool on)
{
    float lo = 0.0, hi = -1.0;
    on = false;
    for (int k = 0; k <= RECV_STEPS; k++) {
        float l = lmax * float(k) / float(RECV_STEPS);
        if (hi < 0.0) {
            if (recv_gap(q + d * l).x > 0.0) hi = l;
            else lo = l;
        }
    }
    if (hi < 0.0) return -1.0;
    if (hi == 0.0) return 0.0; // leaves the glass behind a receiver: stopped
    for (int k = 0; k < RECV_BISECT; k++) {
        float m = 0.5 * (lo + hi);
        if (recv_gap(q + d * m).x > 0.0) hi = m;
        else lo = m;
    }
    vec2 g = recv_gap(q + d * hi);
    on = g.x < 3.0 * u_recv_lin.w * (u_recv_lin.z > 0.5 ? g.y : 1.0);
    return hi;
}

// The depth maps' one crossing: in at p (normal n facing the light's ray
// dir: Schlick f1, Snell), out where the march finds the far surface (f2,
// its normal from the far map; TIR drops the photon), len the way inside; q
// and t2 the exit and the direction out. false: dropped.
bool depth_path(vec3 p, vec3 n, vec3 dir, out float f1, out float f2, out float len, out vec3 q, out vec3 t2)
{
    f2 = 0.0;
    len = 0.0;
    q = p;
    t2 = dir;
    f1 = snell_fresnel_schlick(dot(n, -dir), 1.0, u_ior);
    vec3 t;
    if (!snell_refract(dir, n, 1.0 / u_ior, t)) return false;
    // linear search for the first point past the far surface, then bisection
    float lo = 0.0, hi = -1.0;
    for (int k = 1; k <= LINEAR_STEPS; k++) {
        float l = u_reach * float(k) / float(LINEAR_STEPS);
        if (hi < 0.0) {
            if (past_back(p + t * l) > 0.0) hi = l;
            else lo = l;
        }
    }
    if (hi < 0.0) return false; // never left (an open or concave mesh): dropped
    for (int k = 0; k < BISECT_STEPS; k++) {
        float m = 0.5 * (lo + hi);
        if (past_back(p + t * m) > 0.0) hi = m;
        else lo = m;
    }
    len = 0.5 * (lo + hi);
    q = p + t * len;
    vec4 c = u_light_vp * vec4(q, 1.0);
    float cw;
    vec3 nb = fetch4(u_back_n, u_back_n, c.xy / c.w * 0.5 + 0.5, cw).xyz * 2.0 - 1.0;
    if (cw <= 0.0 || dot(nb, nb) < 1e-8) return false;
    nb = normalize(nb);
    if (dot(nb, t) < 0.0) nb = -nb; // outward, along the ray
    f2 = snell_fresnel_schlick(dot(nb, t), u_ior, 1.0);
    return snell_refract(t, -nb, u_ior, t2); // TIR: dropped
}

// A thin wall crossed at normal n by the photon's ray dir: the slab's transmittance.
vec3 wall(vec3 n, vec3 dir)
{
    vec3 rs, ts;
    snell_thin_slab(dot(n, dir), u_ior, u_sigma, u_thickness, rs, ts);
    return ts;
}

// A thin wall's photon by the depth maps, straight on: in through the
// nearest surface (p, normal n), out through the farthest at the same texel
// ij of the light's view (the photon's ray is that texel's) where it is
// another surface (a closed mesh; an open one's single wall is in both maps
// at the same depth zf). e: the walls' transmittance, the tint at the second
// (u_flux holds the first); q the last wall.
void thin_maps(vec3 p, vec3 n, vec3 dir, ivec2 ij, float zf, out vec3 q, out vec3 e)
{
    float zb = texelFetch(u_back_z, ij, 0).r;
    vec3 nb = texelFetch(u_back_n, ij, 0).xyz * 2.0 - 1.0;
    e = wall(n, dir);
    q = p;
    if (zb > zf) {
        vec4 w = u_light_inv * vec4(vec3((vec2(ij) + 0.5) / float(u_size), zb) * 2.0 - 1.0, 1.0);
        q = w.xyz / w.w;
        e *= u_tint * wall(normalize(nb), dir);
    }
}

// The photon of vertex id: its texel ij of the light's view, where it enters
// the nearest surface (p, light depth z, normal n facing its ray dir) and
// its share of u_flux (spot: the solid angle; 0: outside the cone). false:
// it misses the object. Read again after the BVH's loop at id plus an opaque
// zero (the same read would be kept live through the loop instead).
bool photon_entry(int id, out ivec2 ij, out float z, out vec3 p, out vec3 n, out vec3 dir, out float share)
{
    ij = ivec2(id % u_size, id / u_size);
    vec4 fn = texelFetch(u_front_n, ij, 0);
    z = texelFetch(u_front_z, ij, 0).r;
    vec2 uv = (vec2(ij) + 0.5) / float(u_size);
    vec4 w = u_light_inv * vec4(vec3(uv, z) * 2.0 - 1.0, 1.0);
    p = w.xyz / w.w;
    n = normalize(fn.xyz * 2.0 - 1.0);
    dir = u_dir;
    share = 1.0;
    if (u_spot == 1) {
        // its solid angle: the image-plane cell at distance 1 seen at angle
        // theta off the view's axis (cos^3 theta); none outside the cone
        vec2 x = (uv * 2.0 - 1.0) * u_tan;
        float c = inversesqrt(1.0 + dot(x, x));
        dir = normalize(p - u_pos);
        share = c * c * c * (dot(dir, u_axis) >= u_cos_cone ? 1.0 : 0.0);
    }
    if (dot(n, dir) > 0.0) n = -n;
    return fn.a >= 0.5;
}

#if SNELL_PHOTON_BVH
// The photon's path by the mesh's BVH (exact.frag's rays and model,
// ref_caustics.c through): from o along the light's ray dir, in where it
// meets the mesh (photon_entry: the nearest-surface map's point and normal
// where the ray misses it, at the silhouette), inside from surface to
// surface, TIR followed, refracted out, and in again where its way out
// meets the mesh once more, the entry counted, up to u_max_interfaces
// surfaces; at the cap it leaves through the next surface in its
// direction. e: the transmittance, (1 - Schlick) at every refraction, the
// tint at every entry after the first (u_flux holds the first),
// Beer-Lambert inside; q and t2 the last exit (world) and the direction
// out. false: dropped. A thin wall (u_thickness > 0) goes straight on from
// o through every wall on its line, up to u_max_interfaces: e the walls'
// transmittance, the tint at each after the first, q the last wall (the map's point
// where the ray misses the mesh).
// One traversal call site for all the photon's rays (each call site is a
// copy of the walk, common/bvh.glsl): each iteration traces one ray, from
// outside (the first, or a way out that may meet the mesh again) or inside.
bool bvh_path(vec3 o, vec3 dir, vec3 n_map, out vec3 q, out vec3 t2, out vec3 e)
{
    mat3 inv3 = mat3(u_inv_model);
    bool thin = u_thickness > 0.0, inside = false;
    vec3 p = (u_inv_model * vec4(o, 1.0)).xyz, d = dir;
    int at = RAY_FIRST, depth = 0;
    float len = 0.0;
    e = thin ? wall(n_map, dir) : vec3(1.0);
    for (int i = 0; i < 2 * MAX_INTERFACES + 2; i++) {
        if (thin && i >= MAX_INTERFACES) break;
        Ray ray = make_ray(p, inv3 * d);
        float t = 3.0e38;
        int h = closest(ray, u_eps, t, at);
        vec3 ps, ns;
        surface_at(max(h, 0), ray, d, ps, ns);
        if (thin) {                                     // straight on through the next wall
            if (h < 0 || i >= u_max_interfaces) break;
            at = h;
            p = ps;
            e = (i == 0 ? vec3(1.0) : e * u_tint) * wall(ns, d);
            continue;
        }
        if (inside) {
            // the next surface from inside (none: an open mesh, it leaves in
            // its direction); at the cap the way ends there
            bool cap = h >= 0 && depth >= u_max_interfaces, left = false;
            if (h >= 0) {
                len += t;
                at = h;
                p = ps;
            }
            if (h >= 0 && !cap) {
                depth++;
                vec3 o2;
                left = snell_refract(d, ns, u_ior, o2); // refracted out, or totally reflected
                if (left) e *= 1.0 - snell_fresnel_schlick(dot(ns, -d), u_ior, 1.0);
                d = normalize(o2);
            }
            if (h < 0 || cap || left) {
                e *= exp(-u_sigma * len);
                if (depth >= u_max_interfaces) break;
                inside = false;
            }
            continue;
        }
        // outside: the first ray (a miss: the map's point), or the way out
        // meeting the mesh again (a miss: out for good)
        if (h < 0 && i > 0) break;
        at = h >= 0 ? h : RAY_AFTER_MISS;
        // the first ray's miss: the map's point and normal, read again
        ivec2 ij;
        float z, share;
        vec3 pm, nm, dm;
        photon_entry(gl_VertexID + (u_max_interfaces >> 9), ij, z, pm, nm, dm, share);
        p = h >= 0 ? ps : (u_inv_model * vec4(pm, 1.0)).xyz;
        vec3 n = h >= 0 ? ns : nm, tr;
        if (!snell_refract(d, n, 1.0 / u_ior, tr)) return false;
        e *= (depth > 0 ? u_tint : vec3(1.0)) * (1.0 - snell_fresnel_schlick(dot(n, -d), 1.0, u_ior));
        d = normalize(tr);
        depth++;
        len = 0.0;
        inside = true;
    }
    // set here, not carried through the loop: a thin wall's way goes
    // straight on (d is dir), its last wall p (none met: the map's point)
    q = (u_model * vec4(p, 1.0)).xyz;
    if (thin && at == RAY_FIRST) { // the map's point, read again
        ivec2 ij;
        float z, share;
        vec3 nm, dm;
        photon_entry(gl_VertexID + (u_max_interfaces >> 8), ij, z, q, nm, dm, share);
    }
    t2 = d;
    return true;
}
#endif

#ifdef SNELL_PHOTON_CHAIN
// The object entry e belongs to.
int object_of(int e)
{
    int t = int(fetch_f(u_tri_base + 6 * e).w), k = 0;
    for (int j = 1; j < SNELL_PHOTON_CHAIN; j++) k += t >= u_chain_first[j] ? 1 : 0;
    return k;
}

// The photon through the casters in sequence (ref_caustics.c chain): from o
// along the light's ray dir it counts only if the light meets this caster
// first (else it is another's photon; a miss: light past it); through each
// object it meets as bvh_path goes through one, by that one's material (the
// tint at every entry but the photon's first, which u_flux holds), leaving
// it for the next object it meets (the one it left not seen), up to
// SNELL_PHOTON_CHAIN objects; one more stops it (as the reference's
// landing). q and t2 the last exit and the direction out, e the
// transmittance. false: dropped.
// One traversal call site, as bvh_path: each iteration traces one ray in
// one of four roles: the first (FIRST), inside object k (INSIDE), out of k
// where it may meet k again (OUT), or past k's cap, stepping over k's
// surfaces to the next object (SKIP; q_cap holds where the way goes on).
#define CHAIN_FIRST 0
#define CHAIN_INSIDE 1
#define CHAIN_OUT 2
#define CHAIN_SKIP 3
bool chain_path(vec3 o, vec3 dir, out vec3 q, out vec3 t2, out vec3 e)
{
    vec3 p = o, d = dir, q_cap = o;
    int at = RAY_FIRST, role = CHAIN_FIRST, k = u_chain_self, v = 0, depth = 0, m = 0;
    float len = 0.0;
    e = vec3(1.0);
    q = o;
    t2 = dir;
    for (int i = 0; i < SNELL_PHOTON_CHAIN * 4 * (MAX_INTERFACES + 1); i++) {
        float ior = u_chain_ior[k], eps = u_chain_eps[k];
        Ray ray = make_ray(p, d);
        float t = 3.0e38;
        int h = closest(ray, eps, t, at);
        vec3 ps, ns;
        surface_at(max(h, 0), ray, d, ps, ns);
        int obj = h >= 0 ? object_of(h) : -1;
        if (role == CHAIN_FIRST && obj != u_chain_self) return false;
        if (role == CHAIN_INSIDE) {
            // as bvh_path's inside rays, by object k's material
            bool cap = h >= 0 && depth >= u_chain_maxif[k], left = false;
            if (h >= 0) {
                len += t;
                at = h;
                p = ps;
            }
            if (h >= 0 && !cap) {
                depth++;
                vec3 o2;
                left = snell_refract(d, ns, ior, o2);
                if (left) e *= 1.0 - snell_fresnel_schlick(dot(ns, -d), ior, 1.0);
                d = normalize(o2);
            }
            if (h < 0 || cap || left) {
                e *= exp(-u_chain_sigma[k] * len);
                role = CHAIN_OUT;
                q_cap = p;
                if (depth >= u_chain_maxif[k]) role = CHAIN_SKIP; // at the cap it sees k no more
                m = role == CHAIN_SKIP ? 0 : m;
            }
            continue;
        }
        if (role == CHAIN_SKIP) {
            // k's surfaces stepped over (at most MAX_INTERFACES of them)
            if (h >= 0 && obj == k) {
                at = h;
                p = ps;
                if (++m < MAX_INTERFACES) continue;
                h = -1;
            }
            p = q_cap;
        }
        if (role == CHAIN_OUT || role == CHAIN_SKIP) {
            if (h < 0) break;                              // out for good: it lands
            if (obj != k) {                                // the next object
                if (v == SNELL_PHOTON_CHAIN - 1) return false; // one more object past the cap: stopped
                v++;
                k = obj;
                depth = 0;
                m = 0;
            } else {
                m++;
            }
        } else {
            m = 0;
        }
        // in at entry h of object k (its m-th entry)
        at = h;
        p = ps;
        vec3 tint = v == 0 && m == 0 ? vec3(1.0) : u_chain_tint[k];
        ior = u_chain_ior[k];
        if (u_chain_thick[k] > 0.0) { // a thin wall: the slab, straight on
            vec3 rs, ts;
            snell_thin_slab(dot(ns, d), ior, u_chain_sigma[k], u_chain_thick[k], rs, ts);
            e *= tint * ts;
            depth++;
            role = depth >= u_chain_maxif[k] ? CHAIN_SKIP : CHAIN_OUT;
            q_cap = p;
            m = role == CHAIN_SKIP ? 0 : m;
        } else {
            vec3 tr;
            if (!snell_refract(d, ns, 1.0 / ior, tr)) return false;
            e *= tint * (1.0 - snell_fresnel_schlick(dot(ns, -d), 1.0, ior));
            d = normalize(tr);
            depth++;
            len = 0.0;
            role = CHAIN_INSIDE;
        }
    }
    q = role == CHAIN_SKIP ? q_cap : p;
    t2 = d;
    return true;
}
#endif

// The photon's splat: its clip position and flux. false: none (dropped, or
// no photon).
bool photon(out vec4 pos, out vec4 flux4)
{
    ivec2 ij;
    float z, share;
    vec3 p, n, dir;
    // missed the object (direct light), or outside the spot's cone
    if (!photon_entry(gl_VertexID, ij, z, p, n, dir, share) || share <= 0.0) return false;
    vec3 q, t2 = dir, e = vec3(1.0);
    float f1 = 0.0, f2 = 0.0, len = 0.0;
    bool through = true, by_maps = true;
#ifdef SNELL_PHOTON_CHAIN
    vec3 o = u_spot == 1 ? u_pos : p - dir * (dot(p - u_chain_sphere.xyz, dir) + u_chain_sphere.w + 1.0);
    through = chain_path(o, dir, q, t2, e) && !bvh_over(); // past the node budget: dropped
    by_maps = false;
#elif SNELL_PHOTON_BVH
    through = bvh_path(p - dir * u_reach, dir, n, q, t2, e);
    by_maps = bvh_over(); // past the node budget: the depth maps' path
    if (by_maps) e = vec3(1.0);
    // the entry again: the walk's loop carries none of it
    photon_entry(gl_VertexID + (u_max_interfaces >> 8), ij, z, p, n, dir, share);
#endif
    if (by_maps && u_thickness > 0.0) thin_maps(p, n, dir, ij, z, q, e);
    else if (by_maps) through = depth_path(p, n, dir, f1, f2, len, q, t2);
    if (!through) return false;
    // where the plane (if any) meets it; its way there, or the reach
    float sp = -1.0, lmax = u_recv_reach;
    if (u_has_plane == 1 && t2.y < 0.0) sp = (u_plane.x - q.y) / t2.y;
    if (sp >= 0.0) lmax = sp;
    if (u_target == 0 && sp < 0.0) return false; // never reaches the plane's lit side (or the object reaches below it)
    bool on = false;
    float so = u_recv == 1 ? recv_march(q, t2, lmax, on) : -1.0;
    if (u_target == 0 && so >= 0.0) return false; // an opaque object stops it first
    if (u_target == 1 && !(so >= 0.0 && on)) return false;
    vec3 flux = (u_target == 0 ? u_flux : u_flux_recv) * share * (1.0 - f1) * (1.0 - f2) * exp(-u_sigma * len) * e;
    if (u_target == 1) {
        vec3 h = q + t2 * so;
        vec4 c = u_recv_vp * vec4(h, 1.0);
        if (u_spot == 1) { // the texel's solid angle: cos^3 off the frame's axis (straight down)
            float cl = (u_pos.y - h.y) / length(h - u_pos);
            flux /= cl * cl * cl;
#ifdef SNELL_LIGHT_RANGE
            // Flux per solid angle is intensity, which an RGB10_A2 map's range
            // (irradiance) cannot hold: as irradiance at the frame's far plane,
            // so that no texel saturates below the range's irradiance
            // (common/opaque_lit.glsl scales it back).
            flux /= u_recv_lin.y * u_recv_lin.y;
#endif
        }
        flux4 = vec4(flux, (flux.r + flux.g + flux.b) / 3.0);
        pos = vec4(c.xy / c.w, 0.0, 1.0);
        return true;
    }
    float s = sp;
    vec3 h = q + t2 * s;
    flux4 = vec4(flux, (flux.r + flux.g + flux.b) / 3.0);
    pos = vec4((h.x - u_plane.y) / u_plane.w, (h.z - u_plane.z) / u_plane.w, 0.0, 1.0);
    return true;
}

// The outputs written once, at the end: an output written early and again
// later is a register live through every loop between.
void main()
{
    vec4 pos, flux;
    bool lit = photon(pos, flux);
    gl_PointSize = 4.0;
    gl_Position = lit ? pos : vec4(4.0, 4.0, 4.0, 1.0); // dropped photons: outside the clip volume
    v_flux = lit ? flux : vec4(0.0);
}
