/* SPDX-License-Identifier: MIT */
/* glstate.c — save/restore of every piece of GL state snell's per-frame calls
 * may change or its output depends on. Saved only with the EXTERNAL backend:
 * glGet* can stall a real driver's pipeline, so an owned context skips it.
 * Also the frame's defaults for state no pass sets (all backends), and the
 * pixel pack/unpack scope of read-backs and uploads. */
/* the real unit calls: this file is what the wrappers of core/gl.h call */
#define SNELL_GL_UNTRACKED 1
#include "core/glstate.h"
#include "core/gl.h"
#include "core/core.h"
#include "core/ctx.h"

/* The calling thread's innermost units scope and its active unit (a GL
 * context is current on one thread, whose calls these follow); one
 * thread-local object, so that each function finds it once. */
static SNELL__THREAD_LOCAL struct {
    snell__units *scope;
    int active;
} g_units;

/* The first use of unit u in every open scope: saved where a scope saves
 * (before any reset changes it), then its sampler object unbound where one
 * resets. The unit is active on return when any scope saved it. */
static void use_unit(int u)
{
    unsigned bit = 1u << u;
    snell__units *s;
    int saved = 0, reset = 0;
    GLint b[4];
    if (u < 0 || u >= SNELL__UNITS_MAX) return;
    for (s = g_units.scope; s; s = s->outer) {
        if (s->used & bit) continue;
        if (s->save && !saved) {
            glActiveTexture((GLenum)(GL_TEXTURE0 + u));
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &b[0]);
            glGetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP, &b[1]);
            glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &b[2]);
            glGetIntegerv(GL_SAMPLER_BINDING, &b[3]);
            glActiveTexture((GLenum)(GL_TEXTURE0 + g_units.active));
            saved = 1;
        }
        if (s->save) {
            s->tex_2d[u] = b[0], s->tex_cube[u] = b[1], s->tex_2d_array[u] = b[2];
            s->sampler[u] = b[3];
        }
        reset |= s->reset_samplers;
        s->used |= bit;
    }
    if (reset) glBindSampler((GLuint)u, 0);
}

void snell__active_texture(GLenum unit)
{
    g_units.active = (int)unit - GL_TEXTURE0;
    glActiveTexture(unit);
    use_unit(g_units.active);
}

void snell__texture_nearest(GLenum target, int clamp)
{
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (!clamp) return;
    glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void snell__bind_texture(GLenum target, GLuint texture)
{
    use_unit(g_units.active);
    glBindTexture(target, texture);
}

void snell__bind_sampler(GLuint unit, GLuint sampler)
{
    use_unit((int)unit);
    glBindSampler(unit, sampler);
}

void snell__units_begin(snell__units *u, int save, int reset_samplers)
{
    u->outer = g_units.scope;
    u->used = 0;
    u->save = save, u->reset_samplers = reset_samplers;
    if (!g_units.scope) {
        GLint active = GL_TEXTURE0;
        if (save) glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
        else glActiveTexture(GL_TEXTURE0);
        g_units.active = (int)active - GL_TEXTURE0;
    }
    g_units.scope = u;
}

void snell__units_end(snell__units *u)
{
    int i;
    g_units.scope = u->outer;
    for (i = 0; u->save && i < SNELL__UNITS_MAX; i++) {
        if (!(u->used >> i & 1u)) continue;
        glActiveTexture((GLenum)(GL_TEXTURE0 + i));
        glBindTexture(GL_TEXTURE_2D, (GLuint)u->tex_2d[i]);
        glBindTexture(GL_TEXTURE_CUBE_MAP, (GLuint)u->tex_cube[i]);
        glBindTexture(GL_TEXTURE_2D_ARRAY, (GLuint)u->tex_2d_array[i]);
        glBindSampler((GLuint)i, (GLuint)u->sampler[i]);
    }
    if (u->save && u->used) glActiveTexture((GLenum)(GL_TEXTURE0 + g_units.active));
}

int snell__units_count(const snell__units *u)
{
    unsigned m = u->used;
    int n = 0;
    for (; m; m &= m - 1) n++;
    return n;
}

/* The capabilities a frame may change, bit i of snell_glstate.caps for k_caps[i]. */
static const unsigned short k_caps[] = {GL_DEPTH_TEST, GL_CULL_FACE, GL_BLEND, GL_SCISSOR_TEST, GL_STENCIL_TEST,
                                GL_POLYGON_OFFSET_FILL, GL_DITHER, GL_RASTERIZER_DISCARD,
                                GL_SAMPLE_ALPHA_TO_COVERAGE, GL_SAMPLE_COVERAGE, GL_PRIMITIVE_RESTART_FIXED_INDEX};
#define CAPS (int)(sizeof k_caps / sizeof k_caps[0])

static void pixel_save(snell__pixel_store *p, int pack)
{
    glGetIntegerv(pack ? GL_PIXEL_PACK_BUFFER_BINDING : GL_PIXEL_UNPACK_BUFFER_BINDING, &p->buffer);
    glGetIntegerv(pack ? GL_PACK_ALIGNMENT : GL_UNPACK_ALIGNMENT, &p->alignment);
    glGetIntegerv(pack ? GL_PACK_ROW_LENGTH : GL_UNPACK_ROW_LENGTH, &p->row_length);
    glGetIntegerv(pack ? GL_PACK_SKIP_ROWS : GL_UNPACK_SKIP_ROWS, &p->skip_rows);
    glGetIntegerv(pack ? GL_PACK_SKIP_PIXELS : GL_UNPACK_SKIP_PIXELS, &p->skip_pixels);
    p->image_height = p->skip_images = 0;
    if (!pack) {
        glGetIntegerv(GL_UNPACK_IMAGE_HEIGHT, &p->image_height);
        glGetIntegerv(GL_UNPACK_SKIP_IMAGES, &p->skip_images);
    }
}

static void pixel_set(const snell__pixel_store *p, int pack)
{
    glBindBuffer(pack ? GL_PIXEL_PACK_BUFFER : GL_PIXEL_UNPACK_BUFFER, (GLuint)p->buffer);
    glPixelStorei(pack ? GL_PACK_ALIGNMENT : GL_UNPACK_ALIGNMENT, p->alignment);
    glPixelStorei(pack ? GL_PACK_ROW_LENGTH : GL_UNPACK_ROW_LENGTH, p->row_length);
    glPixelStorei(pack ? GL_PACK_SKIP_ROWS : GL_UNPACK_SKIP_ROWS, p->skip_rows);
    glPixelStorei(pack ? GL_PACK_SKIP_PIXELS : GL_UNPACK_SKIP_PIXELS, p->skip_pixels);
    if (!pack) {
        glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, p->image_height);
        glPixelStorei(GL_UNPACK_SKIP_IMAGES, p->skip_images);
    }
}

