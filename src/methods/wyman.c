/* SPDX-License-Identifier: MIT */
/* wyman.c — two-sided refraction in image space (Wyman 2005, as in the
 * seed's 3.4.1): refract at the front surface, put the exit point at
 * P2 = P1 + d T1 with d interpolated between d_V (front to farthest back
 * face along the view ray, from the frame's back-face pass) and d_N (the
 * thickness along the inward normal), read the normal at P2's projection
 * from the back-face map, refract out. d_N is this method's prepared
 * resource: one ray cast per vertex against the mesh (CPU BVH), per mesh
 * version, kept in a vertex buffer bound as attribute 2 (snell__object.vao). */
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "mesh/bvh.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* AUTO shading on llvmpipe: single-surface's measured crossover (8 px per
 * front triangle), not yet measured for this kernel; its per-pixel cost lies
 * between single's and the cubemap's, so the true crossover is likely
 * higher (the cubemap's is "always screen space"). */
#define WYMAN_SOFTWARE_SCREEN_PPT 8.0f

/* fit(): above this hidden fraction (snell_mesh_analysis) view rays cross
 * more than two surfaces often enough that the farthest back face is the
 * wrong exit (measured below, wyman_fit). */
#define WYMAN_MAX_HIDDEN 0.6f

/* One mesh version's d_N (the prepared resource). */
typedef struct wyman_prepared {
    unsigned vao, vbo;     /* the mesh's buffers + attribute 2 = d_N / dn_scale, in the GPU copy's vertex order */
    float dn_scale;        /* object units of an attribute value of 1: the mesh's bounding diameter */
    uint32_t misses;       /* vertices whose inward ray found no surface (bounding-sphere chord used) */
} wyman_prepared;

/* A program's own uniforms (over its cache slot's loc). */
typedef struct wyman_locs {
    int dn_scale, back_band;
} wyman_locs;
SNELL__PROGRAM_LOCS_FIT(wyman_locs);

typedef struct wyman_state {
    snell__output_kind out;
    snell__program_cache *programs; /* the renderer's: keyed by variant, absorption, dispersion variant */
} wyman_state;

static void wyman_destroy(snell_ctx *ctx, void *state);

static snell_status get_prog(snell_ctx *ctx, wyman_state *s, int screen, int absorb, int dispersion,
                             const snell__program_slot **out)
{
    const int key[3] = {screen, absorb, dispersion};
    int hit;
    snell__program_slot *p = snell__program_cache_get(s->programs, SNELL_METHOD_WYMAN, key, 3, &hit);
    if (!hit) {
        char defines[128];
        wyman_locs *loc = SNELL__PROGRAM_LOCS_OF(wyman_locs, p);
        snell_status st;
        snprintf(defines, sizeof defines, "#define SNELL_VERTEX_AUX 1\n#define SNELL_ABSORB %d\n#define SNELL_DISPERSION %d\n",
                 absorb, dispersion);
        st = snell__glass_program_build(ctx, "wyman.frag", s->out, defines, screen, &p->g);
        if (st != SNELL_OK) return st;
        loc->dn_scale = glGetUniformLocation(p->g.prog, "u_dn_scale");
        loc->back_band = glGetUniformLocation(p->g.prog, "u_back_band");
    }
    *out = p;
    return SNELL_OK;
}

static snell_status wyman_create(snell_ctx *ctx, snell__output_kind out, snell__program_cache *programs, void **state)
{
    wyman_state *s = (wyman_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    const snell__program_slot *p;
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    s->out = out;
    s->programs = programs;
    st = get_prog(ctx, s, 0, 0, 0, &p);
    if (st != SNELL_OK) {
        wyman_destroy(ctx, s);
        return st;
    }
    *state = s;
    return SNELL_OK;
}

static void wyman_destroy(snell_ctx *ctx, void *state)
{
    if (state) snell__free(&ctx->alloc, state);
}

/* The seed's limits (3.4.1): one entry and one exit, the exit always on the
 * farthest back face; light leaving through a front face or a nearer back
 * face is wrong by construction, and the normal there is a guess when P2
 * projects outside the silhouette. That is a solid's model: an open or
 * non-manifold mesh bounds no solid (its "back faces" need not be where light
 * leaves), so there it only runs. On closed meshes of low depth complexity it
 * is two-sided without a centre or a bake, which is what the cubemap (earlier
 * in the registry) needs: AUTO reaches it when the cubemap declined, e.g. a
 * closed mesh whose centre is outside. */
static snell__fit wyman_fit(const snell_mesh_analysis *an, const snell_glass_resolved *g, char *why, size_t n)
{
    (void)g;
    /* Measured (tests/test_wyman.c, 160x160, vs the reference with 2
     * interfaces): torus (hidden 0.45) 0.20 rad mean against single's 0.63;
     * goblet (0.97, a view ray crosses four surfaces) 0.56 against 0.46,
     * worse than single: WYMAN_MAX_HIDDEN separates them. */
    if (!snell__fit_solid_few_surfaces(an, WYMAN_MAX_HIDDEN, why, n)) return SNELL__FIT_RUNS;
    /* Even where its preconditions hold, the interpolated exit distance is
     * an approximation that oliveira's search (later in cost order) removes
     * for a little more cost and far less error (bench/BENCHMARKS.md). So AUTO
     * uses it only as a fallback; explicit use is never warned. */
    snell__why(why, n, "closed, %.2f <= %.2f hidden: entry and farthest back face in image space; the exit distance "
                       "is interpolated (oliveira searches it)", an->hidden_fraction, WYMAN_MAX_HIDDEN);
    return SNELL__FIT_RUNS;
}

static void wyman_key(const snell__object *o, int key[4])
{
    (void)o;
    key[0] = key[1] = key[2] = key[3] = 0;
}

/* d_N of a vertex (object space): distance along -n to the nearest surface,
 * from just off the vertex (its own triangles start at t = 0). Where nothing
 * is hit (an open mesh, a ray through a crack) the chord of the bounding
 * sphere about the box centre along -n stands in. */
static double thickness(const snell__bvh *bvh, const snell_mesh *m, const float *pos, const float *nrm, int *miss)
{
    double o[3], d[3], c[3], oc[3], b = 0.0, cc = 0.0, r = m->bradius, len = 0.0;
    snell__bvh_hit hit;
    int k;
    for (k = 0; k < 3; k++) {
        o[k] = pos[k];
        d[k] = -(double)nrm[k];
        len += d[k] * d[k];
    }
    *miss = 0;
    if (!(len > 0.0)) return 0.0;
    if (snell__bvh_closest(bvh, o, d, 1e-5 * r, 4.0 * r / sqrt(len), SNELL__BVH_NONE, &hit)) return hit.t * sqrt(len);
    *miss = 1;
    for (k = 0; k < 3; k++) {
        c[k] = 0.5 * ((double)m->bmin[k] + m->bmax[k]);
        oc[k] = o[k] - c[k];
        b += oc[k] * d[k] / sqrt(len);
        cc += oc[k] * oc[k];
    }
    cc -= r * r;
    return fmax(-b + sqrt(fmax(b * b - cc, 0.0)), 0.0);
}

static snell_status wyman_prepare(snell_ctx *ctx, void *state, const snell__object *o, void *prepared,
                                  snell_object_stats *stats)
{
    wyman_prepared *p = (wyman_prepared *)prepared;
    const snell_mesh *m = o->mesh;
    size_t nv = m->vertex_count, i;
    float *vert = (float *)snell__calloc(&ctx->alloc, 6 * nv, sizeof(float));
    uint32_t *idx = (uint32_t *)snell__calloc(&ctx->alloc, 3 * (size_t)m->triangle_count, sizeof(uint32_t));
    float *dn = (float *)snell__calloc(&ctx->alloc, nv, sizeof(float));
    snell__bvh *bvh = NULL;
    snell_status st;
    (void)state;
    (void)stats;
    st = vert && idx && dn ? SNELL_OK : snell__fail(ctx, SNELL_E_NOMEM, "out of memory for wyman's d_N");
    /* The GPU copy's vertex order (mesh_gpu.c may reorder): d_N depends only
     * on a vertex's position and normal, so it is computed for those. */
    if (st == SNELL_OK) st = snell__mesh_gpu_layout(m, vert, idx);
    if (st == SNELL_OK) st = snell__bvh_build_mesh(ctx, m, NULL, &bvh);
    if (st == SNELL_OK) {
        p->dn_scale = 2.0f * (m->bradius > 0.0f ? m->bradius : 1.0f);
        p->misses = 0;
        for (i = 0; i < nv; i++) {
            int miss;
            double t = thickness(bvh, m, vert + 6 * i, vert + 6 * i + 3, &miss);
            dn[i] = (float)fmin(fmax(t / p->dn_scale, 0.0), 1.0);
            p->misses += (uint32_t)miss;
        }
        if (!p->vao) {
            glGenVertexArrays(1, &p->vao);
            glGenBuffers(1, &p->vbo);
        }
        glBindVertexArray(p->vao);
        glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)0);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)(3 * sizeof(float)));
        glBindBuffer(GL_ARRAY_BUFFER, p->vbo);
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(nv * sizeof(float)), dn, GL_STATIC_DRAW);
        glEnableVertexAttribArray(2);
        glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, sizeof(float), (const void *)0);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
        glBindVertexArray(0);
        if (glGetError() != GL_NO_ERROR) st = snell__fail(ctx, SNELL_E_GL, "GL error uploading wyman's d_N");
    }
    snell__bvh_destroy(bvh);
    snell__free(&ctx->alloc, vert);
    snell__free(&ctx->alloc, idx);
    snell__free(&ctx->alloc, dn);
    return st;
}

