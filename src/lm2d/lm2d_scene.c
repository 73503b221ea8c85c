/* SPDX-License-Identifier: MIT */
#define _XOPEN_SOURCE 700 /* realpath */
/* lm2d_scene.c — 2D scene objects, lights, CSV polygons and the text scene
 * format; flattening into one edge array with normals (Brückner 6.2.1-6.2.2). */
#include "lm2d/lm2d_scene.h"
#include "core/ctx.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LM2D_MAX_FILE (64u << 20)
#define LM2D_MAX_POINTS 1000000
/* Points all the objects of one scene file may hold. Each "object FILE.csv"
 * line of a few bytes reads a CSV of up to LM2D_MAX_POINTS points (64 MiB),
 * so without it a scene file's cost would not be bounded by its own size: a
 * 20 KB file naming one 1M-point CSV a thousand times would parse 2e9 bytes
 * and hold 8 GB of points. Beyond it: SNELL_E_LIMIT, after at most
 * one CSV more than the bound. */
#define LM2D_MAX_SCENE_POINTS (4 * LM2D_MAX_POINTS)
#define LM2D_MAX_RAYS 100000000
#define LM2D_PI 3.14159265358979323846f

snell_material2d lm2d_material_resolve(const snell_material2d *m)
{
    snell_material2d r = *m;
    if (r.ior == 0.0f) r.ior = 1.0f;
    if (r.color[0] == 0.0f && r.color[1] == 0.0f && r.color[2] == 0.0f) r.color[0] = r.color[1] = r.color[2] = 1.0f;
    return r;
}

static snell_status check_material(const snell_ctx *ctx, const snell_material2d *m)
{
    int k;
    if (!(m->transmission >= 0.0f && m->transmission <= 1.0f) || !(m->absorption >= 0.0f && m->absorption <= 1.0f) ||
        !(m->diffuse >= 0.0f && m->diffuse <= 1.0f))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d: material t, d, a must lie in [0,1] (t=%g d=%g a=%g)",
                           (double)m->transmission, (double)m->diffuse, (double)m->absorption);
    if (!(m->opaqueness >= 0.0f) || !isfinite(m->opaqueness))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d: opaqueness must be finite and >= 0");
    if (!(m->ior == 0.0f || (m->ior >= 1.0f && m->ior <= 10.0f)))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d: ior %g outside [1,10] (0 = 1)", (double)m->ior);
    for (k = 0; k < 3; k++)
        if (!(m->color[k] >= 0.0f && m->color[k] <= 1.0f))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d: material colour must lie in [0,1]");
    if (!(m->smooth_angle >= 0.0f && m->smooth_angle <= LM2D_PI))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d: smooth_angle must lie in [0,pi]");
    return SNELL_OK;
}

snell_status snell_scene2d_create(snell_ctx *ctx, snell_scene2d **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    snell_scene2d *s;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_scene2d_create: out is NULL");
    *out = NULL;
    s = (snell_scene2d *)snell__calloc(al, 1, sizeof *s);
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "snell_scene2d_create: out of memory");
    s->ctx = ctx;
    snell__ctx_retain(ctx); /* s->al lives in ctx: released by snell_scene2d_destroy */
    s->al = al;
    s->geom_dirty = 1;
    *out = s;
    return SNELL_OK;
}

void snell_scene2d_destroy(snell_scene2d *s)
{
    snell_ctx *ctx;
    int i;
    if (!s) return;
    for (i = 0; i < s->n_objs; i++) snell__free(s->al, s->objs[i].pts);
    snell__free(s->al, s->objs);
    snell__free(s->al, s->lights);
    snell__free(s->al, s->edges);
    lm2d_bvh_free(s->al, &s->bvh);
    ctx = s->ctx;
    snell__free(s->al, s);
    snell__ctx_release(ctx);
}

snell_status snell_scene2d_set_bvh_leaf_size(snell_scene2d *s, int leaf_size)
{
    if (!s || leaf_size < 0 || leaf_size > LM2D_BVH_MAX_LEAF)
        return snell__fail(s ? s->ctx : NULL, SNELL_E_INVALID_ARG, "scene2d: leaf size %d outside [0,%d]", leaf_size,
                           LM2D_BVH_MAX_LEAF);
    if (s->leaf_size != leaf_size) {
        s->leaf_size = leaf_size;
        s->geom_dirty = 1; /* same geometry, new tree: paths stay valid, no version bump */
    }
    return SNELL_OK;
}

int snell_scene2d_object_count(const snell_scene2d *s) { return s ? s->n_objs : 0; }
int snell_scene2d_light_count(const snell_scene2d *s) { return s ? s->n_lights : 0; }
int snell_scene2d_edge_count(const snell_scene2d *s)
{
    int i, n = 0;
    if (!s) return 0;
    for (i = 0; i < s->n_objs; i++) n += s->objs[i].n;
    return n;
}

