/* SPDX-License-Identifier: MIT */
/* test_hostile_inputs5.c — issue 49, hostile input, fifth round: one function
 * per finding, each failing on the code before its fix. Without arguments:
 * the CPU-only cases (ctx NULL). With "ctx": those that need a context (label
 * gl). Inputs are made here at run time. */
#define _POSIX_C_SOURCE 200809L /* mkfifo, alarm */
#include "test_util.h"

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* A loader that blocks must fail the test, not hang ctest. */
static void on_alarm(int sig)
{
    static const char msg[] = "FAIL: a call did not return within the alarm (blocked in open()?)\n";
    (void)sig;
    if (write(2, msg, sizeof msg - 1) < 0) _exit(1);
    _exit(1);
}

static int has(const char *msg, const char *needle) { return strstr(msg, needle) != NULL; }

/* ------------------------- a double destroy under SNELL_DEBUG_HANDLES=1 */
/* In a child whose stderr goes to a file: 0 = a mesh destroyed twice, 1 = a
 * context destroyed twice, 2 = a destroyed mesh drawn. Returns the child's
 * signal (77 + 1000 where it had no context) with its stderr in msg. */
static int handles_child(int what, char *msg, size_t n)
{
    const char *path = test_out("hostile5_handles.txt");
    pid_t pid;
    int status = 0;
    FILE *f;
    size_t got;
    fflush(stdout);
    fflush(stderr);
    if ((pid = fork()) == 0) {
        int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        snell_shape_desc sd;
        snell_mesh *m = NULL;
        snell_ctx *ctx = NULL;
        if (fd < 0 || dup2(fd, 2) < 0) _exit(2);
        setenv("SNELL_DEBUG_HANDLES", "1", 1); /* before the library reads it: nothing ran in this process */
        memset(&sd, 0, sizeof sd);
        if (what == 1 || what == 2) {
            if (snell_ctx_create(NULL, &ctx) != SNELL_OK) _exit(77);
        }
        if (what == 1) {
            snell_ctx_destroy(ctx);
            snell_ctx_destroy(ctx);
            _exit(0);
        }
        if (snell_mesh_create_shape(ctx, &sd, &m) != SNELL_OK) _exit(3);
        snell_mesh_destroy(m);
        if (what == 0) snell_mesh_destroy(m);
        if (what == 2) {
            snell_renderer *r = NULL;
            snell_env *env = NULL;
            snell_env_desc ed;
            snell_renderer_desc rd;
            snell_frame_desc fd;
            snell_glass g;
            memset(&ed, 0, sizeof ed);
            memset(&rd, 0, sizeof rd);
            memset(&fd, 0, sizeof fd);
            memset(&g, 0, sizeof g);
            ed.face_size = 16;
            rd.width = rd.height = 16;
            if (snell_env_create(ctx, &ed, &env) != SNELL_OK || snell_renderer_create(ctx, &rd, &r) != SNELL_OK) _exit(4);
            g.mesh = m;
            fd.env = env;
            fd.glass = &g;
            fd.glass_count = 1;
            snell_render(r, &fd, NULL);
        }
        _exit(0);
    }
    waitpid(pid, &status, 0);
    msg[0] = '\0';
    if ((f = fopen(path, "r"))) {
        got = fread(msg, 1, n - 1, f);
        msg[got] = '\0';
        fclose(f);
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 77) return 1077;
    return WIFSIGNALED(status) ? WTERMSIG(status) : -WEXITSTATUS(status);
}

static void test_double_destroy(void)
{
    static const char *const what[] = {"snell_mesh_destroy", "snell_ctx_destroy", "snell_render: a glass or opaque mesh"};
    char msg[512];
    int i;
    for (i = 0; i < 3; i++) {
        int sig = handles_child(i, msg, sizeof msg);
        if (sig == 1077) {
            printf("SKIP %s: no context\n", what[i]);
            continue;
        }
        CHECK(sig == SIGABRT && has(msg, what[i]) && has(msg, "was already destroyed (SNELL_DEBUG_HANDLES)"),
              "%s twice under SNELL_DEBUG_HANDLES=1: signal %d, stderr: %s", what[i], sig, msg);
    }
}

