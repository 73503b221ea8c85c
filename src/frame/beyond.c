/* SPDX-License-Identifier: MIT */
/* beyond.c — see beyond.h. */
#include "frame/beyond.h"
#include "core/gl.h"

const char *const snell__beyond_uniform_names[SNELL__BEYOND_UNIFORMS] = {
    "u_scene_layer_count", "u_scene_capped", "u_scene_glass_ids", "u_scene_opaque_count",
    "u_scene_self",        "u_scene_view_proj", "u_scene_eye",    "u_scene_fwd",
    "u_scene_near",        "u_scene_inv_range", "u_scene_size"};

void snell__beyond_locate(unsigned prog, snell__beyond_locs *l)
{
    int *locs = (int *)(void *)l, i;
    for (i = 0; i < SNELL__BEYOND_UNIFORMS; i++) locs[i] = glGetUniformLocation(prog, snell__beyond_uniform_names[i]);
}

void snell__beyond_uniforms(const snell__beyond_locs *l, const snell__view *v, int self)
{
    const snell__scene_layers *sl = &v->layers;
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
