/* SPDX-License-Identifier: MIT */
/* refine.c — progressive refinement of still frames (snell_renderer_desc.
 * refine = N): while nothing the frame depends on changes (a hash of its
 * inputs, by cause), each frame is one more sample: its projection moved
 * within the pixel by the R2 sequence (Roberts 2018, a Kronecker sequence of
 * the plastic number) and, in exact with inner_fresnel, each exit's
 * reflection followed at random (common/refine.glsl). The samples' mean is
 * kept in RGBA32F and written over the image read back. */
#include "render/stages.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"
#include "frame/env.h"
#include "mesh/mesh.h"
#include "water/water.h"

#include <string.h>

/* What restarts the mean, in the order checked: each its own hash. */
enum { CAUSE_CAMERA, CAUSE_SCENE, CAUSE_ENV, CAUSE_BACKDROP, CAUSE_SETTINGS, CAUSE_METHOD, CAUSES };
static const char *const g_cause[CAUSES] = {
    "the camera or size", "an object, mesh or material", "the environment", "the backdrop",
    "the frame's settings (light, receiver, layers, water, budget, depth, background)",
    "the method or material an object was drawn with (AUTO, budget)"};

typedef struct refine_state {
    int max;                        /* snell_renderer_desc.refine; 0: off */
    int float_target;               /* GL_EXT_color_buffer_float: the mean is kept; 0: frames unrefined */
    int count;                      /* samples in the mean */
    int sample;                     /* this frame's sample index (plan), -1: it adds none */
    int cause;                      /* what restarted the mean last, -1: the first frame */
    int started;                    /* the keys hold a frame */
    uint64_t key[CAUSES];
    int cur;                        /* which accumulation target holds the mean */
    unsigned acc_tex[2], acc_fbo[2], copy_tex, copy_fbo, prog, vao;
    int u_frame, u_acc, u_weight;
} refine_state;

/* FNV-1a, 64 bits, over n bytes; structs are hashed field by field
 * where they have padding. */
static uint64_t mix(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = (const unsigned char *)p;
    while (n--) h = (h ^ *b++) * 1099511628211ull;
    return h;
}
#define MIX(h, x) ((h) = mix((h), &(x), sizeof(x)))

static void keys(const snell__frame *f, uint64_t k[CAUSES])
{
    const snell_frame_desc *fd = f->fd;
    const snell__scene *sc = f->sc;
    const snell_backdrop *b = fd->backdrop;
    int i;
    for (i = 0; i < CAUSES; i++) k[i] = 14695981039346656037ull;
    k[CAUSE_CAMERA] = mix(k[CAUSE_CAMERA], &sc->view.view, sizeof sc->view.view);
    k[CAUSE_CAMERA] = mix(k[CAUSE_CAMERA], &sc->view.proj, sizeof sc->view.proj);
    MIX(k[CAUSE_CAMERA], sc->view.width);
    MIX(k[CAUSE_CAMERA], sc->view.height);
    for (i = 0; i < fd->glass_count; i++) {
        const snell_mesh *m = fd->glass[i].mesh;
        MIX(k[CAUSE_SCENE], m);
        MIX(k[CAUSE_SCENE], m->version);
        MIX(k[CAUSE_SCENE], sc->obj[i].model);
        MIX(k[CAUSE_SCENE], fd->glass[i].material); /* 4-byte fields: no padding */
    }
    MIX(k[CAUSE_SCENE], fd->glass_count);
    for (i = 0; i < fd->opaque_count; i++) {
        const snell_opaque *o = &fd->opaque[i];
        MIX(k[CAUSE_SCENE], o->mesh);
        MIX(k[CAUSE_SCENE], o->mesh->version);
        if (o->model) k[CAUSE_SCENE] = mix(k[CAUSE_SCENE], o->model, 16 * sizeof(float));
        MIX(k[CAUSE_SCENE], o->color);
    }
    MIX(k[CAUSE_SCENE], fd->opaque_count);
    MIX(k[CAUSE_ENV], fd->env);
    if (fd->env) MIX(k[CAUSE_ENV], fd->env->texture); /* NULL in a frame of panels only */
    if (b) {
        MIX(k[CAUSE_BACKDROP], b->source);
        MIX(k[CAUSE_BACKDROP], b->color_texture);
        MIX(k[CAUSE_BACKDROP], b->depth_texture);
        MIX(k[CAUSE_BACKDROP], b->width);
        MIX(k[CAUSE_BACKDROP], b->height);
        MIX(k[CAUSE_BACKDROP], b->region);
        MIX(k[CAUSE_BACKDROP], b->distance);
        if (b->camera) MIX(k[CAUSE_BACKDROP], *b->camera); /* floats and an enum */
    }
    MIX(k[CAUSE_SETTINGS], fd->light);
    MIX(k[CAUSE_SETTINGS], fd->receiver);
    MIX(k[CAUSE_SETTINGS], fd->draw_background);
    MIX(k[CAUSE_SETTINGS], fd->dynamic_env_size);
    MIX(k[CAUSE_SETTINGS], fd->scene_layers);
    MIX(k[CAUSE_SETTINGS], fd->budget_ms);
    MIX(k[CAUSE_SETTINGS], fd->quality_floor_db);
    MIX(k[CAUSE_SETTINGS], fd->depth);
    MIX(k[CAUSE_SETTINGS], fd->water);
    if (fd->water) MIX(k[CAUSE_SETTINGS], fd->water->version);
}

