/* SPDX-License-Identifier: MIT */
/* renderer.c — the renderer object (its target, method states, caches) and
 * snell_render: validate the frame, resolve the scene (scene.c), then run
 * the stage table (stages.c: opaque objects, glass set-up, scene layers,
 * water, back faces, G-buffer, kernels, background, resolves) into the
 * renderer's offscreen target or the bound framebuffer, restoring a host's
 * GL state. After the first frame with given meshes and settings a frame
 * allocates nothing. */
#include "render/renderer.h"
#include "render/stages.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "core/pack.h"
#include "core/program.h"
#include "core/platform.h"
#include "frame/camera.h"
#include "frame/env.h"
#include "frame/glass_program.h"
#include "render/gbuffer.h"

#include <math.h>
#include <string.h>

#define MAX_RENDER_SIZE 16384

static snell_status method_state(void *user, const snell__method *m, void **state);

/* The offscreen target at the frame's size: colour in the texture a stage
 * made (ssaa), else a renderbuffer of the stages' samples (msaa) or one. */
static snell_status make_target(snell_renderer *r)
{
    snell__services *sv = &r->sv;
    GLenum status;
    glGenFramebuffers(1, &sv->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, sv->fbo);
    glGenRenderbuffers(1, &sv->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, sv->depth_rb);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, sv->samples, GL_DEPTH_COMPONENT24, sv->width, sv->height);
    if (sv->color_texture) {
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, sv->color_texture, 0);
    } else {
        glGenRenderbuffers(1, &r->color_rb);
        glBindRenderbuffer(GL_RENDERBUFFER, r->color_rb);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, sv->samples,
                                         sv->out == SNELL__OUT_DIR_FLOAT ? GL_RGBA32F : GL_RGBA8, sv->width,
                                         sv->height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->color_rb);
    }
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, sv->depth_rb);
    status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return snell__fail(r->ctx, SNELL_E_GL, "offscreen %dx%d framebuffer incomplete (0x%x)", sv->width,
                           sv->height, (unsigned)status);
    return glGetError() == GL_NO_ERROR ? SNELL_OK
                                       : snell__fail(r->ctx, SNELL_E_GL, "GL error creating a %dx%d target",
                                                     sv->width, sv->height);
}

/* Each stage's slot, zeroed, then as its create() sets it (and the target
 * with it): made once, so a frame allocates nothing for its stages. */
static snell_status create_stage_states(snell_renderer *r, const snell_renderer_desc *d)
{
    int i;
    snell_status st;
    r->sv.programs = (snell__program_cache *)snell__calloc(&r->ctx->alloc, 1, sizeof *r->sv.programs);
    if (!r->sv.programs) return snell__fail(r->ctx, SNELL_E_NOMEM, "out of memory for the program cache");
    for (i = 0; i < snell__stage_count; i++) {
        const snell__stage *sg = snell__stages[i];
        if (sg->state_size) {
            r->stage_state[i] = snell__calloc(&r->ctx->alloc, 1, sg->state_size);
            if (!r->stage_state[i])
                return snell__fail(r->ctx, SNELL_E_NOMEM, "out of memory for the %s stage", sg->name);
        }
        if (sg->create && (st = sg->create(&r->sv, d, r->stage_state[i])) != SNELL_OK) return st;
    }
    return snell__program_cache_hooks(r->ctx, r->sv.programs, snell__stages, r->stage_state, snell__stage_count);
}

static snell_status create_resources(snell_renderer *r)
{
    snell_status st = SNELL_OK;
    if (r->sv.target == SNELL_TARGET_OFFSCREEN) st = make_target(r);
    if (st == SNELL_OK && r->sv.out != SNELL__OUT_COLOR) {
        size_t n = (size_t)r->sv.width * (size_t)r->sv.height;
        r->readback = (float *)snell__calloc(&r->ctx->alloc, n, 4 * sizeof(float));
        r->readback8 = (uint8_t *)snell__calloc(&r->ctx->alloc, n, 4);
        if (!r->readback || !r->readback8) st = snell__fail(r->ctx, SNELL_E_NOMEM, "out of memory for readback");
    }
    /* The background program of the output kind: shader errors surface here,
     * not in the first frame. Methods are made on first use. */
    if (st == SNELL_OK) st = snell__composite_prepare(r->ctx, &r->comp, r->sv.out);
    return st;
}

