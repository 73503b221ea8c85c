/* SPDX-License-Identifier: MIT */
/* test_hostile_inputs4.c — issue 40, hostile input, fourth round: one
 * function per item of the issue, each failing on the code before its fix.
 * Without arguments: the CPU-only cases (ctx NULL). With "ctx": the cases that
 * need a context with a small snell_ctx_desc.memory_budget (label gl). Inputs
 * are made here at run time; the fuzz corpora hold the small ones too. */
#define _POSIX_C_SOURCE 200809L /* mkfifo, alarm, mmap, symlink */
#define _DEFAULT_SOURCE         /* MAP_ANONYMOUS */
#include "test_util.h"
#include "snell/snell_2d.h"

#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

/* A loader that blocks or loops must fail the test, not hang ctest. */
static void on_alarm(int sig)
{
    static const char msg[] = "FAIL: a call did not return within the alarm (blocked in open()?)\n";
    (void)sig;
    if (write(2, msg, sizeof msg - 1) < 0) _exit(1);
    _exit(1);
}

static const char *path_in(const char *dir, const char *name)
{
    static char buf[4][1024];
    static int k;
    k = (k + 1) % 4;
    if (snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name) >= (int)sizeof buf[k]) buf[k][0] = '\0';
    return buf[k];
}

/* A copy of data that ends where an inaccessible page begins: a read past
 * its end faults in every build. Unmapped by unmap_end(). */
