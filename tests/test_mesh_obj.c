/* SPDX-License-Identifier: MIT */
/* test_mesh_obj.c — OBJ loader: polygons, index forms, normals, dispatch by
 * extension, malformed input (status + line-numbered message), big inputs. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "test_util.h"

#include <locale.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int near3(const float *a, float x, float y, float z, float tol)
{
    return fabsf(a[0] - x) <= tol && fabsf(a[1] - y) <= tol && fabsf(a[2] - z) <= tol;
}

/* Index of the vertex with this position and normal, or -1. */
static int find_vertex(const snell_mesh *m, const float p[3], const float n[3])
{
    uint32_t i;
    for (i = 0; i < snell_mesh_vertex_count(m); i++)
        if (near3(snell_mesh_positions(m) + 3 * i, p[0], p[1], p[2], 1e-6f) &&
            near3(snell_mesh_normals(m) + 3 * i, n[0], n[1], n[2], 1e-5f))
            return (int)i;
    return -1;
}

static void check_unit_normals(const snell_mesh *m, const char *what)
{
    uint32_t i, bad = 0;
    for (i = 0; i < snell_mesh_vertex_count(m); i++) {
        const float *n = snell_mesh_normals(m) + 3 * i;
        if (fabsf(sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1.0f) > 1e-4f) bad++;
    }
    CHECK(bad == 0, "%s: %u normals are not unit length", what, bad);
}

static void test_quad_ngon(void)
{
    snell_mesh *m = NULL;
    float mn[3], mx[3];
    uint32_t i;
    CHECK_OK(snell_mesh_load_obj(NULL, test_data("quad_ngon.obj"), &m));
    if (!m) return;
    /* quad -> 2 triangles, hexagon -> 4 (fan); no vertex is shared between them */
    CHECK(snell_mesh_vertex_count(m) == 10, "vertices %u", snell_mesh_vertex_count(m));
    CHECK(snell_mesh_triangle_count(m) == 6, "triangles %u", snell_mesh_triangle_count(m));
    /* both polygons are CCW seen from +z, so every smooth normal is +z */
    for (i = 0; i < snell_mesh_vertex_count(m); i++)
        CHECK(near3(snell_mesh_normals(m) + 3 * i, 0, 0, 1, 1e-6f), "normal of vertex %u", i);
    snell_mesh_bounds(m, mn, mx);
    CHECK(near3(mn, -1.0f, -0.8660254f, 0.0f, 1e-6f) && near3(mx, 1.0f, 1.0f, 1.0f, 1e-6f),
          "bounds (%g %g %g)-(%g %g %g)", mn[0], mn[1], mn[2], mx[0], mx[1], mx[2]);
    snell_mesh_destroy(m);
}

/* negative_crlf.obj: relative indices, v/vt/vn, v//vn, v/vt and v forms, CRLF
 * line ends, no newline at EOF; normals partly missing. */
static void test_negative_crlf(void)
{
    snell_mesh *m = NULL;
    static const float p0[3] = {0, 0, 0}, p1[3] = {1, 0, 0}, p2[3] = {0, 1, 0}, p3[3] = {0, 0, 1};
    static const float nneg[3] = {0, 0, -1}, npos[3] = {0, 0, 1}, ny[3] = {0, -1, 0};
    float n0[3];
    CHECK_OK(snell_mesh_load_obj(NULL, test_data("negative_crlf.obj"), &m));
    if (!m) return;
    /* unique (v, vn) pairs: (0,0) (2,0) (1,0) | (0,1) (1,1) (3,-) | (0,-) (1,-) */
    CHECK(snell_mesh_vertex_count(m) == 8, "vertices %u", snell_mesh_vertex_count(m));
    CHECK(snell_mesh_triangle_count(m) == 3, "triangles %u", snell_mesh_triangle_count(m));
    CHECK(find_vertex(m, p0, nneg) >= 0 && find_vertex(m, p2, nneg) >= 0 && find_vertex(m, p1, nneg) >= 0,
          "file normals of face 1");
    CHECK(find_vertex(m, p0, npos) >= 0 && find_vertex(m, p1, npos) >= 0, "file normals of face 2");
    /* position 3 is only used by faces 2 and 3, both with geometric normal -y */
    CHECK(find_vertex(m, p3, ny) >= 0, "smooth normal of position 3");
    /* position 0 without a file normal: area-weighted sum over all three faces
     * that use position 0: (0,0,-1) + (0,-1,0) + (0,-1,0), normalised */
    n0[0] = 0.0f;
    n0[1] = -2.0f / sqrtf(5.0f);
    n0[2] = -1.0f / sqrtf(5.0f);
    CHECK(find_vertex(m, p0, n0) >= 0, "smooth normal of position 0 (mixed faces)");
    check_unit_normals(m, "negative_crlf");
    snell_mesh_destroy(m);
}

