// SPDX-License-Identifier: MIT
// bvh.glsl - closest-hit traversal of a mesh's BVH texture (methods/exact.c
// builds and packs it), shared by exact.frag and caustics_photon.vert. Nodes in
// depth-first order with escape indices, then 6 texels a triangle (v0..v2,
// n0..n2, object space); SNELL_NODES_Q16: RGBA32UI, 16-bit bounds. Traversal in
// object space with the world ray parameter. highp throughout. Layout in full:
// docs/ARCHITECTURE.md, "Design notes by file".
#define MAX_INTERFACES 10    // SNELL_EXACT_MAX_INTERFACES
#define TEX_SHIFT 11         // exact.c TEX_WIDTH = 2048
#define TEX_MASK 2047
// Defined by the including program: SNELL_NODE_BUDGET (node visits of all
// of a pixel's or photon's rays; a constant or a uniform), SNELL_NODES_Q16
// (0/1) and SNELL_STACK_WALK (0: stackless, 1: near-first with a short
// stack).

#if SNELL_NODES_Q16
uniform highp usampler2D u_bvh;
#else
uniform highp sampler2D u_bvh;
#endif
uniform int u_node_count;
uniform int u_tri_base;          // texel of triangle entry 0
uniform vec3 u_qlo, u_qstep;     // SNELL_NODES_Q16: the quantisation frame (object space)
uniform mat3 u_normal_matrix;    // object -> world normals
// Nodes this pixel (or photon) visited, all its rays; BVH_OVER once its
// budget (or the stack) ran out: one value, not a count and a flag.
#define BVH_OVER 0x40000000
int g_visits = 0;

// Whether the budget ran out: the answers are then not to be used.
bool bvh_over()
{
    return g_visits >= BVH_OVER;
}

ivec2 texel(int i)
{
    return ivec2(i & TEX_MASK, i >> TEX_SHIFT);
}

#if SNELL_NODES_Q16
vec4 fetch_f(int i)
{
    return uintBitsToFloat(texelFetch(u_bvh, texel(i), 0));
}

// Node i: its bounds and its word: an interior node's escape (>= 0), or for
// a leaf ~(first << 2 | count - 1) (< 0: leaf_range unpacks it; a leaf holds
// at most 4 entries, bvh_gpu.c LEAF_MAX), one value live through the walk,
// not two.
void fetch_node(int i, out vec3 lo, out vec3 hi, out int word)
{
    uvec4 t = texelFetch(u_bvh, texel(i), 0);
    lo = u_qlo + vec3(float(t.x & 0xffffu), float(t.x >> 16), float(t.y & 0xffffu)) * u_qstep;
    hi = u_qlo + vec3(float(t.y >> 16), float(t.z & 0xffffu), float(t.z >> 16)) * u_qstep;
    int low = int(t.w & 0x7fffffffu);
    word = (t.w & 0x80000000u) != 0u ? -low - 1 : low;
}
#else
vec4 fetch_f(int i)
{
    return texelFetch(u_bvh, texel(i), 0);
}

void fetch_node(int i, out vec3 lo, out vec3 hi, out int word)
{
    vec4 a = texelFetch(u_bvh, texel(2 * i), 0);
    vec4 b = texelFetch(u_bvh, texel(2 * i + 1), 0);
    lo = a.xyz;
    hi = b.xyz;
    int first = int(a.w), count = int(b.w);
    word = count > 0 ? -((first << 2) | (count - 1)) - 1 : first;
}
#endif

// A leaf's entries first .. end - 1 from its word.
void leaf_range(int word, out int first, out int end)
{
    int x = -word - 1;
    first = x >> 2;
    end = first + (x & 3) + 1;
}

// A ray o + t d with the per-ray constants of the watertight test (Woop,
// Benthin, Wald 2013; mesh/bvh.c ray_setup): kz the dominant axis, the
// permutation (x, y, z) -> (kx, ky, kz) with kx and ky swapped when d[kz] <
// 0 (kept as one int, not as a matrix: one register, not nine, live
// through the walk); s the shear onto +z; inv for the slab tests.
struct Ray {
    vec3 o, inv, s;
    int perm;        // kz, + 4 when swapped
};

// a's components in the ray's permuted order: exactly the permutation
// matrix's product for finite a.
vec3 ray_perm(Ray r, vec3 a)
{
    int kz = r.perm & 3;
    vec3 q = kz == 0 ? a.yzx : (kz == 1 ? a.zxy : a);
    return r.perm >= 4 ? q.yxz : q;
}

