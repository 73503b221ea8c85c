/* SPDX-License-Identifier: MIT */
/* layers.c — see layers.h. */
#include "render/layers.h"
#include "render/stages.h"
#include "frame/beyond.h"
#include "frame/pass.h"
#include "render/scene.h"
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "core/program.h"

#include <math.h>
#include <string.h>

#define PEEL_UNIT 1 /* the peel program's previous layer (depth_peel.frag u_prev) */

void snell__layers_destroy(snell__layers *l)
{
    snell__peel_targets_release(&l->t);
    if (l->table_tex) glDeleteTextures(1, &l->table_tex);
    if (l->prog) glDeleteProgram(l->prog);
    memset(l, 0, sizeof *l);
    l->last.count = -1;
}

static snell_status create_program(snell_ctx *ctx, snell__layers *l)
{
    snell_status st = snell__program_build(ctx, "object.vert", "depth_peel.frag", NULL, &l->prog);
    if (st != SNELL_OK) return st;
    l->u_model = glGetUniformLocation(l->prog, "u_model");
    l->u_normal_matrix = glGetUniformLocation(l->prog, "u_normal_matrix");
    l->u_view_proj = glGetUniformLocation(l->prog, "u_view_proj");
    l->u_eye = glGetUniformLocation(l->prog, "u_eye");
    l->u_fwd = glGetUniformLocation(l->prog, "u_fwd");
    l->u_near = glGetUniformLocation(l->prog, "u_near");
    l->u_inv_range = glGetUniformLocation(l->prog, "u_inv_range");
    l->u_first = glGetUniformLocation(l->prog, "u_first");
    l->u_prev = glGetUniformLocation(l->prog, "u_prev");
    l->u_id = glGetUniformLocation(l->prog, "u_id");
    return SNELL_OK;
}

/* Layer targets for a w x h target and `layers` layers (made or grown on
 * demand; kept across frames), and the object table (made once). */
static snell_status ensure_targets(snell_ctx *ctx, snell__layers *l, int w, int h, int layers)
{
    int remade;
    snell_status st = snell__peel_targets_ensure(ctx, &l->t, w, h, layers, PEEL_UNIT, "scene layers", &remade);
    if (remade) l->last.count = -1; /* the layers are gone with them */
    if (st != SNELL_OK || l->table_tex) return st;
    glGenTextures(1, &l->table_tex);
    glBindTexture(GL_TEXTURE_2D, l->table_tex);
    snell__texture_nearest(GL_TEXTURE_2D, 0);
    /* RGBA32F is sampleable unfiltered in core GLES 3.0 (texelFetch) */
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, SNELL__LAYERS_IDS, SNELL__LAYERS_TABLE_ROWS);
    glActiveTexture(GL_TEXTURE0);
    if (glGetError() != GL_NO_ERROR) {
        glDeleteTextures(1, &l->table_tex);
        l->table_tex = 0;
        return snell__fail(ctx, SNELL_E_GL, "GL error creating the scene layers' object table");
    }
    return SNELL_OK;
}

/* One object of the peel: what the layer pass draws and the table holds. */
typedef struct layer_item {
    const snell_mesh *mesh;
    const snell__object *glass; /* NULL: opaque */
    mat4 model;
    mat3 normal_matrix;
    float bsphere[4];
    int id;
} layer_item;

static void opaque_item(const snell_opaque *o, int j, layer_item *it)
{
    mat4 inv;
    memset(it, 0, sizeof *it);
    it->mesh = o->mesh;
    if (o->model) memcpy(it->model, o->model, sizeof it->model);
    else glm_mat4_identity(it->model);
    snell__mat4_inv((const float *)it->model, (float *)inv);
    glm_mat4_transpose(inv);
    glm_mat4_pick3(inv, it->normal_matrix);
    snell__bounding_sphere(o->mesh, it->model, it->bsphere);
    it->id = SNELL__LAYERS_OPAQUE_ID0 + j;
}

/* The table's column for an item: row 0 (IOR, tint; IOR 0 = opaque), row 1
 * (absorption per world unit), row 2 (bounding sphere), row 3 (opaque albedo). */
