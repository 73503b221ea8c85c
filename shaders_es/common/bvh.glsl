// SPDX-License-Identifier: MIT
// bvh.glsl - closest-hit traversal of a mesh's BVH texture (methods/exact.c
// builds and packs it, once per mesh version, in the prepared cache), shared
// by exact.frag (eye rays) and caustics_photon.vert (photons from the light).
//
// The BVH (one 2D texture, TEX_WIDTH texels a row, texelFetch only): nodes in
// depth-first order, a node's first child right after it and its escape
// index where the walk goes on a miss (a leaf's escape is the next node, and
// an interior node's second child its first child's escape); then 6 texels per triangle
// entry: v0, v1, v2, n0, n1, n2 in object space. SNELL_NODES_Q16: the
// texture is RGBA32UI, nodes one texel of 16-bit bounds (qlo + q * qstep,
// rounded outward) and a word, triangles the floats' bits.
//
// Spaces: traversal in object space with the world ray parameter (d = M^-1 *
// unit world direction), so t is a world length for any model matrix;
// normals go to world space by the normal matrix. highp throughout.
#define MAX_INTERFACES 10    // SNELL_EXACT_MAX_INTERFACES
#define LEAF_MAX 4           // exact.c LEAF_MAX
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
int g_visits = 0;                // nodes this pixel visited, all its rays
bool g_over = false;             // the budget ran out

ivec2 texel(int i)
{
    return ivec2(i & TEX_MASK, i >> TEX_SHIFT);
}

#if SNELL_NODES_Q16
vec4 fetch_f(int i)
{
    return uintBitsToFloat(texelFetch(u_bvh, texel(i), 0));
}

// Node i: its bounds, and for a leaf its first entry and count (count 0: an
// interior node, first = its escape).
void fetch_node(int i, out vec3 lo, out vec3 hi, out int first, out int count)
{
    uvec4 t = texelFetch(u_bvh, texel(i), 0);
    lo = u_qlo + vec3(float(t.x & 0xffffu), float(t.x >> 16), float(t.y & 0xffffu)) * u_qstep;
    hi = u_qlo + vec3(float(t.y >> 16), float(t.z & 0xffffu), float(t.z >> 16)) * u_qstep;
    bool leaf = (t.w & 0x80000000u) != 0u;
    first = leaf ? int((t.w & 0x7fffffffu) >> 2) : int(t.w);
    count = leaf ? int(t.w & 3u) + 1 : 0;
}
#else
vec4 fetch_f(int i)
{
    return texelFetch(u_bvh, texel(i), 0);
}

void fetch_node(int i, out vec3 lo, out vec3 hi, out int first, out int count)
{
    vec4 a = texelFetch(u_bvh, texel(2 * i), 0);
    vec4 b = texelFetch(u_bvh, texel(2 * i + 1), 0);
    lo = a.xyz;
    hi = b.xyz;
    first = int(a.w);
    count = int(b.w);
}
#endif

// A ray o + t d with the per-ray constants of the watertight test (Woop,
// Benthin, Wald 2013; ref_bvh.c ray_setup): P permutes (x, y, z) into (kx,
// ky, kz), kz the dominant axis, kx and ky swapped when d[kz] < 0; s the
// shear onto +z.
struct Ray {
    vec3 o, d, inv;
    mat3 P;
    vec3 s;
};

Ray make_ray(vec3 o, vec3 d)
{
    Ray r;
    vec3 a = abs(d);
    int kz = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
    vec3 ex = kz == 0 ? vec3(0, 1, 0) : (kz == 1 ? vec3(0, 0, 1) : vec3(1, 0, 0));
    vec3 ey = kz == 0 ? vec3(0, 0, 1) : (kz == 1 ? vec3(1, 0, 0) : vec3(0, 1, 0));
    vec3 ez = kz == 0 ? vec3(1, 0, 0) : (kz == 1 ? vec3(0, 1, 0) : vec3(0, 0, 1));
    float dz = dot(ez, d);
    if (dz < 0.0) {
        vec3 tmp = ex;
        ex = ey;
        ey = tmp;
    }
    r.o = o;
    r.d = d;
    // a zero component would make 1/0; 1e-30 keeps the slab test finite and conservative
    r.inv = 1.0 / mix(d, vec3(1e-30), equal(d, vec3(0.0)));
    r.P = transpose(mat3(ex, ey, ez));
    r.s = vec3(dot(ex, d) / dz, dot(ey, d) / dz, 1.0 / dz);
    return r;
}

