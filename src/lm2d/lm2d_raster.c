/* SPDX-License-Identifier: MIT */
/* lm2d_raster.c — GL_LINES rasterisation of light paths into the lightmap
 * accumulation texture (Brückner 6.5), with saved/restored GL state. */
#include "lm2d/lm2d_raster.h"

#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "core/program.h"

#include <math.h>
#include <string.h>

#define BATCH_LINES 65536
#define FLOATS_PER_VERTEX 5

#ifndef GL_UNSIGNED_INT_2_10_10_10_REV
#define GL_UNSIGNED_INT_2_10_10_10_REV 0x8368
#endif

struct lm2d_gl {
    snell_ctx *ctx;
    int width, height;
    snell_format2d format;
    snell_blend2d blend;
    GLuint tex, fbo, prog, vao, vbo;
    GLint u_size, u_quant, u_frame;
    float quant;               /* 0 for float targets */
    unsigned frame;
    float *verts;              /* BATCH_LINES * 2 vertices */
    void *readback;            /* width * height * 4 floats, allocated on the first read */
};

static snell_format2d pick_format(snell_ctx *ctx, snell_format2d want)
{
    /* float32 blending is an extension of its own in ES (EXT_float_blend) */
    int f32 = snell_ctx_has_gl_extension(ctx, "GL_EXT_color_buffer_float") &&
              snell_ctx_has_gl_extension(ctx, "GL_EXT_float_blend");
    int f16 = snell_ctx_has_gl_extension(ctx, "GL_EXT_color_buffer_half_float") ||
              snell_ctx_has_gl_extension(ctx, "GL_EXT_color_buffer_float");
    if (want == SNELL_FORMAT2D_AUTO) return f32 ? SNELL_FORMAT2D_RGBA32F : f16 ? SNELL_FORMAT2D_RGBA16F : SNELL_FORMAT2D_RGB10A2;
    if (want == SNELL_FORMAT2D_RGBA32F && !f32) return SNELL_FORMAT2D_AUTO;
    if (want == SNELL_FORMAT2D_RGBA16F && !f16) return SNELL_FORMAT2D_AUTO;
    return want;
}

snell_format2d lm2d_gl_format(const lm2d_gl *g) { return g->format; }
unsigned lm2d_gl_texture(const lm2d_gl *g) { return g ? g->tex : 0; }

void lm2d_gl_destroy(lm2d_gl *g)
{
    const snell_alloc *al;
    if (!g) return;
    al = snell__ctx_alloc(g->ctx);
    if (g->fbo) glDeleteFramebuffers(1, &g->fbo);
    if (g->tex) glDeleteTextures(1, &g->tex);
    if (g->prog) glDeleteProgram(g->prog);
    if (g->vao) glDeleteVertexArrays(1, &g->vao);
    if (g->vbo) glDeleteBuffers(1, &g->vbo);
    snell__free(al, g->verts);
    snell__free(al, g->readback);
    snell__free(al, g);
}

