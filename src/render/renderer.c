/* renderer.c — the frame (DESIGN.md "frame"): resolve the scene
 * (scene.c), draw the opaque objects (composite.c), then each glass object
 * back to front with its method (methods/): prepare its resources (cached,
 * prepared.c), update its dynamic environment if it sees opaque objects
 * (env_dynamic.c) and the frame has no scene layers (layers.c: every object
 * peeled together, which the kernels' exit rays march through when the
 * frame has several objects), draw; the background last where nothing was drawn. Into
 * the renderer's offscreen target or the bound framebuffer. After the first
 * frame with given meshes and settings a frame allocates nothing. */
#include "render/renderer.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "core/pack.h"
#include "core/program.h"
#include "core/platform.h"
#include "render/camera.h"
#include "render/env.h"
#include "render/gbuffer.h"

#include <math.h>
#include <string.h>

#define MAX_RENDER_SIZE 16384

static snell_status make_target(snell_renderer *r)
{
    GLenum status;
    glGenFramebuffers(1, &r->fbo);
    glGenRenderbuffers(1, &r->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, r->depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, r->width, r->height);
    if (r->ssaa.factor > 1) { /* the large colour texture the resolve reads */
        glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->ssaa.frame_tex, 0);
    } else if (r->msaa > 1) { /* multisampled colour and depth, resolved by a blit after the frame */
        glBindRenderbuffer(GL_RENDERBUFFER, r->depth_rb);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, r->msaa, GL_DEPTH_COMPONENT24, r->width, r->height);
        glGenRenderbuffers(1, &r->color_rb);
        glBindRenderbuffer(GL_RENDERBUFFER, r->color_rb);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, r->msaa, GL_RGBA8, r->width, r->height);
        glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->color_rb);
        glGenRenderbuffers(1, &r->msaa_rb);
        glBindRenderbuffer(GL_RENDERBUFFER, r->msaa_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, r->width, r->height);
        glGenFramebuffers(1, &r->msaa_fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, r->msaa_fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->msaa_rb);
        status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            return snell__fail(r->ctx, SNELL_E_GL, "MSAA resolve %dx%d framebuffer incomplete (0x%x)", r->width,
                               r->height, (unsigned)status);
        glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    } else {
        glGenRenderbuffers(1, &r->color_rb);
        glBindRenderbuffer(GL_RENDERBUFFER, r->color_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, r->out == SNELL__OUT_DIR_FLOAT ? GL_RGBA32F : GL_RGBA8, r->width,
                              r->height);
        glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->color_rb);
    }
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
    snell_status st = snell__ssaa_create(r->ctx, &r->ssaa, r->ssaa.factor, r->out_width, r->out_height);
    if (st == SNELL_OK && r->target == SNELL_TARGET_OFFSCREEN) st = make_target(r);
    if (st == SNELL_OK && r->out != SNELL__OUT_COLOR) {
        size_t n = (size_t)r->width * (size_t)r->height;
        r->readback = (float *)snell__calloc(&r->ctx->alloc, n, 4 * sizeof(float));
        r->readback8 = (uint8_t *)snell__calloc(&r->ctx->alloc, n, 4);
        if (!r->readback || !r->readback8) st = snell__fail(r->ctx, SNELL_E_NOMEM, "out of memory for readback");
    }
    /* The background program of the output kind: shader errors surface here,
     * not in the first frame. Methods are made on first use. */
    if (st == SNELL_OK) st = snell__composite_prepare(r->ctx, &r->comp, r->out);
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
    if ((st = snell__ctx_check_current(ctx, "snell_renderer_create")) != SNELL_OK) return st;
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
    if (d.ssaa < 0 || d.ssaa > SNELL_MAX_SSAA)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "ssaa %d outside 0..%d", d.ssaa, SNELL_MAX_SSAA);
    if (d.ssaa > 1 && (d.target != SNELL_TARGET_OFFSCREEN || d.output != SNELL_OUTPUT_COLOR))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "ssaa %d needs an offscreen colour renderer", d.ssaa);
    if (d.msaa < 0 || (d.msaa > 1 && (d.target != SNELL_TARGET_OFFSCREEN || d.output != SNELL_OUTPUT_COLOR)))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "msaa %d needs an offscreen colour renderer (0 or 1 = off)",
                           d.msaa);
    if (d.msaa > 1 && d.ssaa > 1)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "msaa %d and ssaa %d: one antialiasing at a time", d.msaa,
                           d.ssaa);
    if (d.msaa > 1) {
        GLint max_samples = 0;
        glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
        if (d.msaa > max_samples)
            return snell__fail(ctx, SNELL_E_UNSUPPORTED, "msaa %d: this GL has at most %d samples", d.msaa,
                               (int)max_samples);
    }
    if (d.ssaa > 1 && (d.width * d.ssaa > max_rb || d.height * d.ssaa > max_rb))
        return snell__fail(ctx, SNELL_E_LIMIT, "render size %dx%d with ssaa %d exceeds %d pixels a side", d.width,
                           d.height, d.ssaa, max_rb);
    r = (snell_renderer *)snell__calloc(&ctx->alloc, 1, sizeof *r);
    if (!r) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    r->ctx = ctx;
    r->layers.last.count = -1; /* no layers peeled yet */
    r->ssaa.factor = d.ssaa > 1 ? d.ssaa : 1;
    r->out_width = d.width;
    r->out_height = d.height;
    r->msaa = d.msaa > 1 ? d.msaa : 0;
    r->width = d.width * r->ssaa.factor;
    r->height = d.height * r->ssaa.factor;
    r->target = d.target;
    if ((unsigned)d.shading > SNELL_SHADING_SCREEN) {
        snell__free(&ctx->alloc, r);
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "unknown shading %d", (int)d.shading);
    }
    r->shading = d.shading;
    if ((unsigned)d.env_lookup > SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT) {
        snell__free(&ctx->alloc, r);
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "unknown env_lookup %d", (int)d.env_lookup);
    }
    r->env_lookup = d.env_lookup;
    r->device = snell__device_class_of(snell_ctx_gl_renderer(ctx));
    r->out = d.output == SNELL_OUTPUT_COLOR ? SNELL__OUT_COLOR
             : d.output == SNELL_OUTPUT_EXIT_DIRECTION && snell_ctx_has_gl_extension(ctx, "GL_EXT_color_buffer_float")
                 ? SNELL__OUT_DIR_FLOAT
                 : SNELL__OUT_DIR_PACKED;
    snell__ctx_retain(ctx); /* from here on released by snell_renderer_destroy */
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
    snell_ctx *ctx;
    snell__gl_scope sc;
    int m;
    if (!r) return;
    /* Its GL objects are deleted in its context, made current for the moment
     * if need be; after snell_ctx_destroy they are gone with it and the GL
     * calls below reach no context (snell__gl_scope_enter). */
    snell__gl_scope_enter(r->ctx, &sc);
    snell__prepared_destroy(r->ctx, &r->prepared);
    snell__water_programs_destroy(&r->water);
    for (m = 0; m < SNELL_METHOD_COUNT_; m++)
        if (r->method_state[m]) snell__method_get((snell_method)m)->destroy(r->ctx, r->method_state[m]);
    snell__env_dynamic_destroy(r->ctx, &r->dyn);
    snell__paraboloid_gen_destroy(&r->dp);
    snell__composite_destroy(&r->comp);
    snell__gbuffer_destroy(&r->gbuffer);
    snell__gbuffer_destroy(&r->backfaces);
    snell__layers_destroy(&r->layers);
    snell__ssaa_destroy(&r->ssaa);
    if (r->msaa_fbo) glDeleteFramebuffers(1, &r->msaa_fbo);
    if (r->msaa_rb) glDeleteRenderbuffers(1, &r->msaa_rb);
    if (r->fbo) glDeleteFramebuffers(1, &r->fbo);
    if (r->color_rb) glDeleteRenderbuffers(1, &r->color_rb);
    if (r->depth_rb) glDeleteRenderbuffers(1, &r->depth_rb);
    snell__gl_scope_leave(&sc);
    ctx = r->ctx;
    snell__free(&ctx->alloc, r->readback);
    snell__free(&ctx->alloc, r->readback8);
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
        snell_status st = m->create(r->ctx, r->out, &r->method_state[id]);
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

