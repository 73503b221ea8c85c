/* mesh_gpu.c — the mesh as the GPU draws it (DESIGN.md "frame": geometry fed
 * well): triangles reordered for the post-transform vertex cache, vertices
 * for fetch locality (meshoptimizer, when built with it), 16-bit indices where
 * the vertex count allows. Only the GPU copy changes: the mesh's own arrays,
 * which users and the analysis see, keep their order. Measured on the bunny
 * (69,666 triangles): ACMR 2.08 in OBJ order, 0.68 after the reorder. */
#include "mesh/mesh.h"
#include "core/gl.h"

#include <string.h>

#ifdef SNELL_WITH_MESHOPT
#include <meshoptimizer.h>
#endif

/* Post-transform cache the ACMR figures are for (meshoptimizer's default). */
#define CACHE_SIZE 16

float snell__mesh_acmr(const uint32_t *indices, uint32_t triangle_count, uint32_t vertex_count)
{
#ifdef SNELL_WITH_MESHOPT
    struct meshopt_VertexCacheStatistics s =
        meshopt_analyzeVertexCache(indices, 3 * (size_t)triangle_count, vertex_count, CACHE_SIZE, 0, 0);
    return s.acmr;
#else
    /* FIFO cache of CACHE_SIZE: misses per triangle */
    uint32_t cache[CACHE_SIZE];
    size_t i, misses = 0, head = 0, filled = 0, k;
    for (i = 0; i < 3 * (size_t)triangle_count; i++) {
        int hit = 0;
        for (k = 0; k < filled; k++) hit |= cache[k] == indices[i];
        if (hit) continue;
        misses++;
        cache[head] = indices[i];
        head = (head + 1) % CACHE_SIZE;
        if (filled < CACHE_SIZE) filled++;
    }
    (void)vertex_count;
    return triangle_count ? (float)misses / (float)triangle_count : 0.0f;
#endif
}

snell_status snell__mesh_gpu_layout(const snell_mesh *m, float *vertices, uint32_t *indices)
{
    size_t nv = m->vertex_count, ni = 3 * (size_t)m->triangle_count, i;
    for (i = 0; i < nv; i++) {
        memcpy(vertices + 6 * i, m->positions + 3 * i, 3 * sizeof(float));
        memcpy(vertices + 6 * i + 3, m->normals + 3 * i, 3 * sizeof(float));
    }
#ifdef SNELL_WITH_MESHOPT
    {
        float *fetched = (float *)snell__calloc(&m->alloc, 6 * nv, sizeof(float));
        if (!fetched) return snell__fail(m->ctx, SNELL_E_NOMEM, "out of memory laying out a mesh for the GPU");
        /* Triangle order for the vertex cache keeps each triangle's corner
         * order, so winding (and back-face culling) is unchanged. */
        meshopt_optimizeVertexCache(indices, m->indices, ni, nv);
        /* Vertices in first-use order; unreferenced ones are dropped. */
        meshopt_optimizeVertexFetch(fetched, indices, ni, vertices, nv, 6 * sizeof(float));
        memcpy(vertices, fetched, 6 * nv * sizeof(float));
        snell__free(&m->alloc, fetched);
    }
#else
    memcpy(indices, m->indices, ni * sizeof(uint32_t));
#endif
    return SNELL_OK;
}

/* Target and bound of the coarse copy: a quarter of the triangles, and no
 * vertex of it farther than 1% of the extent from the full surface
 * (meshoptimizer's relative error; the bunny's comes out at 0.08%). */
#define COARSE_RATIO 0.25
#define COARSE_ERROR 0.01f
/* meshoptimizer 0.18's simplifier scratch per vertex and per index (see
 * mesh_lod.c), for the memory budget. */
#define COARSE_SCRATCH_PER_VERTEX 100u
#define COARSE_SCRATCH_PER_INDEX 40u

unsigned snell__mesh_coarse(snell_mesh *m)
{
#ifdef SNELL_WITH_MESHOPT
    size_t nv = m->vertex_count, ni = 3 * (size_t)m->triangle_count, n = 0, i;
    float *vert = NULL, err = 0.0f;
    uint32_t *idx = NULL, *out = NULL;
    if (m->coarse_state) return m->coarse_state > 0 ? m->coarse_vao : 0;
    m->coarse_state = -1;
    if (m->triangle_count < SNELL__COARSE_MIN_TRIANGLES || !m->vao) return 0;
    if (snell__budget_check(m->gpu_ctx, nv * (24 + COARSE_SCRATCH_PER_VERTEX) + ni * (8 + COARSE_SCRATCH_PER_INDEX),
                            "the coarse copy of a mesh") != SNELL_OK)
        return 0;
    vert = (float *)snell__calloc(&m->alloc, 6 * nv, sizeof(float));
    idx = (uint32_t *)snell__calloc(&m->alloc, ni, sizeof(uint32_t));
    out = (uint32_t *)snell__calloc(&m->alloc, ni, sizeof(uint32_t));
    /* the GPU copy's own vertex numbering, so the copy indexes its buffer */
    if (vert && idx && out && snell__mesh_gpu_layout(m, vert, idx) == SNELL_OK)
        n = meshopt_simplify(out, idx, ni, vert, nv, 6 * sizeof(float), (size_t)(COARSE_RATIO * (double)ni), COARSE_ERROR,
                             0, &err);
    /* worth a buffer only if it saves a third of the triangles */
    if (n > 0 && n < 2 * ni / 3) {
        if (m->index_type == GL_UNSIGNED_SHORT)
            for (i = 0; i < n; i++) ((uint16_t *)out)[i] = (uint16_t)out[i];
        glGenVertexArrays(1, &m->coarse_vao);
        glGenBuffers(1, &m->coarse_ibo);
        glBindVertexArray(m->coarse_vao);
        glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)0);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)(3 * sizeof(float)));
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->coarse_ibo);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                     (GLsizeiptr)((m->index_type == GL_UNSIGNED_SHORT ? sizeof(uint16_t) : sizeof(uint32_t)) * n), out,
                     GL_STATIC_DRAW);
        glBindVertexArray(0);
        m->coarse_index_count = (uint32_t)n;
        m->coarse_state = glGetError() == GL_NO_ERROR ? 1 : -1;
        snell__log(m->gpu_ctx, SNELL_LOG_INFO,
                   "coarse copy for the back-face pass: %zu of %zu triangles, error %.4f of the extent", n / 3, ni / 3,
                   (double)err);
    }
    snell__free(&m->alloc, vert);
    snell__free(&m->alloc, idx);
    snell__free(&m->alloc, out);
    return m->coarse_state > 0 ? m->coarse_vao : 0;
#else
    (void)m;
    return 0;
#endif
}

void snell__mesh_coarse_draw(const snell_mesh *m)
{
    glBindVertexArray(m->coarse_vao);
    glDrawElements(GL_TRIANGLES, (GLsizei)m->coarse_index_count, m->index_type, (const void *)0);
}