static void object_bounds(lm2d_object *o)
{
    int i;
    o->bmin[0] = o->bmin[1] = FLT_MAX;
    o->bmax[0] = o->bmax[1] = -FLT_MAX;
    for (i = 0; i < o->n; i++) {
        float x = o->pts[2 * i] + o->offset[0], y = o->pts[2 * i + 1] + o->offset[1];
        if (x < o->bmin[0]) o->bmin[0] = x;
        if (y < o->bmin[1]) o->bmin[1] = y;
        if (x > o->bmax[0]) o->bmax[0] = x;
        if (y > o->bmax[1]) o->bmax[1] = y;
    }
}

static void note_change(snell_scene2d *s, const float lo[2], const float hi[2])
{
    int k;
    if (!s->changed_any) {
        s->changed_base = s->geom_version;
        s->changed_any = 1;
        for (k = 0; k < 2; k++) {
            s->changed_min[k] = lo[k];
            s->changed_max[k] = hi[k];
        }
    } else {
        for (k = 0; k < 2; k++) {
            if (lo[k] < s->changed_min[k]) s->changed_min[k] = lo[k];
            if (hi[k] > s->changed_max[k]) s->changed_max[k] = hi[k];
        }
    }
    s->geom_version++;
    s->geom_dirty = 1;
}

snell_status snell_scene2d_add_object(snell_scene2d *s, const snell_object2d_desc *desc, int *id)
{
    lm2d_object o;
    int i, n = 0;
    double area = 0.0;
    snell_status st;
    if (!s || !desc) return snell__fail(s ? s->ctx : NULL, SNELL_E_INVALID_ARG, "scene2d_add_object: NULL argument");
    if (!desc->points || desc->point_count < 3)
        return snell__fail(s->ctx, SNELL_E_INVALID_ARG, "scene2d_add_object: need at least 3 points (got %d)",
                           desc->point_count);
    if (desc->point_count > LM2D_MAX_POINTS)
        return snell__fail(s->ctx, SNELL_E_LIMIT, "scene2d_add_object: %d points (limit %d)", desc->point_count,
                           LM2D_MAX_POINTS);
    if (!isfinite(desc->offset[0]) || !isfinite(desc->offset[1]))
        return snell__fail(s->ctx, SNELL_E_INVALID_ARG, "scene2d_add_object: offset not finite");
    if ((st = check_material(s->ctx, &desc->material)) != SNELL_OK) return st;
    memset(&o, 0, sizeof o);
    o.pts = (float *)snell__calloc(s->al, (size_t)desc->point_count, 2 * sizeof(float));
    if (!o.pts) return snell__fail(s->ctx, SNELL_E_NOMEM, "scene2d_add_object: out of memory");
    for (i = 0; i < desc->point_count; i++) {
        float x = desc->points[2 * i], y = desc->points[2 * i + 1];
        if (!isfinite(x) || !isfinite(y) || fabsf(x) > 1e7f || fabsf(y) > 1e7f) {
            snell__free(s->al, o.pts);
            return snell__fail(s->ctx, SNELL_E_INVALID_ARG, "scene2d_add_object: point %d is not finite or beyond 1e7",
                               i);
        }
        /* zero-length edges have no normal: drop repeated points */
        if (n > 0 && o.pts[2 * n - 2] == x && o.pts[2 * n - 1] == y) continue;
        o.pts[2 * n] = x;
        o.pts[2 * n + 1] = y;
        n++;
    }
    while (n > 1 && o.pts[0] == o.pts[2 * n - 2] && o.pts[1] == o.pts[2 * n - 1]) n--; /* explicit closing point */
    for (i = 0; i < n; i++) {
        int j = (i + 1) % n;
        area += (double)o.pts[2 * i] * o.pts[2 * j + 1] - (double)o.pts[2 * j] * o.pts[2 * i + 1];
    }
    if (n < 3 || area == 0.0) {
        snell__free(s->al, o.pts);
        return snell__fail(s->ctx, SNELL_E_INVALID_ARG, "scene2d_add_object: degenerate polygon (%d distinct points, area 0)",
                           n);
    }
    o.n = n;
    o.mat = lm2d_material_resolve(&desc->material);
    o.offset[0] = desc->offset[0];
    o.offset[1] = desc->offset[1];
    object_bounds(&o);
    if (s->n_objs == s->cap_objs) {
        int cap = s->cap_objs ? s->cap_objs * 2 : 8;
        lm2d_object *p = (lm2d_object *)snell__realloc(s->al, s->objs, (size_t)cap * sizeof *p);
        if (!p) {
            snell__free(s->al, o.pts);
            return snell__fail(s->ctx, SNELL_E_NOMEM, "scene2d_add_object: out of memory");
        }
        s->objs = p;
        s->cap_objs = cap;
    }
    s->objs[s->n_objs] = o;
    if (id) *id = s->n_objs;
    s->n_objs++;
    note_change(s, o.bmin, o.bmax);
    return SNELL_OK;
}