int snell__renderer_env_paraboloid(const snell_renderer *r, int dynamic)
{
    (void)dynamic;
    return r->env_lookup == SNELL_ENV_LOOKUP_DUAL_PARABOLOID || r->env_lookup == SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT;
}

/* Logs a method warning once per (object slot, mesh version, method). */
static void warn_once(snell_renderer *r, const snell__object *o, const snell_object_stats *st)
{
    unsigned key = o->mesh->version * 16u + (unsigned)st->method_used;
    if (r->warned[o->index] == key) return;
    r->warned[o->index] = key;
    snell__log(r->ctx, SNELL_LOG_WARN, "glass %d: %s %s", o->index, snell_method_str(st->method_used), st->reason);
}

/* Where an object is shaded (snell_shading): AUTO compares its projected
 * pixels per front triangle with the threshold for this device and method. */
static void choose_shading(snell_renderer *r, snell__object *o, snell_object_stats *st)
{
    snell__object_project(&r->scene.view, o);
    st->pixels_per_triangle = o->pixels_per_triangle;
    float threshold = snell__screen_threshold(r->device, r->object_method[o->index]);
    /* With MSAA, AUTO draws glass forward: the screen-space stage shades
     * whole pixels from a single-sample G-buffer, so its silhouettes would
     * stay aliased. */
    int screen = r->shading == SNELL_SHADING_SCREEN || r->object_method[o->index]->screen_space_only ||
                 (r->shading == SNELL_SHADING_AUTO && !r->msaa && st->pixels_per_triangle < threshold);
    /* An offscreen target's depth buffer is the renderer's own, so the
     * G-buffer pass can write it; a host's framebuffer, or a multisampled
     * one, gets gl_FragDepth. */
    o->screen_space = !screen ? 0 : r->target == SNELL_TARGET_OFFSCREEN && !r->msaa ? SNELL__SCREEN_SHARED_DEPTH
                                                                                      : SNELL__SCREEN_WRITES_DEPTH;
    o->gid = o->index + 1;
    st->screen_space = screen;
}

