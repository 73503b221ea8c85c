/* SPDX-License-Identifier: MIT */
/* test_hostile_files.c — issue 14, files as an attacker writes them: glTF
 * URIs that leave the model's folder (item 2), coordinates at the float range
 * (item 6), coincident triangles that stalled the analysis (item 7), sizes
 * beyond the memory budget and the messages of refused files ("Also"). Each
 * case failed on the code before the fix. Without arguments: CPU-only cases
 * (ctx NULL: the default memory budget). With "ctx": the cases that need a
 * context with a small snell_ctx_desc.memory_budget (GL, label gl).
 * Small inputs are under tests/data/hostile (make_hostile.py); big ones and the
 * folder layouts are made here at run time. */
#define _POSIX_C_SOURCE 200809L /* mkdir, symlink, mkfifo, chdir, alarm */
#include "test_util.h"
#include "mesh/bvh.h"
#include "snell/snell_2d.h"

#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* A decoder that loops forever must fail the test, not hang ctest. */
static void on_alarm(int sig)
{
    static const char msg[] = "FAIL: a call did not return within the alarm (infinite loop?)\n";
    (void)sig;
    if (write(2, msg, sizeof msg - 1) < 0) _exit(1);
    _exit(1);
}

static const char *path_in(const char *dir, const char *name)
{
    static char buf[4][1024];
    static int k;
    k = (k + 1) % 4;
    if (snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name) >= (int)sizeof buf[k]) buf[k][0] = '\0'; /* too long: no such file */
    return buf[k];
}

static void expect_fail(snell_status st, snell_mesh *m, snell_status want, const char *needle, const char *what)
{
    const char *msg = snell_last_error(NULL);
    CHECK(st == want && m == NULL, "%s: got %s (want %s): %s", what, snell_status_str(st), snell_status_str(want), msg);
    if (needle) CHECK(strstr(msg, needle) != NULL, "%s: message lacks \"%s\": %s", what, needle, msg);
    snell_mesh_destroy(m);
}

/* ------------------------------------------------------------ item 2: URIs */

/* A glTF of one triangle whose buffer is uri (byteLength bytes). */
static void write_gltf(const char *path, const char *uri, int byte_length)
{
    char json[2048];
    int n = snprintf(json, sizeof json,
                     "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
                     "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
                     "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"
                     "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36}],"
                     "\"buffers\":[{\"byteLength\":%d,\"uri\":\"%s\"}]}",
                     byte_length, uri);
    CHECK(n > 0 && (size_t)n < sizeof json && test_write_file(path, json, (size_t)n), "writing %s", path);
}

