/* SPDX-License-Identifier: MIT */
/* panels_stage.c — glass panels over the frame (snell_frame_desc.panels,
 * snell_panels.h), drawn last: what lies beneath captured once (the frame's
 * rectangle, or an app's texture), then each shape (a panel, or a merged
 * group) as one quad over its box, its fragment shader the header's model
 * (shaders_es/panel.frag). A panel over one drawn before it sees it: that
 * overlap is copied again first. */
#include "render/renderer.h"
#include "render/stages.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/optics.h"
#include "core/program.h"
#include "frame/panel_model.h"

#include <math.h>
#include <string.h>

#ifndef GL_TEXTURE_BINDING_EXTERNAL_OES
#define GL_TEXTURE_BINDING_EXTERNAL_OES 0x8D67
#endif

enum { SRC_CAPTURE, SRC_TEXTURE, SRC_EXTERNAL, SOURCES };
enum { U_UV, U_SIZE, U_LOD, U_SPREAD, U_COUNT, U_RECT, U_RADIUS, U_EXPONENT, U_MERGE, U_SLAB, U_IOR, U_TINT, U_LIGHT,
       U_SHADOW, U_BENEATH, U_BOX, UNIFORMS };
static const char *const g_uniform[UNIFORMS] = {"u_uv",     "u_size",  "u_lod",  "u_spread", "u_count", "u_rect",
                                                "u_radius", "u_exponent", "u_merge", "u_slab", "u_ior",
                                                "u_tint",   "u_light", "u_shadow", "u_beneath", "u_box"};

/* The budget's cost model: work units a pixel of a shape's box (the field
 * and the light: 3; each tap 1: one, four with frost, times three with
 * dispersion) and 0.1 a pixel of the frame for frost's mip chain, at the
 * rate of a Raspberry Pi 4's V3D (bench/notes/panels.md's estimate by its
 * compiler's statistics): a slow device, so that a budget holds on it. */
#define UNITS_PER_MS 85000.0

typedef struct panel_prog {
    unsigned id;
    int loc[UNIFORMS];
} panel_prog;

/* A shape: a lone panel or a group, drawn where its first panel lies in the
 * list. next[] links a group's members from its first. */
typedef struct panel_shape {
    int first, count;
    float box[4];      /* the frame's pixels it may change, clipped to the frame */
    float recopy[4];   /* where it overlaps shapes drawn before it (empty: x0 >= x1) */
} panel_shape;

/* The overlap search's grid: GRID x GRID cells over the frame, each the
 * bounding box of the drawn shapes' parts in it, so that a shape meets the
 * cells under its box rather than every shape before it. */
#define GRID 16

typedef struct panels_state {
    /* Made on the first frame with panels, for SNELL_MAX_PANELS: a frame allocates nothing after. */
    snell__panel *panel;
    panel_shape *shape;
    int *next;
    float (*cell)[4];   /* GRID * GRID */
    int count, shapes;
    snell_status status; /* of this frame's panels, resolved before validation */
    char msg[200];
    unsigned target_fbo; /* where the frame is drawn, found at plan */
    panel_prog prog[SOURCES][2];
    panel_prog copy[2];  /* an app's texture drawn over a rectangle: 2D, external */
    unsigned capture_tex, capture_fbo, mip_fbo, linear, trilinear, vao;
    int cap_w, cap_h, levels;
    GLenum cap_format;   /* the capture's sized format, the target's own where a blit needs it */
} panels_state;

extern const snell__stage snell__stage_panels;

static void destroy(snell_ctx *ctx, void *state)
{
    panels_state *ps = (panels_state *)state;
    int i, k;
    for (i = 0; i < SOURCES; i++)
        for (k = 0; k < 2; k++)
            if (ps->prog[i][k].id) glDeleteProgram(ps->prog[i][k].id);
    for (k = 0; k < 2; k++)
        if (ps->copy[k].id) glDeleteProgram(ps->copy[k].id);
    if (ps->capture_tex) glDeleteTextures(1, &ps->capture_tex);
    if (ps->capture_fbo) glDeleteFramebuffers(1, &ps->capture_fbo);
    if (ps->mip_fbo) glDeleteFramebuffers(1, &ps->mip_fbo);
    if (ps->linear) glDeleteSamplers(1, &ps->linear);
    if (ps->trilinear) glDeleteSamplers(1, &ps->trilinear);
    if (ps->vao) glDeleteVertexArrays(1, &ps->vao);
    snell__free(&ctx->alloc, ps->panel);
    snell__free(&ctx->alloc, ps->shape);
    snell__free(&ctx->alloc, ps->next);
    snell__free(&ctx->alloc, ps->cell);
}

