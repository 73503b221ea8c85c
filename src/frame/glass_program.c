/* SPDX-License-Identifier: MIT */
/* glass_program.c — build and bind a kernel's program; shared uniforms. */
#include "frame/glass_program.h"
#include "core/gl.h"
#include "core/program.h"
#include "frame/stage.h"

#include <string.h>

const char *snell__output_defines(snell__output_kind out)
{
    switch (out) {
    case SNELL__OUT_DIR_FLOAT: return "#define SNELL_OUTPUT_EXIT_DIR_FLOAT 1\n";
    case SNELL__OUT_DIR_PACKED: return "#define SNELL_OUTPUT_EXIT_DIR_PACKED 1\n";
    default: return "";
    }
}

int snell__glass_variant(const snell__object *o)
{
    return o->screen_space | (o->env_paraboloid ? SNELL__GLASS_ENV_PARABOLOID : 0) | (int)o->stage_bits;
}

snell_status snell__glass_program_build(snell_ctx *ctx, const char *fs_path, snell__output_kind out,
                                        const char *extra_defines, int variant, snell__glass_program *g)
{
    char defines[1024];
    size_t len;
    snell_status st;
    int screen_space = variant & SNELL__GLASS_SHADING_MASK, i, k, offset;
    const snell__kernel_hooks *hooks = g->hooks; /* the cache's (snell__program_cache_get), kept */
    int count = hooks ? hooks->count : 0;
    snprintf(defines, sizeof defines, "%s%s%s%s", snell__output_defines(out),
             screen_space ? "#define SNELL_SCREEN_SPACE 1\n" : "",
             screen_space == SNELL__SCREEN_WRITES_DEPTH ? "#define SNELL_SCREEN_WRITES_DEPTH 1\n" : "",
             variant & SNELL__GLASS_ENV_PARABOLOID ? SNELL__ENV_PARABOLOID_DEFINE : "");
    /* What the frame's stages add (frame/stage.h), in frame order. */
    for (i = 0; i < count; i++) {
        unsigned bits = snell__kernel_hook_bits(hooks, i, (unsigned)variant);
        if (!bits) continue;
        len = strlen(defines);
        snprintf(defines + len, sizeof defines - len, "%s", hooks->stages[i]->kernel->defines(bits));
    }
    len = strlen(defines);
    snprintf(defines + len, sizeof defines - len, "%s", extra_defines ? extra_defines : "");
    memset(g, 0, sizeof *g);
    g->hooks = hooks;
    st = snell__program_build(ctx, screen_space ? "screen.vert" : "object.vert", fs_path, defines, &g->prog);
    if (st != SNELL_OK) return st;
    if ((st = snell__samplers_assign(ctx, g->prog, fs_path, &g->samplers)) != SNELL_OK) {
        snell__glass_program_destroy(g);
        return st;
    }
    g->screen_space = screen_space;
    g->variant = (unsigned)variant;
    for (i = 0, offset = 0; i < count; i++) {
        const snell__kernel_hook *h = hooks->stages[i]->kernel;
        if (!h) continue;
        for (k = 0; k < h->uniform_count; k++)
            g->hook_locs[offset + k] = snell__kernel_hook_bits(hooks, i, g->variant)
                                           ? glGetUniformLocation(g->prog, h->uniform_names[k])
                                           : -1;
        offset += h->uniform_count;
    }
    g->inv_view_proj = glGetUniformLocation(g->prog, "u_inv_view_proj");
    g->inv_size = glGetUniformLocation(g->prog, "u_inv_size");
    g->gid = glGetUniformLocation(g->prog, "u_gid");
    g->model = glGetUniformLocation(g->prog, "u_model");
    g->normal_matrix = glGetUniformLocation(g->prog, "u_normal_matrix");
    g->view_proj = glGetUniformLocation(g->prog, "u_view_proj");
    g->eye = glGetUniformLocation(g->prog, "u_eye");
    g->view_axis = glGetUniformLocation(g->prog, "u_view_axis");
    g->ior = glGetUniformLocation(g->prog, "u_ior");
    g->ior_rgb = glGetUniformLocation(g->prog, "u_ior_rgb");
    g->sigma = glGetUniformLocation(g->prog, "u_sigma");
    g->tint = glGetUniformLocation(g->prog, "u_tint");
    g->bsphere = glGetUniformLocation(g->prog, "u_bsphere");
    return SNELL_OK;
}