static void test_numbers(void)
{
    /* the hand-written number parser against strtod in the C locale */
    const char *src = "v 1.5e-3 -2.25E+2 123456.789\nv +.5 -0. 3.\nv 0.1 1e-30 -7e10\nf 1 2 3 # comment\n";
    static const char *lit[9] = {"1.5e-3", "-2.25E+2", "123456.789", "+.5", "-0.", "3.", "0.1", "1e-30", "-7e10"};
    snell_mesh *m = NULL;
    int i;
    CHECK_OK(snell_mesh_load_obj_mem(NULL, src, strlen(src), &m));
    if (!m) return;
    for (i = 0; i < 9; i++) {
        float want = (float)strtod(lit[i], NULL);
        float got = snell_mesh_positions(m)[i];
        CHECK(got == want || fabsf(got - want) <= 1e-7f * fabsf(want), "'%s' -> %.9g, want %.9g", lit[i], got, want);
    }
    snell_mesh_destroy(m);

    /* a decimal-comma locale must not change the result (strtof would) */
    if (setlocale(LC_NUMERIC, "de_DE.UTF-8") || setlocale(LC_NUMERIC, "de_DE") ||
        setlocale(LC_NUMERIC, "fr_FR.UTF-8")) {
        CHECK_OK(snell_mesh_load_obj_mem(NULL, src, strlen(src), &m));
        if (m) CHECK(snell_mesh_positions(m)[0] == (float)1.5e-3, "locale changed parsing: %g", snell_mesh_positions(m)[0]);
        snell_mesh_destroy(m);
        setlocale(LC_NUMERIC, "C");
    } else {
        printf("note: no decimal-comma locale installed, locale check not run\n");
    }

    /* backslash continues a statement on the next line; line numbers still count */
    {
        const char *cont = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n 3\nf 1 2 7\n";
        CHECK(snell_mesh_load_obj_mem(NULL, cont, strlen(cont), &m) == SNELL_E_PARSE, "continuation");
        CHECK(strstr(snell_last_error(NULL), "line 6") != NULL, "line number after continuation: %s",
              snell_last_error(NULL));
    }
}

struct bad_case {
    const char *name, *src;
    snell_status want;
    const char *line; /* substring the message must contain, or NULL */
};