static void test_uris(void)
{
    static const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    char dir[800], model[1024], cwd[1024], abs_uri[1100];
    snell_mesh *m = NULL;
    snell_status st;
    snprintf(dir, sizeof dir, "%.790s", test_out("hostile_uri"));
    snprintf(model, sizeof model, "%s/model", dir);
    mkdir(dir, 0755);
    mkdir(model, 0755);
    mkdir(path_in(model, "sub"), 0755);
    CHECK(test_write_file(path_in(dir, "secret.bin"), tri, sizeof tri), "secret.bin");
    CHECK(test_write_file(path_in(dir, "cwdonly.bin"), tri, sizeof tri), "cwdonly.bin");
    CHECK(test_write_file(path_in(model, "inside.bin"), tri, sizeof tri), "inside.bin");
    unlink(path_in(model, "link.bin"));
    CHECK(symlink("../secret.bin", path_in(model, "link.bin")) == 0, "symlink");
    unlink(path_in(model, "fifo"));
    CHECK(mkfifo(path_in(model, "fifo"), 0644) == 0, "mkfifo");
    snprintf(abs_uri, sizeof abs_uri, "%s/secret.bin", dir);

    write_gltf(path_in(model, "ok.gltf"), "inside.bin", 36);
    write_gltf(path_in(model, "ok_dots.gltf"), "sub/../inside%2Ebin", 36);
    write_gltf(path_in(model, "dotdot.gltf"), "../secret.bin", 36);
    write_gltf(path_in(model, "pct.gltf"), "..%2Fsecret.bin", 36);
    write_gltf(path_in(model, "size.gltf"), "../secret.bin", 1);
    write_gltf(path_in(model, "abs.gltf"), abs_uri, 36);
    write_gltf(path_in(model, "link.gltf"), "link.bin", 36);
    write_gltf(path_in(model, "cwd.gltf"), "cwdonly.bin", 36);
    write_gltf(path_in(model, "fifo.gltf"), "fifo", 36);
    write_gltf(path_in(model, "dir.gltf"), "sub", 36);

    /* inside the folder: loads (also through "sub/.." and percent-encoding) */
    st = snell_mesh_load_gltf(NULL, path_in(model, "ok.gltf"), &m);
    CHECK(st == SNELL_OK && snell_mesh_vertex_count(m) == 3, "inside the folder: %s", snell_last_error(NULL));
    snell_mesh_destroy(m);
    st = snell_mesh_load_gltf(NULL, path_in(model, "ok_dots.gltf"), &m);
    CHECK(st == SNELL_OK, "sub/../inside%%2Ebin: %s", snell_last_error(NULL));
    snell_mesh_destroy(m);
    /* data: URIs need no file */
    st = snell_mesh_load_gltf(NULL, test_data("nodes.gltf"), &m);
    CHECK(st == SNELL_OK, "data: URI: %s", snell_last_error(NULL));
    snell_mesh_destroy(m);

    /* out of the folder: refused, by "..", by "%2F", by a symlink, by an absolute path */
    st = snell_mesh_load_gltf(NULL, path_in(model, "dotdot.gltf"), &m);
    expect_fail(st, m, SNELL_E_IO, "leaves the model's folder", "../secret.bin");
    st = snell_mesh_load_gltf(NULL, path_in(model, "pct.gltf"), &m);
    expect_fail(st, m, SNELL_E_IO, "leaves the model's folder", "..%2Fsecret.bin");
    st = snell_mesh_load_gltf(NULL, path_in(model, "link.gltf"), &m);
    expect_fail(st, m, SNELL_E_IO, "leaves the model's folder", "symlink out of the folder");
    st = snell_mesh_load_gltf(NULL, path_in(model, "abs.gltf"), &m);
    CHECK(st != SNELL_OK && m == NULL, "absolute URI (model by full path): %s", snell_status_str(st));
    snell_mesh_destroy(m);
    m = NULL;
    /* the size of a refused file must not leak (it is 36 bytes; byteLength says 1) */
    st = snell_mesh_load_gltf(NULL, path_in(model, "size.gltf"), &m);
    CHECK(st != SNELL_OK && m == NULL && !strstr(snell_last_error(NULL), "36"), "size leak: %s",
          snell_last_error(NULL));
    snell_mesh_destroy(m);
    m = NULL;
    /* non-regular files: refused (and a FIFO must not block the load) */
    alarm(20);
    st = snell_mesh_load_gltf(NULL, path_in(model, "fifo.gltf"), &m);
    expect_fail(st, m, SNELL_E_IO, "not a regular file", "FIFO");
    m = NULL;
    st = snell_mesh_load_gltf(NULL, path_in(model, "dir.gltf"), &m);
    CHECK(st != SNELL_OK && m == NULL, "directory URI: %s", snell_status_str(st));
    alarm(0);

    /* relative model paths: the model's folder is the current directory, an
     * absolute URI is refused as such; and tinygltf's fallback to the current
     * directory (cwdonly.bin is not in the model's folder) is not taken */
    if (getcwd(cwd, sizeof cwd) && chdir(model) == 0) {
        st = snell_mesh_load_gltf(NULL, "abs.gltf", &m);
        expect_fail(st, m, SNELL_E_IO, "absolute path", "absolute URI (model in the current directory)");
        m = NULL;
        st = snell_mesh_load_gltf(NULL, "ok.gltf", &m);
        CHECK(st == SNELL_OK, "relative model path: %s", snell_last_error(NULL));
        snell_mesh_destroy(m);
        m = NULL;
        CHECK(chdir(dir) == 0, "chdir");
        st = snell_mesh_load_gltf(NULL, "model/cwd.gltf", &m);
        CHECK(st != SNELL_OK && m == NULL, "URI found only in the current directory loaded: %s",
              snell_status_str(st));
        snell_mesh_destroy(m);
        m = NULL;
        CHECK(chdir(cwd) == 0, "chdir back");
    }

    /* the caller's opt-in */
    st = snell_mesh_load_gltf_ex(NULL, path_in(model, "dotdot.gltf"), SNELL_LOAD_ALLOW_OUTSIDE_FOLDER, &m);
    CHECK(st == SNELL_OK && snell_mesh_vertex_count(m) == 3, "opt-in ../: %s", snell_last_error(NULL));
    snell_mesh_destroy(m);
    st = snell_mesh_load_gltf_ex(NULL, path_in(model, "link.gltf"), SNELL_LOAD_ALLOW_OUTSIDE_FOLDER, &m);
    CHECK(st == SNELL_OK, "opt-in symlink: %s", snell_last_error(NULL));
    snell_mesh_destroy(m);
    st = snell_mesh_load_gltf_ex(NULL, path_in(model, "abs.gltf"), SNELL_LOAD_ALLOW_OUTSIDE_FOLDER, &m);
    CHECK(st == SNELL_OK, "opt-in absolute: %s", snell_last_error(NULL));
    snell_mesh_destroy(m);
    m = NULL;
    alarm(20);
    st = snell_mesh_load_gltf_ex(NULL, path_in(model, "fifo.gltf"), SNELL_LOAD_ALLOW_OUTSIDE_FOLDER, &m);
    expect_fail(st, m, SNELL_E_IO, "not a regular file", "opt-in FIFO");
    alarm(0);
    m = NULL;
    st = snell_mesh_load_gltf_ex(NULL, path_in(model, "ok.gltf"), 0x80, &m);
    expect_fail(st, m, SNELL_E_INVALID_ARG, "flags", "unknown flag");
}

