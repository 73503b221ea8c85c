/* SPDX-License-Identifier: MIT */
/* caustics_receiver.c — the caustics stage's receivers drawn in the view with
 * their maps (the plane; the opaque objects lit, caustics_opaque.frag) and
 * the glass kernels' hook SNELL_RECEIVER (common/receiver.glsl). */
#include "render/caustics_private.h"
#include "frame/glass_program.h"

#include <string.h>

/* The opaque objects lit (caustics_opaque.frag), over what the opaque stage
 * drew: the same vertices (object.vert), depth LEQUAL. */
static void draw_lit_opaque(snell__caustics *c, const snell_frame_desc *fd, const snell__scene *sc)
{
    GLuint p = c->opaque_prog;
    int i;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glUseProgram(p);
    snell__lit_opaque_uniforms(p, c, 0);
    glUniform3fv(glGetUniformLocation(p, "u_eye"), 1, sc->view.eye);
    glUniform4fv(glGetUniformLocation(p, "u_view_axis"), 1, sc->view.view_axis);
    for (i = 0; i < fd->opaque_count; i++) {
        glUniform3fv(glGetUniformLocation(p, "u_color"), 1, fd->opaque[i].color);
        snell__caustics_draw_mesh(p, fd->opaque[i].mesh, fd->opaque[i].model, (const float *)sc->view.view_proj);
    }
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
}

static snell_status draw_receiver(snell__caustics *c, const snell_frame_desc *fd, const snell__scene *sc)
{
    const snell_receiver *rc = &fd->receiver;
    float albedo[3];
    memcpy(albedo, rc->albedo, sizeof rc->albedo);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(c->receiver_prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, c->map_tex);
    glUniform1i(glGetUniformLocation(c->receiver_prog, "u_plane_map"), 0);
    glUniform3fv(glGetUniformLocation(c->receiver_prog, "u_plane_albedo"), 1, albedo);
    glUniform3fv(glGetUniformLocation(c->receiver_prog, "u_eye"), 1, sc->view.eye);
    glUniform4fv(glGetUniformLocation(c->receiver_prog, "u_view_axis"), 1, sc->view.view_axis);
    glUniformMatrix4fv(glGetUniformLocation(c->receiver_prog, "u_view_proj"), 1, GL_FALSE,
                       (const GLfloat *)sc->view.view_proj);
    snell__caustics_plane_uniform(c->receiver_prog, rc);
    glBindVertexArray(c->vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    return SNELL_OK;
}

/* The receivers in the view with the light maps: the plane, the opaque objects lit. */
snell_status snell__caustics_draw_view(snell__caustics *c, const snell_frame_desc *fd, const snell__scene *sc)
{
    if (c->made_opaque) draw_lit_opaque(c, fd, sc);
    return c->made_plane ? draw_receiver(c, fd, sc) : SNELL_OK;
}

/* --- the glass kernels' hook SNELL_RECEIVER ------------------------------ */
void snell__receiver_view(snell__view *v, snell__caustics *c, const snell_receiver *rc)
{
    c->frame_opaque = c->made_opaque;
    c->frame_plane = c->made_plane;
    if (c->made_opaque) {
        snell__textures_publish(&v->textures, "u_shadow", GL_TEXTURE_2D, c->shadow_z, 0);
        snell__textures_publish(&v->textures, "u_recv_z", GL_TEXTURE_2D, c->recv_z, 0);
        snell__textures_publish(&v->textures, "u_caustic", GL_TEXTURE_2D, c->cm_tex, 0);
    }
    memset(c->frame_plane_rect, 0, sizeof c->frame_plane_rect); /* extent 0 without a plane: none seen */
    if (!c->made_plane) return;
    snell__textures_publish(&v->textures, "u_plane_map", GL_TEXTURE_2D, c->map_tex, 0);
    c->frame_plane_rect[0] = rc->height, c->frame_plane_rect[1] = rc->center[0];
    c->frame_plane_rect[2] = rc->center[1], c->frame_plane_rect[3] = rc->extent;
    memcpy(c->frame_albedo, rc->albedo, sizeof rc->albedo);
}

static const char *receiver_defines(unsigned bits)
{
    (void)bits;
    return "#define SNELL_RECEIVER 1\n";
}

static const char *const receiver_uniform_names[SNELL__RECEIVER_UNIFORMS] = {"u_plane", "u_plane_albedo",
                                                                              "u_lit_opaque"};

/* common/opaque_lit.glsl's uniforms of the program in use, its three maps on
 * units unit..unit + 2 (c NULL: the samplers' units alone): the opaque objects lit by the light the maps were
 * made with (caustics_opaque.frag; a kernel without the scene layers has
 * none of these uniforms: -1, ignored). */
void snell__lit_opaque_uniforms(unsigned prog, const snell__caustics *c, int unit)
{
    static const char *const samplers[3] = {"u_shadow", "u_recv_z", "u_caustic"};
    snell__caustics_light L;
    int i;
    for (i = 0; i < 3 && unit >= 0; i++) glUniform1i(glGetUniformLocation(prog, samplers[i]), unit + i);
    if (!c) return;
    if (unit >= 0) {
        const unsigned tex[3] = {c->shadow_z, c->recv_z, c->cm_tex};
        for (i = 0; i < 3; i++) {
            glActiveTexture(GL_TEXTURE0 + (GLenum)(unit + i));
            glBindTexture(GL_TEXTURE_2D, tex[i]);
        }
    }
    snell__caustics_resolve_light(&c->light, &L);
    snell__caustics_frame_uniforms(prog, c);
    snell__caustics_light_uniforms(prog, &L);
    glUniform3fv(glGetUniformLocation(prog, "u_light"), 1, L.col);
    glUniform1f(glGetUniformLocation(prog, "u_bias"), SNELL__CAUSTICS_SHADOW_BIAS);
}

static void receiver_uniforms(const snell__glass_program *g, const int *locs, const void *state,
                              const snell__view *v, const snell__object *o)
{
    const snell__caustics *c = (const snell__caustics *)state;
    (void)v, (void)o;
    glUniform4fv(locs[0], 1, c->frame_plane_rect);
    glUniform3fv(locs[1], 1, c->frame_albedo);
    glUniform1i(locs[2], c->frame_opaque);
    snell__lit_opaque_uniforms(g->prog, c->frame_opaque ? c : NULL, -1);
}

const snell__kernel_hook snell__receiver_hook = {
    .variant_bits = 1,
    .defines = receiver_defines,
    .uniform_names = receiver_uniform_names,
    .uniform_count = SNELL__RECEIVER_UNIFORMS,
    .uniforms = receiver_uniforms,
};