static uint8_t *at_end_of_mapping(const void *data, size_t n, size_t *map_len)
{
    size_t page = (size_t)sysconf(_SC_PAGESIZE), len = (n + page - 1) / page * page + page;
    uint8_t *map = (uint8_t *)mmap(NULL, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (map == (uint8_t *)MAP_FAILED) return NULL;
    if (mprotect(map + len - page, page, PROT_NONE) != 0) {
        munmap(map, len);
        return NULL;
    }
    memcpy(map + len - page - n, data, n);
    *map_len = len;
    return map + len - page - n;
}

static void unmap_end(uint8_t *p, size_t n, size_t map_len)
{
    size_t page = (size_t)sysconf(_SC_PAGESIZE);
    if (p) munmap(p + n + page - map_len, map_len);
}

static int has(const char *msg, const char *needle) { return strstr(msg, needle) != NULL; }

/* ------------------------------------------- item 1: GLB chunks past the buffer */
static void test_glb_chunks(void)
{
    size_t n, map_len;
    uint8_t *file = test_read_file(test_data("../fuzz/regressions/glb_bin_chunk_past_end.glb"), &n);
    uint8_t *buf;
    snell_mesh *m = NULL;
    snell_scene_file *sc = NULL;
    snell_status st;
    CHECK(file != NULL, "glb_bin_chunk_past_end.glb missing");
    if (!file) return;
    buf = at_end_of_mapping(file, n, &map_len);
    CHECK(buf != NULL, "mmap");
    if (buf) {
        st = snell_mesh_load_gltf_mem(NULL, buf, n, &m);
        CHECK(st == SNELL_E_PARSE && !m && has(snell_last_error(NULL), "chunk"), "BIN chunk past the end (mesh): %s: %s",
              snell_status_str(st), snell_last_error(NULL));
        snell_mesh_destroy(m);
        st = snell_scene_load_gltf_mem(NULL, buf, n, &sc);
        CHECK(st == SNELL_E_PARSE && !sc && has(snell_last_error(NULL), "chunk"), "BIN chunk past the end (scene): %s: %s",
              snell_status_str(st), snell_last_error(NULL));
        snell_scene_file_destroy(sc);
        unmap_end(buf, n, map_len);
    }
    free(file);
    file = test_read_file(test_data("nodes.glb"), &n);
    if (file && n > 1676) {
        uint32_t len = 1676; /* the JSON chunk (12 + 8 + 1652) and 4 bytes of the BIN chunk's header */
        memcpy(file + 8, &len, 4);
        buf = at_end_of_mapping(file, len, &map_len);
        m = NULL;
        st = buf ? snell_mesh_load_gltf_mem(NULL, buf, len, &m) : SNELL_E_NOMEM;
        CHECK(st == SNELL_E_PARSE && !m && has(snell_last_error(NULL), "chunk"), "cut chunk header: %s: %s",
              snell_status_str(st), snell_last_error(NULL));
        snell_mesh_destroy(m);
        unmap_end(buf, len, map_len);
    }
    free(file);
}

/* ------------------------------------------------- item 3: FIFOs as inputs */
static void test_fifos(void)
{
    char dir[800];
    snell_mesh *m = NULL;
    snell_scene_file *sc = NULL;
    snell_scene2d *s2 = NULL;
    uint8_t *px = NULL;
    int w, h;
    snell_status st;
    static const char *names[] = {"f.obj", "f.gltf", "f.glb", "f.png", "f.txt", "f.csv"};
    size_t i;
    snprintf(dir, sizeof dir, "%.790s", test_out("hostile4_fifo"));
    mkdir(dir, 0755);
    for (i = 0; i < sizeof names / sizeof names[0]; i++) {
        unlink(path_in(dir, names[i]));
        CHECK(mkfifo(path_in(dir, names[i]), 0644) == 0, "mkfifo %s", names[i]);
    }
    CHECK(test_write_file(path_in(dir, "csv_fifo.txt"), "view 0 0 10 10\nobject f.csv t 1\nlight point pos 1 1\n", 52),
          "csv_fifo.txt");
    alarm(20);
    st = snell_mesh_load_obj(NULL, path_in(dir, "f.obj"), &m);
    CHECK(st == SNELL_E_IO && !m && has(snell_last_error(NULL), "not a regular file"), "OBJ FIFO: %s: %s",
          snell_status_str(st), snell_last_error(NULL));
    st = snell_mesh_load_gltf(NULL, path_in(dir, "f.gltf"), &m);
    CHECK(st == SNELL_E_IO && !m && has(snell_last_error(NULL), "not a regular file"), "glTF FIFO: %s: %s",
          snell_status_str(st), snell_last_error(NULL));
    st = snell_scene_load_gltf(NULL, path_in(dir, "f.glb"), 0, &sc);
    CHECK(st == SNELL_E_IO && !sc && has(snell_last_error(NULL), "not a regular file"), "scene FIFO: %s: %s",
          snell_status_str(st), snell_last_error(NULL));
    st = snell_image_read(path_in(dir, "f.png"), &w, &h, &px);
    CHECK(st == SNELL_E_IO && !px && has(snell_last_error(NULL), "not a regular file"), "image FIFO: %s: %s",
          snell_status_str(st), snell_last_error(NULL));
    st = snell_scene2d_load(NULL, path_in(dir, "f.txt"), &s2, NULL, NULL);
    CHECK(st == SNELL_E_IO && !s2 && has(snell_last_error(NULL), "not a regular file"), "2D scene FIFO: %s: %s",
          snell_status_str(st), snell_last_error(NULL));
    st = snell_scene2d_load(NULL, path_in(dir, "csv_fifo.txt"), &s2, NULL, NULL);
    CHECK(st == SNELL_E_IO && !s2 && has(snell_last_error(NULL), "not a regular file"), "CSV FIFO in a 2D scene: %s: %s",
          snell_status_str(st), snell_last_error(NULL));
    snell_scene2d_destroy(s2);
    alarm(0);
}

/* ------------------------------------------- item 6: PNG decompression bomb */
static void test_png_bomb(void)
{
    uint8_t *px = NULL, *rgba;
    int w = 0, h = 0, y;
    snell_status st;
    /* 1x1 RGBA whose IDAT inflates to 32 MiB (make_hostile.py) */
    st = snell_image_read(test_data("hostile/png_bomb.png"), &w, &h, &px);
    CHECK(st == SNELL_E_PARSE && !px && has(snell_last_error(NULL), "decompression bomb"), "PNG bomb: %s: %s",
          snell_status_str(st), snell_last_error(NULL));
    snell_image_free(px);
    px = NULL;
    /* a real image of some size still decodes, its every row different */
    rgba = (uint8_t *)calloc((size_t)1024 * 512, 4);
    for (y = 0; y < 512; y++) memset(rgba + (size_t)y * 1024 * 4, y & 255, 1024 * 4);
    CHECK_OK(snell_write_png(test_out("hostile4_1024x512.png"), 1024, 512, rgba));
    st = snell_image_read(test_out("hostile4_1024x512.png"), &w, &h, &px);
    CHECK(st == SNELL_OK && w == 1024 && h == 512 && px && px[4 * 1024 * 300] == 300 - 256, "1024x512 PNG: %s",
          snell_last_error(NULL));
    snell_image_free(px);
    free(rgba);
}

/* ------------------------------- item 4: 2D scenes confined to their folder */
static void scene2d_expect(const char *path, snell_status want, const char *needle, const char *secret,
                           const char *what)
{
    snell_scene2d *s2 = NULL;
    snell_status st = snell_scene2d_load(NULL, path, &s2, NULL, NULL);
    const char *msg = snell_last_error(NULL);
    CHECK(st == want && (want != SNELL_OK) == (s2 == NULL), "%s: %s (want %s): %s", what, snell_status_str(st),
          snell_status_str(want), msg);
    if (needle) CHECK(has(msg, needle), "%s: message lacks \"%s\": %s", what, needle, msg);
    if (secret) CHECK(!has(msg, secret), "%s: message shows the file's content: %s", what, msg);
    snell_scene2d_destroy(s2);
}

static void test_scene2d_folder(void)
{
    static const char square[] = "0,0\n1,0\n1,1\n0,1\n";
    static const char secret[] = "name,value\nAPI_KEY,sk-1234567890abcdef\n"; /* a header line, then the key */
    char dir[800], model[1024], text[1400];
    int n;
    snprintf(dir, sizeof dir, "%.790s", test_out("hostile4_scene2d"));
    snprintf(model, sizeof model, "%s/scene", dir);
    mkdir(dir, 0755);
    mkdir(model, 0755);
    mkdir(path_in(model, "sub"), 0755);
    CHECK(test_write_file(path_in(dir, "secret.csv"), secret, sizeof secret - 1), "secret.csv");
    CHECK(test_write_file(path_in(dir, "square.csv"), square, sizeof square - 1), "square.csv");
    CHECK(test_write_file(path_in(model, "inside.csv"), square, sizeof square - 1), "inside.csv");
    CHECK(test_write_file(path_in(model, "bad.csv"), secret, sizeof secret - 1), "bad.csv");
    unlink(path_in(model, "link.csv"));
    CHECK(symlink("../secret.csv", path_in(model, "link.csv")) == 0, "symlink");
#define SCENE(file, body) CHECK(test_write_file(path_in(model, file), body, strlen(body)), file)
    SCENE("ok.txt", "view 0 0 2 2\nobject inside.csv t 1\nobject sub/../inside.csv t 1\n");
    SCENE("dotdot.txt", "view 0 0 2 2\nobject ../secret.csv t 1\n");
    SCENE("dotdot_ok.txt", "view 0 0 2 2\nobject ../square.csv t 1\n");
    SCENE("link.txt", "view 0 0 2 2\nobject link.csv t 1\n");
    SCENE("bad.txt", "view 0 0 2 2\nobject bad.csv t 1\n");
    SCENE("key.txt", "API_KEY=sk-1234567890abcdef\n");
    n = snprintf(text, sizeof text, "view 0 0 2 2\nobject %s/square.csv t 1\n", dir);
    CHECK(n > 0 && (size_t)n < sizeof text && test_write_file(path_in(model, "abs.txt"), text, (size_t)n), "abs.txt");
#undef SCENE
    scene2d_expect(path_in(model, "ok.txt"), SNELL_OK, NULL, NULL, "CSVs inside the folder");
    scene2d_expect(path_in(model, "dotdot.txt"), SNELL_E_IO, "outside the scene's folder", "sk-123", "../secret.csv");
    scene2d_expect(path_in(model, "dotdot_ok.txt"), SNELL_E_IO, "outside the scene's folder", NULL,
                   "../square.csv (a valid polygon)");
    scene2d_expect(path_in(model, "link.txt"), SNELL_E_IO, "outside the scene's folder", "sk-123", "link out");
    scene2d_expect(path_in(model, "abs.txt"), SNELL_E_IO, "relative to the scene's folder", NULL, "absolute path");
    /* a CSV in the folder that is not one, and a scene that is not one: named by line, not quoted */
    scene2d_expect(path_in(model, "bad.txt"), SNELL_E_PARSE, "bad.csv:2", "sk-123", "bad CSV");
    scene2d_expect(path_in(model, "key.txt"), SNELL_E_PARSE, "key.txt:1", "sk-123", "a key file as a scene");
}

/* ------------------------------------- item 8: control characters in messages */
/* 1 if msg holds a C0 control (but newline and tab), DEL or a UTF-8 C1 control. */
static int has_control(const char *msg)
{
    const unsigned char *p = (const unsigned char *)msg;
    for (; *p; p++)
        if ((*p < 0x20 && *p != '\n' && *p != '\t') || *p == 0x7f || (*p == 0xc2 && p[1] >= 0x80 && p[1] <= 0x9f))
            return 1;
    return 0;
}

static void test_control_chars(void)
{
    /* tinygltf quotes the buffer's URI, which JSON escapes made ESC ] 0 ; T BEL (a terminal title) */
    static const char gltf[] = "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":4,\"uri\":"
                               "\"data:application/octet-stream;base64,\\u001b]0;T\\u0007\\u00c2\\u009b\"}]}";
    char dir[800], scene[1024];
    snell_mesh *m = NULL;
    snell_scene2d *s2 = NULL;
    snell_status st;
    const char *msg;
    st = snell_mesh_load_gltf_mem(NULL, gltf, sizeof gltf - 1, &m);
    msg = snell_last_error(NULL);
    CHECK(st != SNELL_OK && !m && has(msg, "]0;T") && !has_control(msg), "tinygltf message with ESC/BEL: %s: %s",
          snell_status_str(st), msg);
    snell_mesh_destroy(m);
    /* a 2D scene naming a CSV whose name clears the screen and rings */
    snprintf(dir, sizeof dir, "%.790s", test_out("hostile4_ctrl"));
    mkdir(dir, 0755);
    snprintf(scene, sizeof scene, "%s", path_in(dir, "ctrl.txt"));
    {
        static const char text[] = "view 0 0 10 10\nobject \033[2J\007.csv t 1\n";
        CHECK(test_write_file(scene, text, sizeof text - 1), "ctrl.txt");
    }
    st = snell_scene2d_load(NULL, scene, &s2, NULL, NULL);
    msg = snell_last_error(NULL);
    CHECK(st == SNELL_E_IO && !s2 && has(msg, "[2J") && !has_control(msg), "2D scene message with ESC/BEL: %s: %s",
          snell_status_str(st), msg);
    snell_scene2d_destroy(s2);
}

/* ------------------------------------------------ item 9: silent wrong frames */
/* A glTF of one triangle (data: URI) in a node given by node_json, with a
 * second primitive of mode `extra_mode` (-1: none) beside it. */
static int gltf_tri(char *out, size_t cap, const char *node_json, int extra_mode)
{
    char extra[96] = "";
    if (extra_mode >= 0) snprintf(extra, sizeof extra, ",{\"attributes\":{\"POSITION\":0},\"mode\":%d}", extra_mode);
    return snprintf(out, cap,
                    "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[%s],"
                    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}%s]}],"
                    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
                    "\"min\":[0,0,0],\"max\":[1,1,0]}],"
                    "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"buffers\":[{\"byteLength\":36,\"uri\":"
                    "\"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}]}",
                    node_json, extra);
}

