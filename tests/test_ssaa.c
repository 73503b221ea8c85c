/* test_ssaa — supersampling (snell_renderer_desc.ssaa): a frame at w x h with
 * ssaa = S equals, channel for channel within 1/255 (the resolve rounds the
 * mean of S^2 bytes once; the CPU mean below rounds the same way), the S x S
 * block means of the same frame rendered at S w x S h without it; for the
 * cubemap kernel on the torus (and the background, by default shading) and
 * for S = 2 and 3. Also the settings that are refused: ssaa outside 0..8, with
 * exit-direction output, with the bound framebuffer, and beyond the largest
 * renderbuffer. */
#include "test_util.h"

#include <stdlib.h>
#include <string.h>

#define W 40
#define H 30

static uint8_t *render(snell_ctx *ctx, const snell_frame_desc *fd, int w, int h, int ssaa)
{
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    uint8_t *px = (uint8_t *)malloc((size_t)w * h * 4);
    memset(&rd, 0, sizeof rd);
    rd.width = w;
    rd.height = h;
    rd.ssaa = ssaa;
    rd.shading = test_shading();
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

static void refused(snell_ctx *ctx, snell_renderer_desc rd, const char *what)
{
    snell_renderer *r = NULL;
    snell_status st = snell_renderer_create(ctx, &rd, &r);
    CHECK(st != SNELL_OK && r == NULL && strstr(snell_last_error(ctx), "ssaa"), "%s is refused with a message (%s)",
          what, snell_last_error(ctx));
    snell_renderer_destroy(r);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL;
    snell_env_desc ed;
    snell_mesh *torus = NULL;
    snell_shape_desc sd;
    snell_frame_desc fd;
    snell_glass g;
    snell_renderer_desc rd;
    int S;
    if (!ctx) SKIP("no GL context");
    memset(&ed, 0, sizeof ed);
    ed.face_size = 64;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &env));
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
    rd.width = rd.height = 4096;
    rd.ssaa = SNELL_MAX_SSAA;
    refused(ctx, rd, "ssaa beyond the largest renderbuffer");
    snell_mesh_destroy(torus);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
