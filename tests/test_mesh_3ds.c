/* SPDX-License-Identifier: MIT */
/* test_mesh_3ds.c — glmark2's model formats (src/mesh/mesh_3ds.c): a .3ds
 * built here chunk by chunk (and tests/data/tetra.3ds, the same bytes, the
 * fuzz seed), every truncation and every single-byte change of it (a status,
 * never a crash; ASan in CI sees any overread), each malformed case with its
 * message; .jobj text and its errors; then, given glmark2-data's folder, every
 * model there by snell_mesh_load, each .3ds against tests/scripts/3ds_to_obj.py's
 * OBJ of it (the same positions and triangles, exactly).
 *   test_mesh_3ds [MODELS_DIR CONVERTER SCRATCH_DIR] */
#include "test_util.h"

#include <stdlib.h>
#include <string.h>

typedef struct buf {
    unsigned char d[1024];
    size_t n;
} buf;

static void put16(buf *b, unsigned v)
{
    b->d[b->n++] = (unsigned char)(v & 0xff);
    b->d[b->n++] = (unsigned char)(v >> 8);
}

static void put32(buf *b, uint32_t v)
{
    put16(b, v & 0xffff);
    put16(b, v >> 16);
}

static void putf(buf *b, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    put32(b, u);
}

/* Opens a chunk; close_chunk writes its length. */
static size_t open_chunk(buf *b, unsigned id)
{
    size_t at = b->n;
    put16(b, id);
    put32(b, 0);
    return at;
}

static void close_chunk(buf *b, size_t at)
{
    uint32_t len = (uint32_t)(b->n - at);
    size_t n = b->n;
    b->n = at + 2;
    put32(b, len);
    b->n = n;
}

