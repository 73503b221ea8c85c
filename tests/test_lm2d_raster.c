/* SPDX-License-Identifier: MIT */
/* test_lm2d_raster.c — GL lines (llvmpipe, forced: AUTO picks the CPU
 * rasteriser here) against the exact CPU rasteriser of the same paths (eq.
 * 4.2): total flux, per-pixel and block-averaged relative error for every
 * accumulation format (float, half, and the fixed-point fallbacks), the screen
 * blend mode, the slope correction (eq. 6.4) on a star of lines, and GL state
 * restoration. Then the rasteriser choice on a ctx: AUTO on llvmpipe is the CPU
 * rasteriser (stats say so and why), GL and CPU can be forced, and the CPU
 * image uploaded into the texture is the one read back. Prints the errors. */
#include "core/gl.h"
#include "test_util.h"
#include "snell/snell_2d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 256
#define H 256

typedef struct errs {
    double total, px, b4, b8;  /* relative: |sum| diff, L1 per pixel, L1 of 4x4 and 8x8 block means */
} errs;

static errs compare(const float *gpu, const float *ref)
{
    errs e;
    double sg = 0, sr = 0, l1 = 0, ref1 = 0;
    int b, bs[2] = {4, 8}, x, y, k;
    for (x = 0; x < W * H * 3; x++) {
        sg += gpu[x];
        sr += ref[x];
        l1 += fabs((double)gpu[x] - ref[x]);
        ref1 += fabs((double)ref[x]);
    }
    e.total = fabs(sg - sr) / sr;
    e.px = l1 / ref1;
    for (b = 0; b < 2; b++) {
        double d = 0, r = 0;
        int n = bs[b];
        for (y = 0; y < H; y += n)
            for (x = 0; x < W; x += n)
                for (k = 0; k < 3; k++) {
                    double g = 0, q = 0;
                    int i, j;
                    for (j = 0; j < n; j++)
                        for (i = 0; i < n; i++) {
                            g += gpu[3 * ((y + j) * W + x + i) + k];
                            q += ref[3 * ((y + j) * W + x + i) + k];
                        }
                    d += fabs(g - q);
                    r += fabs(q);
                }
        if (b == 0) e.b4 = d / r;
        else e.b8 = d / r;
    }
    return e;
}

static snell_scene2d *test_scene(void)
{
    snell_scene2d *s = NULL;
    CHECK_OK(snell_scene2d_load(NULL, test_data("lm2d/shadow.txt"), &s, NULL, NULL));
    return s;
}

static int run(snell_ctx *ctx, snell_scene2d *s, snell_format2d fmt, snell_blend2d blend, float exposure,
               const char *name, double max_total, double max_b8)
{
    snell_lightmap2d_desc d;
    snell_lightmap2d *lm = NULL;
    snell_lightmap2d_stats st;
    float *gpu = (float *)malloc(sizeof(float) * W * H * 3), *ref = (float *)malloc(sizeof(float) * W * H * 3);
    snell_status rc;
    errs e;
    memset(&d, 0, sizeof d);
    d.width = W;
    d.height = H;
    d.format = fmt;
    d.blend = blend;
    d.exposure = exposure;
    d.max_bounces = 3;
    d.seed = 5;
    d.raster = SNELL_RASTER2D_GL;
    rc = snell_lightmap2d_create(ctx, &d, &lm);
    if (rc == SNELL_E_UNSUPPORTED) {
        printf("%-22s skipped: %s\n", name, snell_last_error(ctx));
        free(gpu);
        free(ref);
        return 0;
    }
    CHECK_OK(rc);
    if (!lm) return 1;
    CHECK_OK(snell_lightmap2d_frame(lm, s, &st));
    CHECK(st.format == fmt || fmt == SNELL_FORMAT2D_AUTO, "%s: format %d in use", name, (int)st.format);
    CHECK(st.raster == SNELL_RASTER2D_GL && st.raster_threads == 0, "%s: forced GL lines, stats say %d", name,
          (int)st.raster);
    CHECK_OK(snell_lightmap2d_read_rgb(lm, gpu));
    CHECK_OK(snell_lightmap2d_read_rgb_exact(lm, ref));
    if (fmt == SNELL_FORMAT2D_RGB10A2 || fmt == SNELL_FORMAT2D_RGBA8) {
        /* the fixed-point fallbacks saturate at 1 by design: compare with the clamped reference */
        int i;
        for (i = 0; i < W * H * 3; i++) ref[i] = ref[i] > 1.0f ? 1.0f : ref[i];
    }
    e = compare(gpu, ref);
    printf("%-22s paths %7llu  total %.4f  per-pixel L1 %.4f  4x4 %.4f  8x8 %.4f\n", name,
           (unsigned long long)st.paths, e.total, e.px, e.b4, e.b8);
    CHECK(e.total < max_total, "%s: total flux error %.4f >= %.4f", name, e.total, max_total);
    CHECK(e.b8 < max_b8, "%s: 8x8 block error %.4f >= %.4f", name, e.b8, max_b8);
    snell_lightmap2d_destroy(lm);
    free(gpu);
    free(ref);
    return 0;
}

