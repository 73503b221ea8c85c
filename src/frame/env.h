/* SPDX-License-Identifier: MIT */
/* env.h — environment: six RGBA8 cube faces on the CPU (the exact texels the
 * GPU samples) and the GL cubemap made from them. */
#ifndef SNELL_ENV_H
#define SNELL_ENV_H

#include "core/core.h"

struct snell_env {
    snell_ctx *ctx;
    snell_alloc alloc;
    int size;                  /* face size in texels */
    uint8_t *faces[6];         /* RGBA8, row 0 = GL t=0, GL face order +X -X +Y -Y +Z -Z */
    unsigned texture;          /* GL_TEXTURE_CUBE_MAP, 0 if CPU only */
    int borrowed;              /* texture is the host's (SNELL_ENV_GL_TEXTURE): never deleted here, may
                                * change between frames; faces are NULL */
    unsigned paraboloid;       /* its dual-paraboloid maps (render/env_paraboloid.h), 0 until first used */
    int paraboloid_size;
};

/* Cube face and face coordinates (s,t in [0,1]) of a direction, GL rules
 * (OpenGL ES 3.0 spec table 3.21; Unger 2.2.2 table 1). */
void snell__cube_coords(const double dir[3], int *face, double *s, double *t);
/* Unit direction through face coordinates (s,t) of face; inverse of the above. */
void snell__cube_dir(int face, double s, double t, double dir[3]);

/* An empty RGBA8 cube texture (one level, CLAMP_TO_EDGE, the given min/mag
 * filter) left bound to GL_TEXTURE_CUBE_MAP; for render targets. */
unsigned snell__cube_texture_create(int size, int filter);

#endif
