/* SPDX-License-Identifier: MIT */
/* caustics_maps.c — the caustics stage's light frame and the maps made in it
 * (render/caustics.c): the shadow map of every object, the opaque receivers'
 * depth and caustic maps, the receiver plane's light map with the direct light. */
#include "render/caustics_private.h"
#include "core/light_map.h"
#include "mesh/mesh.h"

#include <math.h>
#include <string.h>

snell_status snell__caustics_complete(snell_ctx *ctx, const char *what)
{
    GLenum s = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (s != GL_FRAMEBUFFER_COMPLETE)
        return snell__fail(ctx, SNELL_E_GL, "caustics: %s framebuffer incomplete (0x%x)", what, (unsigned)s);
    return SNELL_OK;
}

static snell_status shadow_target(snell_ctx *ctx, snell__caustics *c, int size)
{
    GLenum none = GL_NONE;
    if (c->shadow_size == size) return SNELL_OK;
    if (!c->shadow_fbo) {
        glGenFramebuffers(1, &c->shadow_fbo);
        glGenTextures(1, &c->shadow_z);
    }
    glBindTexture(GL_TEXTURE_2D, c->shadow_z);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, NULL);
    /* linear with the compare mode: 2 x 2 percentage-closer filtering */
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glBindFramebuffer(GL_FRAMEBUFFER, c->shadow_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, c->shadow_z, 0);
    glDrawBuffers(1, &none);
    glReadBuffer(GL_NONE);
    if (snell__caustics_complete(ctx, "shadow map") != SNELL_OK) return SNELL_E_GL;
    c->shadow_size = size;
    return SNELL_OK;
}

snell_status snell__caustics_map_target(snell_ctx *ctx, snell__caustics *c, int size)
{
    if (c->map_size == size) return SNELL_OK;
    if (!c->map_fbo) {
        glGenFramebuffers(1, &c->map_fbo);
        glGenTextures(1, &c->map_tex);
    }
    glBindTexture(GL_TEXTURE_2D, c->map_tex);
    snell__light_map_image(c->map_format, size);
    snell__texture_nearest(GL_TEXTURE_2D, 1); /* read bilinearly by caustics_receiver.frag (32F need not filter) */
    glBindFramebuffer(GL_FRAMEBUFFER, c->map_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, c->map_tex, 0);
    if (snell__caustics_complete(ctx, "light map") != SNELL_OK) return SNELL_E_GL;
    c->map_size = size;
    return SNELL_OK;
}

/* --- the light's frame ------------------------------------------------------ */
void snell__caustics_resolve_light(const snell_light *l, snell__caustics_light *o)
{
    float len = sqrtf(l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                      l->direction[2] * l->direction[2]);
    int k;
    o->spot = l->type == SNELL_LIGHT_SPOT;
    for (k = 0; k < 3; k++) {
        o->d[k] = l->direction[k] / len;
        o->pos[k] = l->position[k];
        o->col[k] = l->color[k];
    }
    o->cos_cone = cosf(l->spot_angle);
}

/* A perspective view from eye towards target (spot lights), frustum
 * x/-z in [lo[0], hi[0]], y/-z in [lo[1], hi[1]]. */
void snell__caustics_spot_view(const float eye[3], const float target[3], const float lo[2], const float hi[2],
                               float near_, float far_, mat4 vp)
{
    vec3 up = {0.0f, 1.0f, 0.0f}, dir;
    mat4 view, proj;
    glm_vec3_sub((float *)target, (float *)eye, dir);
    glm_vec3_normalize(dir);
    if (fabsf(dir[1]) > 0.99f) up[0] = 0.0f, up[1] = 0.0f, up[2] = 1.0f;
    glm_lookat((float *)eye, (float *)target, up, view);
    glm_frustum(lo[0] * near_, hi[0] * near_, lo[1] * near_, hi[1] * near_, near_, far_, proj);
    glm_mat4_mul(proj, view, vp);
}

/* An orthographic view along unit d centred on `centre`: x, y in [-half,
 * half] and depths [near, far] from an eye at centre - d * back. */
