/* SPDX-License-Identifier: MIT */
/* water_caustics.c — the container floor's light map (after Evan Wallace's
 * webgl-water): the light refracted at the water surface onto the floor, remade
 * in one draw whenever the surface or the light moved, flux-correct, shadowed by
 * the opaque objects' columns. The caustics stage calls it (render/caustics.c);
 * common/water.glsl reads it. More: docs/ARCHITECTURE.md, "Design notes by
 * file". */
#include "water/water_draw.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/light_map.h"
#include "core/program.h"
#include "mesh/mesh.h"

#include <math.h>
#include <string.h>

#define DEFAULT_LIGHT_MAP 256

static snell_status resources(snell_ctx *ctx, snell_water *w, int size)
{
    snell_status st = SNELL_OK;
    GLenum status;
    if (!w->light_prog) {
        st = snell__program_build(ctx, "water_caustics.vert", "water_caustics.frag",
                                  w->d.sim == SNELL_WATER_SIM_GPU ? "#define SNELL_WATER_STATE_UINT 1\n" : NULL,
                                  &w->light_prog);
        if (st == SNELL_OK) st = snell__samplers_assign(ctx, w->light_prog, "water_caustics.vert", &w->light_samplers);
    }
    if (st == SNELL_OK && !w->column_prog)
        st = snell__program_build(ctx, "object.vert", "water_columns.frag", NULL, &w->column_prog);
    if (st != SNELL_OK || w->light_size == size) return st;
    if (!w->light_fbo) {
        glGenFramebuffers(1, &w->light_fbo);
        glGenTextures(1, &w->light_tex);
    }
    glBindTexture(GL_TEXTURE_2D, w->light_tex);
    snell__light_map_image(w->light_format, size);
    snell__texture_nearest(GL_TEXTURE_2D, 1); /* read bilinearly by hand (water.glsl) */
    glBindFramebuffer(GL_FRAMEBUFFER, w->light_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, w->light_tex, 0);
    status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return snell__fail(ctx, SNELL_E_GL, "water caustics: light map framebuffer incomplete (0x%x)", (unsigned)status);
    w->light_size = size;
    return SNELL_OK;
}

