/* SPDX-License-Identifier: MIT */
/* mesh.c — mesh objects from arrays: validation, smooth normals, bounds,
 * normalisation, GPU upload. Loaders live in mesh_obj.c / mesh_gltf.cpp and
 * procedural shapes in mesh_shapes.c; all of them end in snell__mesh_adopt. */
#include "mesh/mesh.h"
#include "mesh/bvh_gpu.h"
#include "core/ctx.h"
#include "core/gl.h"

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <string.h>

/* Geometry versions are unique across all meshes of the process, so caches
 * keyed on (mesh pointer, version) cannot confuse a freed mesh with a new one
 * allocated at the same address. */
static pthread_mutex_t g_version_lock = PTHREAD_MUTEX_INITIALIZER;
static unsigned g_next_version = 1;

static unsigned next_version(void)
{
    unsigned v;
    pthread_mutex_lock(&g_version_lock);
    v = g_next_version++;
    if (g_next_version == 0) g_next_version = 1; /* 0 means "never uploaded" */
    pthread_mutex_unlock(&g_version_lock);
    return v;
}

/* Box and the bounding sphere about the box centre (normalisation, the
 * renderer's absorption estimate and the reference all use it): once per
 * geometry change, not per frame. In double: with coordinates near 1e38 the
 * centre (a sum of two coordinates) and the squared distances overflow float,
 * which made the radius Inf, the normalisation scale 0 and the mesh a point.
 * A mesh whose extent or radius exceeds the float range (FLT_MAX, 3.4e38)
 * cannot be drawn or normalised: SNELL_E_LIMIT with its size. */
static snell_status compute_bounds(snell_mesh *m)
{
    double lo[3], hi[3], c[3], r2 = 0.0, r, ext = 0.0;
    uint32_t i;
    int k;
    for (k = 0; k < 3; k++) {
        lo[k] = m->vertex_count ? HUGE_VAL : 0.0;
        hi[k] = m->vertex_count ? -HUGE_VAL : 0.0;
    }
    for (i = 0; i < m->vertex_count; i++)
        for (k = 0; k < 3; k++) {
            double v = m->positions[3 * (size_t)i + k];
            if (v < lo[k]) lo[k] = v;
            if (v > hi[k]) hi[k] = v;
        }
    for (k = 0; k < 3; k++) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        if (hi[k] - lo[k] > ext) ext = hi[k] - lo[k];
    }
    for (i = 0; i < m->vertex_count; i++) {
        const float *p = m->positions + 3 * (size_t)i;
        double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
        double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if (d2 > r2) r2 = d2;
    }
    r = sqrt(r2);
    if (!(ext <= FLT_MAX) || !(r <= FLT_MAX))
        return snell__fail(m->ctx, SNELL_E_LIMIT,
                           "mesh too large for float: extent %g, bounding radius %g (the float range ends at %g)",
                           ext, r, (double)FLT_MAX);
    for (k = 0; k < 3; k++) {
        m->bmin[k] = (float)lo[k];
        m->bmax[k] = (float)hi[k];
    }
    m->bradius = (float)r;
    return SNELL_OK;
}

void snell__mesh_compute_normals(const float *pos, const uint32_t *idx, uint32_t nv, uint32_t nt,
                                 float *normals)
{
    uint32_t t, v;
    memset(normals, 0, sizeof(float) * 3 * (size_t)nv);
    for (t = 0; t < nt; t++) {
        const float *a = pos + 3 * idx[3 * t], *b = pos + 3 * idx[3 * t + 1], *c = pos + 3 * idx[3 * t + 2];
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        /* The unnormalised cross product weights each face by its area. */
        float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        int k, j;
        for (j = 0; j < 3; j++)
            for (k = 0; k < 3; k++) normals[3 * idx[3 * t + j] + k] += n[k];
    }
    for (v = 0; v < nv; v++) {
        float *n = normals + 3 * v;
        /* In double: the squares of a tiny (subnormal-range) float sum lose
         * their precision and the "unit" normal is not of unit length
         * (libFuzzer, tests/fuzz/regressions/tiny_normals.obj). */
        double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        if (len > 0.0 && isfinite(len)) {
            n[0] = (float)(n[0] / len); n[1] = (float)(n[1] / len); n[2] = (float)(n[2] / len);
        } else {
            n[0] = 0.0f; n[1] = 1.0f; n[2] = 0.0f;
        }
    }
}

