/* SPDX-License-Identifier: MIT */
/* test_mesh_gltf.c — glTF loader: node hierarchy and transforms (TRS, matrix,
 * mirroring), index types, strips, interleaved buffers, .gltf/.glb/external
 * buffer equivalence, and malformed files (status + non-empty message, no crash). */
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static unsigned char *read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    unsigned char *buf;
    long n;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = (unsigned char *)malloc(n > 0 ? (size_t)n : 1);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    *size = (size_t)n;
    return buf;
}

static int near3(const float *a, float x, float y, float z, float tol)
{
    return fabsf(a[0] - x) <= tol && fabsf(a[1] - y) <= tol && fabsf(a[2] - z) <= tol;
}

static int has_vertex(const snell_mesh *m, float px, float py, float pz, float nx, float ny, float nz)
{
    uint32_t i;
    for (i = 0; i < snell_mesh_vertex_count(m); i++)
        if (near3(snell_mesh_positions(m) + 3 * i, px, py, pz, 1e-5f) &&
            near3(snell_mesh_normals(m) + 3 * i, nx, ny, nz, 1e-5f))
            return 1;
    return 0;
}

/* Expected content of nodes.gltf, derived from the definitions in make_gltf.py. */
static void check_nodes_model(const snell_mesh *m, const char *what)
{
    float mn[3], mx[3];
    uint32_t t;
    /* scene 0 = nodes 0 (children 1, 2), 3, 4: 3 + 3 + 4 + 3 vertices, 1 + 1 + 2 + 1 triangles;
     * node 5 lives in scene 1 only */
    CHECK(snell_mesh_vertex_count(m) == 13, "%s: vertices %u", what, snell_mesh_vertex_count(m));
    CHECK(snell_mesh_triangle_count(m) == 5, "%s: triangles %u", what, snell_mesh_triangle_count(m));
    /* node 1: T(10,0,0) Rz(90) S(2): (1,0,0) -> (0,2,0) -> (10,2,0); (0,1,0) -> (-2,0,0) -> (8,0,0) */
    CHECK(has_vertex(m, 10, 0, 0, 0, 0, 1) && has_vertex(m, 10, 2, 0, 0, 0, 1) && has_vertex(m, 8, 0, 0, 0, 0, 1),
          "%s: node 1 (TRS under a translated parent)", what);
    /* node 2: T(10,0,0) T(0,5,0) S(1,1,-1); mirrored, so the winding flips and the
     * computed normal of the (unchanged, z = 0) triangle faces -z */
    CHECK(has_vertex(m, 10, 5, 0, 0, 0, -1) && has_vertex(m, 11, 5, 0, 0, 0, -1) && has_vertex(m, 10, 6, 0, 0, 0, -1),
          "%s: node 2 (mirroring matrix)", what);
    /* node 3: strip quad at z = -3, computed normals +z */
    CHECK(has_vertex(m, 0, 0, -3, 0, 0, 1) && has_vertex(m, 1, 0, -3, 0, 0, 1) && has_vertex(m, 0, 1, -3, 0, 0, 1) &&
              has_vertex(m, 1, 1, -3, 0, 0, 1),
          "%s: node 3 (triangle strip)", what);
    /* node 4: interleaved position+normal, uint32 indices, T(0,-7,0) */
    CHECK(has_vertex(m, 0, -7, 0, 1, 0, 0) && has_vertex(m, 0, -6, 0, 1, 0, 0) && has_vertex(m, 0, -7, 1, 1, 0, 0),
          "%s: node 4 (interleaved, byteStride 24)", what);
    snell_mesh_bounds(m, mn, mx);
    CHECK(near3(mn, 0, -7, -3, 1e-5f) && near3(mx, 11, 6, 1, 1e-5f), "%s: bounds", what);
    /* every triangle is wound so that its geometric normal agrees with its vertex normals */
    for (t = 0; t < snell_mesh_triangle_count(m); t++) {
        const uint32_t *ix = snell_mesh_indices(m) + 3 * t;
        const float *a = snell_mesh_positions(m) + 3 * ix[0], *b = snell_mesh_positions(m) + 3 * ix[1],
                    *c = snell_mesh_positions(m) + 3 * ix[2], *n = snell_mesh_normals(m) + 3 * ix[0];
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        float g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        CHECK(g[0] * n[0] + g[1] * n[1] + g[2] * n[2] > 0.0f, "%s: triangle %u wound against its normal", what, t);
    }
}

