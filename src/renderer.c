#define _POSIX_C_SOURCE 200809L /* clock_gettime */
/* renderer.c — the frame: background (skybox) then the glass mesh with the
 * chosen refraction kernel, into the renderer's offscreen target or the bound
 * framebuffer. Programs and targets are made at creation; a frame allocates
 * nothing after the first (which uploads the mesh). */
#include "ctx.h"
#include "env.h"
#include "gl.h"
#include "glstate.h"
#include "mesh.h"
#include "program.h"

#include <cglm/cglm.h>
#include <math.h>
#include <string.h>
#include <time.h>

#define MAX_RENDER_SIZE 16384

typedef struct glass_program {
    GLuint prog;
    GLint model, normal_matrix, view_proj, eye, env, ior, sigma, tint, bsphere;
} glass_program;

struct snell_renderer {
    snell_ctx *ctx;
    int width, height;
    snell_target target;
    GLuint fbo, color_rb, depth_rb;
    GLuint empty_vao;               /* skybox draws without attributes */
    GLuint sky_prog;
    GLint sky_inv, sky_env;
    glass_program single;
};

static snell_status build_glass(snell_ctx *ctx, const char *fs, glass_program *g)
{
    snell_status st = snell__program_build(ctx, "glass.vert", fs, NULL, &g->prog);
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

static snell_status make_target(snell_renderer *r)
{
    GLenum status;
    glGenFramebuffers(1, &r->fbo);
    glGenRenderbuffers(1, &r->color_rb);
    glGenRenderbuffers(1, &r->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, r->color_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, r->width, r->height);
    glBindRenderbuffer(GL_RENDERBUFFER, r->depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, r->width, r->height);
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->color_rb);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->depth_rb);
    status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return snell__fail(r->ctx, SNELL_E_GL, "offscreen %dx%d framebuffer incomplete (0x%x)", r->width,
                           r->height, (unsigned)status);
    return glGetError() == GL_NO_ERROR ? SNELL_OK
                                       : snell__fail(r->ctx, SNELL_E_GL, "GL error creating a %dx%d target",
                                                     r->width, r->height);
}

snell_status snell_renderer_create(snell_ctx *ctx, const snell_renderer_desc *desc, snell_renderer **out)
{
    snell_renderer_desc d;
    snell_renderer *r;
    snell_status st;
    snell_glstate saved;
    GLint max_rb = 0;
    if (!ctx || !out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_renderer_create: ctx and out are required");
    *out = NULL;
    memset(&d, 0, sizeof d);
    if (desc) d = *desc;
    if (!d.width) d.width = 512;
    if (!d.height) d.height = 512;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
    if (d.width < 1 || d.height < 1 || d.width > MAX_RENDER_SIZE || d.height > MAX_RENDER_SIZE ||
        (d.target == SNELL_TARGET_OFFSCREEN && (d.width > max_rb || d.height > max_rb)))
        return snell__fail(ctx, SNELL_E_LIMIT, "render size %dx%d outside 1..%d", d.width, d.height,
                           max_rb < MAX_RENDER_SIZE ? max_rb : MAX_RENDER_SIZE);
    if ((unsigned)d.target > SNELL_TARGET_BOUND_FRAMEBUFFER)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "unknown render target %d", (int)d.target);
    r = (snell_renderer *)snell__calloc(&ctx->alloc, 1, sizeof *r);
    if (!r) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    r->ctx = ctx;
    r->width = d.width;
    r->height = d.height;
    r->target = d.target;
    snell__glstate_save(&saved);
    st = snell__program_build(ctx, "skybox.vert", "skybox.frag", NULL, &r->sky_prog);
    if (st == SNELL_OK) {
        r->sky_inv = glGetUniformLocation(r->sky_prog, "u_inv_view_proj_rot");
        r->sky_env = glGetUniformLocation(r->sky_prog, "u_env");
        st = build_glass(ctx, "single.frag", &r->single);
    }
    if (st == SNELL_OK) glGenVertexArrays(1, &r->empty_vao);
    if (st == SNELL_OK && r->target == SNELL_TARGET_OFFSCREEN) st = make_target(r);
    snell__glstate_restore(&saved);
    if (st != SNELL_OK) {
        snell_renderer_destroy(r);
        return st;
    }
    *out = r;
    return SNELL_OK;
}

