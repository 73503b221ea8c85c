/* SPDX-License-Identifier: MIT */
/* test_panels_formats — panels over the host's bound framebuffer in each
 * colour format a GLES 3.0 app or EGL config uses (RGB565, RGB8, RGBA8,
 * RGB10_A2, SRGB8_ALPHA8, RGBA16F/32F, multisampled ones): a flat interior
 * is (1 - F0) times what the buffer held, within the format's step (sRGB:
 * in its encoded values, snell_panels.h); an integer buffer is refused as
 * SNELL_E_UNSUPPORTED. */
#include "test_util.h"
#include "core/gl.h"

#include <EGL/egl.h>
#include <math.h>
#include <string.h>

#define W 96
#define H 64

static snell_ctx *g_ctx;

typedef struct fmt {
    const char *name;
    GLenum format;
    int samples, texture, srgb, is_float, bits; /* bits: of a channel; float: of its mantissa */
} fmt;


/* Renders one frame of panels into the bound framebuffer fbo (W x H). */
static snell_status frame(GLuint fbo, snell_frame_stats *s)
{
    snell_renderer_desc rd;
    snell_renderer *r = NULL;
    snell_frame_desc fd;
    snell_panel p[2];
    snell_status st;
    int i;
    memset(p, 0, sizeof p);
    for (i = 0; i < 2; i++) {
        p[i].center[0] = i ? 66.0f : 30.0f, p[i].center[1] = 32.0f, p[i].size[0] = p[i].size[1] = 40.0f;
        p[i].bevel = p[i].thickness = 8.0f, p[i].ior = 1.5f, p[i].rim = -1.0f, p[i].shadow[0] = -1.0f;
    }
    p[1].frost = 2.0f; /* over the first: its overlap copied again, the mip chain made in the target's format */
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, W, H);
    memset(&rd, 0, sizeof rd);
    rd.width = W, rd.height = H, rd.target = SNELL_TARGET_BOUND_FRAMEBUFFER;
    if ((st = snell_renderer_create(g_ctx, &rd, &r)) != SNELL_OK) return st;
    memset(&fd, 0, sizeof fd);
    fd.draw_background = SNELL_BACKGROUND_NONE, fd.panels = p, fd.panel_count = 2;
    st = snell_render(r, &fd, s);
    snell_renderer_destroy(r);
    return st;
}

static void check(const fmt *f, const float clear[4])
{
    GLuint fbo, rb = 0, depth, tex = 0, rfbo = 0, rrb = 0, read;
    snell_frame_stats s;
    snell_status st;
    float px[4 * 2];
    int c, k, xs[2] = {26, 70};
    double step = f->is_float ? 0.0 : 1.0 / ((1 << f->bits) - 1);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    if (f->texture) {
        glGenTextures(1, &tex);
        glBindTexture(GL_TEXTURE_2D, tex);
        glTexStorage2D(GL_TEXTURE_2D, 1, f->format, W, H);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    } else {
        glGenRenderbuffers(1, &rb);
        glBindRenderbuffer(GL_RENDERBUFFER, rb);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, f->samples, f->format, W, H);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    }
    glGenRenderbuffers(1, &depth); /* a bound framebuffer needs one (render/host_target.h) */
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, f->samples, GL_DEPTH24_STENCIL8, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        printf("%s: not renderable here, skipped\n", f->name);
        glGetError();
        goto done;
    }
    glDisable(GL_DITHER);
    glClearColor(clear[0], clear[1], clear[2], clear[3]);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_DITHER);
    st = frame(fbo, &s);
    if (f->format == GL_RGBA8UI) {
        const char *m = snell_last_error(g_ctx);
        CHECK(st == SNELL_E_UNSUPPORTED && m && strstr(m, "integer"), "%s: refused: %d, %s", f->name, (int)st,
              m ? m : "");
        goto done;
    }
    if (f->srgb && st == SNELL_E_UNSUPPORTED && !snell_ctx_has_gl_extension(g_ctx, "GL_EXT_sRGB_write_control")) {
        /* snell refuses an sRGB host buffer it cannot write unencoded (render/host_target.c) */
        const char *m = snell_last_error(g_ctx);
        CHECK(m && strstr(m, "sRGB_write_control"), "%s: refused for its reason: %s", f->name, m ? m : "");
        printf("%s: no GL_EXT_sRGB_write_control: refused by name, as every frame into it is\n", f->name);
        goto done;
    }
    CHECK_OK_CTX(g_ctx, st);
    if (st != SNELL_OK) goto done;
    CHECK(s.panels_drawn == 2 && s.panels_captures == 2, "%s: %d drawn, %d captures", f->name, s.panels_drawn,
          s.panels_captures);
    read = fbo;
    if (f->samples) { /* resolved into a single-sampled buffer of the same format to read */
        glGenRenderbuffers(1, &rrb);
        glBindRenderbuffer(GL_RENDERBUFFER, rrb);
        glRenderbufferStorage(GL_RENDERBUFFER, f->format, W, H);
        glGenFramebuffers(1, &rfbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, rfbo);
        glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rrb);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        read = rfbo;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, read);
    for (k = 0; k < 2; k++) {
        if (f->is_float) {
            glReadPixels(xs[k], 32, 1, 1, GL_RGBA, GL_FLOAT, px + 4 * k);
        } else {
            GLubyte b[4];
            glReadPixels(xs[k], 32, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, b);
            for (c = 0; c < 4; c++) px[4 * k + c] = (float)b[c] / 255.0f;
        }
    }
    CHECK(glGetError() == GL_NO_ERROR, "%s: no GL error", f->name);
    for (k = 0; k < 2; k++)
        for (c = 0; c < 3; c++) {
            double stored = f->is_float ? clear[c] : floor(clear[c] / step + 0.5) * step, want, tol;
            if (f->srgb) want = 0.96 * stored, tol = 1.0 / 255.0;
            else want = 0.96 * stored, tol = f->is_float ? 2.0 * stored / (1 << f->bits) : step + (f->bits > 8 ? 1.0 / 255.0 : 0.0);
            CHECK(fabs(px[4 * k + c] - want) <= tol + 1e-6, "%s panel %d channel %d: %.4f, (1 - F0) beneath %.4f", f->name,
                  k, c, (double)px[4 * k + c], want);
        }