/* Everything an object needs before any glass is drawn: its method, its
 * mesh on the GPU, its prepared resources and dynamic environment (passes
 * of their own), and where it is shaded. */
static snell_status set_up_glass(snell_renderer *r, const snell_frame_desc *fd, snell__object *o,
                                 snell_object_stats *st)
{
    void *state = NULL;
    int dynamic = fd->opaque_count > 0 && !o->beyond; /* sees them through a dynamic environment */
    snell_status s;
    o->water = !fd->water ? 0 : fd->water->d.sim == SNELL_WATER_SIM_GPU ? 2 : 1; /* its exit rays meet the water */
    st->sees_water = o->water != 0;
    o->env_paraboloid = snell__renderer_env_paraboloid(r, dynamic);
    st->env_paraboloid = o->env_paraboloid;
    s = snell__scene_choose(r->ctx, o, method_state, r, &r->object_method[o->index], &state, st);
    if (s != SNELL_OK) return s;
    r->object_state[o->index] = state;
    if (st->warning) warn_once(r, o, st);
    if ((s = snell__mesh_upload(o->mesh)) != SNELL_OK) return s;
    if ((s = snell__prepared_get(r->ctx, &r->prepared, r->object_method[o->index], state, o, st)) != SNELL_OK) return s;
    if (r->object_method[o->index]->vertex_array && o->prepared)
        o->vao = r->object_method[o->index]->vertex_array(o->prepared);
    o->env_texture = fd->env->texture;
    if (fd->opaque_count > 0 && o->beyond)
        st->skipped |= SNELL_SKIP_DYNAMIC_ENV; /* its exit rays meet them in the scene layers */
    if (dynamic) {
        /* The glass sees the opaque objects through its dynamic environment. */
        s = snell__env_dynamic_update(r->ctx, &r->dyn, &r->comp, o->index, fd->env, fd->opaque, fd->opaque_count,
                                      o->bsphere, o->bsphere[3], fd->dynamic_env_size,
                                      o->env_paraboloid ? &r->dp : NULL,
                                      r->env_lookup == SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT, &o->env_texture, st);
        if (s != SNELL_OK) return s;
    } else if (o->env_paraboloid) {
        if ((s = snell__env_paraboloid(r->ctx, &r->dp, fd->env, &o->env_texture)) != SNELL_OK) return s;
    }
    choose_shading(r, o, st);
    return SNELL_OK;
}

static snell_status draw_glass(snell_renderer *r, snell__object *o, snell_object_stats *st)
{
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(o->env_paraboloid ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_CUBE_MAP, o->env_texture);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    return r->object_method[o->index]->draw(r->ctx, r->object_state[o->index], &r->scene.view, o, st);
}

