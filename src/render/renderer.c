#define _POSIX_C_SOURCE 200809L /* clock_gettime */
/* renderer.c — the frame: background (skybox) then the glass mesh with the
 * chosen refraction kernel (method_*.c), into the renderer's offscreen target
 * or the bound framebuffer. Programs and targets are made at creation; a frame
 * allocates nothing after the first (which uploads the mesh). */
#include "core/ctx.h"
#include "render/env.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "mesh/mesh.h"
#include "render/method.h"
#include "methods/ndcube.h"
#include "render/env_dynamic.h"
#include "core/pack.h"
#include "core/program.h"

#include <math.h>
#include <string.h>
#include <time.h>

#define MAX_RENDER_SIZE 16384

/* Every kernel, indexed by snell_method (AUTO resolves to one of them). */
static const snell__method *const g_methods[] = {NULL, &snell__method_single, &snell__method_cubemap};
#define METHOD_COUNT ((int)(sizeof g_methods / sizeof *g_methods))

struct snell_renderer {
    snell_ctx *ctx;
    int width, height;
    snell_target target;
    snell__output_kind out;
    GLuint fbo, color_rb, depth_rb;
    GLuint empty_vao;               /* the skybox draws without attributes */
    GLuint sky_prog;
    GLint sky_inv, sky_env;
    void *method_state[METHOD_COUNT];
    snell__env_dynamic dyn;         /* opaque objects and the dynamic environment */
    float *readback;                /* RGBA32F scratch for exit directions, made at creation */
    uint8_t *readback8;
};

static snell_status make_target(snell_renderer *r)
{
    GLenum status;
    glGenFramebuffers(1, &r->fbo);
    glGenRenderbuffers(1, &r->color_rb);
    glGenRenderbuffers(1, &r->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, r->color_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, r->out == SNELL__OUT_DIR_FLOAT ? GL_RGBA32F : GL_RGBA8, r->width,
                          r->height);
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

static snell_status create_resources(snell_renderer *r)
{
    snell_status st = snell__program_build(r->ctx, "skybox.vert", "skybox.frag", snell__output_defines(r->out),
                                           &r->sky_prog);
    int m;
    if (st != SNELL_OK) return st;
    r->sky_inv = glGetUniformLocation(r->sky_prog, "u_inv_view_proj_rot");
    r->sky_env = glGetUniformLocation(r->sky_prog, "u_env");
    for (m = 1; m < METHOD_COUNT && st == SNELL_OK; m++)
        st = g_methods[m]->create(r->ctx, r->out, &r->method_state[m]);
    if (st == SNELL_OK) st = snell__env_dynamic_create(r->ctx, r->out, &r->dyn);
    if (st != SNELL_OK) return st;
    glGenVertexArrays(1, &r->empty_vao);
    if (r->target == SNELL_TARGET_OFFSCREEN) st = make_target(r);
    if (st == SNELL_OK && r->out != SNELL__OUT_COLOR) {
        size_t n = (size_t)r->width * (size_t)r->height;
        r->readback = (float *)snell__calloc(&r->ctx->alloc, n, 4 * sizeof(float));
        r->readback8 = (uint8_t *)snell__calloc(&r->ctx->alloc, n, 4);
        if (!r->readback || !r->readback8) st = snell__fail(r->ctx, SNELL_E_NOMEM, "out of memory for readback");
    }
    return st;
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
    if ((unsigned)d.target > SNELL_TARGET_BOUND_FRAMEBUFFER || (unsigned)d.output > SNELL_OUTPUT_EXIT_DIRECTION_PACKED)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "unknown render target %d or output %d", (int)d.target,
                           (int)d.output);
    if (d.output != SNELL_OUTPUT_COLOR && d.target != SNELL_TARGET_OFFSCREEN)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "exit-direction output needs an offscreen target");
    r = (snell_renderer *)snell__calloc(&ctx->alloc, 1, sizeof *r);
    if (!r) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    r->ctx = ctx;
    r->width = d.width;
    r->height = d.height;
    r->target = d.target;
    r->out = d.output == SNELL_OUTPUT_COLOR ? SNELL__OUT_COLOR
             : d.output == SNELL_OUTPUT_EXIT_DIRECTION && snell_ctx_has_gl_extension(ctx, "GL_EXT_color_buffer_float")
                 ? SNELL__OUT_DIR_FLOAT
                 : SNELL__OUT_DIR_PACKED;
    snell__glstate_save(&saved);
    st = create_resources(r);
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
    int m;
    if (!r) return;
    for (m = 1; m < METHOD_COUNT; m++)
        if (r->method_state[m]) g_methods[m]->destroy(r->ctx, r->method_state[m]);
    snell__env_dynamic_destroy(&r->dyn);
    if (r->sky_prog) glDeleteProgram(r->sky_prog);
    if (r->empty_vao) glDeleteVertexArrays(1, &r->empty_vao);
    if (r->fbo) glDeleteFramebuffers(1, &r->fbo);
    if (r->color_rb) glDeleteRenderbuffers(1, &r->color_rb);
    if (r->depth_rb) glDeleteRenderbuffers(1, &r->depth_rb);
    snell__free(&r->ctx->alloc, r->readback);
    snell__free(&r->ctx->alloc, r->readback8);
    snell__free(&r->ctx->alloc, r);
}