/* ---------------------------------------------------- item 6: float range */

static void test_huge_coordinates(void)
{
    snell_mesh *m = NULL;
    float mn[3], mx[3];
    snell_status st;
    uint32_t i;
    int k, ok;

    /* +-1e38: the squared distance overflowed float, the radius was Inf, the
     * scale 0, and the mesh became a point */
    st = snell_mesh_load_obj(NULL, test_data("hostile/huge_coords.obj"), &m);
    CHECK(st == SNELL_OK, "huge_coords.obj: %s", snell_last_error(NULL));
    if (st == SNELL_OK) {
        st = snell_mesh_normalize(m, 1.0f);
        CHECK(st == SNELL_OK, "normalize 1e38: %s", snell_last_error(NULL));
        snell_mesh_bounds(m, mn, mx);
        /* a regular tetrahedron in a cube: half side 1/sqrt(3) */
        for (k = 0, ok = 1; k < 3; k++)
            ok &= fabsf(mx[k] - 0.57735f) < 1e-4f && fabsf(mn[k] + 0.57735f) < 1e-4f;
        CHECK(ok, "normalised 1e38 mesh: bounds (%g %g %g)..(%g %g %g), want +-0.577", mn[0], mn[1], mn[2], mx[0],
              mx[1], mx[2]);
        for (i = 0, ok = 1; i < 3 * snell_mesh_vertex_count(m); i++) ok &= isfinite(snell_mesh_positions(m)[i]);
        CHECK(ok, "normalised 1e38 mesh: finite positions");
        /* a radius whose mesh would not fit in float */
        st = snell_mesh_normalize(m, 3e38f);
        CHECK(st == SNELL_E_INVALID_ARG && strstr(snell_last_error(NULL), "too large"), "normalize(3e38): %s: %s",
              snell_status_str(st), snell_last_error(NULL));
    }
    snell_mesh_destroy(m);
    m = NULL;

    /* 1e-30: the float squared distances underflowed to 0 ("degenerate") */
    st = snell_mesh_load_obj(NULL, test_data("hostile/tiny_coords.obj"), &m);
    CHECK(st == SNELL_OK, "tiny_coords.obj: %s", snell_last_error(NULL));
    if (st == SNELL_OK) {
        st = snell_mesh_normalize(m, 1.0f);
        snell_mesh_bounds(m, mn, mx);
        CHECK(st == SNELL_OK && fabsf(mx[0] - 0.57735f) < 1e-4f, "normalize 1e-30: %s (max x %g)",
              snell_last_error(NULL), mx[0]);
    }
    snell_mesh_destroy(m);
    m = NULL;

    /* -3e38..3e38: the extent is beyond float: a clear error with the size */
    st = snell_mesh_load_obj(NULL, test_data("hostile/too_big_coords.obj"), &m);
    expect_fail(st, m, SNELL_E_LIMIT, "e+38", "extent 6e38 (OBJ)");
    {
        const float p[9] = {3e38f, 0, 0, -3e38f, 0, 0, 0, 1, 0};
        snell_mesh_desc d;
        memset(&d, 0, sizeof d);
        d.positions = p;
        d.vertex_count = 3;
        m = NULL;
        st = snell_mesh_create(NULL, &d, &m);
        expect_fail(st, m, SNELL_E_LIMIT, "too large", "extent 6e38 (snell_mesh_create)");
    }
}