void snell_renderer_destroy(snell_renderer *r)
{
    if (!r) return;
    if (r->single.prog) glDeleteProgram(r->single.prog);
    if (r->sky_prog) glDeleteProgram(r->sky_prog);
    if (r->empty_vao) glDeleteVertexArrays(1, &r->empty_vao);
    if (r->fbo) glDeleteFramebuffers(1, &r->fbo);
    if (r->color_rb) glDeleteRenderbuffers(1, &r->color_rb);
    if (r->depth_rb) glDeleteRenderbuffers(1, &r->depth_rb);
    snell__free(&r->ctx->alloc, r);
}

/* World-space bounding sphere of the mesh: centre of the object-space box,
 * radius = farthest vertex, scaled by the model's largest axis scale. */
static void bounding_sphere(const snell_mesh *m, mat4 model, float out[4])
{
    vec3 c, wc;
    float r2 = 0.0f, s = 0.0f;
    uint32_t i;
    int k;
    for (k = 0; k < 3; k++) c[k] = 0.5f * (m->bmin[k] + m->bmax[k]);
    for (i = 0; i < m->vertex_count; i++) {
        const float *p = m->positions + 3 * i;
        float d2 = (p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) + (p[2] - c[2]) * (p[2] - c[2]);
        if (d2 > r2) r2 = d2;
    }
    for (k = 0; k < 3; k++) {
        float len = sqrtf(model[k][0] * model[k][0] + model[k][1] * model[k][1] + model[k][2] * model[k][2]);
        if (len > s) s = len;
    }
    glm_mat4_mulv3(model, c, 1.0f, wc);
    out[0] = wc[0]; out[1] = wc[1]; out[2] = wc[2];
    out[3] = sqrtf(r2) * s;
}

static void draw_background(snell_renderer *r, mat4 view, mat4 proj)
{
    mat4 rot, vp, inv;
    glm_mat4_copy(view, rot);
    rot[3][0] = rot[3][1] = rot[3][2] = 0.0f;
    glm_mat4_mul(proj, rot, vp);
    glm_mat4_inv(vp, inv);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glUseProgram(r->sky_prog);
    glUniformMatrix4fv(r->sky_inv, 1, GL_FALSE, (const GLfloat *)inv);
    glUniform1i(r->sky_env, 0);
    glBindVertexArray(r->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

static void draw_glass(const glass_program *g, const snell_frame_desc *f, mat4 model, mat4 view_proj,
                       const float eye[3])
{
    mat4 inv;
    mat3 nrm;
    float bs[4];
    const snell_glass_desc *gd = &f->glass;
    float ior = gd->ior > 0.0f ? gd->ior : 1.5f;
    float tint[3] = {1.0f, 1.0f, 1.0f};
    if (gd->tint[0] != 0.0f || gd->tint[1] != 0.0f || gd->tint[2] != 0.0f) memcpy(tint, gd->tint, sizeof tint);
    glm_mat4_inv(model, inv);
    glm_mat4_transpose(inv);
    glm_mat4_pick3(inv, nrm);
    bounding_sphere(f->mesh, model, bs);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(g->prog);
    glUniformMatrix4fv(g->model, 1, GL_FALSE, (const GLfloat *)model);
    glUniformMatrix3fv(g->normal_matrix, 1, GL_FALSE, (const GLfloat *)nrm);
    glUniformMatrix4fv(g->view_proj, 1, GL_FALSE, (const GLfloat *)view_proj);
    glUniform3fv(g->eye, 1, eye);
    glUniform1i(g->env, 0);
    glUniform1f(g->ior, ior);
    glUniform3fv(g->sigma, 1, gd->absorption);
    glUniform3fv(g->tint, 1, tint);
    glUniform4fv(g->bsphere, 1, bs);
    glBindVertexArray(f->mesh->vao);
    glDrawElements(GL_TRIANGLES, (GLsizei)(3 * f->mesh->triangle_count), GL_UNSIGNED_INT, (const void *)0);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* Glass that changes nothing: IOR 1, no absorption, no tint. */
static int is_passthrough(const snell_glass_desc *g)
{
    return g->ior == 1.0f && g->absorption[0] == 0.0f && g->absorption[1] == 0.0f && g->absorption[2] == 0.0f &&
           ((g->tint[0] == 0.0f && g->tint[1] == 0.0f && g->tint[2] == 0.0f) ||
            (g->tint[0] == 1.0f && g->tint[1] == 1.0f && g->tint[2] == 1.0f));
}

static snell_status validate_frame(snell_renderer *r, const snell_frame_desc *f)
{
    const snell_glass_desc *g = &f->glass;
    int k;
    if (!f->env || !f->env->texture)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "frame needs an environment created with a context");
    if (g->ior < 0.0f || !isfinite(g->ior) || (g->ior != 0.0f && (g->ior < 0.05f || g->ior > 100.0f)))
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "IOR %g outside 0.05..100", g->ior);
    for (k = 0; k < 3; k++)
        if (!(g->absorption[k] >= 0.0f) || !isfinite(g->absorption[k]) || !(g->tint[k] >= 0.0f) ||
            !isfinite(g->tint[k]))
            return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "absorption and tint must be finite and >= 0");
    if ((unsigned)g->method > SNELL_METHOD_SINGLE)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "unknown method %d", (int)g->method);
    if (f->model)
        for (k = 0; k < 16; k++)
            if (!isfinite(f->model[k])) return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "model matrix is not finite");
    return SNELL_OK;
}

