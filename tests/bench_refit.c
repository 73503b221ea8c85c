/* SPDX-License-Identifier: MIT */
/* bench_refit — what a deforming mesh costs SNELL_METHOD_EXACT: frames that
 * move the mesh's vertices (snell_mesh_set_vertices, alternating between
 * two shapes) drawn with single (the mesh's own update, no BVH), with exact
 * (its BVH refitted: exact.c), and with exact while the node format
 * alternates too (which makes every frame build the BVH again), beside a
 * static exact frame. A small target keeps the traversal's share small. The
 * four take turns frame by frame; medians of N rounds, each frame ended by
 * glFinish. Not a test: a tool (bench/BENCHMARKS.md, "Exact").
 *
 * usage: bench_refit MESH [SIZE] [ROUNDS]   e.g. bench_refit bunny.obj 32 21 */
#define _POSIX_C_SOURCE 200809L
#include <snell/snell.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define KINDS 4

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
    static const char *const names[KINDS] = {"deforming, single", "deforming, exact (refit)",
                                             "deforming, exact (rebuilt)", "static, exact"};
    snell_ctx *ctx = NULL;
    snell_mesh *mesh = NULL, *still = NULL;
    snell_env *env = NULL;
    snell_renderer *r[KINDS] = {NULL};
    snell_renderer_desc rd;
    snell_glass g[KINDS];
    snell_frame_desc fd;
    float *shape[2] = {NULL, NULL};
    double *t[KINDS] = {NULL};
    int size = argc > 2 ? atoi(argv[2]) : 32, rounds = argc > 3 ? atoi(argv[3]) : 21, k, f, rc = 1;
    uint32_t i, nv;
    if (argc < 2 || size < 1 || rounds < 1) {
        fprintf(stderr, "usage: bench_refit MESH [SIZE] [ROUNDS]\n");
        return 2;
    }
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK || snell_mesh_load(ctx, argv[1], &mesh) != SNELL_OK ||
        snell_mesh_normalize(mesh, 1.0f) != SNELL_OK || snell_mesh_load(ctx, argv[1], &still) != SNELL_OK ||
        snell_mesh_normalize(still, 1.0f) != SNELL_OK || snell_env_create(ctx, &(snell_env_desc){0}, &env) != SNELL_OK) {
        fprintf(stderr, "bench_refit: %s\n", snell_last_error(ctx));
        goto out;
    }
    nv = snell_mesh_vertex_count(mesh);
    shape[0] = (float *)malloc(3 * sizeof(float) * nv);
    shape[1] = (float *)malloc(3 * sizeof(float) * nv);
    for (k = 0; k < KINDS; k++) t[k] = (double *)calloc((size_t)rounds, sizeof(double));
    if (!shape[0] || !shape[1] || !t[0] || !t[1] || !t[2] || !t[3]) goto out;
    memcpy(shape[0], snell_mesh_positions(mesh), 3 * sizeof(float) * nv);
    for (i = 0; i < 3 * nv; i++) shape[1][i] = shape[0][i] * (i % 3 == 1 ? 0.9f : 1.05f);
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = size;
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass_count = 1;
    fd.camera.distance = 3.0f;
    for (k = 0; k < KINDS; k++) {
        memset(&g[k], 0, sizeof g[k]);
        g[k].mesh = k == 3 ? still : mesh; /* the static one: a copy no version change reaches */
        g[k].material.method = k == 0 ? SNELL_METHOD_SINGLE : SNELL_METHOD_EXACT;
        if (snell_renderer_create(ctx, &rd, &r[k]) != SNELL_OK) goto out;
        fd.glass = &g[k];
        if (snell_render(r[k], &fd, NULL) != SNELL_OK) goto out; /* programs, first build */
        snell_renderer_finish(r[k]);
    }
    for (f = 0; f < rounds; f++)
        for (k = 0; k < KINDS; k++) {
            double t0 = now_ms();
            /* each deforming kind sees a new version every frame */
            if (k < 3 && snell_mesh_set_vertices(mesh, shape[(f * KINDS + k) & 1], NULL) != SNELL_OK) goto out;
            if (k == 2) g[k].material.exact.node_format = 1 + (f & 1);
            fd.glass = &g[k];
            if (snell_render(r[k], &fd, NULL) != SNELL_OK) goto out;
            snell_renderer_finish(r[k]);
            t[k][f] = now_ms() - t0;
        }
    printf("%s, %dx%d, %u triangles, medians of %d rounds:\n", argv[1], size, size, snell_mesh_triangle_count(mesh),
           rounds);
    for (k = 0; k < KINDS; k++) {
        qsort(t[k], (size_t)rounds, sizeof(double), cmp_double);
        printf("  %-28s %8.1f ms\n", names[k], t[k][rounds / 2]);
    }
    rc = 0;
out:
    if (rc) fprintf(stderr, "bench_refit: %s\n", snell_last_error(ctx));
    for (k = 0; k < KINDS; k++) {
        snell_renderer_destroy(r[k]);
        free(t[k]);
    }
    free(shape[0]);
    free(shape[1]);
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
    snell_mesh_destroy(still);
    snell_ctx_destroy(ctx);
    return rc;
}
