/* SPDX-License-Identifier: MIT */
/* host_target.c — see host_target.h. */
#include "render/host_target.h"
#include "render/host_depth.h"
#include "core/ctx.h"
#include "core/gl.h"

int snell__fb_attachment(unsigned att, unsigned pname)
{
    GLint v = 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, pname, &v);
    return v;
}

#ifdef SNELL_WITH_HOST_FRAMEBUFFERS
/* Why snell cannot draw into the bound framebuffer, NULL when it can. */
static const char *refusal(GLint fbo, GLint buf, int premultiplied)
{
    GLint type;
    if (glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return "is not complete";
    if (buf == GL_NONE || snell__fb_attachment((GLenum)buf, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) == GL_NONE)
        return "draws to no colour buffer";
    type = snell__fb_attachment((GLenum)buf, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE);
    if (type == GL_INT || type == GL_UNSIGNED_INT) return "has an integer colour buffer";
    if (premultiplied && snell__fb_attachment((GLenum)buf, GL_FRAMEBUFFER_ATTACHMENT_ALPHA_SIZE) == 0)
        return "lacks alpha (premultiplied_alpha)";
    if (snell__fb_attachment(fbo ? GL_DEPTH_ATTACHMENT : GL_DEPTH, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) == GL_NONE)
        return "has no depth buffer"; /* the glass is depth-tested, the background drawn behind it */
    return NULL;
}

#define TEXTURE_WIDTH 0x1000 /* GLES 3.1's GL_TEXTURE_WIDTH, GL_TEXTURE_HEIGHT */
#define TEXTURE_HEIGHT 0x1001
typedef void(GL_APIENTRY *tex_level_fn)(GLenum target, GLint level, GLenum pname, GLint *v);

/* The size of attachment att of the bound draw framebuffer where GLES can
 * tell: a renderbuffer's; a 2D or cube texture level's through GLES 3.1's
 * glGetTexLevelParameteriv (3.0 cannot ask); the default framebuffer's from
 * EGL. 0: unknown. */
static int attachment_size(snell_ctx *ctx, GLint fbo, GLenum att, GLint size[2])
{
    GLint type, name, prev = 0, minor = 0, face, level;
    GLenum target, binding;
    tex_level_fn get;
    if (!fbo) return snell__platform_surface_size(&ctx->platform, size);
    type = snell__fb_attachment(att, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE);
    name = snell__fb_attachment(att, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME);
    if (type == GL_RENDERBUFFER) {
        glGetIntegerv(GL_RENDERBUFFER_BINDING, &prev);
        glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)name);
        glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_WIDTH, &size[0]);
        glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_HEIGHT, &size[1]);
        glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)prev);
        return 1;
    }
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (type != GL_TEXTURE || minor < 1 || snell__fb_attachment(att, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER) ||
        !(get = (tex_level_fn)snell__platform_proc(&ctx->platform, "glGetTexLevelParameteriv")))
        return 0;
    face = snell__fb_attachment(att, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE);
    level = snell__fb_attachment(att, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL);
    target = face ? (GLenum)face : GL_TEXTURE_2D;
    binding = face ? GL_TEXTURE_BINDING_CUBE_MAP : GL_TEXTURE_BINDING_2D;
    glGetIntegerv(binding, &prev);
    glBindTexture(face ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D, (GLuint)name);
    if (glGetError() != GL_NO_ERROR) return 0; /* a 2D array or 3D texture's layer 0: not asked */
    get(target, level, TEXTURE_WIDTH, &size[0]);
    get(target, level, TEXTURE_HEIGHT, &size[1]);
    glBindTexture(face ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D, (GLuint)prev);
    return 1;
}

/* Where the frame's rectangle (x, y, width, height) reaches past the colour
 * or depth buffer GL can size, which one and how large it is; NULL when it fits. */
static const char *too_small(snell_ctx *ctx, GLint fbo, GLenum color, const int rect[4], GLint size[2])
{
    if (attachment_size(ctx, fbo, color, size) && (size[0] < rect[0] + rect[2] || size[1] < rect[1] + rect[3]))
        return "colour buffer";
    if (fbo && attachment_size(ctx, fbo, GL_DEPTH_ATTACHMENT, size) &&
        (size[0] < rect[0] + rect[2] || size[1] < rect[1] + rect[3]))
        return "depth buffer";
    return NULL;
}