static void pixel_default(int pack, int alignment)
{
    snell__pixel_store d = {0, 4, 0, 0, 0, 0, 0};
    d.alignment = alignment;
    pixel_set(&d, pack);
}

void snell__pixel_pack_begin(snell__pixel_store *saved, int alignment)
{
    pixel_save(saved, 1);
    pixel_default(1, alignment);
}

void snell__pixel_pack_end(const snell__pixel_store *saved) { pixel_set(saved, 1); }

void snell__pixel_unpack_begin(snell__pixel_store *saved, int alignment)
{
    pixel_save(saved, 0);
    pixel_default(0, alignment);
}

void snell__pixel_unpack_end(const snell__pixel_store *saved) { pixel_set(saved, 0); }

void snell__glstate_frame_defaults(void)
{
    glDepthRangef(0.0f, 1.0f);
    glDisable(GL_RASTERIZER_DISCARD);
    glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    glDisable(GL_SAMPLE_COVERAGE);
    glDisable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
    glFrontFace(GL_CCW);
    glCullFace(GL_BACK);
    pixel_default(1, 4);
    pixel_default(0, 4);
}

void snell__glstate_save(snell_glstate *s)
{
    int i;
    GLboolean cm[4], dm, tf_active = GL_FALSE, tf_paused = GL_FALSE;
    s->host_errors = snell__gl_errors_take();
    /* A host's active transform feedback would capture snell's draws: paused
     * until the restore (GLES 3.0 2.15.2 allows binding, drawing and
     * program changes while paused). */
    glGetBooleanv(GL_TRANSFORM_FEEDBACK_ACTIVE, &tf_active);
    glGetBooleanv(GL_TRANSFORM_FEEDBACK_PAUSED, &tf_paused);
    s->tf_paused = tf_active && !tf_paused;
    if (s->tf_paused) glPauseTransformFeedback();
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
    glGetIntegerv(GL_RENDERBUFFER_BINDING, &s->renderbuffer);
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &s->array_buffer);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    glGetIntegerv(GL_SCISSOR_BOX, s->scissor_box);
    s->caps = 0;
    for (i = 0; i < CAPS; i++) s->caps |= (glIsEnabled(k_caps[i]) ? 1u : 0u) << i;
    glGetBooleanv(GL_COLOR_WRITEMASK, cm);
    for (i = 0; i < 4; i++) s->color_mask[i] = cm[i];
    glGetBooleanv(GL_DEPTH_WRITEMASK, &dm);
    s->depth_mask = dm;
    glGetIntegerv(GL_DEPTH_FUNC, &s->depth_func);
    glGetIntegerv(GL_CULL_FACE_MODE, &s->cull_mode);
    glGetIntegerv(GL_FRONT_FACE, &s->front_face);
    glGetIntegerv(GL_BLEND_SRC_RGB, &s->blend_src_rgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &s->blend_dst_rgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &s->blend_src_a);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &s->blend_dst_a);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &s->blend_eq_rgb);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &s->blend_eq_a);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, s->clear_color);
    glGetFloatv(GL_DEPTH_CLEAR_VALUE, &s->clear_depth);
    glGetFloatv(GL_DEPTH_RANGE, s->depth_range);
    pixel_save(&s->pack, 1);
    pixel_save(&s->unpack, 0);
    snell__units_begin(&s->units, 1, 0);
    s->active_texture = GL_TEXTURE0 + g_units.active; /* asked by the outermost scope, followed since */
}

