/* SPDX-License-Identifier: MIT */
/* test_slow_inputs.c — issue 26 item 3: inputs made to be slow, not to crash.
 * Every loader and stage must finish within a bound that grows with its input
 * (per byte, corner, point or pixel), or stop at a stated limit. Each case
 * prints its size, its measured time and its bound, and checks what the code
 * counts deterministically where it counts something (the GPU copy's order
 * and its work estimate, copies hidden, the statuses of bounded stages), so a
 * regression shows even on a machine fast enough to hide it. Times are the
 * process's CPU time, not the wall clock: on a shared 2-core machine at load
 * 10 the wall clock ran 5x the CPU time and failed a 2.5 s bound that the
 * work itself (0.5 s) is far inside; a hang is still caught by the wall-clock
 * alarm. Bounds are generous: 0.5 s plus 10x to 100x what the clean inputs of
 * the same size take here, scaled by SNELL_TEST_TIME_SCALE under emulators.
 * CPU only: no context (label unit).
 *
 * Case A is the file of issue 26 item 1: one OBJ face of 120,000 corners on 3
 * vertices, whose vertex-cache reorder took 66 s. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, alarm */
#include "test_util.h"
#include "mesh/mesh.h"
#include "snell/snell_2d.h"

#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* This process's CPU time (all its threads), in seconds. */
static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* A stage that runs away must fail the test with a message, not hang ctest. */
static void on_alarm(int sig)
{
    static const char msg[] = "FAIL: a stage did not return within the alarm (unbounded work?)\n";
    (void)sig;
    if (write(2, msg, sizeof msg - 1) < 0) _exit(1);
    _exit(1);
}

/* Checks one timed stage against base + per_element * n seconds. */
static void check_time(const char *what, double dt, double n, const char *unit, double per_element)
{
    double bound = (0.5 + per_element * n) * test_time_scale();
    printf("  %-44s %10.0f %-8s %8.4f s  (bound %.2f s)\n", what, n, unit, dt, bound);
    CHECK(dt <= bound, "%s: %.3f s for %.0f %s, over its bound %.2f s", what, dt, n, unit, bound);
}

/* Per-element rates of the bounds: ~10-100x the clean inputs' here. */
#define PER_BYTE 2e-6     /* parsers: ~100 MB/s here (OBJ, glTF, scene, CSV) */
#define PER_CORNER 2e-6   /* GPU layout: bunny 0.13 us a corner (vertex-cache order) */
#define PER_TRIANGLE 2e-5 /* analysis, simplifier: bunny 3.6 us / 1.5 us a triangle */
#define PER_PIXEL 1e-6    /* contour: marching squares and RDP */

/* ---------------------------------------------------------------- meshes */

typedef struct mesh_expect {
    int gpu_linear;            /* 1: the reorder must be skipped (work over its bound) */
    int64_t copies;            /* copies_hidden expected (-1: any) */
    snell_status analysis;     /* expected status of snell_mesh_analyze */
    snell_status simplify;     /* expected status of snell_mesh_simplify (ratio 0.25) */
} mesh_expect;

/* The stages a mesh goes through: the GPU layout (what the upload does, no GL
 * needed), the analysis, the simplifier. */
