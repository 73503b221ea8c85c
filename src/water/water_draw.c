/* SPDX-License-Identifier: MIT */
/* water_draw.c — see water_draw.h. The grid is drawn from an index buffer
 * alone (the vertex shader finds node (i, j) from gl_VertexID), two
 * triangles per cell split along the (i, j)-(i+1, j+1) diagonal, as the
 * reference intersects them (ref/ref_water.c); the container is 5 quads with
 * a face number per vertex. Both are made on the first draw of a water. */
#include "water/water_draw.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "core/program.h"
#include "mesh/mesh.h"

#include <math.h>

#include <string.h>

static snell_status make_programs(snell_ctx *ctx, snell__water_programs *p, snell__output_kind out, int env_paraboloid)
{
    static const char *const mode_defines[SNELL__WATER_MODES] = {"", "#define SNELL_WATER_OBJECTS 1\n",
                                                                "#define SNELL_BEYOND 1\n"};
    char defines[256];
    snell_status st = SNELL_OK;
    int gpu, mode;
    for (gpu = 0; gpu < 2; gpu++)
        for (mode = 0; mode < SNELL__WATER_MODES && st == SNELL_OK; mode++) {
            snprintf(defines, sizeof defines, "%s#define SNELL_WATER 1\n%s%s%s", snell__output_defines(out),
                     gpu ? "#define SNELL_WATER_STATE_UINT 1\n" : "", mode_defines[mode],
                     env_paraboloid ? SNELL__ENV_PARABOLOID_DEFINE : "");
            st = snell__program_build(ctx, "water_surface.vert", "water_surface.frag", defines, &p->surface[gpu][mode]);
            if (st == SNELL_OK)
                st = snell__samplers_assign(ctx, p->surface[gpu][mode], "water_surface.frag",
                                            &p->surface_samplers[gpu][mode]);
            if (st == SNELL_OK && mode == 2) snell__beyond_locate(p->surface[gpu][mode], &p->layers[gpu]);
        }
    if (st == SNELL_OK)
        st = snell__program_build(ctx, "water_wall.vert", "water_wall.frag", snell__output_defines(out), &p->wall);
    if (st == SNELL_OK) st = snell__samplers_assign(ctx, p->wall, "water_wall.frag", &p->wall_samplers);
    p->made = st == SNELL_OK;
    return st;
}

void snell__water_programs_destroy(snell__water_programs *p)
{
    int k;
    for (k = 0; k < 2 * SNELL__WATER_MODES; k++)
        if (p->surface[k / SNELL__WATER_MODES][k % SNELL__WATER_MODES])
            glDeleteProgram(p->surface[k / SNELL__WATER_MODES][k % SNELL__WATER_MODES]);
    if (p->wall) glDeleteProgram(p->wall);
    if (p->scene_fbo) glDeleteFramebuffers(1, &p->scene_fbo);
    if (p->scene_color) glDeleteTextures(1, &p->scene_color);
    if (p->scene_depth) glDeleteTextures(1, &p->scene_depth);
    memset(p, 0, sizeof *p);
}

void snell__water_draw_release(snell_water *w)
{
    if (w->grid_ibo) glDeleteBuffers(1, &w->grid_ibo);
    if (w->grid_vao) glDeleteVertexArrays(1, &w->grid_vao);
    if (w->wall_vbo) glDeleteBuffers(1, &w->wall_vbo);
    if (w->wall_vao) glDeleteVertexArrays(1, &w->wall_vao);
    if (w->height_tex) glDeleteTextures(1, &w->height_tex);
    if (w->light_prog) glDeleteProgram(w->light_prog);
    if (w->light_fbo) glDeleteFramebuffers(1, &w->light_fbo);
    if (w->light_tex) glDeleteTextures(1, &w->light_tex);
    if (w->column_prog) glDeleteProgram(w->column_prog);
    if (w->column_fbo[0]) glDeleteFramebuffers(2, w->column_fbo);
    if (w->column_tex[0]) glDeleteTextures(2, w->column_tex);
    memset(w->column_fbo, 0, sizeof w->column_fbo);
    memset(w->column_tex, 0, sizeof w->column_tex);
    w->column_prog = 0;
    w->column_size = 0;
    w->grid_ibo = w->grid_vao = w->wall_vbo = w->wall_vao = w->height_tex = 0;
    w->light_prog = w->light_fbo = w->light_tex = 0;
    memset(&w->light_samplers, 0, sizeof w->light_samplers);
    w->light_size = w->light_valid = 0;
}