snell_status lm2d_gl_create(snell_ctx *ctx, int width, int height, snell_format2d format, snell_blend2d blend,
                            lm2d_gl **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    lm2d_gl *g;
    snell_format2d f;
    snell_glstate ss;
    GLint prev_tex;
    GLenum ifmt, type, status, err;
    snell_status st;
    *out = NULL;
    f = pick_format(ctx, format);
    if (f == SNELL_FORMAT2D_AUTO)
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "lightmap2d: format %d needs GL_EXT_color_buffer_%s",
                           (int)format, format == SNELL_FORMAT2D_RGBA32F ? "float + GL_EXT_float_blend" : "half_float");
    g = (lm2d_gl *)snell__calloc(al, 1, sizeof *g);
    if (!g) return snell__fail(ctx, SNELL_E_NOMEM, "lightmap2d: out of memory");
    g->ctx = ctx;
    g->width = width;
    g->height = height;
    g->format = f;
    g->blend = blend;
    g->quant = f == SNELL_FORMAT2D_RGB10A2 ? 1023.0f : f == SNELL_FORMAT2D_RGBA8 ? 255.0f : 0.0f;
    g->verts = (float *)snell__calloc(al, (size_t)BATCH_LINES * 2, FLOATS_PER_VERTEX * sizeof(float));
    if (!g->verts) {
        snell__free(al, g);
        return snell__fail(ctx, SNELL_E_NOMEM, "lightmap2d: out of memory");
    }
    snell__glstate_save(&ss); /* an earlier error waits outside: not this call's */
    st = snell__program_build(ctx, "lightmap2d/lines.vert", "lightmap2d/lines.frag", NULL, &g->prog);
    if (st != SNELL_OK) {
        snell__glstate_restore(&ss);
        lm2d_gl_destroy(g);
        return st;
    }
    g->u_size = glGetUniformLocation(g->prog, "u_size");
    g->u_quant = glGetUniformLocation(g->prog, "u_quant");
    g->u_frame = glGetUniformLocation(g->prog, "u_frame");
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &prev_tex);
    switch (f) {
    case SNELL_FORMAT2D_RGBA32F: ifmt = GL_RGBA32F; type = GL_FLOAT; break;
    case SNELL_FORMAT2D_RGBA16F: ifmt = GL_RGBA16F; type = GL_HALF_FLOAT; break;
    case SNELL_FORMAT2D_RGB10A2: ifmt = GL_RGB10_A2; type = GL_UNSIGNED_INT_2_10_10_10_REV; break;
    default: ifmt = GL_RGBA8; type = GL_UNSIGNED_BYTE; break;
    }
    glGenTextures(1, &g->tex);
    glBindTexture(GL_TEXTURE_2D, g->tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, ifmt, width, height);
    (void)type;
    snell__texture_nearest(GL_TEXTURE_2D, 0);
    glBindTexture(GL_TEXTURE_2D, (GLuint)prev_tex);
    glGenFramebuffers(1, &g->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, g->tex, 0);
    status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glGenVertexArrays(1, &g->vao);
    glGenBuffers(1, &g->vbo);
    glBindVertexArray(g->vao);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)BATCH_LINES * 2 * FLOATS_PER_VERTEX * sizeof(float), NULL,
                 GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, FLOATS_PER_VERTEX * sizeof(float), (const void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, FLOATS_PER_VERTEX * sizeof(float),
                          (const void *)(2 * sizeof(float)));
    err = glGetError();
    snell__glstate_restore(&ss);
    if (status != GL_FRAMEBUFFER_COMPLETE || err != GL_NO_ERROR) {
        lm2d_gl_destroy(g);
        return snell__fail(ctx, SNELL_E_GL, "lightmap2d: accumulation framebuffer (format %d): status 0x%x, GL error 0x%x",
                           (int)f, (unsigned)status, (unsigned)err);
    }
    *out = g;
    lm2d_gl_clear(g);
    return SNELL_OK;
}

void lm2d_gl_clear(lm2d_gl *g)
{
    GLint prev;
    GLfloat cc[4];
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST), mask[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &prev);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, cc);
    glGetBooleanv(GL_COLOR_WRITEMASK, mask);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, g->fbo);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glClearColor(cc[0], cc[1], cc[2], cc[3]);
    glColorMask(mask[0], mask[1], mask[2], mask[3]);
    if (scissor) glEnable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)prev);
}