/* Whether the frame needs the scene layers (snell_frame_desc.scene_layers):
 * only where a glass object's exit ray, or the water's rays, have something
 * other than the environment and the container to meet. Marks the objects
 * whose kernels march them and lists the glass objects peeled in
 * r->layer_list; returns how many, or -1 for no layers. */
static int choose_scene_layers(snell_renderer *r, const snell_frame_desc *fd, snell_frame_stats *s)
{
    snell__scene *sc = &r->scene;
    int i, n = 0;
    int solid = 0;
    for (i = 0; i < sc->drawn; i++) {
        snell__object *o = &sc->obj[sc->order[i]];
        r->layer_list[n++] = o;
        solid += o->glass->material.thickness <= 0.0f;
    }
    if (fd->scene_layers < 0) {
        snell__why(s->scene_layers_reason, sizeof s->scene_layers_reason, "off (scene_layers -1)");
        return -1;
    }
    if (n == 0 || (n == 1 && fd->opaque_count == 0 && !fd->water)) {
        snell__why(s->scene_layers_reason, sizeof s->scene_layers_reason,
                   "not needed: %s", n == 0 ? "no glass object drawn" : "one glass object and nothing else");
        return -1;
    }
    /* With water, every glass object's kernel reads them too: its exit rays
     * leaving under the water are bent for the water's index with the
     * normal the layers hold (common/beyond.glsl). */
    for (i = 0; i < n; i++) r->layer_list[i]->beyond = 1;
    if (n == 1 && fd->opaque_count == 0) {
        snell__why(s->scene_layers_reason, sizeof s->scene_layers_reason, "one glass object in a frame with water: "
                   "the water's rays meet it, its rays leave into the water");
        return n;
    }
    snell__why(s->scene_layers_reason, sizeof s->scene_layers_reason, "%d glass (%d solid, %d thin walls) and %d opaque "
               "objects%s: exit rays meet the others", n, solid, n - solid, fd->opaque_count,
               fd->water ? " and water" : "");
    return n;
}

static snell_status validate_frame(snell_renderer *r, const snell_frame_desc *fd)
{
    snell_status st = snell__ctx_check_current(r->ctx, "snell_render");
    if (st != SNELL_OK) return st;
    st = snell__camera_validate(r->ctx, &fd->camera, (float)r->width / (float)r->height, "snell_render");
    if (st != SNELL_OK) return st;
    if (!fd->env || !fd->env->texture)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "frame needs an environment created with a context");
    if (fd->env->ctx && fd->env->ctx != r->ctx)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "the environment belongs to another context");
    if (fd->dynamic_env_size != 0 && (fd->dynamic_env_size < 16 || fd->dynamic_env_size > 2048))
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "dynamic_env_size %d outside 16..2048", fd->dynamic_env_size);
    if (fd->water && !SNELL_WITH_WATER)
        return snell__fail(r->ctx, SNELL_E_UNSUPPORTED, "frame has water: built without SNELL_WITH_WATER");
    if (fd->water && fd->water->ctx != r->ctx)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "the water belongs to another context (or to none)");
    if (fd->scene_layers < -1 || fd->scene_layers == 1 || fd->scene_layers > SNELL_MAX_SCENE_LAYERS)
        return snell__fail(r->ctx, SNELL_E_INVALID_ARG, "scene_layers %d: -1 (off), 0 (auto) or 2..%d",
                           fd->scene_layers, SNELL_MAX_SCENE_LAYERS);
    return snell__opaque_validate(r->ctx, fd->opaque, fd->opaque_count);
}

static void begin_frame_state(snell_renderer *r)
{
    if (r->target == SNELL_TARGET_OFFSCREEN) glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glViewport(0, 0, r->width, r->height);
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
    glClearDepthf(1.0f);
    glClear(GL_DEPTH_BUFFER_BIT);
}