/* Its targets are renderbuffers and textures: past either limit, the
 * profile's if lower (core/profile.c), the device cannot make them. */
static snell_status target_limit(snell_ctx *ctx, int size, const char *what)
{
    snell_status st = snell__ctx_limit(ctx, SNELL__LIM_TEXTURE, size, what);
    return st != SNELL_OK ? st : snell__ctx_limit(ctx, SNELL__LIM_RENDERBUFFER, size, what);
}

snell_status snell_renderer_create(snell_ctx *ctx, const snell_renderer_desc *desc, snell_renderer **out)
{
    snell_renderer_desc d;
    snell__services shape; /* the target as the stages shape it, before anything is made */
    snell_renderer *r;
    snell_status st;
    snell_glstate saved;
    int i;
    unsigned host_errors;
    if (!ctx || !out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_renderer_create: ctx and out are required");
    *out = NULL;
    if ((st = snell__ctx_check_current(ctx, "snell_renderer_create")) != SNELL_OK) return st;
    snell_renderer_defaults(desc, &d);
    if (d.width < 1 || d.height < 1 || d.width > MAX_RENDER_SIZE || d.height > MAX_RENDER_SIZE)
        return snell__fail(ctx, SNELL_E_LIMIT, "render size %dx%d outside 1..%d", d.width, d.height, MAX_RENDER_SIZE);
    if (d.target == SNELL_TARGET_OFFSCREEN &&
        (st = target_limit(ctx, d.width > d.height ? d.width : d.height, "render size")) != SNELL_OK)
        return st;
    if ((unsigned)d.target > SNELL_TARGET_BOUND_FRAMEBUFFER || (unsigned)d.output > SNELL_OUTPUT_EXIT_DIRECTION_PACKED)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "unknown render target %d or output %d", (int)d.target,
                           (int)d.output);
    if (d.output != SNELL_OUTPUT_COLOR && d.target != SNELL_TARGET_OFFSCREEN)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "exit-direction output needs an offscreen target");
    memset(&shape, 0, sizeof shape);
    shape.ctx = ctx;
    shape.target = d.target;
    shape.out_width = shape.width = d.width;
    shape.out_height = shape.height = d.height;
    for (i = 0; i < snell__stage_count; i++)
        if (snell__stages[i]->validate_renderer && (st = snell__stages[i]->validate_renderer(&shape, &d)) != SNELL_OK)
            return st;
#if !SNELL_WITH_REFINE
    if (d.refine) return snell__fail(ctx, SNELL_E_UNSUPPORTED, "refine: built without SNELL_WITH_REFINE");