snell_status snell_scene2d_set_object_offset(snell_scene2d *s, int id, const float offset[2])
{
    lm2d_object *o;
    float lo[2], hi[2];
    if (!s || !offset || id < 0 || id >= s->n_objs)
        return snell__fail(s ? s->ctx : NULL, SNELL_E_INVALID_ARG, "scene2d_set_object_offset: bad object %d", id);
    if (!isfinite(offset[0]) || !isfinite(offset[1]))
        return snell__fail(s->ctx, SNELL_E_INVALID_ARG, "scene2d_set_object_offset: offset not finite");
    o = &s->objs[id];
    if (o->offset[0] == offset[0] && o->offset[1] == offset[1]) return SNELL_OK;
    lo[0] = o->bmin[0];
    lo[1] = o->bmin[1];
    hi[0] = o->bmax[0];
    hi[1] = o->bmax[1];
    o->offset[0] = offset[0];
    o->offset[1] = offset[1];
    object_bounds(o);
    note_change(s, lo, hi);
    note_change(s, o->bmin, o->bmax);
    return SNELL_OK;
}

static snell_status resolve_light(const snell_ctx *ctx, const snell_light2d_desc *in, snell_light2d_desc *d)
{
    int k;
    *d = *in;
    if ((unsigned)d->type > SNELL_LIGHT2D_BEAM)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d light: unknown type %d", (int)d->type);
    for (k = 0; k < 2; k++)
        if (!isfinite(d->position[k]) || !isfinite(d->end[k]))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d light: position/end not finite");
    if (!isfinite(d->direction) || !(d->spread >= 0.0f && d->spread <= 2.0f * LM2D_PI + 1e-4f))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d light: direction not finite or spread outside [0, 2 pi]");
    if (!(d->power >= 0.0f) || !isfinite(d->power))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d light: power must be finite and >= 0");
    if (d->rays < 0 || d->rays > LM2D_MAX_RAYS)
        return snell__fail(ctx, SNELL_E_LIMIT, "scene2d light: rays %d outside [0, %d]", d->rays, LM2D_MAX_RAYS);
    for (k = 0; k < 3; k++)
        if (!(d->color[k] >= 0.0f) || !isfinite(d->color[k]))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d light: colour must be finite and >= 0");
    if (d->type != SNELL_LIGHT2D_POINT && d->position[0] == d->end[0] && d->position[1] == d->end[1])
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "scene2d light: bar/beam needs position != end");
    if (d->rays == 0) d->rays = 25000;
    if (d->color[0] == 0.0f && d->color[1] == 0.0f && d->color[2] == 0.0f) d->color[0] = d->color[1] = d->color[2] = 1.0f;
    if (d->spread == 0.0f) d->spread = d->type == SNELL_LIGHT2D_POINT ? 2.0f * LM2D_PI : LM2D_PI;
    if (d->type == SNELL_LIGHT2D_BAR && d->spread > LM2D_PI) d->spread = LM2D_PI;
    return SNELL_OK;
}

snell_status snell_scene2d_add_light(snell_scene2d *s, const snell_light2d_desc *desc, int *id)
{
    snell_light2d_desc d;
    snell_status st;
    if (!s || !desc) return snell__fail(s ? s->ctx : NULL, SNELL_E_INVALID_ARG, "scene2d_add_light: NULL argument");
    if ((st = resolve_light(s->ctx, desc, &d)) != SNELL_OK) return st;
    if (s->n_lights == s->cap_lights) {
        int cap = s->cap_lights ? s->cap_lights * 2 : 4;
        lm2d_light *p = (lm2d_light *)snell__realloc(s->al, s->lights, (size_t)cap * sizeof *p);
        if (!p) return snell__fail(s->ctx, SNELL_E_NOMEM, "scene2d_add_light: out of memory");
        s->lights = p;
        s->cap_lights = cap;
    }
    s->lights[s->n_lights].d = d;
    s->lights[s->n_lights].version = 1;
    if (id) *id = s->n_lights;
    s->n_lights++;
    return SNELL_OK;
}

snell_status snell_scene2d_set_light(snell_scene2d *s, int id, const snell_light2d_desc *desc)
{
    snell_light2d_desc d;
    snell_status st;
    if (!s || !desc || id < 0 || id >= s->n_lights)
        return snell__fail(s ? s->ctx : NULL, SNELL_E_INVALID_ARG, "scene2d_set_light: bad light %d", id);
    if ((st = resolve_light(s->ctx, desc, &d)) != SNELL_OK) return st;
    if (memcmp(&d, &s->lights[id].d, sizeof d) == 0) return SNELL_OK;
    s->lights[id].d = d;
    s->lights[id].version++;
    return SNELL_OK;
}

