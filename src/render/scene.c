/* SPDX-License-Identifier: MIT */
/* scene.c — see scene.h. */
#include "render/scene.h"
#include "render/budget.h"
#include "frame/camera.h"
#include "core/ctx.h"

#include <math.h>
#include <string.h>

/* Glass that changes nothing: IOR 1, no absorption, no tint. */
static int is_passthrough(const snell_glass_resolved *g)
{
    const float *t = g->material.tint;
    return g->material.ior == 1.0f && !g->absorbs && t[0] == 1.0f && t[1] == 1.0f && t[2] == 1.0f;
}

void snell__bounding_sphere(const snell_mesh *m, mat4 model, float out[4])
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

/* Sphere entirely outside one of the frustum's six planes (Gribb-Hartmann:
 * plane = row 3 +- row k of view_proj)? */
static int outside_view(mat4 vp, const float s[4])
{
    int k, sign;
    for (k = 0; k < 3; k++)
        for (sign = -1; sign <= 1; sign += 2) {
            float p[4], len, d;
            int j;
            for (j = 0; j < 4; j++) p[j] = vp[j][3] + (float)sign * vp[j][k];
            len = sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            if (!(len > 0.0f)) continue;
            d = (p[0] * s[0] + p[1] * s[1] + p[2] * s[2] + p[3]) / len;
            if (d < -s[3]) return 1;
        }
    return 0;
}

static snell_status build_object(snell_ctx *ctx, const snell_glass *g, int i, snell__scene *sc,
                                 snell_object_stats *st)
{
    snell__object *o = &sc->obj[i];
    snell_status s;
    mat4 inv;
    vec4 c;
    char why[96];
    int k;
    memset(o, 0, sizeof *o);
    if (!g->mesh) return snell__fail(ctx, SNELL_E_INVALID_ARG, "glass %d has no mesh", i);
    if (!snell__mesh_bind_ctx((snell_mesh *)g->mesh, ctx))
        return snell__fail(ctx, SNELL_E_INVALID_ARG,
                           "glass %d: its mesh belongs to another context (made with it, or drawn there first)", i);
    if (g->model)
        for (k = 0; k < 16; k++)
            if (!isfinite(g->model[k])) return snell__fail(ctx, SNELL_E_INVALID_ARG, "glass %d: model matrix is not finite", i);
    s = snell__glass_resolve_all(&g->material, i, &sc->glass[i]);
    if (s != SNELL_OK) return snell__fail(ctx, s, "%s", snell_last_error(NULL));
    o->index = i;
    o->mesh = (snell_mesh *)g->mesh;
    o->glass = &sc->glass[i];
    if (g->model) memcpy(o->model, g->model, sizeof o->model);
    else glm_mat4_identity(o->model);
    snell__mat4_inv((const float *)o->model, (float *)o->inv_model);
    if (!snell__matrix_invertible((const float *)o->model, why, sizeof why))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "glass %d: model matrix %s", i, why);
    glm_mat4_transpose_to(o->inv_model, inv);
    glm_mat4_pick3(inv, o->normal_matrix);
    o->mirrored = (glm_mat4_det(o->model) < 0.0f) != sc->view.mirrored; /* either flips the winding */
    snell__bounding_sphere(o->mesh, o->model, o->bsphere);
    glm_mat4_mulv(sc->view.view, (vec4){o->bsphere[0], o->bsphere[1], o->bsphere[2], 1.0f}, c);
    o->view_depth = -c[2];
    st->view_depth = o->view_depth;
    st->draw_order = -1;
    for (k = 0; k < SNELL_MAX_METHOD_COUNTERS; k++) st->counters[k] = -1; /* the method counts what it counts */
    st->method_used = SNELL_METHOD_AUTO;
    if (outside_view(sc->view.view_proj, o->bsphere)) {
        st->skipped |= SNELL_SKIP_OUTSIDE_VIEW;
        snell__why(st->reason, sizeof st->reason, "not drawn: its bounding sphere is outside the view");
    } else if (is_passthrough(o->glass) && sc->view.out == SNELL__OUT_COLOR) {
        st->skipped |= SNELL_SKIP_PASSTHROUGH;
        snell__why(st->reason, sizeof st->reason, "not drawn: IOR 1 without absorption or tint changes nothing");
    } else {
        /* back to front: insertion into order[] by decreasing view depth */
        int j = sc->drawn++;
        while (j > 0 && sc->obj[sc->order[j - 1]].view_depth < o->view_depth) {
            sc->order[j] = sc->order[j - 1];
            j--;
        }
        sc->order[j] = i;
    }
    return SNELL_OK;
}