static void gltf_expect(snell_ctx *ctx, const char *node_json, int extra_mode, snell_status want, const char *needle,
                        const char *what)
{
    char json[2048];
    int n = gltf_tri(json, sizeof json, node_json, extra_mode);
    snell_mesh *m = NULL;
    snell_scene_file *sc = NULL;
    snell_status st = snell_mesh_load_gltf_mem(ctx, json, (size_t)n, &m);
    const char *msg = snell_last_error(ctx);
    CHECK(st == want && (st == SNELL_OK) == (m != NULL), "%s (mesh): %s: %s", what, snell_status_str(st), msg);
    if (needle && st != SNELL_OK) CHECK(has(msg, needle), "%s (mesh): message lacks \"%s\": %s", what, needle, msg);
    snell_mesh_destroy(m);
    st = snell_scene_load_gltf_mem(ctx, json, (size_t)n, &sc);
    msg = snell_last_error(ctx);
    CHECK(st == want && (st == SNELL_OK) == (sc != NULL), "%s (scene): %s: %s", what, snell_status_str(st), msg);
    if (needle && st != SNELL_OK) CHECK(has(msg, needle), "%s (scene): message lacks \"%s\": %s", what, needle, msg);
    snell_scene_file_destroy(sc);
}

static void test_wrong_frames(void)
{
    gltf_expect(NULL, "{\"mesh\":0}", -1, SNELL_OK, NULL, "plain triangle");
    gltf_expect(NULL, "{\"mesh\":0,\"matrix\":[1,0,0,1, 0,1,0,1, 0,0,1,1, 0,0,0,1]}", -1, SNELL_E_PARSE,
                "not affine", "bottom row 1,1,1,1");
    gltf_expect(NULL, "{\"mesh\":0,\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,2]}", -1, SNELL_E_PARSE,
                "not affine", "w = 2");
    gltf_expect(NULL, "{\"mesh\":0,\"matrix\":[2,0,0,0, 0,2,0,0, 0,0,2,0, 1,2,3,1]}", -1, SNELL_OK, NULL,
                "affine matrix");
    gltf_expect(NULL, "{\"mesh\":0}", 99, SNELL_E_PARSE, "primitive mode 99", "mode 99");
    gltf_expect(NULL, "{\"mesh\":0}", 1, SNELL_OK, NULL, "a line primitive beside a triangle");
}