static void test_malformed(void)
{
#define TRI3 "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    static const struct bad_case cases[] = {
        {"empty", "", SNELL_E_PARSE, NULL},
        {"comments only", "# nothing\n\n   \n", SNELL_E_PARSE, NULL},
        {"no faces", TRI3, SNELL_E_PARSE, NULL},
        {"truncated vertex", "v 0 0 0\nv 1 0 0\nv 0 1", SNELL_E_PARSE, "line 3"},
        {"truncated number", TRI3 "v 1e", SNELL_E_PARSE, "line 4"},
        {"truncated face", TRI3 "f 1 2", SNELL_E_PARSE, "line 4"},
        {"huge index", TRI3 "f 1 2 99999999\n", SNELL_E_PARSE, "line 4"},
        {"overflowing index", TRI3 "f 1 2 99999999999999999999\n", SNELL_E_PARSE, "line 4"},
        {"zero index", TRI3 "f 1 2 0\n", SNELL_E_PARSE, "line 4"},
        {"negative out of range", TRI3 "f 1 2 -4\n", SNELL_E_PARSE, "line 4"},
        {"forward reference", "f 1 2 3\n" TRI3, SNELL_E_PARSE, "line 1"},
        {"vt out of range", TRI3 "vt 0 0\nf 1/1 2/2 3/1\n", SNELL_E_PARSE, "line 5"},
        {"vn out of range", TRI3 "vn 0 0 1\nf 1//1 2//1 3//2\n", SNELL_E_PARSE, "line 5"},
        {"junk in corner", TRI3 "f 1 2 3a\n", SNELL_E_PARSE, "line 4"},
        {"four fields", TRI3 "f 1/1/1/1 2 3\n", SNELL_E_PARSE, "line 4"},
        {"nan", "v nan 0 0\n", SNELL_E_PARSE, "line 1"},
        {"inf", "v 0 inf 0\n", SNELL_E_PARSE, "line 1"},
        {"beyond float", "v 0 0 1e39\n", SNELL_E_PARSE, "line 1"},
        {"huge exponent", "v 0 0 1e999999999999\n", SNELL_E_PARSE, "line 1"},
        {"nan normal", TRI3 "vn nan 0 1\n", SNELL_E_PARSE, "line 4"},
        {"bad vt", "vt x\n", SNELL_E_PARSE, "line 1"},
        {"crlf line count", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 9\r\n", SNELL_E_PARSE, "line 4"},
        {"binary", "v 0 0 0\n\x7f" "ELF\x02\x01\x01\x00\x00garbage", SNELL_E_PARSE, "line 2"},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snell_mesh *m = (snell_mesh *)&m; /* must be reset to NULL */
        size_t len = strlen(cases[i].src);
        snell_status st;
        if (strcmp(cases[i].name, "binary") == 0) len = 22; /* embedded NUL */
        st = snell_mesh_load_obj_mem(NULL, cases[i].src, len, &m);
        CHECK(st == cases[i].want, "%s: got %s (%s)", cases[i].name, snell_status_str(st), snell_last_error(NULL));
        CHECK(m == NULL, "%s: out not cleared", cases[i].name);
        CHECK(snell_last_error(NULL)[0] != '\0', "%s: empty message", cases[i].name);
        if (cases[i].line)
            CHECK(strstr(snell_last_error(NULL), cases[i].line) != NULL, "%s: message '%s' lacks '%s'",
                  cases[i].name, snell_last_error(NULL), cases[i].line);
        snell_mesh_destroy(st == SNELL_OK ? m : NULL);
    }
    CHECK(snell_mesh_load_obj_mem(NULL, NULL, 5, NULL) == SNELL_E_INVALID_ARG, "NULL out");
    /* the parser must stop at size, not at a NUL: pass a prefix of a valid file */
    {
        const char *src = TRI3 "f 1 2 3\n";
        snell_mesh *m = NULL;
        CHECK(snell_mesh_load_obj_mem(NULL, src, strlen(src) - 9, &m) == SNELL_E_PARSE, "prefix without face");
    }
#undef TRI3
}

/* One face line of 700,000 corners (near the most triangles the default
 * memory budget takes with their analysis), and a grid with many faces. */
