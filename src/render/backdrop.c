/* SPDX-License-Identifier: MIT */
/* backdrop.c — the backdrop stage: the host's scene behind the glass
 * (snell_frame_desc.backdrop). It publishes the host's colour and depth
 * textures (or its own copies of the bound framebuffer's), and its kernel
 * hook, SNELL_BACKDROP, makes every glass kernel's rays that leave the glass
 * search them in screen space before the environment (common/backdrop.glsl
 * via common/beyond.glsl). */
#include "render/host_depth.h"
#include "render/stages.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "frame/camera.h"
#include "frame/glass_program.h"

#include <math.h>
#include <string.h>

#define SNELL__BACKDROP_UNIFORMS 5

typedef struct snell__backdrop snell__backdrop;

/* The stage's state (its slot), which its kernel hook reads. */
struct snell__backdrop {
    unsigned color_sampler, depth_sampler; /* linear colour; nearest depth, no comparison */
    /* COPY_BOUND: the copies, made on first use and remade when the size or depth format changes */
    unsigned color_tex, depth_tex, fbo;
    unsigned depth_format;
    int width, height;
    snell_backdrop desc; /* the frame's, its defaults applied */
    /* this frame's, for the kernels' uniforms */
    float view_proj[16], region[4], size[2], distance; /* distance 0: search the depth */
    float far_;                                        /* the host's far plane's depth: 1, 0 reversed-Z */
};

/* A texture of this context made as GL_TEXTURE_2D: binding one made for
 * another target fails (GLES 3.0 3.8.1); asked on the active unit, put back. */
static snell_status texture_2d(snell_ctx *ctx, unsigned tex, int required, const char *field)
{
    GLint prev = 0;
    const char *why = "a texture of this context";
    if (!tex && !required) return SNELL_OK;
    if (tex && glIsTexture(tex)) {
#ifdef SNELL_WITH_HOST_FRAMEBUFFERS /* the device preset leaves the target's check out (its bytes) */
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &prev);
        glBindTexture(GL_TEXTURE_2D, tex);
        why = glGetError() == GL_NO_ERROR ? NULL : "a GL_TEXTURE_2D";
        glBindTexture(GL_TEXTURE_2D, (GLuint)prev);
#else
        why = NULL, (void)prev;
#endif
    }
    return why ? snell__fail(ctx, SNELL_E_INVALID_ARG, "backdrop.%s %u is not %s", field, tex, why) : SNELL_OK;
}

static snell_status validate(const snell__services *sv, const snell_frame_desc *fd)
{
    const snell_backdrop *b = fd->backdrop;
    snell_ctx *ctx = sv->ctx;
    snell_target target = sv->target;
    snell_status st;
    int k;
    if (!b) return SNELL_OK;
    if ((unsigned)b->source > SNELL_BACKDROP_COPY_BOUND)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "backdrop.source %d is not a snell_backdrop_source", (int)b->source);
    if (b->source == SNELL_BACKDROP_COPY_BOUND && target != SNELL_TARGET_BOUND_FRAMEBUFFER)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "backdrop SNELL_BACKDROP_COPY_BOUND needs a renderer of "
                           "SNELL_TARGET_BOUND_FRAMEBUFFER");
    if (b->source == SNELL_BACKDROP_COPY_BOUND && fd->depth == SNELL_DEPTH_CLEAR)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "backdrop SNELL_BACKDROP_COPY_BOUND with SNELL_DEPTH_CLEAR: "
                           "the depth would be cleared before it is copied");
    if (b->source == SNELL_BACKDROP_TEXTURES) {
        if ((st = texture_2d(ctx, b->color_texture, 1, "color_texture")) != SNELL_OK ||
            (st = texture_2d(ctx, b->depth_texture, 0, "depth_texture")) != SNELL_OK)
            return st;
        if (b->width < 1 || b->height < 1 || b->width > 16384 || b->height > 16384)
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "backdrop.width x height %dx%d outside 1..16384 (the "
                               "textures' size is required)", b->width, b->height);
        if ((b->region[2] || b->region[3]) &&
            (b->region[0] < 0 || b->region[1] < 0 || b->region[2] < 1 || b->region[3] < 1 ||
             b->region[0] > b->width - b->region[2] || b->region[1] > b->height - b->region[3]))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "backdrop.region %d,%d %dx%d is not inside its %dx%d textures",
                               b->region[0], b->region[1], b->region[2], b->region[3], b->width, b->height);
    }
    for (k = 0; k < 4; k++)
        if (b->region[k] && !(b->region[2] || b->region[3]))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "backdrop.region: an offset needs a size");
    if (b->camera && (st = snell__camera_validate(ctx, b->camera, 1.0f, "backdrop")) != SNELL_OK) return st;
    if (!isfinite(b->distance) || !(b->distance > 0.0f))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "backdrop.distance %g: a finite distance > 0",
                           (double)b->distance);
    return SNELL_OK;
}