static void table_column(snell__layers *l, const layer_item *it, const snell_opaque *opaque)
{
    float *r0 = l->table[0][it->id - 1], *r1 = l->table[1][it->id - 1], *r2 = l->table[2][it->id - 1],
          *r3 = l->table[3][it->id - 1];
    int k;
    memset(r0, 0, 4 * sizeof *r0);
    memset(r1, 0, 4 * sizeof *r1);
    memset(r3, 0, 4 * sizeof *r3);
    memcpy(r2, it->bsphere, 4 * sizeof *r2);
    if (it->glass) {
        const snell_glass_resolved *g = it->glass->glass;
        r0[0] = g->material.ior;
        for (k = 0; k < 3; k++) {
            r0[1 + k] = g->material.tint[k];
            r1[k] = g->absorbs ? g->absorption[k] : 0.0f;
        }
        r1[3] = g->material.thickness; /* > 0: a thin wall */
    } else {
        for (k = 0; k < 3; k++) r3[k] = opaque->color[k]; /* resolved by the opaque stage */
    }
}

/* Uploads the frame's object table (materials change without a new peel)
 * and publishes it and the layers for the programs that march them. */
static void publish(snell__layers *l, snell__view *v)
{
    snell__pixel_store unpack;
    int k;
    glBindTexture(GL_TEXTURE_2D, l->table_tex);
    /* from client memory, tightly packed, whatever pixel buffer or unpack state the host has set */
    snell__pixel_unpack_begin(&unpack, 4);
    for (k = 0; k < SNELL__LAYERS_TABLE_ROWS; k++)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, k, SNELL__LAYERS_IDS, 1, GL_RGBA, GL_FLOAT, l->table[k]);
    snell__pixel_unpack_end(&unpack);
    snell__textures_publish(&v->textures, "u_scene_layers", GL_TEXTURE_2D_ARRAY, l->t.array_tex, 0);
    snell__textures_publish(&v->textures, "u_scene_table", GL_TEXTURE_2D, l->table_tex, 0);
}

/* Draws up to `layers` peels of the items into the layer textures (which
 * hold that many); *used: those that hold something. */
static snell_status peel(snell_ctx *ctx, snell__layers *l, const snell__view *v, const layer_item *items, int n,
                         int layers, int *passes, int *used)
{
    const snell__scene_layers *sl = &v->layers;
    snell__pass pass;
    int i, k;
    *used = 0;
    snell__pass_begin(&pass, l->t.fbo, v->width, v->height, 0, GL_LESS, 1.0f);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, l->t.depth_rb);
    glUseProgram(l->prog);
    glUniformMatrix4fv(l->u_view_proj, 1, GL_FALSE, (const GLfloat *)v->view_proj);
    glUniform3fv(l->u_eye, 1, v->eye);
    glUniform3fv(l->u_fwd, 1, sl->fwd);
    glUniform1f(l->u_near, sl->near_);
    glUniform1f(l->u_inv_range, sl->inv_range);
    glUniform1i(l->u_prev, PEEL_UNIT);
    glActiveTexture(GL_TEXTURE0 + PEEL_UNIT);
    for (k = 0; k < layers; k++) {
        GLuint any = 1;
        snell_status st = snell__peel_layer_begin(ctx, &l->t, k);
        if (st != SNELL_OK) {
            snell__pass_end(&pass);
            return st;
        }
        glUniform1i(l->u_first, k == 0);
        glBeginQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE, l->t.query);
        for (i = 0; i < n; i++) {
            glUniformMatrix4fv(l->u_model, 1, GL_FALSE, (const GLfloat *)items[i].model);
            glUniformMatrix3fv(l->u_normal_matrix, 1, GL_FALSE, (const GLfloat *)items[i].normal_matrix);
            glUniform1i(l->u_id, items[i].id);
            snell__mesh_draw(items[i].mesh); /* every face, front and back */
        }
        glEndQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE);
        (*passes)++;
        glGetQueryObjectuiv(l->t.query, GL_QUERY_RESULT, &any);
        if (!any) break; /* nothing behind the last layer: no further peel can hold anything */
        (*used)++;
    }
    snell__pass_end(&pass);
    return SNELL_OK;
}

