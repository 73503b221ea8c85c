/* SPDX-License-Identifier: MIT */
/* platform_egl.c — EGL code shared by the surfaceless and pbuffer backends:
 * extension checks, platform displays, config choice and ES 3.0 context creation. */
#include "core/ctx.h"

#include <pthread.h>
#include <string.h>

#ifndef EGL_OPENGL_ES3_BIT
#define EGL_OPENGL_ES3_BIT 0x0040
#endif
#ifndef EGL_CONTEXT_MAJOR_VERSION
#define EGL_CONTEXT_MAJOR_VERSION 0x3098
#endif
#ifndef EGL_CONTEXT_MINOR_VERSION
#define EGL_CONTEXT_MINOR_VERSION 0x30FB
#endif
#ifndef EGL_CONTEXT_OPENGL_DEBUG
#define EGL_CONTEXT_OPENGL_DEBUG 0x31B0
#endif

typedef EGLDisplay (*get_platform_display_fn)(EGLenum, void *, const EGLint *);

int snell__egl_has_extension(const char *list, const char *name)
{
    size_t n = strlen(name);
    const char *p = list;
    if (!list || !n) return 0;
    while ((p = strstr(p, name)) != NULL) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return 1;
        p += n;
    }
    return 0;
}

const char *snell__egl_error_str(EGLint err)
{
    switch (err) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "EGL error";
    }
}

EGLDisplay snell__egl_platform_display(EGLenum platform, void *native)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    get_platform_display_fn fn = NULL;
    /* eglGetPlatformDisplay is core in EGL 1.5; the EXT entry point covers 1.4. */
    fn = (get_platform_display_fn)eglGetProcAddress("eglGetPlatformDisplay");
    if (!fn && client && snell__egl_has_extension(client, "EGL_EXT_platform_base"))
        fn = (get_platform_display_fn)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!fn) return EGL_NO_DISPLAY;
    return fn(platform, native, NULL);
}

snell_status snell__egl_make_context(snell_ctx *ctx, snell_platform *p, EGLint surface_type,
                                     int want_pbuffer, int debug)
{
    EGLint cfg_attrs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT,
                          EGL_SURFACE_TYPE, surface_type,
                          EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                          EGL_NONE};
    EGLint ctx_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0,
                          EGL_NONE, EGL_NONE, EGL_NONE};
    EGLint pb_attrs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    EGLConfig config;
    EGLint n = 0;

    if (!eglBindAPI(EGL_OPENGL_ES_API))
        return snell__fail(ctx, SNELL_E_EGL, "eglBindAPI(EGL_OPENGL_ES_API) failed: %s",
                           snell__egl_error_str(eglGetError()));
    if (!eglChooseConfig(p->display, cfg_attrs, &config, 1, &n) || n < 1)
        return snell__fail(ctx, SNELL_E_EGL, "no EGL config with OpenGL ES 3 and surface type 0x%x (%s)",
                           (unsigned)surface_type, snell__egl_error_str(eglGetError()));
    if (debug) {
        ctx_attrs[4] = EGL_CONTEXT_OPENGL_DEBUG;
        ctx_attrs[5] = EGL_TRUE;
    }
    p->context = eglCreateContext(p->display, config, EGL_NO_CONTEXT, ctx_attrs);
    if (p->context == EGL_NO_CONTEXT && debug) {
        /* Some drivers reject the debug attribute; a plain context still works. */
        ctx_attrs[4] = EGL_NONE;
        p->context = eglCreateContext(p->display, config, EGL_NO_CONTEXT, ctx_attrs);
    }
    if (p->context == EGL_NO_CONTEXT)
        return snell__fail(ctx, SNELL_E_EGL, "eglCreateContext(OpenGL ES 3.0) failed: %s",
                           snell__egl_error_str(eglGetError()));
    p->owns_context = 1;
    if (want_pbuffer) {
        p->surface = eglCreatePbufferSurface(p->display, config, pb_attrs);
        if (p->surface == EGL_NO_SURFACE)
            return snell__fail(ctx, SNELL_E_EGL, "eglCreatePbufferSurface failed: %s",
                               snell__egl_error_str(eglGetError()));
    }
    if (!eglMakeCurrent(p->display, p->surface, p->surface, p->context))
        return snell__fail(ctx, SNELL_E_EGL, "eglMakeCurrent failed: %s",
                           snell__egl_error_str(eglGetError()));
    return SNELL_OK;
}

/* EGL displays are per-process singletons: two snell contexts on the same
 * display must not eglTerminate it under each other. */
#define MAX_DISPLAYS 8
static pthread_mutex_t g_display_lock = PTHREAD_MUTEX_INITIALIZER;
static struct { EGLDisplay d; int refs; } g_displays[MAX_DISPLAYS];

void snell__egl_display_ref(EGLDisplay d)
{
    int i, free_slot = -1;
    pthread_mutex_lock(&g_display_lock);
    for (i = 0; i < MAX_DISPLAYS; i++) {
        if (g_displays[i].refs && g_displays[i].d == d) {
            g_displays[i].refs++;
            pthread_mutex_unlock(&g_display_lock);
            return;
        }
        if (!g_displays[i].refs && free_slot < 0) free_slot = i;
    }
    if (free_slot >= 0) {
        g_displays[free_slot].d = d;
        g_displays[free_slot].refs = 1;
    }
    pthread_mutex_unlock(&g_display_lock);
}

/* Returns nonzero when the last reference went away (caller terminates). */
static int display_unref(EGLDisplay d)
{
    int i, last = 0;
    pthread_mutex_lock(&g_display_lock);
    for (i = 0; i < MAX_DISPLAYS; i++) {
        if (g_displays[i].refs && g_displays[i].d == d) {
            last = --g_displays[i].refs == 0;
            break;
        }
    }
    pthread_mutex_unlock(&g_display_lock);
    return last;
}

void snell__platform_close(snell_platform *p)
{
    if (p->owns_context && p->display != EGL_NO_DISPLAY) {
        /* Reverse order of creation: release, surface, context, display. */
        /* Restoring whatever was current before creation is not safe (that
         * context may be gone by now), so an owned context is just released. */
        if (eglGetCurrentContext() == p->context)
            eglMakeCurrent(p->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (p->surface != EGL_NO_SURFACE) eglDestroySurface(p->display, p->surface);
        if (p->context != EGL_NO_CONTEXT) eglDestroyContext(p->display, p->context);
    }
    if (p->owns_display && p->display != EGL_NO_DISPLAY && display_unref(p->display))
        eglTerminate(p->display);
    p->display = EGL_NO_DISPLAY;
    p->context = EGL_NO_CONTEXT;
    p->surface = EGL_NO_SURFACE;
    p->owns_context = p->owns_display = 0;
}