static int same_mesh(const snell_mesh *a, const snell_mesh *b)
{
    uint32_t nv = snell_mesh_vertex_count(a), nt = snell_mesh_triangle_count(a);
    return nv == snell_mesh_vertex_count(b) && nt == snell_mesh_triangle_count(b) &&
           !memcmp(snell_mesh_positions(a), snell_mesh_positions(b), 12 * (size_t)nv) &&
           !memcmp(snell_mesh_normals(a), snell_mesh_normals(b), 12 * (size_t)nv) &&
           !memcmp(snell_mesh_indices(a), snell_mesh_indices(b), 12 * (size_t)nt);
}

static void test_valid(void)
{
    snell_mesh *g = NULL, *b = NULL, *e = NULL, *mm = NULL;
    unsigned char *data;
    size_t size;
    CHECK_OK(snell_mesh_load(NULL, test_data("nodes.gltf"), &g));
    if (g) check_nodes_model(g, "nodes.gltf");
    CHECK_OK(snell_mesh_load(NULL, test_data("nodes.glb"), &b));
    CHECK_OK(snell_mesh_load_gltf(NULL, test_data("nodes_ext.gltf"), &e));
    CHECK(g && b && same_mesh(g, b), "nodes.glb differs from nodes.gltf");
    CHECK(g && e && same_mesh(g, e), "nodes_ext.gltf (external nodes.bin) differs from nodes.gltf");

    data = read_file(test_data("nodes.glb"), &size);
    CHECK(data != NULL, "read nodes.glb");
    if (data) {
        CHECK_OK(snell_mesh_load_gltf_mem(NULL, data, size, &mm));
        CHECK(g && mm && same_mesh(g, mm), "GLB from memory differs");
        snell_mesh_destroy(mm);
        mm = NULL;
        free(data);
    }
    /* memory input must not read files: the external-buffer variant fails there */
    data = read_file(test_data("nodes_ext.gltf"), &size);
    if (data) {
        snell_status st = snell_mesh_load_gltf_mem(NULL, data, size, &mm);
        CHECK(st != SNELL_OK && mm == NULL && snell_last_error(NULL)[0], "external buffer from memory: %s",
              snell_status_str(st));
        free(data);
    }
    snell_mesh_destroy(g);
    snell_mesh_destroy(b);
    snell_mesh_destroy(e);
}

/* --- malformed input --------------------------------------------------------- */
static void base64(const unsigned char *in, size_t n, char *out)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t i;
    for (i = 0; i < n; i += 3) {
        unsigned v = (unsigned)in[i] << 16 | (i + 1 < n ? (unsigned)in[i + 1] << 8 : 0) | (i + 2 < n ? in[i + 2] : 0);
        *out++ = tab[(v >> 18) & 63];
        *out++ = tab[(v >> 12) & 63];
        *out++ = i + 1 < n ? tab[(v >> 6) & 63] : '=';
        *out++ = i + 2 < n ? tab[v & 63] : '=';
    }
    *out = 0;
}

/* One triangle: 36 bytes of positions, 3 uint16 indices, 2 bytes padding. */
static char *make_base(const uint16_t idx[3], float x0)
{
    unsigned char buf[44];
    float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    char b64[64], *json = (char *)malloc(2048);
    p[0] = x0;
    memset(buf, 0, sizeof buf);
    memcpy(buf, p, 36);
    memcpy(buf + 36, idx, 6);
    base64(buf, 44, b64);
    sprintf(json,
            "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
            "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},"
            "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],"
            "\"buffers\":[{\"byteLength\":44,\"uri\":\"data:application/octet-stream;base64,%s\"}]}",
            b64);
    return json;
}