static void wyman_release(void *prepared)
{
    wyman_prepared *p = (wyman_prepared *)prepared;
    if (p->vao) glDeleteVertexArrays(1, &p->vao);
    if (p->vbo) glDeleteBuffers(1, &p->vbo);
    p->vao = p->vbo = 0;
}

static unsigned wyman_vertex_array(const void *prepared) { return ((const wyman_prepared *)prepared)->vao; }

static snell_status wyman_draw(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                               snell_object_stats *stats)
{
    wyman_state *s = (wyman_state *)state;
    const wyman_prepared *wp = (const wyman_prepared *)o->prepared;
    int screen = snell__glass_variant(o), absorb = o->glass->absorbs;
    const snell__program_slot *p;
    snell_status st = get_prog(ctx, s, screen, absorb, snell__dispersion_variant(o->glass), &p);
    if (st != SNELL_OK) return st;
    snell__glass_program_use(&p->g, v, o);
    if (!o->screen_space) {
        /* what surface.glsl's screen-space path has set: the back-face lookup needs them forward too */
        glUniformMatrix4fv(p->g.inv_view_proj, 1, GL_FALSE, (const GLfloat *)v->inv_view_proj);
        glUniform2f(p->g.inv_size, 1.0f / (float)v->width, 1.0f / (float)v->height);
        glUniform1i(p->g.gid, o->gid);
    }
    const wyman_locs *loc = SNELL__PROGRAM_LOCS_OF(const wyman_locs, p);
    glUniform1f(loc->dn_scale, wp ? wp->dn_scale : 0.0f);
    glUniform1i(loc->back_band, v->back.band);
    snell__draw_surface(o, stats);
    stats->passes++;
    return SNELL_OK;
}

