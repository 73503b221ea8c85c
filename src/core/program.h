/* SPDX-License-Identifier: MIT */
/* program.h — builds GL programs from the embedded shaders_es/ sources.
 * A source may contain lines `#include "common/x.glsl"`; each chunk is pasted
 * once. The builder prepends `#version 300 es` and the caller's defines, and
 * reports compile/link errors with the info log in the context's message. */
#ifndef SNELL_PROGRAM_H
#define SNELL_PROGRAM_H

#include "core/core.h"

/* The context's shader precision policy: 1 if SNELL_MEDIUMP is mediump. */
int snell__ctx_fragment_mediump(snell_ctx *ctx);

/* Embedded source by path relative to shaders_es/, or NULL. */
const char *snell__shader_source(const char *path);

/* Compiles vs_path + fs_path (embedded files) with `defines` (may be NULL,
 * e.g. "#define FOO 1\n") inserted after #version. */
snell_status snell__program_build(snell_ctx *ctx, const char *vs_path, const char *fs_path,
                                  const char *defines, unsigned *out_program);

/* Same from in-memory sources (used by tests and for generated variants). */
snell_status snell__program_build_src(snell_ctx *ctx, const char *vs_src, const char *fs_src,
                                      const char *defines, unsigned *out_program);

/* Transform-feedback program: the fragment stage discards; varyings captured
 * interleaved-separately (GL_SEPARATE_ATTRIBS). */
snell_status snell__program_build_feedback(snell_ctx *ctx, const char *vs_src, const char *defines,
                                           const char *const *varyings, int n_varyings,
                                           unsigned *out_program);

#endif
