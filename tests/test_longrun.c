/* SPDX-License-Identifier: MIT */
/* test_longrun — the long run of issue 14: 2,000 frames that change every
 * per-frame setting (camera, materials, methods with AUTO, cubemap
 * parameters, moving opaque objects, 0..8 glass objects, dynamic environment
 * size, environment, background, output kinds through four renderers), then
 * 500 create/destroy cycles of environment, mesh and renderer in one context
 * and 500 of a whole context with them (destroyed in varying order).
 * After a warm-up, three things must stay flat:
 *  - snell's own memory, exactly: live blocks and bytes of a counting allocator;
 *  - the GL objects alive, exactly (gl_count.h). Every setting is a function
 *    of the frame number modulo 500, so the caches (LRU program and
 *    prepared-resource caches) cycle with it and checkpoints 500 frames apart
 *    see the same objects;
 *  - RSS (/proc/self/statm), within RSS_SLACK_KB: it includes llvmpipe's and
 *    the C library's memory, which moves by about 1 MB from checkpoint to
 *    checkpoint here (bounded over 8,000 frames; up to +3.5 MB in the first
 *    2,000 with a cold shader cache).
 * Labelled "longrun" only: sanitizers' quarantine and shadow memory are not
 * flat by design. LONGRUN_FRAMES=N runs more frames, LONGRUN_TRACE=1 prints
 * the numbers every 50. */
#define _POSIX_C_SOURCE 200809L
#include "test_util.h"
#include "gl_count.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define FRAMES 2000
static int g_frames = FRAMES; /* LONGRUN_FRAMES overrides, for longer looks */
#define PERIOD 500
#define CYCLES 500
#define SIZE 32
#define N_RENDERERS 4
#define N_MESHES 4

/* RSS growth allowed after the warm-up (see above). A per-frame leak of a
 * frame's scratch (a 32x32 readback is 4-16 KB) would exceed it within 1,500
 * frames; smaller leaks of snell's own memory fail the exact count. */
#define RSS_SLACK_KB 8192

/* snell's own memory, exactly: live blocks and bytes of the context's allocator. */
static long g_blocks, g_bytes;
static void *count_alloc(size_t n, void *u)
{
    size_t *p = (size_t *)malloc(n + sizeof(size_t) * 2);
    (void)u;
    if (!p) return NULL;
    p[0] = n;
    g_blocks++;
    g_bytes += (long)n;
    return p + 2;
}
static void count_free(void *q, void *u)
{
    size_t *p = (size_t *)q;
    (void)u;
    if (!q) return;
    p -= 2;
    g_blocks--;
    g_bytes -= (long)p[0];
    free(p);
}
static void *count_realloc(void *q, size_t n, void *u)
{
    size_t *p = (size_t *)q, old;
    if (!q) return count_alloc(n, u);
    p -= 2;
    old = p[0];
    p = (size_t *)realloc(p, n + sizeof(size_t) * 2);
    if (!p) return NULL;
    p[0] = n;
    g_bytes += (long)n - (long)old;
    return p + 2;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static long rss_kb(void)
{
    long pages = 0, resident = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (!f) return -1;
    if (fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = -1;
    fclose(f);
    return resident < 0 ? -1 : resident * (sysconf(_SC_PAGESIZE) / 1024);
}

static snell_mesh *shape(snell_ctx *ctx, snell_shape s, int segments)
{
    snell_mesh *m = NULL;
    snell_shape_desc sd;
    memset(&sd, 0, sizeof sd);
    sd.shape = s;
    sd.segments = segments;
    sd.rings = segments / 2;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &m));
    return m;
}

static snell_env *env_of(snell_ctx *ctx, int size)
{
    snell_env *e = NULL;
    snell_env_desc ed;
    memset(&ed, 0, sizeof ed);
    ed.face_size = size;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &e));
    return e;
}

