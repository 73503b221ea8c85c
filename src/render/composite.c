/* SPDX-License-Identifier: MIT */
/* composite.c — opaque objects and background; see composite.h. */
#include "render/composite.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"
#include "frame/camera.h"
#include "render/caustics.h"

#include <math.h>
#include <string.h>

/* Builds p once (vs with fs) and finds its uniforms; a location it lacks is -1. */
static snell_status build(snell_ctx *ctx, snell__opaque_prog *p, const char *vs, const char *fs, const char *defines)
{
    snell_status st;
    if (p->prog) return SNELL_OK;
    if ((st = snell__program_build(ctx, vs, fs, defines, &p->prog)) != SNELL_OK) return st;
    p->model = glGetUniformLocation(p->prog, "u_model");
    p->normal_matrix = glGetUniformLocation(p->prog, "u_normal_matrix");
    p->view_proj = glGetUniformLocation(p->prog, "u_view_proj");
    p->eye = glGetUniformLocation(p->prog, "u_eye");
    p->view_axis = glGetUniformLocation(p->prog, "u_view_axis");
    p->color = glGetUniformLocation(p->prog, "u_color");
    p->centre = glGetUniformLocation(p->prog, "u_centre");
    p->layer = glGetUniformLocation(p->prog, "u_layer");
    p->size = glGetUniformLocation(p->prog, "u_size");
    p->depth_range = glGetUniformLocation(p->prog, "u_depth_range");
    return SNELL_OK;
}

void snell__composite_destroy(snell__composite *c)
{
    int k;
    if (c->opaque_dp.prog) glDeleteProgram(c->opaque_dp.prog);
    for (k = 0; k < 2; k++)
        if (c->opaque_lit[k].prog) glDeleteProgram(c->opaque_lit[k].prog);
    for (k = 0; k < SNELL__OUT_KINDS; k++) {
        if (c->opaque[k].prog) glDeleteProgram(c->opaque[k].prog);
        if (c->sky[k][0]) glDeleteProgram(c->sky[k][0]);
        if (c->sky[k][1]) glDeleteProgram(c->sky[k][1]);
    }
    if (c->empty_vao) glDeleteVertexArrays(1, &c->empty_vao);
    memset(c, 0, sizeof *c);
}

snell_status snell__opaque_validate(snell_ctx *ctx, const snell_opaque *list, int count)
{
    char why[96];
    int i, k;
    if (count < 0 || count > SNELL_MAX_OPAQUE || (count > 0 && !list))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "opaque_count %d outside 0..%d or opaque list NULL", count,
                           SNELL_MAX_OPAQUE);
    for (i = 0; i < count; i++) {
        const snell_opaque *o = &list[i];
        if (!o->mesh) return snell__fail(ctx, SNELL_E_INVALID_ARG, "opaque object %d has no mesh", i);
        if (!snell__mesh_bind_ctx((snell_mesh *)o->mesh, ctx))
            return snell__fail(ctx, SNELL_E_INVALID_ARG,
                               "opaque object %d: its mesh belongs to another context (made with it, or drawn there "
                               "first)", i);
        for (k = 0; k < 3; k++)
            if (!(o->color[k] >= 0.0f && o->color[k] <= 1.0f))
                return snell__fail(ctx, SNELL_E_INVALID_ARG, "opaque object %d: colour must lie in 0..1", i);
        if (o->model)
            for (k = 0; k < 16; k++)
                if (!isfinite(o->model[k]))
                    return snell__fail(ctx, SNELL_E_INVALID_ARG, "opaque object %d: model matrix is not finite", i);
        if (o->model && !snell__matrix_invertible(o->model, why, sizeof why))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "opaque object %d: model matrix %s", i, why);
    }
    return SNELL_OK;
}

/* Each object's model, normal matrix and colour, then its mesh, with p in use. */
static void draw_opaque_list(const snell__opaque_prog *p, const snell_opaque *list, int count)
{
    int i;
    for (i = 0; i < count; i++) {
        const snell_opaque *o = &list[i];
        const snell_mesh *m = o->mesh;
        mat4 model, inv;
        mat3 nm;
        if (o->model) memcpy(model, o->model, sizeof model);
        else glm_mat4_identity(model);
        snell__mat4_inv((const float *)model, (float *)inv);
        glm_mat4_transpose(inv);
        glm_mat4_pick3(inv, nm);
        glUniformMatrix4fv(p->model, 1, GL_FALSE, (const GLfloat *)model);
        glUniformMatrix3fv(p->normal_matrix, 1, GL_FALSE, (const GLfloat *)nm);
        glUniform3fv(p->color, 1, o->color);
        snell__mesh_draw(m);
    }
}

/* The meshes uploaded, p built and in use under depth test LESS with depth
 * write, lit's maps and light on their units (caustics_opaque.frag). */
