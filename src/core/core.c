/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
/* core.c — allocator plumbing, status names, error/log reporting, the clock. */
#include "core/core.h"
#include "core/ctx.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static SNELL__THREAD_LOCAL char g_thread_error[1024];

static void *libc_alloc(size_t size, void *user) { (void)user; return malloc(size); }
static void *libc_realloc(void *p, size_t size, void *user) { (void)user; return realloc(p, size); }
static void libc_free(void *p, void *user) { (void)user; free(p); }

static const snell_alloc g_libc_alloc = {{libc_alloc, libc_realloc, libc_free, NULL}};

snell_alloc snell__alloc_from(const snell_allocator *user)
{
    snell_alloc al = g_libc_alloc;
    if (user) {
        if (user->alloc) al.a.alloc = user->alloc;
        if (user->realloc) al.a.realloc = user->realloc;
        if (user->free) al.a.free = user->free;
        al.a.user = user->user;
    }
    return al;
}

const snell_alloc *snell__ctx_alloc(const snell_ctx *ctx)
{
    return ctx ? &ctx->alloc : &g_libc_alloc;
}

void *snell__malloc(const snell_alloc *al, size_t size)
{
    return al->a.alloc(size ? size : 1, al->a.user);
}

void *snell__calloc(const snell_alloc *al, size_t count, size_t size)
{
    int ok = 1;
    size_t total = snell__mul_size(count, size, &ok);
    void *p;
    if (!ok) return NULL;
    p = snell__malloc(al, total);
    if (p) memset(p, 0, total);
    return p;
}

void *snell__realloc(const snell_alloc *al, void *ptr, size_t size)
{
    return al->a.realloc(ptr, size ? size : 1, al->a.user);
}

void snell__free(const snell_alloc *al, void *ptr)
{
    if (ptr) al->a.free(ptr, al->a.user);
}

size_t snell__ctx_budget(const snell_ctx *ctx)
{
    return ctx && ctx->memory_budget ? ctx->memory_budget : SNELL_DEFAULT_MEMORY_BUDGET;
}

snell_status snell__budget_check(const snell_ctx *ctx, size_t bytes, const char *what)
{
    size_t budget = snell__ctx_budget(ctx);
    if (bytes <= budget) return SNELL_OK;
    /* when both round to the same MiB, bytes say how far over it is */
    if ((size_t)((double)bytes / 104857.6) == (size_t)((double)budget / 104857.6))
        return snell__fail(ctx, SNELL_E_LIMIT,
                           "%s needs %zu bytes, more than the memory budget of %zu bytes (snell_ctx_desc.memory_budget)",
                           what, bytes, budget);
    return snell__fail(ctx, SNELL_E_LIMIT,
                       "%s needs %.1f MiB, more than the memory budget of %.1f MiB (snell_ctx_desc.memory_budget)",
                       what, (double)bytes / 1048576.0, (double)budget / 1048576.0);
}

size_t snell__mul_size(size_t a, size_t b, int *ok)
{
    if (a && b > (size_t)-1 / a) {
        *ok = 0;
        return 0;
    }
    return a * b;
}

void snell__why(char *why, size_t n, const char *fmt, ...)
{
    va_list ap;
    int len;
    if (!why || !n) return;
    va_start(ap, fmt);
    len = vsnprintf(why, n, fmt, ap);
    va_end(ap);
    /* A cut reason ends in "...", so that it reads as cut (and a word sought
     * in it cannot match a cut word's first letters); the cut goes back to the
     * start of a UTF-8 character, not through one. */
    if (len >= 0 && (size_t)len >= n && n >= 4) {
        size_t k = n - 4;
        while (k > 0 && ((unsigned char)why[k] & 0xC0) == 0x80) k--;
        memcpy(why + k, "...", 4);
    }
}

static const char g_components[] = SNELL__COMPONENTS;

const char *snell_build_components(void) { return g_components; }

int snell_build_has(const char *component)
{
    const char *p = g_components;
    size_t n = component ? strlen(component) : 0;
    if (n == 0) return 0;
    while ((p = strstr(p, component)) != NULL) {
        int starts = p == g_components || p[-1] == ' ', ends = p[n] == '\0' || p[n] == ' ';
        if (starts && ends) return 1;
        p += n;
    }
    return 0;
}