/* ------------------------------------- item 5: the glTF parse's memory estimate */
/* 4 MiB budget: 40 KB of JSON holding 20,000 numbers in "extras" (about 190
 * bytes a value when parsed: 3.8 MB) passed an estimate of 8 bytes a JSON byte. */
static void test_gltf_values(snell_ctx *ctx)
{
    char tri[2048];
    size_t cap = 64 * 1024, n;
    char *json = (char *)malloc(cap);
    int i, k = gltf_tri(tri, sizeof tri, "{\"mesh\":0}", -1);
    snell_mesh *m = NULL;
    snell_status st;
    const char *msg;
    if (!json || k <= 0) {
        free(json);
        return;
    }
    /* {"extras":[0,0,...], then the triangle's members */
    n = (size_t)snprintf(json, cap, "{\"extras\":[0");
    for (i = 1; i < 20000; i++) json[n++] = ',', json[n++] = '0';
    n += (size_t)snprintf(json + n, cap - n, "],%s", tri + 1);
    st = snell_mesh_load_gltf_mem(ctx, json, n, &m);
    msg = snell_last_error(ctx);
    CHECK(st == SNELL_E_LIMIT && !m && has(msg, "about 20040 values") && has(msg, "memory budget of 4.0 MiB"),
          "20,000 numbers in extras under 4 MiB: %s: %s", snell_status_str(st), msg);
    snell_mesh_destroy(m);
    m = NULL;
    /* the triangle alone loads */
    st = snell_mesh_load_gltf_mem(ctx, tri, (size_t)k, &m);
    CHECK(st == SNELL_OK && m, "the triangle alone under 4 MiB: %s", snell_last_error(ctx));
    snell_mesh_destroy(m);
    free(json);
}