/* The panels resolved with their defaults into the slot (frame/panel_model.c,
 * shared with the reference); validate() reports the outcome. */
static void resolve(const snell__services *sv, snell_frame_desc *fd, void *state)
{
    panels_state *ps = (panels_state *)state;
    const snell_alloc *al = &sv->ctx->alloc;
    ps->status = SNELL_OK;
    ps->count = 0;
    if (!fd->panels && fd->panel_count == 0) return;
    if (!ps->panel && fd->panel_count > 0) {
        ps->panel = (snell__panel *)snell__calloc(al, SNELL_MAX_PANELS, sizeof *ps->panel);
        ps->shape = (panel_shape *)snell__calloc(al, SNELL_MAX_PANELS, sizeof *ps->shape);
        ps->next = (int *)snell__calloc(al, SNELL_MAX_PANELS, sizeof *ps->next);
        ps->cell = (float(*)[4])snell__calloc(al, GRID * GRID, sizeof *ps->cell);
        if (!ps->panel || !ps->shape || !ps->next || !ps->cell) {
            ps->status = SNELL_E_NOMEM;
            snprintf(ps->msg, sizeof ps->msg, "out of memory for %d panels", SNELL_MAX_PANELS);
            return;
        }
    }
    if (snell__panels_resolve(fd->panels, fd->panel_count, ps->panel, ps->msg, sizeof ps->msg)) {
        ps->status = SNELL_E_INVALID_ARG;
        return;
    }
    ps->count = fd->panel_count;
}

static int external_supported(snell_ctx *ctx)
{
    return snell_ctx_has_gl_extension(ctx, "GL_OES_EGL_image_external_essl3");
}

/* A texture of this context that binds as target (GLES 3.0 3.8.1: one made
 * for another target does not); asked on the active unit, put back. */
static int texture_of(unsigned tex, GLenum target, GLenum binding)
{
    GLint prev = 0;
    int ok;
    if (!tex || !glIsTexture(tex)) return 0;
    glGetIntegerv(binding, &prev);
    glBindTexture(target, tex);
    ok = glGetError() == GL_NO_ERROR;
    glBindTexture(target, (GLuint)prev);
    return ok;
}

static snell_status validate(const snell__services *sv, const snell_frame_desc *fd)
{
    const panels_state *ps =
        (const panels_state *)snell__renderer_stage_state((const snell_renderer *)sv->user, &snell__stage_panels);
    const snell_panels_under *u = fd->panels_under;
    snell_ctx *ctx = sv->ctx;
    int k;
    if (ps->status != SNELL_OK) return snell__fail(ctx, ps->status, "%s", ps->msg);
    if (fd->panel_count == 0) return SNELL_OK;
    if (sv->out != SNELL__OUT_COLOR)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "panels need a renderer of SNELL_OUTPUT_COLOR");
    if (!u) return SNELL_OK;
    if ((unsigned)u->source > SNELL_PANELS_UNDER_EXTERNAL)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "panels_under.source %d is not a snell_panels_under_source",
                           (int)u->source);
    for (k = 0; k < 16; k++)
        if (!isfinite(u->uv_transform[k]))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "panels_under.uv_transform[%d] is not finite", k);
    if (u->draw != 0 && u->draw != 1)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "panels_under.draw %d: 0 or 1", u->draw);
    if (u->source == SNELL_PANELS_UNDER_TEXTURE && !texture_of(u->texture, GL_TEXTURE_2D, GL_TEXTURE_BINDING_2D))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "panels_under.texture %u is not a GL_TEXTURE_2D of this context",
                           u->texture);
    if (u->source == SNELL_PANELS_UNDER_EXTERNAL) {
        if (!u->texture)
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "panels_under.texture is required for EXTERNAL");
        if (external_supported(ctx) &&
            !texture_of(u->texture, GL_TEXTURE_EXTERNAL_OES, GL_TEXTURE_BINDING_EXTERNAL_OES))
            return snell__fail(ctx, SNELL_E_INVALID_ARG,
                               "panels_under.texture %u is not a GL_TEXTURE_EXTERNAL_OES of this context", u->texture);
    }
    return SNELL_OK;
}