// Watertight ray-triangle test (ref_bvh.c tri_hit, in float): t in (tmin,
// tmax) and the barycentric weights of v0, v1, v2.
bool tri_hit(Ray r, vec3 v0, vec3 v1, vec3 v2, float tmin, float tmax, out float t, out vec3 b)
{
    vec3 A = r.P * (v0 - r.o), B = r.P * (v1 - r.o), C = r.P * (v2 - r.o);
    float ax = A.x - r.s.x * A.z, ay = A.y - r.s.y * A.z;
    float bx = B.x - r.s.x * B.z, by = B.y - r.s.y * B.z;
    float cx = C.x - r.s.x * C.z, cy = C.y - r.s.y * C.z;
    float u = cx * by - cy * bx;
    float v = ax * cy - ay * cx;
    float w = bx * ay - by * ax;
    t = 0.0;
    b = vec3(0.0);
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
    float det = u + v + w;
    if (det == 0.0) return false;
    float T = u * (r.s.z * A.z) + v * (r.s.z * B.z) + w * (r.s.z * C.z);
    float rcp = 1.0 / det;
    t = T * rcp;
    if (!(t > tmin && t < tmax)) return false;
    b = vec3(u, v, w) * rcp;
    return true;
}

bool box_hit(Ray r, vec3 lo, vec3 hi, float tmax)
{
    vec3 t0 = (lo - r.o) * r.inv, t1 = (hi - r.o) * r.inv;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    return max(max(tn.x, tn.y), max(tn.z, 0.0)) <= min(min(tf.x, tf.y), min(tf.z, tmax));
}

// The leaf's triangles (first .. first + count - 1) against the ray: the closest
// hit so far in best, tbest and b.
void leaf_hits(Ray r, int first, int count, float tmin, inout float tbest, int skip, inout int best, inout vec3 b)
{
    for (int k = 0; k < LEAF_MAX; k++) {
        if (k >= count) break;
        int e = first + k;
        if (e == skip) continue;
        int base = u_tri_base + 6 * e;
        float t;
        vec3 bb;
        if (tri_hit(r, fetch_f(base).xyz, fetch_f(base + 1).xyz, fetch_f(base + 2).xyz, tmin, tbest, t, bb)) {
            tbest = t;
            best = e;
            b = bb;
        }
    }
}

// Closest hit with t in (tmin, tbest), skipping entry skip: its entry (tbest
// and b set) or -1; sets g_over when the pixel's budget (or the stack) runs
// out, and the answer is then not to be used. Stackless: on a hit box the
// walk descends (next node), on a miss or after a leaf it takes the node's
// escape; it needs no stack and has no depth bound, but visits children in
// build order.
#if !SNELL_STACK_WALK
int closest(Ray r, float tmin, inout float tbest, int skip, out vec3 b)
{
    int best = -1;
    int node = 0;
    b = vec3(0.0);
    for (int it = 0; it < SNELL_NODE_BUDGET; it++) {
        if (node >= u_node_count) break;
        if (g_visits >= SNELL_NODE_BUDGET) {
            g_over = true;
            break;
        }
        g_visits++;
        vec3 lo, hi;
        int first, count;
        fetch_node(node, lo, hi, first, count);
        bool in_box = box_hit(r, lo, hi, tbest);
        if (count == 0) {
            node = in_box ? node + 1 : first;
            continue;
        }
        node++;
        if (in_box) leaf_hits(r, first, count, tmin, tbest, skip, best, b);
    }
    return best;
}
#else
#define STACK_SIZE 32
// Slab entry parameter, or 3e38 on a miss.
float box_enter(Ray r, vec3 lo, vec3 hi, float tmax)
{
    vec3 t0 = (lo - r.o) * r.inv, t1 = (hi - r.o) * r.inv;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    float a = max(max(tn.x, tn.y), max(tn.z, 0.0));
    return a <= min(min(tf.x, tf.y), min(tf.z, tmax)) ? a : 3.0e38;
}

