// SPDX-License-Identifier: MIT
// beyond.glsl - what a ray sees once it leaves the kernel's glass object.
// snell_exit(p, dir): the light arriving back along the ray that leaves the
// object at p in direction dir; snell_reflection(p, r): the same for the mirror
// ray off its front. Without SNELL_BEYOND, the environment; with it, the ray is
// marched through the scene layers of every other glass and opaque object
// (Wang 2014, seed 001 3.7, all objects in one peel), then meets the water
// (SNELL_WATER), the host's backdrop (SNELL_BACKDROP), the lit receiver
// (SNELL_RECEIVER), the environment. The march's rules, step by step:
// docs/ARCHITECTURE.md, "Design notes by file".
#ifdef SNELL_RECEIVER
#include "common/receiver.glsl"
#include "common/opaque_lit.glsl"
uniform int u_lit_opaque;
#endif
#ifdef SNELL_BACKDROP
#include "common/backdrop.glsl"
#endif
#ifdef SNELL_WATER
#include "common/water.glsl"
bool beyond_start_in_water = false;
bool beyond_in_water = false; // set by snell_exit from the above
#endif

// What a ray from o along dir in the ambient medium sees past every object.
// The helpers called in beyond_march's loop return at their end only (and
// select rather than branch where they can): an early return leaves a
// flag and a result that GPU compilers keep live through the whole loop.
vec3 beyond_miss(highp vec3 o, highp vec3 dir)
{
    vec3 col = vec3(0.0);
    bool seen = false;
#ifdef SNELL_WATER
    seen = water_seen(o, dir, beyond_in_water, col);
#endif
#ifdef SNELL_RECEIVER
    if (!seen) seen = receiver_seen(o, dir, col);
#endif
#ifdef SNELL_BACKDROP
    if (!seen) seen = backdrop_seen(o, dir, col);
#endif
    if (!seen) col = snell_env(dir);
    return col;
}

#ifdef SNELL_BEYOND
#define BEYOND_MAX_LAYERS 8         // SNELL_MAX_SCENE_LAYERS
#define BEYOND_MAX_INTERFACES 8
#define BEYOND_LINEAR 32          // per bounding diameter: where more steps stop paying (bench/notes/code.md, "beyond.glsl")
#define BEYOND_BINARY 6           // more changes nothing visible (bench/notes/code.md, "beyond.glsl")
#define BEYOND_OPAQUE_ID0 33        // SNELL__LAYERS_OPAQUE_ID0
#define BEYOND_UNKNOWN (-2)
#define BEYOND_PENDING 1            // beyond_march's state: a reflection waits for its look-up
#define BEYOND_ENDING 2             // the march is over: the ray's end is looked up

uniform highp sampler2DArray u_scene_layers; // slice 2k: normal; 2k + 1: depth 24 bits + id 8 bits
uniform highp sampler2D u_scene_table;       // per id - 1: row 0 (ior, tint; ior 0 = opaque),
                                             // row 1 (absorption, thin-wall thickness: 0 solid),
                                             // row 2 bounding sphere, row 3 albedo
uniform int u_scene_layer_count;             // non-empty layers peeled, 1..BEYOND_MAX_LAYERS
uniform int u_scene_capped;                  // 1: surfaces may lie behind the last layer
uniform int u_scene_glass_ids;               // glass ids 1..u_scene_glass_ids may be present
uniform int u_scene_opaque_count;            // opaque ids BEYOND_OPAQUE_ID0 + 0..count - 1
uniform int u_scene_self;                    // the kernel's object's id, skipped
uniform highp mat4 u_scene_view_proj;
uniform highp vec3 u_scene_eye;
uniform highp vec3 u_scene_fwd;              // unit view axis
uniform highp float u_scene_near;            // view depth of depth value 0
uniform highp float u_scene_inv_range;       // depth values per world unit
uniform highp vec2 u_scene_size;             // target size in pixels

bool beyond_pixel(highp vec3 p, out ivec2 px)
{
    highp vec4 c = u_scene_view_proj * vec4(p, 1.0);
    highp vec2 w = (c.xy / c.w * 0.5 + 0.5) * u_scene_size;
    bool on = c.w > 0.0 && !(any(lessThan(w, vec2(0.0))) || any(greaterThanEqual(w, u_scene_size)));
    px = on ? ivec2(w) : ivec2(0);
    return on;
}

highp float beyond_depth(highp vec3 p)
{
    return (dot(p - u_scene_eye, u_scene_fwd) - u_scene_near) * u_scene_inv_range;
}