/* World-space bounding sphere of the mesh: centre of the object-space box,
 * radius = farthest vertex, scaled by the model's largest axis scale. */
static void bounding_sphere(const snell_mesh *m, mat4 model, float out[4])
{
    vec3 c, wc;
    float s = 0.0f;
    int k;
    for (k = 0; k < 3; k++) c[k] = 0.5f * (m->bmin[k] + m->bmax[k]);
    for (k = 0; k < 3; k++) {
        float len = sqrtf(model[k][0] * model[k][0] + model[k][1] * model[k][1] + model[k][2] * model[k][2]);
        if (len > s) s = len;
    }
    glm_mat4_mulv3(model, c, 1.0f, wc);
    out[0] = wc[0]; out[1] = wc[1]; out[2] = wc[2];
    out[3] = m->bradius * s;
}

static void draw_background(snell_renderer *r, snell__frame *f)
{
    mat4 rot, vp, inv;
    glm_mat4_copy(f->view, rot);
    rot[3][0] = rot[3][1] = rot[3][2] = 0.0f;
    glm_mat4_mul(f->proj, rot, vp);
    glm_mat4_inv(vp, inv);
    /* The triangle lies at the far plane (z = w): LEQUAL passes only where
     * nothing nearer was drawn. */
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glUseProgram(r->sky_prog);
    glUniformMatrix4fv(r->sky_inv, 1, GL_FALSE, (const GLfloat *)inv);
    glUniform1i(r->sky_env, 0);
    glBindVertexArray(r->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
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
    if ((int)g->method < 0 || (int)g->method >= METHOD_COUNT)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "unknown method %d", (int)g->method);
    if (g->search_iterations < 0 || g->search_iterations > SNELL_CUBEMAP_MAX_ITERATIONS)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "search_iterations %d outside 0..%d", g->search_iterations,
                           SNELL_CUBEMAP_MAX_ITERATIONS);
    if (g->linear_steps < 0 || g->linear_steps > SNELL_CUBEMAP_MAX_LINEAR_STEPS)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "linear_steps %d outside 0..%d", g->linear_steps,
                           SNELL_CUBEMAP_MAX_LINEAR_STEPS);
    if (g->max_interfaces < 0 || g->max_interfaces > SNELL_CUBEMAP_MAX_INTERFACES)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "max_interfaces %d outside 0..%d", g->max_interfaces,
                           SNELL_CUBEMAP_MAX_INTERFACES);
    if (g->cube_face_size != 0 && (g->cube_face_size < 16 || g->cube_face_size > 2048))
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "cube_face_size %d outside 16..2048", g->cube_face_size);
    if ((unsigned)g->encoding > SNELL_NDCUBE_OCT)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "unknown ndcube encoding %d", (int)g->encoding);
    if (f->model)
        for (k = 0; k < 16; k++)
            if (!isfinite(f->model[k])) return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "model matrix is not finite");
    return snell__env_dynamic_validate(r->ctx, f);
}

