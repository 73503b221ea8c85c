/* SPDX-License-Identifier: MIT */
/* gbuffer.c — see gbuffer.h. */
#include "render/gbuffer.h"
#include "render/stages.h"
#include "frame/pass.h"
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"

#include <math.h>
#include <string.h>

void snell__gbuffer_destroy(snell__gbuffer *g)
{
    if (g->fbo) glDeleteFramebuffers(1, &g->fbo);
    if (g->normal_tex) glDeleteTextures(1, &g->normal_tex);
    if (g->depth_id_tex) glDeleteTextures(1, &g->depth_id_tex);
    if (g->own_depth_rb) glDeleteRenderbuffers(1, &g->own_depth_rb);
    if (g->prog) glDeleteProgram(g->prog);
    if (g->aux_tex) glDeleteTextures(1, &g->aux_tex);
    if (g->prog_aux) glDeleteProgram(g->prog_aux);
    memset(g, 0, sizeof *g);
}

static unsigned make_texture(GLenum internal, GLenum format, GLenum type, int w, int h)
{
    GLuint t = 0;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    snell__texture_nearest(GL_TEXTURE_2D, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, type, NULL);
    return t;
}

static snell_status create(snell_ctx *ctx, snell__gbuffer *g, int w, int h)
{
    GLint prev_fbo = 0;
    snell_status st = snell__program_build(ctx, "object.vert", "gbuffer.frag", NULL, &g->prog);
    if (st != SNELL_OK) return st;
    g->u_model = glGetUniformLocation(g->prog, "u_model");
    g->u_normal_matrix = glGetUniformLocation(g->prog, "u_normal_matrix");
    g->u_view_proj = glGetUniformLocation(g->prog, "u_view_proj");
    g->u_gid = glGetUniformLocation(g->prog, "u_gid");
    g->normal_tex = make_texture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, w, h);
    g->depth_id_tex = make_texture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, w, h);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &prev_fbo);
    glGenFramebuffers(1, &g->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, g->normal_tex, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, g->depth_id_tex, 0);
    {
        static const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glDrawBuffers(2, bufs);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)prev_fbo);
    g->width = w;
    g->height = h;
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "GL error creating the G-buffer");
}

/* Attaches the depth buffer the pass tests and writes: the target's, or one of its own. */
static snell_status attach_depth(snell_ctx *ctx, snell__gbuffer *g, unsigned target_depth)
{
    unsigned rb = target_depth;
    GLenum fst;
    if (!rb) {
        if (!g->own_depth_rb) {
            glGenRenderbuffers(1, &g->own_depth_rb);
            glBindRenderbuffer(GL_RENDERBUFFER, g->own_depth_rb);
            glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, g->width, g->height);
        }
        rb = g->own_depth_rb;
    }
    if (g->attached_depth == rb) return SNELL_OK;
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb);
    fst = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (fst != GL_FRAMEBUFFER_COMPLETE)
        return snell__fail(ctx, SNELL_E_GL, "G-buffer %dx%d framebuffer incomplete (0x%x)", g->width, g->height,
                           (unsigned)fst);
    g->attached_depth = rb;
    return SNELL_OK;
}

/* The aux target and its program (object.vert passes attribute 2 through). */
static snell_status create_aux(snell_ctx *ctx, snell__gbuffer *g)
{
    snell_status st = snell__program_build(ctx, "object.vert", "gbuffer.frag",
                                           "#define SNELL_VERTEX_AUX 1\n#define SNELL_GBUFFER_AUX 1\n", &g->prog_aux);
    if (st != SNELL_OK) return st;
    g->ua_model = glGetUniformLocation(g->prog_aux, "u_model");
    g->ua_normal_matrix = glGetUniformLocation(g->prog_aux, "u_normal_matrix");
    g->ua_view_proj = glGetUniformLocation(g->prog_aux, "u_view_proj");
    g->ua_gid = glGetUniformLocation(g->prog_aux, "u_gid");
    g->aux_tex = make_texture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, g->width, g->height);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D, g->aux_tex, 0);
    return glGetError() == GL_NO_ERROR ? SNELL_OK : snell__fail(ctx, SNELL_E_GL, "GL error creating the G-buffer's aux target");
}