static char g_log[2048];
static void log_cb(snell_log_level level, const char *msg, void *user)
{
    size_t n = strlen(g_log);
    (void)level;
    (void)user;
    snprintf(g_log + n, sizeof g_log - n, "%s\n", msg);
}

/* ---------------------------------------------- item 11: the smaller ones */
static void test_small_cpu(void)
{
    static const char bom_obj[] = "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    char dir[800];
    snell_mesh *m = NULL;
    snell_scene2d *s2 = NULL;
    snell_status st;
    float mx[3] = {1, 1, 1};
    /* NULL outputs are skipped (it segfaulted) */
    snell_mesh_bounds(NULL, NULL, NULL);
    snell_mesh_bounds(NULL, NULL, mx);
    CHECK(mx[0] == 0.0f && mx[2] == 0.0f, "snell_mesh_bounds(NULL, NULL, mx)");
    /* a UTF-8 byte-order mark before the first "v" (the line was dropped) */
    st = snell_mesh_load_obj_mem(NULL, bom_obj, sizeof bom_obj - 1, &m);
    CHECK(st == SNELL_OK && snell_mesh_vertex_count(m) == 3 && snell_mesh_triangle_count(m) == 1,
          "OBJ with a byte-order mark: %s: %s", snell_status_str(st), snell_last_error(NULL));
    snell_mesh_destroy(m);
    /* a folder named as a CSV: "is a directory", not "larger than 67108864 bytes" */
    snprintf(dir, sizeof dir, "%.790s", test_out("hostile4_dircsv"));
    mkdir(dir, 0755);
    mkdir(path_in(dir, "poly.csv"), 0755);
    {
        static const char text[] = "view 0 0 2 2\nobject poly.csv t 1\n";
        CHECK(test_write_file(path_in(dir, "s.txt"), text, sizeof text - 1), "s.txt");
    }
    st = snell_scene2d_load(NULL, path_in(dir, "s.txt"), &s2, NULL, NULL);
    CHECK(st == SNELL_E_IO && has(snell_last_error(NULL), "is a directory") &&
              !has(snell_last_error(NULL), "larger than"),
          "a folder as a CSV: %s: %s", snell_status_str(st), snell_last_error(NULL));
    snell_scene2d_destroy(s2);
}