static void mesh_stages(const char *name, snell_mesh *m, const mesh_expect *e)
{
    size_t nv = snell_mesh_vertex_count(m), nt = snell_mesh_triangle_count(m);
    float *vtx = (float *)malloc(6 * nv * sizeof(float));
    uint32_t *idx = (uint32_t *)malloc(3 * nt * sizeof(uint32_t));
    snell_mesh_gpu_stats gs;
    snell_mesh_analysis a;
    snell_simplify_desc sd;
    snell_simplify_report rep;
    snell_mesh *lod = NULL;
    snell_status st;
    double t0;
    char what[96];

    CHECK_OK(snell_mesh_gpu_stats_get(m, &gs));
    printf("  %s: %zu vertices, %zu triangles; GPU order %d, work %.3g (bound %.3g), %u corners on a vertex, "
           "%u copies hidden\n",
           name, nv, nt, (int)gs.order, gs.order_work, gs.order_work_limit, gs.max_valence, gs.copies_hidden);
    /* the work estimate is exact: it depends on the triangles only */
    CHECK(gs.order_work_limit == 33554432.0 + 64.0 * 3.0 * (double)nt, "%s: work limit %.0f", name,
          gs.order_work_limit);
#ifdef SNELL_WITH_MESHOPT_TEST
    CHECK(gs.order == (e->gpu_linear ? SNELL_GPU_ORDER_LINEAR : SNELL_GPU_ORDER_CACHE),
          "%s: GPU order %d, want %s (work %.3g, bound %.3g)", name, (int)gs.order, e->gpu_linear ? "LINEAR" : "CACHE",
          gs.order_work, gs.order_work_limit);
    CHECK((gs.order_work > gs.order_work_limit) == (gs.order == SNELL_GPU_ORDER_LINEAR), "%s: order vs work", name);
    if (e->copies >= 0)
        CHECK((int64_t)gs.copies_hidden == e->copies, "%s: %u copies hidden, want %lld", name, gs.copies_hidden,
              (long long)e->copies);
    if (gs.order == SNELL_GPU_ORDER_LINEAR)
        CHECK(strstr(gs.reason, "skipped") != NULL, "%s: reason \"%s\"", name, gs.reason);
#else
    CHECK(gs.order == SNELL_GPU_ORDER_SOURCE, "%s: GPU order %d without meshoptimizer", name, (int)gs.order);
#endif
    if (vtx && idx) {
        alarm(60);
        t0 = now_s();
        CHECK_OK(snell__mesh_gpu_layout(m, vtx, idx));
        snprintf(what, sizeof what, "%s: GPU layout", name);
        check_time(what, now_s() - t0, 3.0 * (double)nt, "corners", PER_CORNER);
        alarm(0);
    }
    free(vtx);
    free(idx);

    alarm(60);
    t0 = now_s();
    st = snell_mesh_analyze(m, &a);
    snprintf(what, sizeof what, "%s: analysis (%s)", name, snell_status_str(st));
    check_time(what, now_s() - t0, (double)nt, "tris", PER_TRIANGLE);
    alarm(0);
    CHECK(st == e->analysis, "%s: analysis %s, want %s: %s", name, snell_status_str(st), snell_status_str(e->analysis),
          snell_last_error(NULL));

    memset(&sd, 0, sizeof sd);
    sd.target_ratio = 0.25f;
    alarm(60);
    t0 = now_s();
    st = snell_mesh_simplify(NULL, m, &sd, &lod, &rep);
    snprintf(what, sizeof what, "%s: simplify (%s)", name, snell_status_str(st));
    check_time(what, now_s() - t0, (double)nt, "tris", PER_TRIANGLE);
    alarm(0);
#ifdef SNELL_WITH_MESHOPT_TEST
    CHECK(st == e->simplify, "%s: simplify %s, want %s: %s", name, snell_status_str(st), snell_status_str(e->simplify),
          snell_last_error(NULL));
    if (st == SNELL_E_LIMIT)
        CHECK(strstr(snell_last_error(NULL), "work estimate") != NULL, "%s: simplify message: %s", name,
              snell_last_error(NULL));
#endif
    snell_mesh_destroy(lod);
}

/* An OBJ held in memory, loaded and timed. */
static snell_mesh *load_obj_timed(const char *name, const char *text, size_t n)
{
    snell_mesh *m = NULL;
    snell_status st;
    double t0;
    char what[96];
    alarm(60);
    t0 = now_s();
    st = snell_mesh_load_obj_mem(NULL, text, n, &m);
    snprintf(what, sizeof what, "%s: OBJ load", name);
    check_time(what, now_s() - t0, (double)n, "bytes", PER_BYTE);
    alarm(0);
    CHECK(st == SNELL_OK, "%s: %s", name, snell_last_error(NULL));
    return m;
}

