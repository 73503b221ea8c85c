/* SPDX-License-Identifier: MIT */
/* ref_scene.c — the reference tracer's scene (ref_scene.h): creation and
 * validation of the glass and opaque object lists, materials resolved by
 * snell_glass_defaults' own code (frame/material.c), one BVH over every
 * object's world triangles with the object as the BVH part, filtered
 * closest-hit queries with the GPU's smooth normals, and opaque shading. */
#include "ref/ref_scene.h"
#include "core/optics.h"
#include "ref/ref_trace.h"
#include "core/ctx.h"
#include "mesh/mesh.h"
#include "frame/material.h"
#include "frame/lighting.h"

#include <math.h>
#include <stdio.h>
#include <string.h>


/* ------------------------------------------------------------ queries */

typedef struct query {
    const snell_ref *r;
    const ref_view *v;
} query;

static int sees(const snell_ref *r, const ref_view *v, int part)
{
    if (part >= r->glass_count) return 1; /* opaque */
    if (v->medium >= 0) return part == v->medium;
    if (part == v->excl || v->glass == REF_SEE_NONE) return 0;
    return v->glass == REF_SEE_ALL || part == v->glass;
}

static int accept(uint32_t part, const void *user)
{
    const query *q = (const query *)user;
    return sees(q->r, q->v, (int)part);
}

static int sphere_hit(const snell_ref *r, const ref_sphere *sp, const double o[3], const double d[3], double tmax,
                      ref_surf *s)
{
    double oc[3] = {o[0] - sp->c[0], o[1] - sp->c[1], o[2] - sp->c[2]};
    double a = snell__ref_dot3(d, d), b = snell__ref_dot3(oc, d), c = snell__ref_dot3(oc, oc) - sp->r * sp->r, disc = b * b - a * c, q, t0, t1, t;
    int k;
    if (disc < 0.0) return 0;
    /* Stable roots: q = -(b + sign(b) sqrt(disc)); t = q / a and c / q. */
    q = -(b + (b >= 0.0 ? sqrt(disc) : -sqrt(disc)));
    if (q == 0.0) return 0;
    t0 = q / a;
    t1 = c / q;
    if (t0 > t1) {
        t = t0;
        t0 = t1;
        t1 = t;
    }
    t = t0 > r->eps ? t0 : t1;
    if (!(t > r->eps) || !(t < tmax)) return 0;
    s->t = t;
    for (k = 0; k < 3; k++) s->n[k] = o[k] + t * d[k] - sp->c[k];
    if (!snell__ref_normalize3(s->n)) return 0;
    /* Put the point exactly on the sphere (its radius error would otherwise
     * accumulate along a chain). */
    for (k = 0; k < 3; k++) {
        s->p[k] = sp->c[k] + sp->r * s->n[k];
        s->ng[k] = s->n[k];
    }
    s->prim = SNELL__BVH_NONE;
    return 1;
}

/* 0 if v admits no object at all (e.g. a ray leaving the only glass object
 * of a scene without opaque objects): no need to walk the BVH. */
static int any_seen(const snell_ref *r, const ref_view *v)
{
    if (r->opaque_count > 0 || v->medium >= 0) return 1;
    if (v->glass == REF_SEE_NONE) return 0;
    if (v->glass >= 0) return v->glass != v->excl;
    return r->glass_count > 1 || v->excl != 0;
}

