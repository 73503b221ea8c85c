/* SPDX-License-Identifier: MIT */
/* water_gpu.c — the GPU water simulation: two RG32UI textures holding the fp32
 * bits of (height, velocity), ping-ponged by one pass per step (water_step.frag),
 * drops as their own pass (water_drop.frag), the settle check a max-reduction
 * read back a call later through a pixel buffer and a fence (water_reduce.frag).
 * RG32UI: colour-renderable in GLES 3.0 without extensions and exact, so the GPU
 * integrates the CPU's fp32 numbers. Every pass restores the GL state it
 * touches (the water may step inside a host's loop). */
#include "water/water.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "core/program.h"

#include <string.h>

static snell_status check_fbo(snell_water *w, const char *what)
{
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return snell__fail(w->ctx, SNELL_E_GL, "water: %s framebuffer incomplete (0x%x)", what, (unsigned)status);
    return SNELL_OK;
}

static void make_uint_target(GLuint tex, int size)
{
    glBindTexture(GL_TEXTURE_2D, tex);
    snell__texture_nearest(GL_TEXTURE_2D, 1);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RG32UI, size, size);
}

snell_status snell__water_gpu_create(snell_water *w)
{
    snell_glstate saved;
    snell_status st = SNELL_OK;
    int k, n = w->n;
    size_t nodes = (size_t)n * (size_t)n;
    uint32_t *zeros;
    w->reduce_size = (n + 15) / 16;
    /* Read-back scratch: RGBA_INTEGER rows of the state (GLES 3.0's one
     * guaranteed format for integer targets), also holds the reduction. */
    w->reduce_px = (uint32_t *)snell__calloc(&w->alloc, nodes, 4 * sizeof(uint32_t));
    if (!w->reduce_px) return snell__fail(w->ctx, SNELL_E_NOMEM, "out of memory for the water read-back");
    zeros = w->reduce_px;
    snell__glstate_save(&saved);
    st = snell__program_build(w->ctx, "screen.vert", "water_step.frag", NULL, &w->prog_step);
    if (st == SNELL_OK) st = snell__program_build(w->ctx, "screen.vert", "water_drop.frag", NULL, &w->prog_drop);
    if (st == SNELL_OK) st = snell__program_build(w->ctx, "screen.vert", "water_reduce.frag", NULL, &w->prog_reduce);
    if (st == SNELL_OK) {
        snell__pixel_store unpack;
        glGenTextures(2, w->state_tex);
        glGenFramebuffers(2, w->state_fbo);
        snell__pixel_unpack_begin(&unpack, 4);
        for (k = 0; k < 2 && st == SNELL_OK; k++) {
            make_uint_target(w->state_tex[k], n);
            glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, n, n, GL_RG_INTEGER, GL_UNSIGNED_INT, zeros);
            glBindFramebuffer(GL_FRAMEBUFFER, w->state_fbo[k]);
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, w->state_tex[k], 0);
            st = check_fbo(w, "state");
        }
        snell__pixel_unpack_end(&unpack);
    }
    if (st == SNELL_OK) {
        glGenTextures(1, &w->reduce_tex);
        make_uint_target(w->reduce_tex, w->reduce_size);
        glGenFramebuffers(1, &w->reduce_fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, w->reduce_fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, w->reduce_tex, 0);
        st = check_fbo(w, "reduction");
        glGenVertexArrays(1, &w->empty_vao);
        glGenBuffers(1, &w->reduce_pbo);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, w->reduce_pbo);
        glBufferData(GL_PIXEL_PACK_BUFFER, (GLsizeiptr)w->reduce_size * w->reduce_size * 4 * sizeof(uint32_t), NULL,
                     GL_STREAM_READ);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    }
    if (st == SNELL_OK && glGetError() != GL_NO_ERROR)
        st = snell__fail(w->ctx, SNELL_E_GL, "water: GL error creating the %dx%d RG32UI simulation targets", n, n);
    snell__glstate_restore(&saved);
    return st;
}

static void drop_pending(snell_water *w)
{
    if (w->reduce_fence) glDeleteSync((GLsync)w->reduce_fence);
    w->reduce_fence = NULL;
}

void snell__water_gpu_destroy(snell_water *w)
{
    drop_pending(w);
    if (w->reduce_pbo) glDeleteBuffers(1, &w->reduce_pbo);
    if (w->prog_step) glDeleteProgram(w->prog_step);
    if (w->prog_drop) glDeleteProgram(w->prog_drop);
    if (w->prog_reduce) glDeleteProgram(w->prog_reduce);
    if (w->state_tex[0]) glDeleteTextures(2, w->state_tex);
    if (w->state_fbo[0]) glDeleteFramebuffers(2, w->state_fbo);
    if (w->reduce_tex) glDeleteTextures(1, &w->reduce_tex);
    if (w->reduce_fbo) glDeleteFramebuffers(1, &w->reduce_fbo);
    if (w->empty_vao) glDeleteVertexArrays(1, &w->empty_vao);
}

/* The state common to every simulation pass. */
static void begin_pass(const snell_water *w, GLuint prog)
{
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DITHER);
    glDisable(GL_RASTERIZER_DISCARD);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glUseProgram(prog);
    glBindVertexArray(w->empty_vao);
    glActiveTexture(GL_TEXTURE0);
    glBindSampler(0, 0);
    glUniform1i(glGetUniformLocation(prog, "u_state"), 0);
}