// Layer k at px: its depth (2.0: empty) and id (0: empty).
highp float beyond_layer(ivec2 px, int k, out int id)
{
    highp uvec4 b = uvec4(texelFetch(u_scene_layers, ivec3(px, 2 * k + 1), 0) * 255.0 + 0.5);
    id = int(b.a);
    highp float d = float((b.r << 16u) | (b.g << 8u) | b.b) / 16777215.0;
    return id == 0 ? 2.0 : d;
}

// Layer ids: glass i + 1, opaque BEYOND_OPAQUE_ID0 + j, and thin walls with
// BEYOND_THIN_ID added (render/layers.h), so no table look-up tells them.
#define BEYOND_THIN_ID 128

vec4 beyond_table(int id, int row)
{
    return texelFetch(u_scene_table, ivec2((id & (BEYOND_THIN_ID - 1)) - 1, row), 0);
}

bool beyond_thin(int id)
{
    return id >= BEYOND_THIN_ID;
}

// The medium at p (see the header): 0 air, an id, or BEYOND_UNKNOWN; plus
// BEYOND_THIN_ODD where the thin-wall surfaces in front of p are odd in
// number. The object excl is skipped as the kernel's own is. The layers in
// front of p are walked from the eye: a surface of the object the walk is
// in leaves it, a surface of the object around that one leaves that (one of
// cur's surfaces is missing at this pixel: seen edge-on, or rasterised into
// the neighbour), another enters one (objects are disjoint or nested, two
// deep at most). This agrees with counting each object's surfaces' parity
// without an array of ids; without the middle rule, a missing surface swapped
// two objects (bench/notes/code.md, "beyond.glsl").
#define BEYOND_THIN_ODD 256
int beyond_medium(highp vec3 p, int excl)
{
    ivec2 px;
    bool on = beyond_pixel(p, px);
    highp float z = beyond_depth(p);
    int cur = 0, outer = 0, thin = 0, n = 0;
    for (int k = 0; k < BEYOND_MAX_LAYERS; k++) {
        if (!on || k >= u_scene_layer_count) break;
        int id;
        highp float d = beyond_layer(px, k, id);
        if (id == 0 || d >= z) break; // layers are sorted by depth; empty ones come last
        n++;
        if (id == u_scene_self || id == excl) continue;
        if (beyond_thin(id)) {
            thin ^= BEYOND_THIN_ODD;
        } else if (id == cur) {
            cur = outer; // left it
            outer = 0;
        } else if (id == outer) {
            outer = 0; // left the outer one: a surface of cur's is missing here (see above)
        } else {
            outer = cur; // entered it (inside cur, if any)
            cur = id;
        }
    }
    return !on || (n == u_scene_layer_count && u_scene_capped != 0) ? BEYOND_UNKNOWN : cur | thin;
}

float beyond_ior(int medium)
{
    float glass = beyond_table(max(medium, 1), 0).x;
    float ior = medium > 0 ? glass : 1.0;
#ifdef SNELL_WATER
    ior = medium == 0 && beyond_in_water ? u_water_ior : ior;
#endif
    return ior;
}

// The normal of object id's surface crossed between qa and qb: its layer
// nearest the crossing's depth at qb's pixel, else at qa's; -dir if neither
// has one (no bend).
vec3 beyond_normal(highp vec3 qa, highp vec3 qb, int id, highp vec3 dir)
{
    ivec3 at = ivec3(0, 0, -1); // the normal's texel: none yet
    for (int e = 0; e < 2 + (u_scene_layer_count >> 8); e++) { // a loop, not two copies (see beyond_march)
        highp vec3 q = e == 0 ? qb : qa;
        ivec2 px;
        bool on = beyond_pixel(q, px);
        highp float z = beyond_depth(q), best = 4.0;
        int best_k = -1;
        for (int k = 0; k < BEYOND_MAX_LAYERS; k++) {
            if (!on || k >= u_scene_layer_count) break;
            int lid;
            highp float d = beyond_layer(px, k, lid);
            if (lid == 0) break;
            if (lid == id && abs(d - z) < best) {
                best = abs(d - z);
                best_k = k;
            }
        }
        if (best_k >= 0) {
            at = ivec3(px, 2 * best_k);
            break;
        }
    }
    highp vec4 g = texelFetch(u_scene_layers, max(at, ivec3(0)), 0);
    vec3 n = normalize(snell_oct_decode(vec2(snell_unpack_unorm16(g.xy), snell_unpack_unorm16(g.zw)) * 2.0 - 1.0));
    return at.z >= 0 ? n : -dir;
}