#endif
    if (d.target == SNELL_TARGET_OFFSCREEN) {
        /* the targets made now, before any frame: colour and depth (4 + 4 bytes
         * a pixel, 16 + 4 for exit directions) at the frame's size and samples
         * as the stages shaped it, and the resolved image beside them where
         * that differs from the output; a software GL holds them in this process */
        size_t px = (size_t)shape.width * (size_t)shape.height, out_px = (size_t)d.width * (size_t)d.height;
        size_t bytes = px * (d.output == SNELL_OUTPUT_COLOR ? 8u : 20u) * (shape.samples > 1 ? (size_t)shape.samples : 1u) +
                       (px != out_px || shape.samples > 1 ? out_px * 4u : 0u);
        char what[96];
        snprintf(what, sizeof what, "a %dx%d offscreen renderer", d.width, d.height);
        if ((st = snell__budget_check(ctx, bytes, what)) != SNELL_OK) return st;
    }
    r = (snell_renderer *)snell__calloc(&ctx->alloc, 1, sizeof *r);
    if (!r) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    r->ctx = ctx;
    r->sv = shape;
    r->sv.comp = &r->comp, r->sv.dp = &r->dp, r->sv.dyn = &r->dyn, r->sv.prepared = &r->prepared;
    r->sv.method_state = method_state, r->sv.user = r;
    if ((unsigned)d.shading > SNELL_SHADING_SCREEN) {
        snell__free(&ctx->alloc, r);
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "unknown shading %d", (int)d.shading);
    }
    r->sv.shading = d.shading;
    if ((unsigned)d.env_lookup > SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT) {
        snell__free(&ctx->alloc, r);
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "unknown env_lookup %d", (int)d.env_lookup);
    }
    r->sv.env_lookup = d.env_lookup;
    r->premultiplied = d.premultiplied_alpha;
    r->sv.device = snell__device_class_of(snell_ctx_gl_renderer(ctx));
    r->sv.out = d.output == SNELL_OUTPUT_COLOR ? SNELL__OUT_COLOR
             : d.output == SNELL_OUTPUT_EXIT_DIRECTION && snell_ctx_has_gl_extension(ctx, "GL_EXT_color_buffer_float")
                 ? SNELL__OUT_DIR_FLOAT
                 : SNELL__OUT_DIR_PACKED;
    snell__ctx_retain(ctx); /* from here on released by snell_renderer_destroy */
    host_errors = snell__gl_errors_take();
    snell__glstate_save(&saved);
    st = create_stage_states(r, &d);
    if (st == SNELL_OK) st = create_resources(r);
    snell__glstate_restore(&saved);
    if (ctx->backend == SNELL_BACKEND_EXTERNAL) snell__gl_errors_give(host_errors);
    if (st != SNELL_OK) {
        snell_renderer_destroy(r);
        return st;
    }
    *out = r;
    return SNELL_OK;
}

void snell_renderer_destroy(snell_renderer *r)
{
    snell_ctx *ctx;
    snell__gl_scope sc;
    int m;
    if (!r) return;
    /* Its GL objects are deleted in its context, made current for the moment
     * if need be; after snell_ctx_destroy they are gone with it and the GL
     * calls below reach no context (snell__gl_scope_enter). */
    snell__gl_scope_enter(r->ctx, &sc);
    for (m = snell__stage_count - 1; m >= 0; m--)
        if (r->stage_state[m] && snell__stages[m]->destroy) snell__stages[m]->destroy(r->ctx, r->stage_state[m]);
    snell__prepared_destroy(r->ctx, &r->prepared);
    for (m = 0; m < SNELL_METHOD_COUNT_; m++)
        if (r->method_state[m]) snell__method_get((snell_method)m)->destroy(r->ctx, r->method_state[m]);
    if (r->sv.programs) snell__program_cache_destroy(r->sv.programs);
    snell__env_dynamic_destroy(r->ctx, &r->dyn);
    snell__paraboloid_gen_destroy(&r->dp);
    snell__composite_destroy(&r->comp);
    snell__host_depth_destroy(&r->host_depth);
    snell__host_target_destroy(&r->host_target);
    if (r->sv.fbo) glDeleteFramebuffers(1, &r->sv.fbo);
    if (r->color_rb) glDeleteRenderbuffers(1, &r->color_rb);
    if (r->sv.depth_rb) glDeleteRenderbuffers(1, &r->sv.depth_rb);
    snell__gl_scope_leave(&sc);
    ctx = r->ctx;
    snell__free(&ctx->alloc, r->readback);
    snell__free(&ctx->alloc, r->readback8);
    snell__free(&ctx->alloc, r->sv.programs);
    for (m = 0; m < snell__stage_count; m++) snell__free(&ctx->alloc, r->stage_state[m]);
    snell__free(&ctx->alloc, r);
    snell__ctx_release(ctx);
}

