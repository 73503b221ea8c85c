/* SPDX-License-Identifier: MIT */
/* env_probe.c — snell_renderer_env_probe: the kernels' environment look-up
 * (common/env.glsl) run on the GPU for given directions, one per pixel of a
 * scratch target, so its error can be measured against exact radiance. */
#include "render/renderer.h"
#include "frame/env.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "core/program.h"

#include <string.h>

#define PROBE_WIDTH 1024
#define PROBE_MAX (1 << 20)

typedef struct probe_gl {
    unsigned prog, dirs_tex, target, fbo, vao;
    int width, height, float_target;
} probe_gl;

static void probe_release(probe_gl *p)
{
    if (p->prog) glDeleteProgram(p->prog);
    if (p->dirs_tex) glDeleteTextures(1, &p->dirs_tex);
    if (p->target) glDeleteRenderbuffers(1, &p->target);
    if (p->fbo) glDeleteFramebuffers(1, &p->fbo);
    if (p->vao) glDeleteVertexArrays(1, &p->vao);
}

/* The directions as an RGBA32F texture (texelFetch only: float textures need
 * no filtering extension then), row-major, the tail of the last row zero. */
static snell_status upload_dirs(snell_renderer *r, probe_gl *p, const float *dirs, int n, float *scratch)
{
    snell__pixel_store unpack;
    int i;
    memset(scratch, 0, (size_t)p->width * p->height * 4 * sizeof(float));
    for (i = 0; i < n; i++) memcpy(scratch + 4 * (size_t)i, dirs + 3 * (size_t)i, 3 * sizeof(float));
    snell__pixel_unpack_begin(&unpack, 4);
    glGenTextures(1, &p->dirs_tex);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, p->dirs_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, p->width, p->height, 0, GL_RGBA, GL_FLOAT, scratch);
    snell__texture_nearest(GL_TEXTURE_2D, 0);
    snell__pixel_unpack_end(&unpack);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(r->ctx, SNELL_E_GL, "env probe: direction upload failed");
}

static snell_status run_probe(snell_renderer *r, const snell_env *env, int paraboloid, probe_gl *p, const float *dirs,
                              int n, float *rgb)
{
    snell__pixel_store pack;
    unsigned env_tex = env->texture;
    float *scratch;
    snell_status st;
    int i, u_env, u_dirs;
    scratch = (float *)snell__malloc(&r->ctx->alloc, (size_t)p->width * p->height * 4 * sizeof(float));
    if (!scratch) return snell__fail(r->ctx, SNELL_E_NOMEM, "env probe: out of memory for %d directions", n);
    st = snell__program_build(r->ctx, "screen.vert", "env_probe.frag",
                              paraboloid ? SNELL__ENV_PARABOLOID_DEFINE : NULL, &p->prog);
    if (st == SNELL_OK && paraboloid) st = snell__env_paraboloid(r->ctx, &r->dp, env, &env_tex);
    if (st == SNELL_OK) st = upload_dirs(r, p, dirs, n, scratch);
    if (st == SNELL_OK) {
        p->float_target = snell_ctx_has_gl_extension(r->ctx, "GL_EXT_color_buffer_float");
        glGenRenderbuffers(1, &p->target);
        glBindRenderbuffer(GL_RENDERBUFFER, p->target);
        glRenderbufferStorage(GL_RENDERBUFFER, p->float_target ? GL_RGBA32F : GL_RGBA8, p->width, p->height);
        glGenFramebuffers(1, &p->fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, p->fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, p->target);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            st = snell__fail(r->ctx, SNELL_E_GL, "env probe: target incomplete");
    }
    if (st == SNELL_OK) {
        glViewport(0, 0, p->width, p->height);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_CULL_FACE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glUseProgram(p->prog);
        u_env = glGetUniformLocation(p->prog, "u_env");
        u_dirs = glGetUniformLocation(p->prog, "u_dirs");
        glUniform1i(u_env, 0);
        glUniform1i(u_dirs, 1);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(paraboloid ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_CUBE_MAP, env_tex);
        glGenVertexArrays(1, &p->vao);
        glBindVertexArray(p->vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        snell__pixel_pack_begin(&pack, 4);
        if (p->float_target) {
            glReadPixels(0, 0, p->width, p->height, GL_RGBA, GL_FLOAT, scratch);
            for (i = 0; i < n; i++) memcpy(rgb + 3 * (size_t)i, scratch + 4 * (size_t)i, 3 * sizeof(float));
        } else {
            uint8_t *px = (uint8_t *)scratch; /* 4 bytes a pixel fit in the 16 of the float scratch */
            glReadPixels(0, 0, p->width, p->height, GL_RGBA, GL_UNSIGNED_BYTE, px);
            for (i = 0; i < 3 * n; i++) rgb[i] = px[4 * (i / 3) + i % 3] / 255.0f;
        }
        snell__pixel_pack_end(&pack);
        if (glGetError() != GL_NO_ERROR) st = snell__fail(r->ctx, SNELL_E_GL, "env probe: GL error");
    }
    snell__free(&r->ctx->alloc, scratch);
    return st;
}

snell_status snell_renderer_env_probe(snell_renderer *r, const snell_env *env, snell_env_lookup lookup,
                                      const float *dirs, int n, float *rgb)
{
    snell_glstate saved;
    probe_gl p;
    snell_status st;
    if (!r || !env || !dirs || !rgb)
        return snell__fail(r ? r->ctx : NULL, SNELL_E_INVALID_ARG, "snell_renderer_env_probe: NULL argument");
    if (n < 1 || n > PROBE_MAX)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "snell_renderer_env_probe: n %d outside 1..%d", n, PROBE_MAX);
    if ((unsigned)lookup > SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "snell_renderer_env_probe: unknown look-up %d", (int)lookup);
    if ((st = snell__ctx_check_current(r->ctx, "snell_renderer_env_probe")) != SNELL_OK) return st;
    if (!env->texture || (env->ctx && env->ctx != r->ctx))
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "snell_renderer_env_probe: the environment is not this "
                                                         "context's");
    memset(&p, 0, sizeof p);
    p.width = n < PROBE_WIDTH ? n : PROBE_WIDTH;
    p.height = (n + PROBE_WIDTH - 1) / PROBE_WIDTH;
    snell__glstate_save(&saved);
    st = run_probe(r, env,
                   lookup == SNELL_ENV_LOOKUP_AUTO ? snell__env_lookup_paraboloid(r->sv.env_lookup, 0) : lookup != SNELL_ENV_LOOKUP_CUBE,
                   &p, dirs, n, rgb);
    probe_release(&p);
    glUseProgram(0); /* before restoring: ours is deleted (render/renderer.c says why) */
    snell__glstate_restore(&saved);
    return st;
}