static void translate_scale(float m[16], float x, float y, float z, float s)
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = s;
    m[12] = x;
    m[13] = y;
    m[14] = z;
    m[15] = 1.0f;
}

typedef struct world {
    snell_mesh *mesh[N_MESHES], *cpu_mesh;
    snell_env *env[2];
    snell_renderer *r[N_RENDERERS];
    snell_glass glass[8];
    snell_opaque opaque[3];
    float gm[8][16], om[3][16];
    float *dirs;
    uint8_t *rgba;
} world;

/* Frame u (0..PERIOD-1) of the schedule: every setting moves with u. */
static int frame_settings(world *w, int u, snell_frame_desc *fd)
{
    static const snell_method methods[5] = {SNELL_METHOD_AUTO, SNELL_METHOD_SINGLE, SNELL_METHOD_CUBEMAP,
                                            SNELL_METHOD_AUTO, SNELL_METHOD_CUBEMAP};
    const float t = (float)u * (float)(2.0 * 3.14159265358979 / PERIOD);
    int j, n = u % 10 > 8 ? 8 : u % 10, ri = u % N_RENDERERS;
    memset(fd, 0, sizeof *fd);
    memset(w->glass, 0, sizeof w->glass);
    memset(w->opaque, 0, sizeof w->opaque);
    for (j = 0; j < n; j++) {
        snell_glass *g = &w->glass[j];
        snell_glass_material *m = &g->material;
        int v = u + 3 * j;
        float a = t * 3.0f + (float)j * 0.785f;
        translate_scale(w->gm[j], 1.2f * cosf(a), 0.3f * sinf(2.0f * a), 1.2f * sinf(a),
                        0.25f + 0.05f * (float)(v % 4));
        g->mesh = w->mesh[v % N_MESHES];
        g->model = w->gm[j];
        m->method = methods[v % 5];
        m->ior = 1.1f + 0.1f * (float)(v % 10);
        if (v % 4 == 1) {
            m->attenuation_distance = 0.5f + 0.25f * (float)(v % 5);
            m->attenuation_color[0] = 0.9f;
            m->attenuation_color[1] = 0.5f + 0.1f * (float)(v % 4);
            m->attenuation_color[2] = 0.3f;
        }
        if (v % 20 == 7) m->thickness = 0.05f;
        if (v % 25 == 3) m->tint[0] = 0.8f, m->tint[1] = 0.9f, m->tint[2] = 1.0f;
        if (v % 50 == 11) m->ior = 1.0f; /* passthrough */
        /* cubemap parameters: 8 search programs at most (the cache's size) */
        m->cubemap.iterations = (v / 2) % 2 ? 4 : 6;
        m->cubemap.linear_steps = (v / 4) % 2 ? 2 : 0;
        m->cubemap.max_interfaces = 1 + (v / 5) % 4;
        m->cubemap.face_size = (v / 10) % 2 ? 32 : 16;
        m->cubemap.encoding = (snell_ndcube_encoding)((v / 20) % 3);
    }
    for (j = 0; j < u % 4; j++) {
        float a = -t * 5.0f + (float)j * 2.1f;
        translate_scale(w->om[j], 2.0f * cosf(a), -0.6f + 0.2f * (float)j, 2.0f * sinf(a), 0.3f);
        w->opaque[j].mesh = j == 2 ? w->cpu_mesh : w->mesh[(u + j) % N_MESHES];
        w->opaque[j].model = w->om[j];
        w->opaque[j].color[0] = 0.2f + 0.2f * (float)j;
        w->opaque[j].color[1] = 0.5f;
        w->opaque[j].color[2] = 0.8f - 0.2f * (float)j;
    }
    fd->env = w->env[(u / 2) % 2];
    fd->glass = w->glass;
    fd->glass_count = n;
    fd->opaque = u % 4 ? w->opaque : NULL;
    fd->opaque_count = u % 4;
    fd->draw_background = u % 5 == 0 ? -1 : 0;
    fd->dynamic_env_size = (u / 3) % 3 == 0 ? 0 : (u / 3) % 3 == 1 ? 16 : 32;
    fd->camera.azimuth = t * 2.0f;
    fd->camera.elevation = 0.2f + 0.4f * sinf(t * 5.0f);
    fd->camera.distance = 4.0f + sinf(t * 7.0f);
    fd->camera.fov_y = 0.7f + 0.2f * cosf(t * 3.0f);
    fd->camera.target[1] = 0.1f * sinf(t);
    if (u % 5 == 2) {
        fd->camera.z_near = 0.1f;
        fd->camera.z_far = 50.0f;
    }
    return ri;
}

