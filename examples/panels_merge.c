/* SPDX-License-Identifier: MIT */
/* panels_merge.c — glass panels that merge and split as they move, over an
 * app's picture. Two drops of glass slide through each other under a
 * capsule; all three are one group (snell_panel.group), so where they come
 * near each other their shapes flow into one (a smooth union).
 * The picture is the app's own GL texture, drawn by the frame beneath the
 * panels (SNELL_PANELS_UNDER_TEXTURE with draw = 1).
 *
 *   panels_merge [OUT_PREFIX] [WxH] [PICTURE.png]
 *
 * Writes OUT_PREFIX_0.png .. _5.png (default panels_merge_N.png, 480x270,
 * a drawn test pattern). Exit 0 when the space between the drops is glass
 * while they merge and the picture while they are apart. */
#include <snell/snell.h>

#include <GLES3/gl3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FRAMES 6

/* A test pattern, bottom row first: diagonal colour bands under a grid of
 * dark lines, so that every bend of the light shows. */
static uint8_t *pattern(int w, int h)
{
    uint8_t *p = (uint8_t *)malloc((size_t)w * (size_t)h * 4);
    int x, y;
    for (y = 0; p && y < h; y++)
        for (x = 0; x < w; x++) {
            uint8_t *q = p + 4 * ((size_t)y * (size_t)w + (size_t)x);
            double band = (x + y) * 6.2831853 / (0.25 * w);
            int line = x % 24 < 2 || y % 24 < 2;
            q[0] = (uint8_t)(line ? 30 : 140 + 110 * sin(band));
            q[1] = (uint8_t)(line ? 30 : 140 + 110 * sin(band + 2.1));
            q[2] = (uint8_t)(line ? 40 : 140 + 110 * sin(band + 4.2));
            q[3] = 255;
        }
    return p;
}

/* The picture as a GL texture of the current context. */
static GLuint picture_texture(const uint8_t *rgba, int w, int h)
{
    GLuint t = 0;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    return glGetError() == GL_NO_ERROR ? t : 0;
}

/* Frame f of FRAMES: the drops at x = centre -+ a cos(pi f / (FRAMES - 1)),
 * apart at the first and last frames, through each other in the middle. */
static void place(snell_panel p[3], int f, int w, int h)
{
    float r = 0.2f * (float)h, a = 0.3f * (float)w * cosf(3.14159265f * (float)f / (FRAMES - 1));
    int k;
    memset(p, 0, 3 * sizeof *p);
    for (k = 0; k < 3; k++) {
        p[k].group = 1; /* one shape: they merge where they meet */
        p[k].merge = 0.4f * r; /* the smoothing distance of the union, pixels */
        p[k].shadow[0] = -1.0f; /* no drop shadow: the check below reads the picture between them */
    }
    p[0].center[0] = 0.5f * (float)w - a, p[1].center[0] = 0.5f * (float)w + a;
    p[0].center[1] = p[1].center[1] = 0.5f * (float)h;
    p[0].size[0] = p[0].size[1] = p[1].size[0] = p[1].size[1] = 2.0f * r;
    p[0].radius[0] = p[1].radius[0] = r; /* a circle: the radius of half its side */
    p[0].radius[1] = p[0].radius[2] = p[0].radius[3] = r;
    p[1].radius[1] = p[1].radius[2] = p[1].radius[3] = r;
    p[0].frost = 2.0f; /* the first drop frosted; a group takes its material from its first */
    p[2].center[0] = 0.5f * (float)w, p[2].center[1] = 0.5f * (float)h + 1.15f * r;
    p[2].size[0] = 1.2f * r, p[2].size[1] = 0.4f * r; /* a capsule just above the meeting point */
    p[2].radius[0] = p[2].radius[1] = p[2].radius[2] = p[2].radius[3] = 0.2f * r;
}

