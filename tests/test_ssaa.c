/* SPDX-License-Identifier: MIT */
/* test_ssaa — supersampling (snell_renderer_desc.ssaa): a frame at w x h with
 * ssaa = S equals, channel for channel within 1/255 (the resolve rounds the
 * mean of S^2 bytes once; the CPU mean below rounds the same way), the S x S
 * block means of the same frame rendered at S w x S h without it; for the
 * cubemap kernel on the torus (and the background, by default shading) and
 * for S = 2 and 3. Also the settings that are refused: ssaa outside 0..8, with
 * exit-direction output, with the bound framebuffer, and beyond the largest
 * renderbuffer. MSAA (snell_renderer_desc.msaa): see msaa_check; refused
 * beyond GL_MAX_SAMPLES, with ssaa and on the bound framebuffer. */
#include "test_util.h"
#include "core/gl.h"
#include "snell/snell_metrics.h"

#include <stdlib.h>
#include <string.h>

#define W 40
#define H 30

static uint8_t *render_aa(snell_ctx *ctx, const snell_frame_desc *fd, int w, int h, int ssaa, int msaa,
                          snell_shading shading)
{
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    uint8_t *px = (uint8_t *)malloc((size_t)w * h * 4);
    memset(&rd, 0, sizeof rd);
    rd.width = w;
    rd.height = h;
    rd.ssaa = ssaa;
    rd.msaa = msaa;
    rd.shading = shading;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (!r) {
        free(px);
        return NULL;
    }
    CHECK_OK_CTX(ctx, snell_render(r, fd, NULL));
    CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, px));
    snell_renderer_destroy(r);
    return px;
}

static uint8_t *render(snell_ctx *ctx, const snell_frame_desc *fd, int w, int h, int ssaa)
{
    return render_aa(ctx, fd, w, h, ssaa, 0, test_shading());
}

/* MSAA: pixels whose 3x3 neighbourhood is uniform in the plain forward frame
 * (inside the glass or the background, away from edges) are unchanged, as
 * the kernel runs once per pixel either way; along the glass silhouette (the
 * coverage mask changes within 3x3) the frame moves towards the supersampled
 * one (ssaa 4: the pixel's area): its error against that is below 0.8 of the
 * plain frame's there. Inside the glass MSAA cannot help (one shade a pixel). */
/* Glass coverage of fd's frame at the pixel centres: exit directions that
 * differ from those of the frame without glass (snell_metrics_coverage_mask). */
static uint8_t *coverage(snell_ctx *ctx, const snell_frame_desc *fd)
{
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    snell_frame_desc bg = *fd;
    float *a = (float *)malloc(sizeof(float) * 3 * W * H), *b = (float *)malloc(sizeof(float) * 3 * W * H);
    uint8_t *mask = (uint8_t *)calloc(W * H, 1);
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    rd.shading = SNELL_SHADING_FORWARD;
    bg.glass_count = 0;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (r) {
        CHECK_OK_CTX(ctx, snell_render(r, fd, NULL));
        CHECK_OK_CTX(ctx, snell_renderer_read_exit_dirs(r, a));
        CHECK_OK_CTX(ctx, snell_render(r, &bg, NULL));
        CHECK_OK_CTX(ctx, snell_renderer_read_exit_dirs(r, b));
        CHECK_OK(snell_metrics_coverage_mask(a, b, (long)W * H, mask));
    }
    snell_renderer_destroy(r);
    free(a);
    free(b);
    return mask;
}

static void msaa_check(snell_ctx *ctx, const snell_frame_desc *fd)
{
    uint8_t *cov = coverage(ctx, fd);
    uint8_t *plain = render_aa(ctx, fd, W, H, 0, 0, SNELL_SHADING_FORWARD);
    uint8_t *ms = render_aa(ctx, fd, W, H, 0, 4, SNELL_SHADING_AUTO);
    uint8_t *ss = render_aa(ctx, fd, W, H, 4, 0, SNELL_SHADING_FORWARD);
    long flat_off = 0, edges = 0;
    double e_plain = 0.0, e_ms = 0.0;
    int x, y, k;
    if (!plain || !ms || !ss) goto done;
    for (y = 1; y < H - 1; y++)
        for (x = 1; x < W - 1; x++) {
            size_t i = 4 * ((size_t)y * W + x);
            int dx, dy, flat = 1, silhouette = 0;
            for (dy = -1; dy <= 1; dy++)
                for (dx = -1; dx <= 1; dx++) {
                    silhouette |= cov[(y + dy) * W + x + dx] != cov[y * W + x];
                    for (k = 0; k < 3; k++) flat &= abs(plain[i + 4 * (dy * W + dx) + k] - plain[i + k]) <= 2;
                }
            if (flat) {
                for (k = 0; k < 3; k++) flat_off += abs(ms[i + k] - plain[i + k]) > 1;
                continue;
            }
            if (!silhouette) continue;
            edges++;
            for (k = 0; k < 3; k++) {
                e_plain += abs(plain[i + k] - ss[i + k]);
                e_ms += abs(ms[i + k] - ss[i + k]);
            }
        }
    printf("msaa 4: %ld silhouette pixels, mean |frame - ssaa 4| there %.2f/255 without, %.2f/255 with; %ld flat channels "
           "changed\n", edges, e_plain / (3.0 * edges), e_ms / (3.0 * edges), flat_off);
    CHECK(flat_off == 0, "msaa changed %ld channels away from edges", flat_off);
    CHECK(edges > 30 && e_ms < 0.8 * e_plain, "msaa does not bring the silhouette towards the area average (%.2f vs %.2f)",
          e_ms / (3.0 * edges), e_plain / (3.0 * edges));
done:
    free(cov);
    free(plain);
    free(ms);
    free(ss);
}

