/* SPDX-License-Identifier: MIT */
/* ssaa.c — supersampling resolve; see ssaa.h. */
#include "render/ssaa.h"
#include "render/stages.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"

#include <stdio.h>
#include <string.h>

snell_status snell__ssaa_create(snell_ctx *ctx, snell__ssaa *s, int factor, int w, int h)
{
    char def[64];
    GLenum status;
    snell_status st;
    memset(s, 0, sizeof *s);
    s->factor = factor;
    if (factor <= 1) return SNELL_OK;
    glGenTextures(1, &s->frame_tex);
    glBindTexture(GL_TEXTURE_2D, s->frame_tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, w * factor, h * factor);
    snell__texture_nearest(GL_TEXTURE_2D, 0);
    glGenRenderbuffers(1, &s->resolve_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, s->resolve_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glGenFramebuffers(1, &s->resolve_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->resolve_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s->resolve_rb);
    status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return snell__fail(ctx, SNELL_E_GL, "SSAA resolve %dx%d framebuffer incomplete (0x%x)", w, h, (unsigned)status);
    snprintf(def, sizeof def, "#define SNELL_SSAA %d\n", factor);
    st = snell__program_build(ctx, "skybox.vert", "ssaa_resolve.frag", def, &s->prog);
    if (st != SNELL_OK) return st;
    s->u_frame = glGetUniformLocation(s->prog, "u_frame");
    glGenVertexArrays(1, &s->vao);
    return glGetError() == GL_NO_ERROR
               ? SNELL_OK
               : snell__fail(ctx, SNELL_E_GL, "GL error creating the %dx SSAA targets (%dx%d)", factor, w, h);
}

void snell__ssaa_destroy(snell__ssaa *s)
{
    if (s->frame_tex) glDeleteTextures(1, &s->frame_tex);
    if (s->resolve_rb) glDeleteRenderbuffers(1, &s->resolve_rb);
    if (s->resolve_fbo) glDeleteFramebuffers(1, &s->resolve_fbo);
    if (s->prog) glDeleteProgram(s->prog);
    if (s->vao) glDeleteVertexArrays(1, &s->vao);
    memset(s, 0, sizeof *s);
}

void snell__ssaa_resolve(const snell__ssaa *s, int w, int h)
{
    glBindFramebuffer(GL_FRAMEBUFFER, s->resolve_fbo);
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glUseProgram(s->prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, s->frame_tex);
    glUniform1i(s->u_frame, 0);
    glBindVertexArray(s->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindTexture(GL_TEXTURE_2D, 0);
}

/* The ssaa stage: the frame's size (S times the output's per axis) and, at
 * the renderer's creation, its colour texture; after each frame the samples
 * averaged into the output. */
static snell_status validate_renderer(snell__services *sv, const snell_renderer_desc *d)
{
    int side = d->ssaa * (d->width > d->height ? d->width : d->height);
    snell_ctx *ctx = sv->ctx;
    snell_status st;
    if (d->ssaa < 0 || d->ssaa > SNELL_MAX_SSAA)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "ssaa %d outside 0..%d", d->ssaa, SNELL_MAX_SSAA);
    if (d->ssaa <= 1) return SNELL_OK;
    if (d->target != SNELL_TARGET_OFFSCREEN || d->output != SNELL_OUTPUT_COLOR)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "ssaa %d needs an offscreen colour renderer", d->ssaa);
    st = snell__ctx_limit(ctx, SNELL__LIM_TEXTURE, side, "render size x ssaa");
    if (st == SNELL_OK) st = snell__ctx_limit(ctx, SNELL__LIM_RENDERBUFFER, side, "render size x ssaa");
    sv->width = d->width * d->ssaa;
    sv->height = d->height * d->ssaa;
    return st;
}

static snell_status create(snell__services *sv, const snell_renderer_desc *d, void *state)
{
    snell__ssaa *s = (snell__ssaa *)state;
    snell_status st = snell__ssaa_create(sv->ctx, s, d->ssaa > 1 ? d->ssaa : 1, sv->out_width, sv->out_height);
    if (st != SNELL_OK || s->factor <= 1) return st;
    sv->color_texture = s->frame_tex;
    sv->read_fbo = s->resolve_fbo;
    return SNELL_OK;
}

static void destroy(snell_ctx *ctx, void *state)
{
    (void)ctx;
    snell__ssaa_destroy((snell__ssaa *)state);
}

static int stage_wanted(const snell__frame *f, const void *state)
{
    (void)f;
    return ((const snell__ssaa *)state)->factor > 1;
}

static snell_status stage_run(snell__frame *f, void *state)
{
    snell__ssaa_resolve((const snell__ssaa *)state, f->sv->out_width, f->sv->out_height);
    f->s->passes++;
    return SNELL_OK;
}

const snell__stage snell__stage_ssaa = {
    .name = "ssaa",
    .state_size = sizeof(snell__ssaa),
    .validate_renderer = validate_renderer,
    .create = create,
    .destroy = destroy,
    .wanted = stage_wanted,
    .run = stage_run,
};
