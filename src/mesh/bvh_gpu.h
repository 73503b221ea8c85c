/* SPDX-License-Identifier: MIT */
/* bvh_gpu.h — the triangle BVH as a GPU texture, a mesh-level resource:
 * made on the first ask per node format (snell_exact_nodes), refitted when
 * the mesh's vertices move (a new version, the same triangles), freed with
 * the mesh. The exact method's kernel (exact.frag) and the caustics'
 * photons (caustics_photon.vert) walk it with common/bvh.glsl. Built where
 * one of them is (SNELL__GPU_BVH). */
#ifndef SNELL_BVH_GPU_H
#define SNELL_BVH_GPU_H

#include "mesh/mesh.h"

#define SNELL__GPU_BVH (SNELL__BUILT_exact || SNELL_WITH_CAUSTICS)

/* Texels per row (common/bvh.glsl's TEX_SHIFT): GLES 3.0's smallest
 * GL_MAX_TEXTURE_SIZE, so every device takes the width. */
#define SNELL__GPU_BVH_WIDTH 2048

typedef struct snell__gpu_bvh {
    unsigned texture;               /* RGBA32F (f32 nodes) or RGBA32UI (q16 nodes), SNELL__GPU_BVH_WIDTH wide */
    int q16;                        /* SNELL_NODES_Q16 */
    int node_count, tri_base;       /* nodes; the texel of the first triangle entry */
    const float *qlo, *qstep;       /* q16: bound = qlo + q * qstep (object space) */
    int built;                      /* 1: built or refitted by this call */
} snell__gpu_bvh;

/* The least distance a secondary ray travels before it may hit again, for an
 * object of bounding radius r: exact's kernel's and the photons' alike. */
#define SNELL__BVH_EPS(r) (1e-5f * (r))

/* mesh's BVH in the given node format, up to date with its vertices, in the
 * current context (the mesh's GPU context). */
snell_status snell__mesh_gpu_bvh(snell_ctx *ctx, snell_mesh *mesh, snell_exact_nodes format, snell__gpu_bvh *out);

/* The f32 BVH of a mesh no one keeps (the caustics' casters merged in world
 * space, remade in place each frame) in *state (made on the first call, NULL
 * before; built again, or refitted for the same triangle count, on each);
 * its triangle entries carry their mesh triangle's index in v0's w. */
snell_status snell__gpu_bvh_make(snell_ctx *ctx, const snell_mesh *mesh, void **state, snell__gpu_bvh *out);
/* Frees a BVH made by either; gl: its texture too (its context is current). */
void snell__gpu_bvh_free(void *state, int gl);

#endif