/* What each object was drawn with, known once the glass stage ran. */
static uint64_t drawn_key(const snell__frame *f)
{
    uint64_t k = 14695981039346656037ull;
    int i;
    for (i = 0; i < f->sc->count; i++) {
        const snell__object *o = &f->sc->obj[i];
        MIX(k, o->method);
        MIX(k, o->scale);
        MIX(k, f->sc->glass[i].material);
    }
    return k;
}

/* Sample n's offset within the pixel, in pixels, -0.5..0.5: R2's point n,
 * (0, 0) for n = 0 (the unrefined frame's rays). */
static void offset(int n, double o[2])
{
    const double a1 = 0.7548776662466927, a2 = 0.5698402909980532; /* 1/g, 1/g^2, g^3 = g + 1 */
    double x = 0.5 + a1 * n, y = 0.5 + a2 * n;
    o[0] = x - (double)(long)x - 0.5;
    o[1] = y - (double)(long)y - 0.5;
}

/* The projection moved by (dx, dy) pixels: ndc' = ndc + 2 d / size, i.e.
 * row 0 (1) of every column plus its w row times that. */
static void jitter(snell__view *v, const double o[2])
{
    float *p = (float *)v->proj, dx = (float)(2.0 * o[0] / v->width), dy = (float)(2.0 * o[1] / v->height);
    int c;
    for (c = 0; c < 4; c++) {
        p[4 * c + 0] += dx * p[4 * c + 3];
        p[4 * c + 1] += dy * p[4 * c + 3];
    }
    snell__mat4_mul((const float *)v->proj, (const float *)v->view, (float *)v->view_proj);
    snell__mat4_inv((const float *)v->view_proj, (float *)v->inv_view_proj);
}

static snell_status validate_renderer(snell__services *sv, const snell_renderer_desc *d)
{
    if (d->refine < 0 || d->refine > SNELL_MAX_REFINE)
        return snell__fail(sv->ctx, SNELL_E_INVALID_ARG, "refine %d outside 0..%d", d->refine, SNELL_MAX_REFINE);
    if (d->refine && (d->target != SNELL_TARGET_OFFSCREEN || d->output != SNELL_OUTPUT_COLOR || d->msaa > 1))
        return snell__fail(sv->ctx, SNELL_E_INVALID_ARG,
                           "refine %d needs an offscreen colour renderer without msaa", d->refine);
    return SNELL_OK;
}