Ray make_ray(vec3 o, vec3 d)
{
    Ray r;
    vec3 a = abs(d);
    r.perm = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
    vec3 pd = ray_perm(r, d);
    r.perm += pd.z < 0.0 ? 4 : 0;
    pd = pd.z < 0.0 ? pd.yxz : pd;
    r.o = o;
    // a zero component would make 1/0; 1e-30 keeps the slab test finite and conservative
    r.inv = 1.0 / mix(d, vec3(1e-30), equal(d, vec3(0.0)));
    r.s = vec3(pd.x / pd.z, pd.y / pd.z, 1.0 / pd.z);
    return r;
}

// Watertight ray-triangle test (mesh/bvh.c tri_hit, in float): whether the
// ray meets the triangle at t in (tmin, tmax); t and the barycentric weights
// of v0, v1, v2 are computed whatever the answer (no branches: no value
// merged from several paths, which V3D keeps live through the whole loop).
bool tri_hit(Ray r, vec3 v0, vec3 v1, vec3 v2, float tmin, float tmax, out float t, out vec3 b)
{
    vec3 A = ray_perm(r, v0 - r.o), B = ray_perm(r, v1 - r.o), C = ray_perm(r, v2 - r.o);
    float ax = A.x - r.s.x * A.z, ay = A.y - r.s.y * A.z;
    float bx = B.x - r.s.x * B.z, by = B.y - r.s.y * B.z;
    float cx = C.x - r.s.x * C.z, cy = C.y - r.s.y * C.z;
    float u = cx * by - cy * bx;
    float v = ax * cy - ay * cx;
    float w = bx * ay - by * ax;
    float det = u + v + w;
    float T = u * (r.s.z * A.z) + v * (r.s.z * B.z) + w * (r.s.z * C.z);
    float rcp = 1.0 / det;
    t = T * rcp;
    b = vec3(u, v, w) * rcp;
    bool inside = !((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0));
    return inside && det != 0.0 && t > tmin && t < tmax;
}

// Slab entry parameter of the box (clamped to 0), and whether the ray meets
// it before tmax.
float box_enter(Ray r, vec3 lo, vec3 hi, float tmax, out bool hit)
{
    vec3 t0 = (lo - r.o) * r.inv, t1 = (hi - r.o) * r.inv;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    float a = max(max(tn.x, tn.y), max(tn.z, 0.0));
    hit = a <= min(min(tf.x, tf.y), min(tf.z, tmax));
    return a;
}

#define RAY_FIRST (-1)         // skip: a ray from outside the mesh (the eye's, the light's)
#define RAY_AFTER_MISS (-2)    // skip: a ray on from a point off the mesh's triangles (tmin eps)

// The leaf's triangles against the ray, skipping entry skip: the closest
// hit so far in best and tbest (its weights are computed again by
// surface_at: three fewer values live through the walk). The loop's bound
// is the leaf's own count, not the most a leaf holds: a bound the compiler
// cannot unroll, so one copy of the triangle test serves every leaf (Aila and
// Laine 2009, "Understanding the efficiency of ray traversal on GPUs": the
// while-while walk's inner loop over a leaf's triangles).
void leaf_hits(Ray r, int word, float eps, inout float tbest, int skip, inout int best)
{
    int first, end;
    leaf_range(word, first, end);
    for (int e = first; e < end; e++) {
        int base = u_tri_base + 6 * e;
        float t;
        vec3 b;
        bool h = tri_hit(r, fetch_f(base).xyz, fetch_f(base + 1).xyz, fetch_f(base + 2).xyz,
                         skip == RAY_FIRST ? 0.0 : eps, tbest, t, b) && e != skip;
        tbest = h ? t : tbest;
        best = h ? e : best;
    }
}