snell_status snell__scene_build(snell_ctx *ctx, const snell_frame_desc *fd, int width, int height,
                                snell__output_kind out, snell__scene *sc, snell_frame_stats *stats)
{
    snell__view *v = &sc->view;
    int i;
    if (fd->glass_count < 0 || fd->glass_count > SNELL_MAX_GLASS || (fd->glass_count > 0 && !fd->glass))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "glass_count %d outside 0..%d or glass list NULL",
                           fd->glass_count, SNELL_MAX_GLASS);
    memset(v, 0, sizeof *v);
    v->mirrored = snell__camera_standard(&fd->camera, (float)width / (float)height, v->eye, (float *)v->view,
                                         (float *)v->proj) & SNELL__CAMERA_MIRRORED;
    snell__mat4_mul((const float *)v->proj, (const float *)v->view, (float *)v->view_proj);
    snell__mat4_inv((const float *)v->view_proj, (float *)v->inv_view_proj);
    if (snell__projection_orthographic((const float *)v->proj)) {
        /* every view ray is the eye's -Z in the world (common/view.glsl) */
        vec3 axis = {-v->view[0][2], -v->view[1][2], -v->view[2][2]};
        glm_vec3_normalize(axis);
        memcpy(v->view_axis, axis, sizeof axis);
        v->view_axis[3] = 1.0f;
    }
    v->width = width;
    v->height = height;
    v->out = out;
    v->back.band = 0; /* until a back-face pass says otherwise */
    v->back.width = width;
    v->back.height = height;
    sc->count = fd->glass_count;
    sc->drawn = 0;
    stats->glass_count = fd->glass_count;
    for (i = 0; i < fd->glass_count; i++) {
        snell_status st = build_object(ctx, &fd->glass[i], i, sc, &stats->glass[i]);
        if (st != SNELL_OK) return st;
    }
    for (i = 0; i < sc->drawn; i++) stats->glass[sc->order[i]].draw_order = i;
    return SNELL_OK;
}

/* The object's mesh analysis (cached on the mesh); NULL if it fails (the
 * failure is logged once, when the mesh caches it). */
static const snell_mesh_analysis *analysis_of(snell__object *o, snell_object_stats *st)
{
    const snell_mesh_analysis *an = NULL;
    if (!o->analysis && snell__mesh_analysis(o->mesh, &an) == SNELL_OK) o->analysis = an;
    if (o->analysis) st->hidden_fraction = o->analysis->hidden_fraction;
    return o->analysis;
}

int snell__auto_order(const snell__device_cost *dev, int cls, const snell__method *order[])
{
    int i, j, n = snell_method_count();
    for (i = 0; i < n; i++) {
        const snell__method *m = snell__method_get(snell_method_info_at(i)->method);
        float c = dev ? dev->cost[m->info->method][cls] : 0.0f;
        for (j = i; j > 0 && c > 0.0f; j--) {
            float p = dev->cost[order[j - 1]->info->method][cls];
            if (p > 0.0f && p <= c) break;
            order[j] = order[j - 1];
        }
        order[j] = m;
    }
    return n;
}