/* Bytes a triangle at the analysis's peak (snell_mesh_analyze). */
#define ANALYSIS_BYTES_PER_TRIANGLE 360u

snell_status snell__mesh_budget_check(const snell_ctx *ctx, size_t nv, size_t nt, const char *what)
{
    char why[160];
    double bytes = 24.0 * (double)nv + (12.0 + ANALYSIS_BYTES_PER_TRIANGLE) * (double)nt;
    snprintf(why, sizeof why, "%s: %zu vertices, %zu triangles with their analysis", what, nv, nt);
    return snell__budget_check(ctx, bytes < (double)(size_t)-1 ? (size_t)bytes : (size_t)-1, why);
}

snell_status snell__mesh_adopt(snell_ctx *ctx, const snell_alloc *alloc, float *positions,
                               float *normals, uint32_t *indices, uint32_t vertex_count,
                               uint32_t triangle_count, snell_mesh **out)
{
    snell_mesh *m = NULL;
    snell_status st = SNELL_OK;
    size_t i;
    if (vertex_count > SNELL_MESH_MAX_VERTICES || triangle_count > SNELL_MESH_MAX_TRIANGLES) {
        st = snell__fail(ctx, SNELL_E_LIMIT, "mesh too large: %u vertices, %u triangles (limits %u, %u)",
                         vertex_count, triangle_count, SNELL_MESH_MAX_VERTICES, SNELL_MESH_MAX_TRIANGLES);
        goto fail;
    }
    if (ctx && ctx->destroyed) {
        st = snell__fail(ctx, SNELL_E_INVALID_ARG, "mesh: its context was destroyed (snell_ctx_destroy)");
        goto fail;
    }
    if ((st = snell__mesh_budget_check(ctx, vertex_count, triangle_count, "the mesh")) != SNELL_OK) goto fail;
    if (triangle_count == 0 || vertex_count < 3) {
        st = snell__fail(ctx, SNELL_E_INVALID_ARG, "mesh has no triangles");
        goto fail;
    }
    for (i = 0; i < 3 * (size_t)vertex_count; i++)
        if (!isfinite(positions[i])) {
            st = snell__fail(ctx, SNELL_E_INVALID_ARG, "vertex %zu has a non-finite coordinate", i / 3);
            goto fail;
        }
    for (i = 0; i < 3 * (size_t)triangle_count; i++)
        if (indices[i] >= vertex_count) {
            st = snell__fail(ctx, SNELL_E_INVALID_ARG, "triangle %zu references vertex %u of %u", i / 3,
                             indices[i], vertex_count);
            goto fail;
        }
    m = (snell_mesh *)snell__calloc(alloc, 1, sizeof *m);
    if (!normals) {
        normals = (float *)snell__calloc(alloc, 3 * (size_t)vertex_count, sizeof(float));
        if (normals) snell__mesh_compute_normals(positions, indices, vertex_count, triangle_count, normals);
    }
    if (!m || !normals) {
        st = snell__fail(ctx, SNELL_E_NOMEM, "out of memory for a mesh of %u vertices", vertex_count);
        goto fail;
    }
    m->ctx = ctx;
    m->gpu_ctx = ctx;
    snell__ctx_retain(ctx);
    m->alloc = *alloc;
    m->positions = positions;
    m->normals = normals;
    m->indices = indices;
    m->vertex_count = vertex_count;
    m->triangle_count = triangle_count;
    m->version = next_version();
    st = compute_bounds(m);
    if (st != SNELL_OK) {
        snell_mesh_destroy(m); /* frees the arrays it owns now */
        return st;
    }
    *out = m;
    return SNELL_OK;
fail:
    snell__free(alloc, m);
    snell__free(alloc, positions);
    snell__free(alloc, normals);
    snell__free(alloc, indices);
    return st;
}

