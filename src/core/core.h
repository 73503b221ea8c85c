/* SPDX-License-Identifier: MIT */
/* core.h — allocation through the user's allocator and error reporting.
 * Every module reports failures with snell__fail(), which records the message
 * on the context (or thread-locally when there is none) and returns the status. */
#ifndef SNELL_CORE_H
#define SNELL_CORE_H

#include "snell/snell.h"
#include "snell_components.h" /* generated: SNELL_WITH_<X> 0/1 (cmake/components.cmake) */
#include <stdarg.h>
#include <stdio.h>

#if defined(__GNUC__)
#define SNELL_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define SNELL_PRINTF(a, b)
#endif

/* Per-thread state (the last error, a decode's allocation cap, the GL unit
 * scope); a compiler without it gets one shared copy: one thread only. */
#if defined(__GNUC__) || defined(__clang__)
#define SNELL__THREAD_LOCAL __thread
#elif defined(_MSC_VER)
#define SNELL__THREAD_LOCAL __declspec(thread)
#else
#define SNELL__THREAD_LOCAL
#endif

#define SNELL_PI 3.14159265358979323846

/* An allocator with NULL members filled in from libc. */
typedef struct snell_alloc {
    snell_allocator a;
} snell_alloc;

snell_alloc snell__alloc_from(const snell_allocator *user); /* user may be NULL */
const snell_alloc *snell__ctx_alloc(const snell_ctx *ctx);  /* libc allocator for NULL ctx */

void *snell__malloc(const snell_alloc *al, size_t size);
void *snell__calloc(const snell_alloc *al, size_t count, size_t size); /* overflow-checked */
void *snell__realloc(const snell_alloc *al, void *ptr, size_t size);
void snell__free(const snell_alloc *al, void *ptr);

/* Records "msg" as the last error of ctx (thread-local if ctx is NULL), logs it
 * at ERROR level if a log callback is installed, and returns status. */
snell_status snell__fail(const snell_ctx *ctx, snell_status status, const char *fmt, ...) SNELL_PRINTF(3, 4);
void snell__log(const snell_ctx *ctx, snell_log_level level, const char *fmt, ...) SNELL_PRINTF(3, 4);

/* The software rasteriser a GL_RENDERER string names (llvmpipe, softpipe,
 * SwiftShader, swrast), or NULL for hardware. The precision policy, the
 * shading rule and the 2D rasteriser rule all decide on it. */
const char *snell__software_rasteriser(const char *gl_renderer);

/* Monotonic clock in milliseconds (timing statistics). */
double snell__now_ms(void);

/* Opens an input file for reading: a regular file only, opened so that a FIFO
 * or a device cannot block (file.c). On failure: -1 / NULL, *opened 0 with
 * *why = strerror(errno) when open() failed, *opened 1 with *why "a directory"
 * or "not a regular file" when it was refused. */
int snell__open_regular(const char *path, int *opened, const char **why);
/* The same, refusing a symbolic link as the last component (a glTF's
 * external files, which must stay inside the folders the caller allowed). */
int snell__open_regular_nofollow(const char *path, int *opened, const char **why);
FILE *snell__fopen_regular(const char *path, int *opened, const char **why);

/* 1 where SNELL_DEBUG_HANDLES=1 (snell.h): destroyed contexts and meshes are
 * kept marked dead; snell__handle_dead then reports a second use and aborts. */
int snell__debug_handles(void);
void snell__handle_dead(const char *who, const void *handle);

/* s for a message: cut to fit buf's n bytes with "…" at a character's
 * boundary, newlines and tabs '?' (the message's own filter keeps them). */
const char *snell__quote(const char *s, char *buf, size_t n);

/* 1 if a column-major 4x4 matrix (a model matrix) has a non-zero, finite
 * determinant and a finite inverse: shading needs its inverse transpose.
 * Else 0, and why (if not NULL) says whether it is singular or its
 * determinant only overflows or underflows float ("is singular ..."). */
int snell__matrix_invertible(const float m[16], char *why, size_t n);
/* inv = m's inverse (cglm's glm_mat4_inv, one copy rather than one inlined
 * at every caller: the device build's footprint). Both 16-byte aligned (mat4). */
void snell__mat4_inv(const float m[16], float inv[16]);
/* out = a x b (glm_mat4_mul, one copy likewise). */
void snell__mat4_mul(const float a[16], const float b[16], float out[16]);

/* The context's memory budget (snell_ctx_desc.memory_budget; the default for NULL). */
size_t snell__ctx_budget(const snell_ctx *ctx);
/* SNELL_OK if one request of `bytes` for `what` (e.g. "OBJ positions") fits
 * the budget, else SNELL_E_LIMIT with a message naming the request and the
 * budget. Called before the allocation. */
snell_status snell__budget_check(const snell_ctx *ctx, size_t bytes, const char *what);

/* snell_image_read / snell_image_decode within a given memory budget (a
 * context's, for environments); they report on the thread-local message. */
snell_status snell__image_read_budget(const char *path, size_t budget, int *width, int *height, uint8_t **rgba);
snell_status snell__image_decode_budget(const void *data, size_t size, size_t budget, int *width, int *height,
                                        uint8_t **rgba);

/* size_t multiplication that reports overflow (returns 0 and sets *ok = 0). */
size_t snell__mul_size(size_t a, size_t b, int *ok);

/* snprintf for the reasons people read: a text longer than n - 1 bytes is
 * cut at a character boundary and ends in "..." (with n >= 4). */
void snell__why(char *why, size_t n, const char *fmt, ...) SNELL_PRINTF(3, 4);

#endif