/* Where the frame is drawn when the panels run: the offscreen image read
 * back, or the bound framebuffer (its rectangle at the origin: render/host_target.h). */
static void plan(snell__frame *f, void *state)
{
    panels_state *ps = (panels_state *)state;
    GLint fbo = 0;
    if (f->sv->target == SNELL_TARGET_OFFSCREEN) {
        ps->target_fbo = f->sv->read_fbo ? f->sv->read_fbo : f->sv->fbo;
        return;
    }
    if (ps->count) glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    ps->target_fbo = (unsigned)fbo;
}

static int wanted(const snell__frame *f, const void *state)
{
    (void)f;
    return ((const panels_state *)state)->count > 0;
}

static snell_status build(snell_ctx *ctx, const char *fs, const char *defines, panel_prog *p)
{
    snell_status st;
    int k;
    if (p->id) return SNELL_OK;
    if ((st = snell__program_build(ctx, "panel.vert", fs, defines, &p->id)) != SNELL_OK) return st;
    for (k = 0; k < UNIFORMS; k++) p->loc[k] = glGetUniformLocation(p->id, g_uniform[k]);
    return SNELL_OK;
}

static void box_and(float a[4], const float b[4])
{
    a[0] = a[0] > b[0] ? a[0] : b[0], a[1] = a[1] > b[1] ? a[1] : b[1];
    a[2] = a[2] < b[2] ? a[2] : b[2], a[3] = a[3] < b[3] ? a[3] : b[3];
}

static int box_empty(const float b[4])
{
    return !(b[0] < b[2] && b[1] < b[3]);
}

static void box_grow(float a[4], const float b[4])
{
    a[0] = fminf(a[0], b[0]), a[1] = fminf(a[1], b[1]), a[2] = fmaxf(a[2], b[2]), a[3] = fmaxf(a[3], b[3]);
}

static int grid_cell(float x, int size)
{
    int c = (int)floorf(x * (float)GRID / (float)size);
    return c < 0 ? 0 : c >= GRID ? GRID - 1 : c;
}

/* Grows recopy by where box meets the shapes marked so far (a cell's
 * bounding box of them: never less than the exact overlap), then marks box. */
static void grid_add(panels_state *ps, const float box[4], float recopy[4], int w, int h)
{
    int cx0 = grid_cell(box[0], w), cx1 = grid_cell(box[2], w);
    int cy0 = grid_cell(box[1], h), cy1 = grid_cell(box[3], h), cx, cy;
    for (cy = cy0; cy <= cy1; cy++)
        for (cx = cx0; cx <= cx1; cx++) {
            float *c = ps->cell[cy * GRID + cx], o[4], part[4];
            const float rect[4] = {(float)cx * (float)w / GRID, (float)cy * (float)h / GRID,
                                   (float)(cx + 1) * (float)w / GRID, (float)(cy + 1) * (float)h / GRID};
            memcpy(o, box, sizeof o);
            box_and(o, c);
            if (!box_empty(o)) box_grow(recopy, o);
            memcpy(part, box, sizeof part);
            box_and(part, rect);
            if (!box_empty(part)) box_grow(c, part);
        }
}

/* The shapes in drawing order, their boxes clipped to w x h (culled when
 * empty) and where each overlaps one drawn before it; returns whether any does. */