snell_status snell_mesh_create(snell_ctx *ctx, const snell_mesh_desc *desc, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    float *pos = NULL, *nrm = NULL;
    uint32_t *idx = NULL, nt, i;
    snell_status st;
    if (!desc || !out || !desc->positions)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_create: desc, positions and out are required");
    *out = NULL;
    nt = desc->indices ? desc->triangle_count : desc->vertex_count / 3;
    if (desc->vertex_count > SNELL_MESH_MAX_VERTICES || nt > SNELL_MESH_MAX_TRIANGLES)
        return snell__fail(ctx, SNELL_E_LIMIT, "mesh too large: %u vertices, %u triangles", desc->vertex_count, nt);
    /* positions + normals (given or computed) + indices, counted as one request */
    st = snell__mesh_budget_check(ctx, desc->vertex_count, nt, "snell_mesh_create");
    if (st != SNELL_OK) return st;
    pos = (float *)snell__calloc(al, 3 * (size_t)desc->vertex_count, sizeof(float));
    idx = (uint32_t *)snell__calloc(al, 3 * (size_t)nt, sizeof(uint32_t));
    if (desc->normals) nrm = (float *)snell__calloc(al, 3 * (size_t)desc->vertex_count, sizeof(float));
    if (!pos || !idx || (desc->normals && !nrm)) {
        snell__free(al, pos); snell__free(al, idx); snell__free(al, nrm);
        return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for a mesh of %u vertices", desc->vertex_count);
    }
    memcpy(pos, desc->positions, sizeof(float) * 3 * (size_t)desc->vertex_count);
    for (i = 0; i < 3 * nt; i++) idx[i] = desc->indices ? desc->indices[i] : i;
    if (nrm) memcpy(nrm, desc->normals, sizeof(float) * 3 * (size_t)desc->vertex_count);
    st = snell__mesh_adopt(ctx, al, pos, nrm, idx, desc->vertex_count, nt, out);
    if (st == SNELL_OK && nrm)
        for (i = 0; i < desc->vertex_count; i++) {
            /* Caller normals are renormalised; unusable ones make the mesh invalid. */
            float *n = nrm + 3 * i; /* length in double, as in snell__mesh_compute_normals */
            double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
            if (!(len > 0.0) || !isfinite(len)) {
                snell_mesh_destroy(*out);
                *out = NULL;
                return snell__fail(ctx, SNELL_E_INVALID_ARG, "normal %u is zero or not finite", i);
            }
            n[0] = (float)(n[0] / len); n[1] = (float)(n[1] / len); n[2] = (float)(n[2] / len);
        }
    return st;
}

void snell_mesh_destroy(snell_mesh *m)
{
    snell_alloc al;
    if (!m) return;
    if (snell__debug_handles() && m->dead) snell__handle_dead("snell_mesh_destroy", m);
    if (m->vao || m->vbo || m->ibo || m->coarse_vao || m->coarse_ibo || m->gpu_bvh[0] || m->gpu_bvh[1]) {
        /* In the GL context that holds them; nowhere if it is gone. */
        snell__gl_scope sc;
        int gl = snell__gl_scope_enter(m->gpu_ctx, &sc);
        snell__gpu_bvh_free(m->gpu_bvh[0], gl);
        snell__gpu_bvh_free(m->gpu_bvh[1], gl);
        if (gl) {
            if (m->vao) glDeleteVertexArrays(1, &m->vao);
            if (m->vbo) glDeleteBuffers(1, &m->vbo);
            if (m->ibo) glDeleteBuffers(1, &m->ibo);
            if (m->coarse_vao) glDeleteVertexArrays(1, &m->coarse_vao);
            if (m->coarse_ibo) glDeleteBuffers(1, &m->coarse_ibo);
        }
        snell__gl_scope_leave(&sc);
    }
    snell__ctx_release(m->gpu_ctx);
    al = m->alloc;
    snell__free(&al, m->positions);
    snell__free(&al, m->normals);
    snell__free(&al, m->indices);
    if (snell__debug_handles()) { /* kept, so that a second destroy or draw is caught */
        m->positions = m->normals = NULL;
        m->indices = NULL;
        m->gpu_ctx = NULL;
        m->dead = 1;
        return;
    }
    snell__free(&al, m);
}