/* One quad of the container: corners a, b, c, d in order, face number f. */
static float *quad(float *o, const float a[3], const float b[3], const float c[3], const float d[3], float f)
{
    const float *tri[6] = {a, b, c, a, c, d};
    int k;
    for (k = 0; k < 6; k++) {
        memcpy(o, tri[k], 3 * sizeof(float));
        o[3] = f;
        o += 4;
    }
    return o;
}

static snell_status make_geometry(snell_water *w)
{
    int n = w->n, i, j;
    size_t count = (size_t)(n - 1) * (size_t)(n - 1) * 6;
    uint32_t *idx = (uint32_t *)snell__calloc(&w->alloc, count, sizeof(uint32_t)), *o = idx;
    float s = 0.5f * w->d.width, lo = -w->d.depth, hi = w->d.rim, verts[5 * 6 * 4], *q = verts;
    if (!idx) return snell__fail(w->ctx, SNELL_E_NOMEM, "out of memory for the water grid's indices");
    for (j = 0; j + 1 < n; j++)
        for (i = 0; i + 1 < n; i++) {
            uint32_t a = (uint32_t)(j * n + i), b = a + 1, c = a + (uint32_t)n + 1, d = a + (uint32_t)n;
            o[0] = a, o[1] = b, o[2] = c, o[3] = a, o[4] = c, o[5] = d;
            o += 6;
        }
    glGenVertexArrays(1, &w->grid_vao);
    glBindVertexArray(w->grid_vao);
    glGenBuffers(1, &w->grid_ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, w->grid_ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(count * sizeof(uint32_t)), idx, GL_STATIC_DRAW);
    snell__free(&w->alloc, idx);
    {
        const float f00[3] = {-s, lo, -s}, f10[3] = {s, lo, -s}, f11[3] = {s, lo, s}, f01[3] = {-s, lo, s};
        const float t00[3] = {-s, hi, -s}, t10[3] = {s, hi, -s}, t11[3] = {s, hi, s}, t01[3] = {-s, hi, s};
        q = quad(q, f00, f10, f11, f01, 0.0f);
        q = quad(q, f00, f01, t01, t00, 1.0f);
        q = quad(q, f10, f11, t11, t10, 2.0f);
        q = quad(q, f00, f10, t10, t00, 3.0f);
        quad(q, f01, f11, t11, t01, 4.0f);
    }
    glGenVertexArrays(1, &w->wall_vao);
    glBindVertexArray(w->wall_vao);
    glGenBuffers(1, &w->wall_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, w->wall_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)sizeof verts, verts, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 4 * sizeof(float), (const void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 4 * sizeof(float), (const void *)(3 * sizeof(float)));
    glBindVertexArray(0);
    if (w->d.sim == SNELL_WATER_SIM_CPU) {
        glGenTextures(1, &w->height_tex);
        glBindTexture(GL_TEXTURE_2D, w->height_tex);
        snell__texture_nearest(GL_TEXTURE_2D, 0); /* texelFetch only; R32F is not filterable */
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_R32F, n, n);
    }
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(w->ctx, SNELL_E_GL, "water: GL error making its geometry");
}

static void nearest_texture(GLuint tex, GLenum format, int width, int height)
{
    glBindTexture(GL_TEXTURE_2D, tex);
    snell__texture_nearest(GL_TEXTURE_2D, 1);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
}

snell_status snell__water_copy_scene(snell_ctx *ctx, snell__water_programs *p, unsigned read_fbo, int width, int height)
{
    if (!p->scene_fbo) {
        GLenum status;
        glGenTextures(1, &p->scene_color);
        nearest_texture(p->scene_color, GL_RGBA8, width, height);
        glGenTextures(1, &p->scene_depth);
        nearest_texture(p->scene_depth, GL_DEPTH_COMPONENT24, width, height); /* the target's depth format: blit needs it */
        glGenFramebuffers(1, &p->scene_fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, p->scene_fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, p->scene_color, 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, p->scene_depth, 0);
        status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            return snell__fail(ctx, SNELL_E_GL, "water: scene copy framebuffer incomplete (0x%x)", (unsigned)status);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, p->scene_fbo);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "water: copying the opaque objects failed");
}

