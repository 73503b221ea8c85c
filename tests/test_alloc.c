/* SPDX-License-Identifier: MIT */
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
    snell_glass g, scene[4];
    snell_opaque ob;
    float moved[16] = {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0.8f, 0, 0, 1};
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
        test_frame_one(&fd, &g, mesh, env);
        st = snell_render(r, &fd, NULL);
        if (st == SNELL_OK) st = snell_renderer_read_rgba(r, px);
    }
    if (st == SNELL_OK && render) {
        /* A scene: the prepared-resource cache, a second kernel and the
         * dynamic environments (all allocated on first use) fail cleanly too. */
        memset(scene, 0, sizeof scene);
        memset(&ob, 0, sizeof ob);
        scene[0].mesh = scene[1].mesh = scene[2].mesh = scene[3].mesh = mesh;
        scene[1].model = moved;
        scene[1].material.method = SNELL_METHOD_CUBEMAP;
        scene[1].material.cubemap.face_size = 16;
        scene[2].material.thickness = 0.05f;
        scene[3].model = moved;
        scene[3].material.method = SNELL_METHOD_EXACT; /* its BVH: build, flatten, texture */
        ob.mesh = mesh;
        ob.model = moved;
        fd.glass = scene;
        fd.glass_count = 4;
        fd.opaque = &ob;
        fd.opaque_count = 1;
        st = snell_render(r, &fd, NULL);
    }
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
    snell_ctx_destroy(ctx);
    return st;
}

/* A scene of 8 glass objects (3 meshes; AUTO, explicit SINGLE and CUBEMAP,
 * a thin wall, absorption, two cubemap settings) and 4 opaque objects: after
 * the first frame (analyses, bakes, 8 dynamic environments) frames allocate
 * nothing, whether nothing moved (everything reused) or an opaque object and
 * a glass object move every frame (environments re-rendered in place). */