/* AUTO: the cheapest kernel adequate for the mesh. The cubemap method is
 * exact where the mesh is star-shaped about its centre (snell_mesh_analyze);
 * hidden_fraction is the share of surface it cannot represent. The refracted
 * rays seldom reach most of that surface, so the method stays far better
 * than single-surface well beyond small fractions; measured mean exit-
 * direction errors at 512x512 with the defaults (bench/BENCHMARKS_CUBEMAP.md):
 * bunny (hidden 0.23) 6.3 vs 38.5 degrees, torus (0.47) 10.4 vs 37.6, goblet
 * (0.97, thin bowl wall) 30.0 vs 28.3 - no better than single. The
 * threshold sits between the worst mesh it helps and the one it does not. */
#define AUTO_MAX_HIDDEN 0.6f

static snell_method resolve_method(snell_renderer *r, const snell_frame_desc *f, snell_frame_stats *s)
{
    const snell_mesh_analysis *an = NULL;
    if (f->glass.method != SNELL_METHOD_AUTO) return f->glass.method;
    if (!f->mesh || !r->method_state[SNELL_METHOD_CUBEMAP]) return SNELL_METHOD_SINGLE;
    if (snell__cubemap_analysis(r->ctx, r->method_state[SNELL_METHOD_CUBEMAP], f->mesh, &an) != SNELL_OK)
        return SNELL_METHOD_SINGLE; /* unanalysable (e.g. no area): the method that needs nothing */
    s->hidden_fraction = an->hidden_fraction;
    return an->hidden_fraction <= AUTO_MAX_HIDDEN ? SNELL_METHOD_CUBEMAP : SNELL_METHOD_SINGLE;
}

static void setup_frame(snell_renderer *r, const snell_frame_desc *fd, snell__frame *f)
{
    mat4 inv;
    const snell_glass_desc *g = &fd->glass;
    memset(f, 0, sizeof *f);
    f->desc = fd;
    f->mesh = (snell_mesh *)fd->mesh;
    f->env = fd->env;
    f->ior = g->ior > 0.0f ? g->ior : 1.5f;
    f->tint[0] = f->tint[1] = f->tint[2] = 1.0f;
    if (g->tint[0] != 0.0f || g->tint[1] != 0.0f || g->tint[2] != 0.0f) memcpy(f->tint, g->tint, sizeof f->tint);
    if (fd->model) memcpy(f->model, fd->model, sizeof f->model);
    else glm_mat4_identity(f->model);
    snell_camera_matrices(&fd->camera, (float)r->width / (float)r->height, f->eye, (float *)f->view,
                          (float *)f->proj);
    glm_mat4_mul(f->proj, f->view, f->view_proj);
    glm_mat4_inv(f->model, inv);
    glm_mat4_transpose(inv);
    glm_mat4_pick3(inv, f->normal_matrix);
    if (f->mesh) bounding_sphere(f->mesh, f->model, f->bsphere);
    f->width = r->width;
    f->height = r->height;
}

