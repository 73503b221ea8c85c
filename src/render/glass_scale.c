/* glass_scale.c — see glass_scale.h. The object's method draws as it would
 * at full resolution, into a view whose grid is the frame's divided by the
 * scale: every pass it makes (peels, the kernel) costs 1/scale^2 of its
 * fragments. Its own depth there marks what it covered; the full-resolution
 * pass rasterises the object again, so which pixels are glass, and the
 * depth test against what is already drawn, are exactly as unscaled. */
#include "render/glass_scale.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"
#include "frame/glass_program.h"
#include "frame/pass.h"
#include "render/gbuffer.h"

#include <math.h>
#include <string.h>

/* Texels around the object's rectangle cleared too: glass_scale.frag reads
 * up to two beyond the texel under a covered pixel. */
#define READ_MARGIN 2

void snell__glass_scale_destroy(snell__glass_scale *gs)
{
    if (gs->fbo) glDeleteFramebuffers(1, &gs->fbo);
    if (gs->color_tex) glDeleteTextures(1, &gs->color_tex);
    if (gs->depth_tex) glDeleteTextures(1, &gs->depth_tex);
    if (gs->prog) glDeleteProgram(gs->prog);
    memset(gs, 0, sizeof *gs);
}

float snell__glass_scale_of(const snell__method *m, snell__output_kind out, const snell__object *o)
{
    if (m->needs_back_faces || m->screen_space_only || out != SNELL__OUT_COLOR) return 1.0f;
    return o->glass->material.scale;
}

static void nearest_texture(void)
{
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

/* The program on first use; the target for a w x h grid, kept while it fits. */
static snell_status ensure(snell_ctx *ctx, snell__glass_scale *gs, int w, int h)
{
    GLenum fst;
    GLint bound;
    if (!gs->prog) {
        snell_status st = snell__program_build(ctx, "object.vert", "glass_scale.frag", NULL, &gs->prog);
        if (st != SNELL_OK) return st;
        gs->u_model = glGetUniformLocation(gs->prog, "u_model");
        gs->u_normal_matrix = glGetUniformLocation(gs->prog, "u_normal_matrix");
        gs->u_view_proj = glGetUniformLocation(gs->prog, "u_view_proj");
        gs->u_color = glGetUniformLocation(gs->prog, "u_color");
        gs->u_depth = glGetUniformLocation(gs->prog, "u_depth");
        gs->u_ratio = glGetUniformLocation(gs->prog, "u_ratio");
        gs->u_max = glGetUniformLocation(gs->prog, "u_max");
        gs->u_inv_proj_z = glGetUniformLocation(gs->prog, "u_inv_proj_z");
    }
    if (gs->fbo && gs->width >= w && gs->height >= h) return SNELL_OK;
    if (gs->fbo) glDeleteFramebuffers(1, &gs->fbo);
    if (gs->color_tex) glDeleteTextures(1, &gs->color_tex);
    if (gs->depth_tex) glDeleteTextures(1, &gs->depth_tex);
    glGenTextures(1, &gs->color_tex);
    glBindTexture(GL_TEXTURE_2D, gs->color_tex);
    nearest_texture();
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, w, h);
    glGenTextures(1, &gs->depth_tex);
    glBindTexture(GL_TEXTURE_2D, gs->depth_tex);
    nearest_texture();
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT24, w, h);
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
        snell__glass_scale_destroy(gs);
        return snell__fail(ctx, SNELL_E_GL, "resolution-scale target %dx%d incomplete (0x%x)", w, h, (unsigned)fst);
    }
    return SNELL_OK;
}

/* The object's method at the small grid: the view's size divided (the same
 * projection, so a point lands on the same place of the image), the
 * object's rectangle projected onto it. */
static snell_status draw_small(snell__glass_scale *gs, const snell__view *small, const snell__object *o,
                               snell_object_stats *st, snell__glass_draw_fn draw, void *user)
{
    snell__object so = *o;
    snell__pass pass;
    snell_status s;
    int x0, y0, x1, y1;
    snell__object_project(small, &so);
    x0 = so.scissor[0] - READ_MARGIN > 0 ? so.scissor[0] - READ_MARGIN : 0;
    y0 = so.scissor[1] - READ_MARGIN > 0 ? so.scissor[1] - READ_MARGIN : 0;
    x1 = so.scissor[0] + so.scissor[2] + READ_MARGIN;
    y1 = so.scissor[1] + so.scissor[3] + READ_MARGIN;
    snell__pass_begin(&pass, gs->fbo, small->width, small->height, 0, GL_LESS, 1.0f);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, y0, x1 - x0, y1 - y0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT); /* depth 1: not covered */
    glDisable(GL_SCISSOR_TEST);
    s = draw(user, small, &so, st);
    snell__pass_end(&pass);
    return s;
}

snell_status snell__glass_scale_draw(snell_ctx *ctx, snell__glass_scale *gs, const snell__view *v,
                                     const snell__object *o, snell_object_stats *st, snell__glass_draw_fn draw,
                                     void *user)
{
    snell__view small = *v;
    snell_status s;
    mat4 inv_proj;
    small.width = (int)ceilf((float)v->width / o->scale);
    small.height = (int)ceilf((float)v->height / o->scale);
    if ((s = ensure(ctx, gs, small.width, small.height)) != SNELL_OK) return s;
    if ((s = draw_small(gs, &small, o, st, draw, user)) != SNELL_OK) return s;
    glm_mat4_inv((vec4 *)v->proj, inv_proj);
    glUseProgram(gs->prog);
    glUniformMatrix4fv(gs->u_model, 1, GL_FALSE, (const GLfloat *)o->model);
    glUniformMatrix3fv(gs->u_normal_matrix, 1, GL_FALSE, (const GLfloat *)o->normal_matrix);
    glUniformMatrix4fv(gs->u_view_proj, 1, GL_FALSE, (const GLfloat *)v->view_proj);
    glUniform1i(gs->u_color, SNELL__UNIT_ENV);
    glUniform1i(gs->u_depth, SNELL__UNIT_KERNEL);
    glUniform2f(gs->u_ratio, (float)small.width / (float)v->width, (float)small.height / (float)v->height);
    glUniform2i(gs->u_max, small.width - 1, small.height - 1);
    glUniform4f(gs->u_inv_proj_z, inv_proj[2][2], inv_proj[3][2], inv_proj[2][3], inv_proj[3][3]);
    glActiveTexture(GL_TEXTURE0 + SNELL__UNIT_KERNEL);
    glBindTexture(GL_TEXTURE_2D, gs->depth_tex);
    glActiveTexture(GL_TEXTURE0 + SNELL__UNIT_ENV);
    glBindTexture(GL_TEXTURE_2D, gs->color_tex);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    snell__draw_surface(o, st); /* forward: its faces, back faces culled where the kernel culls them */
    glBindTexture(GL_TEXTURE_2D, 0);
    st->passes++;
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "GL error drawing at scale %g",
                                                                (double)o->scale);
}
