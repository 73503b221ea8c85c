/* test_alloc — every allocation the library makes goes through the context's
 * allocator and is returned: a counting allocator must read zero outstanding
 * blocks after a full create/render/destroy cycle, and an allocator that
 * fails at the N-th request must give SNELL_E_NOMEM (never a crash) and still
 * leave nothing behind. This checks snell's own memory exactly, independent
 * of the GL driver's (which LSan cannot attribute on llvmpipe). */
#include "test_util.h"

#include <stdlib.h>
#include <string.h>

typedef struct counter {
    long outstanding, total;
    long fail_at;  /* fail the request with this index; -1 = never */
} counter;

static void *c_alloc(size_t n, void *u)
{
    counter *c = (counter *)u;
    void *p;
    if (c->fail_at >= 0 && c->total == c->fail_at) { c->total++; return NULL; }
    c->total++;
    p = malloc(n);
    if (p) c->outstanding++;
    return p;
}
static void *c_realloc(void *p, size_t n, void *u)
{
    counter *c = (counter *)u;
    void *q;
    if (c->fail_at >= 0 && c->total == c->fail_at) { c->total++; return NULL; }
    c->total++;
    q = realloc(p, n);
    if (q && !p) c->outstanding++;
    return q;
}
static void c_free(void *p, void *u)
{
    counter *c = (counter *)u;
    if (p) c->outstanding--;
    free(p);
}

/* A context desc whose allocator is the counter c. */
static snell_ctx_desc counting_desc(counter *c)
{
    snell_ctx_desc cd;
    memset(&cd, 0, sizeof cd);
    cd.allocator.alloc = c_alloc;
    cd.allocator.realloc = c_realloc;
    cd.allocator.free = c_free;
    cd.allocator.user = c;
    return cd;
}

/* One full cycle; returns the first failing status (or SNELL_OK). */
static snell_status cycle(counter *c, int render)
{
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_mesh *mesh = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_shape_desc sd;
    snell_env_desc ed;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    static uint8_t px[32 * 32 * 4];
    static const char obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    snell_status st;
    cd = counting_desc(c);
    st = snell_ctx_create(&cd, &ctx);
    if (st != SNELL_OK) return st;
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_TORUS;
    sd.segments = 24;
    sd.rings = 12;
    memset(&ed, 0, sizeof ed);
    ed.face_size = 16;
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = 32;
    st = snell_mesh_create_shape(ctx, &sd, &mesh);
    if (st == SNELL_OK) {
        snell_mesh *m2 = NULL;
        st = snell_mesh_load_obj_mem(ctx, obj, sizeof obj - 1, &m2);
        snell_mesh_destroy(m2);
    }
    if (st == SNELL_OK) st = snell_env_create(ctx, &ed, &env);
    if (st == SNELL_OK && render) st = snell_renderer_create(ctx, &rd, &r);
    if (st == SNELL_OK && render) {
        memset(&fd, 0, sizeof fd);
        fd.mesh = mesh;
        fd.env = env;
        st = snell_render(r, &fd, NULL);
        if (st == SNELL_OK) st = snell_renderer_read_rgba(r, px);
    }
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
    snell_ctx_destroy(ctx);
    return st;
}

int main(void)
{
    counter c;
    long n, total, nomem = 0;
    snell_ctx *probe = test_ctx();
    if (!probe) SKIP("no GL context");
    snell_ctx_destroy(probe);

    memset(&c, 0, sizeof c);
    c.fail_at = -1;
    CHECK_OK(cycle(&c, 1));
    CHECK(c.outstanding == 0, "%ld blocks still allocated after a full cycle", c.outstanding);
    CHECK(c.total > 5, "the allocator must actually be used (%ld calls)", c.total);
    total = c.total;
    printf("full cycle: %ld allocations through the context allocator\n", total);

    /* Fail each allocation in turn. */
    for (n = 0; n < total; n++) {
        snell_status st;
        memset(&c, 0, sizeof c);
        c.fail_at = n;
        st = cycle(&c, 1);
        CHECK(st == SNELL_OK || st == SNELL_E_NOMEM, "failing allocation %ld gave %s: %s", n, snell_status_str(st),
              snell_last_error(NULL));
        nomem += st == SNELL_E_NOMEM;
        CHECK(c.outstanding == 0, "failing allocation %ld leaked %ld blocks", n, c.outstanding);
    }
    printf("%ld failure points checked, %ld reported SNELL_E_NOMEM\n", total, nomem);
    CHECK(nomem > 0, "at least one injected failure must surface as SNELL_E_NOMEM");

    /* A second frame allocates nothing (per-frame calls are allocation-free). */
    {
        snell_ctx_desc cd;
        snell_ctx *ctx = NULL;
        snell_mesh *mesh = NULL;
        snell_env *env = NULL;
        int i;
        snell_renderer *r = NULL;
        snell_frame_desc fd;
        snell_env_desc ed;
        snell_renderer_desc rd;
        long before;
        memset(&c, 0, sizeof c);
        c.fail_at = -1;
        cd = counting_desc(&c);
        memset(&ed, 0, sizeof ed);
        ed.face_size = 16;
        memset(&rd, 0, sizeof rd);
        rd.width = rd.height = 16;
        CHECK_OK(snell_ctx_create(&cd, &ctx));
        CHECK_OK(snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_SPHERE, 16, 8}, &mesh));
        CHECK_OK(snell_env_create(ctx, &ed, &env));
        CHECK_OK(snell_renderer_create(ctx, &rd, &r));
        memset(&fd, 0, sizeof fd);
        fd.mesh = mesh;
        fd.env = env;
        CHECK_OK(snell_render(r, &fd, NULL));
        before = c.total;
        CHECK_OK(snell_render(r, &fd, NULL));
        CHECK_OK(snell_render(r, &fd, NULL));
        CHECK(c.total == before, "frames after the first allocated %ld times", c.total - before);
        /* The cubemap method: after its first frame (analysis, bake), frames
         * allocate nothing; a new search setting builds its program once
         * (the step counts are compile-time constants of the shader), after
         * which switching between seen settings allocates nothing. */
        fd.glass.method = SNELL_METHOD_CUBEMAP;
        CHECK_OK(snell_render(r, &fd, NULL));
        before = c.total;
        CHECK_OK(snell_render(r, &fd, NULL));
        fd.glass.max_interfaces = 4;
        CHECK_OK(snell_render(r, &fd, NULL));
        CHECK(c.total == before, "cubemap frames after the first allocated %ld times", c.total - before);
        fd.glass.search_iterations = 5;
        fd.glass.linear_steps = 3;
        CHECK_OK(snell_render(r, &fd, NULL));
        CHECK(c.total > before, "a new search setting built no program");
        before = c.total;
        for (i = 0; i < 4; i++) {
            fd.glass.search_iterations = i & 1 ? 0 : 5;
            fd.glass.linear_steps = i & 1 ? 0 : 3;
            CHECK_OK(snell_render(r, &fd, NULL));
        }
        CHECK(c.total == before, "switching between built search settings allocated %ld times", c.total - before);
        /* More settings than the program cache holds: the least recently used
         * programs are replaced (and freed: the leak check below). */
        for (i = 1; i <= 12; i++) {
            fd.glass.search_iterations = i;
            CHECK_OK(snell_render(r, &fd, NULL));
        }
        snell_renderer_destroy(r);
        snell_env_destroy(env);
        snell_mesh_destroy(mesh);
        snell_ctx_destroy(ctx);
        CHECK(c.outstanding == 0, "leak");
    }
    return test_finish();
}