/* --------------------------------------- item 7: coincident triangles */

static void test_coincident(void)
{
    const int corners = 40000; /* one face: 39,998 triangles, a third of them the same one */
    size_t cap = 64 + 6 * (size_t)corners, n = 0;
    char *obj = (char *)malloc(cap);
    snell_mesh *m = NULL;
    snell_mesh_analysis a;
    snell_status st;
    double t0, dt;
    int i;
    n += (size_t)snprintf(obj, cap, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf");
    for (i = 0; i < corners; i++) n += (size_t)snprintf(obj + n, cap - n, " %d", 1 + i % 3);
    n += (size_t)snprintf(obj + n, cap - n, "\n");
    st = snell_mesh_load_obj_mem(NULL, obj, n, &m);
    CHECK(st == SNELL_OK && snell_mesh_triangle_count(m) == (uint32_t)corners - 2, "40,000-corner face: %s",
          snell_last_error(NULL));
    free(obj);
    if (st != SNELL_OK) return;

    /* the BVH caps its leaves whatever the centroids (split by halves) */
    {
        snell__bvh *bvh = NULL;
        uint32_t k, biggest = 0;
        CHECK_OK(snell__bvh_build_mesh(NULL, m, NULL, &bvh));
        if (bvh) {
            for (k = 0; k < bvh->node_count; k++)
                if (bvh->nodes[k].count > biggest) biggest = bvh->nodes[k].count;
            CHECK(biggest <= 4 && bvh->depth <= 64, "coincident BVH: largest leaf %u, depth %d", biggest, bvh->depth);
        }
        snell__bvh_destroy(bvh);
    }

    /* the analysis's cost is bounded by the triangle count: a stated failure,
     * quickly (it took 8.5 s here, >100 s reported, before the bound) */
    t0 = now_s();
    st = snell_mesh_analyze(m, &a);
    dt = now_s() - t0;
    CHECK(st == SNELL_E_LIMIT && strstr(snell_last_error(NULL), "work bound"), "coincident analysis: %s: %s",
          snell_status_str(st), snell_last_error(NULL));
    CHECK(dt < 5.0 * test_time_scale(), "coincident analysis took %.2f s (bound %.0f s)", dt, 5.0 * test_time_scale());
    printf("coincident face: analysis %s in %.2f s\n", snell_status_str(st), dt);
    snell_mesh_destroy(m);
}

/* ------------------------------------------------- Also: memory budget */

/* A 2D scene whose one light asks for more path segments than the default
 * budget holds (1e6 rays x 9 segments x 40 bytes = 360 MB; "rays 100000000"
 * asked for 36 GB). */
static void test_budget_lm2d(snell_ctx *ctx, int rays, const char *needle)
{
    char text[256];
    const char *path = test_out("hostile_rays.txt");
    snell_scene2d *scene = NULL;
    snell_lightmap2d *lm = NULL;
    snell_lightmap2d_desc d;
    snell_status st;
    float view[4];
    int size[2];
    int n = snprintf(text, sizeof text, "size 64 64\nview 0 0 64 64\nlight point pos 32 32 power 1 rays %d\n", rays);
    CHECK(test_write_file(path, text, (size_t)n), "writing %s", path);
    st = snell_scene2d_load(ctx, path, &scene, view, size);
    CHECK(st == SNELL_OK, "scene with rays %d: %s", rays, snell_last_error(ctx));
    if (st != SNELL_OK) return;
    memset(&d, 0, sizeof d);
    d.width = d.height = 64;
    d.threads = 1;
    d.cpu_only = 1;
    CHECK_OK_CTX(ctx, snell_lightmap2d_create(ctx, &d, &lm));
    if (lm) {
        st = snell_lightmap2d_frame(lm, scene, NULL);
        CHECK(st == SNELL_E_LIMIT && strstr(snell_last_error(ctx), needle), "rays %d: %s: %s", rays,
              snell_status_str(st), snell_last_error(ctx));
    }
    snell_lightmap2d_destroy(lm);
    snell_scene2d_destroy(scene);
}

/* A .gltf whose data: URI holds bin_bytes bytes (a triangle, then zeros). */
static char *gltf_with_data_uri(size_t bin_bytes, size_t *len)
{
    static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char *head1 = "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
                        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
                        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"
                        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36}],\"buffers\":[{\"byteLength\":";
    const char *head2 = ",\"uri\":\"data:application/octet-stream;base64,";
    const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    size_t nb = (bin_bytes + 2) / 3 * 3, cap = strlen(head1) + 32 + strlen(head2) + nb / 3 * 4 + 16, n, i;
    unsigned char *bin = (unsigned char *)calloc(nb, 1);
    char *s = (char *)malloc(cap);
    if (!bin || !s) {
        free(bin);
        free(s);
        return NULL;
    }
    memcpy(bin, tri, sizeof tri);
    n = (size_t)snprintf(s, cap, "%s%zu%s", head1, nb, head2);
    for (i = 0; i < nb; i += 3) {
        unsigned v = (unsigned)bin[i] << 16 | (unsigned)bin[i + 1] << 8 | bin[i + 2];
        s[n++] = b64[v >> 18 & 63];
        s[n++] = b64[v >> 12 & 63];
        s[n++] = b64[v >> 6 & 63];
        s[n++] = b64[v & 63];
    }
    n += (size_t)snprintf(s + n, cap - n, "\"}]}");
    free(bin);
    *len = n;
    return s;
}