static void run_frame(world *w, snell_ctx *ctx, int i)
{
    snell_frame_desc fd;
    snell_frame_stats fs;
    int ri = frame_settings(w, i % PERIOD, &fd);
    snell_status st = snell_render(w->r[ri], &fd, &fs);
    CHECK(st == SNELL_OK, "frame %d (renderer %d): %s %s", i, ri, snell_status_str(st), snell_last_error(ctx));
    if (st == SNELL_OK && i % 10 == 0) {
        st = ri == 1 || ri == 2 ? snell_renderer_read_exit_dirs(w->r[ri], w->dirs)
                                : snell_renderer_read_rgba(w->r[ri], w->rgba);
        CHECK(st == SNELL_OK, "read %d: %s", i, snell_last_error(ctx));
    }
}

static void frames(snell_ctx *ctx, world *w)
{
    static const snell_output outputs[N_RENDERERS] = {SNELL_OUTPUT_COLOR, SNELL_OUTPUT_EXIT_DIRECTION,
                                                      SNELL_OUTPUT_EXIT_DIRECTION_PACKED, SNELL_OUTPUT_COLOR};
    static const snell_shading shadings[N_RENDERERS] = {SNELL_SHADING_AUTO, SNELL_SHADING_FORWARD,
                                                        SNELL_SHADING_SCREEN, SNELL_SHADING_FORWARD};
    gl_counts base, c;
    long rss0 = 0, rss, rss_max = 0, blocks0 = 0, bytes0 = 0;
    double t0 = now_s();
    int i, k;
    for (k = 0; k < N_RENDERERS; k++) {
        snell_renderer_desc rd;
        memset(&rd, 0, sizeof rd);
        rd.width = SIZE;
        rd.height = SIZE - 8 * (k & 1); /* non-square too */
        rd.output = outputs[k];
        rd.shading = shadings[k];
        CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &w->r[k]));
        if (!w->r[k]) return;
    }
    for (i = 0; i < g_frames; i++) {
        run_frame(w, ctx, i);
        if (test_failed > 20) return;
        if (getenv("LONGRUN_TRACE") && (i + 1) % 50 == 0)
            printf("  %d: RSS %ld KB, snell %ld blocks %ld bytes\n", i + 1, rss_kb(), g_blocks, g_bytes);
        if (i + 1 == PERIOD) {
            base = gl_count_objects();
            rss0 = rss_max = rss_kb();
            blocks0 = g_blocks;
            bytes0 = g_bytes;
            printf("frame %4d (warm-up done): RSS %ld KB, snell %ld blocks %ld bytes, %.1f s\n", i + 1, rss0,
                   blocks0, bytes0, now_s() - t0);
            gl_counts_print(stdout, "  GL", &base);
        } else if (i + 1 > PERIOD && (i + 1) % 100 == 0) {
            rss = rss_kb();
            if (rss > rss_max) rss_max = rss;
            CHECK(g_blocks == blocks0 && g_bytes == bytes0, "frame %d: snell holds %ld blocks, %ld bytes (%ld, %ld "
                  "after the warm-up)", i + 1, g_blocks, g_bytes, blocks0, bytes0);
            CHECK(rss - rss0 <= RSS_SLACK_KB, "frame %d: RSS grew by %ld KB since frame %d (slack %d KB)", i + 1,
                  rss - rss0, PERIOD, RSS_SLACK_KB);
            if ((i + 1) % PERIOD == 0) {
                c = gl_count_objects();
                printf("frame %4d: RSS %ld KB (%+ld), snell %ld blocks %ld bytes, %d GL objects, %.1f s\n", i + 1,
                       rss, rss - rss0, g_blocks, g_bytes, gl_counts_total(&c), now_s() - t0);
                if (!gl_counts_equal(&base, &c)) gl_counts_print(stdout, "  GL now", &c);
                CHECK(gl_counts_equal(&base, &c), "frame %d: %d GL objects, %d after the warm-up", i + 1,
                      gl_counts_total(&c), gl_counts_total(&base));
            }
        }
    }
    printf("frames %d..%d: RSS at most %+ld KB over the warm-up's\n", PERIOD, g_frames, rss_max - rss0);
    for (k = 0; k < N_RENDERERS; k++) snell_renderer_destroy(w->r[k]);
}

