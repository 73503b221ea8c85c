/* env_dynamic.c — dynamic environment (Unger 4.1: "the environment map is
 * rendered from the centre with the background and all other objects", at a
 * lower resolution than the static one). Unlike the seed, which re-renders
 * every frame, the cubemap is re-rendered only when an opaque object, its
 * model or colour, the glass centre or the static environment changed. */
#include "render/env_dynamic.h"
#include "core/ctx.h"
#include "render/env.h"
#include "core/gl.h"
#include "mesh/mesh.h"
#include "methods/ndcube.h"
#include "core/program.h"

#include <math.h>
#include <string.h>

#define MAX_DYN_SIZE 2048

static snell_status build_opaque(snell_ctx *ctx, const char *defines, snell__opaque_prog *p)
{
    snell_status st = snell__program_build(ctx, "opaque.vert", "opaque.frag", defines, &p->prog);
    if (st != SNELL_OK) return st;
    p->model = glGetUniformLocation(p->prog, "u_model");
    p->normal_matrix = glGetUniformLocation(p->prog, "u_normal_matrix");
    p->view_proj = glGetUniformLocation(p->prog, "u_view_proj");
    p->eye = glGetUniformLocation(p->prog, "u_eye");
    p->color = glGetUniformLocation(p->prog, "u_color");
    return SNELL_OK;
}

snell_status snell__env_dynamic_create(snell_ctx *ctx, snell__output_kind out, snell__env_dynamic *d)
{
    snell_status st;
    memset(d, 0, sizeof *d);
    st = build_opaque(ctx, snell__output_defines(out), &d->view_prog);
    if (st == SNELL_OK) st = build_opaque(ctx, NULL, &d->cube_prog);
    if (st == SNELL_OK) st = snell__program_build(ctx, "skybox.vert", "skybox.frag", NULL, &d->sky_prog);
    if (st != SNELL_OK) {
        snell__env_dynamic_destroy(d);
        return st;
    }
    d->sky_inv = glGetUniformLocation(d->sky_prog, "u_inv_view_proj_rot");
    d->sky_env = glGetUniformLocation(d->sky_prog, "u_env");
    return SNELL_OK;
}

void snell__env_dynamic_destroy(snell__env_dynamic *d)
{
    if (d->view_prog.prog) glDeleteProgram(d->view_prog.prog);
    if (d->cube_prog.prog) glDeleteProgram(d->cube_prog.prog);
    if (d->sky_prog) glDeleteProgram(d->sky_prog);
    if (d->texture) glDeleteTextures(1, &d->texture);
    if (d->fbo) glDeleteFramebuffers(1, &d->fbo);
    if (d->depth_rb) glDeleteRenderbuffers(1, &d->depth_rb);
    memset(d, 0, sizeof *d);
}

snell_status snell__env_dynamic_validate(snell_ctx *ctx, const snell_frame_desc *fd)
{
    int i, k;
    if (fd->opaque_count < 0 || fd->opaque_count > SNELL_MAX_OPAQUE || (fd->opaque_count > 0 && !fd->opaque))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "opaque_count %d outside 0..%d or opaque list NULL",
                           fd->opaque_count, SNELL_MAX_OPAQUE);
    if (fd->dynamic_env_size != 0 && (fd->dynamic_env_size < 16 || fd->dynamic_env_size > MAX_DYN_SIZE))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "dynamic_env_size %d outside 16..%d", fd->dynamic_env_size,
                           MAX_DYN_SIZE);
    for (i = 0; i < fd->opaque_count; i++) {
        const snell_opaque *o = &fd->opaque[i];
        if (!o->mesh) return snell__fail(ctx, SNELL_E_INVALID_ARG, "opaque object %d has no mesh", i);
        for (k = 0; k < 3; k++)
            if (!isfinite(o->color[k]) || o->color[k] < 0.0f)
                return snell__fail(ctx, SNELL_E_INVALID_ARG, "opaque object %d: colour must be finite and >= 0", i);
        if (o->model)
            for (k = 0; k < 16; k++)
                if (!isfinite(o->model[k]))
                    return snell__fail(ctx, SNELL_E_INVALID_ARG, "opaque object %d: model matrix is not finite", i);
    }
    return SNELL_OK;
}

static void object_matrices(const snell_opaque *o, mat4 model, mat3 nm, float color[3])
{
    mat4 inv;
    if (o->model) memcpy(model, o->model, sizeof(mat4));
    else glm_mat4_identity(model);
    glm_mat4_inv(model, inv);
    glm_mat4_transpose(inv);
    glm_mat4_pick3(inv, nm);
    if (o->color[0] == 0.0f && o->color[1] == 0.0f && o->color[2] == 0.0f) color[0] = color[1] = color[2] = 0.8f;
    else memcpy(color, o->color, 3 * sizeof(float));
}

static void draw_objects(const snell__opaque_prog *p, const snell_frame_desc *fd, mat4 view_proj, const float eye[3])
{
    int i;
    glUseProgram(p->prog);
    glUniformMatrix4fv(p->view_proj, 1, GL_FALSE, (const GLfloat *)view_proj);
    glUniform3fv(p->eye, 1, eye);
    for (i = 0; i < fd->opaque_count; i++) {
        const snell_mesh *m = fd->opaque[i].mesh;
        mat4 model;
        mat3 nm;
        float color[3];
        object_matrices(&fd->opaque[i], model, nm, color);
        glUniformMatrix4fv(p->model, 1, GL_FALSE, (const GLfloat *)model);
        glUniformMatrix3fv(p->normal_matrix, 1, GL_FALSE, (const GLfloat *)nm);
        glUniform3fv(p->color, 1, color);
        glBindVertexArray(m->vao);
        glDrawElements(GL_TRIANGLES, (GLsizei)(3 * m->triangle_count), GL_UNSIGNED_INT, (const void *)0);
    }
}