/* ------------------------------------------------------------ edges + BVH */
static void edge_normal(const float *a, const float *b, int ccw, float n[2])
{
    float ex = b[0] - a[0], ey = b[1] - a[1], l = sqrtf(ex * ex + ey * ey);
    /* outward = edge rotated by -pi/2 for positive signed area (eq. 2.1), +pi/2 otherwise */
    n[0] = (ccw ? ey : -ey) / l;
    n[1] = (ccw ? -ex : ex) / l;
}

snell_status lm2d_scene_prepare(snell_scene2d *s)
{
    int i, j, total = 0, e = 0;
    float *segs;
    snell_status st;
    if (!s->geom_dirty) return SNELL_OK;
    total = snell_scene2d_edge_count(s);
    if (total > s->cap_edges) {
        lm2d_edge *p = (lm2d_edge *)snell__realloc(s->al, s->edges, (size_t)total * sizeof *p);
        if (!p) return snell__fail(s->ctx, SNELL_E_NOMEM, "scene2d: out of memory for %d edges", total);
        s->edges = p;
        s->cap_edges = total;
    }
    for (i = 0; i < s->n_objs; i++) {
        const lm2d_object *o = &s->objs[i];
        double area = 0.0;
        int ccw, n = o->n;
        float cos_smooth = cosf(o->mat.smooth_angle);
        for (j = 0; j < n; j++) {
            int k = (j + 1) % n;
            area += (double)o->pts[2 * j] * o->pts[2 * k + 1] - (double)o->pts[2 * k] * o->pts[2 * j + 1];
        }
        ccw = area > 0.0;
        for (j = 0; j < n; j++) {
            lm2d_edge *ed = &s->edges[e + j];
            const float *a = o->pts + 2 * j, *b = o->pts + 2 * ((j + 1) % n);
            ed->p1[0] = a[0] + o->offset[0];
            ed->p1[1] = a[1] + o->offset[1];
            ed->p2[0] = b[0] + o->offset[0];
            ed->p2[1] = b[1] + o->offset[1];
            edge_normal(a, b, ccw, ed->ng);
            ed->obj = i;
        }
        /* Point normals (6.2.1.1): two per vertex, merged where the outline is smooth. */
        for (j = 0; j < n; j++) {
            lm2d_edge *in = &s->edges[e + (j + n - 1) % n], *out = &s->edges[e + j];
            float c = in->ng[0] * out->ng[0] + in->ng[1] * out->ng[1];
            if (o->mat.smooth_angle > 0.0f && c >= cos_smooth && c > -0.999f) {
                float sx = in->ng[0] + out->ng[0], sy = in->ng[1] + out->ng[1], l = sqrtf(sx * sx + sy * sy);
                in->n2[0] = out->n1[0] = sx / l;
                in->n2[1] = out->n1[1] = sy / l;
            } else {
                in->n2[0] = in->ng[0];
                in->n2[1] = in->ng[1];
                out->n1[0] = out->ng[0];
                out->n1[1] = out->ng[1];
            }
        }
        e += n;
    }
    s->n_edges = total;
    lm2d_bvh_free(s->al, &s->bvh);
    segs = (float *)snell__calloc(s->al, (size_t)(total ? total : 1), 4 * sizeof(float));
    if (!segs) return snell__fail(s->ctx, SNELL_E_NOMEM, "scene2d: out of memory");
    for (i = 0; i < total; i++) {
        memcpy(segs + 4 * i, s->edges[i].p1, 2 * sizeof(float));
        memcpy(segs + 4 * i + 2, s->edges[i].p2, 2 * sizeof(float));
    }
    st = lm2d_bvh_build(s->ctx, s->al, segs, total, s->leaf_size ? s->leaf_size : LM2D_BVH_DEFAULT_LEAF, &s->bvh);
    snell__free(s->al, segs);
    if (st != SNELL_OK) return st;
    s->geom_dirty = 0;
    return SNELL_OK;
}