static void test_big(void)
{
    const size_t corners = 700000;
    size_t cap = 64 + corners * 2, len, i;
    char *src = (char *)malloc(cap);
    snell_mesh *m = NULL;
    double t0;
    if (!src) return;
    len = (size_t)sprintf(src, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf");
    for (i = 0; i < corners; i++) {
        src[len++] = ' ';
        src[len++] = (char)('1' + i % 3);
    }
    CHECK_OK(snell_mesh_load_obj_mem(NULL, src, len, &m)); /* no trailing newline */
    CHECK(m && snell_mesh_triangle_count(m) == corners - 2, "700,000-corner face: %u triangles",
          snell_mesh_triangle_count(m));
    snell_mesh_destroy(m);
    free(src);

    {
        const int n = 300; /* (n+1)^2 vertices, 2 n^2 triangles */
        int x, y;
        size_t bcap = (size_t)(n + 1) * (n + 1) * 32 + (size_t)n * n * 40;
        char *b = (char *)malloc(bcap), *p = b;
        if (!b) return;
        for (y = 0; y <= n; y++)
            for (x = 0; x <= n; x++) p += sprintf(p, "v %d %d %g\n", x, y, 0.001 * ((x * y) % 7));
        for (y = 0; y < n; y++)
            for (x = 0; x < n; x++) {
                int a = y * (n + 1) + x + 1;
                p += sprintf(p, "f %d %d %d %d\n", a, a + 1, a + n + 2, a + n + 1);
            }
        t0 = now_s();
        m = NULL;
        CHECK_OK(snell_mesh_load_obj_mem(NULL, b, (size_t)(p - b), &m));
        printf("grid %dx%d (%zu bytes): %.1f ms\n", n, n, (size_t)(p - b), 1e3 * (now_s() - t0));
        CHECK(m && snell_mesh_vertex_count(m) == (uint32_t)((n + 1) * (n + 1)), "grid vertices %u",
              snell_mesh_vertex_count(m));
        CHECK(m && snell_mesh_triangle_count(m) == (uint32_t)(2 * n * n), "grid triangles");
        snell_mesh_destroy(m);
        free(b);
    }
}

static void test_dispatch(void)
{
    snell_mesh *m = NULL;
    FILE *f;
    snell_status st;
    /* extension match is case-insensitive */
    f = fopen(test_out("UPPER.OBJ"), "wb");
    if (f) {
        fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", f);
        fclose(f);
        CHECK_OK(snell_mesh_load(NULL, test_out("UPPER.OBJ"), &m));
        CHECK(m && snell_mesh_triangle_count(m) == 1, "UPPER.OBJ");
        snell_mesh_destroy(m);
        m = NULL;
    }
    st = snell_mesh_load(NULL, test_data("quad_ngon.stl"), &m);
    CHECK(st == SNELL_E_UNSUPPORTED && strstr(snell_last_error(NULL), "quad_ngon.stl"), "unknown extension: %s %s",
          snell_status_str(st), snell_last_error(NULL));
    st = snell_mesh_load(NULL, test_data("does_not_exist.obj"), &m);
    CHECK(st == SNELL_E_IO && m == NULL, "missing file: %s", snell_status_str(st));
    st = snell_mesh_load(NULL, NULL, &m);
    CHECK(st == SNELL_E_INVALID_ARG, "NULL path");
#ifndef SNELL_TEST_HAVE_GLTF
    st = snell_mesh_load(NULL, test_data("nodes.gltf"), &m);
    CHECK(st == SNELL_E_UNSUPPORTED, "glTF without SNELL_WITH_GLTF: %s", snell_status_str(st));
#endif
}

static void test_bunny(void)
{
    const char *path = "/usr/share/glmark2/models/bunny.obj";
    snell_mesh *m = NULL;
    double t0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        printf("note: %s not installed, bunny check not run\n", path);
        return;
    }
    fclose(f);
    t0 = now_s();
    CHECK_OK(snell_mesh_load(NULL, path, &m));
    printf("bunny.obj: %u vertices, %u triangles, %.1f ms\n", snell_mesh_vertex_count(m),
           snell_mesh_triangle_count(m), 1e3 * (now_s() - t0));
    /* the file has no normals, so one output vertex per position */
    CHECK(m && snell_mesh_vertex_count(m) == 34835, "bunny vertices %u", snell_mesh_vertex_count(m));
    if (m) check_unit_normals(m, "bunny");
    snell_mesh_destroy(m);
}

int main(void)
{
    test_quad_ngon();
    test_negative_crlf();
    test_numbers();
    test_malformed();
    test_big();
    test_dispatch();
    test_bunny();
    return test_finish();
}
