/* SPDX-License-Identifier: MIT */
/* stages.c — the frame as a table of stages in frame order (frame/stage.h):
 * AUTO by budget's plan -> opaque objects -> caustics (the light's maps, which
 * the glass set-up's dynamic environments light the opaque objects with) ->
 * glass set-up (method, mesh, prepared resources, dynamic
 * environment, shading) -> scene layers -> water -> back faces -> G-buffer
 * -> kernels (an object at a resolution scale through render/glass_scale.c)
 * -> background -> resolves. snell_render (renderer.c) runs the
 * entries a frame wants. A stage that changes what kernels compute adds its
 * kernel hook here too (layers: SNELL_BEYOND; water: SNELL_WATER): a new
 * stage is one entry of g_stages, its own file and shader chunk. */
#include "render/stages.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "frame/beyond.h"
#include "frame/env.h"
#include "frame/glass_program.h"

#include <string.h>

/* Methods are created on first use; one that fails (a device that cannot
 * compile its shaders, say) fails alone and is not retried, except after
 * running out of memory. */
snell_status snell__renderer_method_state(void *user, const snell__method *m, void **state)
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
    float threshold = snell__screen_threshold(r->device, r->object_method[o->index], o->analysis && o->analysis->convex);
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
static snell_status set_up_glass(const snell__frame *f, snell__object *o, snell_object_stats *st)
{
    snell_renderer *r = f->r;
    const snell_frame_desc *fd = f->fd;
    void *state = NULL;
    int beyond = f->n_layers >= 0; /* its exit rays march the scene layers */
    int dynamic = fd->opaque_count > 0 && !beyond; /* sees them through a dynamic environment */
    snell_status s;
    int i;
    o->stage_bits = 0;
    for (i = 0; i < snell__stage_count; i++)
        if (snell__stages[i].kernel_variant) o->stage_bits |= snell__stages[i].kernel_variant(f, o);
    o->env_paraboloid = snell__renderer_env_paraboloid(r, dynamic);
    st->env_paraboloid = o->env_paraboloid;
    s = snell__scene_choose(r->ctx, o, snell__renderer_method_state, r, &r->object_method[o->index], &state, st);
    if (s != SNELL_OK) return s;
    r->object_state[o->index] = state;
    if (st->warning) warn_once(r, o, st);
    if ((s = snell__mesh_upload(o->mesh)) != SNELL_OK) return s;
    if ((s = snell__prepared_get(r->ctx, &r->prepared, r->object_method[o->index], state, o, st)) != SNELL_OK) return s;
    if (r->object_method[o->index]->vertex_array && o->prepared)
        o->vao = r->object_method[o->index]->vertex_array(o->prepared);
    o->env_texture = fd->env->texture;
    if (fd->opaque_count > 0 && beyond)
        st->skipped |= SNELL_SKIP_DYNAMIC_ENV; /* its exit rays meet them in the scene layers */
    if (dynamic) {
        /* The glass sees the opaque objects through its dynamic environment,
         * lit as the caustics stage (run before this one) lit them. */
        s = snell__env_dynamic_update(r->ctx, &r->dyn, &r->comp, o->index, fd->env, fd->opaque, fd->opaque_count,
                                      o->bsphere, o->bsphere[3], fd->dynamic_env_size,
                                      o->env_paraboloid ? &r->dp : NULL,
                                      r->env_lookup == SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT,
                                      f->sc->view.lit_opaque, &o->env_texture, st);
        if (s != SNELL_OK) return s;
    } else if (o->env_paraboloid) {
        if ((s = snell__env_paraboloid(r->ctx, &r->dp, fd->env, &o->env_texture)) != SNELL_OK) return s;
    }
    o->scale = snell__glass_scale_of(r->object_method[o->index], r->out, o);
    st->scale = o->scale;
    choose_shading(r, o, st);
    return SNELL_OK;
}