/* ------------------------------------------------------------------ files */
snell_status lm2d_read_file(const snell_ctx *ctx, const snell_alloc *al, const char *path, char **text, size_t *size)
{
    FILE *f;
    long len;
    char *buf;
    const char *why;
    int opened;
    *text = NULL;
    *size = 0;
    f = snell__fopen_regular(path, &opened, &why);
    if (!f && !opened) return snell__fail(ctx, SNELL_E_IO, "cannot open \"%s\": %s", path, why);
    if (!f) return snell__fail(ctx, SNELL_E_IO, "\"%s\" is %s", path, why);
    if (fseek(f, 0, SEEK_END) != 0 || (len = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return snell__fail(ctx, SNELL_E_IO, "cannot read \"%s\" (not a regular file?)", path);
    }
    if ((unsigned long)len > LM2D_MAX_FILE) {
        fclose(f);
        return snell__fail(ctx, SNELL_E_LIMIT, "\"%s\" is larger than %u bytes", path, LM2D_MAX_FILE);
    }
    buf = (char *)snell__malloc(al, (size_t)len + 1);
    if (!buf) {
        fclose(f);
        return snell__fail(ctx, SNELL_E_NOMEM, "out of memory reading \"%s\"", path);
    }
    if (len > 0 && fread(buf, 1, (size_t)len, f) != (size_t)len) {
        fclose(f);
        snell__free(al, buf);
        return snell__fail(ctx, SNELL_E_IO, "short read on \"%s\"", path);
    }
    fclose(f);
    buf[len] = '\0';
    *text = buf;
    *size = (size_t)len;
    return SNELL_OK;
}

/* Parses a float that must span [s, end) exactly. */
static int parse_float(const char *s, const char *end, float *out)
{
    char tmp[64];
    char *e;
    double v;
    size_t n = (size_t)(end - s);
    if (n == 0 || n >= sizeof tmp) return 0;
    memcpy(tmp, s, n);
    tmp[n] = '\0';
    errno = 0;
    v = strtod(tmp, &e);
    if (e != tmp + n || errno == ERANGE || !isfinite(v) || fabs(v) > 1e30) return 0;
    *out = (float)v;
    return 1;
}

static const char *trim_left(const char *a, const char *b)
{
    while (a < b && (*a == ' ' || *a == '\t' || *a == '\r')) a++;
    return a;
}

static const char *trim_right(const char *a, const char *b)
{
    while (b > a && (b[-1] == ' ' || b[-1] == '\t' || b[-1] == '\r')) b--;
    return b;
}

snell_status lm2d_parse_csv(const snell_ctx *ctx, const snell_alloc *al, const char *text, size_t size,
                            const char *name, float **pts, int *n)
{
    const char *p = text, *end = text + size;
    int line = 0, count = 0, cap = 0, header_ok = 1;
    float *out = NULL;
    *pts = NULL;
    *n = 0;
    if (memchr(text, '\0', size))
        return snell__fail(ctx, SNELL_E_PARSE, "%s: binary data (NUL byte) in CSV", name);
    while (p < end) {
        const char *eol = (const char *)memchr(p, '\n', (size_t)(end - p));
        const char *a, *b, *sep;
        float x, y;
        if (!eol) eol = end;
        line++;
        a = trim_left(p, eol);
        b = trim_right(a, eol);
        p = eol + 1;
        if (a == b || *a == '#') continue;
        sep = a;
        while (sep < b && *sep != ',' && *sep != ';') sep++;
        if (sep == b) {
            snell__free(al, out);
            return snell__fail(ctx, SNELL_E_PARSE, "%s:%d: expected \"x,y\"", name, line);
        }
        if (!parse_float(trim_left(a, sep), trim_right(a, sep), &x) ||
            !parse_float(trim_left(sep + 1, b), trim_right(sep + 1, b), &y)) {
            /* one non-numeric header line ("x,y") before the first point is allowed */
            if (header_ok && count == 0 && isalpha((unsigned char)*a)) {
                header_ok = 0;
                continue;
            }
            snell__free(al, out);
            /* the line itself is not quoted: messages show no file content */
            return snell__fail(ctx, SNELL_E_PARSE, "%s:%d: not two finite numbers \"x,y\"", name, line);
        }
        header_ok = 0;
        if (count >= LM2D_MAX_POINTS) {
            snell__free(al, out);
            return snell__fail(ctx, SNELL_E_LIMIT, "%s: more than %d points", name, LM2D_MAX_POINTS);
        }
        if (count == cap) {
            int nc = cap ? cap * 2 : 64;
            float *q = (float *)snell__realloc(al, out, (size_t)nc * 2 * sizeof(float));
            if (!q) {
                snell__free(al, out);
                return snell__fail(ctx, SNELL_E_NOMEM, "%s: out of memory", name);
            }
            out = q;
            cap = nc;
        }
        out[2 * count] = x;
        out[2 * count + 1] = y;
        count++;
    }
    if (count < 3) {
        snell__free(al, out);
        return snell__fail(ctx, SNELL_E_PARSE, "%s: a polygon needs at least 3 points (found %d)", name, count);
    }
    *pts = out;
    *n = count;
    return SNELL_OK;
}

snell_status snell_scene2d_add_object_csv(snell_scene2d *s, const char *path, const snell_material2d *material,
                                          const float offset[2], int *id)
{
    char *text;
    size_t size;
    float *pts;
    int n;
    snell_status st;
    snell_object2d_desc d;
    if (!s || !path) return snell__fail(s ? s->ctx : NULL, SNELL_E_INVALID_ARG, "scene2d_add_object_csv: NULL argument");
    if ((st = lm2d_read_file(s->ctx, s->al, path, &text, &size)) != SNELL_OK) return st;
    st = lm2d_parse_csv(s->ctx, s->al, text, size, path, &pts, &n);
    snell__free(s->al, text);
    if (st != SNELL_OK) return st;
    memset(&d, 0, sizeof d);
    d.points = pts;
    d.point_count = n;
    if (material) d.material = *material;
    if (offset) {
        d.offset[0] = offset[0];
        d.offset[1] = offset[1];
    }
    st = snell_scene2d_add_object(s, &d, id);
    snell__free(s->al, pts);
    return st;
}

/* ------------------------------------------------------------ text scenes */
#define MAX_TOKENS 4096

typedef struct tok_line {
    const char *tok[MAX_TOKENS];
    int len[MAX_TOKENS];
    int n;
} tok_line;

static int tok_is(const tok_line *t, int i, const char *s)
{
    return i < t->n && (size_t)t->len[i] == strlen(s) && strncmp(t->tok[i], s, (size_t)t->len[i]) == 0;
}

static int tok_float(const tok_line *t, int i, float *v)
{
    return i < t->n && parse_float(t->tok[i], t->tok[i] + t->len[i], v);
}

/* Reads `count` numbers after key at index *i; advances *i. */
static snell_status key_floats(const snell_scene2d *s, const tok_line *t, int *i, int count, float *v,
                               const char *name, int line)
{
    int k;
    for (k = 0; k < count; k++)
        if (!tok_float(t, *i + 1 + k, &v[k]))
            return snell__fail(s->ctx, SNELL_E_PARSE, "%s:%d: \"%.*s\" needs %d number(s)", name, line, t->len[*i],
                               t->tok[*i], count);
    *i += count + 1;
    return SNELL_OK;
}

static snell_status parse_material(snell_scene2d *s, const tok_line *t, int i, snell_material2d *m, float offset[2],
                                   const char *name, int line)
{
    snell_status st = SNELL_OK;
    float deg;
    while (i < t->n && st == SNELL_OK) {
        if (tok_is(t, i, "t")) st = key_floats(s, t, &i, 1, &m->transmission, name, line);
        else if (tok_is(t, i, "o")) st = key_floats(s, t, &i, 1, &m->opaqueness, name, line);
        else if (tok_is(t, i, "d")) st = key_floats(s, t, &i, 1, &m->diffuse, name, line);
        else if (tok_is(t, i, "a")) st = key_floats(s, t, &i, 1, &m->absorption, name, line);
        else if (tok_is(t, i, "ior")) st = key_floats(s, t, &i, 1, &m->ior, name, line);
        else if (tok_is(t, i, "color")) st = key_floats(s, t, &i, 3, m->color, name, line);
        else if (tok_is(t, i, "offset")) st = key_floats(s, t, &i, 2, offset, name, line);
        else if (tok_is(t, i, "smooth")) {
            st = key_floats(s, t, &i, 1, &deg, name, line);
            m->smooth_angle = deg * LM2D_PI / 180.0f;
        } else
            return snell__fail(s->ctx, SNELL_E_PARSE,
                               "%s:%d: unknown object key (word %d; keys: t o d a ior color offset smooth)", name, line,
                               i + 1);
    }
    return st;
}

/* Prefixes "file:line: " to the message a nested call left (copied first: the
 * message lives in the buffer snell__fail writes to). */
static snell_status rewrap(const snell_scene2d *s, snell_status st, const char *name, int line)
{
    char msg[768];
    snprintf(msg, sizeof msg, "%s", snell_last_error(s->ctx));
    return snell__fail(s->ctx, st, "%s:%d: %s", name, line, msg);
}

static snell_status parse_light(snell_scene2d *s, const tok_line *t, const char *name, int line)
{
    snell_light2d_desc d;
    snell_status st = SNELL_OK;
    int i = 2;
    float deg, rays, two;
    memset(&d, 0, sizeof d);
    if (tok_is(t, 1, "point")) d.type = SNELL_LIGHT2D_POINT;
    else if (tok_is(t, 1, "bar")) d.type = SNELL_LIGHT2D_BAR;
    else if (tok_is(t, 1, "beam")) d.type = SNELL_LIGHT2D_BEAM;
    else return snell__fail(s->ctx, SNELL_E_PARSE, "%s:%d: light type must be point, bar or beam", name, line);
    d.power = 1.0f;
    while (i < t->n && st == SNELL_OK) {
        if (tok_is(t, i, "pos")) st = key_floats(s, t, &i, 2, d.position, name, line);
        else if (tok_is(t, i, "end")) st = key_floats(s, t, &i, 2, d.end, name, line);
        else if (tok_is(t, i, "power")) st = key_floats(s, t, &i, 1, &d.power, name, line);
        else if (tok_is(t, i, "color")) st = key_floats(s, t, &i, 3, d.color, name, line);
        else if (tok_is(t, i, "dir")) {
            st = key_floats(s, t, &i, 1, &deg, name, line);
            d.direction = deg * LM2D_PI / 180.0f;
        } else if (tok_is(t, i, "spread")) {
            st = key_floats(s, t, &i, 1, &deg, name, line);
            d.spread = deg * LM2D_PI / 180.0f;
        } else if (tok_is(t, i, "rays")) {
            st = key_floats(s, t, &i, 1, &rays, name, line);
            if (st == SNELL_OK && (rays < 0.0f || rays > (float)LM2D_MAX_RAYS || rays != floorf(rays)))
                return snell__fail(s->ctx, SNELL_E_PARSE, "%s:%d: rays must be an integer in [0, %d]", name, line,
                                   LM2D_MAX_RAYS);
            if (st == SNELL_OK) d.rays = (int)rays; /* only once range-checked (found by fuzzing) */
        } else if (tok_is(t, i, "two_sided")) {
            st = key_floats(s, t, &i, 1, &two, name, line);
            d.two_sided = two != 0.0f;
        } else
            return snell__fail(s->ctx, SNELL_E_PARSE,
                               "%s:%d: unknown light key (word %d; keys: pos end power color dir spread rays two_sided)",
                               name, line, i + 1);
    }
    if (st != SNELL_OK) return st;
    st = snell_scene2d_add_light(s, &d, NULL);
    if (st != SNELL_OK) return rewrap(s, st, name, line);
    return SNELL_OK;
}

/* A scene file names CSVs inside its own folder only, as glTF URIs (a scene
 * from elsewhere must not read ../secret or a link out of the folder). A
 * file that does not exist is left for the read to report. */
static snell_status confine(const snell_scene2d *s, const char *path, const char *base, const char *name, int line)
{
    char root[PATH_MAX], real[PATH_MAX];
    size_t n;
    if (!realpath(base[0] ? base : ".", root))
        return snell__fail(s->ctx, SNELL_E_IO, "%s:%d: cannot resolve the scene's folder: %s", name, line,
                           strerror(errno));
    if (!realpath(path, real)) return SNELL_OK;
    n = strlen(root);
    if (n > 1 && (strncmp(real, root, n) != 0 || real[n] != '/'))
        return snell__fail(s->ctx, SNELL_E_IO, "%s:%d: object CSV \"%s\" is outside the scene's folder", name, line,
                           path);
    return SNELL_OK;
}

static snell_status parse_line(snell_scene2d *s, const tok_line *t, const char *name, int line, const char *base,
                               float view[4], int size[2])
{
    snell_material2d m;
    float off[2] = {0.0f, 0.0f};
    snell_status st;
    memset(&m, 0, sizeof m);
    if (tok_is(t, 0, "view")) {
        float v[4];
        int k;
        for (k = 0; k < 4; k++)
            if (!tok_float(t, 1 + k, &v[k]) || t->n != 5)
                return snell__fail(s->ctx, SNELL_E_PARSE, "%s:%d: view needs 4 numbers X0 Y0 X1 Y1", name, line);
        if (!(v[2] > v[0] && v[3] > v[1]))
            return snell__fail(s->ctx, SNELL_E_PARSE, "%s:%d: view needs X1 > X0 and Y1 > Y0", name, line);
        if (view) memcpy(view, v, sizeof v);
        return SNELL_OK;
    }
    if (tok_is(t, 0, "size")) {
        float w, h;
        if (t->n != 3 || !tok_float(t, 1, &w) || !tok_float(t, 2, &h) || w < 1 || h < 1 || w > 16384 || h > 16384 ||
            w != floorf(w) || h != floorf(h))
            return snell__fail(s->ctx, SNELL_E_PARSE, "%s:%d: size needs two integers in [1,16384]", name, line);
        if (size) {
            size[0] = (int)w;
            size[1] = (int)h;
        }
        return SNELL_OK;
    }
    if (tok_is(t, 0, "light")) return parse_light(s, t, name, line);
    if (tok_is(t, 0, "object")) {
        char path[1024];
        int n;
        if (t->n < 2) return snell__fail(s->ctx, SNELL_E_PARSE, "%s:%d: object needs a CSV file name", name, line);
        if (t->tok[1][0] == '/')
            return snell__fail(s->ctx, SNELL_E_IO, "%s:%d: object CSV must be a path relative to the scene's folder",
                               name, line);
        n = snprintf(path, sizeof path, "%s%.*s", base, t->len[1], t->tok[1]);
        if (n < 0 || (size_t)n >= sizeof path)
            return snell__fail(s->ctx, SNELL_E_LIMIT, "%s:%d: CSV path too long", name, line);
        if ((st = parse_material(s, t, 2, &m, off, name, line)) != SNELL_OK) return st;
        if ((st = confine(s, path, base, name, line)) != SNELL_OK) return st;
        st = snell_scene2d_add_object_csv(s, path, &m, off, NULL);
        if (st != SNELL_OK) return rewrap(s, st, name, line);
        return SNELL_OK;
    }
    if (tok_is(t, 0, "polygon")) {
        float pts[2 * (MAX_TOKENS / 2)];
        int i = 1, n = 0;
        snell_object2d_desc d;
        while (i < t->n && !tok_is(t, i, ";")) {
            if (!tok_float(t, i, &pts[n]))
                return snell__fail(s->ctx, SNELL_E_PARSE, "%s:%d: polygon coordinate %d is not a number", name, line,
                                   i);
            n++;
            i++;
        }
        if (n % 2 || n < 6)
            return snell__fail(s->ctx, SNELL_E_PARSE, "%s:%d: polygon needs at least 3 x y pairs", name, line);
        if ((st = parse_material(s, t, i + 1, &m, off, name, line)) != SNELL_OK) return st;
        memset(&d, 0, sizeof d);
        d.points = pts;
        d.point_count = n / 2;
        d.material = m;
        d.offset[0] = off[0];
        d.offset[1] = off[1];
        st = snell_scene2d_add_object(s, &d, NULL);
        if (st != SNELL_OK) return rewrap(s, st, name, line);
        return SNELL_OK;
    }
    /* the word is not quoted: a scene loaded from the wrong file (a key, a
     * password) would otherwise show its first word */
    return snell__fail(s->ctx, SNELL_E_PARSE,
                       "%s:%d: unknown directive (expected view, size, object, polygon or light)", name, line);
}

snell_status lm2d_scene_parse(snell_scene2d *s, const char *text, const char *name, const char *base, float view[4],
                              int size[2])
{
    const char *p = text, *end = text + strlen(text);
    int line = 0, i;
    long points = 0;
    tok_line *t = (tok_line *)snell__malloc(s->al, sizeof *t);
    snell_status st = SNELL_OK;
    if (!t) return snell__fail(s->ctx, SNELL_E_NOMEM, "%s: out of memory", name);
    while (p < end && st == SNELL_OK) {
        const char *eol = (const char *)memchr(p, '\n', (size_t)(end - p)), *q;
        if (!eol) eol = end;
        line++;
        t->n = 0;
        for (q = p; q < eol;) {
            const char *a;
            while (q < eol && isspace((unsigned char)*q)) q++;
            if (q >= eol || *q == '#') break;
            a = q;
            while (q < eol && !isspace((unsigned char)*q)) q++;
            if (t->n == MAX_TOKENS) {
                st = snell__fail(s->ctx, SNELL_E_LIMIT, "%s:%d: more than %d tokens on a line", name, line, MAX_TOKENS);
                break;
            }
            t->tok[t->n] = a;
            t->len[t->n++] = (int)(q - a);
        }
        p = eol + 1;
        if (st != SNELL_OK || t->n == 0) continue;
        i = s->n_objs;
        st = parse_line(s, t, name, line, base, view, size);
        for (; i < s->n_objs; i++) points += s->objs[i].n;
        if (st == SNELL_OK && points > LM2D_MAX_SCENE_POINTS)
            st = snell__fail(s->ctx, SNELL_E_LIMIT, "%s:%d: the scene's objects hold more than %d points", name, line,
                             LM2D_MAX_SCENE_POINTS);
    }
    snell__free(s->al, t);
    return st;
}

snell_status snell_scene2d_load(snell_ctx *ctx, const char *path, snell_scene2d **out, float view[4], int size[2])
{
    snell_scene2d *s;
    char *text, base[1024];
    const char *slash;
    size_t n;
    snell_status st;
    if (!out || !path) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_scene2d_load: NULL argument");
    *out = NULL;
    if (view) memset(view, 0, 4 * sizeof(float));
    if (size) size[0] = size[1] = 0;
    if ((st = snell_scene2d_create(ctx, &s)) != SNELL_OK) return st;
    if ((st = lm2d_read_file(ctx, s->al, path, &text, &n)) != SNELL_OK) {
        snell_scene2d_destroy(s);
        return st;
    }
    if (memchr(text, '\0', n)) {
        snell__free(s->al, text);
        snell_scene2d_destroy(s);
        return snell__fail(ctx, SNELL_E_PARSE, "%s: binary data (NUL byte) in scene file", path);
    }
    slash = strrchr(path, '/');
    if (slash && (size_t)(slash - path + 1) < sizeof base) {
        memcpy(base, path, (size_t)(slash - path + 1));
        base[slash - path + 1] = '\0';
    } else {
        base[0] = '\0';
    }
    st = lm2d_scene_parse(s, text, path, base, view, size);
    snell__free(s->al, text);
    if (st != SNELL_OK) {
        snell_scene2d_destroy(s);
        return st;
    }
    *out = s;
    return SNELL_OK;
}