/* Lines from the centre at 64 angles (thesis Abb. 6.15): with the flux
 * correction every direction deposits the same flux per unit length, so the
 * GPU flux inside a ring matches the exact one sector by sector. */
static void star(snell_ctx *ctx)
{
    snell_scene2d *s;
    snell_light2d_desc L;
    snell_lightmap2d_desc d;
    snell_lightmap2d *lm = NULL;
    float *gpu = (float *)malloc(sizeof(float) * W * H * 3), *ref = (float *)malloc(sizeof(float) * W * H * 3);
    double sg[8] = {0}, sr[8] = {0}, worst = 0;
    int x, y, k;
    CHECK_OK(snell_scene2d_create(NULL, &s));
    memset(&L, 0, sizeof L);
    L.position[0] = 128.3f;
    L.position[1] = 127.6f;
    L.power = 1;
    L.rays = 720;
    CHECK_OK(snell_scene2d_add_light(s, &L, NULL));
    memset(&d, 0, sizeof d);
    d.width = W;
    d.height = H;
    d.exposure = 100;
    d.raster = SNELL_RASTER2D_GL;
    CHECK_OK(snell_lightmap2d_create(ctx, &d, &lm));
    CHECK_OK(snell_lightmap2d_frame(lm, s, NULL));
    CHECK_OK(snell_lightmap2d_read_rgb(lm, gpu));
    CHECK_OK(snell_lightmap2d_read_rgb_exact(lm, ref));
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            double dx = x + 0.5 - 128.3, dy = y + 0.5 - 127.6, r = sqrt(dx * dx + dy * dy);
            int sec = (int)((atan2(dy, dx) + 3.14159265) / (2 * 3.14159265) * 8) & 7;
            if (r < 40 || r > 110) continue;
            sg[sec] += gpu[3 * (y * W + x)];
            sr[sec] += ref[3 * (y * W + x)];
        }
    for (k = 0; k < 8; k++) {
        double e = fabs(sg[k] - sr[k]) / sr[k];
        if (e > worst) worst = e;
    }
    printf("star: worst sector flux error %.4f (8 sectors of the ring r in [40,110])\n", worst);
    CHECK(worst < 0.01, "slope correction: sector flux error %.4f", worst);
    snell_lightmap2d_destroy(lm);
    snell_scene2d_destroy(s);
    free(gpu);
    free(ref);
}

static void state_restore(snell_ctx *ctx, snell_scene2d *s, snell_raster2d raster)
{
    snell_lightmap2d_desc d;
    snell_lightmap2d *lm = NULL;
    GLuint fbo, tex, pbo;
    GLint v[4], b, prog, src, dst, t2d, unpack, align, rowlen;
    memset(&d, 0, sizeof d);
    d.width = 64;
    d.height = 64;
    d.raster = raster;
    CHECK_OK(snell_lightmap2d_create(ctx, &d, &lm));
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, 8, 8);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glViewport(1, 2, 3, 4);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    /* what the CPU rasteriser's texture upload touches */
    glGenBuffers(1, &pbo);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pbo);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 5);
    CHECK_OK(snell_lightmap2d_frame(lm, s, NULL));
    glGetIntegerv(GL_VIEWPORT, v);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &b);
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    glGetIntegerv(GL_BLEND_SRC_RGB, &src);
    glGetIntegerv(GL_BLEND_DST_RGB, &dst);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &t2d);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &align);
    glGetIntegerv(GL_UNPACK_ROW_LENGTH, &rowlen);
    CHECK(v[0] == 1 && v[1] == 2 && v[2] == 3 && v[3] == 4, "viewport not restored");
    CHECK((GLuint)b == fbo, "framebuffer not restored");
    CHECK(prog == 0 && !glIsEnabled(GL_BLEND), "program/blend enable not restored");
    CHECK(src == GL_SRC_ALPHA && dst == GL_ONE_MINUS_SRC_ALPHA, "blend func not restored");
    CHECK((GLuint)t2d == tex, "texture binding not restored (raster %d)", (int)raster);
    CHECK((GLuint)unpack == pbo && align == 1 && rowlen == 5, "unpack state not restored (raster %d)", (int)raster);
    CHECK(glGetError() == GL_NO_ERROR, "GL error after the frame (raster %d)", (int)raster);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glDeleteBuffers(1, &pbo);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    snell_lightmap2d_destroy(lm);
}