snell_status lm2d_gl_draw(lm2d_gl *g, const lm2d_path *paths, size_t n, const lm2d_raster_view *v, float scale)
{
    snell_glstate ss;
    float sx = (float)v->width / (v->hi[0] - v->lo[0]), sy = (float)v->height / (v->hi[1] - v->lo[1]);
    size_t i = 0;
    GLenum err;
    if (n == 0) return SNELL_OK;
    snell__glstate_save(&ss);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, g->fbo);
    glViewport(0, 0, g->width, g->height);
    glUseProgram(g->prog);
    glUniform2f(g->u_size, (float)g->width, (float)g->height);
    glUniform1f(g->u_quant, g->quant);
    glBindVertexArray(g->vao);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    /* 6.5.3: plain sum, or "screen": dst = src + dst (1 - src) */
    glBlendFunc(GL_ONE, g->blend == SNELL_BLEND2D_SCREEN ? GL_ONE_MINUS_SRC_COLOR : GL_ONE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DITHER);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
    while (i < n) {
        size_t m = n - i < BATCH_LINES ? n - i : BATCH_LINES, j;
        float *p = g->verts;
        for (j = 0; j < m; j++) {
            const lm2d_path *q = &paths[i + j];
            float x0 = (q->x0 - v->lo[0]) * sx, y0 = (q->y0 - v->lo[1]) * sy;
            float x1 = (q->x1 - v->lo[0]) * sx, y1 = (q->y1 - v->lo[1]) * sy;
            float dx = fabsf(x1 - x0), dy = fabsf(y1 - y0), mx = dx > dy ? dx : dy;
            /* eq. 6.4: GL lights max(|px|,|py|) pixels for a line of length |p| */
            float c = mx > 0.0f ? sqrtf(dx * dx + dy * dy) / mx : 1.0f, k = scale;
            if (c < 1.0f) c = 1.0f;
            if (c > 1.41421356f) c = 1.41421356f;
            k *= c;
            p[0] = x0;
            p[1] = y0;
            p[2] = q->c0[0] * k;
            p[3] = q->c0[1] * k;
            p[4] = q->c0[2] * k;
            p[5] = x1;
            p[6] = y1;
            p[7] = q->c1[0] * k;
            p[8] = q->c1[1] * k;
            p[9] = q->c1[2] * k;
            p += 10;
        }
        glUniform1ui(g->u_frame, g->frame++);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(m * 2 * FLOATS_PER_VERTEX * sizeof(float)), g->verts);
        glDrawArrays(GL_LINES, 0, (GLsizei)(m * 2));
        i += m;
    }
    err = glGetError();
    snell__glstate_restore(&ss);
    if (err != GL_NO_ERROR) return snell__fail(g->ctx, SNELL_E_GL, "lightmap2d: GL error 0x%x drawing paths", (unsigned)err);
    return SNELL_OK;
}

snell_status lm2d_gl_read(lm2d_gl *g, float *rgb, float scale)
{
    const snell_alloc *al = snell__ctx_alloc(g->ctx);
    GLint prev;
    snell__pixel_store pack;
    int x, y, w = g->width, h = g->height;
    GLenum err;
    unsigned host_errors;
    if (!g->readback) {
        g->readback = snell__calloc(al, (size_t)w * (size_t)h, 4 * sizeof(float));
        if (!g->readback) return snell__fail(g->ctx, SNELL_E_NOMEM, "lightmap2d: out of memory for readback");
    }
    host_errors = snell__gl_errors_take();
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev);
    snell__pixel_pack_begin(&pack, 4); /* client memory, whatever pixel buffer the host bound */
    glBindFramebuffer(GL_READ_FRAMEBUFFER, g->fbo);
    if (g->quant == 0.0f) glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, g->readback);
    else if (g->format == SNELL_FORMAT2D_RGB10A2)
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV, g->readback);
    else glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, g->readback);
    snell__pixel_pack_end(&pack);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)prev);
    err = glGetError();
    snell__gl_errors_give(host_errors);
    if (err != GL_NO_ERROR) return snell__fail(g->ctx, SNELL_E_GL, "lightmap2d: GL error 0x%x reading the lightmap", (unsigned)err);
    /* GL rows are bottom first; the lightmap is stored top row first */
    for (y = 0; y < h; y++) {
        float *dst = rgb + 3 * (size_t)(h - 1 - y) * (size_t)w;
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            if (g->quant == 0.0f) {
                const float *s = (const float *)g->readback + 4 * i;
                dst[3 * x] = s[0] * scale;
                dst[3 * x + 1] = s[1] * scale;
                dst[3 * x + 2] = s[2] * scale;
            } else if (g->format == SNELL_FORMAT2D_RGB10A2) {
                uint32_t p = ((const uint32_t *)g->readback)[i];
                dst[3 * x] = (float)(p & 1023u) / 1023.0f * scale;
                dst[3 * x + 1] = (float)((p >> 10) & 1023u) / 1023.0f * scale;
                dst[3 * x + 2] = (float)((p >> 20) & 1023u) / 1023.0f * scale;
            } else {
                const uint8_t *s = (const uint8_t *)g->readback + 4 * i;
                dst[3 * x] = (float)s[0] / 255.0f * scale;
                dst[3 * x + 1] = (float)s[1] / 255.0f * scale;
                dst[3 * x + 2] = (float)s[2] / 255.0f * scale;
            }
        }
    }
    return SNELL_OK;
}

