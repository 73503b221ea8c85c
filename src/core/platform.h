/* SPDX-License-Identifier: MIT */
/* platform.h — the small interface each EGL backend implements
 * (platform_surfaceless.c, platform_pbuffer.c, platform_external.c).
 * To add a backend: write platform_xxx.c with an open function filling the
 * struct below, and add it to snell_ctx_create's dispatch. */
#ifndef SNELL_PLATFORM_H
#define SNELL_PLATFORM_H

#include "core/core.h"
#include <EGL/egl.h>

/* A host's context made without EGL (GLX: SDL2 and GLFW on X11): GLX's own
 * calls, found in the process (platform_external.c), to ask which context is
 * current, detach it for a moment and find GL functions. All NULL for EGL. */
typedef void (*snell__gl_fn)(void);
typedef struct snell__glx {
    void *lib;                   /* dlopen handle of the loaded GLX library */
    void *(*current)(void);      /* glXGetCurrentContext */
    void *(*display)(void);      /* glXGetCurrentDisplay */
    unsigned long (*draw)(void); /* glXGetCurrentDrawable */
    unsigned long (*read)(void); /* glXGetCurrentReadDrawable */
    int (*make_current)(void *display, unsigned long draw, unsigned long read, void *context);
    snell__gl_fn (*proc)(const unsigned char *name); /* glXGetProcAddressARB */
} snell__glx;

typedef struct snell_platform {
    snell__glx glx;                 /* a GLX host context (EXTERNAL), else all NULL */
    int foreign;                    /* EXTERNAL, neither EGL nor GLX: any current GL context is taken */
    EGLDisplay display;
    EGLContext context;
    EGLSurface surface;             /* EGL_NO_SURFACE when surfaceless */
    int owns_display;               /* we called eglInitialize and must terminate */
    int owns_context;               /* 0 for EXTERNAL */
} snell_platform;

/* Each returns SNELL_OK with a current ES 3.x context, or a status whose
 * message (via snell__fail on ctx) says which step failed. */
snell_status snell__platform_open_surfaceless(snell_ctx *ctx, snell_platform *p, int debug);
snell_status snell__platform_open_pbuffer(snell_ctx *ctx, snell_platform *p, int debug);
snell_status snell__platform_open_external(snell_ctx *ctx, snell_platform *p);
void snell__platform_close(snell_platform *p);
/* The GL context current on this thread as the platform knows it (EGL, GLX;
 * for a foreign one p->context while GL answers), NULL when none. */
void *snell__platform_current(const snell_platform *p);
/* A GL or extension function of the current context: GLX's or EGL's
 * look-up where that made it, else the GLES library's own export. */
snell__gl_fn snell__platform_proc(const snell_platform *p, const char *name);
/* The size of the current EGL draw surface (the default framebuffer's), 0
 * when EGL does not know it (a GLX or foreign context, none current). */
int snell__platform_surface_size(const snell_platform *p, int size[2]);

/* Shared EGL helpers (platform_egl.c). */
int snell__egl_has_extension(const char *list, const char *name);
const char *snell__egl_error_str(EGLint err);
/* Chooses an ES3 config with the given surface type bits, creates an ES 3.0
 * context (debug flag if asked) and makes it current with surface (may be none). */
snell_status snell__egl_make_context(snell_ctx *ctx, snell_platform *p, EGLint surface_type,
                                     int want_pbuffer, int debug);
/* Count a display we eglInitialize'd; snell__platform_close terminates it
 * only when the last snell context on it goes away. */
void snell__egl_display_ref(EGLDisplay d);
/* Display for an EGL platform enum via eglGetPlatformDisplay(EXT); EGL_NO_DISPLAY on failure. */
EGLDisplay snell__egl_platform_display(EGLenum platform, void *native);

#endif