/* The context cases of item 11 (4 MiB budget): a renderer beyond it, a
 * budget message that rounds both sides to the same MiB, a model scale whose
 * determinant overflows, an environment whose context was destroyed. */
static void test_small_ctx(snell_ctx *ctx)
{
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    snell_lightmap2d_desc ld;
    snell_lightmap2d *lm = NULL;
    snell_env_desc ed;
    snell_env *env = NULL, *env2 = NULL;
    snell_mesh *mesh = NULL;
    snell_frame_desc fd;
    snell_glass g;
    snell_ctx *ctx2 = NULL;
    snell_status st;
    float model[16] = {1e20f, 0, 0, 0, 0, 1e20f, 0, 0, 0, 0, 1e20f, 0, 0, 0, 0, 1};
    const char *msg;
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = 1024; /* 8 MiB of colour and depth */
    st = snell_renderer_create(ctx, &rd, &r);
    msg = snell_last_error(ctx);
    CHECK(st == SNELL_E_LIMIT && !r && has(msg, "1024x1024 offscreen renderer") && has(msg, "memory budget"),
          "1024^2 renderer in 4 MiB: %s: %s", snell_status_str(st), msg);
    snell_renderer_destroy(r);
    r = NULL;
    /* 481 x 545 pixels of 16 bytes: 16 bytes over 4 MiB */
    memset(&ld, 0, sizeof ld);
    ld.width = 481;
    ld.height = 545;
    ld.cpu_only = 1;
    st = snell_lightmap2d_create(ctx, &ld, &lm);
    msg = snell_last_error(ctx);
    CHECK(st == SNELL_E_LIMIT && has(msg, "needs 4194320 bytes, more than the memory budget of 4194304 bytes"),
          "budget message at the rounding: %s: %s", snell_status_str(st), msg);
    snell_lightmap2d_destroy(lm);
    /* a model scale of 1e20: its determinant overflows, the matrix is not singular */
    memset(&ed, 0, sizeof ed);
    ed.face_size = 16;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &env));
    {
        snell_shape_desc sd;
        memset(&sd, 0, sizeof sd);
        sd.shape = SNELL_SHAPE_SPHERE;
        CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &mesh));
    }
    rd.width = rd.height = 32;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (r && env && mesh) {
        test_frame_one(&fd, &g, mesh, env);
        g.model = model;
        st = snell_render(r, &fd, NULL);
        msg = snell_last_error(ctx);
        CHECK(st == SNELL_E_INVALID_ARG && has(msg, "overflows") && !has(msg, "singular"), "scale 1e20: %s: %s",
              snell_status_str(st), msg);
        /* an environment of a context destroyed since */
        if (snell_ctx_create(NULL, &ctx2) == SNELL_OK) {
            CHECK_OK_CTX(ctx2, snell_env_create(ctx2, &ed, &env2));
            snell_ctx_destroy(ctx2);
            snell_ctx_make_current(ctx);
            g.model = NULL;
            fd.env = env2;
            st = snell_render(r, &fd, NULL);
            msg = snell_last_error(ctx);
            CHECK(st == SNELL_E_INVALID_ARG && has(msg, "went with its context"), "env of a destroyed context: %s: %s",
                  snell_status_str(st), msg);
            snell_env_destroy(env2);
        }
    }
    snell_renderer_destroy(r);
    snell_mesh_destroy(mesh);
    snell_env_destroy(env);
}

/* ------------------------------------ item 2: the 2D lightmap's memory budget */
/* A lightmap of w x h (cpu_only as given) on a scene of `lights` point lights
 * of `rays` rays each, in a glass box; returns the status of its first frame
 * (or of its creation) and leaves the message in the context. */