static void scene_frames(void)
{
    enum { NG = 8, NO = 4 };
    counter c;
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_mesh *mesh[3] = {NULL, NULL, NULL};
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_frame_desc fd;
    snell_frame_stats fs;
    snell_glass g[NG];
    snell_opaque ob[NO];
    float gm[NG][16], om[NO][16];
    snell_env_desc ed;
    snell_renderer_desc rd;
    const float sigma[3] = {0.4f, 0.2f, 0.1f};
    long before;
    int i, f, ok = 1;
    memset(&c, 0, sizeof c);
    c.fail_at = -1;
    cd = counting_desc(&c);
    memset(&ed, 0, sizeof ed);
    ed.face_size = 32;
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = 48;
    CHECK_OK(snell_ctx_create(&cd, &ctx));
    if (!ctx) return;
    CHECK_OK(snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_SPHERE, 16, 8}, &mesh[0]));
    CHECK_OK(snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_TORUS, 16, 8}, &mesh[1]));
    CHECK_OK(snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_CUBE, 0, 0}, &mesh[2]));
    CHECK_OK(snell_env_create(ctx, &ed, &env));
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!mesh[0] || !mesh[1] || !mesh[2] || !env || !r) goto out;
    memset(g, 0, sizeof g);
    memset(ob, 0, sizeof ob);
    memset(gm, 0, sizeof gm);
    memset(om, 0, sizeof om);
    for (i = 0; i < NG; i++) {
        /* a 4 x 2 grid of objects of radius 0.3 in front of the camera */
        gm[i][0] = gm[i][5] = gm[i][10] = 0.3f;
        gm[i][12] = -1.2f + 0.8f * (float)(i % 4);
        gm[i][13] = i < 4 ? 0.4f : -0.4f;
        gm[i][14] = -0.1f * (float)i;
        gm[i][15] = 1.0f;
        g[i].mesh = mesh[i % 3];
        g[i].model = gm[i];
    }
    g[1].material.method = SNELL_METHOD_SINGLE;
    g[2].material.method = SNELL_METHOD_CUBEMAP;
    g[3].material.thickness = 0.02f;
    snell_glass_set_absorption(&g[4].material, sigma);
    g[5].material.method = SNELL_METHOD_CUBEMAP;
    g[5].material.cubemap.face_size = 64;
    g[5].material.cubemap.encoding = SNELL_NDCUBE_OCT;
    g[6].material.ior = 1.33f;
    g[7].material.method = SNELL_METHOD_CUBEMAP;
    g[7].material.cubemap.max_interfaces = 1; /* no search */
    for (i = 0; i < NO; i++) {
        om[i][0] = om[i][5] = om[i][10] = 0.25f;
        om[i][12] = -1.5f + 1.0f * (float)i;
        om[i][13] = -1.2f;
        om[i][14] = -1.5f;
        om[i][15] = 1.0f;
        ob[i].mesh = mesh[2 - i % 2];
        ob[i].model = om[i];
        ob[i].color[i % 3] = 0.9f;
    }
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass = g;
    fd.glass_count = NG;
    fd.opaque = ob;
    fd.opaque_count = NO;
    fd.camera.distance = 4.0f;
    fd.scene_layers = -1; /* first the dynamic environments; the scene layers below */
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    for (i = 0; i < NG; i++) ok &= fs.glass[i].draw_order >= 0 && fs.glass[i].env_updated == 1;
    CHECK(ok && fs.opaque_drawn == NO, "every object drawn, every dynamic environment rendered");
    before = c.total;
    for (f = 0; f < 3; f++) CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(c.total == before, "%d glass + %d opaque: frames after the first allocated %ld times", NG, NO,
          c.total - before);
    for (i = 0, ok = 1; i < NG; i++) ok &= (fs.glass[i].skipped & SNELL_SKIP_ENV_UPDATE) && !fs.glass[i].prepared;
    CHECK(ok, "nothing moved: environments and prepared resources reused");
    before = c.total;
    for (f = 0; f < 4; f++) {
        om[f % NO][13] += 0.05f; /* an opaque object moves: every environment is re-rendered */
        gm[f % NG][12] += 0.01f; /* and a glass object */
        CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
        for (i = 0, ok = 1; i < NG; i++) ok &= fs.glass[i].env_updated == 1;
        CHECK(ok, "frame %d: a moved opaque object re-renders every environment", f);
    }
    CHECK(c.total == before, "moving objects: frames allocated %ld times", c.total - before);
    /* The default for such a frame: the scene layers instead of dynamic
     * environments (render/layers.c); after the frame that makes them,
     * frames allocate nothing either. */
    fd.scene_layers = 0;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    CHECK(fs.scene_layer_passes >= 2 && (fs.glass[0].skipped & SNELL_SKIP_DYNAMIC_ENV) && fs.glass[0].env_updated == 0,
          "scene layers: %d peels, skipped 0x%x (%s)", fs.scene_layer_passes, fs.glass[0].skipped,
          fs.scene_layers_reason);
    before = c.total;
    for (f = 0; f < 4; f++) {
        om[f % NO][13] += 0.05f;
        gm[f % NG][12] += 0.01f;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, &fs));
    }
    CHECK(c.total == before, "scene layers, moving objects: frames allocated %ld times", c.total - before);
out:
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    for (i = 0; i < 3; i++) snell_mesh_destroy(mesh[i]);
    snell_ctx_destroy(ctx);
    CHECK(c.outstanding == 0, "scene: %ld blocks leaked", c.outstanding);
}

/* snell_mesh_simplify (level of detail): its arrays and the new mesh come from
 * the context's allocator, all returned; failing each request in turn gives
 * SNELL_E_NOMEM (or success) and leaks nothing. Without meshoptimizer it is
 * SNELL_E_UNSUPPORTED and allocates nothing. */