static void refused(snell_ctx *ctx, snell_renderer_desc rd, const char *what)
{
    snell_renderer *r = NULL;
    snell_status st = snell_renderer_create(ctx, &rd, &r);
    CHECK(st != SNELL_OK && r == NULL && (strstr(snell_last_error(ctx), "ssaa") || strstr(snell_last_error(ctx), "msaa")),
          "%s is refused with a message (%s)", what, snell_last_error(ctx));
    snell_renderer_destroy(r);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL;
    snell_mesh *torus = NULL;
    snell_shape_desc sd;
    snell_frame_desc fd;
    snell_glass g;
    snell_renderer_desc rd;
    int S;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 64);
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_TORUS;
    sd.segments = 48;
    sd.rings = 24;
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &torus));
    if (!env || !torus) return test_finish();
    test_frame_one(&fd, &g, torus, env);
    g.material.method = SNELL_METHOD_CUBEMAP;
    fd.camera.elevation = 0.5f;
    fd.camera.distance = 3.0f;
    for (S = 2; S <= 3; S++) {
        uint8_t *a = render(ctx, &fd, W, H, S), *b = render(ctx, &fd, W * S, H * S, 1);
        int x, y, k, worst = 0;
        long off = 0;
        if (!a || !b) {
            free(a);
            free(b);
            continue;
        }
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x++)
                for (k = 0; k < 3; k++) {
                    int i, j, sum = 0, mean, d;
                    for (j = 0; j < S; j++)
                        for (i = 0; i < S; i++) sum += b[4 * ((size_t)(y * S + j) * W * S + x * S + i) + k];
                    mean = (2 * sum + S * S) / (2 * S * S); /* round(sum / S^2) */
                    d = abs(a[4 * ((size_t)y * W + x) + k] - mean);
                    if (d > worst) worst = d;
                    off += d > 0;
                }
        printf("ssaa %d: %ld of %d channels off the block means by 1, worst %d\n", S, off, W * H * 3, worst);
        CHECK(worst <= 1, "ssaa %d: a pixel differs from its %dx%d block mean by %d/255", S, S, S, worst);
        free(a);
        free(b);
    }
    {
        GLint max_samples = 0;
        glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
        if (max_samples >= 4) msaa_check(ctx, &fd);
        else printf("msaa: skipped, GL_MAX_SAMPLES %d\n", (int)max_samples);
        memset(&rd, 0, sizeof rd);
        rd.width = W;
        rd.height = H;
        rd.msaa = max_samples + 1;
        refused(ctx, rd, "msaa beyond GL_MAX_SAMPLES");
        rd.msaa = 2;
        rd.ssaa = 2;
        refused(ctx, rd, "msaa with ssaa");
        rd.ssaa = 0;
        rd.target = SNELL_TARGET_BOUND_FRAMEBUFFER;
        refused(ctx, rd, "msaa on the bound framebuffer");
    }
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.ssaa = SNELL_MAX_SSAA + 1;
    refused(ctx, rd, "ssaa beyond the limit");
    rd.ssaa = -1;
    refused(ctx, rd, "a negative ssaa");
    rd.ssaa = 2;
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    refused(ctx, rd, "ssaa with exit-direction output");
    rd.output = SNELL_OUTPUT_COLOR;
    rd.target = SNELL_TARGET_BOUND_FRAMEBUFFER;
    refused(ctx, rd, "ssaa on the bound framebuffer");
    rd.target = SNELL_TARGET_OFFSCREEN;
    {
        /* a size the context takes (a device profile's renderbuffer may be 2048), ssaa times it not */
        snell_device_limits lim;
        snell_ctx_limits(ctx, &lim);
        rd.width = rd.height = lim.limit[SNELL_LIMIT_RENDERBUFFER_SIZE] < 4096 ? lim.limit[SNELL_LIMIT_RENDERBUFFER_SIZE] : 4096;
    }
    rd.ssaa = SNELL_MAX_SSAA;
    refused(ctx, rd, "ssaa beyond the largest renderbuffer");
    snell_mesh_destroy(torus);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