void snell__glstate_restore(snell_glstate *s)
{
    int i;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fbo);
    glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)s->renderbuffer);
    glUseProgram((GLuint)s->program);
    glBindVertexArray((GLuint)s->vao);
    glBindBuffer(GL_ARRAY_BUFFER, (GLuint)s->array_buffer);
    snell__units_end(&s->units);
    glActiveTexture((GLenum)s->active_texture);
    g_units.active = s->active_texture - GL_TEXTURE0;
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glScissor(s->scissor_box[0], s->scissor_box[1], s->scissor_box[2], s->scissor_box[3]);
    for (i = 0; i < CAPS; i++) {
        if (s->caps >> i & 1u) glEnable(k_caps[i]);
        else glDisable(k_caps[i]);
    }
    glColorMask(s->color_mask[0], s->color_mask[1], s->color_mask[2], s->color_mask[3]);
    glDepthMask(s->depth_mask);
    glDepthFunc((GLenum)s->depth_func);
    glCullFace((GLenum)s->cull_mode);
    glFrontFace((GLenum)s->front_face);
    glBlendFuncSeparate((GLenum)s->blend_src_rgb, (GLenum)s->blend_dst_rgb, (GLenum)s->blend_src_a,
                        (GLenum)s->blend_dst_a);
    glBlendEquationSeparate((GLenum)s->blend_eq_rgb, (GLenum)s->blend_eq_a);
    glClearColor(s->clear_color[0], s->clear_color[1], s->clear_color[2], s->clear_color[3]);
    glClearDepthf(s->clear_depth);
    glDepthRangef(s->depth_range[0], s->depth_range[1]);
    pixel_set(&s->pack, 1);
    pixel_set(&s->unpack, 0);
    if (s->tf_paused) glResumeTransformFeedback(); /* the host's program is current again */
    snell__gl_errors_give(s->host_errors);
}

/* GL keeps at most one flag per error kind and glGetError clears the one it
 * returns, so a host's pending error cannot be read without taking it: taken
 * before snell's work (which checks only its own errors), then raised again
 * by a call that fails the same way and changes nothing (GLES 3.0 2.5). */
unsigned snell__gl_errors_take(void)
{
    unsigned mask = 0;
    GLenum e;
    int i;
    for (i = 0; i < 8 && (e = glGetError()) != GL_NO_ERROR; i++)
        if (e >= GL_INVALID_ENUM && e <= GL_INVALID_FRAMEBUFFER_OPERATION) mask |= 1u << (e - GL_INVALID_ENUM);
    return mask;
}

void snell__gl_errors_give(unsigned mask)
{
    GLint v;
    GLuint fbo = 0, prev = 0;
    if (mask & 1u << (GL_INVALID_ENUM - GL_INVALID_ENUM)) glGetIntegerv(GL_NONE, &v);
    if (mask & 1u << (GL_INVALID_VALUE - GL_INVALID_ENUM)) glGetShaderiv(0, GL_SHADER_TYPE, &v); /* 0 is no shader */
    if (mask & 1u << (GL_INVALID_OPERATION - GL_INVALID_ENUM))
        glGetQueryObjectuiv(0, GL_QUERY_RESULT_AVAILABLE, &prev); /* 0 is no query */
    if (mask & 1u << (GL_INVALID_FRAMEBUFFER_OPERATION - GL_INVALID_ENUM)) {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &v);
        glGenFramebuffers(1, &fbo); /* no attachment: incomplete, so a clear of nothing fails */
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        glClear(0);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)v);
        glDeleteFramebuffers(1, &fbo);
    }
}