done:
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    if (rfbo) glDeleteFramebuffers(1, &rfbo);
    if (rb) glDeleteRenderbuffers(1, &rb);
    glDeleteRenderbuffers(1, &depth);
    if (rrb) glDeleteRenderbuffers(1, &rrb);
    if (tex) glDeleteTextures(1, &tex);
}

int main(void)
{
    static const float unorm[4] = {0.6f, 0.35f, 0.2f, 1.0f}, dark[4] = {0.12f, 0.3f, 0.06f, 1.0f},
                       hdr[4] = {3.0f, 0.5f, 0.25f, 1.0f};
    static const fmt fmts[] = {
        {"RGBA8 texture", GL_RGBA8, 0, 1, 0, 0, 8},
        {"RGB565 renderbuffer", GL_RGB565, 0, 0, 0, 0, 5},
        {"RGB8 renderbuffer", GL_RGB8, 0, 0, 0, 0, 8},
        {"RGB10_A2 texture", GL_RGB10_A2, 0, 1, 0, 0, 10},
        {"SRGB8_ALPHA8 texture", GL_SRGB8_ALPHA8, 0, 1, 1, 0, 8},
        {"RGBA8 x4", GL_RGBA8, 4, 0, 0, 0, 8},
        {"RGB565 x4", GL_RGB565, 4, 0, 0, 0, 5},
        {"SRGB8_ALPHA8 x4", GL_SRGB8_ALPHA8, 4, 0, 1, 0, 8},
        {"RGB10_A2 x4", GL_RGB10_A2, 4, 0, 0, 0, 10},
        {"RGBA8UI renderbuffer", GL_RGBA8UI, 0, 0, 0, 0, 8},
    };
    static const fmt floats[] = {
        {"RGBA16F texture", GL_RGBA16F, 0, 1, 0, 1, 10},
        {"RGBA32F texture", GL_RGBA32F, 0, 1, 0, 1, 10},
        {"R11F_G11F_B10F texture", GL_R11F_G11F_B10F, 0, 1, 0, 1, 5},
        {"RGBA16F x4", GL_RGBA16F, 4, 0, 0, 1, 10},
    };
    EGLDisplay dpy;
    EGLContext egl;
    snell_ctx_desc d;
    size_t i;
    if (!test_host_context(&dpy, &egl)) SKIP("cannot make a host context here");
    memset(&d, 0, sizeof d);
    d.backend = SNELL_BACKEND_EXTERNAL;
    CHECK_OK(snell_ctx_create(&d, &g_ctx));
    if (!g_ctx) return test_finish();
    for (i = 0; i < sizeof fmts / sizeof fmts[0]; i++) check(&fmts[i], fmts[i].srgb ? dark : unorm);
    if (snell_ctx_has_gl_extension(g_ctx, "GL_EXT_color_buffer_float"))
        for (i = 0; i < sizeof floats / sizeof floats[0]; i++)
            check(&floats[i], floats[i].format == GL_R11F_G11F_B10F ? unorm : hdr);
    else
        printf("no GL_EXT_color_buffer_float: float buffers not tried\n");
    snell_ctx_destroy(g_ctx);
    return test_finish();
}