/* The frame's rectangle of the host's colour (draw buffer 0) and depth
 * (unless mapped) into the copy (in), or back (out). */
static void copy_blit(const snell__host_target *t, int in)
{
    const int *v = t->rect;
    GLint read = GL_BACK;
    GLbitfield bits = GL_COLOR_BUFFER_BIT;
    if (!t->mapped)
        bits |= GL_DEPTH_BUFFER_BIT | (t->copy_format == GL_DEPTH24_STENCIL8 || t->copy_format == GL_DEPTH32F_STENCIL8
                                           ? GL_STENCIL_BUFFER_BIT : 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, in ? t->fbo : t->copy_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, in ? t->copy_fbo : t->fbo);
    glGetIntegerv(GL_READ_BUFFER, &read);
    if (in) glReadBuffer(t->draw_buffers[0]);
    if (in) glBlitFramebuffer(v[0], v[1], v[0] + v[2], v[1] + v[3], 0, 0, v[2], v[3], bits, GL_NEAREST);
    else glBlitFramebuffer(0, 0, v[2], v[3], v[0], v[1], v[0] + v[2], v[1] + v[3], bits, GL_NEAREST);
    glReadBuffer((GLenum)read);
    glBindFramebuffer(GL_FRAMEBUFFER, in ? t->copy_fbo : t->fbo);
}

static void copy_free(snell__host_target *t)
{
    if (t->copy_fbo) glDeleteFramebuffers(1, &t->copy_fbo);
    if (t->copy_rb[0]) glDeleteRenderbuffers(2, t->copy_rb);
    if (t->copy_depth) glDeleteTextures(1, &t->copy_depth);
    t->copy_fbo = t->copy_rb[0] = t->copy_rb[1] = t->copy_depth = 0;
}

/* A viewport off the origin (two eyes side by side, a split screen) or a
 * depth of another convention (reversed-Z): the frame is drawn into a copy
 * of its rectangle, colour and depth (a mapped depth: 32-bit float, mapped
 * in), and copied back after; snell's passes then see a target of their own
 * size at 0, 0. */
static snell_status redirect(snell_ctx *ctx, snell__host_target *t)
{
    unsigned format = snell__host_depth_format((int)t->fbo);
    const int *v = t->rect;
    GLint samples = 0;
    glGetIntegerv(GL_SAMPLE_BUFFERS, &samples);
    if (!format || samples > 0)
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "snell_render: %s needs a single-sampled depth buffer a blit "
                           "can copy (16, 24 or 32F bits)", t->mapped ? "a reversed-Z camera's depth test" :
                           "a viewport off the origin");
    if (t->mapped) format = GL_DEPTH_COMPONENT32F;
    if (!t->copy_fbo || t->copy_format != format || t->copy_size[0] != v[2] || t->copy_size[1] != v[3] ||
        !t->copy_depth != !t->mapped) {
        copy_free(t);
        glGenFramebuffers(1, &t->copy_fbo);
        glGenRenderbuffers(2, t->copy_rb);
        glBindRenderbuffer(GL_RENDERBUFFER, t->copy_rb[0]);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, v[2], v[3]);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t->copy_fbo);
        glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->copy_rb[0]);
        if (t->mapped) {
            /* a texture: the map back reads it */
            glGenTextures(1, &t->copy_depth);
            glBindTexture(GL_TEXTURE_2D, t->copy_depth);
            glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, v[2], v[3]);
            snell__texture_nearest(GL_TEXTURE_2D, 1);
            glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t->copy_depth, 0);
        } else {
            glBindRenderbuffer(GL_RENDERBUFFER, t->copy_rb[1]);
            glRenderbufferStorage(GL_RENDERBUFFER, format, v[2], v[3]);
            glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER,
                                      format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8
                                          ? GL_DEPTH_STENCIL_ATTACHMENT
                                          : GL_DEPTH_ATTACHMENT,
                                      GL_RENDERBUFFER, t->copy_rb[1]);
        }
        t->copy_format = format, t->copy_size[0] = v[2], t->copy_size[1] = v[3];
    }
    copy_blit(t, 1);
    t->copied = 1;
    return t->mapped ? snell__depth_map_in(ctx, &t->map, t->fbo, v, t->copy_fbo) : SNELL_OK;
}

