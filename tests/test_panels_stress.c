/* SPDX-License-Identifier: MIT */
/* test_panels_stress — hostile panels test_panels does not cover: 4,096
 * panels each over the one before (every overlap copied again: the stats
 * count them, the frame's time bounded), a 1x1 frame, an app's texture of
 * another size than the frame read through a uv transform that leaves
 * 0..1 (its edge texels, clamped: snell_panels.h); frost over a panel
 * blurring what that panel drew. */
#include "test_util.h"
#include "core/gl.h"

#include <EGL/egl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define W 96
#define H 64

static snell_ctx *g_ctx;

static snell_renderer *offscreen(int w, int h)
{
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    memset(&rd, 0, sizeof rd);
    rd.width = w, rd.height = h;
    CHECK_OK_CTX(g_ctx, snell_renderer_create(g_ctx, &rd, &r));
    return r;
}

/* A w x h texture whose column i is (40 + 50 i, 200 - 40 i, 90) in every row. */
static GLuint columns(int w, int h)
{
    GLubyte px[4 * 16 * 16];
    GLuint t;
    int i, j;
    for (j = 0; j < h; j++)
        for (i = 0; i < w; i++) {
            GLubyte *p = px + 4 * (j * w + i);
            p[0] = (GLubyte)(40 + 50 * i), p[1] = (GLubyte)(200 - 40 * i), p[2] = 90, p[3] = 255;
        }
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, px);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

/* A flat pane (no bevel, rim or shadow) of w x h at (cx, cy). */
static snell_panel pane(float cx, float cy, float w, float h)
{
    snell_panel p;
    memset(&p, 0, sizeof p);
    p.center[0] = cx, p.center[1] = cy, p.size[0] = w, p.size[1] = h;
    p.radius[0] = p.radius[1] = p.radius[2] = p.radius[3] = -1.0f;
    p.bevel = -1.0f, p.ior = 1.5f, p.rim = -1.0f, p.shadow[0] = -1.0f;
    return p;
}

static snell_status draw(snell_renderer *r, const snell_panel *p, int n, const snell_panels_under *u,
                         snell_frame_stats *s, uint8_t *img)
{
    snell_frame_desc fd;
    snell_status st;
    memset(&fd, 0, sizeof fd);
    fd.draw_background = SNELL_BACKGROUND_NONE, fd.panels = p, fd.panel_count = n, fd.panels_under = u;
    st = snell_render(r, &fd, s);
    if (st == SNELL_OK && img) st = snell_renderer_read_rgba(r, img);
    return st;
}

/* A frosted panel over another blurs what that one drew: the overlap's
 * mip levels made again over its box match a frame that held the first
 * panel already (its whole chain made). */
static void check_frost_over(snell_renderer *r, GLuint tex)
{
    static uint8_t one[4 * W * H], first[4 * W * H], two[4 * W * H], flip[4 * W * H];
    snell_panels_under u;
    snell_frame_stats s;
    snell_panel p[2];
    GLuint held;
    int x, y, c, worst = 0;
    memset(&u, 0, sizeof u);
    u.source = SNELL_PANELS_UNDER_TEXTURE, u.texture = tex, u.draw = 1;
    u.uv_transform[0] = 0.3f, u.uv_transform[5] = u.uv_transform[10] = u.uv_transform[15] = 1.0f; /* a ramp */
    p[0] = pane(35, 32, 50, 40), p[0].bevel = p[0].thickness = 10.0f; /* its bevel: structure to blur */
    p[1] = pane(60, 32, 60, 56), p[1].frost = 4.0f;
    CHECK_OK_CTX(g_ctx, draw(r, p, 2, &u, &s, one));
    CHECK(s.panels_captures == 2, "frost over a panel: %d captures", s.panels_captures);
    CHECK_OK_CTX(g_ctx, draw(r, p, 1, &u, &s, first));
    for (y = 0; y < H; y++) memcpy(flip + 4 * (size_t)y * W, first + 4 * (size_t)(H - 1 - y) * W, 4 * W);
    glGenTextures(1, &held);
    glBindTexture(GL_TEXTURE_2D, held);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, flip);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glBindTexture(GL_TEXTURE_2D, 0);
    memset(u.uv_transform, 0, sizeof u.uv_transform);
    u.texture = held;
    CHECK_OK_CTX(g_ctx, draw(r, p + 1, 1, &u, &s, two));
    /* inside both, farther than the blur's reach from the overlap box's edges */
    for (y = 26; y < 38; y++)
        for (x = 46; x < 54; x++)
            for (c = 0; c < 3; c++) {
                int d = abs(one[4 * ((size_t)y * W + x) + c] - two[4 * ((size_t)y * W + x) + c]);
                worst = d > worst ? d : worst;
            }
    CHECK(worst <= 2, "frost over a panel against a frame holding it: %d levels off", worst);
    glDeleteTextures(1, &held);
}