snell__program_slot *snell__program_cache_get(snell__program_cache *c, snell_method method, const int *key, int n,
                                              int *hit)
{
    snell__program_slot *victim = &c->slot[0];
    int i;
    ++c->clock;
    for (i = 0; i < SNELL__PROGRAM_CACHE; i++) {
        snell__program_slot *s = &c->slot[i];
        if (s->g.prog && s->method == (int)method && !memcmp(s->key, key, (size_t)n * sizeof *key)) {
            s->last_use = c->clock;
            *hit = 1;
            return s;
        }
        if (!s->g.prog || (victim->g.prog && s->last_use < victim->last_use)) victim = s;
    }
    snell__glass_program_destroy(&victim->g);
    memset(victim->key, 0, sizeof victim->key);
    memcpy(victim->key, key, (size_t)n * sizeof *key);
    memset(victim->loc, -1, sizeof victim->loc);
    victim->binary_length = -1;
    victim->method = (int)method;
    victim->g.hooks = &c->hooks;
    victim->last_use = c->clock;
    c->built++;
    *hit = 0;
    return victim;
}

unsigned snell__kernel_hook_bits(const snell__kernel_hooks *h, int i, unsigned variant)
{
    const snell__kernel_hook *k = h->stages[i]->kernel;
    return k ? (variant >> h->shift[i]) & ((1u << k->variant_bits) - 1u) : 0u;
}

snell_status snell__program_cache_hooks(snell_ctx *ctx, snell__program_cache *c, const snell__stage *const *stages,
                                        void *const *states, int count)
{
    unsigned shift = SNELL__GLASS_STAGE_SHIFT;
    int i, uniforms = 0;
    c->hooks.stages = stages;
    c->hooks.states = states;
    c->hooks.count = count;
    for (i = 0; i < count; i++) {
        const snell__kernel_hook *h = stages[i]->kernel;
        c->hooks.shift[i] = shift;
        if (!h) continue;
        shift += (unsigned)h->variant_bits;
        uniforms += h->uniform_count;
    }
    if (shift > SNELL__GLASS_VARIANT_BITS || uniforms > SNELL__HOOK_LOCS)
        return snell__fail(ctx, SNELL_E_LIMIT, "the stages' kernel hooks take %u variant bits and %d uniforms, "
                           "more than %d and %d", shift, uniforms, SNELL__GLASS_VARIANT_BITS, SNELL__HOOK_LOCS);
    return SNELL_OK;
}

void snell__program_cache_destroy(snell__program_cache *c)
{
    int i;
    for (i = 0; i < SNELL__PROGRAM_CACHE; i++) snell__glass_program_destroy(&c->slot[i].g);
}

int snell__program_cache_count(snell__program_cache *c, size_t *binary_bytes)
{
    int i, n = 0;
    size_t bytes = 0;
    for (i = 0; i < SNELL__PROGRAM_CACHE; i++) {
        snell__program_slot *s = &c->slot[i];
        if (!s->g.prog) continue;
        n++;
        if (s->binary_length < 0) {
            GLint len = 0;
            glGetProgramiv(s->g.prog, GL_PROGRAM_BINARY_LENGTH, &len);
            s->binary_length = len > 0 ? len : 0;
        }
        bytes += (size_t)s->binary_length;
    }
    if (binary_bytes) *binary_bytes = bytes;
    return n;
}

int snell__dispersion_variant(const snell_glass_resolved *g)
{
    if (!g->disperses) return 0;
    return g->material.dispersion_model == SNELL_DISPERSION_PER_CHANNEL ? 1 : 2;
}

void snell__glass_program_destroy(snell__glass_program *g)
{
    if (g->prog) glDeleteProgram(g->prog);
    g->prog = 0;
}

void snell__glass_program_bind(const snell__glass_program *g, const char *name, unsigned target, unsigned texture,
                               unsigned sampler)
{
    snell__samplers_bind(&g->samplers, name, target, texture, sampler);
}