static snell_status make_target(GLenum format, int w, int h, unsigned *tex, unsigned *fbo)
{
    glGenTextures(1, tex);
    glBindTexture(GL_TEXTURE_2D, *tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
    snell__texture_nearest(GL_TEXTURE_2D, 1);
    glGenFramebuffers(1, fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, *tex, 0);
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE ? SNELL_OK : SNELL_E_GL;
}

/* The targets at the output's size, made once: the frame's copy (RGBA8)
 * and two RGBA32F means, read one and written the other. */
static snell_status create(snell__services *sv, const snell_renderer_desc *d, void *state)
{
    refine_state *rs = (refine_state *)state;
    int w = sv->out_width, h = sv->out_height, i;
    snell_status st;
    rs->max = d->refine;
    if (!rs->max) return SNELL_OK;
    rs->float_target = snell_ctx_has_gl_extension(sv->ctx, "GL_EXT_color_buffer_float");
    if (!rs->float_target) return SNELL_OK;
    if ((st = snell__budget_check(sv->ctx, (size_t)w * (size_t)h * 36u, "the refine stage's targets")) != SNELL_OK)
        return st;
    st = make_target(GL_RGBA8, w, h, &rs->copy_tex, &rs->copy_fbo);
    for (i = 0; i < 2 && st == SNELL_OK; i++) st = make_target(GL_RGBA32F, w, h, &rs->acc_tex[i], &rs->acc_fbo[i]);
    if (st != SNELL_OK) return snell__fail(sv->ctx, SNELL_E_GL, "refine: %dx%d targets incomplete", w, h);
    if ((st = snell__program_build(sv->ctx, "skybox.vert", "refine_mean.frag", "", &rs->prog)) != SNELL_OK) return st;
    rs->u_frame = glGetUniformLocation(rs->prog, "u_frame");
    rs->u_acc = glGetUniformLocation(rs->prog, "u_acc");
    rs->u_weight = glGetUniformLocation(rs->prog, "u_weight");
    glGenVertexArrays(1, &rs->vao);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(sv->ctx, SNELL_E_GL, "GL error creating the refine stage");
}

static void destroy(snell_ctx *ctx, void *state)
{
    refine_state *rs = (refine_state *)state;
    (void)ctx;
    if (rs->acc_tex[0]) glDeleteTextures(2, rs->acc_tex);
    if (rs->acc_fbo[0]) glDeleteFramebuffers(2, rs->acc_fbo);
    if (rs->copy_tex) glDeleteTextures(1, &rs->copy_tex);
    if (rs->copy_fbo) glDeleteFramebuffers(1, &rs->copy_fbo);
    if (rs->prog) glDeleteProgram(rs->prog);
    if (rs->vao) glDeleteVertexArrays(1, &rs->vao);
}

/* Before any stage draws: restart on a change, and move this sample's view. */
static void plan(snell__frame *f, void *state)
{
    refine_state *rs = (refine_state *)state;
    uint64_t k[CAUSES];
    int i;
    double o[2];
    rs->sample = -1;
    if (!rs->max) return;
    if (!rs->float_target) {
        snell__why(f->s->refine_reason, sizeof f->s->refine_reason,
                   "off: no float colour target (GL_EXT_color_buffer_float) to keep the mean in");
        return;
    }
    keys(f, k);
    k[CAUSE_METHOD] = rs->key[CAUSE_METHOD]; /* judged after the glass stage (run) */
    for (i = 0; i < CAUSES && rs->started && k[i] == rs->key[i]; i++) {}
    if (i < CAUSES) {
        rs->count = 0;
        rs->cause = rs->started ? i : -1;
    }
    memcpy(rs->key, k, sizeof k);
    rs->started = 1;
    if (rs->count >= rs->max) return; /* the mean is complete: kept as it is */
    rs->sample = rs->count;
    offset(rs->sample, o);
    jitter(&f->sc->view, o);
}

static int wanted(const snell__frame *f, const void *state)
{
    const refine_state *rs = (const refine_state *)state;
    (void)f;
    return rs->max && rs->float_target;
}

static void draw(const refine_state *rs, unsigned fbo, unsigned acc, float weight, int w, int h)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glUniform1f(rs->u_weight, weight);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, acc);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