static const snell_param_info g_params[] = {
    {.name = "back_detail",
     .offset = offsetof(snell_glass_material, wyman.back_detail),
     .help = SNELL__BACK_DETAIL_HELP,
     .min = 0, .max = 2, .def = SNELL_BACK_DETAIL_AUTO, .value_names = snell__back_detail_names},
    {.name = "guard_band",
     .offset = offsetof(snell_glass_material, wyman.guard_band),
     .help = SNELL__GUARD_HELP,
     .min = -1, .max = SNELL_MAX_GUARD_BAND, .def = SNELL__GUARD_DEFAULT},
};


static snell_back_detail wyman_back_detail(const snell_glass_resolved *g) { return g->material.wyman.back_detail; }
static int wyman_guard(const snell_glass_resolved *g) { return g->material.wyman.guard_band; }

static const snell_method_info g_info = {
    .method = SNELL_METHOD_WYMAN,
    .name = "wyman",
    .summary = "two-sided in image space: exit interpolated between view-ray and normal thickness, back-face normal (Wyman 2005)",
    .needs = "a closed mesh (no centre, no star shape); per frame a back-face pass",
    .param_count = (int)(sizeof g_params / sizeof *g_params),
    .params = g_params,
    .counter_count = 0,
    .counters = NULL,
    .ref_interfaces = 2,
    .ref_chord_absorption = 0,
    .default_sweep = "",
}; /* its model stops after two interfaces (TIR reflects and leaves) */

/* AUTO by budget's rungs (frame/method.h): method, parameter, value; frame
 * time over single's and glass PSNR vs FULL for a convex, a bunny-like, a
 * torus-like and an open mesh; resolution scale (bench/notes/budget_rungs.md). */
static const snell_budget_rung g_rungs[] = {
    {SNELL_METHOD_WYMAN, NULL, 0, {2.22f, 1.33f, 1.92f, 1.86f}, {18.59f, 15.27f, 17.01f, 17.26f}, 1, NULL},
};

const snell__method snell__method_wyman = {
    .info = &g_info,
    .needs_analysis = 1,
    .fit = wyman_fit,
    .create = wyman_create,
    .destroy = wyman_destroy,
    .prepared_size = sizeof(wyman_prepared),
    .key = wyman_key,
    .prepare = wyman_prepare,
    .release = wyman_release,
    .draw = wyman_draw,
    .software_screen_ppt = WYMAN_SOFTWARE_SCREEN_PPT,
    .needs_back_faces = 1,
    .back_detail = wyman_back_detail,
    .back_guard_percent = wyman_guard,
    .vertex_array = wyman_vertex_array,
    .rungs = g_rungs,
    .rung_count = (int)(sizeof g_rungs / sizeof *g_rungs),
};
