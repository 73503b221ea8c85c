/* SPDX-License-Identifier: MIT */
/* profile.h — device profiles: named sets of GL limits and extensions of real
 * GLES 3.0 devices; a context under a profile uses only what it has. */
#ifndef SNELL_PROFILE_H
#define SNELL_PROFILE_H

#include "core/core.h"

/* The limits snell checks, in snell_limit's order. */
enum {
    SNELL__LIM_TEXTURE, SNELL__LIM_CUBE, SNELL__LIM_LAYERS, SNELL__LIM_RENDERBUFFER, SNELL__LIM_SAMPLES,
    SNELL__LIM_UNITS, SNELL__LIM_FRAG_VECTORS, SNELL__LIM_VERT_VECTORS, SNELL__LIM_VARYINGS,
    SNELL__LIM_DRAW_BUFFERS, SNELL__LIMITS
};

typedef struct snell__profile {
    char name[14];                      /* arrays, not pointers: no relocations in a shared library */
    unsigned char ext;                  /* bit i: snell__profile_ext[i] is there */
    unsigned short limit[SNELL__LIMITS];
} snell__profile;

#define SNELL__PROFILE_EXTS 6
extern const char snell__profile_ext[SNELL__PROFILE_EXTS][31];
extern const snell__profile snell__profiles[];
extern const int snell__profile_count;

/* The GL enum each limit is read with. */
extern const unsigned short snell__limit_enum[SNELL__LIMITS];

/* SNELL_OK if value fits the context's limit `which` (the GL context's,
 * lowered by its profile); else SNELL_E_UNSUPPORTED naming what, the limit
 * and the profile. */
snell_status snell__ctx_limit(snell_ctx *ctx, int which, int value, const char *what);
/* 1 if value fits the context's limit `which`, quietly. */
int snell__ctx_fits(const snell_ctx *ctx, int which, int value);

/* Each answer a profile can change (an extension, a limit check or value)
 * appended with its driver's own value to the file SNELL_PROFILE_TRACE names:
 * tests/scripts/profile_tests.py runs a test under another profile only when
 * one of its answers would differ there. */
void snell__profile_trace(const snell_ctx *ctx, const char *fmt, ...);

typedef char snell__limits_public[(int)SNELL__LIMITS == (int)SNELL_LIMIT_COUNT ? 1 : -1];

#endif
