/* SPDX-License-Identifier: MIT */
/* env_paraboloid.c — dual-paraboloid maps from a cubemap; see env_paraboloid.h
 * and common/env.glsl for the parameterisation and the rim. */
#include "render/env_paraboloid.h"
#include "frame/env.h"
#include "frame/pass.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"

#include <math.h>

void snell__paraboloid_gen_destroy(snell__paraboloid_gen *g)
{
    if (g->prog) glDeleteProgram(g->prog);
    if (g->fbo) glDeleteFramebuffers(1, &g->fbo);
    g->prog = g->fbo = 0;
}

int snell__paraboloid_size(int cube_size)
{
    GLint max_tex = 0;
    int size = 2 * cube_size;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_tex);
    if (size > 4096) size = 4096;
    if (max_tex > 0 && size > max_tex) size = max_tex;
    return size;
}

static double dp_scale(int size) { return 0.5 * (size - 2.0 * SNELL__DP_MARGIN) / size; }

void snell__dp_coords(const double dir[3], int size, double *u, double *v, int *layer)
{
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double x = dir[0] / len, y = dir[1] / len, z = dir[2] / len, k = dp_scale(size) / (1.0 + fabs(z));
    *u = 0.5 + k * x;
    *v = 0.5 + k * y;
    *layer = z < 0.0;
}

void snell__dp_dir(double u, double v, int layer, int size, double dir[3])
{
    double s = (u - 0.5) / dp_scale(size), t = (v - 0.5) / dp_scale(size), r2 = s * s + t * t;
    double z = (1.0 - r2) / (1.0 + r2);
    dir[0] = 2.0 * s / (1.0 + r2);
    dir[1] = 2.0 * t / (1.0 + r2);
    dir[2] = layer ? -z : z;
}

static snell_status make_generator(snell_ctx *ctx, snell__paraboloid_gen *g)
{
    snell_status st;
    if (g->prog) return SNELL_OK;
    st = snell__program_build(ctx, "screen.vert", "env_paraboloid.frag", NULL, &g->prog);
    if (st != SNELL_OK) return st;
    g->u_layer = glGetUniformLocation(g->prog, "u_layer");
    g->u_size = glGetUniformLocation(g->prog, "u_size");
    g->u_env = glGetUniformLocation(g->prog, "u_env");
    glGenFramebuffers(1, &g->fbo);
    return SNELL_OK;
}

static unsigned texture_create(int size)
{
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D_ARRAY, tex);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA8, size, size, 2);
    /* GL_LINEAR without mipmaps, as the cube: the look-ups differ only in
     * how directions become texels. */
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return tex;
}

void snell__paraboloid_texture(int size, unsigned *tex, int *tex_size)
{
    if (*tex && *tex_size == size) return;
    if (*tex) glDeleteTextures(1, tex);
    *tex = texture_create(size);
    *tex_size = size;
}

snell_status snell__paraboloid_draw_layer(snell_ctx *ctx, snell__paraboloid_gen *g, unsigned cube, int layer,
                                          int size)
{
    snell_status st = make_generator(ctx, g);
    if (st != SNELL_OK) return st;
    glUseProgram(g->prog);
    glUniform1i(g->u_env, 0);
    glUniform1f(g->u_size, (float)size);
    glUniform1f(g->u_layer, (float)layer);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
    glBindVertexArray(0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    return SNELL_OK;
}

snell_status snell__paraboloid_from_cube(snell_ctx *ctx, snell__paraboloid_gen *g, unsigned cube, int size,
                                         unsigned *tex, int *tex_size)
{
    snell__pass pass;
    GLint prev_cube = 0, prev_array = 0, prev_vao = 0;
    snell_status st = make_generator(ctx, g);
    int layer;
    if (st != SNELL_OK) return st;
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP, &prev_cube);
    glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &prev_array);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &prev_vao);
    snell__paraboloid_texture(size, tex, tex_size);
    snell__pass_begin(&pass, g->fbo, size, size, 0, GL_ALWAYS, 1.0f); /* no depth attachment */
    for (layer = 0; layer < 2 && st == SNELL_OK; layer++) {
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, *tex, 0, layer);
        if (layer == 0 && glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            st = snell__fail(ctx, SNELL_E_GL, "dual-paraboloid framebuffer incomplete");
            break;
        }
        st = snell__paraboloid_draw_layer(ctx, g, cube, layer, size);
    }
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, 0, 0, 0);
    snell__pass_end(&pass);
    glBindTexture(GL_TEXTURE_CUBE_MAP, (GLuint)prev_cube);
    glBindTexture(GL_TEXTURE_2D_ARRAY, (GLuint)prev_array);
    glBindVertexArray((GLuint)prev_vao);
    if (st == SNELL_OK && glGetError() != GL_NO_ERROR)
        st = snell__fail(ctx, SNELL_E_GL, "GL error making %dx%d dual-paraboloid maps", size, size);
    return st;
}

snell_status snell__env_paraboloid(snell_ctx *ctx, snell__paraboloid_gen *g, const snell_env *env, unsigned *tex)
{
    /* A cache on the environment, as the mesh keeps its analysis: made once
     * from the cube it never changes; a host's cube (borrowed) may change
     * between frames, so its maps are drawn again each time. */
    snell_env *e = (snell_env *)env;
    snell_status st = SNELL_OK;
    if (!e->paraboloid || e->borrowed)
        st = snell__paraboloid_from_cube(ctx, g, e->texture, snell__paraboloid_size(e->size), &e->paraboloid,
                                         &e->paraboloid_size);
    *tex = e->paraboloid;
    return st;
}