void snell__caustics_light_view(const float d[3], const float centre[3], float back, float lo[2], float hi[2],
                                float near_, float far_, mat4 vp)
{
    vec3 eye, up = {0.0f, 1.0f, 0.0f};
    mat4 view, proj;
    if (fabsf(d[1]) > 0.99f) up[0] = 1.0f, up[1] = 0.0f;
    eye[0] = centre[0] - d[0] * back, eye[1] = centre[1] - d[1] * back, eye[2] = centre[2] - d[2] * back;
    glm_lookat(eye, (float *)centre, up, view);
    glm_ortho(lo[0], hi[0], lo[1], hi[1], near_, far_, proj);
    glm_mat4_mul(proj, view, vp);
}

void snell__caustics_draw_mesh(GLuint prog, const snell_mesh *m, const float *model, const float vp[16])
{
    mat4 mm, inv;
    mat3 nm;
    if (model) memcpy(mm, model, sizeof mm);
    else glm_mat4_identity(mm);
    glm_mat4_inv(mm, inv);
    glm_mat4_transpose(inv);
    glm_mat4_pick3(inv, nm);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_model"), 1, GL_FALSE, (const GLfloat *)mm);
    glUniformMatrix3fv(glGetUniformLocation(prog, "u_normal_matrix"), 1, GL_FALSE, (const GLfloat *)nm);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE, vp);
    snell__mesh_draw(m);
}

void snell__caustics_plane_uniform(GLuint prog, const snell_receiver *rc)
{
    glUniform4f(glGetUniformLocation(prog, "u_plane"), rc->height, rc->center[0], rc->center[1], rc->extent);
}

static void opaque_sphere(const snell_opaque *o, float b[4])
{
    mat4 m;
    if (o->model) memcpy(m, o->model, sizeof m);
    else glm_mat4_identity(m);
    snell__bounding_sphere(o->mesh, m, b);
}

static void grow(float lo[2], float hi[2], float x, float y)
{
    if (x < lo[0]) lo[0] = x;
    if (x > hi[0]) hi[0] = x;
    if (y < lo[1]) lo[1] = y;
    if (y > hi[1]) hi[1] = y;
}

