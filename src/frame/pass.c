/* SPDX-License-Identifier: MIT */
/* pass.c — see pass.h. The state saved is what passes change and what the
 * frame around them relies on. Not the program: every draw binds its own,
 * and the current one may be a deleted program kept alive only by being
 * current, whose name would be invalid by the time it was restored. */
#include "frame/pass.h"
#include "core/gl.h"

void snell__pass_begin(snell__pass *p, unsigned fbo, int width, int height, unsigned clear, int depth_func,
                       float clear_depth)
{
    GLboolean b;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &p->fbo);
    glGetIntegerv(GL_VIEWPORT, p->viewport);
    glGetIntegerv(GL_DEPTH_FUNC, &p->depth_func);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &p->active_texture);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &b);
    p->depth_mask = b;
    p->depth_test = glIsEnabled(GL_DEPTH_TEST);
    p->cull_face = glIsEnabled(GL_CULL_FACE);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, p->clear_color);
    glGetFloatv(GL_DEPTH_CLEAR_VALUE, &p->clear_depth);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc((GLenum)depth_func);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClearDepthf(clear_depth);
    if (clear) glClear(clear);
}

void snell__pass_end(const snell__pass *p)
{
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)p->fbo);
    glViewport(p->viewport[0], p->viewport[1], p->viewport[2], p->viewport[3]);
    glDepthFunc((GLenum)p->depth_func);
    glDepthMask(p->depth_mask);
    if (p->depth_test) glEnable(GL_DEPTH_TEST);
    else glDisable(GL_DEPTH_TEST);
    if (p->cull_face) glEnable(GL_CULL_FACE);
    else glDisable(GL_CULL_FACE);
    glClearColor(p->clear_color[0], p->clear_color[1], p->clear_color[2], p->clear_color[3]);
    glClearDepthf(p->clear_depth);
    glActiveTexture((GLenum)p->active_texture);
}