static int wanted(const snell__frame *f, const void *state)
{
    (void)state;
    return f->fd->backdrop != NULL;
}

static void sampler(unsigned *s, GLint filter)
{
    glGenSamplers(1, s);
    glSamplerParameteri(*s, GL_TEXTURE_MIN_FILTER, filter);
    glSamplerParameteri(*s, GL_TEXTURE_MAG_FILTER, filter);
    glSamplerParameteri(*s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(*s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(*s, GL_TEXTURE_COMPARE_MODE, GL_NONE); /* a depth texture reads its depth */
}

/* Copies the bound draw framebuffer's colour, and its depth where its format
 * is one a blit can match (render/host_depth.h), into the state's textures.
 * *depth: 1 the depth was copied. */
static snell_status copy_bound(snell_ctx *ctx, snell__backdrop *b, int w, int h, int *depth)
{
    GLint fbo = 0, drawn = GL_BACK, read = GL_BACK;
    unsigned format;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_DRAW_BUFFER0, &drawn); /* copied from, not the host's read buffer */
    format = snell__host_depth_format(fbo);
    if (!b->color_tex || b->width != w || b->height != h || b->depth_format != format) {
        if (b->color_tex) glDeleteTextures(1, &b->color_tex);
        if (b->depth_tex) glDeleteTextures(1, &b->depth_tex);
        if (b->fbo) glDeleteFramebuffers(1, &b->fbo); /* none of the old attachments stays */
        glGenFramebuffers(1, &b->fbo);
        glGenTextures(1, &b->color_tex);
        glBindTexture(GL_TEXTURE_2D, b->color_tex);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, w, h);
        b->depth_tex = 0;
        if (format) {
            glGenTextures(1, &b->depth_tex);
            glBindTexture(GL_TEXTURE_2D, b->depth_tex);
            glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
        }
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, b->fbo);
        glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, b->color_tex, 0);
        if (format)
            glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER,
                                   format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8
                                       ? GL_DEPTH_STENCIL_ATTACHMENT
                                       : GL_DEPTH_ATTACHMENT,
                                   GL_TEXTURE_2D, b->depth_tex, 0);
        b->width = w, b->height = h, b->depth_format = format;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)fbo);
    glGetIntegerv(GL_READ_BUFFER, &read);
    glReadBuffer((GLenum)drawn);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, b->fbo);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT | (format ? GL_DEPTH_BUFFER_BIT : 0), GL_NEAREST);
    glReadBuffer((GLenum)read);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    *depth = format != 0;
    if (glGetError() != GL_NO_ERROR)
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "backdrop SNELL_BACKDROP_COPY_BOUND: copying the bound "
                           "framebuffer (%dx%d, depth format 0x%x) failed: a multisampled one must match RGBA8",
                           w, h, format);
    return SNELL_OK;
}

/* Region all 0 = the whole texture (COPY_BOUND: the renderer's size), distance 0 = the default;
 * before validation (any other value is kept for validate() to judge). */
static void resolve(const snell__services *sv, snell_frame_desc *fd, void *state)
{
    snell__backdrop *b = (snell__backdrop *)state;
    snell_backdrop *d = &b->desc;
    if (!fd->backdrop) return;
    *d = *fd->backdrop;
    if (d->source == SNELL_BACKDROP_COPY_BOUND) d->width = sv->width, d->height = sv->height;
    if (!(d->region[0] || d->region[1] || d->region[2] || d->region[3]))
        d->region[2] = d->width, d->region[3] = d->height;
    if (d->distance == 0.0f) d->distance = SNELL_DEFAULT_BACKDROP_DISTANCE;
    fd->backdrop = d;
}