int main(int argc, char **argv)
{
    const char *prefix = argc > 1 ? argv[1] : "panels_merge";
    int w = 480, h = 270, f, rc = 1, decoded = 0, changed_all = 1, mid_apart = -1, mid_merged = -1;
    uint8_t *picture = NULL, *frame = NULL;
    snell_ctx *ctx = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_panels_under under;
    snell_frame_desc fd;
    snell_frame_stats stats;
    snell_panel panels[3];
    GLuint tex = 0;
    if (argc > 2 && (sscanf(argv[2], "%dx%d", &w, &h) != 2 || w < 32 || h < 32 || w > 4096 || h > 4096)) {
        fprintf(stderr, "panels_merge: size '%s': want WxH, 32..4096\n", argv[2]);
        return 2;
    }
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK) { /* snell's own context, current: the app's texture goes in it */
        fprintf(stderr, "panels_merge: no GLES 3.0 context here: %s\n", snell_last_error(NULL));
        return 77;
    }
    if (argc > 3) { /* a picture of the app's: the frame takes its size */
        size_t row, y;
        if (snell_image_read(argv[3], &w, &h, &picture) != SNELL_OK) {
            fprintf(stderr, "panels_merge: %s\n", snell_last_error(NULL));
            goto done;
        }
        decoded = 1;
        row = (size_t)w * 4; /* top row first -> GL's bottom row first */
        frame = (uint8_t *)malloc(row);
        for (y = 0; frame && y < (size_t)h / 2; y++) {
            memcpy(frame, picture + y * row, row);
            memcpy(picture + y * row, picture + ((size_t)h - 1 - y) * row, row);
            memcpy(picture + ((size_t)h - 1 - y) * row, frame, row);
        }
        free(frame);
    } else {
        picture = pattern(w, h);
    }
    frame = (uint8_t *)malloc((size_t)w * (size_t)h * 4);
    if (!picture || !frame || !(tex = picture_texture(picture, w, h))) {
        fprintf(stderr, "panels_merge: no memory or texture for a %dx%d picture\n", w, h);
        goto done;
    }
    memset(&rd, 0, sizeof rd);
    rd.width = w, rd.height = h; /* offscreen, read back below */
    if (snell_renderer_create(ctx, &rd, &r) != SNELL_OK) {
        fprintf(stderr, "panels_merge: %s\n", snell_last_error(ctx));
        goto done;
    }
    memset(&under, 0, sizeof under);
    under.source = SNELL_PANELS_UNDER_TEXTURE;
    under.texture = tex;
    under.draw = 1; /* the frame draws the picture, then the panels over it */
    for (f = 0; f < FRAMES; f++) {
        char path[512];
        int x = w / 2, y = h / 2, k, changed = 0;
        const uint8_t *mid;
        place(panels, f, w, h);
        memset(&fd, 0, sizeof fd); /* a frame of panels only: no environment, no glass objects */
        fd.draw_background = SNELL_BACKGROUND_NONE;
        fd.panels = panels;
        fd.panel_count = 3;
        fd.panels_under = &under;
        if (snell_render(r, &fd, &stats) != SNELL_OK || snell_renderer_read_rgba(r, frame) != SNELL_OK) {
            fprintf(stderr, "panels_merge: frame %d: %s\n", f, snell_last_error(ctx));
            goto done;
        }
        snprintf(path, sizeof path, "%s_%d.png", prefix, f);
        if (snell_write_png(path, w, h, frame) != SNELL_OK) {
            fprintf(stderr, "panels_merge: %s\n", snell_last_error(NULL));
            goto done;
        }
        /* read_rgba is top row first, the picture bottom row first */
        for (k = 0; k < w * h; k++)
            changed += memcmp(frame + 4 * (size_t)k,
                              picture + 4 * ((size_t)(h - 1 - k / w) * (size_t)w + (size_t)(k % w)), 3) != 0;
        mid = frame + 4 * ((size_t)(h - 1 - y) * (size_t)w + (size_t)x);
        k = memcmp(mid, picture + 4 * ((size_t)y * (size_t)w + (size_t)x), 3) != 0; /* glass between the drops */
        if (f == 0) mid_apart = k;
        if (f == FRAMES / 2) mid_merged = k;
        changed_all = changed_all && changed > w * h / 50;
        printf("panels_merge: frame %d: %d pixels of glass, %d shape(s) drawn, between the drops: %s; wrote %s\n", f,
               changed, stats.panels_drawn, k ? "glass" : "the picture", path);
    }
    rc = changed_all && mid_apart == 0 && mid_merged == 1 ? 0 : 1;
    printf("panels_merge: %s\n", rc ? "FAILED: the drops did not merge and split" : "the drops merged and split");
done:
    if (tex) glDeleteTextures(1, &tex);
    snell_renderer_destroy(r);
    snell_ctx_destroy(ctx);
    if (decoded)
        snell_image_free(picture);
    else
        free(picture);
    free(frame);
    return rc;
}
