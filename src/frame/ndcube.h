/* SPDX-License-Identifier: MIT */
/* ndcube.h — the normal+distance cubemap of Li et al. as in Unger 4.1: per
 * direction from a centre inside the mesh, the farthest surface's normal and
 * distance packed into RGBA8 (pack.h), baked in 6 passes (GLES 3.0 has no
 * geometry shader); plus the cube-face cameras shared with env_dynamic.c. */
#ifndef SNELL_NDCUBE_H
#define SNELL_NDCUBE_H

#include "core/core.h"
#include "mesh/mesh.h"
#include "frame/method.h"

#include <cglm/cglm.h>

/* View-projection (90 degree square frustum) that renders GL cube face
 * `face` (0..5 = +X -X +Y -Y +Z -Z) seen from eye, so that window (x, y)
 * lands on the face's (s, t) texel when the face is the colour attachment. */
void snell__cube_face_view_proj(int face, const float eye[3], float z_near, float z_far, mat4 out);

/* The bake programs, one per encoding; built once per renderer. */
typedef struct snell__ndcube_baker {
    unsigned prog[2];                /* [0] PLAIN, [1] OCT */
    int u_view_proj[2], u_centre[2], u_inv_radius[2];
    unsigned fbo, depth_rb;
    int depth_size;                  /* size of depth_rb, 0 = none yet */
} snell__ndcube_baker;

/* One baked cubemap (object space). */
typedef struct snell__ndcube {
    unsigned texture;                /* GL_TEXTURE_CUBE_MAP, RGBA8, 0 = none */
    int face_size;
    snell_ndcube_encoding encoding;  /* PLAIN or OCT (never DEFAULT) */
    float centre[3];                 /* object space */
    float radius;                    /* object units; texel distance d = |p - centre| / radius */
} snell__ndcube;

snell_status snell__ndcube_baker_create(snell_ctx *ctx, snell__ndcube_baker *b);
void snell__ndcube_baker_destroy(snell__ndcube_baker *b);

/* (Re)bakes cube for mesh (uploaded) about centre with the given radius
 * (>= every vertex's distance). Reallocates the texture only if face size or
 * encoding changed. Restores the pass state (frame/pass.h); leaves texture
 * unit 1's cube binding changed. */
snell_status snell__ndcube_bake(snell_ctx *ctx, snell__ndcube_baker *b, snell_mesh *mesh, const float centre[3],
                                float radius, int face_size, snell_ndcube_encoding enc, snell__ndcube *cube);
void snell__ndcube_release(snell__ndcube *cube);

/* Reads face (0..5) as RGBA8, row 0 = t = 0 (for tests); rgba: 4*size*size. */
snell_status snell__ndcube_read_face(snell_ctx *ctx, snell__ndcube_baker *b, const snell__ndcube *cube, int face,
                                     uint8_t *rgba);

#endif