/* One cycle in ctx: environment, mesh, renderer, a frame, destroyed in an order that varies. */
static void cycle_objects(snell_ctx *ctx, int i)
{
    snell_env *env = env_of(ctx, 8 + 8 * (i % 2));
    snell_mesh *mesh = shape(ctx, (snell_shape)(i % 4), 8 + 4 * (i % 3)), *cpu = shape(NULL, SNELL_SHAPE_CUBE, 8);
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_glass g;
    snell_opaque op;
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = 16;
    rd.output = i % 3 == 2 ? SNELL_OUTPUT_EXIT_DIRECTION : SNELL_OUTPUT_COLOR;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    test_frame_one(&fd, &g, mesh, env);
    g.material.method = i % 2 ? SNELL_METHOD_SINGLE : SNELL_METHOD_CUBEMAP;
    g.material.cubemap.face_size = 16;
    memset(&op, 0, sizeof op);
    op.mesh = cpu;
    if (i % 4 == 1) {
        fd.opaque = &op;
        fd.opaque_count = 1;
    }
    if (r && env && mesh) CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    if (i % 2) {
        snell_renderer_destroy(r);
        snell_mesh_destroy(mesh);
        snell_mesh_destroy(cpu);
        snell_env_destroy(env);
    } else {
        snell_env_destroy(env);
        snell_mesh_destroy(cpu);
        snell_mesh_destroy(mesh);
        snell_renderer_destroy(r);
    }
}

/* One cycle of a whole context; every third destroys the context first. */
static void cycle_context(int i)
{
    snell_ctx *ctx = NULL;
    snell_ctx_desc cd;
    snell_env *env;
    snell_mesh *mesh;
    snell_renderer *r = NULL;
    snell_frame_desc fd;
    snell_glass g;
    memset(&cd, 0, sizeof cd);
    cd.allocator.alloc = count_alloc;
    cd.allocator.realloc = count_realloc;
    cd.allocator.free = count_free;
    CHECK_OK(snell_ctx_create(&cd, &ctx));
    if (!ctx) return;
    env = env_of(ctx, 8);
    mesh = shape(ctx, SNELL_SHAPE_SPHERE, 8);
    r = test_renderer(ctx, 8, 8);
    test_frame_one(&fd, &g, mesh, env);
    g.material.method = SNELL_METHOD_SINGLE;
    if (r && i % 5 == 0) CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    if (i % 3 == 0) snell_ctx_destroy(ctx);
    snell_renderer_destroy(r);
    snell_mesh_destroy(mesh);
    snell_env_destroy(env);
    if (i % 3 != 0) snell_ctx_destroy(ctx);
}

/* n cycles of fn; snell's memory must return to where it was after each,
 * RSS stay within the slack of its value after the first 100. */