static const float TETRA_V[5][3] = {{0, 0, 0}, {9, 9, 9}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
static const unsigned TETRA_F[4][3] = {{0, 3, 2}, {0, 2, 4}, {0, 4, 3}, {2, 3, 4}};

/* main > editor > {a material chunk, object "tetra" > trimesh > {vertices (one, 9 9 9,
 * used by no face), faces (with a smoothing sub-chunk after the list), a local
 * frame}}: the skipped chunks are where a reader that does not skip by length fails. */
static void tetra_3ds(buf *b)
{
    size_t m, e, o, t, c;
    int i, k;
    b->n = 0;
    m = open_chunk(b, 0x4D4D);
    c = open_chunk(b, 0x0002); /* version */
    put32(b, 3);
    close_chunk(b, c);
    e = open_chunk(b, 0x3D3D);
    c = open_chunk(b, 0xAFFF); /* a material, skipped */
    put32(b, 0x12345678);
    close_chunk(b, c);
    o = open_chunk(b, 0x4000);
    memcpy(b->d + b->n, "tetra", 6);
    b->n += 6;
    t = open_chunk(b, 0x4100);
    c = open_chunk(b, 0x4110);
    put16(b, 5);
    for (i = 0; i < 5; i++)
        for (k = 0; k < 3; k++) putf(b, TETRA_V[i][k]);
    close_chunk(b, c);
    c = open_chunk(b, 0x4120);
    put16(b, 4);
    for (i = 0; i < 4; i++) {
        for (k = 0; k < 3; k++) put16(b, TETRA_F[i][k]);
        put16(b, 7); /* flags */
    }
    {
        size_t s = open_chunk(b, 0x4150); /* smoothing groups, inside the face chunk */
        for (i = 0; i < 4; i++) put32(b, 1);
        close_chunk(b, s);
    }
    close_chunk(b, c);
    c = open_chunk(b, 0x4160); /* local frame: not applied */
    for (i = 0; i < 12; i++) putf(b, 2.0f);
    close_chunk(b, c);
    close_chunk(b, t);
    close_chunk(b, o);
    close_chunk(b, e);
    close_chunk(b, m);
}

static void test_tetra(void)
{
    buf b;
    snell_mesh *m = NULL;
    /* faces first use 0, 3, 2, 4: that is the order kept; 9 9 9 is dropped */
    static const float want_pos[4][3] = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
    static const uint32_t want_idx[12] = {0, 1, 2, 0, 2, 3, 0, 3, 1, 2, 1, 3};
    tetra_3ds(&b);
    CHECK_OK(snell_mesh_load_3ds_mem(NULL, b.d, b.n, &m));
    if (!m) return;
    CHECK(snell_mesh_vertex_count(m) == 4 && snell_mesh_triangle_count(m) == 4, "tetra: %u vertices, %u triangles",
          snell_mesh_vertex_count(m), snell_mesh_triangle_count(m));
    if (snell_mesh_vertex_count(m) == 4 && snell_mesh_triangle_count(m) == 4) {
        CHECK(memcmp(snell_mesh_positions(m), want_pos, sizeof want_pos) == 0, "tetra: positions");
        CHECK(memcmp(snell_mesh_indices(m), want_idx, sizeof want_idx) == 0, "tetra: indices");
    }
    snell_mesh_destroy(m);
    {
        /* the fuzz seed is these bytes */
        FILE *f = fopen(test_data("tetra.3ds"), "rb");
        unsigned char file[1024];
        size_t n = f ? fread(file, 1, sizeof file, f) : 0;
        if (f) fclose(f);
        CHECK(n == b.n && memcmp(file, b.d, n) == 0, "tests/data/tetra.3ds (%zu bytes) is not tetra_3ds() (%zu)", n, b.n);
    }
    CHECK_OK(snell_mesh_load(NULL, test_data("tetra.3ds"), &m));
    CHECK(m && snell_mesh_triangle_count(m) == 4, "snell_mesh_load of tetra.3ds");
    snell_mesh_destroy(m);
}

/* Copies into a block of exactly n bytes, so ASan sees a read past it. */
static snell_status load_exact(const unsigned char *d, size_t n, snell_mesh **m)
{
    unsigned char *copy = (unsigned char *)malloc(n ? n : 1);
    snell_status st;
    if (n) memcpy(copy, d, n);
    st = snell_mesh_load_3ds_mem(NULL, copy, n, m);
    free(copy);
    return st;
}

static void test_hostile_3ds(void)
{
    buf b, h;
    snell_mesh *m = NULL;
    size_t n, i, bad = 0;
    tetra_3ds(&b);
    /* every truncation is refused with a message */
    for (n = 0; n < b.n; n++) {
        snell_status st = load_exact(b.d, n, &m);
        if (st != SNELL_E_PARSE || m || !snell_last_error(NULL)[0]) bad++;
        snell_mesh_destroy(m);
        m = NULL;
    }
    CHECK(bad == 0, "%zu of %zu truncations not refused with SNELL_E_PARSE", bad, b.n);
    /* every byte set to 0xff and to 0x00: a valid mesh or a refusal with a message */
    bad = 0;
    for (i = 0; i < b.n; i++) {
        int v;
        for (v = 0; v < 2; v++) {
            snell_status st;
            h = b;
            h.d[i] = v ? 0xff : 0x00;
            st = load_exact(h.d, h.n, &m);
            if ((st == SNELL_OK) != (m != NULL) || (st != SNELL_OK && !snell_last_error(NULL)[0]) ||
                (st != SNELL_OK && st != SNELL_E_PARSE && st != SNELL_E_INVALID_ARG))
                bad++;
            snell_mesh_destroy(m);
            m = NULL;
        }
    }
    CHECK(bad == 0, "%zu single-byte changes gave no mesh and no message", bad);

    /* the cases, each with what its message names */
    {
        static const struct {
            size_t at; /* byte offset into tetra_3ds()'s buffer to overwrite, or 0 for none */
            unsigned value16;
            int wide;
            const char *msg;
        } cases[] = {
            {0, 0x1234, 0, "no main chunk"},
            {2, 0xffff, 1, "has length"},
        };
        size_t k;
        for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
            h = b;
            h.d[cases[k].at] = (unsigned char)(cases[k].value16 & 0xff);
            h.d[cases[k].at + 1] = (unsigned char)(cases[k].value16 >> 8);
            if (cases[k].wide) h.d[cases[k].at + 2] = h.d[cases[k].at + 3] = 0xff;
            CHECK(load_exact(h.d, h.n, &m) == SNELL_E_PARSE && !m &&
                      strstr(snell_last_error(NULL), cases[k].msg) != NULL,
                  "case %zu: '%s'", k, snell_last_error(NULL));
        }
    }
    {
        /* find the face list and its first index, the vertex count and the name */
        size_t fl = 0, vl = 0, nm = 0;
        for (i = 0; i + 6 < b.n; i++) {
            if (!fl && b.d[i] == 0x20 && b.d[i + 1] == 0x41) fl = i;
            if (!vl && b.d[i] == 0x10 && b.d[i + 1] == 0x41) vl = i;
            if (!nm && memcmp(b.d + i, "tetra", 5) == 0) nm = i;
        }
        CHECK(fl && vl && nm, "layout of the built tetra");
        h = b;
        h.d[fl + 8] = 5; /* first face's first corner: vertex 5 of 5 */
        CHECK(load_exact(h.d, h.n, &m) == SNELL_E_PARSE && strstr(snell_last_error(NULL), "uses vertex 5 of 5"),
              "index out of range: '%s'", snell_last_error(NULL));
        h = b;
        h.d[vl + 6] = 200; /* 200 vertices in a chunk of 5 */
        CHECK(load_exact(h.d, h.n, &m) == SNELL_E_PARSE && strstr(snell_last_error(NULL), "200 vertices do not fit"),
              "vertex count: '%s'", snell_last_error(NULL));
        h = b;
        h.d[fl + 6] = 0xff; /* 0x..ff faces */
        h.d[fl + 7] = 0xff;
        CHECK(load_exact(h.d, h.n, &m) == SNELL_E_PARSE && strstr(snell_last_error(NULL), "65535 faces do not fit"),
              "face count: '%s'", snell_last_error(NULL));
        h = b;
        memset(h.d + nm, 'x', (size_t)(vl - 6 - nm)); /* the name runs to the trimesh chunk: no NUL in the object */
        for (i = vl - 6; i < b.n && i < vl + 200; i++) if (h.d[i] == 0) h.d[i] = 1;
        CHECK(load_exact(h.d, h.n, &m) != SNELL_OK && snell_last_error(NULL)[0], "name without NUL: '%s'",
              snell_last_error(NULL));
        h = b;
        h.d[fl + 6] = h.d[fl + 7] = 0; /* no faces: nothing to draw */
        CHECK(load_exact(h.d, h.n, &m) == SNELL_E_PARSE && strstr(snell_last_error(NULL), "no triangle mesh"),
              "no faces: '%s'", snell_last_error(NULL));
    }
    CHECK(snell_mesh_load_3ds_mem(NULL, NULL, 4, &m) == SNELL_E_INVALID_ARG, "NULL data");
    CHECK(snell_mesh_load_3ds_mem(NULL, b.d, b.n, NULL) == SNELL_E_INVALID_ARG, "NULL out");
}