void snell__gbuffer_publish(const snell__gbuffer *g, snell__textures *ts, int back)
{
    snell__textures_publish(ts, back ? "u_bnormal" : "u_gnormal", GL_TEXTURE_2D, g->normal_tex, 0);
    snell__textures_publish(ts, back ? "u_bdepth_id" : "u_gdepth_id", GL_TEXTURE_2D, g->depth_id_tex, 0);
    if (!back && g->aux_tex) snell__textures_publish(ts, "u_gaux", GL_TEXTURE_2D, g->aux_tex, 0);
}

/* The front (G-buffer) or the farthest surface (back-face pass) of the objects. */
static snell_status draw_surfaces(snell_ctx *ctx, snell__gbuffer *g, const snell__view *v,
                                  snell__object *const *objects, int count, unsigned target_depth, int back,
                                  int band, snell_object_stats *stats)
{
    static const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    snell__pass pass;
    snell_status st;
    mat4 view_proj;
    int i, aux = 0, b;
    /* The maps keep the largest guard band a frame has asked for (they grow
     * once, not back and forth); frames that need none draw only the centre. */
    if (g->fbo && band > g->band) snell__gbuffer_destroy(g);
    if (!g->fbo) {
        int keep = band;
        st = create(ctx, g, v->width + 2 * band, v->height + 2 * band);
        if (st != SNELL_OK) {
            snell__gbuffer_destroy(g);
            return st;
        }
        g->band = keep;
    }
    b = g->band;
    for (i = 0; i < count && !back; i++) aux |= objects[i]->vao != 0;
    /* Front: the target's depth already holds the opaque objects, so glass
     * behind them fails the test here and costs nothing later; only colour is
     * cleared. Back: the farthest surface, in a depth buffer of its own. */
    snell__pass_begin(&pass, g->fbo, g->width, g->height, 0, back ? GL_GREATER : GL_LESS,
                      back ? 0.0f : 1.0f);
    if ((st = attach_depth(ctx, g, target_depth)) != SNELL_OK || (aux && !g->aux_tex && (st = create_aux(ctx, g)) != SNELL_OK)) {
        snell__pass_end(&pass);
        return st;
    }
    glDrawBuffers(aux ? 3 : 2, bufs);
    glm_mat4_copy((vec4 *)v->view_proj, view_proj);
    if (band > 0) {
        /* the whole map: the projection widened so the target's pixels land
         * at texel + b, the band around them showing what lies just off it */
        mat4 widen = GLM_MAT4_IDENTITY_INIT;
        widen[0][0] = (float)v->width / (float)g->width;
        widen[1][1] = (float)v->height / (float)g->height;
        snell__mat4_mul((const float *)widen, (const float *)v->view_proj, (float *)view_proj);
    } else {
        glViewport(b, b, v->width, v->height);
    }
    {
        /* Only the depth+id target needs clearing, and only where a kernel
         * will read it: inside the objects' scissor rectangles (the normal
         * and aux targets are read only where the id matches, i.e. where
         * this frame wrote them): full-target clears cost a share of a
         * cheap frame (bench/notes/code.md, "gbuffer.c"). */
        static const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const GLfloat depth = back ? 0.0f : 1.0f;
        int lo[2] = {g->width, g->height}, hi[2] = {0, 0};
        for (i = 0; i < count; i++) {
            const int *rect = objects[i]->scissor;
            if (rect[0] < lo[0]) lo[0] = rect[0];
            if (rect[1] < lo[1]) lo[1] = rect[1];
            if (rect[0] + rect[2] > hi[0]) hi[0] = rect[0] + rect[2];
            if (rect[1] + rect[3] > hi[1]) hi[1] = rect[1] + rect[3];
        }
        if (band > 0) { /* the band too */
            lo[0] = lo[1] = 0;
            hi[0] = g->width;
            hi[1] = g->height;
        } else if (b > 0) {
            lo[0] += b;
            lo[1] += b;
            hi[0] += b;
            hi[1] += b;
        }
        glEnable(GL_SCISSOR_TEST);
        glScissor(lo[0], lo[1], hi[0] > lo[0] ? hi[0] - lo[0] : 0, hi[1] > lo[1] ? hi[1] - lo[1] : 0);
        glClearBufferfv(GL_COLOR, 1, zero);
        if (!target_depth) glClearBufferfv(GL_DEPTH, 0, &depth);
        glDisable(GL_SCISSOR_TEST);
    }
    glUseProgram(aux ? g->prog_aux : g->prog);
    glUniformMatrix4fv(aux ? g->ua_view_proj : g->u_view_proj, 1, GL_FALSE, (const GLfloat *)view_proj);
    for (i = 0; i < count; i++) {
        const snell__object *o = objects[i];
        snell_object_stats *st = &stats[o->index];
        glUniformMatrix4fv(aux ? g->ua_model : g->u_model, 1, GL_FALSE, (const GLfloat *)o->model);
        glUniformMatrix3fv(aux ? g->ua_normal_matrix : g->u_normal_matrix, 1, GL_FALSE,
                           (const GLfloat *)o->normal_matrix);
        glUniform1i(aux ? g->ua_gid : g->u_gid, o->gid);
        if (back) {
            /* the farthest surface of a closed mesh is a back face: cull the front ones */
            int winding = snell__mesh_winding(o->mesh);
            if (winding != 0) {
                glEnable(GL_CULL_FACE);
                glCullFace((winding < 0) != (o->mirrored != 0) ? GL_BACK : GL_FRONT);
                glFrontFace(GL_CCW);
            }
        } else if (o->glass->material.thickness <= 0.0f) {
            /* thin walls are walls from both sides; every kernel starts at the front surface */
            snell__cull_back_faces(o, st);
        }
        if (back && o->back_coarse && snell__mesh_coarse(o->mesh)) {
            snell__mesh_coarse_draw(o->mesh);
            glDisable(GL_CULL_FACE);
            st->skipped |= SNELL_SKIP_BACK_DETAIL;
        } else {
            snell__draw_object(o);
        }
        st->passes++;
    }
    snell__pass_end(&pass);
    return SNELL_OK;
}