static void test_budget_default(void)
{
    snell_mesh *m = NULL;
    snell_status st;
    size_t len = 0;
    char *g;
    uint8_t *px = NULL;
    int w, h;

    /* a 40 MB data: URI: tinygltf would hold ~8x that; over the 256 MiB default */
    g = gltf_with_data_uri((size_t)30 << 20, &len);
    CHECK(g != NULL, "40 MB glTF");
    if (g) {
        st = snell_mesh_load_gltf_mem(NULL, g, len, &m);
        expect_fail(st, m, SNELL_E_LIMIT, "memory budget of 256.0 MiB", "40 MB data: URI");
        free(g);
    }
    /* a small one still loads */
    g = gltf_with_data_uri(4096, &len);
    if (g) {
        m = NULL;
        st = snell_mesh_load_gltf_mem(NULL, g, len, &m);
        CHECK(st == SNELL_OK, "4 KB data: URI: %s", snell_last_error(NULL));
        snell_mesh_destroy(m);
        free(g);
    }
    /* an 8192x4096 HDR decodes through 640 MiB of floats: over the default
     * budget, refused before stb allocates (the file holds no pixels at all) */
    {
        static const char hdr[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4096 +X 8192\n";
        st = snell_image_decode(hdr, sizeof hdr - 1, &w, &h, &px);
        CHECK(st == SNELL_E_LIMIT && px == NULL && strstr(snell_last_error(NULL), "memory budget"),
              "8192x4096 HDR: %s: %s", snell_status_str(st), snell_last_error(NULL));
        snell_image_free(px);
        px = NULL;
    }
    test_budget_lm2d(NULL, 1000000, "memory budget of 256.0 MiB");
}

static void test_budget_ctx(void)
{
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_mesh *m = NULL;
    snell_status st;
    size_t len = 0, n = 0, i;
    char *text, *g;
    memset(&cd, 0, sizeof cd);
    cd.memory_budget = (size_t)1 << 20; /* 1 MiB */
    st = snell_ctx_create(&cd, &ctx);
    if (st != SNELL_OK) {
        printf("SKIP budget cases: no context (%s)\n", snell_last_error(NULL));
        return;
    }
    /* OBJ: 100,000 vertices need well over 1 MiB of parse arrays */
    text = (char *)malloc(100000 * 8 + 64);
    for (i = 0; i < 100000; i++) n += (size_t)sprintf(text + n, "v %d 0 0\n", (int)(i % 10));
    n += (size_t)sprintf(text + n, "f 1 2 3\n");
    st = snell_mesh_load_obj_mem(ctx, text, n, &m);
    CHECK(st == SNELL_E_LIMIT && m == NULL && strstr(snell_last_error(ctx), "memory budget of 1.0 MiB"),
          "OBJ over a 1 MiB budget: %s: %s", snell_status_str(st), snell_last_error(ctx));
    free(text);
    /* within it: loads */
    m = NULL;
    st = snell_mesh_load_obj(ctx, test_data("quad_ngon.obj"), &m);
    CHECK(st == SNELL_OK, "small OBJ within 1 MiB: %s", snell_last_error(ctx));
    snell_mesh_destroy(m);
    /* glTF: a 300 KB data: URI (~3 MB to parse) */
    g = gltf_with_data_uri(300000, &len);
    if (g) {
        m = NULL;
        st = snell_mesh_load_gltf_mem(ctx, g, len, &m);
        CHECK(st == SNELL_E_LIMIT && m == NULL && strstr(snell_last_error(ctx), "memory budget of 1.0 MiB"),
              "glTF over a 1 MiB budget: %s: %s", snell_status_str(st), snell_last_error(ctx));
        free(g);
    }
    /* snell_mesh_create of 100,000 vertices (2.4 MB) */
    {
        float *p = (float *)calloc(300000, sizeof(float));
        snell_mesh_desc d;
        memset(&d, 0, sizeof d);
        p[3] = p[7] = 1.0f;
        d.positions = p;
        d.vertex_count = 99999;
        m = NULL;
        st = snell_mesh_create(ctx, &d, &m);
        CHECK(st == SNELL_E_LIMIT && m == NULL && strstr(snell_last_error(ctx), "memory budget"),
              "mesh_create over budget: %s: %s", snell_status_str(st), snell_last_error(ctx));
        free(p);
    }
    /* an environment image of 512x512 (2 MiB to decode) */
    {
        uint8_t *rgba = (uint8_t *)calloc(512 * 512, 4);
        const char *png = test_out("hostile_512.png");
        snell_env_desc ed;
        snell_env *env = NULL;
        CHECK_OK(snell_write_png(png, 512, 512, rgba));
        memset(&ed, 0, sizeof ed);
        ed.source = SNELL_ENV_EQUIRECT;
        ed.equirect_path = png;
        ed.face_size = 16;
        st = snell_env_create(ctx, &ed, &env);
        CHECK(st == SNELL_E_LIMIT && env == NULL && strstr(snell_last_error(ctx), "memory budget of 1.0 MiB"),
              "env image over budget: %s: %s", snell_status_str(st), snell_last_error(ctx));
        snell_env_destroy(env);
        free(rgba);
    }
    /* the 2D path buffer: 100,000 rays x 9 segments */
    test_budget_lm2d(ctx, 100000, "memory budget of 1.0 MiB");
    snell_ctx_destroy(ctx);
}

/* ------------------------------------------------- Also: the messages */

static void test_messages(void)
{
    snell_mesh *m = NULL;
    snell_status st;
    uint8_t *px = NULL;
    int w, h;

    /* an over-size PNG says the size limit, not "unknown type, or corrupt" */
    st = snell_image_read(test_data("images/bad_huge_dims.png"), &w, &h, &px);
    CHECK(st == SNELL_E_LIMIT && strstr(snell_last_error(NULL), "16384"), "100000^2 PNG: %s: %s",
          snell_status_str(st), snell_last_error(NULL));
    st = snell_image_read(test_data("hostile/huge_dims.hdr"), &w, &h, &px);
    CHECK(st == SNELL_E_LIMIT && strstr(snell_last_error(NULL), "16384"), "20000-wide HDR: %s: %s",
          snell_status_str(st), snell_last_error(NULL));
    /* a directory is a directory, not 9223372036854775807 bytes */
    st = snell_image_read(test_data("hostile"), &w, &h, &px);
    CHECK(st == SNELL_E_IO && strstr(snell_last_error(NULL), "directory") &&
              !strstr(snell_last_error(NULL), "9223372036854775807"),
          "image from a directory: %s: %s", snell_status_str(st), snell_last_error(NULL));
    st = snell_mesh_load_obj(NULL, test_data("hostile"), &m);
    expect_fail(st, m, SNELL_E_IO, "directory", "OBJ from a directory");
    m = NULL;
    st = snell_mesh_load_gltf(NULL, test_data("hostile"), &m);
    expect_fail(st, m, SNELL_E_IO, "directory", "glTF from a directory");
    m = NULL;
    /* truncated HDRs are rejected (the run-length one, last below, made stb loop forever) */
    st = snell_image_read(test_data("hostile/truncated_flat.hdr"), &w, &h, &px);
    CHECK(st == SNELL_E_PARSE && px == NULL && strstr(snell_last_error(NULL), "truncated"),
          "truncated flat HDR: %s: %s", snell_status_str(st), snell_last_error(NULL));
    snell_image_free(px);
    px = NULL;
    /* complete HDRs still decode */
    st = snell_image_read(test_data("hostile/rle_8x8.hdr"), &w, &h, &px);
    /* RGBE (128, 128, 128, 128) is 0.5: 128 as RGBA8 */
    CHECK(st == SNELL_OK && w == 8 && h == 8 && px && px[0] == 128 && px[4 * 63 + 2] == 128,
          "complete RLE HDR: %s (%d)", snell_status_str(st), px ? px[0] : -1);
    snell_image_free(px);
    px = NULL;
    st = snell_image_read(test_data("images/ok.hdr"), &w, &h, &px);
    CHECK(st == SNELL_OK, "ok.hdr: %s", snell_last_error(NULL));
    snell_image_free(px);
    /* glTF 1.0, Draco, other required extensions */
    st = snell_mesh_load_gltf(NULL, test_data("hostile/gltf1.gltf"), &m);
    expect_fail(st, m, SNELL_E_UNSUPPORTED, "glTF 1.0 is not supported", "glTF 1.0");
    m = NULL;
    st = snell_mesh_load_gltf(NULL, test_data("hostile/draco.gltf"), &m);
    expect_fail(st, m, SNELL_E_UNSUPPORTED, "KHR_draco_mesh_compression", "Draco");
    CHECK(strstr(snell_last_error(NULL), "not supported") != NULL, "Draco: %s", snell_last_error(NULL));
    m = NULL;
    st = snell_mesh_load_gltf(NULL, test_data("hostile/required_unknown.gltf"), &m);
    expect_fail(st, m, SNELL_E_UNSUPPORTED, "EXT_snell_unknown", "unknown required extension");
    m = NULL;
    st = snell_mesh_load_gltf(NULL, test_data("hostile/required_materials.gltf"), &m);
    CHECK(st == SNELL_OK, "required KHR_materials_ior: %s", snell_last_error(NULL));
    snell_mesh_destroy(m);
    alarm(20);
    px = NULL;
    st = snell_image_read(test_data("hostile/truncated_rle.hdr"), &w, &h, &px);
    CHECK(st == SNELL_E_PARSE && px == NULL && strstr(snell_last_error(NULL), "truncated"),
          "truncated RLE HDR: %s: %s", snell_status_str(st), snell_last_error(NULL));
    snell_image_free(px);
    alarm(0);
}

int main(int argc, char **argv)
{
    signal(SIGALRM, on_alarm);
    if (argc > 1 && strcmp(argv[1], "ctx") == 0) {
        test_budget_ctx();
        return test_finish();
    }
    test_uris();
    test_huge_coordinates();
    test_coincident();
    test_budget_default();
    test_messages();
    return test_finish();
}