int snell__ref_hit(const snell_ref *r, const double o[3], const double d[3], uint32_t skip, const ref_view *v,
                   ref_surf *s)
{
    snell__bvh_hit h;
    const uint32_t *tri;
    query q;
    double vsum[3];
    int k;
    if (!any_seen(r, v)) return 0;
    if (r->analytic) {
        int i, found = 0;
        for (i = 0; i < r->glass_count; i++)
            if (sees(r, v, i) && sphere_hit(r, &r->sph[i], o, d, found ? s->t : HUGE_VAL, s)) {
                s->object = i;
                found = 1;
            }
        return found;
    }
    q.r = r;
    q.v = v;
    if (!snell__bvh_closest_filtered(r->bvh, o, d, r->eps, HUGE_VAL, skip, accept, &q, &h)) return 0;
    tri = r->indices + 3 * (size_t)h.tri;
    s->t = h.t;
    s->prim = h.tri;
    s->object = (int)h.part < r->glass_count ? (int)h.part : -2 - ((int)h.part - r->glass_count);
    for (k = 0; k < 3; k++) {
        s->p[k] = h.p[k];
        /* Barycentric interpolation of the world vertex normals, as the GPU
         * interpolates v_world_normal (perspective-correct = barycentric). */
        s->n[k] = h.b[0] * r->normals[3 * (size_t)tri[0] + k] + h.b[1] * r->normals[3 * (size_t)tri[1] + k] +
                  h.b[2] * r->normals[3 * (size_t)tri[2] + k];
        vsum[k] = r->normals[3 * (size_t)tri[0] + k] + r->normals[3 * (size_t)tri[1] + k] +
                  r->normals[3 * (size_t)tri[2] + k];
    }
    {
        /* The plane's normal, on the side of the vertex normals (their sum:
         * not the interpolated one, which can cancel or tilt past 90 degrees). */
        const double *w = r->bvh->tri_verts + 9 * (size_t)h.entry;
        double e1[3] = {w[3] - w[0], w[4] - w[1], w[5] - w[2]}, e2[3] = {w[6] - w[0], w[7] - w[1], w[8] - w[2]};
        s->ng[0] = e1[1] * e2[2] - e1[2] * e2[1];
        s->ng[1] = e1[2] * e2[0] - e1[0] * e2[2];
        s->ng[2] = e1[0] * e2[1] - e1[1] * e2[0];
        if (!snell__ref_normalize3(s->ng)) { /* degenerate triangle (the BVH hit it edge-on) */
            s->ng[0] = -d[0];
            s->ng[1] = -d[1];
            s->ng[2] = -d[2];
            snell__ref_normalize3(s->ng);
        }
        if (snell__ref_dot3(s->ng, vsum) < 0.0)
            for (k = 0; k < 3; k++) s->ng[k] = -s->ng[k];
    }
    if (!snell__ref_normalize3(s->n)) /* opposite vertex normals cancelled: the face normal */
        memcpy(s->n, s->ng, sizeof s->n);
    return 1;
}

void snell__ref_shade_opaque(const snell_ref *r, int j, const ref_surf *s, double rgb[3])
{
    /* opaque.frag: half-Lambert light from normalize(0.3, 1, 0.2), n unflipped. */
    const double ll = sqrt(0.3 * 0.3 + 1.0 + 0.2 * 0.2), L[3] = {0.3 / ll, 1.0 / ll, 0.2 / ll};
    double l = 0.5 + 0.5 * snell__ref_dot3(s->n, L);
    int k;
    if (r->lit) {
        snell__ref_lit_irradiance(r, s, rgb);
        for (k = 0; k < 3; k++) rgb[k] *= r->opaque_color[j][k];
        return;
    }
    for (k = 0; k < 3; k++) rgb[k] = r->opaque_color[j][k] * (0.25 + 0.75 * l);
}

/* ------------------------------------------------------------ materials */

static snell_status set_material(snell_ref *r, int index, const snell_glass_material *m, const char *who)
{
    snell_glass_resolved res;
    ref_glass *g = &r->glass[index];
    snell_status st = snell__glass_resolve(m, index, &res);
    int k;
    if (st != SNELL_OK) {
        /* material.c reports without a context: pass its message on to ours. */
        char msg[256];
        snprintf(msg, sizeof msg, "%s", snell_last_error(NULL));
        return snell__fail(r->ctx, st, "%s: %s", who, msg);
    }
    g->res = res;
    g->ior = (double)res.material.ior;
    snell_optd_ior_rgb(g->ior, res.disperses ? (double)res.material.dispersion : 0.0, g->ior_rgb);
    g->thickness = (double)res.material.thickness;
    g->thin = g->thickness > 0.0;
    g->has_sigma = 0;
    for (k = 0; k < 3; k++) {
        g->sigma[k] = (double)res.absorption[k];
        if (g->sigma[k] > 0.0) g->has_sigma = 1;
        g->tint[k] = (double)res.material.tint[k];
    }
    return SNELL_OK;
}

snell_status snell_ref_set_material(snell_ref *ref, int index, const snell_glass_material *material)
{
    if (!ref) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ref_set_material: ref is NULL");
    if (index < 0 || index >= ref->glass_count)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_set_material: glass %d of %d", index,
                           ref->glass_count);
    return set_material(ref, index, material, "snell_ref_set_material");
}