/* Two unit vectors across unit d (the beam's coordinates). */
static void across(const float d[3], float u[3], float v[3])
{
    float a[3] = {0.0f, 1.0f, 0.0f}, len;
    if (fabsf(d[1]) > 0.99f) a[0] = 1.0f, a[1] = 0.0f;
    u[0] = a[1] * d[2] - a[2] * d[1], u[1] = a[2] * d[0] - a[0] * d[2], u[2] = a[0] * d[1] - a[1] * d[0];
    len = sqrtf(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    u[0] /= len, u[1] /= len, u[2] /= len;
    v[0] = d[1] * u[2] - d[2] * u[1], v[1] = d[2] * u[0] - d[0] * u[2], v[2] = d[0] * u[1] - d[1] * u[0];
}

static const float g_identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; /* a NULL model */

/* The objects' key: FNV-1a over their meshes, mesh versions and models. */
static uint64_t column_key(const snell_opaque *list, int count)
{
    uint64_t h = 1469598103934665603u;
    int i;
    size_t k;
    for (i = 0; i < count; i++) {
        const unsigned char *part[3] = {(const unsigned char *)&list[i].mesh,
                                        (const unsigned char *)&list[i].mesh->version,
                                        (const unsigned char *)(list[i].model ? list[i].model : g_identity)};
        const size_t bytes[3] = {sizeof list[i].mesh, sizeof list[i].mesh->version, 16 * sizeof(float)};
        int j;
        for (j = 0; j < 3; j++)
            for (k = 0; k < bytes[j]; k++) h = (h ^ part[j][k]) * 1099511628211u;
    }
    return h ^ (uint64_t)count;
}

/* The opaque objects seen from straight above over the floor's square,
 * size x size like the light map: the depth of their highest surface over
 * each texel (column_tex[0], the nearest) and of their lowest ([1], the
 * farthest), orthographic between the highest and lowest point of their
 * bounding spheres (nothing of them clipped). water_caustics.frag takes a
 * column as solid between the two: exact for one convex object over a
 * texel; a concave object's overhangs, and two objects one over the other,
 * are filled in between. Objects outside the square are not seen. */
static snell_status draw_columns(snell_ctx *ctx, snell_water *w, const snell_opaque *list, int count, int size)
{
    float top = w->d.rim, bottom = -w->d.depth, half = 0.5f * w->d.width, vp[16] = {0};
    GLenum none = GL_NONE;
    int i, k;
    for (i = 0; i < count; i++) {
        float s[4];
        snell_status st = snell__mesh_upload((snell_mesh *)list[i].mesh);
        if (st != SNELL_OK) return st;
        snell__water_object_sphere(&list[i], s);
        if (s[1] + s[3] > top) top = s[1] + s[3];
        if (s[1] - s[3] < bottom) bottom = s[1] - s[3];
    }
    if (w->column_size != size) {
        if (!w->column_fbo[0]) {
            glGenFramebuffers(2, w->column_fbo);
            glGenTextures(2, w->column_tex);
        }
        for (k = 0; k < 2; k++) {
            glBindTexture(GL_TEXTURE_2D, w->column_tex[k]);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, size, size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, NULL);
            snell__texture_nearest(GL_TEXTURE_2D, 1);
            glBindFramebuffer(GL_FRAMEBUFFER, w->column_fbo[k]);
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, w->column_tex[k], 0);
            glDrawBuffers(1, &none);
            glReadBuffer(GL_NONE);
            if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
                return snell__fail(ctx, SNELL_E_GL, "water caustics: the objects' column map is incomplete");
        }
        w->column_size = size;
    }
    /* x, z over the square to clip x, y (the light map's layout); depth 0 at top, 1 at bottom */
    vp[0] = 1.0f / half;
    vp[9] = 1.0f / half;
    vp[6] = -2.0f / (top - bottom);
    vp[14] = 2.0f * top / (top - bottom) - 1.0f;
    vp[15] = 1.0f;
    glUseProgram(w->column_prog);
    glUniformMatrix4fv(glGetUniformLocation(w->column_prog, "u_view_proj"), 1, GL_FALSE, vp);
    glViewport(0, 0, size, size);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    for (k = 0; k < 2; k++) { /* the nearest surface from above, then the farthest */
        glBindFramebuffer(GL_FRAMEBUFFER, w->column_fbo[k]);
        glClearDepthf(k ? 0.0f : 1.0f);
        glClear(GL_DEPTH_BUFFER_BIT);
        glDepthFunc(k ? GL_GREATER : GL_LESS);
        for (i = 0; i < count; i++) {
            glUniformMatrix4fv(glGetUniformLocation(w->column_prog, "u_model"), 1, GL_FALSE,
                               list[i].model ? list[i].model : g_identity);
            snell__mesh_draw(list[i].mesh);
        }
    }
    glClearDepthf(1.0f);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    w->column_top = top;
    w->column_range = top - bottom;
    return SNELL_OK;
}

