/* ctx.h — the context: allocator, logging, the platform backend that owns (or
 * borrows) the EGL context, GL capabilities probed once, and saved GL state. */
#ifndef SNELL_CTX_H
#define SNELL_CTX_H

#include "core/core.h"
#include "core/platform.h"

struct snell_ctx {
    snell_alloc alloc;
    snell_log_fn log;
    void *log_user;
    snell_backend backend;          /* the one in use after fallbacks */
    snell_platform platform;
    char gl_renderer[128];
    char *gl_extensions;            /* space-separated, with a leading and trailing space */
    int has_khr_debug;
    int debug_installed;
    char last_error[1024];
};

#endif