int snell__mesh_bind_ctx(snell_mesh *m, snell_ctx *ctx)
{
    if (snell__debug_handles() && m->dead) snell__handle_dead("snell_render: a glass or opaque mesh", m);
    if (m->gpu_ctx) return m->gpu_ctx == ctx;
    if (m->ctx && m->ctx != ctx) return 0;
    m->gpu_ctx = ctx;
    snell__ctx_retain(ctx);
    return 1;
}

/* In double, like compute_bounds: the centre and the scale of a mesh near
 * the float range (or far below it) are not representable in float. */
snell_status snell_mesh_normalize(snell_mesh *m, float radius)
{
    double c[3], s;
    uint32_t i;
    int k;
    snell_status st;
    if (!m) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_mesh_normalize: mesh is NULL");
    if (radius == 0.0f) radius = 1.0f;
    if (!(radius > 0.0f) || !isfinite(radius))
        return snell__fail(m->ctx, SNELL_E_INVALID_ARG, "snell_mesh_normalize: radius %g is not positive", radius);
    if ((double)radius > 0.5 * FLT_MAX)
        return snell__fail(m->ctx, SNELL_E_INVALID_ARG,
                           "snell_mesh_normalize: radius %g too large (the mesh's extent, up to twice the radius, "
                           "must stay below the float range %g)", radius, (double)FLT_MAX);
    if (!(m->bradius > 0.0f))
        return snell__fail(m->ctx, SNELL_E_INVALID_ARG, "mesh is degenerate (all vertices coincide)");
    for (k = 0; k < 3; k++) c[k] = 0.5 * ((double)m->bmin[k] + (double)m->bmax[k]);
    s = (double)radius / (double)m->bradius;
    for (i = 0; i < m->vertex_count; i++)
        for (k = 0; k < 3; k++) {
            float *p = &m->positions[3 * (size_t)i + k];
            *p = (float)(((double)*p - c[k]) * s);
        }
    m->version = next_version();
    st = compute_bounds(m); /* cannot fail: extent <= 2 * radius (a float rounding above) < FLT_MAX */
    return st;
}

snell_status snell_mesh_set_vertices(snell_mesh *m, const float *positions, const float *normals)
{
    double c[3];
    size_t i, n;
    int k;
    snell_status st;
    if (!m || !positions)
        return snell__fail(m ? m->ctx : NULL, SNELL_E_INVALID_ARG, "snell_mesh_set_vertices: mesh and positions required");
    n = 3 * (size_t)m->vertex_count;
    /* everything checked before anything changes: a refused call leaves the mesh as it was */
    for (i = 0; i < n; i++)
        if (!isfinite(positions[i]) || (normals && !isfinite(normals[i])))
            return snell__fail(m->ctx, SNELL_E_INVALID_ARG, "snell_mesh_set_vertices: vertex %zu has a non-finite %s",
                               i / 3, isfinite(positions[i]) ? "normal" : "coordinate");
    for (i = 0; normals && i < n; i += 3) {
        double len = sqrt((double)normals[i] * normals[i] + (double)normals[i + 1] * normals[i + 1] +
                          (double)normals[i + 2] * normals[i + 2]);
        if (!(len > 0.0)) return snell__fail(m->ctx, SNELL_E_INVALID_ARG, "snell_mesh_set_vertices: normal %zu is zero", i / 3);
    }
    /* the extent must stay representable, as compute_bounds requires */
    for (k = 0; k < 3; k++) {
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        for (i = (size_t)k; i < n; i += 3) {
            lo = fmin(lo, positions[i]);
            hi = fmax(hi, positions[i]);
        }
        c[k] = hi - lo;
        if (!(c[k] < FLT_MAX))
            return snell__fail(m->ctx, SNELL_E_LIMIT, "snell_mesh_set_vertices: extent %g exceeds the float range", c[k]);
    }
    memcpy(m->positions, positions, n * sizeof(float));
    if (normals) {
        for (i = 0; i < n; i += 3) {
            double len = sqrt((double)normals[i] * normals[i] + (double)normals[i + 1] * normals[i + 1] +
                              (double)normals[i + 2] * normals[i + 2]);
            for (k = 0; k < 3; k++) m->normals[i + k] = (float)(normals[i + k] / len);
        }
    } else {
        snell__mesh_compute_normals(m->positions, m->indices, m->vertex_count, m->triangle_count, m->normals);
    }
    m->version = next_version();
    st = compute_bounds(m);
    return st;
}

