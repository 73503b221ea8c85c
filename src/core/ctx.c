/* ctx.c — context creation over the platform backends, GL capability probing
 * and KHR_debug forwarding to the log callback. */
#include "core/ctx.h"
#include "core/gl.h"

#include <stdio.h>
#include <string.h>

static void GL_APIENTRY debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity,
                                       GLsizei length, const GLchar *message, const void *user)
{
    const snell_ctx *ctx = (const snell_ctx *)user;
    snell_log_level level = SNELL_LOG_DEBUG;
    (void)source; (void)length;
    if (severity == GL_DEBUG_SEVERITY_HIGH_KHR) level = SNELL_LOG_ERROR;
    else if (severity == GL_DEBUG_SEVERITY_MEDIUM_KHR || type == GL_DEBUG_TYPE_ERROR_KHR) level = SNELL_LOG_WARN;
    else if (severity == GL_DEBUG_SEVERITY_LOW_KHR) level = SNELL_LOG_INFO;
    snell__log(ctx, level, "GL debug [%u]: %s", id, message);
}

/* Reads GL_EXTENSIONS via glGetStringi (ES 3.0) into one " a b c " string so
 * lookups are exact-token matches. */
static snell_status probe_gl(snell_ctx *ctx)
{
    GLint count = 0, i;
    size_t len = 2;
    char *p;
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    const char *version = (const char *)glGetString(GL_VERSION);
    GLint major = 0;
    if (!version)
        return snell__fail(ctx, SNELL_E_GL, "glGetString(GL_VERSION) returned NULL: no usable GL context");
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    if (major < 3 || strncmp(version, "OpenGL ES", 9) != 0)
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "OpenGL ES 3.0 or newer required, context is \"%s\"", version);
    snprintf(ctx->gl_renderer, sizeof ctx->gl_renderer, "%s", renderer ? renderer : "unknown");
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (i = 0; i < count; i++) len += strlen((const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i)) + 1;
    ctx->gl_extensions = (char *)snell__malloc(&ctx->alloc, len + 1);
    if (!ctx->gl_extensions) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for the extension list");
    p = ctx->gl_extensions;
    *p++ = ' ';
    for (i = 0; i < count; i++) {
        const char *e = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        size_t n = strlen(e);
        memcpy(p, e, n);
        p += n;
        *p++ = ' ';
    }
    *p = '\0';
    ctx->has_khr_debug = snell_ctx_has_gl_extension(ctx, "GL_KHR_debug");
    return SNELL_OK;
}

static void install_debug(snell_ctx *ctx, int enable)
{
    PFNGLDEBUGMESSAGECALLBACKKHRPROC cb;
    if (!ctx->has_khr_debug || !ctx->log) return;
    cb = (PFNGLDEBUGMESSAGECALLBACKKHRPROC)eglGetProcAddress("glDebugMessageCallbackKHR");
    if (!cb) return;
    if (enable) {
        cb(debug_callback, ctx);
        if (ctx->backend != SNELL_BACKEND_EXTERNAL) glEnable(GL_DEBUG_OUTPUT_KHR);
    } else {
        cb(NULL, NULL);
    }
}

snell_status snell_ctx_create(const snell_ctx_desc *desc, snell_ctx **out)
{
    snell_ctx_desc d;
    snell_alloc al;
    snell_ctx *ctx;
    snell_status st;

    if (!out) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ctx_create: out is NULL");
    *out = NULL;
    memset(&d, 0, sizeof d);
    if (desc) d = *desc;
    if ((unsigned)d.backend > SNELL_BACKEND_EXTERNAL)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ctx_create: unknown backend %d", (int)d.backend);
    al = snell__alloc_from(&d.allocator);
    ctx = (snell_ctx *)snell__calloc(&al, 1, sizeof *ctx);
    if (!ctx) return snell__fail(NULL, SNELL_E_NOMEM, "snell_ctx_create: out of memory");
    ctx->alloc = al;
    ctx->log = d.log;
    ctx->log_user = d.log_user;
    ctx->platform.display = EGL_NO_DISPLAY;
    ctx->platform.context = EGL_NO_CONTEXT;
    ctx->platform.surface = EGL_NO_SURFACE;

    switch (d.backend) {
    case SNELL_BACKEND_DEFAULT:
    case SNELL_BACKEND_SURFACELESS:
        ctx->backend = SNELL_BACKEND_SURFACELESS;
        st = snell__platform_open_surfaceless(ctx, &ctx->platform, d.gl_debug);
        if (st != SNELL_OK) {
            snell__log(ctx, SNELL_LOG_INFO, "surfaceless EGL failed (%s); falling back to a pbuffer",
                       ctx->last_error);
            snell__platform_close(&ctx->platform);
            ctx->backend = SNELL_BACKEND_PBUFFER;
            st = snell__platform_open_pbuffer(ctx, &ctx->platform, d.gl_debug);
        }
        break;
    case SNELL_BACKEND_PBUFFER:
        ctx->backend = SNELL_BACKEND_PBUFFER;
        st = snell__platform_open_pbuffer(ctx, &ctx->platform, d.gl_debug);
        break;
    default:
        ctx->backend = SNELL_BACKEND_EXTERNAL;
        st = snell__platform_open_external(ctx, &ctx->platform);
        break;
    }
    if (st == SNELL_OK) st = probe_gl(ctx);
    if (st != SNELL_OK) {
        /* Copy the message out before the context (which holds it) is freed. */
        snell__fail(NULL, st, "%s", ctx->last_error);
        snell_ctx_destroy(ctx);
        return st;
    }
    /* A host's context may have its own debug callback: only take it over when asked. */
    ctx->debug_installed = ctx->backend != SNELL_BACKEND_EXTERNAL || d.gl_debug;
    if (ctx->debug_installed) install_debug(ctx, 1);
    *out = ctx;
    return SNELL_OK;
}

void snell_ctx_destroy(snell_ctx *ctx)
{
    snell_alloc al;
    if (!ctx) return;
    if (ctx->debug_installed) install_debug(ctx, 0);
    snell__platform_close(&ctx->platform);
    al = ctx->alloc;
    snell__free(&al, ctx->gl_extensions);
    snell__free(&al, ctx);
}

snell_backend snell_ctx_backend(const snell_ctx *ctx) { return ctx ? ctx->backend : SNELL_BACKEND_DEFAULT; }

const char *snell_backend_str(snell_backend b)
{
    switch (b) {
    case SNELL_BACKEND_DEFAULT: return "default";
    case SNELL_BACKEND_SURFACELESS: return "surfaceless";
    case SNELL_BACKEND_PBUFFER: return "pbuffer";
    case SNELL_BACKEND_EXTERNAL: return "external";
    }
    return "unknown";
}

int snell_ctx_has_gl_extension(const snell_ctx *ctx, const char *name)
{
    char token[128];
    if (!ctx || !ctx->gl_extensions || !name || strlen(name) + 3 > sizeof token) return 0;
    snprintf(token, sizeof token, " %s ", name);
    return strstr(ctx->gl_extensions, token) != NULL;
}

const char *snell_ctx_gl_renderer(const snell_ctx *ctx) { return ctx ? ctx->gl_renderer : ""; }