/* Methods are created on first use; one that fails (a device that cannot
 * compile its shaders, say) fails alone and is not retried, except after
 * running out of memory. */
static snell_status method_state(void *user, const snell__method *m, void **state)
{
    snell_renderer *r = (snell_renderer *)user;
    int id = (int)m->info->method;
    if (!r->method_state[id] && r->method_status[id] == SNELL_OK) {
        snell_status st = m->create(r->ctx, r->sv.out, r->sv.programs, &r->method_state[id]);
        if (st == SNELL_E_NOMEM) return st;
        if (st != SNELL_OK) {
            r->method_status[id] = st;
            snprintf(r->method_error[id], sizeof r->method_error[id], "%s", snell_last_error(r->ctx));
            snell__log(r->ctx, SNELL_LOG_WARN, "method %s unavailable: %s", m->info->name, r->method_error[id]);
        }
    }
    if (r->method_status[id] != SNELL_OK)
        return snell__fail(r->ctx, r->method_status[id], "method %s unavailable: %s", m->info->name,
                           r->method_error[id]);
    *state = r->method_state[id];
    return SNELL_OK;
}

int snell__env_lookup_paraboloid(snell_env_lookup lookup, int dynamic)
{
    (void)dynamic;
    return lookup == SNELL_ENV_LOOKUP_DUAL_PARABOLOID || lookup == SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT;
}

/* The host cameras whose depth a bound framebuffer's test cannot use: a
 * reversed-Z one's is mapped where host framebuffers are checked
 * (render/host_depth_map.c); an oblique one's is not an affine map of snell's. */
#ifdef SNELL_WITH_HOST_FRAMEBUFFERS
#define UNMAPPED_CAMERAS SNELL__CAMERA_OBLIQUE
#else
#define UNMAPPED_CAMERAS (SNELL__CAMERA_OBLIQUE | SNELL__CAMERA_REVERSED)
#endif

/* The resolved frame fd; its camera as given (snell__camera_validate
 * resolves it itself, and names a plane derived from the distance as such). */
static snell_status validate_frame(snell_renderer *r, const snell_frame_desc *fd, const snell_camera *camera)
{
    int i;
    snell_status st = snell__ctx_check_current(r->ctx, "snell_render");
    if (st != SNELL_OK) return st;
    st = snell__camera_validate(r->ctx, camera, (float)r->sv.width / (float)r->sv.height, "snell_render");
    if (st != SNELL_OK) return st;
    if (snell__depth_mode_of(fd->depth, r->sv.target) != SNELL_DEPTH_CLEAR &&
        (snell__camera_standard(camera, 1.0f, NULL, NULL, NULL) & (SNELL__CAMERA_REVERSED | SNELL__CAMERA_OBLIQUE)) &
            (r->sv.target == SNELL_TARGET_OFFSCREEN ? SNELL__CAMERA_OBLIQUE : UNMAPPED_CAMERAS))
        return snell__fail(r->ctx, SNELL_E_UNSUPPORTED, "snell_render: an oblique%s camera with the target's depth "
                           "tested: snell's depth is a standard projection's; use SNELL_DEPTH_CLEAR",
                           UNMAPPED_CAMERAS & SNELL__CAMERA_REVERSED ? " or reversed-Z" : "");
    if (fd->env && fd->env->ctx && fd->env->ctx->destroyed)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG,
                           "the frame's environment went with its context (snell_ctx_destroy): create it again");
#if !SNELL_WITH_PANELS
    if (fd->panel_count)
        return snell__fail(r->ctx, SNELL_E_UNSUPPORTED, "panels: built without SNELL_WITH_PANELS");
