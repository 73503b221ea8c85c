/* glass_program.c — build and bind a kernel's program; shared uniforms. */
#include "methods/glass_program.h"
#include "core/gl.h"
#include "core/program.h"

#include <string.h>

const char *snell__output_defines(snell__output_kind out)
{
    switch (out) {
    case SNELL__OUT_DIR_FLOAT: return "#define SNELL_OUTPUT_EXIT_DIR_FLOAT 1\n";
    case SNELL__OUT_DIR_PACKED: return "#define SNELL_OUTPUT_EXIT_DIR_PACKED 1\n";
    default: return "";
    }
}

snell_status snell__glass_program_build(snell_ctx *ctx, const char *fs_path, snell__output_kind out,
                                        const char *extra_defines, snell__glass_program *g)
{
    char defines[1024];
    snell_status st;
    snprintf(defines, sizeof defines, "%s%s", snell__output_defines(out), extra_defines ? extra_defines : "");
    memset(g, 0, sizeof *g);
    st = snell__program_build(ctx, "object.vert", fs_path, defines, &g->prog);
    if (st != SNELL_OK) return st;
    g->model = glGetUniformLocation(g->prog, "u_model");
    g->normal_matrix = glGetUniformLocation(g->prog, "u_normal_matrix");
    g->view_proj = glGetUniformLocation(g->prog, "u_view_proj");
    g->eye = glGetUniformLocation(g->prog, "u_eye");
    g->env = glGetUniformLocation(g->prog, "u_env");
    g->ior = glGetUniformLocation(g->prog, "u_ior");
    g->sigma = glGetUniformLocation(g->prog, "u_sigma");
    g->tint = glGetUniformLocation(g->prog, "u_tint");
    g->bsphere = glGetUniformLocation(g->prog, "u_bsphere");
    return SNELL_OK;
}

void snell__glass_program_destroy(snell__glass_program *g)
{
    if (g->prog) glDeleteProgram(g->prog);
    g->prog = 0;
}

void snell__glass_program_use(const snell__glass_program *g, const snell__view *v, const snell__object *o)
{
    glUseProgram(g->prog);
    glUniformMatrix4fv(g->model, 1, GL_FALSE, (const GLfloat *)o->model);
    glUniformMatrix3fv(g->normal_matrix, 1, GL_FALSE, (const GLfloat *)o->normal_matrix);
    glUniformMatrix4fv(g->view_proj, 1, GL_FALSE, (const GLfloat *)v->view_proj);
    glUniform3fv(g->eye, 1, v->eye);
    glUniform1i(g->env, 0);
    glUniform1f(g->ior, o->glass->material.ior);
    glUniform3fv(g->sigma, 1, o->glass->absorption);
    glUniform3fv(g->tint, 1, o->glass->material.tint);
    glUniform4fv(g->bsphere, 1, o->bsphere);
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
    glBindVertexArray(o->mesh->vao);
    glDrawElements(GL_TRIANGLES, (GLsizei)(3 * o->mesh->triangle_count), GL_UNSIGNED_INT, (const void *)0);
    glDisable(GL_CULL_FACE);
}