snell_status snell__gbuffer_draw(snell_ctx *ctx, snell__gbuffer *g, const snell__view *v, snell__object *const *objects,
                                 int count, unsigned target_depth, snell_object_stats *stats)
{
    return draw_surfaces(ctx, g, v, objects, count, target_depth, 0, 0, stats);
}

snell_status snell__gbuffer_draw_back(snell_ctx *ctx, snell__gbuffer *g, const snell__view *v,
                                      snell__object *const *objects, int count, int band, snell__back_maps *maps,
                                      snell_object_stats *stats)
{
    snell_status st = draw_surfaces(ctx, g, v, objects, count, 0, 1, band, stats);
    maps->band = g->band;
    maps->width = g->width;
    maps->height = g->height;
    return st;
}

snell__device_class snell__device_class_of(const char *gl_renderer)
{
    static const char *const tilers[] = {"Mali", "Adreno", "PowerVR", "VideoCore", "V3D", "Apple", "Immortalis"};
    size_t i;
    if (snell__software_rasteriser(gl_renderer)) return SNELL__DEVICE_SOFTWARE;
    for (i = 0; gl_renderer && i < sizeof tilers / sizeof *tilers; i++)
        if (strstr(gl_renderer, tilers[i])) return SNELL__DEVICE_TILER;
    return SNELL__DEVICE_IMMEDIATE;
}

float snell__screen_threshold(snell__device_class device, const snell__method *method, int convex)
{
    switch (device) {
    /* Software rasterisers shade 4x4 blocks: the crossover measured per method. */
    case SNELL__DEVICE_SOFTWARE:
        return convex && method->software_screen_ppt_convex > 0.0f ? method->software_screen_ppt_convex
                                                                   : method->software_screen_ppt;
    /* Not measured yet (no GPU here), from how they work: tile-based GPUs pay
     * the extra pass in memory bandwidth, so only for sub-pixel triangles;
     * immediate-mode GPUs shade 2x2 quads, so most lanes idle below a few pixels. */
    case SNELL__DEVICE_TILER: return 1.0f;
    default: return 4.0f;
    }
}

