/* SPDX-License-Identifier: MIT */
/* host_depth_map.c — see host_depth_map.h. */
#include "render/host_depth_map.h"
#include "render/host_depth.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"

#include <string.h>

#ifdef SNELL_WITH_HOST_FRAMEBUFFERS
static void depth_texture(unsigned tex, unsigned format, int w, int h)
{
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
}

static GLenum depth_attachment(unsigned format)
{
    return format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8 ? GL_DEPTH_STENCIL_ATTACHMENT
                                                                          : GL_DEPTH_ATTACHMENT;
}

/* The copies and programs, made on first use and when the host's format or the size changes. */
static snell_status prepare(snell_ctx *ctx, snell__depth_map *m, unsigned format, int w, int h)
{
    snell_status st = SNELL_OK;
    if (!m->prog[0]) st = snell__program_build(ctx, "screen.vert", "host_depth_map.frag", NULL, &m->prog[0]);
    if (st == SNELL_OK && !m->prog[1])
        st = snell__program_build(ctx, "screen.vert", "host_depth_map.frag", "#define SNELL_DEPTH_BACK 1\n", &m->prog[1]);
    if (st != SNELL_OK) return st;
    if (!m->vao) glGenVertexArrays(1, &m->vao);
    if (m->host_tex && m->host_format == format && m->size[0] == w && m->size[1] == h) return SNELL_OK;
    if (m->host_tex) glDeleteTextures(1, &m->host_tex), glDeleteTextures(1, &m->before_tex);
    if (m->host_fbo) glDeleteFramebuffers(1, &m->host_fbo), glDeleteFramebuffers(1, &m->before_fbo);
    glGenTextures(1, &m->host_tex);
    glGenTextures(1, &m->before_tex);
    glGenFramebuffers(1, &m->host_fbo);
    glGenFramebuffers(1, &m->before_fbo);
    depth_texture(m->host_tex, format, w, h);
    depth_texture(m->before_tex, GL_DEPTH_COMPONENT32F, w, h);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m->host_fbo);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, depth_attachment(format), GL_TEXTURE_2D, m->host_tex, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m->before_fbo);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, m->before_tex, 0);
    m->host_format = format, m->size[0] = w, m->size[1] = h;
    return SNELL_OK;
}

/* Draws prog over the bound framebuffer's rect, writing depth only. */
static void draw(const snell__depth_map *m, int back, unsigned tex, const int rect[4], const double map[2],
                 const float far_[2])
{
    GLuint prog = m->prog[back];
    glViewport(rect[0], rect[1], rect[2], rect[3]);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glUseProgram(prog);
    glBindVertexArray(m->vao);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex);
    glUniform1i(glGetUniformLocation(prog, "u_depth"), 0);
    if (back) {
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D, m->before_tex);
        glUniform1i(glGetUniformLocation(prog, "u_before"), 1);
        glActiveTexture(GL_TEXTURE0);
    }
    glUniform2f(glGetUniformLocation(prog, "u_map"), (float)map[0], (float)map[1]);
    glUniform2f(glGetUniformLocation(prog, "u_far"), far_[0], far_[1]);
    glUniform2i(glGetUniformLocation(prog, "u_offset"), rect[0], rect[1]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_LESS);
}

snell_status snell__depth_map_in(snell_ctx *ctx, snell__depth_map *m, unsigned host_fbo, const int rect[4],
                                 unsigned copy_fbo)
{
    /* Snell's far plane is 1; the host's is where its depth runs to: 0 reversed. */
    const float far_[2] = {m->map[0] < 0.0 ? 0.0f : 1.0f, 1.0f};
    const int at0[4] = {0, 0, rect[2], rect[3]};
    unsigned format;
    snell_status st;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, host_fbo);
    format = snell__host_depth_format((int)host_fbo);
    if (!format)
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "snell_render: a reversed-Z camera needs a depth buffer a blit "
                           "can copy (16, 24 or 32F bits) to map its depth");
    if ((st = prepare(ctx, m, format, rect[2], rect[3])) != SNELL_OK) return st;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, host_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m->host_fbo);
    glBlitFramebuffer(rect[0], rect[1], rect[0] + rect[2], rect[1] + rect[3], 0, 0, rect[2], rect[3],
                      GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, copy_fbo);
    draw(m, 0, m->host_tex, at0, m->map, far_);
    /* What the frame starts from, to tell the pixels it changed. */
    glBindFramebuffer(GL_READ_FRAMEBUFFER, copy_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m->before_fbo);
    glBlitFramebuffer(0, 0, rect[2], rect[3], 0, 0, rect[2], rect[3], GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, copy_fbo);
    return glGetError() == GL_NO_ERROR ? SNELL_OK
                                       : snell__fail(ctx, SNELL_E_GL, "snell_render: mapping the host's depth failed");
}

snell_status snell__depth_map_back(snell_ctx *ctx, snell__depth_map *m, unsigned host_fbo, const int rect[4],
                                   unsigned copy_depth)
{
    const double back[2] = {1.0 / m->map[0], -m->map[1] / m->map[0]};
    const float far_[2] = {1.0f, m->map[0] < 0.0 ? 0.0f : 1.0f};
    glBindFramebuffer(GL_FRAMEBUFFER, host_fbo);
    draw(m, 1, copy_depth, rect, back, far_);
    return glGetError() == GL_NO_ERROR ? SNELL_OK
                                       : snell__fail(ctx, SNELL_E_GL, "snell_render: giving the host its depth failed");
}

void snell__depth_map_destroy(snell__depth_map *m)
{
    if (m->host_tex) glDeleteTextures(1, &m->host_tex), glDeleteTextures(1, &m->before_tex);
    if (m->host_fbo) glDeleteFramebuffers(1, &m->host_fbo), glDeleteFramebuffers(1, &m->before_fbo);
    if (m->prog[0]) glDeleteProgram(m->prog[0]);
    if (m->prog[1]) glDeleteProgram(m->prog[1]);
    if (m->vao) glDeleteVertexArrays(1, &m->vao);
    memset(m, 0, sizeof *m);
}
#endif
