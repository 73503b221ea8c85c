/* SPDX-License-Identifier: MIT */
/* glass_scale.c — see glass_scale.h. The object's method draws as at full
 * resolution in screen space, into a view whose grid is the frame's divided by
 * the scale (every pass costs 1/scale^2 of its fragments); the full-resolution
 * pass then shades each of its pixels once more with a few texture reads, so
 * coverage and depth test are exactly as unscaled. The error it adds is the
 * supersampling it gives up. More: docs/ARCHITECTURE.md, "Design notes by
 * file". */
#include "render/glass_scale.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "frame/pass.h"

#include <math.h>
#include <string.h>

/* Texels around the object's rectangle cleared too: glass_scale.frag reads
 * up to two beyond the texel under a covered pixel. */
#define READ_MARGIN 2

static void release_target(snell__glass_scale *gs)
{
    if (gs->fbo) glDeleteFramebuffers(1, &gs->fbo);
    if (gs->color_tex) glDeleteTextures(1, &gs->color_tex);
    if (gs->depth_tex) glDeleteTextures(1, &gs->depth_tex);
    gs->fbo = gs->color_tex = gs->depth_tex = 0;
    gs->width = gs->height = 0;
}

void snell__glass_scale_destroy(snell__glass_scale *gs)
{
    int i;
    release_target(gs);
    snell__gbuffer_destroy(&gs->gbuffer);
    for (i = 0; i <= SNELL__GLASS_SHADING_MASK; i++) snell__glass_program_destroy(&gs->prog[i]);
    memset(gs, 0, sizeof *gs);
}

int snell__glass_scale_max(const snell__method *m) { return m->needs_back_faces ? 1 : SNELL_MAX_GLASS_SCALE; }

float snell__glass_scale_of(const snell__method *m, snell__output_kind out, const snell__object *o)
{
    if (snell__glass_scale_max(m) == 1 || out != SNELL__OUT_COLOR) return 1.0f;
    return o->glass->material.scale;
}

static unsigned make_texture(GLenum format, int w, int h)
{
    unsigned t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    snell__texture_nearest(GL_TEXTURE_2D, 1);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
    return t;
}

/* The target (and the G-buffer) for a w x h grid, kept while they fit: a
 * frame's objects at scales 2 and 4 share what the first made for 2. */
static snell_status ensure_target(snell_ctx *ctx, snell__glass_scale *gs, int w, int h)
{
    GLenum fst;
    GLint bound;
    if (gs->fbo && gs->width >= w && gs->height >= h) return SNELL_OK;
    release_target(gs);
    snell__gbuffer_destroy(&gs->gbuffer); /* made again at this size by its first draw */
    glActiveTexture(GL_TEXTURE0);
    gs->color_tex = make_texture(GL_RGBA8, w, h);
    gs->depth_tex = make_texture(GL_DEPTH_COMPONENT24, w, h);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenFramebuffers(1, &gs->fbo);
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &bound);
    glBindFramebuffer(GL_FRAMEBUFFER, gs->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, gs->color_tex, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, gs->depth_tex, 0);
    fst = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)bound);
    gs->width = w;
    gs->height = h;
    if (fst != GL_FRAMEBUFFER_COMPLETE || glGetError() != GL_NO_ERROR) {
        release_target(gs);
        return snell__fail(ctx, SNELL_E_GL, "resolution-scale target %dx%d incomplete (0x%x)", w, h, (unsigned)fst);
    }
    return SNELL_OK;
}

static snell_status ensure_program(snell_ctx *ctx, snell__glass_scale *gs, int shading)
{
    snell__glass_program *g = &gs->prog[shading];
    snell_status st;
    if (g->prog) return SNELL_OK;
    if ((st = snell__glass_program_build(ctx, "glass_scale.frag", SNELL__OUT_COLOR, NULL, shading, g)) != SNELL_OK)
        return st;
    gs->u_ratio[shading] = glGetUniformLocation(g->prog, "u_ratio");
    gs->u_max[shading] = glGetUniformLocation(g->prog, "u_max");
    gs->u_thickness[shading] = glGetUniformLocation(g->prog, "u_thickness");
    return SNELL_OK;
}