void snell__caustics_make_frame(const snell_frame_desc *fd, const snell__scene *sc, const snell__caustics_light *L,
                                snell__caustics_frame *F)
{
    const snell_receiver *rc = &fd->receiver;
    int plane = rc->extent > 0.0f, i, k;
    float centre[3] = {rc->center[0], rc->height, rc->center[1]};
    float back = 1.0f, lo[2] = {1e30f, 1e30f}, hi[2] = {-1e30f, -1e30f}, far_ = 0.0f, b[4];
    mat4 view;
    const float *d = L->d;
    F->size = rc->map_size;
    F->size = F->size * 2 > 2048 ? 2048 : F->size * 2;
    if (!plane) { /* the opaque receivers' mean centre */
        centre[0] = centre[1] = centre[2] = 0.0f;
        for (i = 0; i < fd->opaque_count; i++) {
            opaque_sphere(&fd->opaque[i], b);
            for (k = 0; k < 3; k++) centre[k] += b[k] / (float)fd->opaque_count;
        }
    }
    if (L->spot) {
        float below[3] = {L->pos[0], L->pos[1] - 1.0f, L->pos[2]}, up[3] = {0.0f, 0.0f, 1.0f};
        glm_lookat((float *)L->pos, below, up, view);
    } else {
        /* behind every caster: the eye's distance from the centre along -d */
        for (i = 0; i < sc->count + fd->opaque_count; i++) {
            float t;
            if (i < sc->count) memcpy(b, sc->obj[i].bsphere, sizeof b);
            else opaque_sphere(&fd->opaque[i - sc->count], b);
            t = -((b[0] - centre[0]) * d[0] + (b[1] - centre[1]) * d[1] + (b[2] - centre[2]) * d[2]) + b[3];
            if (t + 1.0f > back) back = t + 1.0f;
        }
        {
            vec3 eye, up = {0.0f, 1.0f, 0.0f};
            if (fabsf(d[1]) > 0.99f) up[0] = 1.0f, up[1] = 0.0f;
            for (k = 0; k < 3; k++) eye[k] = centre[k] - d[k] * back;
            glm_lookat(eye, centre, up, view);
        }
    }
    /* the square's corners in the light's view fix the window and the far plane */
    for (k = 0; k < 4 && plane; k++) {
        vec4 p = {rc->center[0] + ((k & 1) ? rc->extent : -rc->extent), rc->height,
                  rc->center[1] + ((k & 2) ? rc->extent : -rc->extent), 1.0f}, q;
        glm_mat4_mulv(view, p, q);
        if (L->spot) { /* directions x/-z, y/-z; the plane is below the light (else nothing is lit) */
            float z = -q[2] > 1e-3f ? -q[2] : 1e-3f;
            q[0] /= z, q[1] /= z;
        }
        grow(lo, hi, q[0], q[1]);
        if (-q[2] > far_) far_ = -q[2];
    }
    /* and the opaque receivers' bounding spheres (spot: their boxes' corners; one
     * above the light widens the window to its limit) */
    for (i = 0; i < fd->opaque_count; i++) {
        vec4 c, q;
        opaque_sphere(&fd->opaque[i], b);
        c[0] = b[0], c[1] = b[1], c[2] = b[2], c[3] = 1.0f;
        glm_mat4_mulv(view, c, q);
        if (-q[2] + b[3] > far_) far_ = -q[2] + b[3];
        if (!L->spot) {
            grow(lo, hi, q[0] - b[3], q[1] - b[3]);
            grow(lo, hi, q[0] + b[3], q[1] + b[3]);
        } else {
            for (k = 0; k < 8; k++) {
                float x = q[0] + ((k & 1) ? b[3] : -b[3]), y = q[1] + ((k & 2) ? b[3] : -b[3]);
                float z = -q[2] + ((k & 4) ? b[3] : -b[3]);
                if (z > 1e-3f) grow(lo, hi, x / z, y / z);
                else grow(lo, hi, x < 0.0f ? -1e3f : 1e3f, y < 0.0f ? -1e3f : 1e3f);
            }
        }
    }
    if (L->spot) {
        float h = plane ? L->pos[1] - rc->height : 0.0f, t = 12.0f; /* at most ~170 degrees across */
        float wx, wy;
        for (i = 0; i < 2; i++) {
            if (lo[i] < -t) lo[i] = -t;
            if (hi[i] > t) hi[i] = t;
        }
        if (fd->opaque_count > 0 && far_ > h) h = far_;
        if (h <= 1e-3f) h = 1e-3f;
        F->near_ = h * 0.01f, F->far_ = h * 1.01f + 1e-3f;
        snell__caustics_spot_view(L->pos, (float[3]){L->pos[0], L->pos[1] - 1.0f, L->pos[2]}, lo, hi, F->near_, F->far_,
                                  F->vp);
        wx = fmaxf(-lo[0], hi[0]), wy = fmaxf(-lo[1], hi[1]);
        F->reach = F->far_ * sqrtf(1.0f + wx * wx + wy * wy);
    } else {
        F->near_ = 0.01f, F->far_ = far_ + 1.0f;
        snell__caustics_light_view(d, centre, back, lo, hi, F->near_, F->far_, F->vp);
        F->reach = sqrtf((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                         (F->far_ - F->near_) * (F->far_ - F->near_));
    }
    F->texel = fmaxf(hi[0] - lo[0], hi[1] - lo[1]) / (float)F->size;
    F->area = (hi[0] - lo[0]) * (hi[1] - lo[1]) / ((float)F->size * (float)F->size);
}

/* A depth-only pass from the light into fbo (size x size), cleared, with the depth program. */
static void begin_depth_pass(const snell__caustics *c, GLuint fbo, int size)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, size, size);
    glDepthMask(GL_TRUE);
    glClearDepthf(1.0f);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(c->map_prog);
}

/* The shadow map in the light frame: every casting glass and opaque object. */
snell_status snell__caustics_draw_shadows(snell_ctx *ctx, snell__caustics *c, const snell_frame_desc *fd,
                                          const snell__scene *sc, const snell__caustics_frame *F)
{
    snell_status st;
    int i;
    if ((st = shadow_target(ctx, c, F->size)) != SNELL_OK) return st;
    begin_depth_pass(c, c->shadow_fbo, F->size);
    for (i = 0; i < sc->count; i++)
        if (snell__caustics_casts(&sc->obj[i]))
            snell__caustics_draw_mesh(c->map_prog, sc->obj[i].mesh, (const float *)sc->obj[i].model,
                                      (const float *)F->vp);
    for (i = 0; i < fd->opaque_count; i++)
        snell__caustics_draw_mesh(c->map_prog, fd->opaque[i].mesh, fd->opaque[i].model, (const float *)F->vp);
    return SNELL_OK;
}