static snell_status begin(snell_ctx *ctx, snell__opaque_prog *p, const char *vs, const char *defines,
                          const snell_opaque *list, int count, const struct snell__caustics *lit)
{
    snell_status st;
    int i;
    for (i = 0; i < count; i++)
        if ((st = snell__mesh_upload((snell_mesh *)list[i].mesh)) != SNELL_OK) return st;
    if ((st = build(ctx, p, vs, lit ? "caustics_opaque.frag" : "opaque.frag", defines)) != SNELL_OK) return st;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(p->prog);
    if (lit) {
        /* unit 0 keeps the environment */
        snell__lit_opaque_uniforms(p->prog, lit, 1);
        glActiveTexture(GL_TEXTURE0);
    }
    return SNELL_OK;
}

snell_status snell__composite_opaque(snell_ctx *ctx, snell__composite *c, snell__output_kind kind,
                                     const snell_opaque *list, int count, const float view_proj[16],
                                     const float eye[3], const float view_axis[4], const struct snell__caustics *lit)
{
    static const float perspective[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    snell__opaque_prog *p = lit ? &c->opaque_lit[0] : &c->opaque[kind];
    snell_status st;
    if (count == 0) return SNELL_OK;
    if ((st = begin(ctx, p, "object.vert", snell__output_defines(kind), list, count, lit)) != SNELL_OK) return st;
    glUniformMatrix4fv(p->view_proj, 1, GL_FALSE, view_proj);
    glUniform3fv(p->eye, 1, eye);
    glUniform4fv(p->view_axis, 1, view_axis ? view_axis : perspective);
    draw_opaque_list(p, list, count);
    return SNELL_OK;
}

snell_status snell__composite_opaque_paraboloid(snell_ctx *ctx, snell__composite *c, const snell_opaque *list,
                                               int count, const float centre[3], int layer, int size, float z_near,
                                               float z_far, const struct snell__caustics *lit)
{
    snell__opaque_prog *p = lit ? &c->opaque_lit[1] : &c->opaque_dp;
    snell_status st;
    if (count == 0) return SNELL_OK;
    st = begin(ctx, p, "opaque_paraboloid.vert", "#define SNELL_PARABOLOID_VIEW 1\n", list, count, lit);
    if (st != SNELL_OK) return st;
    glUniform3fv(p->eye, 1, centre);
    glUniform3fv(p->centre, 1, centre);
    glUniform1f(p->layer, (float)layer);
    glUniform1f(p->size, (float)size);
    glUniform2f(p->depth_range, z_near, z_far);
    draw_opaque_list(p, list, count);
    return SNELL_OK;
}

static snell_status sky_prog(snell_ctx *ctx, snell__composite *c, snell__output_kind kind, int paraboloid)
{
    if (!c->sky[kind][paraboloid]) {
        char defines[160];
        snell_status st;
        snprintf(defines, sizeof defines, "%s%s", snell__output_defines(kind),
                 paraboloid ? SNELL__ENV_PARABOLOID_DEFINE : "");
        st = snell__program_build(ctx, "skybox.vert", "skybox.frag", defines, &c->sky[kind][paraboloid]);
        if (st != SNELL_OK) return st;
        c->sky_inv[kind][paraboloid] = glGetUniformLocation(c->sky[kind][paraboloid], "u_inv_view_proj_rot");
        c->sky_env[kind][paraboloid] = glGetUniformLocation(c->sky[kind][paraboloid], "u_env");
    }
    if (!c->empty_vao) glGenVertexArrays(1, &c->empty_vao);
    return SNELL_OK;
}

snell_status snell__composite_prepare(snell_ctx *ctx, snell__composite *c, snell__output_kind kind)
{
    return sky_prog(ctx, c, kind, 0);
}

snell_status snell__composite_background(snell_ctx *ctx, snell__composite *c, snell__output_kind kind,
                                         const float rot_view_proj[16])
{
    mat4 inv;
    snell__mat4_inv(rot_view_proj, (float *)inv);
    return snell__composite_background_lookup(ctx, c, kind, 0, (const float *)inv);
}

snell_status snell__composite_background_lookup(snell_ctx *ctx, snell__composite *c, snell__output_kind kind,
                                                int paraboloid, const float inv_rot_view_proj[16])
{
    snell_status st = sky_prog(ctx, c, kind, paraboloid);
    if (st != SNELL_OK) return st;
    /* The triangle lies at the far plane (z = w): LEQUAL passes only where
     * nothing nearer was drawn. */
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glUseProgram(c->sky[kind][paraboloid]);
    glUniformMatrix4fv(c->sky_inv[kind][paraboloid], 1, GL_FALSE, inv_rot_view_proj);
    glUniform1i(c->sky_env[kind][paraboloid], 0);
    glBindVertexArray(c->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
    return SNELL_OK;
}
