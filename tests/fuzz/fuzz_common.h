/* SPDX-License-Identifier: MIT */
/* fuzz_common.h — shared by the fuzz targets: mesh invariants that must hold for
 * every accepted input, and a replay main() for builds without libFuzzer
 * (ctest feeds it the files under tests/data). */
#ifndef SNELL_FUZZ_COMMON_H
#define SNELL_FUZZ_COMMON_H

#define _DEFAULT_SOURCE /* MAP_ANONYMOUS */
#include "snell/snell.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A copy of the input that ends exactly where an inaccessible page begins, so
 * a loader reading even one byte past [data, data + size) faults in every
 * build, not only under ASan (a caller's mmap'd file has no redzone after it).
 * The copy lives until the next call. */
static inline const uint8_t *fuzz_at_end_of_mapping(const uint8_t *data, size_t size)
{
    static uint8_t *map;
    static size_t map_len;
    size_t page = (size_t)sysconf(_SC_PAGESIZE), len = (size + page - 1) / page * page + page;
    if (map) munmap(map, map_len);
    map = (uint8_t *)mmap(NULL, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (map == (uint8_t *)MAP_FAILED) abort();
    map_len = len;
    if (mprotect(map + len - page, page, PROT_NONE) != 0) abort();
    if (size) memcpy(map + len - page - size, data, size);
    return map + len - page - size;
}

/* The stages that consume loaded data (docs/ARCHITECTURE.md "Tests and CI"): normalisation and
 * the analysis either fail with a message or give sane values (positions
 * within the unit sphere after normalising, fractions in [0,1], finite radii
 * with inner <= outer). The analysis's cost is bounded by the triangle count
 * (mesh_analyze.c WORK_*), so a slow input is a finding too (libFuzzer -timeout). */
/* The level of detail (snell_mesh_simplify, half the triangles): fails with a
 * message and no mesh (SNELL_E_UNSUPPORTED without meshoptimizer), or gives a
 * valid mesh with no more triangles, which is closed if the source was. */
static inline void fuzz_check_simplify(const snell_mesh *m, const snell_mesh_analysis *src)
{
    snell_simplify_desc d;
    snell_simplify_report rep;
    snell_mesh_analysis a;
    snell_mesh *lod = NULL;
    snell_status st;
    uint32_t i;
    memset(&d, 0, sizeof d);
    d.target_ratio = 0.5f;
    st = snell_mesh_simplify(NULL, m, &d, &lod, &rep);
    if (st != SNELL_OK) {
        if (lod || !snell_last_error(NULL)[0]) abort();
        return;
    }
    if (!lod || rep.triangles_after != snell_mesh_triangle_count(lod) ||
        rep.triangles_after > snell_mesh_triangle_count(m))
        abort();
    for (i = 0; i < 3 * snell_mesh_triangle_count(lod); i++)
        if (snell_mesh_indices(lod)[i] >= snell_mesh_vertex_count(lod)) abort();
    for (i = 0; i < 3 * snell_mesh_vertex_count(lod); i++)
        if (!isfinite(snell_mesh_positions(lod)[i]) || !isfinite(snell_mesh_normals(lod)[i])) abort();
    if (src->closed && snell_mesh_analyze(lod, &a) == SNELL_OK && !a.closed) abort();
    snell_mesh_destroy(lod);
}

static inline void fuzz_check_stages(snell_mesh *m)
{
    snell_mesh_analysis a;
    snell_status st = snell_mesh_normalize(m, 1.0f);
    uint32_t i;
    int k;
    if (st != SNELL_OK) {
        if (!snell_last_error(NULL)[0]) abort();
    } else {
        for (i = 0; i < 3 * snell_mesh_vertex_count(m); i++) {
            float p = snell_mesh_positions(m)[i];
            if (!isfinite(p) || fabsf(p) > 1.001f) abort();
        }
    }
    st = snell_mesh_analyze(m, &a);
    if (st != SNELL_OK) {
        if (!snell_last_error(NULL)[0]) abort();
        return;
    }
    for (k = 0; k < 3; k++)
        if (!isfinite(a.centre[k])) abort();
    if (!(a.hidden_fraction >= 0.0f && a.hidden_fraction <= 1.0f) || !(a.radius >= 0.0f) || !isfinite(a.radius) ||
        !(a.inner_radius >= 0.0f && a.inner_radius <= a.radius * 1.001f + 1e-6f) || a.samples <= 0)
        abort();
    if (a.closed && (a.boundary_edges || a.nonmanifold_edges || a.flipped_edges)) abort();
    if (a.convex && !a.closed) abort();
    fuzz_check_simplify(m, &a);
}

/* A loader either fails with a message and no mesh, or returns a mesh whose
 * indices are in range, positions finite and normals unit; the mesh then goes
 * through fuzz_check_stages. abort() otherwise, so both libFuzzer and ctest
 * report it. */
static inline void fuzz_check_result(snell_status st, snell_mesh *m)
{
    uint32_t i, nv, nt;
    if (st != SNELL_OK) {
        if (m || !snell_last_error(NULL)[0]) abort();
        return;
    }
    if (!m) abort();
    nv = snell_mesh_vertex_count(m);
    nt = snell_mesh_triangle_count(m);
    if (nv == 0 || nt == 0) abort();
    for (i = 0; i < 3 * nt; i++)
        if (snell_mesh_indices(m)[i] >= nv) abort();
    for (i = 0; i < nv; i++) {
        const float *p = snell_mesh_positions(m) + 3 * i, *n = snell_mesh_normals(m) + 3 * i;
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]) || !(fabsf(len - 1.0f) < 1e-3f)) abort();
    }
    fuzz_check_stages(m);
    snell_mesh_destroy(m);
}

#ifndef SNELL_LIBFUZZER
/* Replay: run every file named on the command line through the target. */
int main(int argc, char **argv)
{
    int i, n = 0;
    for (i = 1; i < argc; i++) {
        FILE *f = fopen(argv[i], "rb");
        uint8_t *buf;
        long len;
        if (!f) {
            fprintf(stderr, "cannot open %s\n", argv[i]);
            return 1;
        }
        fseek(f, 0, SEEK_END);
        len = ftell(f);
        fseek(f, 0, SEEK_SET);
        buf = (uint8_t *)malloc(len > 0 ? (size_t)len : 1);
        if (!buf || (len > 0 && fread(buf, 1, (size_t)len, f) != (size_t)len)) {
            fprintf(stderr, "cannot read %s\n", argv[i]);
            fclose(f);
            free(buf);
            return 1;
        }
        fclose(f);
        LLVMFuzzerTestOneInput(buf, (size_t)len);
        free(buf);
        n++;
    }
    printf("replayed %d inputs\n", n);
    return 0;
}
#endif

#endif