/* The opaque receivers in the light frame: their nearest depth (where
 * photons stop, and which surface a caustic texel belongs to), and their
 * caustic map cleared for the photons. */
snell_status snell__caustics_draw_receivers(snell_ctx *ctx, snell__caustics *c, const snell_frame_desc *fd,
                                            const snell__caustics_frame *F)
{
    int i;
    if (c->recv_size != F->size) {
        snell_status st;
        if (!c->recv_fbo) {
            glGenFramebuffers(1, &c->recv_fbo);
            glGenTextures(1, &c->recv_z);
            glGenFramebuffers(1, &c->cm_fbo);
            glGenTextures(1, &c->cm_tex);
        }
        glBindTexture(GL_TEXTURE_2D, c->recv_z);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, F->size, F->size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, NULL);
        snell__texture_nearest(GL_TEXTURE_2D, 1);
        glBindTexture(GL_TEXTURE_2D, c->cm_tex);
        snell__light_map_image(c->map_format, F->size);
        snell__texture_nearest(GL_TEXTURE_2D, 1);
        glBindFramebuffer(GL_FRAMEBUFFER, c->cm_fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, c->cm_tex, 0);
        if ((st = snell__caustics_complete(ctx, "caustic map")) != SNELL_OK) return st;
        glBindFramebuffer(GL_FRAMEBUFFER, c->recv_fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, c->recv_z, 0);
        {
            GLenum none = GL_NONE;
            glDrawBuffers(1, &none);
            glReadBuffer(GL_NONE);
        }
        if ((st = snell__caustics_complete(ctx, "receiver depth")) != SNELL_OK) return st;
        c->recv_size = F->size;
    }
    begin_depth_pass(c, c->recv_fbo, F->size);
    for (i = 0; i < fd->opaque_count; i++)
        snell__caustics_draw_mesh(c->map_prog, fd->opaque[i].mesh, fd->opaque[i].model, (const float *)F->vp);
    glBindFramebuffer(GL_FRAMEBUFFER, c->cm_fbo);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    return SNELL_OK;
}

void snell__caustics_light_uniforms(GLuint prog, const snell__caustics_light *L)
{
    glUniform1i(glGetUniformLocation(prog, "u_spot"), L->spot);
    glUniform3fv(glGetUniformLocation(prog, "u_dir"), 1, L->d);
    glUniform3fv(glGetUniformLocation(prog, "u_pos"), 1, L->pos);
    glUniform3fv(glGetUniformLocation(prog, "u_axis"), 1, L->d);
    glUniform1f(glGetUniformLocation(prog, "u_cos_cone"), L->cos_cone);
}

/* The direct light into the light map (replacing what it held). */
void snell__caustics_draw_direct(snell__caustics *c, const snell_frame_desc *fd, const snell__caustics_light *L,
                                 const snell__caustics_frame *F)
{
    glBindFramebuffer(GL_FRAMEBUFFER, c->map_fbo);
    glViewport(0, 0, c->map_size, c->map_size);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glUseProgram(c->direct_prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, c->shadow_z);
    glUniform1i(glGetUniformLocation(c->direct_prog, "u_shadow"), 0);
    glUniformMatrix4fv(glGetUniformLocation(c->direct_prog, "u_shadow_vp"), 1, GL_FALSE, (const GLfloat *)F->vp);
    snell__caustics_plane_uniform(c->direct_prog, &fd->receiver);
    glUniform3fv(glGetUniformLocation(c->direct_prog, "u_color"), 1, L->col);
    snell__caustics_light_uniforms(c->direct_prog, L);
    glUniform1f(glGetUniformLocation(c->direct_prog, "u_texel"), 2.0f / (float)c->map_size);
    glUniform1f(glGetUniformLocation(c->direct_prog, "u_bias"), SNELL__CAUSTICS_SHADOW_BIAS);
    glBindVertexArray(c->vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

/* The light frame's uniforms (photons and lit opaque shading). */
void snell__caustics_frame_uniforms(GLuint prog, const snell__caustics *c)
{
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_recv_vp"), 1, GL_FALSE, c->frame_vp);
    glUniform4fv(glGetUniformLocation(prog, "u_recv_lin"), 1, c->frame_lin);
}
