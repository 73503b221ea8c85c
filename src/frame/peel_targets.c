/* SPDX-License-Identifier: MIT */
/* peel_targets.c — see peel_targets.h. */
#include "frame/peel_targets.h"
#include "core/ctx.h"
#include "core/gl.h"

void snell__peel_targets_release(snell__peel_targets *t)
{
    if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
    if (t->array_tex) glDeleteTextures(1, &t->array_tex);
    if (t->next_tex[0]) glDeleteTextures(2, t->next_tex);
    if (t->depth_rb) glDeleteRenderbuffers(1, &t->depth_rb);
    if (t->query) glDeleteQueries(1, &t->query);
    t->fbo = t->array_tex = t->next_tex[0] = t->next_tex[1] = t->depth_rb = t->query = 0;
    t->width = t->height = t->capacity = 0;
}

snell_status snell__peel_targets_ensure(snell_ctx *ctx, snell__peel_targets *t, int w, int h, int layers, int unit,
                                        const char *what, int *remade)
{
    int i;
    *remade = 0;
    if (t->fbo && t->width >= w && t->height >= h && t->capacity >= layers) return SNELL_OK;
    snell__peel_targets_release(t);
    *remade = 1;
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glGenTextures(1, &t->array_tex);
    glBindTexture(GL_TEXTURE_2D_ARRAY, t->array_tex);
    snell__texture_nearest(GL_TEXTURE_2D_ARRAY, 1);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA8, w, h, 2 * layers);
    glGenTextures(2, t->next_tex);
    for (i = 0; i < 2; i++) {
        glBindTexture(GL_TEXTURE_2D, t->next_tex[i]);
        snell__texture_nearest(GL_TEXTURE_2D, 1);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, w, h);
    }
    glActiveTexture(GL_TEXTURE0);
    glGenRenderbuffers(1, &t->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, t->depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glGenFramebuffers(1, &t->fbo);
    glGenQueries(1, &t->query);
    t->width = w;
    t->height = h;
    t->capacity = layers;
    if (glGetError() != GL_NO_ERROR) {
        snell__peel_targets_release(t);
        return snell__fail(ctx, SNELL_E_GL, "GL error creating %d %s of %dx%d", layers, what, w, h);
    }
    return SNELL_OK;
}

snell_status snell__peel_layer_begin(snell_ctx *ctx, const snell__peel_targets *t, int k)
{
    static const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    static const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t->array_tex, 0, 2 * k);
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, t->array_tex, 0, 2 * k + 1);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D, t->next_tex[k & 1], 0);
    glDrawBuffers(3, bufs);
    if (k == 0) {
        GLenum fst = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (fst != GL_FRAMEBUFFER_COMPLETE)
            return snell__fail(ctx, SNELL_E_GL, "peel framebuffer incomplete (0x%x)", (unsigned)fst);
    }
    /* flag/id 0 marks empty texels; the previous layer is read, not written */
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfv(GL_COLOR, 1, zero);
    glClearBufferfv(GL_COLOR, 2, zero);
    glClear(GL_DEPTH_BUFFER_BIT);
    glBindTexture(GL_TEXTURE_2D, t->next_tex[(k + 1) & 1]);
    return SNELL_OK;
}
