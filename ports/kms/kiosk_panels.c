/* SPDX-License-Identifier: MIT */
/* kiosk_panels.c — glass panels over the kiosk's frame (kiosk.h): over the
 * configured scene as snell draws it, or over a slideshow of pictures, each
 * uploaded as a GL texture when it comes on and drawn by the frame under
 * its panels (SNELL_PANELS_UNDER_TEXTURE). */
#include "kiosk.h"
#include "cli_input.h"

#include <GLES3/gl3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void kiosk_panels_open(kiosk_panels *kp, const kiosk_options *o)
{
    memset(kp, 0, sizeof *kp);
    kp->o = o;
    kp->slide = -1;
}

/* Slide i into the texture: decoded, rows turned bottom first for GL. */
static int load_slide(kiosk_panels *kp, int i, char *msg, size_t n)
{
    const char *path = kp->o->slides[i];
    uint8_t *rgba = NULL, *row;
    char safe[256];
    int w, h, y;
    size_t stride;
    if (snell_image_read(path, &w, &h, &rgba) != SNELL_OK)
        return snprintf(msg, n, "--slide %s: %s", cli_safe(path, safe, sizeof safe), snell_last_error(NULL)), 0;
    stride = (size_t)w * 4;
    if (!(row = (uint8_t *)malloc(stride))) {
        snell_image_free(rgba);
        return snprintf(msg, n, "out of memory for --slide %s", cli_safe(path, safe, sizeof safe)), 0;
    }
    for (y = 0; y < h / 2; y++) {
        memcpy(row, rgba + (size_t)y * stride, stride);
        memcpy(rgba + (size_t)y * stride, rgba + (size_t)(h - 1 - y) * stride, stride);
        memcpy(rgba + (size_t)(h - 1 - y) * stride, row, stride);
    }
    free(row);
    if (!kp->texture) glGenTextures(1, &kp->texture);
    glBindTexture(GL_TEXTURE_2D, kp->texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    snell_image_free(rgba);
    if (glGetError() != GL_NO_ERROR)
        return snprintf(msg, n, "--slide %s: GL refused a %dx%d texture", cli_safe(path, safe, sizeof safe), w, h), 0;
    kp->slide = i;
    return 1;
}

int kiosk_panels_frame(kiosk_panels *kp, double t_s, snell_frame_desc *fd, char *msg, size_t n)
{
    const kiosk_options *o = kp->o;
    int due;
    if (!o->panels.count) return 1;
    if (o->slide_count) {
        snell_depth_mode depth = fd->depth;
        due = (int)fmod(floor(t_s / o->slide_s), (double)o->slide_count);
        if (due != kp->slide && !load_slide(kp, due, msg, n)) return 0;
        /* a frame of panels only: the picture is all that lies beneath */
        memset(fd, 0, sizeof *fd);
        fd->depth = depth;
        fd->draw_background = SNELL_BACKGROUND_NONE;
        kp->under.source = SNELL_PANELS_UNDER_TEXTURE;
        kp->under.texture = kp->texture;
        kp->under.draw = 1;
        fd->panels_under = &kp->under;
    }
    fd->panels = o->panels.panels;
    fd->panel_count = o->panels.count;
    return 1;
}

void kiosk_panels_close(kiosk_panels *kp)
{
    if (kp->texture) glDeleteTextures(1, &kp->texture);
    kp->texture = 0;
    kp->slide = -1;
}