uint32_t snell_mesh_vertex_count(const snell_mesh *m) { return m ? m->vertex_count : 0; }
uint32_t snell_mesh_triangle_count(const snell_mesh *m) { return m ? m->triangle_count : 0; }
const float *snell_mesh_positions(const snell_mesh *m) { return m ? m->positions : NULL; }
const float *snell_mesh_normals(const snell_mesh *m) { return m ? m->normals : NULL; }
const uint32_t *snell_mesh_indices(const snell_mesh *m) { return m ? m->indices : NULL; }

void snell_mesh_bounds(const snell_mesh *m, float mn[3], float mx[3])
{
    int k;
    for (k = 0; k < 3; k++) { /* NULL outputs are skipped, as the other getters take NULL */
        if (mn) mn[k] = m ? m->bmin[k] : 0.0f;
        if (mx) mx[k] = m ? m->bmax[k] : 0.0f;
    }
}

void snell__mesh_draw(const snell_mesh *m)
{
    glBindVertexArray(m->vao);
    glDrawElements(GL_TRIANGLES, (GLsizei)(3 * m->triangle_count), m->index_type, (const void *)0);
}

snell_status snell__mesh_upload(snell_mesh *m)
{
    size_t nv = m->vertex_count, ni = 3 * (size_t)m->triangle_count, i;
    float *interleaved;
    uint32_t *idx;
    snell_status st;
    if (m->vao && m->uploaded_version == m->version) return SNELL_OK;
    interleaved = (float *)snell__calloc(&m->alloc, 6 * nv, sizeof(float));
    idx = (uint32_t *)snell__calloc(&m->alloc, ni, sizeof(uint32_t));
    st = interleaved && idx ? snell__mesh_gpu_layout(m, interleaved, idx)
                            : snell__fail(m->ctx, SNELL_E_NOMEM, "out of memory uploading a mesh");
    if (st == SNELL_OK && !m->order_warned) {
        /* said once a mesh: the order depends on the triangles only, which
         * snell_mesh_set_vertices (re-uploaded every frame it is called) keeps */
        snell_mesh_gpu_stats gs;
        if (snell__mesh_gpu_order(m, &gs) == SNELL_OK && gs.order == SNELL_GPU_ORDER_LINEAR)
            snell__log(m->gpu_ctx, SNELL_LOG_WARN, "mesh of %u triangles: %s (snell_mesh_gpu_stats_get)",
                       m->triangle_count, gs.reason);
        m->order_warned = 1;
    }
    if (st != SNELL_OK) {
        snell__free(&m->alloc, interleaved);
        snell__free(&m->alloc, idx);
        return st;
    }
    /* 16-bit indices where they fit: half the index bandwidth. */
    m->index_type = nv <= 65536 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT;
    if (m->index_type == GL_UNSIGNED_SHORT)
        for (i = 0; i < ni; i++) ((uint16_t *)idx)[i] = (uint16_t)idx[i];
    if (!m->vao) {
        glGenVertexArrays(1, &m->vao);
        glGenBuffers(1, &m->vbo);
        glGenBuffers(1, &m->ibo);
    }
    glBindVertexArray(m->vao);
    glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * 6 * nv), interleaved, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)(3 * sizeof(float)));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 (GLsizeiptr)((m->index_type == GL_UNSIGNED_SHORT ? sizeof(uint16_t) : sizeof(uint32_t)) * ni), idx,
                 GL_STATIC_DRAW);
    glBindVertexArray(0);
    snell__free(&m->alloc, interleaved);
    snell__free(&m->alloc, idx);
    m->uploaded_version = m->version;
    return glGetError() == GL_NO_ERROR ? SNELL_OK
                                       : snell__fail(m->ctx, SNELL_E_GL, "GL error uploading mesh buffers");
}