static snell_status run(snell__frame *f, void *state)
{
    const snell__services *sv = f->sv;
    const snell_backdrop *bd = f->fd->backdrop;
    snell__view *v = &f->sc->view;
    snell__backdrop *b = (snell__backdrop *)state;
    unsigned color = bd->color_texture, depth_tex = bd->depth_texture;
    int depth = depth_tex != 0, k;
    snell_status st;
    if (!b->color_sampler) {
        sampler(&b->color_sampler, GL_LINEAR);
        sampler(&b->depth_sampler, GL_NEAREST);
    }
    if (bd->source == SNELL_BACKDROP_COPY_BOUND) {
        if ((st = copy_bound(sv->ctx, b, bd->width, bd->height, &depth)) != SNELL_OK) return st;
        color = b->color_tex, depth_tex = b->depth_tex;
    }
    for (k = 0; k < 4; k++) b->region[k] = (float)bd->region[k];
    b->size[0] = (float)bd->width, b->size[1] = (float)bd->height;
    b->distance = depth ? 0.0f : bd->distance;
    /* The host's own matrices: its depth is theirs (the frame's may be standardised, frame/camera.h). */
    k = snell__camera_standard(bd->camera ? bd->camera : &f->fd->camera, b->region[2] / b->region[3], NULL, NULL,
                               NULL);
    b->far_ = k & SNELL__CAMERA_REVERSED ? 0.0f : 1.0f;
    if (bd->camera || (k & SNELL__CAMERA_CHANGED)) {
        mat4 view, proj, vp;
        float eye[3];
        snell_camera_matrices(bd->camera ? bd->camera : &f->fd->camera, b->region[2] / b->region[3], eye,
                              (float *)view, (float *)proj);
        snell__mat4_mul((const float *)proj, (const float *)view, (float *)vp);
        memcpy(b->view_proj, vp, sizeof b->view_proj);
    } else {
        memcpy(b->view_proj, v->view_proj, sizeof b->view_proj);
    }
    snell__textures_publish(&v->textures, "u_backdrop_color", GL_TEXTURE_2D, color, b->color_sampler);
    snell__textures_publish(&v->textures, "u_backdrop_depth", GL_TEXTURE_2D, depth_tex, b->depth_sampler);
    f->s->backdrop = depth ? 2 : 1;
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(sv->ctx, SNELL_E_GL, "GL error setting up the backdrop");
}

/* Every kernel's rays that leave the glass meet the backdrop. */
static unsigned variant(const snell__frame *f, const void *state, const snell__object *o)
{
    (void)state, (void)o;
    return f->fd->backdrop ? 1u : 0u;
}

static const char *backdrop_defines(unsigned bits)
{
    (void)bits;
    return "#define SNELL_BACKDROP 1\n";
}

static const char *const backdrop_uniform_names[SNELL__BACKDROP_UNIFORMS] = {
    "u_backdrop_view_proj", "u_backdrop_region", "u_backdrop_size", "u_backdrop_distance", "u_backdrop_far"};

static void backdrop_uniforms(const snell__glass_program *g, const int *locs, const void *state,
                              const snell__view *v, const snell__object *o)
{
    const snell__backdrop *b = (const snell__backdrop *)state;
    (void)g, (void)v, (void)o;
    glUniformMatrix4fv(locs[0], 1, GL_FALSE, b->view_proj);
    glUniform4fv(locs[1], 1, b->region);
    glUniform2fv(locs[2], 1, b->size);
    glUniform1f(locs[3], b->distance);
    glUniform1f(locs[4], b->far_);
}

static const snell__kernel_hook g_hook = {
    .variant_bits = 1,
    .defines = backdrop_defines,
    .uniform_names = backdrop_uniform_names,
    .uniform_count = SNELL__BACKDROP_UNIFORMS,
    .uniforms = backdrop_uniforms,
};

static void destroy(snell_ctx *ctx, void *state)
{
    snell__backdrop *b = (snell__backdrop *)state;
    (void)ctx;
    if (b->color_sampler) glDeleteSamplers(1, &b->color_sampler);
    if (b->depth_sampler) glDeleteSamplers(1, &b->depth_sampler);
    if (b->color_tex) glDeleteTextures(1, &b->color_tex);
    if (b->depth_tex) glDeleteTextures(1, &b->depth_tex);
    if (b->fbo) glDeleteFramebuffers(1, &b->fbo);
}

const snell__stage snell__stage_backdrop = {
    .name = "backdrop",
    .state_size = sizeof(snell__backdrop),
    .destroy = destroy,
    .validate = validate,
    .resolve = resolve,
    .wanted = wanted,
    .run = run,
    .kernel_variant = variant,
    .kernel = &g_hook,
};
