/* SPDX-License-Identifier: MIT */
/* host_depth.c — see host_depth.h. */
#include "render/host_depth.h"
#include "render/host_target.h"
#include "core/gl.h"

#include <string.h>

snell_depth_mode snell__depth_mode_of(snell_depth_mode asked, snell_target target)
{
    if (asked != SNELL_DEPTH_DEFAULT) return asked;
    return target == SNELL_TARGET_OFFSCREEN ? SNELL_DEPTH_CLEAR : SNELL_DEPTH_TEST;
}

unsigned snell__host_depth_format(int fbo)
{
    /* A missing attachment's size is an error to ask, for the default
     * framebuffer too (GLES 3.0 6.1.13): its type is asked first. */
    GLenum d = fbo ? GL_DEPTH_ATTACHMENT : GL_DEPTH, st = fbo ? GL_STENCIL_ATTACHMENT : GL_STENCIL;
    GLint depth = 0, stencil = 0, type = 0;
    if (snell__fb_attachment(d, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) != GL_NONE) {
        depth = snell__fb_attachment(d, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE);
        type = snell__fb_attachment(d, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE);
    }
    if (depth && snell__fb_attachment(st, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) != GL_NONE)
        stencil = snell__fb_attachment(st, GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE);
    if (type == GL_FLOAT && depth == 32) return stencil ? GL_DEPTH32F_STENCIL8 : GL_DEPTH_COMPONENT32F;
    if (depth == 24) return stencil ? GL_DEPTH24_STENCIL8 : GL_DEPTH_COMPONENT24;
    if (depth == 16 && !stencil) return GL_DEPTH_COMPONENT16;
    return 0;
}

/* A packed depth-stencil copied whole: its depth alone may be copied through
 * float, which rounds 24-bit values (Mesa); the stencil snell never writes. */
static GLbitfield copy_bits(unsigned format)
{
    return GL_DEPTH_BUFFER_BIT |
           (format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8 ? GL_STENCIL_BUFFER_BIT : 0);
}

snell_status snell__host_depth_begin(snell_ctx *ctx, snell__host_depth *d, snell_depth_mode mode, int width,
                                     int height)
{
    GLint fbo = 0, samples = 0;
    unsigned format;
    d->saved = 0;
    if (mode == SNELL_DEPTH_CLEAR) {
        glDepthMask(GL_TRUE);
        glClearDepthf(1.0f);
        glClear(GL_DEPTH_BUFFER_BIT);
        return SNELL_OK;
    }
    if (mode != SNELL_DEPTH_TEST_NO_WRITE) return SNELL_OK;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_SAMPLE_BUFFERS, &samples);
    if (samples > 0)
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "SNELL_DEPTH_TEST_NO_WRITE: the bound framebuffer is "
                           "multisampled; its depth cannot be copied back (use SNELL_DEPTH_TEST)");
    format = snell__host_depth_format(fbo);
    if (!format)
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "SNELL_DEPTH_TEST_NO_WRITE: the bound framebuffer has no depth "
                           "buffer of a format that can be copied (16, 24 or 32F bits)");
    if (!d->rb || d->format != format || d->width != width || d->height != height) {
        snell__host_depth_destroy(d);
        glGenRenderbuffers(1, &d->rb);
        glBindRenderbuffer(GL_RENDERBUFFER, d->rb);
        glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
        glGenFramebuffers(1, &d->fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, d->fbo);
        glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER,
                                  format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8
                                      ? GL_DEPTH_STENCIL_ATTACHMENT
                                      : GL_DEPTH_ATTACHMENT,
                                  GL_RENDERBUFFER, d->rb);
        d->format = format;
        d->width = width;
        d->height = height;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, d->fbo);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, copy_bits(format), GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    if (glGetError() != GL_NO_ERROR) {
        snell__host_depth_destroy(d);
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "SNELL_DEPTH_TEST_NO_WRITE: copying the bound framebuffer's "
                           "depth (format 0x%x, %dx%d) failed", format, width, height);
    }
    d->target_fbo = (unsigned)fbo;
    d->saved = 1;
    return SNELL_OK;
}

snell_status snell__host_depth_end(snell_ctx *ctx, snell__host_depth *d)
{
    if (!d->saved) return SNELL_OK;
    d->saved = 0;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, d->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, d->target_fbo);
    glBlitFramebuffer(0, 0, d->width, d->height, 0, 0, d->width, d->height, copy_bits(d->format), GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, d->target_fbo);
    return glGetError() == GL_NO_ERROR ? SNELL_OK
                                       : snell__fail(ctx, SNELL_E_GL, "SNELL_DEPTH_TEST_NO_WRITE: giving the depth back failed");
}

void snell__host_depth_destroy(snell__host_depth *d)
{
    if (d->fbo) glDeleteFramebuffers(1, &d->fbo);
    if (d->rb) glDeleteRenderbuffers(1, &d->rb);
    memset(d, 0, sizeof *d);
}