/* ---------------------------------------------- FIFOs as .3ds and .jobj */
static void test_fifos(void)
{
    static const char *names[] = {"hostile5_fifo.3ds", "hostile5_fifo.jobj"};
    size_t i;
    for (i = 0; i < 2; i++) {
        char path[1024];
        snell_mesh *m = NULL;
        snell_status st;
        snprintf(path, sizeof path, "%s", test_out(names[i]));
        unlink(path);
        CHECK(mkfifo(path, 0644) == 0, "mkfifo %s", path);
        alarm(5);
        st = snell_mesh_load(NULL, path, &m);
        alarm(0);
        CHECK(st == SNELL_E_IO && !m && has(snell_last_error(NULL), "not a regular file"), "%s: %s: %s", names[i],
              snell_status_str(st), snell_last_error(NULL));
        unlink(path);
    }
}

/* ------------------------------------------ jobj: a byte-order mark, tabs */
static void test_jobj_text(void)
{
    static const char bom[] = "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\ni 0\ni 1\ni 2\n";
    static const char tabs[] = "v\t0 0 0\nv 1 0 0\nv 0 1 0\ni\t0\ni\t1 \ni 2\t\n";
    snell_mesh *m = NULL;
    snell_status st = snell_mesh_load_jobj_mem(NULL, bom, sizeof bom - 1, &m);
    CHECK(st == SNELL_OK && m && snell_mesh_triangle_count(m) == 1, "jobj with a BOM: %s: %s", snell_status_str(st),
          snell_last_error(NULL));
    snell_mesh_destroy(m);
    m = NULL;
    st = snell_mesh_load_jobj_mem(NULL, tabs, sizeof tabs - 1, &m);
    CHECK(st == SNELL_OK && m && snell_mesh_triangle_count(m) == 1, "jobj with tabs: %s: %s", snell_status_str(st),
          snell_last_error(NULL));
    snell_mesh_destroy(m);
}

/* ------------------------- glTF scene nodes that no frame could draw */
static void scene_scale(const char *scale, snell_status want, const char *needle)
{
    char json[2048];
    snell_scene_file *sc = NULL;
    snell_status st;
    /* one triangle of glass (KHR_materials_transmission) under a scaled node */
    int n = snprintf(json, sizeof json,
                     "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
                     "\"nodes\":[{\"mesh\":0,\"scale\":[%s,%s,%s]}],"
                     "\"materials\":[{\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1}}}],"
                     "\"extensionsUsed\":[\"KHR_materials_transmission\"],"
                     "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0}]}],"
                     "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
                     "\"min\":[0,0,0],\"max\":[1,1,0]}],"
                     "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"buffers\":[{\"byteLength\":36,\"uri\":"
                     "\"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}]}",
                     scale, scale, scale);
    st = snell_scene_load_gltf_mem(NULL, json, (size_t)n, &sc);
    CHECK(st == want && (st == SNELL_OK) == (sc != NULL), "node scale %s: %s: %s", scale, snell_status_str(st),
          snell_last_error(NULL));
    if (needle && st != SNELL_OK)
        CHECK(has(snell_last_error(NULL), needle), "node scale %s: message lacks \"%s\": %s", scale, needle,
              snell_last_error(NULL));
    snell_scene_file_destroy(sc);
}

static void test_gltf_scale(void)
{
    scene_scale("1", SNELL_OK, NULL);
    scene_scale("0", SNELL_E_PARSE, "node 0: its world transform is singular (determinant 0)");
    scene_scale("1e-40", SNELL_E_PARSE, "node 0: its world transform is singular");
    scene_scale("1e30", SNELL_E_PARSE, "node 0: its world transform is too large for float");
}