// Closest hit with t in (tmin, tbest), skipping entry skip (the one the ray
// starts on; RAY_AFTER_MISS: none, RAY_FIRST: none and tmin 0, else tmin
// eps; the bound is derived where it is used, not kept in a register): its
// entry (tbest set) or -1; marks the pixel over (bvh_over) when its budget
// (or the stack) runs out, and the answer is then not to be used. Every
// call site is a copy of the walk: a program calls it from one place, in a
// loop over its rays.
// Stackless: on a hit box the walk descends (next node), on a miss or after
// a leaf it takes the node's escape; it needs no stack and has no depth
// bound, but visits children in build order.
#if !SNELL_STACK_WALK
int closest(Ray r, float eps, inout float tbest, int skip)
{
    int best = -1;
    int node = 0;
    // every iteration counts a visit, so the budget ends the loop
    while (g_visits < BVH_OVER) {
        if (node >= u_node_count) break;
        if (g_visits >= SNELL_NODE_BUDGET) {
            g_visits = BVH_OVER;
            break;
        }
        g_visits++;
        vec3 lo, hi;
        int word;
        fetch_node(node, lo, hi, word);
        bool in_box;
        box_enter(r, lo, hi, tbest, in_box);
        if (word < 0 && in_box) leaf_hits(r, word, eps, tbest, skip, best);
        node = word < 0 || in_box ? node + 1 : word;
    }
    return best;
}
#else
#define STACK_SIZE 32
#define POP (-2147483647 - 1)    // cur: take the next node from the stack (no leaf word is this low)
// Near-first with a short stack (Aila and Laine 2009's while-while walk):
// both children's boxes tested, the nearer visited, the farther pushed;
// a popped node is fetched and visited unless the ray enters its box no
// nearer than the closest hit so far (its entry parameter computed again:
// the value the push saw, so the stack holds node indices only). The root
// starts on the stack. The node to visit is one int: a leaf's word (< 0),
// an interior node's index (its escape is not needed here), or POP. At
// most one push per level, so STACK_SIZE bounds the tree depth it walks; a
// pixel that would overflow it falls back.
int closest(Ray r, float eps, inout float tbest, int skip)
{
    int stack[STACK_SIZE];
    stack[0] = 0;
    int sp = 1, best = -1, cur = POP;
    g_visits++;                                              // the root
    // Every node it visits was counted when its parent's children were
    // fetched (the root here), so the budget ends the loop; its condition
    // holds until then (a loop without one compiles worse on Adreno).
    while (g_visits < BVH_OVER) {
        if (cur == POP) {
            bool found = false;
            while (sp > 0) {
                sp--;
                int node = stack[sp], word;
                vec3 lo, hi;
                bool hit;
                fetch_node(node, lo, hi, word);
                cur = word < 0 ? word : node;
                float a = box_enter(r, lo, hi, 3.0e38, hit);
                if (hit && a < tbest) {
                    found = true;
                    break;
                }
            }
            if (!found) break;
        }
        if (g_visits >= SNELL_NODE_BUDGET) {
            g_visits = BVH_OVER;
            break;
        }
        if (cur < 0) {
            leaf_hits(r, cur, eps, tbest, skip, best);
            cur = POP;
        } else {
            vec3 lo0, hi0, lo1, hi1;
            int w0, w1;
            bool h0, h1;
            int c0 = cur + 1;
            g_visits += 2;
            fetch_node(c0, lo0, hi0, w0);
            int c1 = w0 < 0 ? c0 + 1 : w0;
            fetch_node(c1, lo1, hi1, w1);
            float t0 = box_enter(r, lo0, hi0, tbest, h0), t1 = box_enter(r, lo1, hi1, tbest, h1);
            t0 = h0 ? t0 : 3.0e38;
            t1 = h1 ? t1 : 3.0e38;
            bool near0 = t0 <= t1;
            if ((near0 ? t1 : t0) < 1.0e38) {
                if (sp >= STACK_SIZE) {
                    g_visits = BVH_OVER;                         // deeper than the stack: the fallback
                    break;
                }
                stack[sp] = near0 ? c1 : c0;
                sp++;
            }
            cur = !((near0 ? t0 : t1) < 1.0e38) ? POP : near0 ? (w0 < 0 ? w0 : c0) : (w1 < 0 ? w1 : c1);
        }
    }
    return best;
}
#endif

// Entry e's point (object space, on the triangle, at the weights at which
// ray r meets it: those closest() found, computed again) and its smooth
// world normal facing the ray d (world): the interpolated vertex normals
// (ref_scene.c: the face normal where they cancel).
void surface_at(int e, Ray r, vec3 d, out vec3 p, out vec3 n)
{
    int base = u_tri_base + 6 * e;
    vec3 v0 = fetch_f(base).xyz, v1 = fetch_f(base + 1).xyz, v2 = fetch_f(base + 2).xyz;
    float t;
    vec3 b;
    tri_hit(r, v0, v1, v2, 0.0, 0.0, t, b);
    p = b.x * v0 + b.y * v1 + b.z * v2;
    vec3 s = u_normal_matrix * (b.x * fetch_f(base + 3).xyz + b.y * fetch_f(base + 4).xyz + b.z * fetch_f(base + 5).xyz);
    if (dot(s, s) == 0.0) s = u_normal_matrix * cross(v1 - v0, v2 - v0);
    n = normalize(s);
    if (dot(n, d) > 0.0) n = -n;
}
