/* SPDX-License-Identifier: MIT */
/* test_refine — progressive refinement (snell_renderer_desc.refine): off,
 * no stage and no samples; on, a method without random
 * branches first draws the plain frame; exact with its FULL-model terms nears
 * FULL (4 x 4 rays) as frames are added; the same frames give the same bytes;
 * each kind of change restarts the mean; a complete mean stays; bad settings
 * are refused; frames after the second allocate nothing. Without
 * GL_EXT_color_buffer_float (Mesa's override) frames are drawn unrefined and
 * the reason says why. */
#include "test_util.h"
#include "core/gl.h"
#include "snell/snell_ref.h"

#include <stdlib.h>
#include <string.h>

#define W 48
#define H 40
#define N ((size_t)W * H)

static snell_renderer *make(snell_ctx *ctx, int refine)
{
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.shading = test_shading();
    rd.refine = refine;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    return r;
}

/* One frame of r into px; its stats in *s. */
static void frame(snell_ctx *ctx, snell_renderer *r, const snell_frame_desc *fd, uint8_t *px, snell_frame_stats *s)
{
    CHECK_OK_CTX(ctx, snell_render(r, fd, s));
    CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, px));
}

static void refused(snell_ctx *ctx, snell_renderer_desc rd, const char *what)
{
    snell_renderer *r = NULL;
    snell_status st = snell_renderer_create(ctx, &rd, &r);
    CHECK(st == SNELL_E_INVALID_ARG && !r && strstr(snell_last_error(ctx), "refine"), "%s is refused (%s)", what,
          snell_last_error(ctx));
    snell_renderer_destroy(r);
}

/* Off: no stage, no samples, no reason (the default image is checked
 * byte for byte against the reference image outside this test). */
static void off(snell_ctx *ctx, const snell_frame_desc *fd)
{
    snell_renderer *a = make(ctx, 0);
    uint8_t *pa = malloc(4 * N);
    snell_frame_stats sa;
    int k;
    if (!a) goto done;
    for (k = 0; k < 2; k++) {
        frame(ctx, a, fd, pa, &sa);
        CHECK(sa.refine_samples == 0 && !sa.refine_reason[0] && !strstr(sa.stages, "refine"),
              "refine 0: %d samples (%s), stages %s", sa.refine_samples, sa.refine_reason, sa.stages);
    }
done:
    snell_renderer_destroy(a);
    free(pa);
}

/* Without a float target: drawn as unrefined, the reason naming the extension. */
static void no_float(snell_ctx *ctx, const snell_frame_desc *fd)
{
    snell_renderer *a = make(ctx, 8), *b = make(ctx, 0);
    uint8_t *pa = malloc(4 * N), *pb = malloc(4 * N);
    snell_frame_stats s;
    int k;
    if (!a || !b) goto done;
    for (k = 0; k < 3; k++) {
        frame(ctx, a, fd, pa, &s);
        frame(ctx, b, fd, pb, NULL);
        CHECK(memcmp(pa, pb, 4 * N) == 0 && s.refine_samples == 0 &&
                  strstr(s.refine_reason, "GL_EXT_color_buffer_float"),
              "without a float target: frame %d %s the plain one, %d samples (%s)", k,
              memcmp(pa, pb, 4 * N) ? "differs from" : "is", s.refine_samples, s.refine_reason);
    }
    printf("no float target: %s\n", s.refine_reason);
done:
    snell_renderer_destroy(a);
    snell_renderer_destroy(b);
    free(pa);
    free(pb);
}

/* PSNR of px against the reference rgb over the glass pixels (hit). */
static double glass_psnr(const uint8_t *px, const uint8_t *ref, const uint8_t *hit)
{
    int count = 0;
    return test_psnr_mask(px, ref, hit, (int)N, &count);
}