snell_status snell__layers_draw(snell_ctx *ctx, snell__layers *l, snell__view *v, snell__object *const *glass,
                                int glass_count, const snell_opaque *opaque, int opaque_count, int max_layers,
                                int *passes, int *reused)
{
    layer_item items[SNELL_MAX_GLASS + SNELL_MAX_OPAQUE];
    float lo = HUGE_VALF, hi = -HUGE_VALF;
    snell__scene_layers *sl = &v->layers;
    snell_status st;
    int n = 0, i, k, used = 0;
    *passes = 0;
    *reused = 0;
    memset(sl, 0, sizeof *sl);
    for (i = 0; i < glass_count; i++) {
        layer_item *it = &items[n++];
        memset(it, 0, sizeof *it);
        it->mesh = glass[i]->mesh;
        it->glass = glass[i];
        glm_mat4_copy((vec4 *)glass[i]->model, it->model);
        glm_mat3_copy((vec3 *)glass[i]->normal_matrix, it->normal_matrix);
        memcpy(it->bsphere, glass[i]->bsphere, sizeof it->bsphere);
        it->id = glass[i]->index + 1;
    }
    for (i = 0; i < opaque_count; i++) opaque_item(&opaque[i], i, &items[n++]);
    if (!l->prog && (st = create_program(ctx, l)) != SNELL_OK) return st;

    /* the depth frame: the view-axis range of every item's bounding sphere */
    for (k = 0; k < 3; k++) sl->fwd[k] = -v->view[k][2];
    for (i = 0; i < n; i++) {
        float c = 0.0f;
        for (k = 0; k < 3; k++) c += (items[i].bsphere[k] - v->eye[k]) * sl->fwd[k];
        if (c - items[i].bsphere[3] < lo) lo = c - items[i].bsphere[3];
        if (c + items[i].bsphere[3] > hi) hi = c + items[i].bsphere[3];
    }
    sl->near_ = lo;
    sl->inv_range = hi > lo ? 1.0f / (hi - lo) : 1.0f;
    sl->width = v->width;
    sl->height = v->height;

    /* the table: a radius of 0 marks an id without an object this frame */
    memset(l->table, 0, sizeof l->table);
    for (i = 0; i < n; i++) table_column(l, &items[i], items[i].glass ? NULL : &opaque[items[i].id - SNELL__LAYERS_OPAQUE_ID0]);
    for (i = 0; i < glass_count; i++) /* after the table: the column is the object's */
        if (glass[i]->glass->material.thickness > 0.0f) items[i].id += SNELL__LAYERS_THIN_ID;

    /* the key: what the peels depend on */
    memset(&l->key, 0, sizeof l->key);
    memcpy(l->key.view_proj, v->view_proj, sizeof l->key.view_proj);
    l->key.width = v->width;
    l->key.height = v->height;
    l->key.max_layers = max_layers;
    l->key.count = n;
    for (i = 0; i < n; i++) {
        memcpy(l->key.item[i].model, items[i].model, sizeof l->key.item[i].model);
        l->key.item[i].mesh_version = items[i].mesh->version;
        l->key.item[i].id = items[i].id;
    }
    if (l->last.count == n && !memcmp(&l->key, &l->last, sizeof l->key)) {
        *sl = l->last_layers;
        *reused = 1;
        publish(l, v);
        return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "GL error binding scene layers");
    }

    l->last.count = -1; /* until these peels are complete */
    /* The layers start at SNELL__LAYERS_START and grow (up to max_layers,
     * kept for later frames) when every one came out full: memory and peels
     * follow what the scene needs (8 layers of 1920x1080 RGBA8 pairs are
     * 133 MB). A grown frame peels again at once, so no frame shows a cut. */
    for (;;) {
        int cap = l->grown > 0 ? l->grown : SNELL__LAYERS_START;
        if (cap > max_layers) cap = max_layers;
        if ((st = ensure_targets(ctx, l, v->width, v->height, cap)) != SNELL_OK) return st;
        if ((st = peel(ctx, l, v, items, n, cap, passes, &used)) != SNELL_OK) return st;
        if (used < cap || cap >= max_layers) {
            sl->capped = used == cap;
            break;
        }
        l->grown = 2 * cap < max_layers ? 2 * cap : max_layers;
    }
    sl->count = used;
    for (i = 0; i < glass_count; i++)
        if (glass[i]->index + 1 > sl->glass_ids) sl->glass_ids = glass[i]->index + 1;
    sl->opaque_count = opaque_count;
    l->last = l->key;
    l->last_layers = *sl;
    publish(l, v);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "GL error peeling scene layers");
}



/* --- the scene layers stage ------------------------------------------------ */

typedef struct layers_stage {
    snell__layers layers;
    snell__object *list[SNELL_MAX_GLASS]; /* the glass objects peeled */
    int count;                      /* of them, -1: no layers this frame */
} layers_stage;

static snell_status stage_create(snell__services *sv, const snell_renderer_desc *d, void *state)
{
    (void)sv, (void)d;
    ((layers_stage *)state)->layers.last.count = -1; /* none peeled yet */
    return SNELL_OK;
}

static void stage_destroy(snell_ctx *ctx, void *state)
{
    (void)ctx;
    snell__layers_destroy(&((layers_stage *)state)->layers);
}