static int shapes(panels_state *ps, int w, int h)
{
    const float frame[4] = {0.0f, 0.0f, (float)w, (float)h};
    int i, j, any = 0;
    ps->shapes = 0;
    for (i = 0; i < ps->count; i++) ps->next[i] = -1;
    for (i = 0; i < GRID * GRID; i++)
        ps->cell[i][0] = ps->cell[i][1] = INFINITY, ps->cell[i][2] = ps->cell[i][3] = -INFINITY;
    for (i = 0; i < ps->count; i++) {
        panel_shape *s;
        int g = ps->panel[i].group, last = i;
        for (j = 0; g && j < i && ps->panel[j].group != g; j++) {}
        if (g && j < i) continue; /* a member of a group drawn at its first panel */
        s = &ps->shape[ps->shapes];
        s->first = i, s->count = 0;
        s->box[0] = s->box[1] = INFINITY, s->box[2] = s->box[3] = -INFINITY;
        for (j = i; j < ps->count; j++) {
            float b[4];
            if (j != i && (!g || ps->panel[j].group != g)) continue;
            if (j != i) ps->next[last] = j, last = j;
            s->count++;
            snell__panel_bounds(&ps->panel[j], b);
            s->box[0] = fminf(s->box[0], b[0]), s->box[1] = fminf(s->box[1], b[1]);
            s->box[2] = fmaxf(s->box[2], b[2]), s->box[3] = fmaxf(s->box[3], b[3]);
            if (!g) break;
        }
        box_and(s->box, frame);
        if (box_empty(s->box)) continue;
        s->recopy[0] = s->recopy[1] = INFINITY, s->recopy[2] = s->recopy[3] = -INFINITY;
        grid_add(ps, s->box, s->recopy, w, h);
        any |= !box_empty(s->recopy);
        ps->shapes++;
    }
    return any;
}

static double box_pixels(const float b[4])
{
    return (double)(b[2] - b[0]) * (double)(b[3] - b[1]);
}

/* The panels' estimated cost in ms (UNITS_PER_MS), with frost and dispersion or without. */
static double estimate_ms(const panels_state *ps, int w, int h, int frost, int dispersion)
{
    double units = 0.0;
    int i, any_frost = 0;
    for (i = 0; i < ps->shapes; i++) {
        const snell__panel *p = &ps->panel[ps->shape[i].first];
        double taps = (frost && p->frost > 0.0f ? 4.0 : 1.0) * (dispersion && p->dispersion > 0.0f ? 3.0 : 1.0);
        units += box_pixels(ps->shape[i].box) * (3.0 + taps);
        any_frost |= frost && p->frost > 0.0f;
    }
    if (any_frost) units += 0.1 * (double)w * (double)h;
    return units / UNITS_PER_MS;
}

/* The capture's format for what the target's colour buffer holds. A blit
 * from a multisampled buffer needs the identical format, and converts
 * only fixed-point to fixed-point or float to float (GLES 3.0 4.3.3), so
 * the capture takes the buffer's own format where one is color-renderable
 * and filterable (table 3.13).
 * Returns 0 (and names the buffer in msg) where none serves. */
static GLenum capture_format(const panels_state *ps, char *msg, size_t size)
{
    GLint type = GL_UNSIGNED_NORMALIZED, enc = GL_LINEAR, r = 8, g = 8, b = 8, a = 8, samples = 0, drawn = GL_BACK;
    GLenum att;
    glBindFramebuffer(GL_FRAMEBUFFER, ps->target_fbo);
    glGetIntegerv(GL_DRAW_BUFFER0, &drawn);
    glGetIntegerv(GL_SAMPLE_BUFFERS, &samples);
    att = ps->target_fbo ? (GLenum)drawn : GL_BACK;
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING, &enc);
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, &r);
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_GREEN_SIZE, &g);
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_BLUE_SIZE, &b);
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_ALPHA_SIZE, &a);
    glGetError(); /* a query the driver refuses leaves the RGBA8 defaults */
    if (type == GL_UNSIGNED_NORMALIZED && enc == GL_SRGB) {
        if (r == 8 && g == 8 && b == 8 && (a == 8 || !samples)) return GL_SRGB8_ALPHA8;
    } else if (type == GL_UNSIGNED_NORMALIZED) {
        if (r == 5 && g == 6 && b == 5 && a == 0) return GL_RGB565;
        if (r == 8 && g == 8 && b == 8) return a ? GL_RGBA8 : GL_RGB8;
        if (r == 10 && g == 10 && b == 10 && a == 2) return GL_RGB10_A2;
        if (r == 4 && g == 4 && b == 4 && a == 4) return GL_RGBA4;
        if (r == 5 && g == 5 && b == 5 && a == 1) return GL_RGB5_A1;
        if (!samples) return GL_RGBA8;
    } else if (type == GL_FLOAT) {
        if (r == 11 && g == 11 && b == 10) return GL_R11F_G11F_B10F;
        if (r == 16 && g == 16 && b == 16 && a == 16) return GL_RGBA16F;
        if (!samples) return GL_RGBA16F;
    }
    snprintf(msg, size, "panels cannot read the target's colour buffer (%s%s, %d/%d/%d/%d bits%s)",
             type == GL_FLOAT ? "float" : type == GL_INT ? "signed integer" : type == GL_UNSIGNED_INT ? "unsigned integer"
                                                                                                       : "normalized",
             enc == GL_SRGB ? " sRGB" : "", r, g, b, a, samples ? ", multisampled" : "");
    return 0;
}