/* Exact with its terms nears FULL: PSNR after 1, 4, 16 and 48 frames. */
static void converges(snell_ctx *ctx, snell_frame_desc fd, snell_glass *g)
{
    snell_ref *ref = NULL;
    snell_ref_params p;
    float *rgb = malloc(3 * N * sizeof(float));
    uint8_t *ref8 = malloc(4 * N), *hit = malloc(N), *px = malloc(4 * N), *plain = malloc(4 * N);
    snell_renderer *r = NULL, *r0 = NULL;
    snell_frame_stats s;
    static const int at[] = {1, 4, 16, 48};
    double db[4], db_plain;
    int n, k = 0;
    g->material.method = SNELL_METHOD_EXACT;
    g->material.exact.fresnel = SNELL_FRESNEL_EXACT;
    g->material.exact.inner_fresnel = SNELL_INNER_FRESNEL_ON;
    g->material.exact.reentry = SNELL_EXACT_REENTRY_ON;
    CHECK_OK_CTX(ctx, test_ref_create(ctx, &fd, &ref));
    if (!ref) goto done;
    test_ref_params(&fd, W, H, 10, &p);
    p.mode = SNELL_REF_FULL;
    p.samples = 4;
    CHECK_OK(test_ref_render(ref, &p, rgb, NULL, hit));
    snell_ref_rgb_to_rgba8(rgb, W, H, ref8);
    r = make(ctx, 64);
    r0 = make(ctx, 0);
    if (!r || !r0) goto done;
    frame(ctx, r0, &fd, plain, NULL);
    db_plain = glass_psnr(plain, ref8, hit);
    for (n = 1; n <= 48; n++) {
        frame(ctx, r, &fd, px, &s);
        if (n != at[k]) continue;
        CHECK(s.refine_samples == n, "frame %d: %d samples", n, s.refine_samples);
        db[k++] = glass_psnr(px, ref8, hit);
    }
    printf("exact + terms against FULL (4x4 rays), glass PSNR: unrefined %.2f dB; refined %.2f, %.2f, %.2f, %.2f dB "
           "after 1, 4, 16, 48 frames\n", db_plain, db[0], db[1], db[2], db[3]);
    CHECK(db[1] > db[0] + 1.0 && db[2] > db[1] && db[3] > db[2] - 0.1 && db[3] > db_plain + 2.0,
          "the error against FULL does not fall with frames");
done:
    snell_renderer_destroy(r);
    snell_renderer_destroy(r0);
    snell_ref_destroy(ref);
    free(rgb);
    free(ref8);
    free(hit);
    free(px);
    free(plain);
}

/* The same frames, the same bytes; the first refined frame of cubemap (no
 * random branch, offset 0) is the plain frame. */
static void deterministic(snell_ctx *ctx, const snell_frame_desc *fd, const snell_frame_desc *exact_fd)
{
    snell_renderer *a = make(ctx, 16), *b = make(ctx, 16), *c = make(ctx, 0);
    uint8_t *pa = malloc(4 * N), *pb = malloc(4 * N);
    int k;
    if (!a || !b || !c) goto done;
    frame(ctx, a, fd, pa, NULL);
    frame(ctx, c, fd, pb, NULL);
    CHECK(memcmp(pa, pb, 4 * N) == 0, "the first refined cubemap frame differs from the plain frame");
    /* exact with inner_fresnel: its first sample follows each exit one way
     * at random instead of splitting it (the same rays otherwise) */
    {
        long differ = 0;
        size_t i;
        frame(ctx, b, exact_fd, pa, NULL);
        frame(ctx, c, exact_fd, pb, NULL);
        for (i = 0; i < 4 * N; i++) differ += pa[i] != pb[i];
        printf("exact + inner_fresnel: the first sample differs from the split frame in %ld channels\n", differ);
        CHECK(differ > 0, "the first sample of exact + inner_fresnel is the split frame: no random branch");
        snell_renderer_destroy(b);
        b = make(ctx, 16);
        if (!b) goto done;
    }
    frame(ctx, b, fd, pb, NULL);
    for (k = 0; k < 5; k++) {
        frame(ctx, a, exact_fd, pa, NULL);
        frame(ctx, b, exact_fd, pb, NULL);
        CHECK(memcmp(pa, pb, 4 * N) == 0, "two renderers' refined frame %d differ", k);
    }
done:
    snell_renderer_destroy(a);
    snell_renderer_destroy(b);
    snell_renderer_destroy(c);
    free(pa);
    free(pb);
}