snell_status snell_render(snell_renderer *r, const snell_frame_desc *f, snell_frame_stats *stats)
{
    snell_glstate saved;
    snell_frame_stats s;
    snell_status st;
    mat4 model, view, proj, view_proj;
    float eye[3];
    int external;
    double t0 = now_ms();
    if (!r || !f) return snell__fail(r ? r->ctx : NULL, SNELL_E_INVALID_ARG, "snell_render: renderer and frame required");
    st = validate_frame(r, f);
    if (st != SNELL_OK) return st;
    memset(&s, 0, sizeof s);
    external = r->ctx->backend == SNELL_BACKEND_EXTERNAL;
    if (external) snell__glstate_save(&saved);

    if (f->model) memcpy(model, f->model, sizeof model);
    else glm_mat4_identity(model);
    snell_camera_matrices(&f->camera, (float)r->width / (float)r->height, eye, (float *)view, (float *)proj);
    glm_mat4_mul(proj, view, view_proj);

    if (r->target == SNELL_TARGET_OFFSCREEN) glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glViewport(0, 0, r->width, r->height);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glClearDepthf(1.0f);
    glClear(GL_DEPTH_BUFFER_BIT);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_CUBE_MAP, f->env->texture);

    if (f->draw_background >= 0) {
        draw_background(r, view, proj);
        s.passes++;
    }
    s.method_used = SNELL_METHOD_SINGLE;
    if (f->mesh && is_passthrough(&f->glass)) {
        s.skipped_passthrough = 1;
    } else if (f->mesh) {
        st = snell__mesh_upload((snell_mesh *)f->mesh);
        if (st == SNELL_OK) {
            draw_glass(&r->single, f, model, view_proj, eye);
            s.passes++;
        }
    }
    glBindVertexArray(0);
    if (external) snell__glstate_restore(&saved);
    if (st == SNELL_OK && glGetError() != GL_NO_ERROR) st = snell__fail(r->ctx, SNELL_E_GL, "GL error during the frame");
    s.cpu_ms = now_ms() - t0;
    if (stats) *stats = s;
    return st;
}

snell_status snell_renderer_read_rgba(snell_renderer *r, uint8_t *pixels)
{
    GLint prev_fbo = 0, prev_align = 4;
    int y;
    size_t row;
    if (!r || !pixels) return snell__fail(r ? r->ctx : NULL, SNELL_E_INVALID_ARG, "read_rgba: NULL argument");
    if (r->target != SNELL_TARGET_OFFSCREEN)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "read_rgba needs an offscreen renderer");
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev_fbo);
    glGetIntegerv(GL_PACK_ALIGNMENT, &prev_align);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, r->width, r->height, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)prev_fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, prev_align);
    /* GL's row 0 is the bottom; flip in place so row 0 is the top. */
    row = (size_t)r->width * 4;
    for (y = 0; y < r->height / 2; y++) {
        uint8_t *a = pixels + (size_t)y * row, *b = pixels + (size_t)(r->height - 1 - y) * row;
        size_t i;
        for (i = 0; i < row; i++) {
            uint8_t t = a[i];
            a[i] = b[i];
            b[i] = t;
        }
    }
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(r->ctx, SNELL_E_GL, "glReadPixels failed");
}

void snell_renderer_finish(snell_renderer *r)
{
    (void)r;
    glFinish();
}