/* The object's method into the bound target, at the view's grid. */
static snell_status draw_method(void *user, const snell__view *v, const snell__object *o, snell_object_stats *st)
{
    snell_renderer *r = (snell_renderer *)user;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    return r->object_method[o->index]->draw(r->ctx, r->object_state[o->index], v, o, st);
}

static snell_status draw_glass(snell_renderer *r, snell__object *o, snell_object_stats *stats)
{
    if (o->scale > 1.0f)
        return snell__glass_scale_draw(r->ctx, &r->glass_scale, &r->scene.view, o, stats, draw_method, r);
    return draw_method(r, &r->scene.view, o, &stats[o->index]);
}

/* Whether the frame needs the scene layers (snell_frame_desc.scene_layers):
 * only where a glass object's exit ray, or the water's rays, have something
 * other than the environment and the container to meet. Lists the glass
 * objects peeled (every one drawn, whose kernels then march them) in
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
     * normal the layers hold (common/beyond.glsl): every object drawn marches
     * them (layers_variant). */
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


/* --- the stages, in frame order ------------------------------------------ */

static snell_status run_opaque(snell__frame *f)
{
    snell_renderer *r = f->r;
    snell_status st = snell__composite_opaque(r->ctx, &r->comp, r->out, f->fd->opaque, f->fd->opaque_count,
                                              (const float *)f->sc->view.view_proj, f->sc->view.eye, f->sc->view.view_axis,
                                              NULL);
    if (f->fd->opaque_count > 0) {
        f->s->opaque_drawn = f->fd->opaque_count;
        f->s->passes++;
    }
    return st;
}

/* The caustics: the receiver plane lit by the light, directly where no
 * object shadows it and through the glass (render/caustics.c), drawn like
 * an opaque object before the glass. Only in colour output. */
static int want_caustics(const snell__frame *f)
{
    if (!snell__caustics_wanted(f->fd, f->s->caustics_reason, sizeof f->s->caustics_reason)) return 0;
    if (f->r->out != SNELL__OUT_COLOR) {
        snell__why(f->s->caustics_reason, sizeof f->s->caustics_reason, "not in exit-direction output");
        return 0;
    }
    return 1;
}

static snell_status run_caustics(snell__frame *f)
{
    snell_status st = snell__caustics_run(f->r->ctx, &f->r->caustics, &f->r->prepared, f->fd, f->sc, f->s);
    if (st == SNELL_OK) snell__receiver_view(&f->sc->view, &f->r->caustics, &f->fd->receiver);
    return st;
}

/* Every kernel's exit and reflected rays meet the lit plane before the
 * environment, and see the opaque objects lit. */
static unsigned receiver_variant(const snell__frame *f, const snell__object *o)
{
    (void)o;
    return f->sc->view.receiver_map || f->sc->view.lit_opaque ? SNELL__GLASS_RECEIVER : 0;
}

/* Glass: the objects shaded in screen space share one G-buffer pass,
 * which leaves each pixel the nearest of their surfaces, then run their
 * kernels (in any order: they cover disjoint pixels); then the forward
 * ones back to front (Franke), each depth-tested against all of those. */
static snell_status run_glass(snell__frame *f)
{
    snell_renderer *r = f->r;
    snell__scene *sc = f->sc;
    snell_status st = SNELL_OK;
    int i;
    f->n_layers = choose_scene_layers(r, f->fd, f->s);
    for (i = 0; i < sc->drawn && st == SNELL_OK; i++) {
        int k = sc->order[i];
        snell__object *o = &sc->obj[k];
        const snell__method *m;
        st = set_up_glass(f, o, &f->s->glass[k]);
        if (st != SNELL_OK) break;
        m = r->object_method[k];
        if (o->screen_space) r->screen_list[f->n_screen++] = o;
        if (m->needs_back_faces) {
            o->back_coarse = m->back_detail && m->back_detail(o->glass) == SNELL_BACK_DETAIL_AUTO &&
                             o->pixels_per_triangle < SNELL__BACK_COARSE_PPT;
            o->back_guard = o->crosses_edge && m->back_guard_percent && m->back_guard_percent(o->glass) > 0
                                ? (m->back_guard_percent(o->glass) * r->height + 99) / 100
                                : 0;
            if (o->back_guard > f->band) f->band = o->back_guard;
            r->back_list[f->n_back++] = o;
        }
    }
    return st;
}