// The next stretch of o + t dir with t > t0 inside the bounding sphere (grown
// by one step) of an object other than self: [ta, tb] and that object's
// step. False: the ray meets no other object.
bool beyond_stretch(highp vec3 o, highp vec3 dir, highp float t0, out highp float ta, out highp float tb,
                    out highp float step)
{
    ta = 1e30;
    tb = 0.0;
    step = 1.0;
    bool found = false;
    int count = u_scene_glass_ids + u_scene_opaque_count;
    for (int i = 0; i < 128; i++) { // SNELL_MAX_GLASS + SNELL_MAX_OPAQUE ids at most
        if (i >= count) break;
        int id = i < u_scene_glass_ids ? i + 1 : BEYOND_OPAQUE_ID0 + i - u_scene_glass_ids;
        if (id == (u_scene_self & (BEYOND_THIN_ID - 1))) continue;
        highp vec4 s = beyond_table(id, 2);
        if (s.w <= 0.0) continue; // not in this frame's layers
        highp float st = 2.0 * s.w / float(BEYOND_LINEAR), r = s.w + st;
        highp vec3 oc = o - s.xyz;
        highp float b = dot(oc, dir), disc = b * b - dot(oc, oc) + r * r;
        if (disc < 0.0) continue;
        highp float q = sqrt(disc), t1 = max(-b - q, t0), t2 = -b + q;
        if (t2 <= t0) continue;
        if (t1 < ta) {
            ta = t1;
            tb = t2;
            step = st;
            found = true;
        }
    }
    return found;
}

// Where a ray inside glass object `medium` from o must have left it: the far
// side of its bounding sphere grown by a step.
highp float beyond_inside_stretch(int medium, highp vec3 o, highp vec3 dir, out highp float step)
{
    highp vec4 s = beyond_table(medium, 2);
    step = 2.0 * s.w / float(BEYOND_LINEAR);
    highp float r = s.w + step;
    highp vec3 oc = o - s.xyz;
    highp float b = dot(oc, dir);
    return max(-b + sqrt(max(b * b - dot(oc, oc) + r * r, 0.0)), 0.0);
}