/* Reads state_tex[cur] into the target of the other one and swaps. */
static void ping_pong(snell_water *w)
{
    glBindFramebuffer(GL_FRAMEBUFFER, w->state_fbo[1 - w->cur]);
    glViewport(0, 0, w->n, w->n);
    glBindTexture(GL_TEXTURE_2D, w->state_tex[w->cur]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    w->cur = 1 - w->cur;
}

static snell_status end_pass(snell_water *w, snell_glstate *saved, const char *what)
{
    GLenum err = glGetError();
    glUseProgram(0);
    glBindVertexArray(0);
    snell__glstate_restore(saved);
    return err == GL_NO_ERROR ? SNELL_OK : snell__fail(w->ctx, SNELL_E_GL, "water: GL error 0x%x in the %s pass", err, what);
}

snell_status snell__water_gpu_step(snell_water *w, float k, float dt, float damp, int steps)
{
    snell_glstate saved;
    int i;
    snell__glstate_save(&saved);
    begin_pass(w, w->prog_step);
    glUniform1i(glGetUniformLocation(w->prog_step, "u_n"), w->n);
    glUniform1f(glGetUniformLocation(w->prog_step, "u_k"), k);
    glUniform1f(glGetUniformLocation(w->prog_step, "u_dt"), dt);
    glUniform1f(glGetUniformLocation(w->prog_step, "u_damp"), damp);
    for (i = 0; i < steps; i++) ping_pong(w);
    return end_pass(w, &saved, "step");
}

snell_status snell__water_gpu_drop(snell_water *w, float x, float z, float radius, float amplitude)
{
    snell_glstate saved;
    drop_pending(w); /* a settle check from before the drop says nothing now */
    snell__glstate_save(&saved);
    begin_pass(w, w->prog_drop);
    glUniform1f(glGetUniformLocation(w->prog_drop, "u_half"), 0.5f * w->d.width);
    glUniform1f(glGetUniformLocation(w->prog_drop, "u_dx"), w->dx);
    glUniform4f(glGetUniformLocation(w->prog_drop, "u_drop"), x, z, radius, amplitude);
    ping_pong(w);
    return end_pass(w, &saved, "drop");
}

snell_status snell__water_gpu_deviation(snell_water *w, float *dev_h, float *dev_v, int *known)
{
    snell_glstate saved;
    snell__pixel_store pack;
    int i, m = w->reduce_size;
    GLsizeiptr bytes = (GLsizeiptr)m * m * 4 * sizeof(uint32_t);
    float mh = 0.0f, mv = 0.0f;
    *known = 0;
    snell__glstate_save(&saved);
    if (w->reduce_fence) {
        /* Issued a call ago: on a GPU long finished; waits only if not. */
        GLenum r = glClientWaitSync((GLsync)w->reduce_fence, GL_SYNC_FLUSH_COMMANDS_BIT, (GLuint64)1000000000);
        const uint32_t *px = NULL;
        drop_pending(w);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, w->reduce_pbo);
        if (r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED)
            px = (const uint32_t *)glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, bytes, GL_MAP_READ_BIT);
        if (px) {
            for (i = 0; i < m * m; i++) {
                float a, b;
                memcpy(&a, &px[4 * i], sizeof a);
                memcpy(&b, &px[4 * i + 1], sizeof b);
                if (a > mh) mh = a;
                if (b > mv) mv = b;
            }
            glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
            *known = 1;
        }
    }
    begin_pass(w, w->prog_reduce);
    glUniform1i(glGetUniformLocation(w->prog_reduce, "u_n"), w->n);
    glUniform1f(glGetUniformLocation(w->prog_reduce, "u_mean"), (float)w->mean);
    glBindFramebuffer(GL_FRAMEBUFFER, w->reduce_fbo);
    glViewport(0, 0, m, m);
    glBindTexture(GL_TEXTURE_2D, w->state_tex[w->cur]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    snell__pixel_pack_begin(&pack, 4);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, w->reduce_pbo);
    glReadPixels(0, 0, m, m, GL_RGBA_INTEGER, GL_UNSIGNED_INT, (void *)0);
    snell__pixel_pack_end(&pack);
    w->reduce_fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    *dev_h = mh;
    *dev_v = mv * w->dx / w->d.wave_speed;
    return end_pass(w, &saved, "settle reduction");
}

snell_status snell__water_gpu_read(snell_water *w, float *h, float *v)
{
    snell_glstate saved;
    snell__pixel_store pack;
    size_t i, nodes = (size_t)w->n * (size_t)w->n;
    GLenum err;
    snell__glstate_save(&saved);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, w->state_fbo[w->cur]);
    snell__pixel_pack_begin(&pack, 4);
    glReadPixels(0, 0, w->n, w->n, GL_RGBA_INTEGER, GL_UNSIGNED_INT, w->reduce_px);
    snell__pixel_pack_end(&pack);
    err = glGetError();
    snell__glstate_restore(&saved);
    if (err != GL_NO_ERROR) return snell__fail(w->ctx, SNELL_E_GL, "water: reading the state back failed (0x%x)", err);
    for (i = 0; i < nodes; i++) {
        if (h) memcpy(&h[i], &w->reduce_px[4 * i], sizeof(float));
        if (v) memcpy(&v[i], &w->reduce_px[4 * i + 1], sizeof(float));
    }
    return SNELL_OK;
}