/* The capture at w x h with a full mip chain (frost), made once. */
static snell_status capture_make(snell_ctx *ctx, panels_state *ps, GLenum format, int w, int h)
{
    int big = w > h ? w : h;
    size_t texel = format == GL_RGBA16F ? 8u : 4u;
    snell_status st;
    if (ps->capture_tex && ps->cap_w == w && ps->cap_h == h && ps->cap_format == format) return SNELL_OK;
    if ((st = snell__budget_check(ctx, (size_t)w * (size_t)h * texel * 4u / 3u, "the panels' capture")) != SNELL_OK)
        return st;
    if (ps->capture_tex) glDeleteTextures(1, &ps->capture_tex);
    if (!ps->capture_fbo) glGenFramebuffers(1, &ps->capture_fbo);
    for (ps->levels = 1; big > 1; big >>= 1) ps->levels++;
    glGenTextures(1, &ps->capture_tex);
    glBindTexture(GL_TEXTURE_2D, ps->capture_tex);
    glTexStorage2D(GL_TEXTURE_2D, ps->levels, format, w, h);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, ps->capture_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, ps->capture_tex, 0);
    ps->cap_w = w, ps->cap_h = h, ps->cap_format = format;
    if (glGetError() != GL_NO_ERROR || glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        glDeleteTextures(1, &ps->capture_tex);
        ps->capture_tex = 0;
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "panels: a %dx%d capture of format 0x%04x cannot be drawn to here",
                           w, h, (unsigned)format);
    }
    return SNELL_OK;
}

/* The target's pixels in b (rounded out to whole pixels) copied into the capture. */
static void capture_copy(const panels_state *ps, const float b[4])
{
    GLint x0 = (GLint)floorf(b[0]), y0 = (GLint)floorf(b[1]), x1 = (GLint)ceilf(b[2]), y1 = (GLint)ceilf(b[3]);
    GLint drawn = GL_BACK, read = GL_BACK;
    glBindFramebuffer(GL_FRAMEBUFFER, ps->target_fbo);
    glGetIntegerv(GL_DRAW_BUFFER0, &drawn);
    glGetIntegerv(GL_READ_BUFFER, &read);
    glReadBuffer((GLenum)drawn); /* what the frame drew, not the host's read buffer */
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, ps->capture_fbo);
    glBlitFramebuffer(x0, y0, x1, y1, x0, y0, x1, y1, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glReadBuffer((GLenum)read);
}

/* The mip chain over b only, after b was copied again: each level's box
 * (rounded out) a 2:1 linear blit of the level above, the 2x2 mean that
 * glGenerateMipmap makes, so that N overlaps cost N boxes, not N frames. */