#endif
    /* A frame of panels only (snell_frame_desc.panels) looks up no environment. */
    if (!fd->env && !(fd->panel_count > 0 && fd->glass_count == 0 && fd->opaque_count == 0 && !fd->water &&
                      fd->draw_background == SNELL_BACKGROUND_NONE))
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "frame needs an environment created with a context");
    if (fd->env && !fd->env->texture)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "frame needs an environment created with a context");
    if (fd->env && fd->env->ctx && fd->env->ctx != r->ctx)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "the environment belongs to another context");
    if ((fd->env || fd->dynamic_env_size) && (fd->dynamic_env_size < 16 || fd->dynamic_env_size > 2048))
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "dynamic_env_size %d outside 16..2048", fd->dynamic_env_size);
    if ((unsigned)fd->depth > SNELL_DEPTH_TEST_NO_WRITE)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "depth %d is not a snell_depth_mode", (int)fd->depth);
    if (fd->depth == SNELL_DEPTH_TEST_NO_WRITE && r->sv.target == SNELL_TARGET_OFFSCREEN)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "SNELL_DEPTH_TEST_NO_WRITE is for a bound framebuffer: "
                           "the offscreen target's depth is the renderer's own");
    for (i = 0; i < snell__stage_count; i++)
        if (snell__stages[i]->validate && (st = snell__stages[i]->validate(&r->sv, fd)) != SNELL_OK) return st;
    return SNELL_OK;
}

/* The frame's fixed state; the target's depth as the frame's mode asks
 * (render/host_depth.h: never cleared for a bound framebuffer unless asked). */
static snell_status begin_frame_state(snell_renderer *r, const snell_frame_desc *fd)
{
    snell_status st;
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_POLYGON_OFFSET_FILL);
    /* Dithering (on by default) may change the low bits of UNORM8 writes: it
     * would corrupt packed exit directions and make images driver-dependent. */
    glDisable(GL_DITHER);
    snell__glstate_frame_defaults();
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    /* the host's framebuffer checked (and its viewport read) with no scissor or discard on its copies */
    if (r->sv.target == SNELL_TARGET_OFFSCREEN) glBindFramebuffer(GL_FRAMEBUFFER, r->sv.fbo);
    else {
        double map[2];
        const double *mapped = NULL;
#ifdef SNELL_WITH_HOST_FRAMEBUFFERS
        if (snell__depth_mode_of(fd->depth, r->sv.target) != SNELL_DEPTH_CLEAR &&
            snell__camera_depth_map(&fd->camera, (float)r->sv.width / (float)r->sv.height, map))
            mapped = map;
#endif
        (void)map;
        if ((st = snell__host_target_begin(r->ctx, &r->host_target, r->sv.width, r->sv.height, r->premultiplied,
                                           mapped)) != SNELL_OK)
            return st;
    }
    glViewport(0, 0, r->sv.width, r->sv.height);
    return snell__host_depth_begin(r->ctx, &r->host_depth, snell__depth_mode_of(fd->depth, r->sv.target), r->sv.width,
                                   r->sv.height);
}