/* ------------------------------------------------------------ creation */

static snell_status ref_alloc(snell_ctx *ctx, snell_ref **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    snell_ref *r = (snell_ref *)snell__calloc(al, 1, sizeof *r);
    if (!r) return snell__fail(ctx, SNELL_E_NOMEM, "reference: out of memory");
    r->ctx = ctx;
    snell__ctx_retain(ctx); /* its messages go to ctx, which may be destroyed first */
    r->alloc = *al;
    *out = r;
    return SNELL_OK;
}

/* The model of an object (NULL = identity) in double, its normal matrix N =
 * inverse-transpose of the 3x3 (column-major) and its largest column length. */
static snell_status object_model(snell_ctx *ctx, const char *kind, int i, const float *model, double M[16], double N[9],
                                 double *scale)
{
    double a, b, c, d, e, f, g, h, ii, det;
    int k;
    for (k = 0; k < 16; k++) {
        M[k] = model ? (double)model[k] : (k % 5 == 0 ? 1.0 : 0.0);
        if (!isfinite(M[k]))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: %s[%d].model is not finite", kind, i);
    }
    a = M[0], b = M[4], c = M[8], d = M[1], e = M[5], f = M[9], g = M[2], h = M[6], ii = M[10];
    det = a * (e * ii - f * h) - b * (d * ii - f * g) + c * (d * h - e * g);
    if (!(fabs(det) > 0.0) || !isfinite(det))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: %s[%d].model is singular", kind, i);
    /* N[col*3+row] = cofactor(row, col) / det of the row-major 3x3. */
    N[0] = (e * ii - f * h) / det;
    N[3] = -(d * ii - f * g) / det;
    N[6] = (d * h - e * g) / det;
    N[1] = -(b * ii - c * h) / det;
    N[4] = (a * ii - c * g) / det;
    N[7] = -(a * h - b * g) / det;
    N[2] = (b * f - c * e) / det;
    N[5] = -(a * f - c * d) / det;
    N[8] = (a * e - b * d) / det;
    *scale = 0.0;
    for (k = 0; k < 3; k++) {
        double len = sqrt(M[4 * k] * M[4 * k] + M[4 * k + 1] * M[4 * k + 1] + M[4 * k + 2] * M[4 * k + 2]);
        if (len > *scale) *scale = len;
    }
    return SNELL_OK;
}

static snell_status check_mesh(snell_ctx *ctx, const char *kind, int i, const snell_mesh *m)
{
    if (!m) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: %s[%d].mesh is NULL", kind, i);
    if (!m->triangle_count || !m->positions || !m->normals || !m->indices)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: %s[%d].mesh has no triangles", kind, i);
    return SNELL_OK;
}

static snell_status check_desc(snell_ctx *ctx, const snell_ref_desc *desc)
{
    int i, k;
    snell_status st;
    if (!desc) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: desc is NULL");
    if (desc->glass_count < 0 || desc->glass_count > SNELL_MAX_GLASS || desc->opaque_count < 0 ||
        desc->opaque_count > SNELL_MAX_OPAQUE)
        return snell__fail(ctx, SNELL_E_INVALID_ARG,
                           "snell_ref_create: glass_count %d / opaque_count %d outside 0..%d / 0..%d",
                           desc->glass_count, desc->opaque_count, SNELL_MAX_GLASS, SNELL_MAX_OPAQUE);
    if (desc->glass_count + desc->opaque_count == 0)
        return snell__fail(ctx, SNELL_E_INVALID_ARG,
                           "snell_ref_create: the scene has no objects (glass_count and opaque_count are 0)");
    if ((desc->glass_count && !desc->glass) || (desc->opaque_count && !desc->opaque))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: glass or opaque list is NULL");
    for (i = 0; i < desc->glass_count; i++)
        if ((st = check_mesh(ctx, "glass", i, desc->glass[i].mesh)) != SNELL_OK) return st;
    for (i = 0; i < desc->opaque_count; i++) {
        const float *c = desc->opaque[i].color;
        if ((st = check_mesh(ctx, "opaque", i, desc->opaque[i].mesh)) != SNELL_OK) return st;
        for (k = 0; k < 3; k++)
            if (!(c[k] >= 0.0f && c[k] <= 1.0f))
                return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: opaque[%d].color outside 0..1", i);
    }
    return SNELL_OK;
}