/* Three frames of fd, then one of changed: the mean restarts (1 sample, the
 * cause named), and goes on from there (2). */
static void restart(snell_ctx *ctx, const snell_frame_desc *fd, const snell_frame_desc *changed, const char *what,
                    const char *cause)
{
    snell_renderer *r = make(ctx, 16);
    uint8_t *px = malloc(4 * N);
    snell_frame_stats s;
    int k;
    if (!r) goto done;
    for (k = 0; k < 3; k++) frame(ctx, r, fd, px, &s);
    CHECK(s.refine_samples == 3, "%s: %d samples before the change", what, s.refine_samples);
    frame(ctx, r, changed, px, &s);
    CHECK(s.refine_samples == 1 && strstr(s.refine_reason, cause), "%s: %d samples after it (%s)", what,
          s.refine_samples, s.refine_reason);
    frame(ctx, r, changed, px, &s);
    CHECK(s.refine_samples == 2, "%s: %d samples a frame later", what, s.refine_samples);
    printf("%s: restarted (%s)\n", what, s.refine_reason);
done:
    snell_renderer_destroy(r);
    free(px);
}

/* The library's allocations (the context's allocator counts them). */
static long g_allocs;
static void *count_alloc(size_t n, void *u)
{
    (void)u;
    g_allocs++;
    return malloc(n);
}
static void *count_realloc(void *p, size_t n, void *u)
{
    (void)u;
    g_allocs++;
    return realloc(p, n);
}

/* After the first frames (programs built) a refined frame allocates nothing. */
static void no_allocation(snell_ctx *ctx, const snell_frame_desc *fd)
{
    snell_renderer *r = make(ctx, 16);
    uint8_t *px = malloc(4 * N);
    long before;
    int k;
    if (!r) goto done;
    frame(ctx, r, fd, px, NULL);
    frame(ctx, r, fd, px, NULL);
    before = g_allocs;
    for (k = 0; k < 6; k++) frame(ctx, r, fd, px, NULL);
    CHECK(before > 0 && g_allocs == before, "the allocator counted %ld, then six refined frames allocated %ld times",
          before, g_allocs - before);
done:
    snell_renderer_destroy(r);
    free(px);
}

/* Once complete the mean stays: the image and the count. */
static void complete(snell_ctx *ctx, const snell_frame_desc *fd)
{
    snell_renderer *r = make(ctx, 3);
    uint8_t *pa = malloc(4 * N), *pb = malloc(4 * N);
    snell_frame_stats s;
    int k;
    if (!r) goto done;
    for (k = 0; k < 3; k++) frame(ctx, r, fd, pa, &s);
    for (k = 0; k < 2; k++) {
        frame(ctx, r, fd, pb, &s);
        CHECK(s.refine_samples == 3 && memcmp(pa, pb, 4 * N) == 0, "after the mean is complete: %d samples, %s",
              s.refine_samples, memcmp(pa, pb, 4 * N) ? "the image changed" : "the same image");
    }
done:
    snell_renderer_destroy(r);
    free(pa);
    free(pb);
}