snell_status snell__scene_choose(snell_ctx *ctx, snell__object *o, snell__method_state_fn get_state, void *user,
                                 const snell__method **method, void **state, snell_object_stats *st)
{
    const snell_glass_material *g = &o->glass->material;
    const snell__method *best = NULL, *fallback = NULL;
    void *best_state = NULL, *fallback_state = NULL;
    char why[SNELL_REASON_SIZE], rejected[SNELL_REASON_SIZE] = "", fallback_why[SNELL_REASON_SIZE] = "";
    char runs[SNELL_REASON_SIZE] = "";
    const snell__method *order[SNELL_METHOD_COUNT_];
    snell_status s;
    int i, n_order;

    if (g->thickness > 0.0f || g->method != SNELL_METHOD_AUTO) {
        /* A thin wall has no interior: every method reduces to the slab model. */
        const snell__method *m = snell__method_get(g->thickness > 0.0f ? SNELL_METHOD_SINGLE : g->method);
        const snell_mesh_analysis *an = NULL;
        snell__fit fit = SNELL__FIT_ADEQUATE;
        if (m->needs_analysis) an = analysis_of(o, st);
        else st->skipped |= SNELL_SKIP_ANALYSIS;
        if (m->fit) fit = m->fit(an, o->glass, why, sizeof why);
        if ((s = get_state(user, m, state)) != SNELL_OK) return s;
        *method = m;
        st->method_used = m->info->method;
        if (o->budget_note)
            snell__why(st->reason, sizeof st->reason, "auto by budget: %s", o->budget_note);
        else if (g->thickness > 0.0f)
            snell__why(st->reason, sizeof st->reason, "%s%s: %s", g->method == SNELL_METHOD_AUTO ? "auto" : "thin wall",
                       g->method == SNELL_METHOD_AUTO ? "" : " (any method)", why);
        else if (fit == SNELL__FIT_FAILS) {
            st->warning = 1;
            snell__why(st->reason, sizeof st->reason, "requested, but it %s", why);
        } else
            snell__why(st->reason, sizeof st->reason, "requested (%s)", why);
        return SNELL_OK;
    }
    /* AUTO: the cheapest adequate method, in the device's cost order where it is modelled */
    n_order = snell__auto_order(ctx->cost, ctx->cost ? snell__budget_class(analysis_of(o, st), o->glass) : 0, order);
    for (i = 0; i < n_order && !best; i++) {
        const snell__method *m = order[i];
        snell__fit fit = SNELL__FIT_ADEQUATE;
        void *ms = NULL;
        size_t n = strlen(rejected);
        if (m->fit) fit = m->fit(m->needs_analysis ? analysis_of(o, st) : NULL, o->glass, why, sizeof why);
        if (fit != SNELL__FIT_FAILS && (s = get_state(user, m, &ms)) != SNELL_OK) {
            if (s == SNELL_E_NOMEM) return s; /* not the device's fault: no fallback */
            snell__why(why, sizeof why, "unavailable on this device: %s", snell_last_error(ctx));
            fit = SNELL__FIT_FAILS;
        }
        if (fit == SNELL__FIT_ADEQUATE) {
            best = m;
            best_state = ms;
        } else if (fit == SNELL__FIT_RUNS && !fallback) {
            fallback = m;
            fallback_state = ms;
            snell__why(fallback_why, sizeof fallback_why, "%s", why);
        } else if (fit == SNELL__FIT_RUNS) {
            size_t r = strlen(runs);
            snell__why(runs + r, sizeof runs - r, "%s%s %s", r ? "; " : "", m->info->name, why);
        } else
            snell__why(rejected + n, sizeof rejected - n, "%s%s %s", n ? "; " : "", m->info->name, why);
    }
    /* what fails the mesh first (it says what the mesh lacks), then what runs but is not picked */
    if (runs[0]) {
        size_t n = strlen(rejected);
        snell__why(rejected + n, sizeof rejected - n, "%s%s", n ? "; " : "", runs);
    }
    if (best) {
        *method = best;
        *state = best_state;
        snell__why(st->reason, sizeof st->reason, "auto: %s%s%s", why, ctx->cost ? "; cheapest on " : "",
                   ctx->cost ? ctx->cost->name : "");
    } else if (fallback) {
        *method = fallback;
        *state = fallback_state;
        snell__why(st->reason, sizeof st->reason, "auto fallback (%s): %s", fallback_why, rejected);
    } else
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "glass %d: no method can draw it: %s", o->index, rejected);
    st->method_used = (*method)->info->method;
    return SNELL_OK;
}