snell_status snell_render(snell_renderer *r, const snell_frame_desc *fd, snell_frame_stats *stats)
{
    snell__frame f;
    snell_frame_stats *s;
    snell_glstate saved;
    snell__units units;
    snell_status st;
    int external, i;
    unsigned host_errors;
    size_t named = 0;
    double t0 = snell__now_ms();
    if (!r || !fd) return snell__fail(r ? r->ctx : NULL, SNELL_E_INVALID_ARG, "snell_render: renderer and frame required");
    s = &r->stats;
    memset(s, 0, sizeof *s);
    if ((st = snell__ctx_check_current(r->ctx, "snell_render")) != SNELL_OK) return st;
    /* The host's pending GL errors wait outside the frame (core/glstate.h). */
    external = r->ctx->backend == SNELL_BACKEND_EXTERNAL;
    host_errors = snell__gl_errors_take();
    /* The frame resolved once (sokol_gfx's order): its defaults, then each
     * stage's part; then the resolved copy validated, so that a message
     * names the value the frame would use and no stage sees a zero that
     * means a default. */
    snell_frame_defaults(fd, &r->frame);
    for (i = 0; i < snell__stage_count; i++)
        if (snell__stages[i]->resolve) snell__stages[i]->resolve(&r->sv, &r->frame, r->stage_state[i]);
    st = validate_frame(r, &r->frame, &fd->camera);
    fd = &r->frame;
    if (st == SNELL_OK) st = snell__scene_build(r->ctx, fd, r->sv.width, r->sv.height, r->sv.out, &r->scene, s);
    if (st != SNELL_OK) {
        if (external) snell__gl_errors_give(host_errors);
        return st;
    }
    memset(&f, 0, sizeof f);
    f.sv = &r->sv, f.fd = fd, f.s = s, f.sc = &r->scene, f.state = r->stage_state, f.start_ms = t0;
    if (external) snell__glstate_save(&saved);
    snell__units_begin(&units, 0, 1); /* the frame's units: each one's sampler object unbound at its first use */
    st = begin_frame_state(r, fd);
    snell__prepared_frame(&r->prepared);
    /* The stage table in frame order (stages.c): each plans, then runs if this frame wants it. */
    for (i = 0; i < snell__stage_count; i++)
        if (snell__stages[i]->plan) snell__stages[i]->plan(&f, r->stage_state[i]);
    for (i = 0; i < snell__stage_count && st == SNELL_OK; i++) {
        const snell__stage *sg = snell__stages[i];
        if (sg->wanted && !sg->wanted(&f, r->stage_state[i])) continue;
        st = sg->run(&f, r->stage_state[i]);
        named += (size_t)snprintf(s->stages + named, named < sizeof s->stages ? sizeof s->stages - named : 0, "%s%s",
                                  named ? " " : "", sg->name);
    }
    /* Leave no program of ours current: one deleted while current (renderer
     * destroyed) lives on until replaced, and a later pass that saved and
     * restores its name would then name a freed program. */
    glUseProgram(0);
    glBindVertexArray(0);
    if (r->sv.target != SNELL_TARGET_OFFSCREEN) {
        snell_status back = snell__host_depth_end(r->ctx, &r->host_depth);
        if (st == SNELL_OK) st = back;
        back = snell__host_target_end(r->ctx, &r->host_target);
        if (st == SNELL_OK) st = back;
    }
    snell__units_end(&units);
    s->texture_units = snell__units_count(&units);
    if (external) snell__glstate_restore(&saved);
    if (st == SNELL_OK && glGetError() != GL_NO_ERROR) st = snell__fail(r->ctx, SNELL_E_GL, "GL error during the frame");
    for (i = 0; i < snell__stage_count; i++)
        if (snell__stages[i]->frame_end) snell__stages[i]->frame_end(&f, r->stage_state[i], st);
    if (external) snell__gl_errors_give(host_errors);
    for (i = 0; i < r->scene.count; i++) s->passes += s->glass[i].passes;
    s->passes += s->background_drawn;
    s->fragment_mediump = snell__ctx_fragment_mediump(r->ctx);
    s->programs = snell__program_cache_count(r->sv.programs, &s->program_bytes);
    s->programs_built = r->sv.programs->built;
    s->cpu_ms = snell__now_ms() - t0;
    if (stats) memcpy(stats, s, sizeof *s);
    return st;
}

/* The GPU finished what r issued: the stages that wait for it (the budget's clock) are told. */
static void gpu_done(snell_renderer *r)
{
    int i;
    for (i = 0; i < snell__stage_count; i++)
        if (snell__stages[i]->gpu_done) snell__stages[i]->gpu_done(r->stage_state[i]);
}

/* Reads the offscreen colour buffer (bottom row first, as GL stores it). */
static snell_status read_target(snell_renderer *r, GLenum type, void *pixels)
{
    GLint prev_fbo = 0;
    snell__pixel_store pack;
    unsigned host_errors;
    snell_status st = snell__ctx_check_current(r->ctx, "snell_renderer_read");
    if (st != SNELL_OK) return st;
    host_errors = snell__gl_errors_take();
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev_fbo);
    /* Into client memory, tightly packed, whatever pixel buffer or pack state the host has set. */
    snell__pixel_pack_begin(&pack, 1);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->sv.read_fbo ? r->sv.read_fbo : r->sv.fbo);
    glReadPixels(0, 0, r->sv.out_width, r->sv.out_height, GL_RGBA, type, pixels);
    gpu_done(r);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)prev_fbo);
    snell__pixel_pack_end(&pack);
    st = glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(r->ctx, SNELL_E_GL, "glReadPixels failed");
    snell__gl_errors_give(host_errors);
    return st;
}