// Near-first with a short stack: both children's boxes tested, the nearer
// visited, the farther pushed with its entry parameter (skipped on pop once
// a hit is nearer). At most one push per level, so STACK_SIZE bounds the
// tree depth it walks; a pixel that would overflow it falls back.
int closest(Ray r, float tmin, inout float tbest, int skip, out vec3 b)
{
    int stack[STACK_SIZE];
    float stack_t[STACK_SIZE];
    int sp = 0, best = -1;
    vec3 lo, hi;
    int first, count;
    b = vec3(0.0);
    g_visits++;
    fetch_node(0, lo, hi, first, count);
    if (box_enter(r, lo, hi, tbest) > 1.0e38) return -1;
    int node = 0;
    for (int it = 0; it < SNELL_NODE_BUDGET; it++) {
        if (g_visits >= SNELL_NODE_BUDGET) {
            g_over = true;
            break;
        }
        bool pop = true;
        if (count > 0) {
            leaf_hits(r, first, count, tmin, tbest, skip, best, b);
        } else {
            vec3 lo0, hi0, lo1, hi1;
            int f0, n0, f1, n1;
            int c0 = node + 1;
            g_visits += 2;
            fetch_node(c0, lo0, hi0, f0, n0);
            int c1 = n0 > 0 ? c0 + 1 : f0;
            fetch_node(c1, lo1, hi1, f1, n1);
            float t0 = box_enter(r, lo0, hi0, tbest), t1 = box_enter(r, lo1, hi1, tbest);
            bool near0 = t0 <= t1;
            float tn = near0 ? t0 : t1, tf = near0 ? t1 : t0;
            if (tf < 1.0e38) {
                if (sp >= STACK_SIZE) {
                    g_over = true;                               // deeper than the stack: the fallback
                    break;
                }
                stack[sp] = near0 ? c1 : c0;
                stack_t[sp] = tf;
                sp++;
            }
            if (tn < 1.0e38) {
                node = near0 ? c0 : c1;
                first = near0 ? f0 : f1;
                count = near0 ? n0 : n1;
                pop = false;
            }
        }
        if (pop) {
            bool found = false;
            for (int q = 0; q < STACK_SIZE; q++) {
                if (sp == 0) break;
                sp--;
                if (stack_t[sp] < tbest) {
                    node = stack[sp];
                    found = true;
                    break;
                }
            }
            if (!found) break;
            fetch_node(node, lo, hi, first, count);
        }
    }
    return best;
}
#endif

// Entry e's point at weights b (object space, on the triangle, as the
// reference's hit point) and its smooth world normal facing the ray d
// (world): the interpolated vertex normals (ref_scene.c: the face normal
// where they cancel).
void surface_at(int e, vec3 b, vec3 d, out vec3 p, out vec3 n)
{
    int base = u_tri_base + 6 * e;
    vec3 v0 = fetch_f(base).xyz, v1 = fetch_f(base + 1).xyz, v2 = fetch_f(base + 2).xyz;
    p = b.x * v0 + b.y * v1 + b.z * v2;
    vec3 s = u_normal_matrix * (b.x * fetch_f(base + 3).xyz + b.y * fetch_f(base + 4).xyz + b.z * fetch_f(base + 5).xyz);
    if (dot(s, s) == 0.0) s = u_normal_matrix * cross(v1 - v0, v2 - v0);
    n = normalize(s);
    if (dot(n, d) > 0.0) n = -n;
}