// The march (see the header). exit_of_self: dir is the kernel's refracted
// exit ray (re-bent for the water where it leaves under it), else a mirror
// ray off the object's front (snell_reflection).
vec3 beyond_march(highp vec3 p, inout highp vec3 dir, bool exit_of_self)
{
#ifdef SNELL_WATER
    beyond_in_water = beyond_start_in_water || water_contains(p);
    if (exit_of_self && beyond_in_water && !beyond_start_in_water && u_scene_self > 0 && !beyond_thin(u_scene_self)) {
        // The kernel refracted its ray out into air; it leaves under the
        // water: bent again for the water's index (the tangential part
        // scales by 1 / ior), with the normal of its object's surface there
        // from the layers. A ray the kernel reflected totally (beyond
        // glass-air's critical angle, short of glass-water's) stays so.
        highp vec3 n = beyond_normal(p, p, u_scene_self, -dir);
        if (dot(n, dir) < 0.0) n = -n;
        highp vec3 tw = (dir - dot(dir, n) * n) / u_water_ior;
        dir = normalize(tw + sqrt(max(1.0 - dot(tw, tw), 0.0)) * n);
    }
#endif
    vec3 radiance = vec3(0.0); // reflections met on the way
    vec3 thr = vec3(1.0);      // what reaches the eye of the light along the current ray
    // a ray that leaves its object inside another (nested glass) starts in it
    int medium = beyond_medium(p, 0); // the medium, and the thin walls' parity (BEYOND_THIN_ODD)
    if (medium < 0 || (medium & 255) >= BEYOND_OPAQUE_ID0) medium = 0;
    int crossed = 0;
    int left = 0; // the object the ray last left: not re-entered (see the header)
    highp vec3 o = p;
    highp float t0 = 0.0;
    // What the ray sees past every object is looked up in one place, the top
    // of a round (GPU compilers inline each call site, and beyond_miss holds
    // the water's and the receiver's look-ups): first a reflection met on the
    // way (from miss_o along miss_d, weighted miss_w; BEYOND_PENDING), then,
    // once the march is over (BEYOND_ENDING), the ray's own end.
    highp vec3 miss_o = p, miss_d = dir;
    vec3 miss_w = vec3(0.0);
    int state = 0;
    // each round crosses a surface (at most BEYOND_MAX_INTERFACES) or passes
    // one object's bounding sphere; the last two look up what remains
    for (int round = 0; round < BEYOND_MAX_INTERFACES + 34; round++) {
        if (round == BEYOND_MAX_INTERFACES + 32) state |= BEYOND_ENDING;
        bool last = state == BEYOND_ENDING;
        miss_o = last ? o : miss_o;
        miss_d = last ? dir : miss_d;
        miss_w = last ? thr : miss_w;
        if (state != 0) radiance += miss_w * beyond_miss(miss_o, miss_d);
        if (last) break;
        state &= BEYOND_ENDING;
        if (state != 0) continue; // the reflection is in: the end next round
        highp float ta, tb, step;
        int inside = medium & 255; // the glass object the ray is in, 0 air
        highp float water_t = 3.0e38; // in the air: how far from o the water or the container is met
#ifdef SNELL_WATER
        // found each round (past an object's sphere, t0 > 0, the same again):
        // a value kept from round to round is live through the whole loop
        highp vec3 water_n = vec3(0.0, 1.0, 0.0);
        int water_what = -1;
        if (inside == 0 && !beyond_in_water) {
            water_what = water_air_hit(o, dir, water_t, water_n);
            if (water_what < 0) water_t = 3.0e38;
        }
#endif
        bool to_water = false;
        if (inside > 0) {
            ta = 0.0;
            tb = beyond_inside_stretch(inside, o, dir, step);
        } else if (!beyond_stretch(o, dir, t0, ta, tb, step)) {
            to_water = water_t < 3.0e38;
            if (!to_water) {
                state = BEYOND_ENDING;
                continue;
            }
        } else if (ta > water_t) {
            to_water = true;
        }
        // linear: the first sample whose medium differs
        highp float ia = ta, ib = -1.0;
        int m_new = medium;
        bool unknown = false;
        for (int i = 1; i <= 4 * BEYOND_LINEAR; i++) { // a stretch is at most a grown diameter: < 2 LINEAR steps
            if (to_water) break;
            highp float t = min(ta + float(i) * step, tb);
            int m = beyond_medium(o + t * dir, left);
            if (m == BEYOND_UNKNOWN) {
                unknown = true;
                break;
            }
            if (m != medium) {
                ib = t;
                m_new = m;
                break;
            }
            ia = t;
            if (t >= tb) break;
        }
        if (unknown) {
            state = BEYOND_ENDING;
            continue;
        }
        if (inside == 0 && (to_water || (ib < 0.0 ? tb : ib) > water_t)) {
#ifdef SNELL_WATER
            // the water (or the container) comes first: a face ends the
            // ray (beyond_miss finds it again); at the surface it is
            // refracted into the water and goes on there (the reflected part
            // from the walls and the sky)
            if (water_what != WATER_SURFACE) {
                state = BEYOND_ENDING;
                continue;
            }
            highp vec3 q = o + water_t * dir;
            highp vec3 wn = dot(water_n, dir) > 0.0 ? -water_n : water_n, wt;
            float wf = snell_fresnel_schlick_sel(-dot(dir, wn), 1.0, u_water_ior);
            radiance += thr * wf * water_walls_above(q, snell_reflect(dir, wn));
            thr *= 1.0 - wf;
            snell_refract_sel(dir, wn, 1.0 / u_water_ior, wt);
            dir = normalize(wt);
            o = q;
            t0 = 0.0;
            beyond_in_water = true;
            if (++crossed >= BEYOND_MAX_INTERFACES) state = BEYOND_ENDING;
            continue;
#endif
        }
        if (ib < 0.0) {
            if (inside > 0) {
                // no far surface in the layers: it leaves in its direction (peel.frag's rule)
                thr *= snell_beer_lambert(beyond_table(inside, 1).rgb, tb);
                left = inside;
                medium &= BEYOND_THIN_ODD;
                o += tb * dir;
                t0 = 0.0;
            } else {
                t0 = tb; // on to the next object's sphere
            }
            continue;
        }
        // the count is not a constant to the compiler, so that it keeps the
        // loop (unrolled, each step is a copy of beyond_medium's layer walk)
        for (int s = 0; s < BEYOND_BINARY + (u_scene_layer_count >> 8); s++) {
            highp float tm = 0.5 * (ia + ib);
            int m = beyond_medium(o + tm * dir, left);
            if (m == medium) {
                ia = tm;
            } else {
                ib = tm;
                if (m != BEYOND_UNKNOWN) m_new = m;
            }
        }
        highp vec3 qa = o + ia * dir, qb = o + ib * dir;
        if (inside > 0) thr *= snell_beer_lambert(beyond_table(inside, 1).rgb, ib);
#ifdef SNELL_WATER
        else if (beyond_in_water) thr *= snell_beer_lambert(u_water_sigma, ib);
#endif
        int entered = m_new & 255;
        if (entered == inside && (m_new ^ medium) == BEYOND_THIN_ODD) {
            // a thin wall: which one is the nearest thin layer to the crossing
            int wall = 0;
            ivec2 px;
            if (beyond_pixel(qb, px)) {
                highp float z = beyond_depth(qb), best = 4.0;
                for (int k = 0; k < BEYOND_MAX_LAYERS; k++) {
                    if (k >= u_scene_layer_count) break;
                    int lid;
                    highp float d = beyond_layer(px, k, lid);
                    if (lid == 0) break;
                    if (lid != u_scene_self && beyond_thin(lid) && abs(d - z) < best) {
                        best = abs(d - z);
                        wall = lid;
                    }
                }
            }
            if (wall > 0) {
                vec3 nw = beyond_normal(qa, qb, wall, dir);
                vec3 rs, ts;
                vec4 w0 = beyond_table(wall, 0), w1 = beyond_table(wall, 1);
                snell_thin_slab(dot(nw, dir), w0.x, w1.rgb, w1.w, rs, ts);
                if (dot(nw, dir) > 0.0) nw = -nw;
                miss_o = qb;
                miss_d = snell_reflect(dir, nw);
                miss_w = thr * rs;
                state = BEYOND_PENDING;
                thr *= ts * w0.yzw;
            }
            // the whole object is one slab (the single kernel's thin walls,
            // the reference's model): its other wall is not crossed again
            o = qb;
            if (wall > 0) left = wall;
            medium = beyond_medium(o, left);
            if (medium == BEYOND_UNKNOWN) {
                state |= BEYOND_ENDING;
                continue;
            }
            t0 = 0.0;
            if (++crossed >= BEYOND_MAX_INTERFACES) state |= BEYOND_ENDING;
            continue;
        }
        vec3 n = beyond_normal(qa, qb, entered > 0 ? entered : inside, dir);
        if (entered >= BEYOND_OPAQUE_ID0) {
#ifdef SNELL_RECEIVER
            // at qa, the air side of the crossing (qb lies inside: its shadow
            // look-up would find the object itself)
            if (u_lit_opaque == 1) return radiance + thr * beyond_table(entered, 3).rgb * snell_lit_irradiance(qa, n);
#endif
            // opaque.frag's light: half-Lambert from the sky, the mesh's own normal
            float l = 0.5 + 0.5 * dot(n, normalize(vec3(0.3, 1.0, 0.2)));
            radiance += thr * beyond_table(entered, 3).rgb * (0.25 + 0.75 * l);
            return radiance;
        }
        if (dot(n, dir) > 0.0) n = -n; // face the ray
        float n1 = beyond_ior(inside), n2 = beyond_ior(entered);
        vec3 out_dir;
        bool through = snell_refract_sel(dir, n, n1 / n2, out_dir);
        if (inside == 0) {
            // an entry from air: its reflection, and the tint
            float f = snell_fresnel_sel(-dot(dir, n), n1, n2);
            // one texture level (no mipmaps): the look-up needs no derivatives here
            miss_o = qb;
            miss_d = snell_reflect(dir, n);
            miss_w = thr * f;
            state = BEYOND_PENDING;
            thr *= (1.0 - f) * beyond_table(entered, 0).yzw;
        }
        dir = normalize(out_dir);
        if (through) {
            o = qb;
            if (inside > 0) left = inside;
            medium = m_new;
        } else {
            o = qa; // TIR: from the last point inside
        }
        t0 = 0.0;
        if (++crossed >= BEYOND_MAX_INTERFACES) state |= BEYOND_ENDING; // the cap: leaves in its direction
    }
    return radiance;
}

vec3 snell_exit(highp vec3 p, inout highp vec3 dir)
{
    return beyond_march(p, dir, true);
}

vec3 snell_reflection(highp vec3 p, highp vec3 r)
{
    highp vec3 d = r;
    return beyond_march(p, d, false);
}
#else
vec3 snell_exit(highp vec3 p, inout highp vec3 dir)
{
    return beyond_miss(p, dir);
}

vec3 snell_reflection(highp vec3 p, highp vec3 r)
{
    return beyond_miss(p, r);
}
#endif