static snell_status lm2d_case(snell_ctx *ctx, int w, int h, int cpu_only, int lights, int rays)
{
    char text[4096];
    const char *path = test_out("hostile4_lights.txt");
    snell_scene2d *scene = NULL;
    snell_lightmap2d *lm = NULL;
    snell_lightmap2d_desc d;
    snell_status st;
    int n, i;
    n = snprintf(text, sizeof text, "view 0 0 100 100\npolygon 10 10 90 10 90 90 10 90 ; t 1 ior 1.5\n");
    for (i = 0; i < lights && n < (int)sizeof text - 80; i++)
        n += snprintf(text + n, sizeof text - (size_t)n, "light point pos %d 50 rays %d\n", 20 + i, rays);
    CHECK(test_write_file(path, text, (size_t)n), "writing %s", path);
    st = snell_scene2d_load(ctx, path, &scene, NULL, NULL);
    CHECK(st == SNELL_OK, "scene of %d lights: %s", lights, snell_last_error(ctx));
    if (st != SNELL_OK) return st;
    memset(&d, 0, sizeof d);
    d.width = w;
    d.height = h;
    d.threads = 2;
    d.cpu_only = cpu_only;
    st = snell_lightmap2d_create(ctx, &d, &lm);
    if (st == SNELL_OK) st = snell_lightmap2d_frame(lm, scene, NULL);
    snell_lightmap2d_destroy(lm);
    snell_scene2d_destroy(scene);
    return st;
}

static void test_lm2d_budget(snell_ctx *ctx)
{
    snell_status st;
    const char *msg;
    /* 4 MiB budget: a 1024x1024 lightmap holds 16 MiB of floats on the CPU alone */
    st = lm2d_case(ctx, 1024, 1024, 1, 1, 100);
    msg = snell_last_error(ctx);
    CHECK(st == SNELL_E_LIMIT && has(msg, "1024x1024 lightmap") && has(msg, "memory budget of 4.0 MiB"),
          "1024^2 lightmap over 4 MiB: %s: %s", snell_status_str(st), msg);
    /* with GL the texture and its readback count too: 512x256 is 2 MiB on the CPU, 6 MiB with GL */
    st = lm2d_case(ctx, 512, 256, 0, 1, 100);
    msg = snell_last_error(ctx);
    CHECK(st == SNELL_E_LIMIT && has(msg, "512x256 lightmap"), "512x256 GL lightmap over 4 MiB: %s: %s",
          snell_status_str(st), msg);
    /* twelve lights of 2,000 rays: each light's 720 KB path buffer fits, their sum (and the bins) does not */
    st = lm2d_case(ctx, 64, 64, 1, 12, 2000);
    msg = snell_last_error(ctx);
    CHECK(st == SNELL_E_LIMIT && has(msg, "12 lights") && has(msg, "memory budget of 4.0 MiB"),
          "12 lights over 4 MiB: %s: %s", snell_status_str(st), msg);
    /* what fits still renders: one light of 1,000 rays on 64x64 */
    st = lm2d_case(ctx, 64, 64, 1, 1, 1000);
    CHECK(st == SNELL_OK, "small 2D scene in 4 MiB: %s", snell_last_error(ctx));
    st = lm2d_case(ctx, 64, 64, 0, 1, 1000);
    CHECK(st == SNELL_OK, "small 2D scene with GL in 4 MiB: %s", snell_last_error(ctx));
}

static void test_ctx_cases(void)
{
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_status st;
    memset(&cd, 0, sizeof cd);
    cd.memory_budget = (size_t)4 << 20;
    cd.log = log_cb;
    st = snell_ctx_create(&cd, &ctx);
    if (st != SNELL_OK) {
        printf("SKIP budget cases: no context (%s)\n", snell_last_error(NULL));
        return;
    }
    /* item 9: a line primitive left out says so */
    g_log[0] = '\0';
    gltf_expect(ctx, "{\"mesh\":0}", 1, SNELL_OK, NULL, "a line primitive beside a triangle");
    CHECK(has(g_log, "points or lines (mode 1) left out"), "no log line for a line primitive: %s", g_log);
    test_lm2d_budget(ctx);
    test_gltf_values(ctx);
    test_small_ctx(ctx);
    snell_ctx_destroy(ctx);
}

int main(int argc, char **argv)
{
    signal(SIGALRM, on_alarm);
    if (argc > 1 && strcmp(argv[1], "ctx") == 0) {
        test_ctx_cases();
        return test_finish();
    }
    test_glb_chunks();
    test_fifos();
    test_png_bomb();
    test_control_chars();
    test_scene2d_folder();
    test_small_cpu();
    test_wrong_frames();
    return test_finish();
}