static void test_jobj(void)
{
    static const char good[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\r\n"
                               "vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n"
                               "vt 0 0 0\nvc 1 1 1\n\n"
                               "i 0\ni 2\ni 1\ni 0\ni 1\ni 3\n";
    static const struct {
        const char *text, *msg;
    } bad[] = {
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\ni 0\ni 1\n", "not whole triangles"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\ni 0\ni 1\ni x\n", "line 6: 'i' needs one index"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\ni 0\ni 1\ni 99999999999\n", "line 6: 'i' needs one index"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\ni 0\ni 1\ni 7\n", "line 6"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\ni 0\ni 1\ni 2\n", "1 normals for 3 vertices"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "line 4: not a v, vn, vt, vc or i line"},
        {"v 0 0 0\nv 1 0 0\ni 0\ni 1\ni 1\nv 0 1 0\n", "line 6: a vertex after the indices"},
        {"v 0 0 zz\nv 1 0 0\nv 0 1 0\ni 0\ni 1\ni 2\n", "line 1"},
        {"", "no faces"},
    };
    snell_mesh *m = NULL;
    size_t k;
    CHECK_OK(snell_mesh_load_jobj_mem(NULL, good, sizeof good - 1, &m));
    if (m) {
        CHECK(snell_mesh_triangle_count(m) == 2 && snell_mesh_vertex_count(m) == 4, "jobj: %u triangles, %u vertices",
              snell_mesh_triangle_count(m), snell_mesh_vertex_count(m));
        CHECK(snell_mesh_indices(m)[1] < snell_mesh_vertex_count(m), "jobj: indices");
        snell_mesh_destroy(m);
        m = NULL;
    }
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        size_t n = strlen(bad[k].text);
        char *copy = (char *)malloc(n + 1);
        snell_status st;
        memcpy(copy, bad[k].text, n);
        st = snell_mesh_load_jobj_mem(NULL, copy, n, &m);
        CHECK(st == SNELL_E_PARSE && !m && strstr(snell_last_error(NULL), bad[k].msg) != NULL,
              "jobj case %zu: %s '%s' (want '%s')", k, snell_status_str(st), snell_last_error(NULL), bad[k].msg);
        snell_mesh_destroy(m);
        m = NULL;
        free(copy);
    }
    /* every truncation of the good text: a mesh or a message */
    for (k = 0; k < sizeof good - 1; k++) {
        char *copy = (char *)malloc(k + 1);
        snell_status st;
        memcpy(copy, good, k);
        st = snell_mesh_load_jobj_mem(NULL, copy, k, &m);
        CHECK((st == SNELL_OK) == (m != NULL) && (st == SNELL_OK || snell_last_error(NULL)[0]), "truncated at %zu", k);
        snell_mesh_destroy(m);
        m = NULL;
        free(copy);
    }
}