/* The scene layers: every solid glass object drawn and every opaque one,
 * peeled together once, before any kernel reads them. */
static int want_layers(const snell__frame *f) { return f->n_layers >= 0; }

static snell_status run_layers(snell__frame *f)
{
    snell_renderer *r = f->r;
    int peels = 0;
    snell_status st = snell__layers_draw(r->ctx, &r->layers, &f->sc->view, r->layer_list, f->n_layers, f->fd->opaque,
                                         f->fd->opaque_count,
                                         f->fd->scene_layers > 0 ? f->fd->scene_layers : SNELL_DEFAULT_SCENE_LAYERS,
                                         &peels, &f->s->scene_layers_reused);
    f->s->scene_layer_passes = peels;
    f->s->scene_layers = f->sc->view.layers.count;
    f->s->passes += peels;
    return st;
}

/* Every kernel of a frame with layers marches them (common/beyond.glsl). */
static unsigned layers_variant(const snell__frame *f, const snell__object *o)
{
    (void)o;
    return f->n_layers >= 0 ? SNELL__GLASS_BEYOND : 0;
}

static const char *layers_defines(unsigned bits)
{
    (void)bits;
    return "#define SNELL_BEYOND 1\n";
}

static void layers_uniforms(const snell__glass_program *g, const int *locs, const snell__view *v,
                            const snell__object *o)
{
    (void)g;
    snell__beyond_uniforms((const snell__beyond_locs *)(const void *)locs, v,
                           o->index + 1 + (o->glass->material.thickness > 0.0f ? SNELL__LAYERS_THIN_ID : 0));
}

static const snell__kernel_hook g_layers_hook = {
    .variant_mask = SNELL__GLASS_BEYOND,
    .defines = layers_defines,
    .uniform_names = snell__beyond_uniform_names,
    .uniform_count = SNELL__BEYOND_UNIFORMS,
    .uniforms = layers_uniforms,
};

/* The water and its container are opaque to what follows: glass behind
 * them is depth-tested away, glass in front is drawn over them; the
 * glass kernels drawn after see the water along their exit rays
 * (common/water.glsl), the water sees the glass and opaque objects in it
 * through the scene layers. */
static int want_water(const snell__frame *f) { return f->fd->water != NULL; }

static snell_status run_water(snell__frame *f)
{
    snell_renderer *r = f->r;
    const snell_frame_desc *fd = f->fd;
    snell_status st = SNELL_OK;
    /* Without layers (no glass), opaque objects in the water are
     * searched for in a copy of what the opaque pass drew: an offscreen
     * single-sample colour target (a host's framebuffer or a
     * multisampled one cannot be copied with its depth format known;
     * exit directions need no colour): cheaper and more accurate than
     * peeling them into layers for the water alone (bench/notes/code.md,
     * "stages.c"). */
    int layers = f->n_layers >= 0, i;
    int objects = !layers && fd->opaque_count > 0 && r->target == SNELL_TARGET_OFFSCREEN && !r->msaa &&
                  r->out == SNELL__OUT_COLOR;
    unsigned env_tex = fd->env->texture;
    int paraboloid = snell__renderer_env_paraboloid(r, 0); /* the water sees the static environment */
    if (objects) {
        st = snell__water_copy_scene(r->ctx, &r->water, r->fbo, r->width, r->height);
        glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    }
    if (st == SNELL_OK && paraboloid) st = snell__env_paraboloid(r->ctx, &r->dp, fd->env, &env_tex);
    if (st == SNELL_OK)
        st = snell__water_draw(r->ctx, &r->water, r->out, fd->water, &f->sc->view, env_tex, paraboloid, fd->opaque,
                               objects ? fd->opaque_count : 0, layers, f->s);
    if (st == SNELL_OK) snell__water_publish(fd->water, &f->sc->view.textures);
    f->s->water_objects = objects || layers; /* layers: at least one glass object drawn */
    f->s->water_layers = layers;
    for (i = 0; i < f->sc->drawn; i++) f->s->glass[f->sc->order[i]].sees_water = 1;
    return st;
}