snell_status snell_render(snell_renderer *r, const snell_frame_desc *fd, snell_frame_stats *stats)
{
    snell_glstate saved;
    snell_frame_stats s;
    snell_status st;
    snell__frame f;
    snell_method m;
    int external;
    double t0 = now_ms();
    if (!r || !fd) return snell__fail(r ? r->ctx : NULL, SNELL_E_INVALID_ARG, "snell_render: renderer and frame required");
    st = validate_frame(r, fd);
    if (st != SNELL_OK) return st;
    memset(&s, 0, sizeof s);
    external = r->ctx->backend == SNELL_BACKEND_EXTERNAL;
    if (external) snell__glstate_save(&saved);
    setup_frame(r, fd, &f);

    if (r->target == SNELL_TARGET_OFFSCREEN) glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glViewport(0, 0, r->width, r->height);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    /* Dithering (on by default) may change the low bits of UNORM8 writes: it
     * would corrupt packed exit directions and make images driver-dependent. */
    glDisable(GL_DITHER);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glClearDepthf(1.0f);
    glClear(GL_DEPTH_BUFFER_BIT);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_CUBE_MAP, f.env->texture);

    m = resolve_method(r, fd, &s);
    s.method_used = m;
    if (f.mesh && is_passthrough(&fd->glass) && r->out == SNELL__OUT_COLOR) {
        s.skipped_passthrough = 1;
    }
    if (fd->opaque_count > 0) st = snell__opaque_draw_view(&r->dyn, &f, &s);
    if (st == SNELL_OK && f.mesh && !s.skipped_passthrough && fd->opaque_count > 0) {
        /* The glass sees the opaque objects through a dynamic environment. */
        GLint fbo = 0;
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
        st = snell__env_dynamic_update(r->ctx, &r->dyn, &f, &s);
        if (s.env_updated) {
            glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
            glViewport(0, 0, r->width, r->height);
        }
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_CUBE_MAP, r->dyn.texture);
    }
    if (st == SNELL_OK && f.mesh && !s.skipped_passthrough) {
        st = snell__mesh_upload(f.mesh);
        if (st == SNELL_OK) {
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_LESS);
            glDepthMask(GL_TRUE);
            st = g_methods[m]->draw(r->ctx, r->method_state[m], &f, &s);
        }
    }
    /* The background goes last, where the depth buffer is still clear, so
     * pixels covered by glass or opaque objects are never shaded twice.
     * Exit-direction output always needs it (misses = the view ray). */
    if (st == SNELL_OK && (fd->draw_background >= 0 || r->out != SNELL__OUT_COLOR)) {
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_CUBE_MAP, f.env->texture);
        draw_background(r, &f);
        s.passes++;
    }
    glBindVertexArray(0);
    if (external) snell__glstate_restore(&saved);
    if (st == SNELL_OK && glGetError() != GL_NO_ERROR) st = snell__fail(r->ctx, SNELL_E_GL, "GL error during the frame");
    s.cpu_ms = now_ms() - t0;
    if (stats) *stats = s;
    return st;
}

/* Reads the offscreen colour buffer (bottom row first, as GL stores it). */
static snell_status read_target(snell_renderer *r, GLenum type, void *pixels)
{
    GLint prev_fbo = 0, prev_align = 4;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev_fbo);
    glGetIntegerv(GL_PACK_ALIGNMENT, &prev_align);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, r->width, r->height, GL_RGBA, type, pixels);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)prev_fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, prev_align);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(r->ctx, SNELL_E_GL, "glReadPixels failed");
}

snell_status snell_renderer_read_rgba(snell_renderer *r, uint8_t *pixels)
{
    int y;
    size_t row;
    snell_status st;
    if (!r || !pixels) return snell__fail(r ? r->ctx : NULL, SNELL_E_INVALID_ARG, "read_rgba: NULL argument");
    if (r->target != SNELL_TARGET_OFFSCREEN || r->out != SNELL__OUT_COLOR)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "read_rgba needs an offscreen colour renderer");
    if ((st = read_target(r, GL_UNSIGNED_BYTE, pixels)) != SNELL_OK) return st;
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
    return SNELL_OK;
}

snell_status snell_renderer_read_exit_dirs(snell_renderer *r, float *xyz)
{
    int x, y;
    snell_status st;
    if (!r || !xyz) return snell__fail(r ? r->ctx : NULL, SNELL_E_INVALID_ARG, "read_exit_dirs: NULL argument");
    if (r->out == SNELL__OUT_COLOR)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "renderer was not created with SNELL_OUTPUT_EXIT_DIRECTION");
    st = r->out == SNELL__OUT_DIR_FLOAT ? read_target(r, GL_FLOAT, r->readback)
                                        : read_target(r, GL_UNSIGNED_BYTE, r->readback8);
    if (st != SNELL_OK) return st;
    for (y = 0; y < r->height; y++)
        for (x = 0; x < r->width; x++) {
            size_t src = (size_t)(r->height - 1 - y) * r->width + x, dst = (size_t)y * r->width + x;
            if (r->out == SNELL__OUT_DIR_FLOAT) {
                memcpy(xyz + 3 * dst, r->readback + 4 * src, 3 * sizeof(float));
            } else {
                snell_unpack_dir_rgba8(r->readback8 + 4 * src, xyz + 3 * dst);
            }
        }
    return SNELL_OK;
}

const char *snell_renderer_exit_dir_encoding(const snell_renderer *r)
{
    if (!r || r->out == SNELL__OUT_COLOR) return "none";
    return r->out == SNELL__OUT_DIR_FLOAT ? "float" : "packed-rgba8";
}

void snell_renderer_finish(snell_renderer *r)
{
    (void)r;
    glFinish();
}