static void mips_over(panels_state *ps, const float b[4])
{
    int x0 = (int)floorf(b[0]), y0 = (int)floorf(b[1]), x1 = (int)ceilf(b[2]), y1 = (int)ceilf(b[3]), l;
    if (!ps->mip_fbo) glGenFramebuffers(1, &ps->mip_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, ps->capture_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, ps->mip_fbo);
    for (l = 1; l < ps->levels; l++) {
        int w = ps->cap_w >> l > 1 ? ps->cap_w >> l : 1, h = ps->cap_h >> l > 1 ? ps->cap_h >> l : 1;
        int pw = ps->cap_w >> (l - 1) > 1 ? ps->cap_w >> (l - 1) : 1, ph = ps->cap_h >> (l - 1) > 1 ? ps->cap_h >> (l - 1) : 1;
        x0 >>= 1, y0 >>= 1, x1 = (x1 + 1) >> 1, y1 = (y1 + 1) >> 1;
        if (x1 > w) x1 = w;
        if (y1 > h) y1 = h;
        glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, ps->capture_tex, l - 1);
        glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, ps->capture_tex, l);
        glBlitFramebuffer(2 * x0, 2 * y0, 2 * x1 < pw ? 2 * x1 : pw, 2 * y1 < ph ? 2 * y1 : ph, x0, y0, x1, y1,
                          GL_COLOR_BUFFER_BIT, GL_LINEAR);
    }
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, ps->capture_tex, 0);
}