static snell_mesh *create_mesh(const float *pos, uint32_t nv, const uint32_t *idx, uint32_t nt)
{
    snell_mesh_desc d;
    snell_mesh *m = NULL;
    memset(&d, 0, sizeof d);
    d.positions = pos;
    d.vertex_count = nv;
    d.indices = idx;
    d.triangle_count = nt;
    CHECK_OK(snell_mesh_create(NULL, &d, &m));
    return m;
}

/* A: one face of `corners` corners cycling through 3 vertices (issue 26):
 * fan-triangulated, a third of the triangles is the one real triangle, the
 * rest have a repeated corner. */
static void case_face_repeated(int corners)
{
    size_t cap = 64 + 2 * (size_t)corners, n = 0;
    char *obj = (char *)malloc(cap);
    snell_mesh *m;
    mesh_expect e = {1, 0, SNELL_E_LIMIT, SNELL_OK};
    int i;
    printf("A. one OBJ face of %d corners on 3 vertices\n", corners);
    n += (size_t)snprintf(obj, cap, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf");
    for (i = 0; i < corners; i++) n += (size_t)snprintf(obj + n, cap - n, " %d", 1 + i % 3);
    n += (size_t)snprintf(obj + n, cap - n, "\n");
    m = load_obj_timed("face", obj, n);
    free(obj);
    if (!m) return;
    CHECK(snell_mesh_triangle_count(m) == (uint32_t)corners - 2, "face: %u triangles", snell_mesh_triangle_count(m));
    /* the fan (1, k, k+1): corners 1 2 3 repeat, so every third triangle is
     * (1 2 3); the others have a repeated corner and are not copies */
    e.copies = (corners - 2 + 2) / 3 - 1;
    mesh_stages("face", m, &e);
    snell_mesh_destroy(m);
}

/* B: a disc of n triangles fanned about its centre (valence n: a real, if
 * odd, mesh: the reorder and the simplifier are quadratic in it). */
static void case_fan(uint32_t n)
{
    float *p = (float *)malloc(3 * (size_t)(n + 1) * sizeof(float));
    uint32_t *idx = (uint32_t *)malloc(3 * (size_t)n * sizeof(uint32_t)), i;
    mesh_expect e = {1, 0, SNELL_E_LIMIT, SNELL_E_LIMIT};
    snell_mesh *m;
    printf("B. a disc of %u triangles fanned about one vertex\n", n);
    p[0] = p[1] = p[2] = 0.0f;
    for (i = 0; i < n; i++) {
        double a = 6.283185307179586 * i / n;
        p[3 * (i + 1)] = (float)cos(a);
        p[3 * (i + 1) + 1] = (float)sin(a);
        p[3 * (i + 1) + 2] = 0.0f;
        idx[3 * i] = 0;
        idx[3 * i + 1] = 1 + i;
        idx[3 * i + 2] = 1 + (i + 1) % n;
    }
    m = create_mesh(p, n + 1, idx, n);
    free(p);
    free(idx);
    if (!m) return;
    /* the analysis stops at its work bound: the flat disc's rays from
     * candidates in its plane run along it, through thousands of slivers */
    mesh_stages("fan", m, &e);
    snell_mesh_destroy(m);
}

/* C: all vertices equal: n triangles of 3 distinct vertices each, all at
 * the origin (no area anywhere), from an OBJ. */
static void case_all_equal(int nt)
{
    size_t cap = 64 + 64 * (size_t)nt, n = 0;
    char *obj = (char *)malloc(cap);
    snell_mesh *m;
    mesh_expect e = {0, 0, SNELL_E_INVALID_ARG, SNELL_E_INVALID_ARG};
    int i;
    printf("C. %d triangles, all %d vertices at one point\n", nt, 3 * nt);
    for (i = 0; i < 3 * nt; i++) n += (size_t)snprintf(obj + n, cap - n, "v 0 0 0\n");
    for (i = 0; i < nt; i++) n += (size_t)snprintf(obj + n, cap - n, "f %d %d %d\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
    m = load_obj_timed("all equal", obj, n);
    free(obj);
    if (!m) return;
    CHECK(snell_mesh_normalize(m, 1.0f) == SNELL_E_INVALID_ARG, "all equal: normalize must refuse");
    mesh_stages("all equal", m, &e);
    snell_mesh_destroy(m);
}

/* D: repeated indices: nt triangles (0, 0, 0) on a mesh of 3 vertices (the
 * one vertex carries every corner; nothing is drawn). */
static void case_repeated_index(uint32_t nt)
{
    static const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t *idx = (uint32_t *)calloc(3 * (size_t)nt + 3, sizeof(uint32_t));
    mesh_expect e = {1, 0, SNELL_E_INVALID_ARG, SNELL_E_INVALID_ARG};
    snell_mesh *m;
    printf("D. %u triangles (0 0 0)\n", nt);
    m = create_mesh(p, 3, idx, nt);
    free(idx);
    if (!m) return;
    mesh_stages("repeated index", m, &e);
    snell_mesh_destroy(m);
}

/* E: k copies of a closed tetrahedron on the same 4 vertices. */
static void case_coincident_tets(uint32_t k)
{
    static const float p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const uint32_t tet[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    uint32_t *idx = (uint32_t *)malloc(12 * (size_t)k * sizeof(uint32_t)), i;
    mesh_expect e = {1, 0, SNELL_E_LIMIT, SNELL_OK};
    snell_mesh *m;
    printf("E. %u coincident copies of a tetrahedron\n", k);
    for (i = 0; i < k; i++) memcpy(idx + 12 * (size_t)i, tet, sizeof tet);
    m = create_mesh(p, 4, idx, 4 * k);
    free(idx);
    if (!m) return;
    e.copies = 4 * ((int64_t)k - 1);
    mesh_stages("tetrahedra", m, &e);
    snell_mesh_destroy(m);
}

/* F: n coincident triangles on their own vertices (3n vertices at 3 points):
 * no shared vertex, so the GPU order is cheap; the weld joins them all. */
static void case_split_coincident(uint32_t n)
{
    float *p = (float *)malloc(9 * (size_t)n * sizeof(float));
    uint32_t *idx = (uint32_t *)malloc(3 * (size_t)n * sizeof(uint32_t)), i;
    static const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    mesh_expect e = {0, -1, SNELL_E_LIMIT, SNELL_OK};
    snell_mesh *m;
    printf("F. %u coincident triangles, each on its own 3 vertices\n", n);
    for (i = 0; i < n; i++) {
        memcpy(p + 9 * (size_t)i, tri, sizeof tri);
        idx[3 * i] = 3 * i;
        idx[3 * i + 1] = 3 * i + 1;
        idx[3 * i + 2] = 3 * i + 2;
    }
    m = create_mesh(p, 3 * n, idx, n);
    free(p);
    free(idx);
    if (!m) return;
    mesh_stages("split coincident", m, &e);
    snell_mesh_destroy(m);
}

/* ------------------------------------------------------------------ glTF */

static char *b64(const unsigned char *bin, size_t nb, char *out)
{
    static const char k[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t i, n = 0;
    for (i = 0; i < nb; i += 3) {
        unsigned v = (unsigned)bin[i] << 16 | (unsigned)(i + 1 < nb ? bin[i + 1] : 0) << 8 |
                     (unsigned)(i + 2 < nb ? bin[i + 2] : 0);
        out[n++] = k[v >> 18 & 63];
        out[n++] = k[v >> 12 & 63];
        out[n++] = i + 1 < nb ? k[v >> 6 & 63] : '=';
        out[n++] = i + 2 < nb ? k[v & 63] : '=';
    }
    out[n] = '\0';
    return out;
}

/* A glTF of one triangle mesh whose node tree is `nodes` (the JSON of the
 * "nodes" array) with scene roots `roots`. */
static char *gltf_with_nodes(const char *nodes, const char *roots, size_t *len)
{
    static const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    char data[64];
    size_t cap = strlen(nodes) + strlen(roots) + 1024;
    char *s = (char *)malloc(cap);
    int n = snprintf(s, cap,
                     "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":%s}],\"nodes\":%s,"
                     "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
                     "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"
                     "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36}],"
                     "\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/octet-stream;base64,%s\"}]}",
                     roots, nodes, b64((const unsigned char *)tri, sizeof tri, data));
    *len = (size_t)n;
    return s;
}

/* work: the elements the load handles besides the file's bytes (instances
 * of a shared subtree: 9 floats each, up to the 2^20 instance limit) */
static void gltf_case(const char *what, const char *nodes, const char *roots, snell_status want, uint32_t want_tris,
                      double work)
{
    size_t len = 0;
    char *g = gltf_with_nodes(nodes, roots, &len);
    snell_mesh *m = NULL;
    snell_status st;
    double t0;
    char label[96];
    alarm(60);
    t0 = now_s();
    st = snell_mesh_load_gltf_mem(NULL, g, len, &m);
    snprintf(label, sizeof label, "%s (%s)", what, snell_status_str(st));
    if (st == SNELL_E_UNSUPPORTED) {
        printf("  %s: skipped, built without glTF\n", what);
    } else {
        /* per byte, and per triangle made (instances multiply the file) */
        check_time(label, now_s() - t0, (double)len + work, "bytes+", PER_BYTE);
        CHECK(st == want, "%s: %s, want %s: %s", what, snell_status_str(st), snell_status_str(want),
              snell_last_error(NULL));
        if (m) CHECK(snell_mesh_triangle_count(m) == want_tris, "%s: %u triangles", what, snell_mesh_triangle_count(m));
    }
    alarm(0);
    snell_mesh_destroy(m);
    free(g);
}

static void case_gltf(void)
{
    size_t cap = 64 * 4096, n, i;
    char *nodes = (char *)malloc(cap);
    printf("G. glTF node trees\n");
    /* a chain of 256 nodes (the loader's depth limit) and one of 300 */
    {
        int depth;
        for (depth = 256; depth <= 300; depth += 44) {
            char what[64];
            n = (size_t)snprintf(nodes, cap, "[");
            for (i = 0; i < (size_t)depth; i++)
                n += (size_t)snprintf(nodes + n, cap - n, "%s{\"children\":[%zu]}", i ? "," : "", i + 1);
            n += (size_t)snprintf(nodes + n, cap - n, ",{\"mesh\":0}]");
            snprintf(what, sizeof what, "chain of %d nodes", depth + 1);
            gltf_case(what, nodes, "[0]", depth <= 256 ? SNELL_OK : SNELL_E_PARSE, 1, (double)depth);
        }
    }
    /* shared subtrees: node k has node k+1 twice as children, so 2^d
     * instances of the leaf's triangle from d + 1 nodes */
    {
        int d;
        for (d = 16; d <= 21; d += 5) {
            char what[64];
            n = (size_t)snprintf(nodes, cap, "[");
            for (i = 0; i < (size_t)d; i++)
                n += (size_t)snprintf(nodes + n, cap - n, "%s{\"children\":[%zu,%zu]}", i ? "," : "", i + 1, i + 1);
            n += (size_t)snprintf(nodes + n, cap - n, ",{\"mesh\":0}]");
            snprintf(what, sizeof what, "2^%d instances from %d nodes", d, d + 1);
            /* 2^21 leaf instances (and as many inner ones) are over the 2^20 instance limit */
            gltf_case(what, nodes, "[0]", d <= 16 ? SNELL_OK : SNELL_E_LIMIT, 1u << d, 9.0 * (double)(1u << (d < 20 ? d : 20)));
        }
    }
    /* many roots: 4096 instances of one mesh listed in the scene */
    n = (size_t)snprintf(nodes, cap, "[");
    for (i = 0; i < 4096; i++) n += (size_t)snprintf(nodes + n, cap - n, "%s%zu", i ? "," : "", (size_t)0);
    n += (size_t)snprintf(nodes + n, cap - n, "]");
    gltf_case("4096 scene roots on one node", "[{\"mesh\":0}]", nodes, SNELL_OK, 4096, 9.0 * 4096);
    free(nodes);
    /* deep JSON: 200,000 nested arrays in "extras" */
    {
        size_t depth = 200000, len = 0;
        char *deep = (char *)malloc(2 * depth + 64);
        char *g;
        snell_mesh *m = NULL;
        snell_status st;
        double t0;
        n = (size_t)snprintf(deep, 64, "[{\"mesh\":0,\"extras\":");
        memset(deep + n, '[', depth);
        memset(deep + n + depth, ']', depth);
        snprintf(deep + n + 2 * depth, 8, "}]");
        g = gltf_with_nodes(deep, "[0]", &len);
        alarm(60);
        t0 = now_s();
        st = snell_mesh_load_gltf_mem(NULL, g, len, &m);
        if (st != SNELL_E_UNSUPPORTED) {
            check_time("JSON nested 200,000 deep", now_s() - t0, (double)len, "bytes", PER_BYTE);
            CHECK(st == SNELL_E_LIMIT, "deep JSON: %s: %s", snell_status_str(st), snell_last_error(NULL));
        }
        alarm(0);
        snell_mesh_destroy(m);
        free(g);
        free(deep);
    }
}

/* -------------------------------------------------------------------- 2D */

static snell_status scene2d_timed(const char *what, const char *path, double bytes, snell_status want,
                                  const char *needle)
{
    snell_scene2d *s = NULL;
    snell_status st;
    double t0;
    char label[96];
    float view[4];
    int size[2];
    alarm(60);
    t0 = now_s();
    st = snell_scene2d_load(NULL, path, &s, view, size);
    snprintf(label, sizeof label, "%s (%s)", what, snell_status_str(st));
    alarm(0);
    snell_scene2d_destroy(s);
    if (st == SNELL_E_UNSUPPORTED) {
        printf("  %s: skipped, built without lm2d\n", what);
        return st;
    }
    check_time(label, now_s() - t0, bytes, "bytes", PER_BYTE);
    CHECK(st == want, "%s: %s, want %s: %s", what, snell_status_str(st), snell_status_str(want),
          snell_last_error(NULL));
    if (needle) CHECK(strstr(snell_last_error(NULL), needle) != NULL, "%s: message: %s", what, snell_last_error(NULL));
    return st;
}

static void case_scene2d(void)
{
    char scene[1024], csv[1024]; /* test_out's buffer is static: one copy each */
    size_t cap = (size_t)16 << 20, n = 0, csv_bytes;
    char *text = (char *)malloc(cap);
    int i, j;
    printf("H. 2D scene files\n");
    snprintf(scene, sizeof scene, "%s", test_out("slow_scene.txt"));
    snprintf(csv, sizeof csv, "%s", test_out("slow_points.csv"));
    /* 400 polygon lines of 2000 points each (800,000 points, 9.6 MB) */
    for (i = 0; i < 400; i++) {
        n += (size_t)snprintf(text + n, cap - n, "polygon");
        for (j = 0; j < 2000; j++) {
            double a = 6.283185307179586 * j / 2000;
            n += (size_t)snprintf(text + n, cap - n, " %.2f %.2f", 32 + 20 * cos(a), 32 + 20 * sin(a));
        }
        n += (size_t)snprintf(text + n, cap - n, " ; t 1 ior 1.5\n");
    }
    CHECK(test_write_file(scene, text, n), "writing %s", scene);
    if (scene2d_timed("400 polygons of 2000 points", scene, (double)n, SNELL_OK, NULL) == SNELL_E_UNSUPPORTED) {
        free(text);
        return;
    }
    /* one line of 5000 tokens: over the 4096 a line holds */
    n = (size_t)snprintf(text, cap, "polygon");
    for (j = 0; j < 5000; j++) n += (size_t)snprintf(text + n, cap - n, " 1");
    n += (size_t)snprintf(text + n, cap - n, "\n");
    CHECK(test_write_file(scene, text, n), "writing %s", scene);
    scene2d_timed("a line of 5000 tokens", scene, (double)n, SNELL_E_LIMIT, "tokens");
    /* 10 MB of comments and blank lines */
    for (n = 0; n + 16 < (size_t)10 << 20 && n + 16 < cap;) n += (size_t)snprintf(text + n, cap - n, "#\n\n   \n");
    CHECK(test_write_file(scene, text, n), "writing %s", scene);
    scene2d_timed("10 MB of comments", scene, (double)n, SNELL_OK, NULL);
    /* a CSV of 200,000 points named on 30 lines of a 1 KB scene: 6M points
     * (issue 26: the scene's cost was not bounded by its bytes) */
    for (n = 0, j = 0; j < 200000; j++) {
        double a = 6.283185307179586 * j / 200000;
        n += (size_t)snprintf(text + n, cap - n, "%.4f,%.4f\n", 32 + 20 * cos(a), 32 + 20 * sin(a));
    }
    CHECK(test_write_file(csv, text, n), "writing %s", csv);
    csv_bytes = n;
    for (n = 0, i = 0; i < 30; i++) n += (size_t)snprintf(text + n, cap - n, "object slow_points.csv t 1\n");
    CHECK(test_write_file(scene, text, n), "writing %s", scene);
    /* bounded by the points the scene may hold (4M: 21 reads of the CSV) */
    scene2d_timed("one 200k-point CSV named 30 times", scene, 21.0 * (double)csv_bytes, SNELL_E_LIMIT,
                  "more than 4000000 points");
    /* a CSV of 1,000,000 equal points: a degenerate polygon */
    for (n = 0, j = 0; j < 1000000 && n + 16 < cap; j++) n += (size_t)snprintf(text + n, cap - n, "1,1\n");
    CHECK(test_write_file(csv, text, n), "writing %s", csv);
    csv_bytes = n;
    n = (size_t)snprintf(text, cap, "object slow_points.csv\n");
    CHECK(test_write_file(scene, text, n), "writing %s", scene);
    scene2d_timed("a CSV of 1M equal points", scene, (double)csv_bytes, SNELL_E_INVALID_ARG, "degenerate");
    free(text);
}

/* Contours of images made to be slow: a checkerboard (a loop around every
 * pixel) and a spiral (one long outline that RDP splits many times). */
static void case_contour(int size)
{
    uint8_t *rgba = (uint8_t *)calloc((size_t)size * size, 4);
    float *pts = NULL;
    int count = 0, x, y;
    snell_status st;
    double t0;
    printf("I. 2D contours of %dx%d images\n", size, size);
    for (y = 0; y < size; y++)
        for (x = 0; x < size; x++) rgba[4 * ((size_t)y * size + x) + 3] = (uint8_t)(((x ^ y) & 1) ? 255 : 0);
    alarm(60);
    t0 = now_s();
    st = snell_contour2d_from_alpha(NULL, rgba, size, size, 128, 0.5f, &pts, &count);
    alarm(0);
    if (st == SNELL_E_UNSUPPORTED) {
        printf("  contours: skipped, built without lm2d\n");
        free(rgba);
        return;
    }
    check_time("checkerboard contour", now_s() - t0, (double)size * size, "pixels", PER_PIXEL);
    snell_contour2d_free(NULL, pts);
    pts = NULL;
    /* an Archimedean spiral arm, 3 pixels wide, turns 6 pixels apart */
    memset(rgba, 0, (size_t)size * size * 4);
    for (y = 0; y < size; y++)
        for (x = 0; x < size; x++) {
            double dx = x - size / 2.0, dy = y - size / 2.0, r = sqrt(dx * dx + dy * dy), a = atan2(dy, dx);
            double u = fmod(r - 6.0 * a / 6.283185307179586 + 600.0, 6.0);
            if (u < 3.0) rgba[4 * ((size_t)y * size + x) + 3] = 255;
        }
    alarm(60);
    t0 = now_s();
    st = snell_contour2d_from_alpha(NULL, rgba, size, size, 128, 0.5f, &pts, &count);
    alarm(0);
    check_time("spiral contour", now_s() - t0, (double)size * size, "pixels", PER_PIXEL);
    CHECK(st == SNELL_OK, "spiral: %s", snell_last_error(NULL));
    /* RDP stops at its work bound here (176 distance tests a point, the
     * bound 128 + 2^24 in all): 165,550 points kept instead of 58,998 */
    printf("  spiral: %d points kept\n", count);
    snell_contour2d_free(NULL, pts);
    free(rgba);
}

/* The 2D lightmap's first frame of a scene file (ctx NULL: the default memory
 * budget, CPU only): within the per-byte bound of its file, with status want. */
static void lightmap2d_timed(const char *what, const char *path, double bytes, int size, snell_status want)
{
    snell_scene2d *s = NULL;
    snell_lightmap2d *lm = NULL;
    snell_lightmap2d_desc d;
    snell_status st;
    double t0;
    char label[96];
    alarm(60);
    t0 = now_s();
    st = snell_scene2d_load(NULL, path, &s, NULL, NULL);
    if (st == SNELL_OK) {
        memset(&d, 0, sizeof d);
        d.width = d.height = size;
        d.cpu_only = 1;
        st = snell_lightmap2d_create(NULL, &d, &lm);
        if (st == SNELL_OK) st = snell_lightmap2d_frame(lm, s, NULL);
    }
    alarm(0);
    snprintf(label, sizeof label, "%s (%s)", what, snell_status_str(st));
    snell_lightmap2d_destroy(lm);
    snell_scene2d_destroy(s);
    check_time(label, now_s() - t0, bytes, "bytes", PER_BYTE);
    CHECK(st == want, "%s: %s, want %s: %s", what, snell_status_str(st), snell_status_str(want),
          snell_last_error(NULL));
    if (want == SNELL_E_LIMIT)
        CHECK(strstr(snell_last_error(NULL), "memory budget") != NULL, "%s: message: %s", what, snell_last_error(NULL));
}

/* Scene files of a few hundred bytes to a few MB that ask the lightmap for
 * gigabytes (issue 40 item 2): refused before allocating, in about no time. */
static void case_lightmap2d(void)
{
    char scene[1024];
    size_t cap = (size_t)24 << 20, n;
    char *text = (char *)malloc(cap);
    int i;
    printf("J. 2D lightmap frames\n");
    snprintf(scene, sizeof scene, "%s", test_out("slow_lights.txt"));
    /* twelve lights of 500,000 rays in a glass box whose walls trap light (TIR) */
    n = (size_t)snprintf(text, cap, "view 0 0 100 100\npolygon 10 10 90 10 90 90 10 90 ; t 1 ior 1.5\n");
    for (i = 0; i < 12; i++) n += (size_t)snprintf(text + n, cap - n, "light point pos %d 50 rays 500000\n", 20 + 5 * i);
    CHECK(test_write_file(scene, text, n), "writing %s", scene);
    lightmap2d_timed("12 lights of 500,000 rays", scene, (double)n, 256, SNELL_E_LIMIT);
    /* a million lights of the default rays (22 MB) */
    n = (size_t)snprintf(text, cap, "view 0 0 100 100\npolygon 10 10 90 10 90 90 10 90 ; t 1 ior 1.5\n");
    for (i = 0; i < 1000000 && n + 32 < cap; i++)
        n += (size_t)snprintf(text + n, cap - n, "light point pos %d 50\n", 20 + i % 60);
    CHECK(test_write_file(scene, text, n), "writing %s", scene);
    lightmap2d_timed("a million lights", scene, (double)n, 256, SNELL_E_LIMIT);
    /* a 16384^2 lightmap (4 GiB of floats) for a one-light scene */
    n = (size_t)snprintf(text, cap, "view 0 0 100 100\nlight point pos 50 50 rays 100\n");
    CHECK(test_write_file(scene, text, n), "writing %s", scene);
    lightmap2d_timed("a 16384x16384 lightmap", scene, (double)n, 16384, SNELL_E_LIMIT);
    lightmap2d_timed("the same scene on 256x256", scene, (double)n, 256, SNELL_OK);
    free(text);
}

int main(void)
{
    signal(SIGALRM, on_alarm);
    setvbuf(stdout, NULL, _IOLBF, 0); /* each case's line out before a stage that might hang */
    case_face_repeated(120000);
    case_fan(100000);
    case_all_equal(50000);
    case_repeated_index(50000);
    case_coincident_tets(10000);
    case_split_coincident(50000);
    case_gltf();
    case_scene2d();
    case_contour(1024);
    case_lightmap2d();
    return test_finish();
}