snell_status snell_renderer_read_rgba(snell_renderer *r, uint8_t *pixels)
{
    int y;
    size_t row;
    snell_status st;
    if (!r || !pixels) return snell__fail(r ? r->ctx : NULL, SNELL_E_INVALID_ARG, "read_rgba: NULL argument");
    if (r->sv.target != SNELL_TARGET_OFFSCREEN || r->sv.out != SNELL__OUT_COLOR)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "read_rgba needs an offscreen colour renderer");
    if ((st = read_target(r, GL_UNSIGNED_BYTE, pixels)) != SNELL_OK) return st;
    /* GL's row 0 is the bottom; flip in place so row 0 is the top. */
    row = (size_t)r->sv.out_width * 4;
    for (y = 0; y < r->sv.out_height / 2; y++) {
        uint8_t *a = pixels + (size_t)y * row, *b = pixels + (size_t)(r->sv.out_height - 1 - y) * row;
        size_t i;
        for (i = 0; i < row; i++) {
            uint8_t t = a[i];
            a[i] = b[i];
            b[i] = t;
        }
    }
    return SNELL_OK;
}

/* The exit-direction target read back into xyz (3 floats a pixel) or into
 * mask (the coverage flag), top row first. */
static snell_status read_output(snell_renderer *r, float *xyz, uint8_t *mask)
{
    int x, y, f = r && r->sv.out == SNELL__OUT_DIR_FLOAT;
    snell_status st;
    if (!r || (!xyz && !mask))
        return snell__fail(r ? r->ctx : NULL, SNELL_E_INVALID_ARG, "read_exit_dirs/coverage: NULL argument");
    if (r->sv.out == SNELL__OUT_COLOR)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "renderer was not created with SNELL_OUTPUT_EXIT_DIRECTION");
    st = f ? read_target(r, GL_FLOAT, r->readback) : read_target(r, GL_UNSIGNED_BYTE, r->readback8);
    if (st != SNELL_OK) return st;
    for (y = 0; y < r->sv.height; y++)
        for (x = 0; x < r->sv.width; x++) {
            size_t src = (size_t)(r->sv.height - 1 - y) * r->sv.width + x, dst = (size_t)y * r->sv.width + x;
            /* output.glsl: alpha 0 where the path met no glass (any other
             * value, exact's fallback mark included, is glass); packed, the
             * low bit of the last byte. */
            if (mask) mask[dst] = (uint8_t)(f ? r->readback[4 * src + 3] != 0.0f : (r->readback8[4 * src + 3] & 1u));
            else if (f) memcpy(xyz + 3 * dst, r->readback + 4 * src, 3 * sizeof(float));
            else (void)snell_unpack_exit_rgba8(r->readback8 + 4 * src, xyz + 3 * dst);
        }
    return SNELL_OK;
}

snell_status snell_renderer_read_exit_dirs(snell_renderer *r, float *xyz)
{
    return read_output(r, xyz, NULL);
}

snell_status snell_renderer_read_coverage(snell_renderer *r, uint8_t *mask)
{
    return read_output(r, NULL, mask);
}

const char *snell_renderer_exit_dir_encoding(const snell_renderer *r)
{
    if (!r || r->sv.out == SNELL__OUT_COLOR) return "none";
    return r->sv.out == SNELL__OUT_DIR_FLOAT ? "float" : "packed-rgba8";
}

void snell_renderer_finish(snell_renderer *r)
{
    glFinish();
    if (r) gpu_done(r);
}
