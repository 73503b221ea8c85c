/* beyond.c — see beyond.h. */
#include "frame/beyond.h"
#include "core/gl.h"

void snell__beyond_locate(unsigned prog, snell__beyond_locs *l)
{
    l->layers = glGetUniformLocation(prog, "u_scene_layers");
    l->table = glGetUniformLocation(prog, "u_scene_table");
    l->layer_count = glGetUniformLocation(prog, "u_scene_layer_count");
    l->capped = glGetUniformLocation(prog, "u_scene_capped");
    l->glass_ids = glGetUniformLocation(prog, "u_scene_glass_ids");
    l->opaque_count = glGetUniformLocation(prog, "u_scene_opaque_count");
    l->self = glGetUniformLocation(prog, "u_scene_self");
    l->view_proj = glGetUniformLocation(prog, "u_scene_view_proj");
    l->eye = glGetUniformLocation(prog, "u_scene_eye");
    l->fwd = glGetUniformLocation(prog, "u_scene_fwd");
    l->near_ = glGetUniformLocation(prog, "u_scene_near");
    l->inv_range = glGetUniformLocation(prog, "u_scene_inv_range");
    l->size = glGetUniformLocation(prog, "u_scene_size");
}

void snell__beyond_uniforms(const snell__beyond_locs *l, const snell__view *v, int self)
{
    const snell__scene_layers *sl = &v->layers;
    glUniform1i(l->layers, SNELL__LAYERS_UNIT);
    glUniform1i(l->table, SNELL__LAYERS_TABLE_UNIT);
    glUniform1i(l->layer_count, sl->count);
    glUniform1i(l->capped, sl->capped);
    glUniform1i(l->glass_ids, sl->glass_ids);
    glUniform1i(l->opaque_count, sl->opaque_count);
    glUniform1i(l->self, self);
    glUniformMatrix4fv(l->view_proj, 1, GL_FALSE, (const GLfloat *)v->view_proj);
    glUniform3fv(l->eye, 1, v->eye);
    glUniform3fv(l->fwd, 1, sl->fwd);
    glUniform1f(l->near_, sl->near_);
    glUniform1f(l->inv_range, sl->inv_range);
    glUniform2f(l->size, (float)sl->width, (float)sl->height);
}