/* Every kernel's exit rays meet the water (heights as the simulation keeps them). */
static unsigned water_variant(const snell__frame *f, const snell__object *o)
{
    (void)o;
    if (!f->fd->water) return 0;
    return SNELL__GLASS_WATER | (f->fd->water->d.sim == SNELL_WATER_SIM_GPU ? SNELL__GLASS_WATER_UINT : 0);
}

static const char *water_defines(unsigned bits)
{
    return bits & SNELL__GLASS_WATER_UINT ? "#define SNELL_WATER 1\n#define SNELL_WATER_STATE_UINT 1\n"
                                          : "#define SNELL_WATER 1\n";
}

static void water_uniforms(const snell__glass_program *g, const int *locs, const snell__view *v,
                           const snell__object *o)
{
    (void)g, (void)o;
    snell__water_set_uniforms(locs, v->water);
}

static const snell__kernel_hook g_water_hook = {
    .variant_mask = SNELL__GLASS_WATER | SNELL__GLASS_WATER_UINT,
    .defines = water_defines,
    .uniform_names = snell__water_uniform_names,
    .uniform_count = SNELL__WATER_UNIFORMS,
    .uniforms = water_uniforms,
};

/* One back-face pass for every object whose method reads back faces. */
static int want_back_faces(const snell__frame *f) { return f->n_back > 0; }

static snell_status run_back_faces(snell__frame *f)
{
    snell_renderer *r = f->r;
    snell_status st = snell__gbuffer_draw_back(r->ctx, &r->backfaces, &f->sc->view, r->back_list, f->n_back, f->band,
                                               &f->sc->view.back, f->s->glass);
    snell__gbuffer_publish(&r->backfaces, &f->sc->view.textures, 1);
    f->s->back_face_pass = 1;
    f->s->back_face_guard = f->band;
    return st;
}

static int want_gbuffer(const snell__frame *f) { return f->n_screen > 0; }

/* Where the G-buffer keeps an object's whole front surface (o->front_whole:
 * peel takes its first layer from there): no other object of the pass
 * overlaps its scissor rectangle, and the G-buffer's depth holds nothing
 * drawn before (its own buffer, or a target's with no opaque object, water
 * or receiver plane, whose screen bounds are not at hand here). */
static snell_status run_gbuffer(snell__frame *f)
{
    snell_renderer *r = f->r;
    unsigned depth = r->target == SNELL_TARGET_OFFSCREEN && !r->msaa ? r->depth_rb : 0;
    int clear = !depth || (f->fd->opaque_count == 0 && !f->fd->water && !f->sc->view.receiver_map), i, j;
    snell_status st;
    for (i = 0; i < f->n_screen; i++) {
        const int *a = r->screen_list[i]->scissor;
        r->screen_list[i]->front_whole = clear;
        for (j = 0; j < f->n_screen; j++) {
            const int *b = r->screen_list[j]->scissor;
            if (j != i && a[0] < b[0] + b[2] && b[0] < a[0] + a[2] && a[1] < b[1] + b[3] && b[1] < a[1] + a[3])
                r->screen_list[i]->front_whole = 0;
        }
    }
    st = snell__gbuffer_draw(r->ctx, &r->gbuffer, &f->sc->view, r->screen_list, f->n_screen, depth, f->s->glass);
    snell__gbuffer_publish(&r->gbuffer, &f->sc->view.textures, 0);
    return st;
}

static snell_status run_kernels(snell__frame *f)
{
    snell_renderer *r = f->r;
    snell__scene *sc = f->sc;
    snell_status st = SNELL_OK;
    int i;
    for (i = 0; i < f->n_screen && st == SNELL_OK; i++)
        st = draw_glass(r, r->screen_list[i], f->s->glass);
    for (i = 0; i < sc->drawn && st == SNELL_OK; i++) {
        int k = sc->order[i];
        if (!sc->obj[k].screen_space) st = draw_glass(r, &sc->obj[k], f->s->glass);
    }
    return st;
}