static void sampler(unsigned *s, GLint min)
{
    glGenSamplers(1, s);
    glSamplerParameteri(*s, GL_TEXTURE_MIN_FILTER, min);
    glSamplerParameteri(*s, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(*s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(*s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

/* The app's texture over the whole w x h of the bound framebuffer. */
static void draw_texture(const panel_prog *p, const float *uv, int w, int h)
{
    const float box[4] = {0.0f, 0.0f, (float)w, (float)h};
    glUseProgram(p->id);
    glUniformMatrix4fv(p->loc[U_UV], 1, GL_FALSE, uv);
    glUniform2f(p->loc[U_SIZE], (float)w, (float)h);
    glUniform4fv(p->loc[U_BOX], 1, box);
    glUniform1i(p->loc[U_BENEATH], 0);
    glViewport(0, 0, w, h);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

static void draw_shape(const panels_state *ps, const panel_prog *p, const panel_shape *s, int frost, int dispersion,
                       int w, int h)
{
    const snell__panel *m = &ps->panel[s->first];
    float rect[4 * SNELL_PANEL_GROUP_MAX], radius[4 * SNELL_PANEL_GROUP_MAX], expo[SNELL_PANEL_GROUP_MAX];
    float ior[3], lod = 0.0f, spread = 0.0f;
    int i = s->first, n = 0;
    for (; i >= 0 && n < SNELL_PANEL_GROUP_MAX; i = ps->next[i], n++) {
        const snell__panel *q = &ps->panel[i];
        memcpy(rect + 4 * n, q->center, 2 * sizeof(float));
        memcpy(rect + 4 * n + 2, q->half, 2 * sizeof(float));
        memcpy(radius + 4 * n, q->radius, 4 * sizeof(float));
        expo[n] = q->exponent;
    }
    snell_opt_ior_rgb(m->ior, dispersion ? m->dispersion : 0.0f, ior);
    /* Frost, a Gaussian of sigma f: level L of the mip chain is a blur of
     * variance (3 4^L - 1) / 12 pixels^2 per axis (each halving's box of
     * two adds 4^(k-1) / 4, the bilinear tent of level L 4^L / 6); L makes
     * it half of f^2, and four taps at (+-a, +-a) add the other half: four
     * overlapping blobs, nearer a Gaussian than one tap of a coarser level. */
    if (frost && m->frost > 0.0f) {
        lod = fmaxf(0.0f, 0.5f * log2f((6.0f * m->frost * m->frost + 1.0f) / 3.0f));
        spread = sqrtf(fmaxf(0.0f, m->frost * m->frost - (3.0f * exp2f(2.0f * lod) - 1.0f) / 12.0f));
    }
    glUniform1f(p->loc[U_LOD], lod);
    glUniform1f(p->loc[U_SPREAD], spread);
    glUniform1i(p->loc[U_COUNT], n);
    glUniform4fv(p->loc[U_RECT], n, rect);
    glUniform4fv(p->loc[U_RADIUS], n, radius);
    glUniform1fv(p->loc[U_EXPONENT], n, expo);
    glUniform1f(p->loc[U_MERGE], m->merge);
    glUniform3f(p->loc[U_SLAB], m->thickness, m->bevel, m->profile == SNELL_PANEL_BEVEL_SQUIRCLE ? 1.0f : 0.0f);
    glUniform3fv(p->loc[U_IOR], 1, ior);
    glUniform4fv(p->loc[U_TINT], 1, m->tint);
    glUniform4f(p->loc[U_LIGHT], m->light[0], m->light[1], m->light[2], m->rim);
    glUniform4fv(p->loc[U_SHADOW], 1, m->shadow);
    glUniform4fv(p->loc[U_BOX], 1, s->box);
    glUniform2f(p->loc[U_SIZE], (float)w, (float)h);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

static snell_status run(snell__frame *f, void *state)
{
    panels_state *ps = (panels_state *)state;
    const snell__services *sv = f->sv;
    const snell_frame_desc *fd = f->fd;
    snell_frame_stats *s = f->s;
    snell_ctx *ctx = sv->ctx;
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const snell_panels_under *u = fd->panels_under;
    const float *uv = identity;
    int w = sv->out_width, h = sv->out_height, source = SRC_CAPTURE, frost = 1, dispersion = 1;
    int any_frost = 0, any_dispersion = 0, overlap, capture, i, k;
    GLint prev_external = 0;
    size_t n = 0;
    snell_status st;
    const char *where = "the frame's rectangle";

    overlap = shapes(ps, w, h);
    for (i = 0; i < ps->shapes; i++) {
        any_frost |= ps->panel[ps->shape[i].first].frost > 0.0f;
        any_dispersion |= ps->panel[ps->shape[i].first].dispersion > 0.0f;
    }
    if (u && u->source != SNELL_PANELS_UNDER_TARGET) {
        for (k = 0; k < 16 && u->uv_transform[k] == 0.0f; k++) {}
        if (k < 16) uv = u->uv_transform;
        if (u->source == SNELL_PANELS_UNDER_TEXTURE) source = SRC_TEXTURE, where = "the app's texture";
        else if (external_supported(ctx)) source = SRC_EXTERNAL, where = "the app's external texture";
        else where = "the frame's rectangle (EXTERNAL without GL_OES_EGL_image_external_essl3)";
    }
    n += (size_t)snprintf(s->panels_reason, sizeof s->panels_reason, "beneath: %s", where);
    /* The budget: frost goes first (a mip chain of the frame and a blurred
     * read), then dispersion (two more refractions and taps a pixel). */
    if (fd->budget_ms > 0.0f) {
        double full = estimate_ms(ps, w, h, 1, 1);
        if (any_frost && full > fd->budget_ms) frost = 0, s->panels_dropped |= SNELL_PANELS_DROPPED_FROST;
        if (any_dispersion && estimate_ms(ps, w, h, frost, 1) > fd->budget_ms)
            dispersion = 0, s->panels_dropped |= SNELL_PANELS_DROPPED_DISPERSION;
        if (s->panels_dropped && n < sizeof s->panels_reason)
            snprintf(s->panels_reason + n, sizeof s->panels_reason - n,
                     "; %.2f ms estimated over the budget's %.2f: %s%s%s dropped", full, (double)fd->budget_ms,
                     frost ? "" : "frost", frost || dispersion ? "" : " and ", dispersion ? "" : "dispersion");
    }
    capture = source == SRC_CAPTURE || (frost && any_frost) || overlap;

    if (!ps->linear) {
        sampler(&ps->linear, GL_LINEAR);
        sampler(&ps->trilinear, GL_LINEAR_MIPMAP_LINEAR);
        glGenVertexArrays(1, &ps->vao);
    }
    if (source != SRC_CAPTURE) {
        k = source == SRC_EXTERNAL;
        if ((st = build(ctx, "panel_copy.frag", k ? "#define PANEL_EXTERNAL 1\n" : "", &ps->copy[k])) != SNELL_OK)
            return st;
    }
    if (capture) {
        GLenum format = GL_RGBA8; /* an app's texture drawn in, unless overlaps copy the target in too */
        if ((source == SRC_CAPTURE || overlap) && !(format = capture_format(ps, ps->msg, sizeof ps->msg)))
            return snell__fail(ctx, SNELL_E_UNSUPPORTED, "%s", ps->msg);
        if ((st = capture_make(ctx, ps, format, w, h)) != SNELL_OK) return st;
    }
    for (k = 0; k < 2; k++) {
        static const char *const defines[SOURCES][2] = {
            {"", "#define PANEL_DISPERSION 1\n"},
            {"#define PANEL_SOURCE 1\n", "#define PANEL_SOURCE 1\n#define PANEL_DISPERSION 1\n"},
            {"#define PANEL_SOURCE 2\n", "#define PANEL_SOURCE 2\n#define PANEL_DISPERSION 1\n"}};
        int src = capture ? SRC_CAPTURE : source;
        if ((k == 0 || (dispersion && any_dispersion)) &&
            (st = build(ctx, "panel.frag", defines[src][k], &ps->prog[src][k])) != SNELL_OK)
            return st;
    }

    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_FALSE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindVertexArray(ps->vao);
    glActiveTexture(GL_TEXTURE0);
    if (source == SRC_EXTERNAL) {
        glGetIntegerv(GL_TEXTURE_BINDING_EXTERNAL_OES, &prev_external); /* not among the units the frame restores */
        glBindTexture(GL_TEXTURE_EXTERNAL_OES, u->texture);
    } else if (source == SRC_TEXTURE) {
        glBindTexture(GL_TEXTURE_2D, u->texture);
    }
    glBindSampler(0, ps->linear);
    /* The app's texture: drawn as the picture under the panels, and into
     * the capture where one is read. */
    if (source != SRC_CAPTURE && u->draw) {
        glBindFramebuffer(GL_FRAMEBUFFER, ps->target_fbo);
        draw_texture(&ps->copy[source == SRC_EXTERNAL], uv, w, h);
    }
    if (capture) {
        const float all[4] = {0.0f, 0.0f, (float)w, (float)h};
        if (source == SRC_CAPTURE) {
            capture_copy(ps, all);
        } else {
            glBindFramebuffer(GL_FRAMEBUFFER, ps->capture_fbo);
            draw_texture(&ps->copy[source == SRC_EXTERNAL], uv, w, h);
        }
        s->panels_captures++;
        if (source == SRC_EXTERNAL) glBindTexture(GL_TEXTURE_EXTERNAL_OES, (GLuint)prev_external);
        glBindTexture(GL_TEXTURE_2D, ps->capture_tex);
        if (frost && any_frost) glGenerateMipmap(GL_TEXTURE_2D);
        glBindSampler(0, frost && any_frost ? ps->trilinear : ps->linear);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, ps->target_fbo);
    glViewport(0, 0, w, h);
    for (i = 0; i < ps->shapes; i++) {
        const panel_shape *sh = &ps->shape[i];
        int disp = dispersion && ps->panel[sh->first].dispersion > 0.0f;
        const panel_prog *p = &ps->prog[capture ? SRC_CAPTURE : source][disp];
        if (capture && !box_empty(sh->recopy)) {
            capture_copy(ps, sh->recopy);
            if (frost && any_frost) mips_over(ps, sh->recopy);
            glBindFramebuffer(GL_FRAMEBUFFER, ps->target_fbo);
            s->panels_captures++;
        }
        glUseProgram(p->id);
        glUniform1i(p->loc[U_BENEATH], 0);
        glUniformMatrix4fv(p->loc[U_UV], 1, GL_FALSE, uv);
        draw_shape(ps, p, sh, frost, disp, w, h);
        s->panels_drawn++;
    }
    s->passes += ps->shapes;
    glBindSampler(0, 0);
    if (source == SRC_EXTERNAL && !capture) glBindTexture(GL_TEXTURE_EXTERNAL_OES, (GLuint)prev_external);
    glBindTexture(GL_TEXTURE_2D, 0);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "GL error drawing the panels");
}

const snell__stage snell__stage_panels = {
    .name = "panels",
    .state_size = sizeof(panels_state),
    .destroy = destroy,
    .validate = validate,
    .resolve = resolve,
    .plan = plan,
    .wanted = wanted,
    .run = run,
};
