/* SPDX-License-Identifier: MIT */
/* textures.h — texture units bound per program, by sampler name. A program's
 * samplers get units 0..n-1, once, when it is linked (snell__samplers_assign);
 * whoever made a texture publishes it under the name of the sampler that reads
 * it (the frame's snell__view.textures, or binds it directly), and each program
 * binds what its own source declares when it is used. No unit is reserved
 * frame-wide, so a program takes only the units it really samples, and a
 * variant that would need more than the context has fails when built. */
#ifndef SNELL_TEXTURES_H
#define SNELL_TEXTURES_H

#include "core/core.h"

/* The most samplers one program may have: what GLES 3.0 guarantees for the
 * fragment stage (GL_MAX_TEXTURE_IMAGE_UNITS >= 16). */
#define SNELL__PROGRAM_SAMPLERS 16
/* The most textures a frame publishes at once. */
#define SNELL__FRAME_TEXTURES 16

typedef struct snell__texture {
    const char *name;               /* the sampler's name in GLSL, a string literal */
    unsigned hash;                  /* of name (snell__sampler_hash) */
    unsigned target, texture, sampler; /* sampler: a sampler object, 0 none */
} snell__texture;

typedef struct snell__textures {
    int count;
    snell__texture t[SNELL__FRAME_TEXTURES];
} snell__textures;

/* A program's samplers: unit i reads the sampler whose name hashes to hash[i]. */
typedef struct snell__samplers {
    int count;
    unsigned hash[SNELL__PROGRAM_SAMPLERS];
} snell__samplers;

unsigned snell__sampler_hash(const char *name);

/* Publishes (or replaces) the texture read by samplers called name. */
void snell__textures_publish(snell__textures *ts, const char *name, unsigned target, unsigned texture,
                             unsigned sampler);

/* Gives each active sampler of the linked program prog its unit and sets its
 * uniform once. Fails with SNELL_E_UNSUPPORTED, naming the samplers, when
 * they are more than the context's fragment units (or than
 * SNELL__PROGRAM_SAMPLERS); `what` names the program in that message. */
snell_status snell__samplers_assign(snell_ctx *ctx, unsigned prog, const char *what, snell__samplers *s);
/* The unit of the sampler called name, -1 if the program has none. */
int snell__samplers_unit(const snell__samplers *s, const char *name);
/* Binds texture (and sampler object, 0 none) on the unit of the sampler
 * called name; nothing if the program has none. Leaves unit 0 active. */
void snell__samplers_bind(const snell__samplers *s, const char *name, unsigned target, unsigned texture,
                          unsigned sampler);
/* Binds every published texture the program samples. Leaves unit 0 active. */
void snell__samplers_bind_published(const snell__samplers *s, const snell__textures *ts);

#endif