int main(void)
{
    static snell_panel chain[SNELL_MAX_PANELS];
    static uint8_t img[4 * W * H];
    EGLDisplay dpy;
    EGLContext egl;
    snell_ctx_desc d;
    snell_renderer *r, *one;
    snell_panels_under u;
    snell_frame_stats s;
    snell_panel p;
    GLuint tex, small;
    double t0, ms;
    int i, c;
    if (!test_host_context(&dpy, &egl)) SKIP("cannot make a host context here");
    memset(&d, 0, sizeof d);
    d.backend = SNELL_BACKEND_EXTERNAL;
    CHECK_OK(snell_ctx_create(&d, &g_ctx));
    if (!g_ctx) return test_finish();
    r = offscreen(W, H), one = offscreen(1, 1);
    tex = columns(4, 2), small = columns(1, 1);
    memset(&u, 0, sizeof u);
    u.source = SNELL_PANELS_UNDER_TEXTURE, u.draw = 1;

    /* An app's 4x2 texture over the 96x64 frame, u scaled by 3: past u = 1
     * the right edge's texel, the pane (1 - F0) times it. */
    u.texture = tex, u.uv_transform[0] = 3.0f, u.uv_transform[5] = u.uv_transform[10] = u.uv_transform[15] = 1.0f;
    p = pane(48, 32, 200, 200);
    CHECK_OK_CTX(g_ctx, draw(r, &p, 1, &u, &s, img));
    for (c = 0; c < 3; c++) {
        const int edge[3] = {40 + 50 * 3, 200 - 40 * 3, 90};
        int got = img[4 * ((size_t)(H - 1 - 32) * W + 90) + c];
        CHECK(fabs(got - 0.96 * edge[c]) <= 1.0, "uv past 1: channel %d %d, (1 - F0) edge %.1f", c, got, 0.96 * edge[c]);
    }

    check_frost_over(r, tex);

    /* A 1x1 frame under a pane larger than it. */
    u.texture = small;
    memset(u.uv_transform, 0, sizeof u.uv_transform);
    p = pane(0.5f, 0.5f, 10, 10);
    CHECK_OK_CTX(g_ctx, draw(one, &p, 1, &u, &s, img));
    CHECK(s.panels_drawn == 1 && fabs(img[0] - 0.96 * 40) <= 1.0 && fabs(img[1] - 0.96 * 200) <= 1.0,
          "1x1 frame: %d drawn, %d %d", s.panels_drawn, img[0], img[1]);

    /* 4,096 panels, each over the one before: one capture for the frame, one copy again for each overlap. */
    for (i = 0; i < SNELL_MAX_PANELS; i++) chain[i] = pane(20.0f + 0.01f * (float)i, 32, 12, 12);
    u.texture = tex;
    t0 = (double)clock();
    CHECK_OK_CTX(g_ctx, draw(r, chain, SNELL_MAX_PANELS, &u, &s, img));
    ms = ((double)clock() - t0) * 1000.0 / CLOCKS_PER_SEC;
    CHECK(s.panels_drawn == SNELL_MAX_PANELS && s.panels_captures == SNELL_MAX_PANELS,
          "4,096 in a chain: %d drawn, %d captures", s.panels_drawn, s.panels_captures);
    CHECK(ms < 20000.0 * test_time_scale(), "4,096 in a chain: %.0f ms CPU", ms);
    printf("4,096 panels in a chain: %d drawn, %d captures, %.0f ms CPU\n", s.panels_drawn, s.panels_captures, ms);
    CHECK(abs(img[4 * ((size_t)(H - 1 - 32) * W + 94)] - (40 + 50 * 3)) <= 1, "beside the chain: beneath as drawn");

    glDeleteTextures(1, &tex);
    glDeleteTextures(1, &small);
    snell_renderer_destroy(one);
    snell_renderer_destroy(r);
    snell_ctx_destroy(g_ctx);
    return test_finish();
}