/* ------------- the analysis of a convex mesh far from unit size (subnormal) */
static void test_analysis_scale(void)
{
    static const float scales[] = {1.0f, 1e-20f, 1e-40f, 1e20f};
    static const uint32_t idx[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                     2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3};
    size_t i;
    for (i = 0; i < sizeof scales / sizeof scales[0]; i++) {
        float p[24], s = scales[i];
        snell_mesh_desc d;
        snell_mesh *m = NULL;
        snell_mesh_analysis a;
        snell_status st;
        int v;
        for (v = 0; v < 8; v++) { /* a cube */
            p[3 * v] = ((v & 1) ^ ((v >> 1) & 1)) ? s : -s;
            p[3 * v + 1] = (v & 2) ? s : -s;
            p[3 * v + 2] = (v & 4) ? s : -s;
        }
        memset(&d, 0, sizeof d);
        d.positions = p;
        d.indices = idx;
        d.vertex_count = 8;
        d.triangle_count = 12;
        CHECK_OK(snell_mesh_create(NULL, &d, &m));
        if (!m) continue;
        memset(&a, 0, sizeof a);
        st = snell_mesh_analyze(m, &a);
        CHECK(st == SNELL_OK && a.convex && a.inside && a.hidden_fraction == 0.0f &&
                  a.radius > 1.7f * s && a.radius < 1.8f * s && a.inner_radius > 0.99f * s,
              "cube of half-size %g: %s, convex %d, inside %d, hidden %g, radius %g, inner %g", s,
              snell_status_str(st), a.convex, a.inside, a.hidden_fraction, a.radius, a.inner_radius);
        snell_mesh_destroy(m);
    }
}

/* ----------------------------- a device profile's name in the message */
static void test_profile_name(void)
{
    size_t n = (size_t)1 << 20;
    char *name = (char *)malloc(n + 1);
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_status st;
    const char *msg;
    if (!name) return;
    memset(name, 'x', n);
    name[n] = '\0';
    memset(&cd, 0, sizeof cd);
    cd.device_profile = name;
    st = snell_ctx_create(&cd, &ctx);
    msg = snell_last_error(NULL);
    CHECK(st == SNELL_E_INVALID_ARG && has(msg, "xxx\xe2\x80\xa6\" (known: gles30-min"),
          "a 1 MiB profile name is cut with an ellipsis and the known names stay: %s: %.200s", snell_status_str(st), msg);
    snell_ctx_destroy(ctx);
    cd.device_profile = "rpi\nFAKE: injected line";
    st = snell_ctx_create(&cd, &ctx);
    msg = snell_last_error(NULL);
    CHECK(st == SNELL_E_INVALID_ARG && !strchr(msg, '\n') && has(msg, "rpi?FAKE"), "a newline in a profile name: %s: %s",
          snell_status_str(st), msg);
    snell_ctx_destroy(ctx);
    free(name);
}

/* ---------------------- a mesh's budget counts its analysis (item 2) */
static void put16(unsigned char *p, unsigned v) { p[0] = (unsigned char)v, p[1] = (unsigned char)(v >> 8); }
static void put32(unsigned char *p, uint32_t v) { put16(p, v & 0xffff), put16(p + 2, v >> 16); }

/* A .3ds of one object: a strip of nv vertices, nv - 2 triangles. Its size in *n. */
static unsigned char *strip_3ds(unsigned nv, size_t *n)
{
    unsigned nf = nv - 2, i;
    size_t vbytes = 6 + 2 + 12 * (size_t)nv, fbytes = 6 + 2 + 8 * (size_t)nf, tri = 6 + vbytes + fbytes;
    size_t obj = 6 + 2 + tri, ed = 6 + obj, total = 6 + ed;
    unsigned char *d = (unsigned char *)calloc(total, 1), *p = d;
    if (!d) return NULL;
    put16(p, 0x4D4D), put32(p + 2, (uint32_t)total), p += 6;
    put16(p, 0x3D3D), put32(p + 2, (uint32_t)ed), p += 6;
    put16(p, 0x4000), put32(p + 2, (uint32_t)obj), p += 6;
    p[0] = 'o', p += 2;
    put16(p, 0x4100), put32(p + 2, (uint32_t)tri), p += 6;
    put16(p, 0x4110), put32(p + 2, (uint32_t)vbytes), put16(p + 6, nv), p += 8;
    for (i = 0; i < nv; i++, p += 12) {
        float xyz[3] = {(float)(i / 2), (float)(i % 2), (float)(i % 3) * 0.1f};
        memcpy(p, xyz, 12);
    }
    put16(p, 0x4120), put32(p + 2, (uint32_t)fbytes), put16(p + 6, nf), p += 8;
    for (i = 0; i < nf; i++, p += 8) put16(p, i), put16(p + 2, i + 1), put16(p + 4, i + 2);
    *n = total;
    return d;
}