const char *const snell__water_uniform_names[SNELL__WATER_UNIFORMS] = {
    "u_water_half", "u_water_depth", "u_water_tile_size", "u_water_rim", "u_water_ior",
    "u_water_sigma", "u_water_n",    "u_water_dx",        "u_water_lit"};

void snell__water_set_uniforms(const int *locs, const snell_water *w)
{
    glUniform1f(locs[0], 0.5f * w->d.width);
    glUniform1f(locs[1], w->d.depth);
    glUniform1f(locs[2], w->d.tile_size);
    glUniform1f(locs[3], w->d.rim);
    glUniform1f(locs[4], w->d.ior);
    glUniform3fv(locs[5], 1, w->sigma);
    glUniform1i(locs[6], w->n);
    glUniform1f(locs[7], w->dx);
    glUniform1i(locs[8], w->lit);
}

void snell__water_publish(const snell_water *w, snell__textures *ts)
{
    snell__textures_publish(ts, "u_water_heights", GL_TEXTURE_2D,
                            w->d.sim == SNELL_WATER_SIM_GPU ? w->state_tex[w->cur] : w->height_tex, 0);
    /* the floor's light map: read only where lit */
    snell__textures_publish(ts, "u_water_light", GL_TEXTURE_2D, w->lit ? w->light_tex : 0, 0);
}

void snell__water_uniforms(unsigned prog, const snell__samplers *samplers, const snell_water *w)
{
    snell__textures ts = {0};
    int locs[SNELL__WATER_UNIFORMS], i;
    for (i = 0; i < SNELL__WATER_UNIFORMS; i++) locs[i] = glGetUniformLocation(prog, snell__water_uniform_names[i]);
    snell__water_set_uniforms(locs, w);
    snell__water_publish(w, &ts);
    snell__samplers_bind_published(samplers, &ts);
}

#define MAX_SPHERES 16 /* water_surface.frag's SNELL_WATER_MAX_SPHERES */

void snell__water_object_sphere(const snell_opaque *o, float s[4])
{
    const snell_mesh *m = o->mesh;
    float c[3], scale = 1.0f;
    int k;
    for (k = 0; k < 3; k++) c[k] = 0.5f * (m->bmin[k] + m->bmax[k]);
    if (o->model) {
        const float *mm = o->model;
        scale = 0.0f;
        for (k = 0; k < 3; k++) {
            float len = sqrtf(mm[4 * k] * mm[4 * k] + mm[4 * k + 1] * mm[4 * k + 1] + mm[4 * k + 2] * mm[4 * k + 2]);
            if (len > scale) scale = len;
        }
        for (k = 0; k < 3; k++) s[k] = mm[k] * c[0] + mm[4 + k] * c[1] + mm[8 + k] * c[2] + mm[12 + k];
    } else {
        for (k = 0; k < 3; k++) s[k] = c[k];
    }
    s[3] = m->bradius * scale * 1.001f;
}

/* The spheres the search is limited to: one per object, or one around them all beyond MAX_SPHERES. */
static int object_spheres(const snell_opaque *objects, int count, float out[MAX_SPHERES][4])
{
    int i, k;
    if (count <= MAX_SPHERES) {
        for (i = 0; i < count; i++) snell__water_object_sphere(&objects[i], out[i]);
        return count;
    }
    {
        float lo[3] = {HUGE_VALF, HUGE_VALF, HUGE_VALF}, hi[3] = {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF}, r = 0.0f, s[4];
        for (i = 0; i < count; i++) {
            snell__water_object_sphere(&objects[i], s);
            for (k = 0; k < 3; k++) {
                lo[k] = fminf(lo[k], s[k] - s[3]);
                hi[k] = fmaxf(hi[k], s[k] + s[3]);
            }
        }
        for (k = 0; k < 3; k++) {
            out[0][k] = 0.5f * (lo[k] + hi[k]);
            r += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
        }
        out[0][3] = sqrtf(r) * 1.001f; /* half the box diagonal: holds every sphere's box */
        return 1;
    }
}