static void set_eps(snell_ref *r, const double lo[3], const double hi[3])
{
    /* Ray epsilon: far above the rounding of hit points (~1e-16 of the
     * coordinates), far below any feature of a sane scene. */
    double ext = 0.0;
    int k;
    for (k = 0; k < 3; k++) {
        double e = fabs(lo[k]) > fabs(hi[k]) ? fabs(lo[k]) : fabs(hi[k]);
        if (e > ext) ext = e;
    }
    r->eps = 1e-9 * (ext > 0.0 ? ext : 1.0);
}

snell_status snell_ref_create(snell_ctx *ctx, const snell_ref_desc *desc, snell_ref **out)
{
    snell__bvh_part parts[SNELL_MAX_GLASS + SNELL_MAX_OPAQUE];
    snell_ref *r = NULL;
    snell_status st;
    uint64_t nv_total = 0, nt_total = 0;
    uint32_t vbase = 0, tbase = 0;
    int np, i, k;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ref_create: out is NULL");
    *out = NULL;
    if ((st = check_desc(ctx, desc)) != SNELL_OK) return st;
    np = desc->glass_count + desc->opaque_count;
    for (i = 0; i < np; i++) {
        const snell_mesh *m = i < desc->glass_count ? desc->glass[i].mesh : desc->opaque[i - desc->glass_count].mesh;
        nv_total += m->vertex_count;
        nt_total += m->triangle_count;
    }
    if (nt_total > SNELL__BVH_MAX_TRIANGLES || nv_total > 0xfffffff0u)
        return snell__fail(ctx, SNELL_E_LIMIT,
                           "snell_ref_create: %llu triangles / %llu vertices in all exceed the limit of %u triangles",
                           (unsigned long long)nt_total, (unsigned long long)nv_total, SNELL__BVH_MAX_TRIANGLES);
    if ((st = ref_alloc(ctx, &r)) != SNELL_OK) return st;
    r->glass_count = desc->glass_count;
    r->opaque_count = desc->opaque_count;
    r->normals = (double *)snell__calloc(&r->alloc, 3 * (size_t)nv_total, sizeof(double));
    r->indices = (uint32_t *)snell__calloc(&r->alloc, 3 * (size_t)nt_total, sizeof(uint32_t));
    if (!r->normals || !r->indices) {
        snell_ref_destroy(r);
        return snell__fail(ctx, SNELL_E_NOMEM, "snell_ref_create: out of memory for %llu triangles",
                           (unsigned long long)nt_total);
    }
    for (i = 0; i < np; i++) {
        int glass = i < desc->glass_count, j = glass ? i : i - desc->glass_count;
        const snell_mesh *m = glass ? desc->glass[i].mesh : desc->opaque[j].mesh;
        const float *model = glass ? desc->glass[i].model : desc->opaque[j].model;
        double M[16] = {0}, N[9] = {0}, s = 0.0; /* zeroed: -O3 cannot see object_model fill them */
        uint32_t v, t;
        if ((st = object_model(ctx, glass ? "glass" : "opaque", j, model, M, N, &s)) != SNELL_OK) {
            snell_ref_destroy(r);
            return st;
        }
        for (v = 0; v < m->vertex_count; v++) {
            const float *n = m->normals + 3 * (size_t)v;
            double *w = r->normals + 3 * ((size_t)vbase + v);
            for (k = 0; k < 3; k++) w[k] = N[k] * n[0] + N[3 + k] * n[1] + N[6 + k] * n[2];
        }
        for (t = 0; t < 3 * m->triangle_count; t++) r->indices[3 * (size_t)tbase + t] = vbase + m->indices[t];
        parts[i].positions = m->positions;
        parts[i].vertex_count = m->vertex_count;
        parts[i].indices = m->indices;
        parts[i].triangle_count = m->triangle_count;
        parts[i].model = model;
        vbase += m->vertex_count;
        tbase += m->triangle_count;
        if (glass) {
            /* Bounding sphere as the renderer gives single.frag: the mesh's own radius. */
            ref_glass *g = &r->glass[i];
            double c[3];
            for (k = 0; k < 3; k++) c[k] = 0.5 * ((double)m->bmin[k] + (double)m->bmax[k]);
            for (k = 0; k < 3; k++) g->bs_c[k] = M[k] * c[0] + M[4 + k] * c[1] + M[8 + k] * c[2] + M[12 + k];
            g->bs_r = (double)m->bradius * s;
            if ((st = set_material(r, i, &desc->glass[i].material, "snell_ref_create")) != SNELL_OK) {
                snell_ref_destroy(r);
                return st;
            }
        } else {
            snell_opaque o;
            double bc[3];
            snell__opaque_defaults(&desc->opaque[j], &o); /* the renderer's albedo */
            for (k = 0; k < 3; k++) r->opaque_color[j][k] = (double)o.color[k];
            for (k = 0; k < 3; k++) bc[k] = 0.5 * ((double)m->bmin[k] + (double)m->bmax[k]);
            for (k = 0; k < 3; k++)
                r->opaque_bs[j][k] = M[k] * bc[0] + M[4 + k] * bc[1] + M[8 + k] * bc[2] + M[12 + k];
            r->opaque_bs[j][3] = (double)m->bradius * s;
        }
    }
    if ((st = snell__bvh_build_parts(ctx, parts, (uint32_t)np, &r->bvh)) != SNELL_OK) {
        snell_ref_destroy(r);
        return st;
    }
    set_eps(r, r->bvh->bmin, r->bvh->bmax);
    *out = r;
    return SNELL_OK;
}