const char *snell_status_str(snell_status s)
{
    switch (s) {
    case SNELL_OK: return "SNELL_OK";
    case SNELL_E_INVALID_ARG: return "SNELL_E_INVALID_ARG";
    case SNELL_E_IO: return "SNELL_E_IO";
    case SNELL_E_PARSE: return "SNELL_E_PARSE";
    case SNELL_E_GL: return "SNELL_E_GL";
    case SNELL_E_EGL: return "SNELL_E_EGL";
    case SNELL_E_UNSUPPORTED: return "SNELL_E_UNSUPPORTED";
    case SNELL_E_NOMEM: return "SNELL_E_NOMEM";
    case SNELL_E_LIMIT: return "SNELL_E_LIMIT";
    }
    return "SNELL_E_UNKNOWN";
}

const char *snell_last_error(const snell_ctx *ctx)
{
    return ctx ? ctx->last_error : g_thread_error;
}

/* Messages quote file names and file content (tokens, URIs, tinygltf's
 * errors); a terminal would act on their control characters (ESC sequences
 * retitle or clear it, BEL rings). Every C0 control but newline and tab, DEL
 * and the UTF-8 encoded C1 controls (U+0080..U+009F) become '?'. */
static void scrub(char *s)
{
    unsigned char *p = (unsigned char *)s;
    for (; *p; p++) {
        if ((*p < 0x20 && *p != '\n' && *p != '\t') || *p == 0x7f) *p = '?';
        else if (*p == 0xc2 && p[1] >= 0x80 && p[1] <= 0x9f) p[0] = p[1] = '?';
    }
}

int snell__debug_handles(void)
{
    static int on = -1; /* read once: a race writes the same value */
    if (on < 0) {
        const char *v = getenv("SNELL_DEBUG_HANDLES");
        on = v && !strcmp(v, "1");
    }
    return on;
}

void snell__handle_dead(const char *who, const void *handle)
{
    /* the one place the library prints and aborts: the user asked for it */
    fprintf(stderr, "snell: %s: %p was already destroyed (SNELL_DEBUG_HANDLES)\n", who, handle);
    abort();
}

const char *snell__quote(const char *s, char *buf, size_t n)
{
    size_t len = strlen(s), i;
    if (len < n) {
        memcpy(buf, s, len + 1);
    } else { /* cut where a UTF-8 character begins, then the ellipsis */
        len = n - 4;
        while (len > 0 && ((unsigned char)s[len] & 0xc0) == 0x80) len--;
        memcpy(buf, s, len);
        memcpy(buf + len, "\xe2\x80\xa6", 4);
    }
    for (i = 0; buf[i]; i++)
        if (buf[i] == '\n' || buf[i] == '\t') buf[i] = '?';
    return buf;
}

static void vlog(const snell_ctx *ctx, snell_log_level level, const char *fmt, va_list ap)
{
    char buf[1024];
    if (!ctx || !ctx->log) return;
    vsnprintf(buf, sizeof buf, fmt, ap);
    scrub(buf);
    ctx->log(level, buf, ctx->log_user);
}

snell_status snell__fail(const snell_ctx *ctx, snell_status status, const char *fmt, ...)
{
    va_list ap;
    /* The message buffer is part of the context's bookkeeping, not of its GL
     * state, so writing it through a const pointer is acceptable here. */
    char *dst = ctx ? ((snell_ctx *)ctx)->last_error : g_thread_error;
    size_t cap = ctx ? sizeof ctx->last_error : sizeof g_thread_error;
    va_start(ap, fmt);
    vsnprintf(dst, cap, fmt, ap);
    va_end(ap);
    scrub(dst);
    if (ctx && ctx->log) ctx->log(SNELL_LOG_ERROR, dst, ctx->log_user);
    return status;
}

void snell__log(const snell_ctx *ctx, snell_log_level level, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vlog(ctx, level, fmt, ap);
    va_end(ap);
}

double snell__now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

const char *snell__software_rasteriser(const char *gl_renderer)
{
    static const char *const names[] = {"llvmpipe", "softpipe", "SwiftShader", "swrast"};
    size_t i;
    for (i = 0; gl_renderer && i < sizeof names / sizeof *names; i++)
        if (strstr(gl_renderer, names[i])) return names[i];
    return NULL;
}