static snell_status stage_validate(const snell__services *sv, const snell_frame_desc *fd)
{
    if (fd->scene_layers != -1 && (fd->scene_layers < 2 || fd->scene_layers > SNELL_MAX_SCENE_LAYERS))
        return snell__fail(sv->ctx, SNELL_E_INVALID_ARG, "scene_layers %d: -1 (off) or 2..%d", fd->scene_layers,
                           SNELL_MAX_SCENE_LAYERS);
    return SNELL_OK;
}

/* Whether the frame needs the scene layers (snell_frame_desc.scene_layers):
 * only where a glass object's exit ray, or the water's rays, have something
 * other than the environment and the container to meet. Decided before the
 * glass is set up: every kernel of a frame with layers marches them. */
static void stage_plan(snell__frame *f, void *state)
{
    layers_stage *ls = (layers_stage *)state;
    const snell_frame_desc *fd = f->fd;
    snell_frame_stats *s = f->s;
    snell__scene *sc = f->sc;
    int i, n = 0, solid = 0;
    for (i = 0; i < sc->drawn; i++) {
        snell__object *o = &sc->obj[sc->order[i]];
        ls->list[n++] = o;
        solid += o->glass->material.thickness <= 0.0f;
    }
    ls->count = -1;
    if (fd->scene_layers < 0) {
        snell__why(s->scene_layers_reason, sizeof s->scene_layers_reason, "off (scene_layers -1)");
        return;
    }
    if (n == 0 || (n == 1 && fd->opaque_count == 0 && !fd->water)) {
        snell__why(s->scene_layers_reason, sizeof s->scene_layers_reason, "not needed: %s",
                   n == 0 ? "no glass object drawn" : "one glass object and nothing else");
        return;
    }
    /* With water, every glass object's kernel reads them too: its exit rays
     * leaving under the water are bent for the water's index with the
     * normal the layers hold (common/beyond.glsl). */
    if (n == 1 && fd->opaque_count == 0)
        snell__why(s->scene_layers_reason, sizeof s->scene_layers_reason, "one glass object in a frame with water: "
                   "the water's rays meet it, its rays leave into the water");
    else
        snell__why(s->scene_layers_reason, sizeof s->scene_layers_reason, "%d glass (%d solid, %d thin walls) and %d "
                   "opaque objects%s: exit rays meet the others", n, solid, n - solid, fd->opaque_count,
                   fd->water ? " and water" : "");
    ls->count = n;
}

static int stage_wanted(const snell__frame *f, const void *state)
{
    (void)f;
    return ((const layers_stage *)state)->count >= 0;
}

/* Every solid glass object drawn and every opaque one, peeled together
 * once, before any kernel reads them. */
static snell_status stage_run(snell__frame *f, void *state)
{
    layers_stage *ls = (layers_stage *)state;
    int peels = 0;
    snell_status st = snell__layers_draw(f->sv->ctx, &ls->layers, &f->sc->view, ls->list, ls->count, f->fd->opaque,
                                         f->fd->opaque_count,
                                         f->fd->scene_layers,
                                         &peels, &f->s->scene_layers_reused);
    f->sc->view.layers.active = 1;
    f->s->scene_layer_passes = peels;
    f->s->scene_layers = f->sc->view.layers.count;
    f->s->passes += peels;
    return st;
}

static unsigned stage_variant(const snell__frame *f, const void *state, const snell__object *o)
{
    (void)f, (void)o;
    return ((const layers_stage *)state)->count >= 0 ? 1u : 0u;
}

static const char *hook_defines(unsigned bits)
{
    (void)bits;
    return "#define SNELL_BEYOND 1\n";
}

static void hook_uniforms(const snell__glass_program *g, const int *locs, const void *state, const snell__view *v,
                          const snell__object *o)
{
    (void)g, (void)state;
    snell__beyond_uniforms((const snell__beyond_locs *)(const void *)locs, v,
                           o->index + 1 + (o->glass->material.thickness > 0.0f ? SNELL__LAYERS_THIN_ID : 0));
}

static const snell__kernel_hook g_hook = {
    .variant_bits = 1,
    .defines = hook_defines,
    .uniform_names = snell__beyond_uniform_names,
    .uniform_count = SNELL__BEYOND_UNIFORMS,
    .uniforms = hook_uniforms,
};

const snell__stage snell__stage_layers = {
    .name = "layers",
    .state_size = sizeof(layers_stage),
    .create = stage_create,
    .destroy = stage_destroy,
    .validate = stage_validate,
    .plan = stage_plan,
    .wanted = stage_wanted,
    .run = stage_run,
    .kernel_variant = stage_variant,
    .kernel = &g_hook,
};
