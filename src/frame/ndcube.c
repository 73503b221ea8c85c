/* SPDX-License-Identifier: MIT */
/* ndcube.c — bake the normal+distance cubemap (Unger 4.1, Li et al. 2007):
 * 6 passes (one per face) of the mesh from the centre with depth test GREATER
 * and culling off, so the farthest surface wins; see ndcube.h. */
#include "frame/ndcube.h"
#include "frame/env.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "core/program.h"
#include "frame/pass.h"

#include <string.h>

#define MAX_FACE 2048

void snell__cube_face_view_proj(int face, const float eye[3], float z_near, float z_far, mat4 out)
{
    /* GL cube face orientation (GLES 3.0 table 3.21): looking along the major
     * axis, s grows with the camera's right and t with its up vector. */
    static const float look[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const float up[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    vec3 e, c, u;
    mat4 view, proj;
    int k;
    for (k = 0; k < 3; k++) {
        e[k] = eye[k];
        c[k] = eye[k] + look[face][k];
        u[k] = up[face][k];
    }
    glm_lookat(e, c, u, view);
    glm_perspective((float)(SNELL_PI / 2.0), 1.0f, z_near, z_far, proj);
    snell__mat4_mul((const float *)proj, (const float *)view, (float *)out);
}

snell_status snell__ndcube_baker_create(snell_ctx *ctx, snell__ndcube_baker *b)
{
    static const char *defines[2] = {"#define SNELL_NDCUBE_PLAIN 1\n", "#define SNELL_NDCUBE_OCT 1\n"};
    int i;
    memset(b, 0, sizeof *b);
    for (i = 0; i < 2; i++) {
        snell_status st = snell__program_build(ctx, "ndcube_bake.vert", "ndcube_bake.frag", defines[i], &b->prog[i]);
        if (st != SNELL_OK) {
            snell__ndcube_baker_destroy(b);
            return st;
        }
        b->u_view_proj[i] = glGetUniformLocation(b->prog[i], "u_view_proj");
        b->u_centre[i] = glGetUniformLocation(b->prog[i], "u_centre");
        b->u_inv_radius[i] = glGetUniformLocation(b->prog[i], "u_inv_radius");
    }
    glGenFramebuffers(1, &b->fbo);
    glGenRenderbuffers(1, &b->depth_rb);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "GL error creating the ndcube baker");
}

void snell__ndcube_baker_destroy(snell__ndcube_baker *b)
{
    int i;
    for (i = 0; i < 2; i++)
        if (b->prog[i]) glDeleteProgram(b->prog[i]);
    if (b->fbo) glDeleteFramebuffers(1, &b->fbo);
    if (b->depth_rb) glDeleteRenderbuffers(1, &b->depth_rb);
    memset(b, 0, sizeof *b);
}

void snell__ndcube_release(snell__ndcube *cube)
{
    if (cube->texture) glDeleteTextures(1, &cube->texture);
    memset(cube, 0, sizeof *cube);
}

static snell_status make_texture(snell_ctx *ctx, snell__ndcube *cube, int size, snell_ndcube_encoding enc)
{
    /* PLAIN channels are each linear in what they hold, so GL_LINEAR filtering
     * interpolates normal and distance between texels (Unger's setup). OCT
     * must be fetched unfiltered: bytes of a 16-bit split and octahedral
     * coordinates do not interpolate. */
    GLint filter = enc == SNELL_NDCUBE_PLAIN ? GL_LINEAR : GL_NEAREST;
    snell__ndcube_release(cube);
    cube->texture = snell__cube_texture_create(size, filter);
    cube->face_size = size;
    cube->encoding = enc;
    return glGetError() == GL_NO_ERROR ? SNELL_OK
                                       : snell__fail(ctx, SNELL_E_GL, "cannot create a %dx%d ndcube texture", size, size);
}

snell_status snell__ndcube_bake(snell_ctx *ctx, snell__ndcube_baker *b, snell_mesh *mesh, const float centre[3],
                                float radius, int face_size, snell_ndcube_encoding enc, snell__ndcube *cube)
{
    int face, pi = enc == SNELL_NDCUBE_OCT ? 1 : 0;
    snell__pass pass;
    snell_status st;
    if (face_size < 1 || face_size > MAX_FACE || !(radius > 0.0f) || (enc != SNELL_NDCUBE_PLAIN && enc != SNELL_NDCUBE_OCT))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "ndcube: face size %d, radius %g or encoding %d invalid",
                           face_size, radius, (int)enc);
    glActiveTexture(GL_TEXTURE1);
    if (!cube->texture || cube->face_size != face_size || cube->encoding != enc) {
        st = make_texture(ctx, cube, face_size, enc);
        if (st != SNELL_OK) return st;
    }
    if (b->depth_size != face_size) {
        glBindRenderbuffer(GL_RENDERBUFFER, b->depth_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, face_size, face_size);
        b->depth_size = face_size;
    }
    memcpy(cube->centre, centre, sizeof cube->centre);
    cube->radius = radius;

    /* d = 0 clear: "no surface", every point counts as outside; GREATER with
     * depth cleared to 0 keeps the farthest surface. */
    snell__pass_begin(&pass, b->fbo, face_size, face_size, 0, GL_GREATER, 0.0f);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, b->depth_rb);
    glUseProgram(b->prog[pi]);
    glUniform3fv(b->u_centre[pi], 1, centre);
    /* Slightly more than 1/radius would clip the farthest vertex's depth at
     * exactly 1; the shader clamps d to [0,1], and depth 1.0 still passes
     * GREATER against the cleared 0. */
    glUniform1f(b->u_inv_radius[pi], 1.0f / radius);
    glBindVertexArray(mesh->vao);
    for (face = 0; face < 6; face++) {
        mat4 vp;
        GLenum fst;
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, (GLenum)(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face),
                               cube->texture, 0);
        if (face == 0 && (fst = glCheckFramebufferStatus(GL_FRAMEBUFFER)) != GL_FRAMEBUFFER_COMPLETE) {
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
            snell__pass_end(&pass);
            return snell__fail(ctx, SNELL_E_GL, "ndcube framebuffer incomplete (0x%x)", (unsigned)fst);
        }
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        /* near: surfaces closer than 1e-4 radius to the centre are clipped (a
         * centre that close to the surface is rejected by the analysis anyway);
         * far: every vertex lies within radius. */
        snell__cube_face_view_proj(face, centre, radius * 1e-4f, radius * 1.01f, vp);
        glUniformMatrix4fv(b->u_view_proj[pi], 1, GL_FALSE, (const GLfloat *)vp);
        snell__mesh_draw(mesh);
    }
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    snell__pass_end(&pass);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "GL error baking the ndcube");
}

snell_status snell__ndcube_read_face(snell_ctx *ctx, snell__ndcube_baker *b, const snell__ndcube *cube, int face,
                                     uint8_t *rgba)
{
    GLint prev_read = 0;
    snell__pixel_store pack;
    GLenum fst;
    if (!cube->texture || face < 0 || face > 5 || !rgba)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "ndcube_read_face: no cube, bad face %d or NULL", face);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev_read);
    snell__pixel_pack_begin(&pack, 1); /* client memory, tight rows, whatever the host set */
    glBindFramebuffer(GL_READ_FRAMEBUFFER, b->fbo);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, (GLenum)(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face),
                           cube->texture, 0);
    fst = glCheckFramebufferStatus(GL_READ_FRAMEBUFFER);
    if (fst == GL_FRAMEBUFFER_COMPLETE)
        glReadPixels(0, 0, cube->face_size, cube->face_size, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)prev_read);
    snell__pixel_pack_end(&pack);
    if (fst != GL_FRAMEBUFFER_COMPLETE) return snell__fail(ctx, SNELL_E_GL, "ndcube face not readable (0x%x)", (unsigned)fst);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "GL error reading an ndcube face");
}
