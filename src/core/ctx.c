/* SPDX-License-Identifier: MIT */
/* ctx.c — context creation over the platform backends, GL capability probing
 * and KHR_debug forwarding to the log callback. */
#include "core/ctx.h"
#include "core/gl.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static pthread_mutex_t g_ref_lock = PTHREAD_MUTEX_INITIALIZER;

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
    for (i = 0; i < SNELL__LIMITS; i++) {
        GLint v = 0;
        glGetIntegerv(snell__limit_enum[i], &v);
        ctx->limit_raw[i] = v;
        ctx->limit[i] = ctx->profile && ctx->profile->limit[i] < v ? ctx->profile->limit[i] : v;
    }
    ctx->cost = snell__device_cost_find(ctx->gl_renderer);
    return SNELL_OK;
}

/* The profile named by the description, else by SNELL_DEVICE_PROFILE. */
static snell_status find_profile(const char *name, const snell__profile **out)
{
    char names[96] = "", quoted[64];
    int i;
    *out = NULL;
    if (!name) name = getenv("SNELL_DEVICE_PROFILE");
    if (!name || !*name) return SNELL_OK;
    for (i = 0; i < snell__profile_count; i++) {
        if (strcmp(name, snell__profiles[i].name) == 0) {
            *out = &snell__profiles[i];
            return SNELL_OK;
        }
        snprintf(names + strlen(names), sizeof names - strlen(names), " %s", snell__profiles[i].name);
    }
    return snell__fail(NULL, SNELL_E_INVALID_ARG, "unknown device profile \"%s\" (known:%s)",
                       snell__quote(name, quoted, sizeof quoted), names);
}

/* Installs snell's KHR_debug callback, keeping the one it replaces (a host's
 * with its user pointer), or puts that one back. */
static void install_debug(snell_ctx *ctx, int enable)
{
    PFNGLDEBUGMESSAGECALLBACKKHRPROC cb;
    PFNGLGETPOINTERVKHRPROC get;
    GLDEBUGPROCKHR host;
    if (!ctx->log) return; /* asked only then: a profile's KHR_debug changes nothing else */
    if (enable) ctx->has_khr_debug = snell_ctx_has_gl_extension(ctx, "GL_KHR_debug");
    if (!ctx->has_khr_debug) return;
    cb = (PFNGLDEBUGMESSAGECALLBACKKHRPROC)snell__platform_proc(&ctx->platform, "glDebugMessageCallbackKHR");
    get = (PFNGLGETPOINTERVKHRPROC)snell__platform_proc(&ctx->platform, "glGetPointervKHR");
    if (!cb) return;
    if (enable) {
        if (get) {
            get(GL_DEBUG_CALLBACK_FUNCTION_KHR, &ctx->host_debug[0]);
            get(GL_DEBUG_CALLBACK_USER_PARAM_KHR, &ctx->host_debug[1]);
        }
        cb(debug_callback, ctx);
        if (ctx->backend != SNELL_BACKEND_EXTERNAL) glEnable(GL_DEBUG_OUTPUT_KHR);
    } else {
        memcpy(&host, &ctx->host_debug[0], sizeof host);
        cb(host, ctx->host_debug[1]);
    }
}