/* The background goes last, where the depth buffer is still clear, so
 * pixels covered by glass or opaque objects are never shaded twice.
 * Exit-direction output always needs it (misses = the view ray). */
static int want_background(const snell__frame *f)
{
    return f->fd->draw_background >= 0 || f->r->out != SNELL__OUT_COLOR;
}

static snell_status run_background(snell__frame *f)
{
    snell_renderer *r = f->r;
    snell_status st = SNELL_OK;
    mat4 rot, vp, inv; /* inv: a pixel's far-plane point to the direction it sees */
    int paraboloid = snell__renderer_env_paraboloid(r, 0);
    unsigned tex = f->fd->env->texture;
    if (f->sc->view.view_axis[3] > 0.5f) {
        /* orthographic: every view ray, so every background pixel, looks
         * along the axis (as the reference's rays do) */
        glm_mat4_zero(inv);
        memcpy(inv[3], f->sc->view.view_axis, 3 * sizeof(float));
        inv[3][3] = 1.0f;
    } else {
        glm_mat4_copy(f->sc->view.view, rot);
        rot[3][0] = rot[3][1] = rot[3][2] = 0.0f;
        glm_mat4_mul(f->sc->view.proj, rot, vp);
        glm_mat4_inv(vp, inv);
    }
    if (paraboloid) st = snell__env_paraboloid(r->ctx, &r->dp, f->fd->env, &tex);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(paraboloid ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_CUBE_MAP, tex);
    if (st == SNELL_OK)
        st = snell__composite_background_lookup(r->ctx, &r->comp, r->out, paraboloid, (const float *)inv);
    f->s->background_drawn = 1;
    f->s->background_paraboloid = paraboloid;
    return st;
}

static int want_ssaa(const snell__frame *f) { return f->r->ssaa.factor > 1; }

static snell_status run_ssaa(snell__frame *f)
{
    snell__ssaa_resolve(&f->r->ssaa, f->r->out_width, f->r->out_height);
    f->s->passes++;
    return SNELL_OK;
}

static int want_msaa(const snell__frame *f) { return f->r->msaa != 0; }

/* The resolve: the samples' mean per pixel. */
static snell_status run_msaa(snell__frame *f)
{
    snell_renderer *r = f->r;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r->msaa_fbo);
    glBlitFramebuffer(0, 0, r->width, r->height, 0, 0, r->width, r->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    f->s->passes++;
    return SNELL_OK;
}

/* --- the table ------------------------------------------------------------ */

const snell__stage snell__stages[] = {
    {"budget", snell__budget_wanted, snell__budget_run, NULL, NULL},
    {"opaque", NULL, run_opaque, NULL, NULL},
    {"caustics", want_caustics, run_caustics, receiver_variant, &snell__receiver_hook},
    {"glass", NULL, run_glass, NULL, NULL},
    {"layers", want_layers, run_layers, layers_variant, &g_layers_hook},
    {"water", want_water, run_water, water_variant, &g_water_hook},
    {"back_faces", want_back_faces, run_back_faces, NULL, NULL},
    {"gbuffer", want_gbuffer, run_gbuffer, NULL, NULL},
    {"kernels", NULL, run_kernels, NULL, NULL},
    {"background", want_background, run_background, NULL, NULL},
    {"ssaa", want_ssaa, run_ssaa, NULL, NULL},
    {"msaa", want_msaa, run_msaa, NULL, NULL},
};
const int snell__stage_count = (int)(sizeof snell__stages / sizeof *snell__stages);

/* The hooks' uniforms fit a program's share of locations. */
typedef char snell__hook_locs_fit[SNELL__BEYOND_UNIFORMS + SNELL__WATER_UNIFORMS + SNELL__RECEIVER_UNIFORMS <=
                                          SNELL__HOOK_LOCS ? 1 : -1];