/* base with the first occurrence of from replaced by to (malloc'd). */
static char *replace(const char *base, const char *from, const char *to)
{
    const char *at = strstr(base, from);
    char *out;
    if (!at) {
        CHECK(0, "test bug: '%s' not in the template", from);
        return NULL;
    }
    out = (char *)malloc(strlen(base) + strlen(to) + 1);
    memcpy(out, base, (size_t)(at - base));
    strcpy(out + (at - base), to);
    strcat(out, at + strlen(from));
    return out;
}

struct gcase {
    const char *name, *from, *to;
    snell_status want;
};

static void expect(const char *name, const char *json, size_t len, snell_status want)
{
    snell_mesh *m = (snell_mesh *)&m;
    snell_status st = snell_mesh_load_gltf_mem(NULL, json, len, &m);
    CHECK(st == want, "%s: got %s, want %s (%s)", name, snell_status_str(st), snell_status_str(want),
          snell_last_error(NULL));
    if (st == SNELL_OK) {
        snell_mesh_destroy(m);
    } else {
        CHECK(m == NULL, "%s: out not cleared", name);
        CHECK(snell_last_error(NULL)[0] != '\0', "%s: empty message", name);
    }
}

static void test_malformed_json(void)
{
    static const uint16_t good[3] = {0, 1, 2}, bad[3] = {0, 1, 7};
    static const struct gcase cases[] = {
        {"valid", "", "", SNELL_OK},
        {"bad JSON", "\"scenes\"", "\"scenes\":{[", SNELL_E_PARSE},
        {"accessor beyond view", "\"count\":3,\"type\":\"VEC3\"", "\"count\":1000,\"type\":\"VEC3\"", SNELL_E_PARSE},
        {"accessor offset beyond view", "\"componentType\":5126,", "\"byteOffset\":4294967295,\"componentType\":5126,",
         SNELL_E_PARSE},
        {"byteStride too small", "\"byteLength\":36}", "\"byteLength\":36,\"byteStride\":8}", SNELL_E_PARSE},
        {"byteStride overruns view", "\"byteLength\":36}", "\"byteLength\":36,\"byteStride\":16}", SNELL_E_PARSE},
        {"byteStride too large", "\"byteLength\":36}", "\"byteLength\":36,\"byteStride\":256}", SNELL_E_PARSE},
        {"view beyond buffer", "\"byteOffset\":36,\"byteLength\":6", "\"byteOffset\":40,\"byteLength\":6", SNELL_E_PARSE},
        {"missing buffers", "\"buffers\":[", "\"buffers\":[],\"x\":[", SNELL_E_PARSE},
        {"buffer index", "{\"buffer\":0,\"byteOffset\":36", "{\"buffer\":3,\"byteOffset\":36", SNELL_E_PARSE},
        {"missing bufferView", "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},",
         "\"bufferViews\":[", SNELL_E_PARSE},
        {"accessor index", "\"POSITION\":0", "\"POSITION\":9", SNELL_E_PARSE},
        {"indices index", "\"indices\":1", "\"indices\":-5", SNELL_E_PARSE},
        {"mesh index", "{\"mesh\":0}", "{\"mesh\":5}", SNELL_E_PARSE},
        {"node index", "{\"nodes\":[0]}", "{\"nodes\":[7]}", SNELL_E_PARSE},
        {"node cycle", "{\"mesh\":0}", "{\"mesh\":0,\"children\":[0]}", SNELL_E_PARSE},
        {"matrix size", "{\"mesh\":0}", "{\"mesh\":0,\"matrix\":[1,2,3]}", SNELL_E_PARSE},
        {"zero quaternion", "{\"mesh\":0}", "{\"mesh\":0,\"rotation\":[0,0,0,0]}", SNELL_E_PARSE},
        {"huge scale", "{\"mesh\":0}", "{\"mesh\":0,\"scale\":[1e300,1e300,1e300]}", SNELL_E_PARSE},
        {"position type", "\"count\":3,\"type\":\"VEC3\"", "\"count\":3,\"type\":\"VEC2\"", SNELL_E_PARSE},
        {"index type", "\"componentType\":5123", "\"componentType\":5126", SNELL_E_PARSE},
        {"position ints", "\"componentType\":5126", "\"componentType\":5123", SNELL_E_UNSUPPORTED},
        {"sparse", "\"count\":3,\"type\":\"VEC3\"",
         "\"count\":3,\"type\":\"VEC3\",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":5123},"
         "\"values\":{\"bufferView\":0}}",
         SNELL_E_UNSUPPORTED},
        {"lines only", "\"indices\":1", "\"indices\":1,\"mode\":1", SNELL_E_PARSE},
        {"external file", "data:application/octet-stream;base64,", "nodes.bin?", SNELL_E_PARSE},
        {"zero scale hides all", "{\"mesh\":0}", "{\"mesh\":0,\"scale\":[0,0,0]}", SNELL_E_PARSE},
        {"no scenes: root nodes", "\"scenes\":[{\"nodes\":[0]}],", "", SNELL_OK},
    };
    char *base = make_base(good, 0.0f), *nan_base, *badidx;
    float nanv = (float)NAN;
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *json = cases[i].from[0] ? replace(base, cases[i].from, cases[i].to) : NULL;
        const char *j = json ? json : base;
        if (cases[i].from[0] && !json) continue;
        expect(cases[i].name, j, strlen(j), cases[i].want);
        free(json);
    }
    badidx = make_base(bad, 0.0f);
    expect("index out of range", badidx, strlen(badidx), SNELL_E_PARSE);
    nan_base = make_base(good, nanv);
    expect("NaN position", nan_base, strlen(nan_base), SNELL_E_PARSE);
    expect("truncated JSON", base, strlen(base) / 2, SNELL_E_PARSE);
    expect("garbage", "\x01\x02\xff\xfe garbage", 12, SNELL_E_PARSE);
    {
        /* deeply nested JSON overflowed the stack inside tinygltf (found while
         * testing); the loader now refuses nesting beyond 512 levels */
        const size_t depth = 200000;
        const char *head = "{\"asset\":{\"version\":\"2.0\"},\"extras\":";
        size_t hl = strlen(head), k;
        char *deep = (char *)malloc(hl + 2 * depth + 2);
        if (deep) {
            memcpy(deep, head, hl);
            for (k = 0; k < depth; k++) {
                deep[hl + k] = '[';
                deep[hl + depth + k] = ']';
            }
            deep[hl + 2 * depth] = '}';
            expect("200000-deep JSON", deep, hl + 2 * depth + 1, SNELL_E_LIMIT);
            free(deep);
        }
    }
    {
        /* brackets inside strings (also after an escaped quote) do not count */
        char str[1100], *to, *json;
        size_t k;
        strcpy(str, "{\"version\":\"2.0\",\"extras\":{\"s\":\"\\\"");
        for (k = strlen(str); k < 1000; k++) str[k] = '[';
        strcpy(str + 1000, "\"}}");
        to = str;
        json = replace(base, "{\"version\":\"2.0\"}", to);
        if (json) expect("brackets in strings", json, strlen(json), SNELL_OK);
        free(json);
    }
    {
        snell_mesh *m = NULL;
        CHECK(snell_mesh_load_gltf_mem(NULL, base, 0, &m) == SNELL_E_INVALID_ARG, "empty input");
        CHECK(snell_mesh_load_gltf(NULL, test_data("missing.gltf"), &m) == SNELL_E_IO, "missing file");
        CHECK(snell_mesh_load_gltf(NULL, NULL, &m) == SNELL_E_INVALID_ARG && !m &&
                  strstr(snell_last_error(NULL), "snell_mesh_load_gltf: path is NULL"),
              "NULL path: %s", snell_last_error(NULL));
        CHECK(snell_mesh_load_gltf_ex(NULL, test_data("missing.gltf"), 0x80u, &m) == SNELL_E_INVALID_ARG && !m &&
                  strstr(snell_last_error(NULL), "snell_mesh_load_gltf: unknown flags 0x80"),
              "unknown flags: %s", snell_last_error(NULL));
        CHECK(snell_mesh_load_gltf(NULL, test_data("missing.gltf"), NULL) == SNELL_E_INVALID_ARG, "NULL out");
    }
    free(base);
    free(badidx);
    free(nan_base);
}