void lm2d_gl_finish(lm2d_gl *g)
{
    (void)g;
    glFinish();
}

snell_status lm2d_gl_upload(lm2d_gl *g, const float *img, float mul, int one_minus)
{
    const snell_alloc *al = snell__ctx_alloc(g->ctx);
    GLint prev_tex, unpack_buf, align, row_len, skip_rows, skip_px;
    size_t i, n = (size_t)g->width * (size_t)g->height;
    const void *data = img;
    unsigned host_errors;
    GLenum err;
    if (g->quant != 0.0f || one_minus || mul != 1.0f) {
        if (!g->readback) {
            g->readback = snell__calloc(al, n, 4 * sizeof(float));
            if (!g->readback) return snell__fail(g->ctx, SNELL_E_NOMEM, "lightmap2d: out of memory for the upload");
        }
        data = g->readback;
        for (i = 0; i < n; i++) {
            const float *s = img + LM2D_RASTER_PX * i;
            float v[3];
            int k;
            for (k = 0; k < 3; k++) v[k] = one_minus ? 1.0f - s[k] : s[k] * mul;
            if (g->quant == 0.0f) {
                float *d = (float *)g->readback + 4 * i;
                d[0] = v[0];
                d[1] = v[1];
                d[2] = v[2];
                d[3] = 0.0f;
            } else {
                uint32_t c[3];
                for (k = 0; k < 3; k++) {
                    float x = v[k] > 0.0f ? (v[k] < 1.0f ? v[k] : 1.0f) : 0.0f;
                    c[k] = (uint32_t)(x * g->quant + 0.5f);
                }
                ((uint32_t *)g->readback)[i] = g->format == SNELL_FORMAT2D_RGB10A2
                                                   ? c[0] | c[1] << 10 | c[2] << 20
                                                   : c[0] | c[1] << 8 | c[2] << 16;
            }
        }
    }
    host_errors = snell__gl_errors_take(); /* the host's wait outside (core/glstate.h) */
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &prev_tex);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_buf);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &align);
    glGetIntegerv(GL_UNPACK_ROW_LENGTH, &row_len);
    glGetIntegerv(GL_UNPACK_SKIP_ROWS, &skip_rows);
    glGetIntegerv(GL_UNPACK_SKIP_PIXELS, &skip_px);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glBindTexture(GL_TEXTURE_2D, g->tex);
    if (g->quant == 0.0f)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, g->width, g->height, GL_RGBA, GL_FLOAT, data);
    else if (g->format == SNELL_FORMAT2D_RGB10A2)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, g->width, g->height, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV, data);
    else glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, g->width, g->height, GL_RGBA, GL_UNSIGNED_BYTE, data);
    glBindTexture(GL_TEXTURE_2D, (GLuint)prev_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, align);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, row_len);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, skip_rows);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, skip_px);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, (GLuint)unpack_buf);
    err = glGetError();
    snell__gl_errors_give(host_errors);
    if (err != GL_NO_ERROR)
        return snell__fail(g->ctx, SNELL_E_GL, "lightmap2d: GL error 0x%x uploading the lightmap", (unsigned)err);
    return SNELL_OK;
}