snell_status snell__ref_create_spheres(snell_ctx *ctx, int count, const double *centres, const double *radii,
                                       snell_ref **out)
{
    snell_ref *r = NULL;
    snell_status st;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int i, k;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference spheres: out is NULL");
    *out = NULL;
    if (count < 1 || count > SNELL_MAX_GLASS || !centres || !radii)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference spheres: 1..%d centres and radii required",
                           SNELL_MAX_GLASS);
    for (i = 0; i < count; i++)
        if (!(radii[i] > 0.0) || !isfinite(radii[i]) || !isfinite(centres[3 * i]) || !isfinite(centres[3 * i + 1]) ||
            !isfinite(centres[3 * i + 2]))
            return snell__fail(ctx, SNELL_E_INVALID_ARG,
                               "reference spheres: sphere %d needs a finite centre and "
                               "positive radius",
                               i);
    if ((st = ref_alloc(ctx, &r)) != SNELL_OK) return st;
    r->analytic = 1;
    r->glass_count = count;
    for (i = 0; i < count; i++) {
        ref_glass *g = &r->glass[i];
        for (k = 0; k < 3; k++) {
            r->sph[i].c[k] = g->bs_c[k] = centres[3 * i + k];
            if (centres[3 * i + k] - radii[i] < lo[k]) lo[k] = centres[3 * i + k] - radii[i];
            if (centres[3 * i + k] + radii[i] > hi[k]) hi[k] = centres[3 * i + k] + radii[i];
        }
        r->sph[i].r = g->bs_r = radii[i];
        if ((st = set_material(r, i, NULL, "reference spheres")) != SNELL_OK) {
            snell_ref_destroy(r);
            return st;
        }
    }
    set_eps(r, lo, hi);
    *out = r;
    return SNELL_OK;
}

snell_status snell__ref_create_sphere(snell_ctx *ctx, const double centre[3], double radius, snell_ref **out)
{
    if (!centre) {
        if (out) *out = NULL;
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference sphere: centre is NULL");
    }
    return snell__ref_create_spheres(ctx, 1, centre, &radius, out);
}

void snell_ref_bounding_sphere(const snell_ref *ref, int index, double centre[3], double *radius)
{
    int ok = ref && index >= 0 && index < ref->glass_count, k;
    for (k = 0; k < 3; k++)
        if (centre) centre[k] = ok ? ref->glass[index].bs_c[k] : 0.0;
    if (radius) *radius = ok ? ref->glass[index].bs_r : 0.0;
}

void snell_ref_destroy(snell_ref *ref)
{
    snell_alloc al;
    if (!ref) return;
    al = ref->alloc;
    snell__ref_lit_free(ref);
    snell__ref_plane_free(ref);
    snell__ref_backdrop_free(ref);
    snell__bvh_destroy(ref->bvh);
    snell__free(&al, ref->normals);
    snell__free(&al, ref->indices);
    snell__ctx_release(ref->ctx);
    snell__free(&al, ref);
}