static void test_malformed_glb(void)
{
    size_t size, n, i;
    unsigned char *glb = read_file(test_data("nodes.glb"), &size), *copy;
    int crashes_would_show = 0;
    if (!glb) {
        CHECK(0, "cannot read nodes.glb");
        return;
    }
    copy = (unsigned char *)malloc(size);
    /* every truncation fails cleanly */
    for (n = 0; n < size; n++) {
        snell_mesh *m = NULL;
        snell_status st;
        memcpy(copy, glb, n);
        st = snell_mesh_load_gltf_mem(NULL, copy, n, &m);
        if (st == SNELL_OK || m || !snell_last_error(NULL)[0]) {
            CHECK(0, "GLB truncated to %zu bytes: %s", n, snell_status_str(st));
            snell_mesh_destroy(m);
            break;
        }
    }
    CHECK(n == size, "all %zu truncations rejected", size);
    /* header fields */
    {
        uint32_t v;
        memcpy(copy, glb, size);
        v = 1;
        memcpy(copy + 4, &v, 4);
        expect("GLB version 1", (const char *)copy, size, SNELL_E_UNSUPPORTED);
        memcpy(copy, glb, size);
        v = 0x7fffffff;
        memcpy(copy + 12, &v, 4);
        expect("GLB JSON chunk too long", (const char *)copy, size, SNELL_E_PARSE);
        memcpy(copy, glb, size);
        v = (uint32_t)size + 100;
        memcpy(copy + 8, &v, 4);
        expect("GLB length beyond data", (const char *)copy, size, SNELL_E_PARSE);
    }
    /* single-byte corruption anywhere: any status is fine, but no crash and a
     * message whenever it fails (ASan/valgrind runs make this meaningful) */
    for (i = 0; i < size; i++) {
        snell_mesh *m = NULL;
        snell_status st;
        memcpy(copy, glb, size);
        copy[i] ^= 0xff;
        st = snell_mesh_load_gltf_mem(NULL, copy, size, &m);
        if (st != SNELL_OK && !snell_last_error(NULL)[0]) crashes_would_show++;
        snell_mesh_destroy(m);
    }
    CHECK(crashes_would_show == 0, "%d corrupted GLBs failed without a message", crashes_would_show);
    free(copy);
    free(glb);
}

/* malformed files written by make_gltf.py, through the file loader */
static void test_bad_files(void)
{
    static const char *files[] = {"bad_accessor.gltf", "bad_stride.gltf", "bad_index.gltf", "bad_truncated.glb"};
    size_t i;
    for (i = 0; i < sizeof files / sizeof files[0]; i++) {
        snell_mesh *m = NULL;
        snell_status st = snell_mesh_load(NULL, test_data(files[i]), &m);
        CHECK(st == SNELL_E_PARSE && m == NULL && snell_last_error(NULL)[0], "%s: %s (%s)", files[i],
              snell_status_str(st), snell_last_error(NULL));
    }
}

int main(void)
{
    test_valid();
    test_bad_files();
    test_malformed_json();
    test_malformed_glb();
    return test_finish();
}