/* columns: the objects' column maps were drawn for this map (draw_columns). */
static void draw_map(snell_water *w, const snell_light *l, int columns)
{
    GLuint prog = w->light_prog;
    float d[3], u[3], v[3], col[3], len, texel = w->d.width / (float)w->light_size;
    int k;
    len = sqrtf(l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                l->direction[2] * l->direction[2]);
    for (k = 0; k < 3; k++) d[k] = l->direction[k] / len, col[k] = l->color[k];
    across(d, u, v);
    glBindFramebuffer(GL_FRAMEBUFFER, w->light_fbo);
    glViewport(0, 0, w->light_size, w->light_size);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(prog);
    snell__water_uniforms(prog, &w->light_samplers, w);
    snell__samplers_bind(&w->light_samplers, "u_water_light", GL_TEXTURE_2D, 0, 0); /* the map being made */
    glUniform1i(glGetUniformLocation(prog, "u_spot"), l->type == SNELL_LIGHT_SPOT);
    glUniform3fv(glGetUniformLocation(prog, "u_dir"), 1, d);
    glUniform3fv(glGetUniformLocation(prog, "u_pos"), 1, l->position);
    glUniform3fv(glGetUniformLocation(prog, "u_beam_u"), 1, u);
    glUniform3fv(glGetUniformLocation(prog, "u_beam_v"), 1, v);
    glUniform3fv(glGetUniformLocation(prog, "u_color"), 1, col);
    glUniform1f(glGetUniformLocation(prog, "u_cos_cone"), cosf(l->spot_angle));
    glUniform1f(glGetUniformLocation(prog, "u_texel_area"), texel * texel);
    glUniform1i(glGetUniformLocation(prog, "u_columns"), columns);
    glUniform1f(glGetUniformLocation(prog, "u_column_top"), w->column_top);
    glUniform1f(glGetUniformLocation(prog, "u_column_range"), w->column_range);
    snell__samplers_bind(&w->light_samplers, "u_column_high", GL_TEXTURE_2D, columns ? w->column_tex[0] : 0, 0);
    snell__samplers_bind(&w->light_samplers, "u_column_low", GL_TEXTURE_2D, columns ? w->column_tex[1] : 0, 0);
    glBindVertexArray(w->grid_vao);
    glDrawElements(GL_TRIANGLES, (GLsizei)((w->n - 1) * (w->n - 1) * 6), GL_UNSIGNED_INT, (const void *)0);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
}

snell_status snell__water_caustics(snell_ctx *ctx, snell_water *w, const snell_light *light,
                                   const snell_opaque *objects, int count, snell_frame_stats *s)
{
    uint64_t key;
    char *why = s->caustics_reason;
    size_t room = sizeof s->caustics_reason, used = strlen(why);
    const char *sep = used ? "; " : "";
    int size = w->d.light_map ? w->d.light_map : DEFAULT_LIGHT_MAP;
    GLint fbo = 0, viewport[4];
    snell_status st;
    if (!w->light_format) w->light_format = snell__light_map_format(ctx);
    w->lit_pending = 1;
    key = column_key(objects, count);
    if (w->light_valid && w->light_version == w->version && w->light_size == size &&
        memcmp(&w->light_key, light, sizeof *light) == 0 && w->column_key == key) {
        snell__why(why + used, room - used, "%swater floor: reused (nothing moved)", sep);
        return snell__water_upload(w, s);
    }
    w->light_valid = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_VIEWPORT, viewport);
    st = snell__water_upload(w, s);
    if (st == SNELL_OK) st = resources(ctx, w, size);
    if (st == SNELL_OK && count > 0) st = draw_columns(ctx, w, objects, count, size);
    if (st == SNELL_OK) draw_map(w, light, count > 0);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glDepthMask(GL_TRUE);
    if (st == SNELL_OK && glGetError() != GL_NO_ERROR) st = snell__fail(ctx, SNELL_E_GL, "water caustics: GL error");
    if (st != SNELL_OK) {
        w->lit_pending = 0;
        return st;
    }
    w->light_valid = 1;
    w->light_version = w->version;
    memcpy(&w->light_key, light, sizeof *light);
    w->column_key = key;
    s->passes += 1 + 2 * (count > 0);
    snell__why(why + used, room - used, "%swater floor: made (something moved), %dx%d %s map of %dx%d nodes, %d opaque "
               "shadowing", sep, size, size, snell__light_map_str(w->light_format), w->n, w->n, count);
    return SNELL_OK;
}

snell_status snell__water_caustics_read(snell_ctx *ctx, snell_water *w, float *rgba, int *size)
{
    if (!w->light_valid) return snell__fail(ctx, SNELL_E_INVALID_ARG, "water caustics: no light map made yet");
    *size = w->light_size;
    return snell__read_light_map(ctx, w->light_format, w->light_fbo, w->light_size, rgba, "the water floor's light map");
}