/* The object's method at the small grid: the view's size divided (the same
 * projection, so a point lands on the same place of the image), the object
 * in screen space on the small G-buffer, its rectangle projected onto it;
 * the kernel writes the G-buffer's depth into the small target's. */
static snell_status draw_small(snell_ctx *ctx, snell__glass_scale *gs, const snell__view *small,
                               const snell__object *o, snell_object_stats *stats, snell__glass_draw_fn draw,
                               void *user)
{
    snell__object so = *o;
    snell__view sv = *small; /* its textures: this G-buffer's maps in place of the frame's */
    snell__object *list[1];
    snell__pass pass;
    snell_status s;
    int x0, y0, x1, y1;
    snell__object_project(small, &so);
    so.screen_space = SNELL__SCREEN_WRITES_DEPTH;
    list[0] = &so;
    if ((s = snell__gbuffer_draw(ctx, &gs->gbuffer, small, list, 1, 0, stats)) != SNELL_OK) return s;
    snell__gbuffer_publish(&gs->gbuffer, &sv.textures, 0);
    x0 = so.scissor[0] - READ_MARGIN > 0 ? so.scissor[0] - READ_MARGIN : 0;
    y0 = so.scissor[1] - READ_MARGIN > 0 ? so.scissor[1] - READ_MARGIN : 0;
    x1 = so.scissor[0] + so.scissor[2] + READ_MARGIN;
    y1 = so.scissor[1] + so.scissor[3] + READ_MARGIN;
    snell__pass_begin(&pass, gs->fbo, small->width, small->height, 0, GL_LESS, 1.0f);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, y0, x1 - x0, y1 - y0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT); /* alpha 0: not covered */
    glDisable(GL_SCISSOR_TEST);
    s = draw(user, &sv, &so, &stats[o->index]);
    snell__pass_end(&pass);
    return s;
}

snell_status snell__glass_scale_draw(snell_ctx *ctx, snell__glass_scale *gs,
                                     const snell__view *v, const snell__object *o, snell_object_stats *stats,
                                     snell__glass_draw_fn draw, void *user)
{
    snell__view small = *v;
    const snell__glass_program *g;
    int sh = o->screen_space;
    snell_status s;
    small.width = (int)ceilf((float)v->width / o->scale);
    small.height = (int)ceilf((float)v->height / o->scale);
    if ((s = ensure_target(ctx, gs, small.width, small.height)) != SNELL_OK) return s;
    if ((s = ensure_program(ctx, gs, sh)) != SNELL_OK) return s;
    if ((s = draw_small(ctx, gs, &small, o, stats, draw, user)) != SNELL_OK) return s;
    g = &gs->prog[sh];
    snell__glass_program_use(g, v, o);
    snell__glass_program_bind(g, "u_small_color", GL_TEXTURE_2D, gs->color_tex, 0);
    glUniform2f(gs->u_ratio[sh], (float)small.width / (float)v->width, (float)small.height / (float)v->height);
    glUniform2i(gs->u_max[sh], small.width - 1, small.height - 1);
    glUniform1f(gs->u_thickness[sh], o->glass->material.thickness > 0.0f ? o->glass->material.thickness : 0.0f);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    snell__draw_surface(o, &stats[o->index]);
    snell__glass_program_bind(g, "u_small_color", GL_TEXTURE_2D, 0, 0); /* the small target is drawn into next */
    stats[o->index].passes++;
    return glGetError() == GL_NO_ERROR ? SNELL_OK
                                       : snell__fail(ctx, SNELL_E_GL, "GL error drawing at scale %g", (double)o->scale);
}