int main(void)
{
    snell_ctx_desc cd = {0};
    snell_ctx *ctx = NULL;
    snell_env *env = NULL, *env2 = NULL;
    snell_mesh *torus = NULL, *moved = NULL;
    snell_shape_desc sd;
    snell_frame_desc fd, ch, exact_fd;
    snell_glass g, g2, ge;
    snell_renderer_desc rd;
    snell_backdrop bd;
    unsigned bd_tex = 0;
    float *pos = NULL;
    int i;
    cd.allocator.alloc = count_alloc;
    cd.allocator.realloc = count_realloc;
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK) SKIP("no GL context");
    env = test_sky(ctx, 64);
    env2 = test_sky(ctx, 32);
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_TORUS;
    sd.segments = 32;
    sd.rings = 16;
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &torus));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &moved));
    if (!env || !env2 || !torus || !moved) return test_finish();
    test_frame_one(&fd, &g, torus, env);
    g.material.method = SNELL_METHOD_CUBEMAP;
    fd.camera.elevation = 0.6f;
    fd.camera.distance = 3.2f;

    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.refine = -1;
    refused(ctx, rd, "refine -1");
    rd.refine = SNELL_MAX_REFINE + 1;
    refused(ctx, rd, "refine past SNELL_MAX_REFINE");
    rd.refine = 4;
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    refused(ctx, rd, "refine with exit directions");
    rd.output = SNELL_OUTPUT_COLOR;
    rd.msaa = 2;
    refused(ctx, rd, "refine with msaa");

    off(ctx, &fd);
    if (!snell_ctx_has_gl_extension(ctx, "GL_EXT_color_buffer_float")) {
        no_float(ctx, &fd);
        goto out;
    }
    exact_fd = fd;
    ge = g;
    exact_fd.glass = &ge;
    ge.material.method = SNELL_METHOD_EXACT;
    ge.material.exact.inner_fresnel = SNELL_INNER_FRESNEL_ON;
    deterministic(ctx, &fd, &exact_fd);
    complete(ctx, &exact_fd);
    no_allocation(ctx, &exact_fd);

    ch = fd;
    ch.camera.azimuth += 0.01f;
    restart(ctx, &fd, &ch, "camera", "camera");
    /* the mesh's geometry changes (its version), the same mesh object */
    {
        snell_frame_desc mf = fd;
        snell_glass mg = g;
        const float *p = snell_mesh_positions(moved);
        int n = snell_mesh_vertex_count(moved);
        mg.mesh = moved;
        mf.glass = &mg;
        pos = malloc(3 * sizeof(float) * (size_t)n);
        for (i = 0; i < 3 * n; i++) pos[i] = p[i] * 1.01f;
        {
            snell_renderer *r = make(ctx, 16);
            uint8_t *px = malloc(4 * N);
            snell_frame_stats s;
            if (r) {
                frame(ctx, r, &mf, px, &s);
                frame(ctx, r, &mf, px, &s);
                CHECK_OK_CTX(ctx, snell_mesh_set_vertices(moved, pos, NULL));
                frame(ctx, r, &mf, px, &s);
                CHECK(s.refine_samples == 1 && strstr(s.refine_reason, "mesh"), "mesh: %d samples after its vertices "
                      "moved (%s)", s.refine_samples, s.refine_reason);
                printf("mesh: restarted (%s)\n", s.refine_reason);
            }
            snell_renderer_destroy(r);
            free(px);
        }
    }
    ch = fd;
    g2 = g;
    ch.glass = &g2;
    g2.material.ior = 1.4f;
    restart(ctx, &fd, &ch, "material", "material");
    g2 = g;
    g2.material.cubemap.iterations = 3;
    restart(ctx, &fd, &ch, "method parameter", "material");
    g2 = g;
    g2.material.method = SNELL_METHOD_SINGLE;
    restart(ctx, &fd, &ch, "method", "material");
    ch = fd;
    ch.env = env2;
    restart(ctx, &fd, &ch, "environment", "environment");
    ch = fd;
    ch.draw_background = SNELL_BACKGROUND_NONE;
    restart(ctx, &fd, &ch, "frame setting", "settings");
    ch = fd;
    glGenTextures(1, &bd_tex);
    glBindTexture(GL_TEXTURE_2D, bd_tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, W, H);
    glBindTexture(GL_TEXTURE_2D, 0);
    memset(&bd, 0, sizeof bd);
    bd.color_texture = bd_tex;
    bd.width = W;
    bd.height = H;
    ch.backdrop = &bd;
    restart(ctx, &fd, &ch, "backdrop", "backdrop");

    converges(ctx, fd, &g);
out:
    if (bd_tex) glDeleteTextures(1, &bd_tex);
    free(pos);
    snell_mesh_destroy(torus);
    snell_mesh_destroy(moved);
    snell_env_destroy(env);
    snell_env_destroy(env2);
    snell_ctx_destroy(ctx);
    return test_finish();
}
