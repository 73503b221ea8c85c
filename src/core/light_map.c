/* SPDX-License-Identifier: MIT */
/* light_map.c — the light maps' format policy (light_map.h): RGBA32F where
 * float targets blend, else RGB10_A2 over a fixed range. */
#include "core/light_map.h"
#include "core/glstate.h"
#include "core/gl.h"
#include "core/core.h"
#include "core/ctx.h"

#include <string.h>

unsigned snell__light_map_format(snell_ctx *ctx)
{
    return snell__light_fixed(ctx) ? GL_RGB10_A2 : GL_RGBA32F;
}

void snell__light_map_image(unsigned format, int size)
{
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)format, size, size, 0, GL_RGBA,
                 format == GL_RGBA32F   ? GL_FLOAT
                 : format == GL_RGBA16F ? GL_HALF_FLOAT
                                        : GL_UNSIGNED_INT_2_10_10_10_REV,
                 NULL);
}

const char *snell__light_map_str(unsigned format)
{
    return format == GL_RGBA32F ? "RGBA32F" : format == GL_RGBA16F ? "RGBA16F" : "RGB10_A2";
}

snell_status snell__read_light_map(snell_ctx *ctx, unsigned format, unsigned fbo, int size, float *rgba,
                                   const char *what)
{
    GLint prev = 0;
    snell__pixel_store pack;
    size_t i;
    int fixed = format == GL_RGB10_A2;
    unsigned host_errors = snell__gl_errors_take(); /* the host's wait outside (core/glstate.h) */
    GLenum err;
    glFinish();
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    snell__pixel_pack_begin(&pack, 4);
    /* GLES 3.0 reads RGB10_A2 as RGBA / UNSIGNED_INT_2_10_10_10_REV: packed
     * into the front of rgba, widened in place from the last pixel */
    glReadPixels(0, 0, size, size, GL_RGBA, fixed ? GL_UNSIGNED_INT_2_10_10_10_REV : GL_FLOAT, rgba);
    snell__pixel_pack_end(&pack);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)prev);
    for (i = fixed ? (size_t)size * (size_t)size : 0; i-- > 0;) {
        uint32_t p;
        memcpy(&p, (const char *)rgba + 4 * i, 4);
        rgba[4 * i + 0] = (float)(p & 1023u) / 1023.0f * SNELL__LIGHT_RANGE;
        rgba[4 * i + 1] = (float)(p >> 10 & 1023u) / 1023.0f * SNELL__LIGHT_RANGE;
        rgba[4 * i + 2] = (float)(p >> 20 & 1023u) / 1023.0f * SNELL__LIGHT_RANGE;
        rgba[4 * i + 3] = (float)(p >> 30) / 3.0f;
    }
    err = glGetError();
    snell__gl_errors_give(host_errors);
    return err == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "reading %s failed", what);
}