snell_status snell__water_upload(snell_water *w, snell_frame_stats *stats)
{
    snell_status st;
    if (!w->grid_vao && (st = make_geometry(w)) != SNELL_OK) return st;
    if (w->d.sim == SNELL_WATER_SIM_CPU && (!w->uploaded || w->uploaded_version != w->version)) {
        snell__pixel_store unpack;
        glBindTexture(GL_TEXTURE_2D, w->height_tex);
        snell__pixel_unpack_begin(&unpack, 4);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w->n, w->n, GL_RED, GL_FLOAT, w->h);
        snell__pixel_unpack_end(&unpack);
        w->uploaded = 1;
        w->uploaded_version = w->version;
        stats->water_uploaded = 1;
    }
    return SNELL_OK;
}

snell_status snell__water_draw(snell_ctx *ctx, snell__water_programs *p, snell__output_kind out, snell_water *w,
                               const snell__view *v, unsigned env_texture, int env_paraboloid,
                               const snell_opaque *objects, int object_count, int layers, snell_frame_stats *stats)
{
    snell_status st;
    GLuint prog;
    if (!p->made && (st = make_programs(ctx, p, out, env_paraboloid)) != SNELL_OK) return st;
    if ((st = snell__water_upload(w, stats)) != SNELL_OK) return st;
    /* the floor is lit in this frame only if the caustics stage made or kept its map for it */
    w->lit = w->lit_pending;
    w->lit_pending = 0;
    const unsigned env_target = env_paraboloid ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_CUBE_MAP;
    const snell__samplers *ss;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);

    glUseProgram(p->wall);
    snell__samplers_bind(&p->wall_samplers, "u_env", env_target, env_texture, 0);
    glUniformMatrix4fv(glGetUniformLocation(p->wall, "u_view_proj"), 1, GL_FALSE, (const float *)v->view_proj);
    glUniform3fv(glGetUniformLocation(p->wall, "u_eye"), 1, v->eye);
    glUniform4fv(glGetUniformLocation(p->wall, "u_view_axis"), 1, v->view_axis);
    snell__water_uniforms(p->wall, &p->wall_samplers, w);
    glBindVertexArray(w->wall_vao);
    glDrawArrays(GL_TRIANGLES, 0, 30);

    prog = p->surface[w->d.sim == SNELL_WATER_SIM_GPU][layers ? 2 : object_count > 0 ? 1 : 0];
    ss = &p->surface_samplers[w->d.sim == SNELL_WATER_SIM_GPU][layers ? 2 : object_count > 0 ? 1 : 0];
    glUseProgram(prog);
    snell__samplers_bind_published(ss, &v->textures); /* the scene layers */
    snell__samplers_bind(ss, "u_env", env_target, env_texture, 0);
    if (layers) {
        snell__beyond_uniforms(&p->layers[w->d.sim == SNELL_WATER_SIM_GPU], v, 0);
    } else if (object_count > 0) {
        float spheres[MAX_SPHERES][4];
        int n_spheres = object_spheres(objects, object_count, spheres);
        glUniform4fv(glGetUniformLocation(prog, "u_spheres"), n_spheres, &spheres[0][0]);
        glUniform1i(glGetUniformLocation(prog, "u_sphere_count"), n_spheres);
        snell__samplers_bind(ss, "u_scene_color", GL_TEXTURE_2D, p->scene_color, 0);
        snell__samplers_bind(ss, "u_scene_depth", GL_TEXTURE_2D, p->scene_depth, 0);
        glUniform2f(glGetUniformLocation(prog, "u_depth_ab"), v->proj[2][2], v->proj[3][2]);
    }
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE, (const float *)v->view_proj);
    glUniform3fv(glGetUniformLocation(prog, "u_eye"), 1, v->eye);
    glUniform4fv(glGetUniformLocation(prog, "u_view_axis"), 1, v->view_axis);
    snell__water_uniforms(prog, ss, w);
    glBindVertexArray(w->grid_vao);
    glDrawElements(GL_TRIANGLES, (GLsizei)((w->n - 1) * (w->n - 1) * 6), GL_UNSIGNED_INT, (const void *)0);
    glBindVertexArray(0);
    stats->water_drawn = 1;
    stats->passes += 2;
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "water: GL error drawing the surface");
}