/* After the resolves: the frame copied, added to the mean (weight 1/n),
 * and the mean written over the image read back. */
static snell_status run(snell__frame *f, void *state)
{
    refine_state *rs = (refine_state *)state;
    const snell__services *sv = f->sv;
    int w = sv->out_width, h = sv->out_height;
    unsigned out = sv->read_fbo ? sv->read_fbo : sv->fbo;
    uint64_t drawn = drawn_key(f);
    if (drawn != rs->key[CAUSE_METHOD]) {
        if (rs->count > 0) rs->cause = CAUSE_METHOD;
        rs->count = 0;
        rs->key[CAUSE_METHOD] = drawn;
    }
    if (rs->sample >= 0 || rs->count == 0) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, out);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, rs->copy_fbo);
        glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glUseProgram(rs->prog);
    glUniform1i(rs->u_frame, 0);
    glUniform1i(rs->u_acc, 1);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, rs->copy_tex);
    glBindVertexArray(rs->vao);
    if (rs->sample >= 0 || rs->count == 0) {
        rs->count++;
        draw(rs, rs->acc_fbo[!rs->cur], rs->acc_tex[rs->cur], 1.0f / (float)rs->count, w, h);
        rs->cur = !rs->cur;
        f->s->passes++;
    }
    draw(rs, out, rs->acc_tex[rs->cur], 0.0f, w, h);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, 0);
    f->s->passes++;
    f->s->refine_samples = rs->count;
    if (rs->cause < 0)
        snell__why(f->s->refine_reason, sizeof f->s->refine_reason, "%d of %d samples since the first frame",
                   rs->count, rs->max);
    else
        snell__why(f->s->refine_reason, sizeof f->s->refine_reason, "%d of %d samples since a change of %s",
                   rs->count, rs->max, g_cause[rs->cause]);
    return SNELL_OK;
}

/* The kernel hook: exact with inner_fresnel follows its exits' reflections
 * at random (common/refine.glsl), seeded by the sample. Asked before the
 * object's method is chosen: the material's option decides (another
 * method's program ignores the define). */
static unsigned variant(const snell__frame *f, const void *state, const snell__object *o)
{
    (void)f;
    return ((const refine_state *)state)->sample >= 0 &&
           o->glass->material.exact.inner_fresnel == SNELL_INNER_FRESNEL_ON;
}

static const char *hook_defines(unsigned bits)
{
    (void)bits;
    return "#define SNELL_REFINE 1\n";
}

static const char *const g_uniforms[] = {"u_refine_seed"};

static void hook_uniforms(const snell__glass_program *g, const int *locs, const void *state, const snell__view *v,
                          const snell__object *o)
{
    (void)g, (void)v, (void)o;
    if (locs[0] >= 0) glUniform1ui(locs[0], (GLuint)((const refine_state *)state)->sample);
}

static const snell__kernel_hook g_hook = {
    .variant_bits = 1,
    .defines = hook_defines,
    .uniform_names = g_uniforms,
    .uniform_count = 1,
    .uniforms = hook_uniforms,
};

const snell__stage snell__stage_refine = {
    .name = "refine",
    .state_size = sizeof(refine_state),
    .validate_renderer = validate_renderer,
    .create = create,
    .destroy = destroy,
    .plan = plan,
    .wanted = wanted,
    .run = run,
    .kernel_variant = variant,
    .kernel = &g_hook,
};