snell_status snell_render(snell_renderer *r, const snell_frame_desc *fd, snell_frame_stats *stats)
{
    snell_frame_stats *s;
    snell__scene *sc;
    snell_glstate saved;
    snell_status st;
    int external, i, n_screen = 0, n_back = 0, band = 0, n_layers = -1;
    double t0 = snell__now_ms();
    if (!r || !fd) return snell__fail(r ? r->ctx : NULL, SNELL_E_INVALID_ARG, "snell_render: renderer and frame required");
    s = &r->stats;
    sc = &r->scene;
    memset(s, 0, sizeof *s);
    st = validate_frame(r, fd);
    if (st == SNELL_OK) st = snell__scene_build(r->ctx, fd, r->width, r->height, r->out, sc, s);
    if (st != SNELL_OK) return st;
    sc->view.water = fd->water;
    external = r->ctx->backend == SNELL_BACKEND_EXTERNAL;
    if (external) snell__glstate_save(&saved);
    begin_frame_state(r);
    snell__prepared_frame(&r->prepared);

    st = snell__composite_opaque(r->ctx, &r->comp, r->out, fd->opaque, fd->opaque_count,
                                 (const float *)sc->view.view_proj, sc->view.eye);
    if (fd->opaque_count > 0) {
        s->opaque_drawn = fd->opaque_count;
        s->passes++;
    }
    if (st == SNELL_OK) n_layers = choose_scene_layers(r, fd, s);
    /* Glass: the objects shaded in screen space share one G-buffer pass,
     * which leaves each pixel the nearest of their surfaces, then run their
     * kernels (in any order: they cover disjoint pixels); then the forward
     * ones back to front (Franke), each depth-tested against all of those. */
    for (i = 0; i < sc->drawn && st == SNELL_OK; i++) {
        int k = sc->order[i];
        st = set_up_glass(r, fd, &sc->obj[k], &s->glass[k]);
        if (st == SNELL_OK && sc->obj[k].screen_space) r->screen_list[n_screen++] = &sc->obj[k];
        if (st == SNELL_OK && r->object_method[k]->needs_back_faces) {
            const snell__method *m = r->object_method[k];
            snell__object *o = &sc->obj[k];
            o->back_coarse = m->back_detail && m->back_detail(o->glass) == SNELL_BACK_DETAIL_AUTO &&
                             o->pixels_per_triangle < SNELL__BACK_COARSE_PPT;
            o->back_guard = o->crosses_edge && m->back_guard_percent && m->back_guard_percent(o->glass) > 0
                                ? (m->back_guard_percent(o->glass) * r->height + 99) / 100
                                : 0;
            if (o->back_guard > band) band = o->back_guard;
            r->back_list[n_back++] = o;
        }
    }
    /* The scene layers: every solid glass object drawn and every opaque one,
     * peeled together once, before any kernel reads them. */
    if (st == SNELL_OK && n_layers >= 0) {
        int peels = 0;
        st = snell__layers_draw(r->ctx, &r->layers, &sc->view, r->layer_list, n_layers, fd->opaque,
                                fd->opaque_count, fd->scene_layers > 0 ? fd->scene_layers : SNELL_DEFAULT_SCENE_LAYERS,
                                &peels, &s->scene_layers_reused);
        s->scene_layer_passes = peels;
        s->scene_layers = sc->view.layers.count;
        s->passes += peels;
    }
    /* The water and its container are opaque to what follows: glass behind
     * them is depth-tested away, glass in front is drawn over them; the
     * glass kernels drawn after see the water along their exit rays
     * (common/water.glsl), the water sees the glass and opaque objects in it
     * through the scene layers. */
    if (st == SNELL_OK && fd->water) {
        /* Without layers (no glass), opaque objects in the water are
         * searched for in a copy of what the opaque pass drew: an offscreen
         * single-sample colour target (a host's framebuffer or a
         * multisampled one cannot be copied with its depth format known;
         * exit directions need no colour). Measured against peeling them
         * into layers for the water alone: 74 against 175 ms and 38.7
         * against 36.1 dB (snell-bench --water --size 256, two spheres). */
        int layers = n_layers >= 0;
        int objects = !layers && fd->opaque_count > 0 && r->target == SNELL_TARGET_OFFSCREEN && !r->msaa &&
                      r->out == SNELL__OUT_COLOR;
        if (objects) {
            st = snell__water_copy_scene(r->ctx, &r->water, r->fbo, r->width, r->height);
            glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
        }
        unsigned env_tex = fd->env->texture;
        int paraboloid = snell__renderer_env_paraboloid(r, 0); /* the water sees the static environment */
        if (st == SNELL_OK && paraboloid) st = snell__env_paraboloid(r->ctx, &r->dp, fd->env, &env_tex);
        if (st == SNELL_OK)
            st = snell__water_draw(r->ctx, &r->water, r->out, fd->water, &sc->view, env_tex, paraboloid, fd->opaque,
                                   objects ? fd->opaque_count : 0, layers, s);
        s->water_objects = objects || layers; /* layers: at least one glass object drawn */
        s->water_layers = layers;
    }
    /* One back-face pass for every object whose method reads back faces;
     * none in frames without such an object. */
    if (st == SNELL_OK && n_back > 0) {
        st = snell__gbuffer_draw_back(r->ctx, &r->backfaces, &sc->view, r->back_list, n_back, band,
                                      &sc->view.back, s->glass);
        s->back_face_pass = 1;
        s->back_face_guard = band;
    }
    if (st == SNELL_OK && n_screen > 0)
        st = snell__gbuffer_draw(r->ctx, &r->gbuffer, &sc->view, r->screen_list, n_screen,
                                 r->target == SNELL_TARGET_OFFSCREEN && !r->msaa ? r->depth_rb : 0, s->glass);
    for (i = 0; i < n_screen && st == SNELL_OK; i++) st = draw_glass(r, r->screen_list[i], &s->glass[r->screen_list[i]->index]);
    for (i = 0; i < sc->drawn && st == SNELL_OK; i++) {
        int k = sc->order[i];
        if (!sc->obj[k].screen_space) st = draw_glass(r, &sc->obj[k], &s->glass[k]);
    }
    /* The background goes last, where the depth buffer is still clear, so
     * pixels covered by glass or opaque objects are never shaded twice.
     * Exit-direction output always needs it (misses = the view ray). */
    if (st == SNELL_OK && (fd->draw_background >= 0 || r->out != SNELL__OUT_COLOR)) {
        mat4 rot, vp;
        glm_mat4_copy(sc->view.view, rot);
        rot[3][0] = rot[3][1] = rot[3][2] = 0.0f;
        glm_mat4_mul(sc->view.proj, rot, vp);
        int paraboloid = snell__renderer_env_paraboloid(r, 0);
        unsigned tex = fd->env->texture;
        if (paraboloid) st = snell__env_paraboloid(r->ctx, &r->dp, fd->env, &tex);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(paraboloid ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_CUBE_MAP, tex);
        if (st == SNELL_OK) st = snell__composite_background_lookup(r->ctx, &r->comp, r->out, paraboloid, (const float *)vp);
        s->background_drawn = 1;
        s->background_paraboloid = paraboloid;
    }
    if (st == SNELL_OK && r->ssaa.factor > 1) {
        snell__ssaa_resolve(&r->ssaa, r->out_width, r->out_height);
        s->passes++;
    }
    if (st == SNELL_OK && r->msaa) { /* resolve: the samples' mean per pixel */
        glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r->msaa_fbo);
        glBlitFramebuffer(0, 0, r->width, r->height, 0, 0, r->width, r->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        s->passes++;
    }
    /* Leave no program of ours current: one deleted while current (renderer
     * destroyed) lives on until replaced, and a later pass that saved and
     * restores its name would then name a freed program. */
    glUseProgram(0);
    glBindVertexArray(0);
    if (external) snell__glstate_restore(&saved);
    if (st == SNELL_OK && glGetError() != GL_NO_ERROR) st = snell__fail(r->ctx, SNELL_E_GL, "GL error during the frame");
    for (i = 0; i < sc->count; i++) s->passes += s->glass[i].passes;
    s->passes += s->background_drawn;
    s->fragment_mediump = snell__ctx_fragment_mediump(r->ctx);
    s->cpu_ms = snell__now_ms() - t0;
    if (stats) memcpy(stats, s, sizeof *s);
    return st;
}

/* Reads the offscreen colour buffer (bottom row first, as GL stores it). */
static snell_status read_target(snell_renderer *r, GLenum type, void *pixels)
{
    GLint prev_fbo = 0;
    snell__pixel_store pack;
    snell_status st = snell__ctx_check_current(r->ctx, "snell_renderer_read");
    if (st != SNELL_OK) return st;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev_fbo);
    /* Into client memory, tightly packed, whatever pixel buffer or pack state the host has set. */
    snell__pixel_pack_begin(&pack, 1);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->ssaa.factor > 1 ? r->ssaa.resolve_fbo : r->msaa ? r->msaa_fbo : r->fbo);
    glReadPixels(0, 0, r->out_width, r->out_height, GL_RGBA, type, pixels);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)prev_fbo);
    snell__pixel_pack_end(&pack);
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
    row = (size_t)r->out_width * 4;
    for (y = 0; y < r->out_height / 2; y++) {
        uint8_t *a = pixels + (size_t)y * row, *b = pixels + (size_t)(r->out_height - 1 - y) * row;
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