snell_status snell_ctx_create(const snell_ctx_desc *desc, snell_ctx **out)
{
    snell_ctx_desc d;
    snell_alloc al;
    snell_ctx *ctx;
    snell_status st;
    const snell__profile *profile;

    if (!out) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ctx_create: out is NULL");
    *out = NULL;
    memset(&d, 0, sizeof d);
    if (desc) d = *desc;
    if ((unsigned)d.backend > SNELL_BACKEND_EXTERNAL)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ctx_create: unknown backend %d", (int)d.backend);
    if ((st = find_profile(d.device_profile, &profile)) != SNELL_OK) return st;
    al = snell__alloc_from(&d.allocator);
    ctx = (snell_ctx *)snell__calloc(&al, 1, sizeof *ctx);
    if (!ctx) return snell__fail(NULL, SNELL_E_NOMEM, "snell_ctx_create: out of memory");
    ctx->alloc = al;
    ctx->refs = 1; /* the caller's handle */
    ctx->profile = profile;
    ctx->profile_trace = getenv("SNELL_PROFILE_TRACE");
    ctx->log = d.log;
    ctx->log_user = d.log_user;
    ctx->memory_budget = d.memory_budget ? d.memory_budget : SNELL_DEFAULT_MEMORY_BUDGET;
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
    ctx->gl_context = ctx->platform.context;
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

void snell__ctx_retain(snell_ctx *ctx)
{
    if (!ctx) return;
    pthread_mutex_lock(&g_ref_lock);
    ctx->refs++;
    pthread_mutex_unlock(&g_ref_lock);
}

void snell__ctx_release(snell_ctx *ctx)
{
    snell_alloc al;
    int last;
    if (!ctx) return;
    pthread_mutex_lock(&g_ref_lock);
    last = --ctx->refs == 0;
    pthread_mutex_unlock(&g_ref_lock);
    if (!last || snell__debug_handles()) return; /* kept destroyed, so that a second destroy is caught */
    al = ctx->alloc;
#ifdef SNELL_WITH_GLX
    if (ctx->platform.glx.lib) dlclose(ctx->platform.glx.lib); /* kept for the late destroys' scopes */
#endif
    snell__free(&al, ctx->gl_extensions);
    snell__free(&al, ctx);
}

/* Objects may outlive their context (snell.h, snell_ctx_destroy): the GL
 * context goes now, the struct with the last object. */
void snell_ctx_destroy(snell_ctx *ctx)
{
    if (ctx && ctx->destroyed && snell__debug_handles()) snell__handle_dead("snell_ctx_destroy", ctx);
    if (!ctx || ctx->destroyed) return;
    if (ctx->debug_installed) {
        snell__gl_scope sc;
        if (snell__gl_scope_enter(ctx, &sc)) install_debug(ctx, 0);
        snell__gl_scope_leave(&sc);
    }
    snell__platform_close(&ctx->platform);
    ctx->destroyed = 1;
    ctx->log = NULL; /* the caller may free log_user now */
    snell__ctx_release(ctx);
}

snell_status snell_ctx_make_current(snell_ctx *ctx)
{
    snell_platform *p;
    if (!ctx) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ctx_make_current: ctx is NULL");
    if (ctx->destroyed)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_ctx_make_current: the context was destroyed");
    p = &ctx->platform;
    if (!p->owns_context) {
        if (snell__platform_current(p) == ctx->gl_context) return SNELL_OK;
        return snell__fail(ctx, SNELL_E_INVALID_ARG,
                           "snell_ctx_make_current: EXTERNAL context: the host's GL context it was created on is "
                           "not current on this thread (the host makes it current, snell cannot)");
    }
    if (!eglMakeCurrent(p->display, p->surface, p->surface, p->context))
        return snell__fail(ctx, SNELL_E_EGL, "snell_ctx_make_current: eglMakeCurrent failed: %s",
                           snell__egl_error_str(eglGetError()));
    return SNELL_OK;
}

snell_status snell__ctx_check_current(snell_ctx *ctx, const char *who)
{
    if (ctx->destroyed)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: its context was destroyed (snell_ctx_destroy)", who);
    if (snell__platform_current(&ctx->platform) != ctx->gl_context)
        return snell__fail(ctx, SNELL_E_INVALID_ARG,
                           ctx->platform.owns_context
                               ? "%s: the context's GL context is not current on this thread (another context was "
                                 "created or made current since): call snell_ctx_make_current first"
                               : "%s: the host's GL context this EXTERNAL context was created on is not current on "
                                 "this thread",
                           who);
    return SNELL_OK;
}

#ifdef SNELL_WITH_GLX
/* A GLX host's context, as snell__gl_scope_enter does for EGL below. */
static int glx_scope_enter(const snell_ctx *ctx, snell__gl_scope *s)
{
    const snell__glx *g = s->glx;
    s->context = g->current();
    s->display = g->display();
    s->glx_draw = g->draw();
    s->glx_read = g->read();
    if (s->context && s->context == ctx->gl_context && !ctx->destroyed) return 1;
    if (s->context && g->make_current(s->display, 0, 0, NULL)) s->switched = 1;
    return 0;
}
#endif

int snell__gl_scope_enter(snell_ctx *ctx, snell__gl_scope *s)
{
    s->switched = 0;
#ifdef SNELL_WITH_GLX
    s->glx = ctx && ctx->platform.glx.lib ? &ctx->platform.glx : NULL;
    if (s->glx) return glx_scope_enter(ctx, s);
#endif
    s->display = eglGetCurrentDisplay();
    s->draw = eglGetCurrentSurface(EGL_DRAW);
    s->read = eglGetCurrentSurface(EGL_READ);
    s->context = eglGetCurrentContext();
    s->used_display = s->display;
    if (ctx && ctx->platform.foreign) return !ctx->destroyed; /* nothing to detach it with */
    if (ctx && !ctx->destroyed) {
        const snell_platform *p = &ctx->platform;
        if (s->context != EGL_NO_CONTEXT && s->context == ctx->gl_context) return 1;
        if (p->owns_context && eglMakeCurrent(p->display, p->surface, p->surface, p->context)) {
            s->used_display = p->display;
            s->switched = 1;
            return 1;
        }
    }
    /* No context current: the GL calls that follow reach none (the GL spec
     * leaves them undefined; the dispatch of libglvnd, Mesa and Android
     * ignores them), so they cannot delete another context's objects. */
    if (s->context != EGL_NO_CONTEXT && eglMakeCurrent(s->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT))
        s->switched = 1;
    return 0;
}

void snell__gl_scope_leave(const snell__gl_scope *s)
{
    if (!s->switched) return;
#ifdef SNELL_WITH_GLX
    if (s->glx) {
        s->glx->make_current(s->display, s->glx_draw, s->glx_read, s->context);
        return;
    }
#endif
    if (s->context != EGL_NO_CONTEXT) eglMakeCurrent(s->display, s->draw, s->read, s->context);
    else eglMakeCurrent(s->used_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
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

/* Under a profile, only the extensions it lists (and the GL context has). */
int snell__light_fixed(snell_ctx *ctx)
{
    /* float blending first: without it (most devices) the float target's answer changes nothing */
    if (!ctx->light_fixed)
        ctx->light_fixed = !snell_ctx_has_gl_extension(ctx, "GL_EXT_float_blend") ||
                                   !snell_ctx_has_gl_extension(ctx, "GL_EXT_color_buffer_float")
                               ? 1
                               : -1;
    return ctx->light_fixed > 0;
}

int snell_ctx_has_gl_extension(const snell_ctx *ctx, const char *name)
{
    char token[128];
    int i, has;
    if (!ctx || !ctx->gl_extensions || !name || strlen(name) + 3 > sizeof token) return 0;
    snprintf(token, sizeof token, " %s ", name);
    has = strstr(ctx->gl_extensions, token) != NULL;
    snell__profile_trace(ctx, "ext %d %s", has, name);
    if (ctx->profile) {
        for (i = 0; i < SNELL__PROFILE_EXTS && strcmp(name, snell__profile_ext[i]) != 0; i++) {}
        if (i == SNELL__PROFILE_EXTS || !(ctx->profile->ext >> i & 1)) return 0;
    }
    return has;
}

const char *snell_ctx_gl_renderer(const snell_ctx *ctx) { return ctx ? ctx->gl_renderer : ""; }
