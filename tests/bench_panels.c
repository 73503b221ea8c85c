/* SPDX-License-Identifier: MIT */
/* bench_panels — issue 51's cost of N glass panels against a plain
 * full-screen copy: an app's texture blitted into a framebuffer of the
 * frame's size (the copy), then frames of N clear panels (180x90, default
 * bevel, rim and shadow, apart on a grid), 4 frosted, 4 dispersive, 4
 * merged in pairs, and one of 8x8 pixels (what a frame of panels costs
 * before its pixels), over that texture drawn first and over the frame's
 * own rectangle; each ended by glFinish, configurations taking turns round
 * by round, medians. A tool, not a test.
 *
 * usage: bench_panels [WxH [ROUNDS]]   e.g. bench_panels 1920x1080 15 */
#include "snell/snell.h"
#include "cli_time.h" /* ports/cli: the median the ports use */

#include <GLES3/gl3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Config 0 is the copy; 1..KINDS the panels over the app's texture, then
 * the same over the frame's own rectangle (SNELL_PANELS_UNDER_TARGET). */
enum { KINDS = 8, CONFIGS = 1 + 2 * KINDS };
static const char *const names[KINDS] = {"1 of 8x8 px, no shadow", "1 clear", "4 clear", "16 clear", "64 clear",
                                         "4 frosted (6 px)", "4 dispersive (Abbe 20)", "4 merged (2 pairs)"};
static const int counts[KINDS] = {1, 1, 4, 16, 64, 4, 4, 4};

static void loadavg(char *buf, size_t n)
{
    FILE *f = fopen("/proc/loadavg", "r");
    buf[0] = 0;
    if (f && fgets(buf, (int)n, f)) buf[strcspn(buf, "\n")] = 0;
    if (f) fclose(f);
}

/* Kind c's panels: the first N cells of an 8x8 grid over the frame, spread. */
static int make_panels(int c, int w, int h, snell_panel *p)
{
    int n = counts[c], i, step = n ? 64 / n : 1;
    for (i = 0; i < n; i++) {
        int cell = i * step, cx = cell % 8, cy = cell / 8;
        memset(&p[i], 0, sizeof p[i]);
        p[i].center[0] = (cx + 0.5f) * w / 8.0f, p[i].center[1] = (cy + 0.5f) * h / 8.0f;
        p[i].size[0] = 180.0f * w / 1920.0f, p[i].size[1] = 90.0f * h / 1080.0f;
        if (c == 0) p[i].size[0] = p[i].size[1] = 8.0f, p[i].shadow[0] = -1.0f;
        if (c == 5) p[i].frost = 6.0f;
        if (c == 6) p[i].dispersion = 1.0f;
        if (c == 7) {
            p[i].group = 1 + i / 2;
            p[i].center[0] = (i & 1 ? 0.45f : 0.55f) * w, p[i].center[1] = (i < 2 ? 0.3f : 0.7f) * h;
        }
    }
    return n;
}

int main(int argc, char **argv)
{
    int w = 1920, h = 1080, rounds = 15, c, k, i;
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_panels_under under[2];
    static snell_panel panels[64];
    snell_frame_stats st[CONFIGS];
    double *t[CONFIGS], med[CONFIGS];
    char before[128], after[128];
    uint8_t *pic;
    GLuint tex, fbo[2], rb;
    if ((argc > 1 && sscanf(argv[1], "%dx%d", &w, &h) != 2) || (argc > 2 && (rounds = atoi(argv[2])) < 1) ||
        w < 64 || h < 64 || w > 8192 || h > 8192 || rounds > 1000) {
        fprintf(stderr, "usage: bench_panels [WxH [ROUNDS]]\n");
        return 2;
    }
    memset(&cd, 0, sizeof cd);
    memset(&rd, 0, sizeof rd);
    rd.width = w, rd.height = h;
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK || snell_renderer_create(ctx, &rd, &r) != SNELL_OK) {
        fprintf(stderr, "bench_panels: %s\n", snell_last_error(ctx));
        return 1;
    }
    pic = malloc((size_t)w * h * 4);
    for (i = 0; i < w * h; i++) {
        int x = i % w, y = i / w, check = ((x / 16) + (y / 16)) & 1;
        pic[4 * i] = (uint8_t)(60 + 120 * x / w + 40 * check), pic[4 * i + 1] = (uint8_t)(40 + 150 * y / h);
        pic[4 * i + 2] = (uint8_t)(200 - 100 * x / w + 30 * check), pic[4 * i + 3] = 255;
    }
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, pic);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glBindTexture(GL_TEXTURE_2D, 0);
    /* The copy: the texture's framebuffer blitted into one of the frame's size. */
    glGenFramebuffers(2, fbo);
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo[0]);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo[1]);
    glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    memset(under, 0, sizeof under);
    under[0].source = SNELL_PANELS_UNDER_TEXTURE, under[0].texture = tex, under[0].draw = 1;
    under[1].source = SNELL_PANELS_UNDER_TARGET;
    for (c = 0; c < CONFIGS; c++) t[c] = calloc((size_t)rounds, sizeof(double));
    loadavg(before, sizeof before);
    for (k = -2; k < rounds; k++) /* two warm-up rounds */
        for (c = 0; c < CONFIGS; c++) {
            snell_frame_desc fd;
            double t0 = cli_now_ms();
            if (c == 0) {
                glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo[0]);
                glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo[1]);
                glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
                glBindFramebuffer(GL_FRAMEBUFFER, 0);
            } else {
                memset(&fd, 0, sizeof fd);
                fd.draw_background = SNELL_BACKGROUND_NONE;
                fd.panels = panels, fd.panel_count = make_panels((c - 1) % KINDS, w, h, panels);
                fd.panels_under = &under[(c - 1) / KINDS];
                if (snell_render(r, &fd, &st[c]) != SNELL_OK) {
                    fprintf(stderr, "bench_panels: %s: %s\n", names[(c - 1) % KINDS], snell_last_error(ctx));
                    return 1;
                }
            }
            glFinish();
            if (k >= 0) t[c][k] = cli_now_ms() - t0;
        }
    loadavg(after, sizeof after);
    printf("bench_panels %dx%d, %d rounds (2 warm-up), configurations taking turns, each frame ended by glFinish\n"
           "GL_RENDERER %s; load average before %s, after %s\n\n| beneath | panels | ms/frame (median) | x copy | "
           "drawn | captures |\n|---|---|---:|---:|---:|---:|\n",
           w, h, rounds, (const char *)glGetString(GL_RENDERER), before, after);
    for (c = 0; c < CONFIGS; c++) med[c] = cli_median(t[c], rounds);
    printf("| the copy (glBlitFramebuffer) | none | %.2f | 1.00 | | |\n", med[0]);
    for (c = 1; c < CONFIGS; c++)
        printf("| %s | %s | %.2f | %.2f | %d | %d |\n", c <= KINDS ? "app's texture, drawn" : "the frame (TARGET)",
               names[(c - 1) % KINDS], med[c], med[c] / med[0], st[c].panels_drawn, st[c].panels_captures);
    for (c = 0; c < CONFIGS; c++) free(t[c]);
    free(pic);
    glDeleteFramebuffers(2, fbo);
    glDeleteRenderbuffers(1, &rb);
    glDeleteTextures(1, &tex);
    snell_renderer_destroy(r);
    snell_ctx_destroy(ctx);
    return 0;
}