/* glmark2-data's models: every one loads by extension; a .3ds gives exactly
 * the converter's OBJ (positions and triangles in the same order). */
static void test_glmark2(const char *dir, const char *converter, const char *scratch)
{
    static const char *models[] = {"asteroid-high.3ds", "asteroid-low.3ds", "bunny.obj", "cat.3ds",
                                   "cube.3ds", "horse.3ds", "jellyfish.jobj"};
    size_t k;
    for (k = 0; k < sizeof models / sizeof models[0]; k++) {
        char path[1024], obj[1024], cmd[3200];
        snell_mesh *m = NULL, *o = NULL;
        snprintf(path, sizeof path, "%s/%s", dir, models[k]);
        CHECK_OK(snell_mesh_load(NULL, path, &m));
        if (!m) continue;
        printf("%s: %u vertices, %u triangles\n", models[k], snell_mesh_vertex_count(m), snell_mesh_triangle_count(m));
        CHECK(snell_mesh_triangle_count(m) > 0, "%s: no triangles", models[k]);
        if (strstr(models[k], ".3ds")) {
            snprintf(obj, sizeof obj, "%s/%s.obj", scratch, models[k]);
            snprintf(cmd, sizeof cmd, "python3 '%s' '%s' '%s'", converter, path, obj);
            CHECK(system(cmd) == 0, "%s failed", cmd);
            CHECK_OK(snell_mesh_load_obj(NULL, obj, &o));
            if (o) {
                uint32_t nv = snell_mesh_vertex_count(m), nt = snell_mesh_triangle_count(m);
                CHECK(snell_mesh_vertex_count(o) == nv && snell_mesh_triangle_count(o) == nt,
                      "%s: %u/%u vertices/triangles, the converter's OBJ %u/%u", models[k], nv, nt,
                      snell_mesh_vertex_count(o), snell_mesh_triangle_count(o));
                if (snell_mesh_vertex_count(o) == nv && snell_mesh_triangle_count(o) == nt) {
                    CHECK(memcmp(snell_mesh_positions(o), snell_mesh_positions(m), 12 * (size_t)nv) == 0,
                          "%s: positions differ from the converter's", models[k]);
                    CHECK(memcmp(snell_mesh_indices(o), snell_mesh_indices(m), 12 * (size_t)nt) == 0,
                          "%s: triangles differ from the converter's", models[k]);
                }
                snell_mesh_destroy(o);
            }
        }
        snell_mesh_destroy(m);
    }
}

int main(int argc, char **argv)
{
    test_tetra();
    test_hostile_3ds();
    test_jobj();
    if (argc > 3) {
        FILE *f = fopen(argv[1], "r"); /* a folder opens for reading on Linux */
        if (f) {
            fclose(f);
            test_glmark2(argv[1], argv[2], argv[3]);
        } else {
            printf("glmark2-data not installed (%s): its models not checked\n", argv[1]);
        }
    }
    return test_finish();
}
