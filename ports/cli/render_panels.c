/* SPDX-License-Identifier: MIT */
/* render_panels.c — snell-render's glass panels (--panels, --under,
 * --reference): the picture beneath as the app's GL texture, the panels on
 * the frame, and snell_ref_panels' image of the same input beside it. */
#include "render.h"
#include "snell/snell_ref.h"

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
    } else if (o->reference && (o->width != p->width || o->height != p->height)) {
        fprintf(stderr,
                "snell-render: --reference reads --under's pixels as they are: give no --size, or the "
                "image's (%dx%d)\n",
                p->width, p->height);
        return 0;
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

int render_panels_plain(snell_ctx *ctx, snell_renderer *r, const render_options *o, render_panels *p,
                        const snell_frame_desc *fd)
{
    snell_frame_desc plain = *fd;
    size_t bytes = (size_t)o->width * (size_t)o->height * 4;
    if (!o->reference) return 1;
    if (p->texture) return 1; /* the picture is what lies beneath */
    /* TARGET: beneath the panels lies the frame drawn without them */
    plain.panels = NULL;
    plain.panel_count = 0;
    if (!(p->plain = (uint8_t *)malloc(bytes))) {
        fprintf(stderr, "snell-render: out of memory for the reference's %dx%d frame\n", o->width, o->height);
        return 0;
    }
    if (snell_render(r, &plain, NULL) != SNELL_OK || snell_renderer_read_rgba(r, p->plain) != SNELL_OK) {
        fprintf(stderr, "snell-render: the frame beneath the panels: %s\n", snell_last_error(ctx));
        return 0;
    }
    flip_rows(p->plain, o->width, o->height);
    return 1;
}

int render_panels_reference(const render_options *o, const render_panels *p)
{
    size_t bytes = (size_t)o->width * (size_t)o->height * 4, len = strlen(o->out);
    uint8_t *out;
    char *path;
    snell_status st;
    int ok = 0;
    if (!o->reference) return 1;
    out = (uint8_t *)malloc(bytes);
    path = (char *)malloc(len + 16);
    if (!out || !path) {
        fprintf(stderr, "snell-render: out of memory for the reference\n");
        goto done;
    }
    /* FILE.png -> FILE_reference.png, beside it */
    memcpy(path, o->out, len + 1);
    if (len >= 4 && !strcmp(path + len - 4, ".png")) path[len - 4] = '\0';
    strcat(path, "_reference.png");
    st = snell_ref_panels(o->panels.panels, o->panels.count, p->texture ? p->image : p->plain, o->width, o->height, 0,
                          out);
    if (st != SNELL_OK) {
        fprintf(stderr, "snell-render: reference: %s\n", snell_last_error(NULL));
        goto done;
    }
    flip_rows(out, o->width, o->height);
    if (snell_write_png(path, o->width, o->height, out) != SNELL_OK) {
        fprintf(stderr, "snell-render: %s\n", snell_last_error(NULL));
        goto done;
    }
    printf("wrote %s (snell_ref_panels, %dx%d)\n", path, o->width, o->height);
    ok = 1;
done:
    free(out);
    free(path);
    return ok;
}

void render_panels_close(render_panels *p)
{
    if (p->texture) glDeleteTextures(1, &p->texture);
    snell_image_free(p->image);
    free(p->plain);
    memset(p, 0, sizeof *p);
}
