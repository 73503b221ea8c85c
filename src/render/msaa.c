/* SPDX-License-Identifier: MIT */
/* msaa.c — the msaa stage (snell_renderer_desc.msaa = N): the offscreen
 * target's colour and depth get N samples a pixel, and after each frame a
 * blit resolves them, the samples' mean, into the single-sample image that
 * snell_renderer_read_rgba reads. */
#include "render/stages.h"
#include "core/ctx.h"
#include "core/gl.h"

typedef struct msaa_state {
    int samples;                    /* 0: off */
    unsigned fbo, rb;               /* the single-sample image it resolves into */
} msaa_state;

static snell_status validate_renderer(snell__services *sv, const snell_renderer_desc *d)
{
    snell_ctx *ctx = sv->ctx;
    if (d->msaa < 0 || (d->msaa > 1 && (d->target != SNELL_TARGET_OFFSCREEN || d->output != SNELL_OUTPUT_COLOR)))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "msaa %d needs an offscreen colour renderer (0 or 1 = off)",
                           d->msaa);
    if (d->msaa > 1 && d->ssaa > 1)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "msaa %d and ssaa %d: one antialiasing at a time", d->msaa,
                           d->ssaa);
    sv->samples = d->msaa > 1 ? d->msaa : 0;
    return sv->samples ? snell__ctx_limit(ctx, SNELL__LIM_SAMPLES, d->msaa, "msaa") : SNELL_OK;
}

static snell_status create(snell__services *sv, const snell_renderer_desc *d, void *state)
{
    msaa_state *m = (msaa_state *)state;
    GLenum status;
    (void)d; /* validate_renderer() read it into sv->samples */
    if (!sv->samples) return SNELL_OK;
    m->samples = sv->samples;
    glGenRenderbuffers(1, &m->rb);
    glBindRenderbuffer(GL_RENDERBUFFER, m->rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, sv->width, sv->height);
    glGenFramebuffers(1, &m->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, m->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m->rb);
    status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return snell__fail(sv->ctx, SNELL_E_GL, "MSAA resolve %dx%d framebuffer incomplete (0x%x)", sv->width,
                           sv->height, (unsigned)status);
    sv->read_fbo = m->fbo;
    return SNELL_OK;
}

static void destroy(snell_ctx *ctx, void *state)
{
    msaa_state *m = (msaa_state *)state;
    (void)ctx;
    if (m->fbo) glDeleteFramebuffers(1, &m->fbo);
    if (m->rb) glDeleteRenderbuffers(1, &m->rb);
}

static int wanted(const snell__frame *f, const void *state)
{
    (void)f;
    return ((const msaa_state *)state)->samples != 0;
}

static snell_status run(snell__frame *f, void *state)
{
    const snell__services *sv = f->sv;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, sv->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, ((const msaa_state *)state)->fbo);
    glBlitFramebuffer(0, 0, sv->width, sv->height, 0, 0, sv->width, sv->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    f->s->passes++;
    return SNELL_OK;
}

const snell__stage snell__stage_msaa = {
    .name = "msaa",
    .state_size = sizeof(msaa_state),
    .validate_renderer = validate_renderer,
    .create = create,
    .destroy = destroy,
    .wanted = wanted,
    .run = run,
};