void snell__glass_program_use(const snell__glass_program *g, const snell__view *v, const snell__object *o)
{
    int i, offset = 0;
    glUseProgram(g->prog);
    snell__samplers_bind_published(&g->samplers, &v->textures);
    snell__samplers_bind(&g->samplers, "u_env", o->env_paraboloid ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_CUBE_MAP,
                         o->env_texture, 0);
    glUniformMatrix4fv(g->model, 1, GL_FALSE, (const GLfloat *)o->model);
    glUniformMatrix3fv(g->normal_matrix, 1, GL_FALSE, (const GLfloat *)o->normal_matrix);
    glUniformMatrix4fv(g->view_proj, 1, GL_FALSE, (const GLfloat *)v->view_proj);
    glUniform3fv(g->eye, 1, v->eye);
    glUniform4fv(g->view_axis, 1, v->view_axis);
    glUniform1f(g->ior, o->glass->material.ior);
    glUniform3fv(g->ior_rgb, 1, o->glass->ior_rgb);
    glUniform3fv(g->sigma, 1, o->glass->absorption);
    glUniform3fv(g->tint, 1, o->glass->material.tint);
    glUniform4fv(g->bsphere, 1, o->bsphere);
    for (i = 0; g->hooks && i < g->hooks->count; i++) {
        const snell__kernel_hook *h = g->hooks->stages[i]->kernel;
        if (!h) continue;
        if (snell__kernel_hook_bits(g->hooks, i, g->variant))
            h->uniforms(g, g->hook_locs + offset, g->hooks->states[i], v, o);
        offset += h->uniform_count;
    }
    if (g->screen_space) {
        glUniformMatrix4fv(g->inv_view_proj, 1, GL_FALSE, (const GLfloat *)v->inv_view_proj);
        glUniform2f(g->inv_size, 1.0f / (float)v->width, 1.0f / (float)v->height);
        glUniform1i(g->gid, o->gid);
    }
}

int snell__fit_solid_few_surfaces(const snell_mesh_analysis *an, float max_hidden, char *why, size_t n)
{
    if (!an) {
        snell__why(why, n, "mesh analysis failed: closedness unknown");
        return 0;
    }
    if (!an->closed) {
        snell__why(why, n, "open or non-manifold (%u boundary, %u non-manifold, %u flipped edges): no solid's back "
                           "faces", (unsigned)an->boundary_edges, (unsigned)an->nonmanifold_edges,
                   (unsigned)an->flipped_edges);
        return 0;
    }
    if (an->pieces > 1) {
        snell__why(why, n, "closed, but %u separate pieces: the farthest back face may be another piece's",
                   (unsigned)an->pieces);
        return 0;
    }
    if (an->hidden_fraction > max_hidden) {
        snell__why(why, n, "closed, but %.2f > %.2f of the surface is hidden from the centre: light leaves through "
                           "surfaces before the farthest back face", an->hidden_fraction, max_hidden);
        return 0;
    }
    return 1;
}

int snell__cull_back_faces(const snell__object *o, snell_object_stats *stats)
{
    int winding = snell__mesh_winding(o->mesh), flip;
    if (winding == 0) return 0;
    flip = (winding < 0) != (o->mirrored != 0);
    glEnable(GL_CULL_FACE);
    glCullFace(flip ? GL_FRONT : GL_BACK);
    glFrontFace(GL_CCW);
    stats->skipped |= SNELL_SKIP_BACK_FACES;
    return 1;
}

void snell__draw_object(const snell__object *o)
{
    if (o->vao) {
        /* the method's VAO: the mesh's buffers plus attribute 2 */
        glBindVertexArray(o->vao);
        glDrawElements(GL_TRIANGLES, (GLsizei)(3 * o->mesh->triangle_count), o->mesh->index_type, (const void *)0);
    } else {
        snell__mesh_draw(o->mesh);
    }
    glDisable(GL_CULL_FACE);
}

void snell__draw_surface(const snell__object *o, snell_object_stats *stats)
{
    if (!o->screen_space) {
        if (o->glass->material.thickness <= 0.0f) snell__cull_back_faces(o, stats);
        snell__draw_object(o);
        return;
    }
    /* The G-buffer holds the front surface; the full-screen triangle at the
     * far plane passes GREATER where the target's depth holds something
     * nearer (the G-buffer pass wrote the glass there), so the rasteriser's
     * depth test, not the kernel, rejects uncovered pixels. With a depth
     * buffer of the G-buffer's own the kernel writes gl_FragDepth instead. */
    glEnable(GL_SCISSOR_TEST);
    glScissor(o->scissor[0], o->scissor[1], o->scissor[2], o->scissor[3]);
    if (o->screen_space == SNELL__SCREEN_SHARED_DEPTH) {
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_FALSE);
    }
    glBindVertexArray(0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_SCISSOR_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
}