snell_status snell__opaque_draw_view(snell__env_dynamic *d, const snell__frame *f, snell_frame_stats *stats)
{
    const snell_frame_desc *fd = f->desc;
    int i;
    for (i = 0; i < fd->opaque_count; i++) {
        snell_status st = snell__mesh_upload((snell_mesh *)fd->opaque[i].mesh);
        if (st != SNELL_OK) return st;
    }
    if (!fd->opaque_count) return SNELL_OK;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    draw_objects(&d->view_prog, fd, (vec4 *)f->view_proj, f->eye);
    stats->passes++;
    return SNELL_OK;
}

/* Did anything the cubemap shows change since it was rendered? */
static int changed(const snell__env_dynamic *d, const snell__frame *f, int size)
{
    const snell_frame_desc *fd = f->desc;
    int i;
    if (!d->valid || d->size != size || d->env != f->env || d->count != fd->opaque_count ||
        memcmp(d->centre, f->bsphere, sizeof d->centre))
        return 1;
    for (i = 0; i < fd->opaque_count; i++) {
        const snell_opaque *o = &fd->opaque[i];
        float ident[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        if (d->mesh[i] != o->mesh || d->version[i] != o->mesh->version ||
            memcmp(d->model[i], o->model ? o->model : ident, sizeof d->model[i]) ||
            memcmp(d->color[i], o->color, sizeof d->color[i]))
            return 1;
    }
    return 0;
}

static void remember(snell__env_dynamic *d, const snell__frame *f)
{
    const snell_frame_desc *fd = f->desc;
    int i;
    static const float ident[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    d->valid = 1;
    d->env = f->env;
    memcpy(d->centre, f->bsphere, sizeof d->centre);
    d->count = fd->opaque_count;
    for (i = 0; i < fd->opaque_count; i++) {
        const snell_opaque *o = &fd->opaque[i];
        d->mesh[i] = o->mesh;
        d->version[i] = o->mesh->version;
        memcpy(d->model[i], o->model ? o->model : ident, sizeof d->model[i]);
        memcpy(d->color[i], o->color, sizeof d->color[i]);
    }
}

snell_status snell__env_dynamic_update(snell_ctx *ctx, snell__env_dynamic *d, const snell__frame *f,
                                       snell_frame_stats *stats)
{
    const snell_frame_desc *fd = f->desc;
    int size = fd->dynamic_env_size, face;
    float z_near, z_far;
    if (!size) {
        /* Unger 4.1: lower resolution than the static map; half of it, capped. */
        size = f->env->size / 2;
        if (size > 256) size = 256;
        if (size < 16) size = 16;
    }
    if (!changed(d, f, size)) {
        stats->env_skipped = 1;
        return SNELL_OK;
    }
    if (d->size != size) {
        if (d->texture) glDeleteTextures(1, &d->texture);
        if (!d->fbo) glGenFramebuffers(1, &d->fbo);
        if (!d->depth_rb) glGenRenderbuffers(1, &d->depth_rb);
        d->texture = snell__cube_texture_create(size, GL_LINEAR);
        glBindRenderbuffer(GL_RENDERBUFFER, d->depth_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, size, size);
        d->size = size;
        d->valid = 0;
        if (glGetError() != GL_NO_ERROR)
            return snell__fail(ctx, SNELL_E_GL, "cannot create a %dx%d dynamic environment", size, size);
    }
    /* Seen from the glass centre: objects beyond the glass's own bounding
     * sphere matter; the near plane sits at 1% of its radius. */
    z_near = f->bsphere[3] > 0.0f ? 0.01f * f->bsphere[3] : 0.01f;
    z_far = 1e4f * z_near + 1000.0f;
    glBindFramebuffer(GL_FRAMEBUFFER, d->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, d->depth_rb);
    glViewport(0, 0, size, size);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_CUBE_MAP, f->env->texture);
    for (face = 0; face < 6; face++) {
        mat4 vp, rot_vp, inv;
        float origin[3] = {0, 0, 0};
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, (GLenum)(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face),
                               d->texture, 0);
        if (face == 0 && glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return snell__fail(ctx, SNELL_E_GL, "dynamic environment framebuffer incomplete");
        glDepthMask(GL_TRUE);
        glClear(GL_DEPTH_BUFFER_BIT);
        /* background: the static environment through this face */
        snell__cube_face_view_proj(face, origin, z_near, z_far, rot_vp);
        glm_mat4_inv(rot_vp, inv);
        glDisable(GL_DEPTH_TEST);
        glUseProgram(d->sky_prog);
        glUniformMatrix4fv(d->sky_inv, 1, GL_FALSE, (const GLfloat *)inv);
        glUniform1i(d->sky_env, 0);
        glBindVertexArray(0); /* the skybox needs no attributes */
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        snell__cube_face_view_proj(face, f->bsphere, z_near, z_far, vp);
        draw_objects(&d->cube_prog, fd, vp, f->bsphere);
        stats->passes += 1 + (fd->opaque_count > 0);
    }
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    remember(d, f);
    stats->env_updated = 1;
    return glGetError() == GL_NO_ERROR ? SNELL_OK
                                       : snell__fail(ctx, SNELL_E_GL, "GL error rendering the dynamic environment");
}