static snell_status simplify_cycle(counter *c)
{
    snell_ctx_desc cd = counting_desc(c);
    snell_ctx *ctx = NULL;
    snell_mesh *src = NULL, *lod = NULL;
    snell_simplify_desc sd;
    snell_status st = snell_ctx_create(&cd, &ctx);
    if (st != SNELL_OK) return st;
    memset(&sd, 0, sizeof sd);
    sd.target_ratio = 0.25f;
    st = snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_TORUS, 48, 24}, &src);
    if (st == SNELL_OK) st = snell_mesh_simplify(ctx, src, &sd, &lod, NULL);
    if (st != SNELL_OK && lod) st = SNELL_E_INVALID_ARG; /* no mesh on failure */
    snell_mesh_destroy(lod);
    snell_mesh_destroy(src);
    snell_ctx_destroy(ctx);
    return st;
}

static void simplify_alloc(void)
{
    counter c;
    long total, n, nomem = 0;
    snell_status st;
    memset(&c, 0, sizeof c);
    c.fail_at = -1;
    st = simplify_cycle(&c);
    CHECK(st == SNELL_OK || st == SNELL_E_UNSUPPORTED, "simplify: %s", snell_status_str(st));
    CHECK(c.outstanding == 0, "simplify: %ld blocks leaked", c.outstanding);
    if (st != SNELL_OK) return;
    total = c.total;
    for (n = 0; n < total; n++) {
        memset(&c, 0, sizeof c);
        c.fail_at = n;
        st = simplify_cycle(&c);
        CHECK(st == SNELL_OK || st == SNELL_E_NOMEM, "simplify, failing allocation %ld: %s", n, snell_status_str(st));
        nomem += st == SNELL_E_NOMEM;
        CHECK(c.outstanding == 0, "simplify, failing allocation %ld leaked %ld blocks", n, c.outstanding);
    }
    printf("simplify: %ld allocations, each failed in turn (%ld gave SNELL_E_NOMEM)\n", total, nomem);
    CHECK(nomem > 0, "simplify: no injected failure surfaced");
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
        snell_glass g;
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
        test_frame_one(&fd, &g, mesh, env);
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        before = c.total;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        CHECK(c.total == before, "frames after the first allocated %ld times", c.total - before);
        /* exact: after its first frame (BVH build, program), frames allocate nothing */
        g.material.method = SNELL_METHOD_EXACT;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        before = c.total;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        CHECK(c.total == before, "exact frames after the first allocated %ld times", c.total - before);
        /* The cubemap method: after its first frame (analysis, bake), frames
         * allocate nothing; a new search setting builds its program once
         * (the step counts are compile-time constants of the shader), after
         * which switching between seen settings allocates nothing. */
        g.material.method = SNELL_METHOD_CUBEMAP;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        before = c.total;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        g.material.cubemap.max_interfaces = 4;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        CHECK(c.total == before, "cubemap frames after the first allocated %ld times", c.total - before);
        g.material.cubemap.iterations = 5;
        g.material.cubemap.linear_steps = 3;
        CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        CHECK(c.total > before, "a new search setting built no program");
        before = c.total;
        for (i = 0; i < 4; i++) {
            g.material.cubemap.iterations = i & 1 ? 0 : 5;
            g.material.cubemap.linear_steps = i & 1 ? 0 : 3;
            CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        }
        CHECK(c.total == before, "switching between built search settings allocated %ld times", c.total - before);
        /* More settings than the program cache holds: the least recently used
         * programs are replaced (and freed: the leak check below). */
        for (i = 1; i <= 12; i++) {
            g.material.cubemap.iterations = i;
            CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
        }
        snell_renderer_destroy(r);
        snell_env_destroy(env);
        snell_mesh_destroy(mesh);
        snell_ctx_destroy(ctx);
        CHECK(c.outstanding == 0, "leak");
    }
    scene_frames();
    simplify_alloc();
    return test_finish();
}