/* The lightmap's texture as float RGB, top row first (GL rows are bottom first). */
/* The texture's values; *fixed set when it is RGB10_A2 (no float target:
 * GLES 3.0 reads it as UNSIGNED_INT_2_10_10_10_REV, its implementation read
 * type, and no longer as floats). */
static void read_texture(unsigned tex, float *rgb, int *fixed)
{
    static float px[W * H * 4];
    GLuint fbo;
    GLint prev, type = 0;
    int x, y, k;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glGetIntegerv(GL_IMPLEMENTATION_COLOR_READ_TYPE, &type);
    *fixed = type == GL_UNSIGNED_INT_2_10_10_10_REV;
    glReadPixels(0, 0, W, H, GL_RGBA, *fixed ? GL_UNSIGNED_INT_2_10_10_10_REV : GL_FLOAT, px);
    for (k = W * H; *fixed && k-- > 0;) { /* widened in place from the last texel */
        unsigned p;
        memcpy(&p, (const char *)px + 4 * k, 4);
        px[4 * k] = (float)(p & 1023u) / 1023.0f;
        px[4 * k + 1] = (float)(p >> 10 & 1023u) / 1023.0f;
        px[4 * k + 2] = (float)(p >> 20 & 1023u) / 1023.0f;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)prev);
    glDeleteFramebuffers(1, &fbo);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++)
            for (k = 0; k < 3; k++) rgb[3 * (y * W + x) + k] = px[4 * ((H - 1 - y) * W + x) + k];
}

/* AUTO on llvmpipe: the CPU rasteriser, said in the stats with the reason; the
 * same image as without GL (bitwise), and the same values in the texture a
 * host would draw (raw sum for float ADD, display values for SCREEN). Forcing
 * GL lines gives GL lines. */
