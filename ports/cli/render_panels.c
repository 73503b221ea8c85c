/* SPDX-License-Identifier: MIT */
/* render_panels.c — snell-render's glass panels (--panels, --under): the
 * picture beneath as the app's GL texture, the panels on the frame. */
#include "render.h"

#include <GLES3/gl3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Rows of a width x height RGBA8 image reversed in place: PNGs are top row
 * first, GL textures and snell_ref_panels bottom row first. */
static void flip_rows(uint8_t *rgba, int width, int height)
{
    size_t row = (size_t)width * 4;
    uint8_t *tmp = (uint8_t *)malloc(row);
    int y;
    if (!tmp) return;
    for (y = 0; y < height / 2; y++) {
        memcpy(tmp, rgba + (size_t)y * row, row);
        memcpy(rgba + (size_t)y * row, rgba + (size_t)(height - 1 - y) * row, row);
        memcpy(rgba + (size_t)(height - 1 - y) * row, tmp, row);
    }
    free(tmp);
}

int render_panels_open(snell_ctx *ctx, render_options *o, render_panels *p)
{
    GLint max_size = 0;
    memset(p, 0, sizeof *p);
    if (!o->under_file) return 1;
    if (snell_image_read(o->under_file, &p->width, &p->height, &p->image) != SNELL_OK) {
        fprintf(stderr, "snell-render: --under: %s\n", snell_last_error(NULL));
        return 0;
    }
    if (!o->size_given) { /* the frame is the picture's size */
        o->width = p->width;
        o->height = p->height;
    }
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (p->width > max_size || p->height > max_size) {
        fprintf(stderr, "snell-render: --under %dx%d: larger than this GL's textures (%d)\n", p->width, p->height,
                (int)max_size);
        return 0;
    }
    flip_rows(p->image, p->width, p->height); /* GL's rows: bottom first */
    glGenTextures(1, &p->texture);
    glBindTexture(GL_TEXTURE_2D, p->texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, p->width, p->height, 0, GL_RGBA, GL_UNSIGNED_BYTE, p->image);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    if (glGetError() != GL_NO_ERROR) {
        fprintf(stderr, "snell-render: --under: GL refused a %dx%d texture\n", p->width, p->height);
        return 0;
    }
    p->under.source = SNELL_PANELS_UNDER_TEXTURE;
    p->under.texture = p->texture;
    p->under.draw = 1; /* the picture drawn first, over the whole frame */
    (void)ctx;
    return 1;
}

void render_panels_frame(const render_options *o, const render_panels *p, snell_frame_desc *fd)
{
    fd->panels = o->panels.panels;
    fd->panel_count = o->panels.count;
    if (!p->texture) return; /* over the scene's frame as drawn (TARGET) */
    fd->panels_under = &p->under;
    /* a frame of panels only: the picture is all that lies beneath */
    fd->env = NULL;
    fd->glass = NULL;
    fd->glass_count = 0;
    fd->opaque = NULL;
    fd->opaque_count = 0;
    fd->draw_background = SNELL_BACKGROUND_NONE;
}

void render_panels_close(render_panels *p)
{
    if (p->texture) glDeleteTextures(1, &p->texture);
    snell_image_free(p->image);
    memset(p, 0, sizeof *p);
}