/* Does the sphere reach past one of the frustum's four side planes (the
 * target's edges)? Planes from the rows of view_proj (Gribb and Hartmann):
 * w +- x >= 0, w +- y >= 0 inside. */
static int sphere_crosses_sides(const snell__view *v, const float s[4])
{
    const float(*m)[4] = (const float(*)[4])v->view_proj;
    int axis, sign;
    for (axis = 0; axis < 2; axis++)
        for (sign = -1; sign <= 1; sign += 2) {
            float p[4], len;
            int k;
            for (k = 0; k < 4; k++) p[k] = m[k][3] + (float)sign * m[k][axis];
            len = sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            if (len > 0.0f && (p[0] * s[0] + p[1] * s[1] + p[2] * s[2] + p[3]) / len < s[3]) return 1;
        }
    return 0;
}

/* Window-space bounds of the sphere, from its bounding box's 8 corners. */
static int project_sphere(const snell__view *v, const float s[4], float lo[2], float hi[2])
{
    int c, k;
    lo[0] = lo[1] = HUGE_VALF;
    hi[0] = hi[1] = -HUGE_VALF;
    for (c = 0; c < 8; c++) {
        vec4 p = {s[0] + ((c & 1) ? s[3] : -s[3]), s[1] + ((c & 2) ? s[3] : -s[3]), s[2] + ((c & 4) ? s[3] : -s[3]),
                  1.0f}, q;
        glm_mat4_mulv((vec4 *)v->view_proj, p, q);
        if (!(q[3] > 1e-6f)) return 0; /* a corner at or behind the eye: no bound */
        for (k = 0; k < 2; k++) {
            float w = (q[k] / q[3] * 0.5f + 0.5f) * (float)(k ? v->height : v->width);
            if (w < lo[k]) lo[k] = w;
            if (w > hi[k]) hi[k] = w;
        }
    }
    return 1;
}

void snell__object_project(const snell__view *v, snell__object *o)
{
    float lo[2], hi[2], area, front = 0.5f * (float)o->mesh->triangle_count;
    int x0, y0, x1, y1;
    if (!project_sphere(v, o->bsphere, lo, hi)) {
        o->pixels_per_triangle = 0.0f; /* very near: treat as dense */
        o->crosses_edge = 1;
        o->scissor[0] = o->scissor[1] = 0;
        o->scissor[2] = v->width;
        o->scissor[3] = v->height;
        return;
    }
    o->crosses_edge = sphere_crosses_sides(v, o->bsphere);
    /* clipped to the target */
    lo[0] = fmaxf(lo[0], 0.0f);
    lo[1] = fmaxf(lo[1], 0.0f);
    hi[0] = fminf(hi[0], (float)v->width);
    hi[1] = fminf(hi[1], (float)v->height);
    /* the sphere's disc inscribed in its screen box */
    area = hi[0] > lo[0] && hi[1] > lo[1] ? 0.785398f * (hi[0] - lo[0]) * (hi[1] - lo[1]) : 0.0f;
    o->pixels_per_triangle = front > 0.0f ? area / front : 0.0f;
    x0 = (int)floorf(lo[0]);
    y0 = (int)floorf(lo[1]);
    x1 = (int)ceilf(hi[0]);
    y1 = (int)ceilf(hi[1]);
    o->scissor[0] = x0;
    o->scissor[1] = y0;
    o->scissor[2] = x1 > x0 ? x1 - x0 : 0;
    o->scissor[3] = y1 > y0 ? y1 - y0 : 0;
}


/* --- the back-face and G-buffer stages ------------------------------------ */

typedef struct pass_stage {
    snell__gbuffer g;
    snell__object *list[SNELL_MAX_GLASS];
} pass_stage;

static void stage_destroy(snell_ctx *ctx, void *state)
{
    (void)ctx;
    snell__gbuffer_destroy(&((pass_stage *)state)->g);
}