static void choice(snell_ctx *ctx, snell_scene2d *s)
{
    static float a[W * H * 3], b[W * H * 3], t[W * H * 3];
    snell_lightmap2d_desc d;
    snell_lightmap2d *lm = NULL, *cpu = NULL;
    snell_lightmap2d_stats st;
    int soft = strstr(snell_ctx_gl_renderer(ctx), "llvmpipe") != NULL, i, bl;
    double err;
    for (bl = 0; bl < 2; bl++) {
        memset(&d, 0, sizeof d);
        d.width = W;
        d.height = H;
        d.max_bounces = 3;
        d.seed = 5;
        d.blend = bl ? SNELL_BLEND2D_SCREEN : SNELL_BLEND2D_ADD;
        d.exposure = bl ? 0.05f : 1.0f;
        CHECK_OK_CTX(ctx, snell_lightmap2d_create(ctx, &d, &lm));
        d.cpu_only = 1;
        CHECK_OK_CTX(ctx, snell_lightmap2d_create(ctx, &d, &cpu));
        if (!lm || !cpu) return;
        CHECK_OK(snell_lightmap2d_frame(lm, s, &st));
        printf("auto on '%s': raster %d on %d threads (%s), upload %.2f ms\n", snell_ctx_gl_renderer(ctx),
               (int)st.raster, st.raster_threads, st.raster_reason, st.upload_ms);
        if (soft) {
            CHECK(st.raster == SNELL_RASTER2D_CPU && st.raster_threads >= 1, "llvmpipe: AUTO chose %d", (int)st.raster);
            CHECK(strstr(st.raster_reason, "auto") && strstr(st.raster_reason, "llvmpipe"), "reason '%s'",
                  st.raster_reason);
        }
        CHECK_OK(snell_lightmap2d_frame(cpu, s, NULL));
        CHECK_OK(snell_lightmap2d_read_rgb(lm, a));
        CHECK_OK(snell_lightmap2d_read_rgb(cpu, b));
        if (st.raster == SNELL_RASTER2D_CPU) {
            CHECK(memcmp(a, b, sizeof a) == 0, "CPU rasteriser with a ctx differs from cpu_only (blend %d)", bl);
            CHECK(snell_lightmap2d_texture(lm) != 0 && snell_lightmap2d_texture(cpu) == 0, "textures %u %u",
                  snell_lightmap2d_texture(lm), snell_lightmap2d_texture(cpu));
            int fixed = 0, half = st.format == SNELL_FORMAT2D_RGBA16F;
            read_texture(snell_lightmap2d_texture(lm), t, &fixed);
            err = 0.0;
            for (i = 0; i < W * H * 3; i++) {
                /* float ADD holds the raw sum (exposure 1, one pass here):
                 * RGBA16F within a unit in the last place (the GL may round
                 * toward zero); RGB10_A2 that clamped to 0..1 and rounded
                 * to 1/1023 */
                double e = fabs((double)t[i] - (fixed ? fmin(a[i], 1.0) : a[i]));
                if (half) e /= fmax(fabs(a[i]), 6.2e-5); /* relative, above half's smallest normal */
                if (e > err) err = e;
            }
            CHECK(err < (fixed ? 0.5 / 1023.0 + 1e-6 : half ? 1.0 / 1024.0 + 1e-6 : 1e-6),
                  "texture (%s) differs from the image read back by %.3g%s (blend %d)",
                  fixed ? "RGB10_A2" : half ? "RGBA16F" : "RGBA32F", err, half ? " of the value" : "", bl);
        }
        snell_lightmap2d_destroy(lm);
        snell_lightmap2d_destroy(cpu);
        lm = cpu = NULL;
    }
    /* forced either way */
    memset(&d, 0, sizeof d);
    d.width = d.height = 32;
    d.raster = SNELL_RASTER2D_GL;
    CHECK_OK(snell_lightmap2d_create(ctx, &d, &lm));
    CHECK_OK(snell_lightmap2d_frame(lm, s, &st));
    CHECK(st.raster == SNELL_RASTER2D_GL && strstr(st.raster_reason, "requested"), "forced GL: %d (%s)",
          (int)st.raster, st.raster_reason);
    snell_lightmap2d_destroy(lm);
    d.raster = SNELL_RASTER2D_CPU;
    CHECK_OK(snell_lightmap2d_create(ctx, &d, &lm));
    CHECK_OK(snell_lightmap2d_frame(lm, s, &st));
    CHECK(st.raster == SNELL_RASTER2D_CPU && strstr(st.raster_reason, "requested"), "forced CPU: %d (%s)",
          (int)st.raster, st.raster_reason);
    snell_lightmap2d_destroy(lm);
    d.raster = SNELL_RASTER2D_GL;
    d.cpu_only = 1;
    lm = NULL;
    CHECK(snell_lightmap2d_create(ctx, &d, &lm) == SNELL_E_INVALID_ARG && !lm, "GL lines with cpu_only accepted");
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_scene2d *s;
    if (!ctx) SKIP("no GL context");
    s = test_scene();
    if (!s) return test_finish();
    /* exposure so that the lit floor is ~1: the fixed-point fallbacks saturate above 1 */
    /* Bounds are the measured errors (see bench/BENCHMARKS2D.md) with about 2x margin.
     * RGBA16F is biased low: each blend rounds the sum to 11 bits, and here one
     * contribution is ~1/1000 of the sum (measured -8 %). The fixed-point
     * fallbacks round each line value stochastically and stay unbiased. */
    run(ctx, s, SNELL_FORMAT2D_RGBA32F, SNELL_BLEND2D_ADD, 1.0f, "RGBA32F add", 0.002, 0.003);
    run(ctx, s, SNELL_FORMAT2D_RGBA16F, SNELL_BLEND2D_ADD, 1.0f, "RGBA16F add", 0.15, 0.15);
    run(ctx, s, SNELL_FORMAT2D_RGB10A2, SNELL_BLEND2D_ADD, 1.0f, "RGB10A2 add (fallback)", 0.005, 0.006);
    run(ctx, s, SNELL_FORMAT2D_RGBA8, SNELL_BLEND2D_ADD, 1.0f, "RGBA8 add (fallback)", 0.01, 0.02);
    run(ctx, s, SNELL_FORMAT2D_RGBA32F, SNELL_BLEND2D_SCREEN, 1.0f, "RGBA32F screen", 0.002, 0.003);
    star(ctx);
    state_restore(ctx, s, SNELL_RASTER2D_GL);
    state_restore(ctx, s, SNELL_RASTER2D_CPU);
    choice(ctx, s);
    snell_scene2d_destroy(s);
    snell_ctx_destroy(ctx);
    return test_finish();
}