static void cycles(const char *what, void (*fn)(snell_ctx *, int), snell_ctx *ctx)
{
    long blocks0 = g_blocks, bytes0 = g_bytes, rss0 = 0, rss, rss_max = 0;
    double t = now_s();
    int i, leaks = 0;
    for (i = 0; i < CYCLES && test_failed <= 20; i++) {
        fn(ctx, i);
        leaks += g_blocks != blocks0 || g_bytes != bytes0;
        rss = rss_kb();
        if (i + 1 == 100) rss0 = rss_max = rss;
        if (i + 1 > 100 && rss > rss_max) rss_max = rss;
    }
    rss = rss_kb();
    printf("%d %s cycles: RSS %ld KB, at most %+ld KB over cycle 100's; snell %ld blocks; %.1f s\n", CYCLES, what, rss,
           rss_max - rss0, g_blocks, now_s() - t);
    CHECK(leaks == 0, "%s cycles: %d of %d left snell memory behind (%ld blocks %ld bytes, %ld %ld before)", what,
          leaks, CYCLES, g_blocks, g_bytes, blocks0, bytes0);
    CHECK(rss_max - rss0 <= RSS_SLACK_KB, "%s cycles: RSS grew by %ld KB over cycles 100..%d", what, rss_max - rss0,
          CYCLES);
}

static void cycle_objects_fn(snell_ctx *ctx, int i) { cycle_objects(ctx, i); }
static void cycle_context_fn(snell_ctx *ctx, int i) { (void)ctx; cycle_context(i); }

int main(void)
{
    snell_ctx *ctx = NULL;
    snell_ctx_desc cd;
    world w;
    gl_counts before, after;
    double t0 = now_s(), t;
    int k;
    if (getenv("LONGRUN_FRAMES")) g_frames = atoi(getenv("LONGRUN_FRAMES")) / PERIOD * PERIOD;
    if (g_frames < 2 * PERIOD) g_frames = 2 * PERIOD;
    memset(&cd, 0, sizeof cd);
    cd.allocator.alloc = count_alloc;
    cd.allocator.realloc = count_realloc;
    cd.allocator.free = count_free;
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK) SKIP("no GL context: %s", snell_last_error(NULL));
    memset(&w, 0, sizeof w);
    for (k = 0; k < N_MESHES; k++) w.mesh[k] = shape(ctx, (snell_shape)k, 16);
    w.cpu_mesh = shape(NULL, SNELL_SHAPE_TORUS, 12);
    w.env[0] = env_of(ctx, 16);
    w.env[1] = env_of(ctx, 32);
    w.dirs = (float *)malloc((size_t)SIZE * SIZE * 3 * sizeof(float));
    w.rgba = (uint8_t *)malloc((size_t)SIZE * SIZE * 4);
    if (!w.dirs || !w.rgba) return 1;

    frames(ctx, &w);
    t = now_s();
    printf("%d frames: %.1f s\n", g_frames, t - t0);

    /* Objects made and destroyed in one context: the same GL objects alive after. */
    before = gl_count_objects();
    cycles("object", cycle_objects_fn, ctx);
    after = gl_count_objects();
    if (!gl_counts_equal(&before, &after)) {
        gl_counts_print(stdout, "  GL before", &before);
        gl_counts_print(stdout, "  GL after", &after);
    }
    CHECK(gl_counts_equal(&before, &after), "GL objects %d after the object cycles, %d before",
          gl_counts_total(&after), gl_counts_total(&before));
    /* Whole contexts (ctx stays alive, so the EGL display is not re-initialised each time). */
    cycles("context", cycle_context_fn, ctx);

    CHECK_OK(snell_ctx_make_current(ctx));
    for (k = 0; k < N_MESHES; k++) snell_mesh_destroy(w.mesh[k]);
    snell_mesh_destroy(w.cpu_mesh);
    snell_env_destroy(w.env[0]);
    snell_env_destroy(w.env[1]);
    snell_ctx_destroy(ctx);
    free(w.dirs);
    free(w.rgba);
    printf("total %.1f s\n", now_s() - t0);
    return test_finish();
}