/* One back-face pass for every object whose method reads back faces. */
static int back_wanted(const snell__frame *f, const void *state)
{
    int i;
    (void)state;
    for (i = 0; i < f->sc->drawn; i++)
        if (f->sc->obj[f->sc->order[i]].method->needs_back_faces) return 1;
    return 0;
}

/* Each object's detail and guard band (o->back_coarse, o->back_guard); the
 * pass keeps the largest band. */
static snell_status back_run(snell__frame *f, void *state)
{
    pass_stage *ps = (pass_stage *)state;
    const snell__services *sv = f->sv;
    snell__scene *sc = f->sc;
    int i, n = 0, band = 0;
    snell_status st;
    for (i = 0; i < sc->drawn; i++) {
        snell__object *o = &sc->obj[sc->order[i]];
        const snell__method *m = o->method;
        if (!m->needs_back_faces) continue;
        o->back_coarse = m->back_detail && m->back_detail(o->glass) == SNELL_BACK_DETAIL_AUTO &&
                         o->pixels_per_triangle < SNELL__BACK_COARSE_PPT;
        o->back_guard = o->crosses_edge && m->back_guard_percent && m->back_guard_percent(o->glass) > 0
                            ? (m->back_guard_percent(o->glass) * sv->height + 99) / 100
                            : 0;
        if (o->back_guard > band) band = o->back_guard;
        ps->list[n++] = o;
    }
    st = snell__gbuffer_draw_back(sv->ctx, &ps->g, &sc->view, ps->list, n, band, &sc->view.back, f->s->glass);
    snell__gbuffer_publish(&ps->g, &sc->view.textures, 1);
    f->s->back_face_pass = 1;
    f->s->back_face_guard = band;
    return st;
}

const snell__stage snell__stage_back_faces = {
    .name = "back_faces",
    .state_size = sizeof(pass_stage),
    .destroy = stage_destroy,
    .wanted = back_wanted,
    .run = back_run,
};

static int gbuffer_wanted(const snell__frame *f, const void *state)
{
    int i;
    (void)state;
    for (i = 0; i < f->sc->drawn; i++)
        if (f->sc->obj[f->sc->order[i]].screen_space) return 1;
    return 0;
}

/* Where the G-buffer keeps an object's whole front surface (o->front_whole:
 * peel takes its first layer from there): no other object of the pass
 * overlaps its scissor rectangle, and the G-buffer's depth holds nothing
 * drawn before (its own buffer, or a target's with no opaque object, water
 * or receiver plane, whose screen bounds are not at hand here). */
static snell_status gbuffer_run(snell__frame *f, void *state)
{
    pass_stage *ps = (pass_stage *)state;
    const snell__services *sv = f->sv;
    snell__scene *sc = f->sc;
    unsigned depth = sv->target == SNELL_TARGET_OFFSCREEN && !sv->samples ? sv->depth_rb : 0;
    int clear = !depth || !f->depth_drawn, i, j, n = 0;
    snell_status st;
    for (i = 0; i < sc->drawn; i++)
        if (sc->obj[sc->order[i]].screen_space) ps->list[n++] = &sc->obj[sc->order[i]];
    for (i = 0; i < n; i++) {
        const int *a = ps->list[i]->scissor;
        ps->list[i]->front_whole = clear;
        for (j = 0; j < n; j++) {
            const int *b = ps->list[j]->scissor;
            if (j != i && a[0] < b[0] + b[2] && b[0] < a[0] + a[2] && a[1] < b[1] + b[3] && b[1] < a[1] + a[3])
                ps->list[i]->front_whole = 0;
        }
    }
    st = snell__gbuffer_draw(sv->ctx, &ps->g, &sc->view, ps->list, n, depth, f->s->glass);
    snell__gbuffer_publish(&ps->g, &sc->view.textures, 0);
    return st;
}

const snell__stage snell__stage_gbuffer = {
    .name = "gbuffer",
    .state_size = sizeof(pass_stage),
    .destroy = stage_destroy,
    .wanted = gbuffer_wanted,
    .run = gbuffer_run,
};
