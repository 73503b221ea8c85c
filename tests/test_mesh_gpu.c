/* SPDX-License-Identifier: MIT */
/* test_mesh_gpu — the GPU copy of a mesh (src/mesh/mesh_gpu.c): reordered
 * for the vertex cache and fetch, it still holds exactly the mesh's
 * triangles, each with its corner order (winding), and its cache miss ratio
 * drops: on a sphere whose triangles were shuffled, and on the bunny. */
#include "test_util.h"
#include "mesh/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct tri_key {
    float v[9]; /* corner positions, rotated so the smallest corner comes first (winding kept) */
} tri_key;

static int cmp_float9(const void *a, const void *b) { return memcmp(a, b, sizeof(tri_key)); }

static void key_of(const float *p0, const float *p1, const float *p2, tri_key *k)
{
    const float *c[3] = {p0, p1, p2};
    int first = 0, i;
    for (i = 1; i < 3; i++)
        if (memcmp(c[i], c[first], 3 * sizeof(float)) < 0) first = i;
    for (i = 0; i < 3; i++) memcpy(k->v + 3 * i, c[(first + i) % 3], 3 * sizeof(float));
}

/* The GPU layout holds the same triangles, same winding, as the mesh. */
static void check_layout(const snell_mesh *m, const char *name, float *acmr_before, float *acmr_after)
{
    size_t nt = m->triangle_count, nv = m->vertex_count, t;
    float *vtx = (float *)malloc(6 * nv * sizeof(float));
    uint32_t *idx = (uint32_t *)malloc(3 * nt * sizeof(uint32_t));
    tri_key *a = (tri_key *)malloc(nt * sizeof *a), *b = (tri_key *)malloc(nt * sizeof *b);
    CHECK_OK(snell__mesh_gpu_layout(m, vtx, idx));
    for (t = 0; t < nt; t++) {
        key_of(m->positions + 3 * m->indices[3 * t], m->positions + 3 * m->indices[3 * t + 1],
               m->positions + 3 * m->indices[3 * t + 2], &a[t]);
        key_of(vtx + 6 * idx[3 * t], vtx + 6 * idx[3 * t + 1], vtx + 6 * idx[3 * t + 2], &b[t]);
    }
    qsort(a, nt, sizeof *a, cmp_float9);
    qsort(b, nt, sizeof *b, cmp_float9);
    CHECK(memcmp(a, b, nt * sizeof *a) == 0, "%s: the GPU copy's triangles differ from the mesh's", name);
    *acmr_before = snell__mesh_acmr(m->indices, m->triangle_count, m->vertex_count);
    *acmr_after = snell__mesh_acmr(idx, m->triangle_count, m->vertex_count);
    printf("%s: %zu triangles, ACMR %.3f -> %.3f\n", name, nt, *acmr_before, *acmr_after);
    free(vtx);
    free(idx);
    free(a);
    free(b);
}

int main(void)
{
    snell_mesh *sphere = NULL, *shuffled = NULL, *bunny = NULL;
    snell_mesh_desc md;
    uint32_t *idx;
    float before, after;
    size_t t, nt;
    CHECK_OK(snell_mesh_create_shape(NULL, &(snell_shape_desc){SNELL_SHAPE_SPHERE, 64, 32}, &sphere));
    if (!sphere) return test_finish();
    /* Triangles in a deterministic random order: a worst case for the cache. */
    nt = sphere->triangle_count;
    idx = (uint32_t *)malloc(3 * nt * sizeof(uint32_t));
    memcpy(idx, sphere->indices, 3 * nt * sizeof(uint32_t));
    {
        uint32_t s = 12345u;
        for (t = nt - 1; t > 0; t--) {
            uint32_t j, k, tmp;
            s = s * 1664525u + 1013904223u;
            j = s % (uint32_t)(t + 1);
            for (k = 0; k < 3; k++) {
                tmp = idx[3 * t + k];
                idx[3 * t + k] = idx[3 * j + k];
                idx[3 * j + k] = tmp;
            }
        }
    }
    memset(&md, 0, sizeof md);
    md.positions = sphere->positions;
    md.normals = sphere->normals;
    md.indices = idx;
    md.vertex_count = sphere->vertex_count;
    md.triangle_count = (uint32_t)nt;
    CHECK_OK(snell_mesh_create(NULL, &md, &shuffled));
    if (shuffled) {
        check_layout(shuffled, "shuffled sphere", &before, &after);
#ifdef SNELL_WITH_MESHOPT_TEST
        CHECK(after < 0.8f * before, "vertex-cache reorder: ACMR %.3f -> %.3f", before, after);
#endif
        CHECK(after <= before, "the reorder made the cache worse: %.3f -> %.3f", before, after);
    }
    if (snell_mesh_load(NULL, "/usr/share/glmark2/models/bunny.obj", &bunny) == SNELL_OK) {
        check_layout(bunny, "bunny", &before, &after);
        CHECK(after <= before, "bunny: %.3f -> %.3f", before, after);
    } else {
        printf("bunny skipped: /usr/share/glmark2/models/bunny.obj not installed (glmark2-data)\n");
    }
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(shuffled);
    snell_mesh_destroy(bunny);
    free(idx);
    return test_finish();
}