static void test_mesh_budget(snell_ctx *ctx)
{
    size_t n;
    unsigned char *big, *small;
    snell_mesh *m = NULL;
    snell_status st;
    /* 20,000 triangles: 0.5 MB of arrays, but over 7 MB with the analysis of the first frame */
    big = strip_3ds(20002, &n);
    st = big ? snell_mesh_load_3ds_mem(ctx, big, n, &m) : SNELL_E_NOMEM;
    CHECK(st == SNELL_E_LIMIT && !m && has(snell_last_error(ctx), "with their analysis"),
          "20,000 triangles of .3ds in 4 MiB: %s: %s", snell_status_str(st), snell_last_error(ctx));
    snell_mesh_destroy(m);
    m = NULL;
    small = strip_3ds(1002, &n);
    st = small ? snell_mesh_load_3ds_mem(ctx, small, n, &m) : SNELL_E_NOMEM;
    CHECK(st == SNELL_OK && m, "1,000 triangles of .3ds in 4 MiB: %s: %s", snell_status_str(st), snell_last_error(ctx));
    snell_mesh_destroy(m);
    free(big);
    free(small);
}

/* ------------------------------- GL cases: a context with a device profile */
static void test_ctx_cases(void)
{
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_status st;
    memset(&cd, 0, sizeof cd);
    cd.device_profile = "powervr-rogue"; /* textures and renderbuffers of 2048 */
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK) {
        printf("SKIP: no context (%s)\n", snell_last_error(NULL));
        return;
    }
    /* over the profile's limit is SNELL_E_UNSUPPORTED, as the header says; over 16384 SNELL_E_LIMIT */
    memset(&rd, 0, sizeof rd);
    rd.width = 4096;
    rd.height = 16;
    st = snell_renderer_create(ctx, &rd, &r);
    CHECK(st == SNELL_E_UNSUPPORTED && has(snell_last_error(ctx), "render size 4096: over the texture_size 2048") &&
              has(snell_last_error(ctx), "powervr-rogue"),
          "4096 wide on powervr-rogue: %s: %s", snell_status_str(st), snell_last_error(ctx));
    snell_renderer_destroy(r);
    r = NULL;
    rd.width = 1024;
    rd.ssaa = 4;
    st = snell_renderer_create(ctx, &rd, &r);
    CHECK(st == SNELL_E_UNSUPPORTED, "1024 x ssaa 4 on powervr-rogue: %s: %s", snell_status_str(st),
          snell_last_error(ctx));
    snell_renderer_destroy(r);
    r = NULL;
    rd.width = 20000;
    rd.ssaa = 0;
    st = snell_renderer_create(ctx, &rd, &r);
    CHECK(st == SNELL_E_LIMIT, "20000 wide: %s: %s", snell_status_str(st), snell_last_error(ctx));
    snell_renderer_destroy(r);
    snell_ctx_destroy(ctx);
    memset(&cd, 0, sizeof cd);
    cd.memory_budget = (size_t)4 << 20;
    if (snell_ctx_create(&cd, &ctx) == SNELL_OK) test_mesh_budget(ctx);
    snell_ctx_destroy(ctx);
}

int main(int argc, char **argv)
{
    signal(SIGALRM, on_alarm);
    if (argc > 1 && strcmp(argv[1], "ctx") == 0) {
        test_ctx_cases();
        return test_finish();
    }
    test_double_destroy(); /* first: its children read SNELL_DEBUG_HANDLES before anything else does */
    test_fifos();
    test_jobj_text();
    test_gltf_scale();
    test_analysis_scale();
    test_profile_name();
    return test_finish();
}