snell_status snell__host_target_begin(snell_ctx *ctx, snell__host_target *t, int width, int height,
                                      int premultiplied, const double *depth_map)
{
    GLint fbo = 0, buf = GL_NONE, max = 1, i;
    const char *why;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_DRAW_BUFFER0, &buf);
    t->fbo = (unsigned)fbo;
    t->draw_buffer_count = t->srgb_write = t->copied = 0;
    t->mapped = depth_map != NULL;
    if (depth_map) t->map.map[0] = depth_map[0], t->map.map[1] = depth_map[1];
    if (!(why = refusal(fbo, buf, premultiplied)) &&
        snell__fb_attachment((GLenum)buf, GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING) == GL_SRGB) {
        /* snell's colour is display-referred already: written as it is, not encoded again */
        if (!snell_ctx_has_gl_extension(ctx, "GL_EXT_sRGB_write_control"))
            why = "is sRGB: no GL_EXT_sRGB_write_control";
        else if ((t->srgb_write = glIsEnabled(GL_FRAMEBUFFER_SRGB_EXT)))
            glDisable(GL_FRAMEBUFFER_SRGB_EXT);
    }
    /* Other draw buffers would get undefined values (GLES 3.0 3.9.2.3): off for the frame. */
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &max);
    if (max > SNELL__HOST_DRAW_BUFFERS) max = SNELL__HOST_DRAW_BUFFERS;
    for (i = 0; i < max && !why; i++) {
        GLint b = GL_NONE;
        glGetIntegerv(GL_DRAW_BUFFER0 + i, &b);
        t->draw_buffers[i] = (unsigned)b;
        if (b != GL_NONE && i > 0) t->draw_buffer_count = max;
    }
    if (why) return snell__fail(ctx, SNELL_E_UNSUPPORTED, "snell_render: the bound framebuffer %d %s", fbo, why);
    if (t->draw_buffer_count) glDrawBuffers(1, (const GLenum *)t->draw_buffers);
    /* The host's viewport: at the origin the frame is drawn at 0, 0 (its size
     * the renderer's); elsewhere it must be the renderer's size. */
    glGetIntegerv(GL_VIEWPORT, t->viewport);
    {
        int rect[4];
        GLint size[2] = {0, 0};
        const char *which;
        rect[0] = t->viewport[0], rect[1] = t->viewport[1], rect[2] = width, rect[3] = height;
        if ((which = too_small(ctx, fbo, (GLenum)buf, rect, size)))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_render: the bound framebuffer %d's %s is %dx%d, the "
                               "renderer draws %dx%d at %d,%d", fbo, which, size[0], size[1], width, height, rect[0],
                               rect[1]);
    }
    t->rect[0] = t->viewport[0], t->rect[1] = t->viewport[1], t->rect[2] = width, t->rect[3] = height;
    if (!t->viewport[0] && !t->viewport[1] && !t->mapped) return SNELL_OK;
    if ((t->viewport[2] == width && t->viewport[3] == height) || (!t->viewport[0] && !t->viewport[1]))
        return redirect(ctx, t);
    return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_render: the viewport is %dx%d at %d,%d, the renderer %dx%d",
                       t->viewport[2], t->viewport[3], t->viewport[0], t->viewport[1], width, height);
}

snell_status snell__host_target_end(snell_ctx *ctx, snell__host_target *t)
{
    snell_status st = SNELL_OK;
    if (t->copied) copy_blit(t, 0);
    if (t->copied && t->mapped) st = snell__depth_map_back(ctx, &t->map, t->fbo, t->rect, t->copy_depth);
    t->copied = 0;
    if (t->srgb_write) glEnable(GL_FRAMEBUFFER_SRGB_EXT);
    t->srgb_write = 0;
    if (!t->draw_buffer_count) return st;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t->fbo);
    glDrawBuffers(t->draw_buffer_count, (const GLenum *)t->draw_buffers);
    t->draw_buffer_count = 0;
    return st;
}

void snell__host_target_destroy(snell__host_target *t)
{
    copy_free(t);
    snell__depth_map_destroy(&t->map);
}
#endif
