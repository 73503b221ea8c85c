/* SPDX-License-Identifier: MIT */
/* platform_external.c — borrow the caller's current GLES 3.x context, made
 * with EGL, with GLX (SDL2 and GLFW on X11) or otherwise. Nothing is created
 * or destroyed; the renderer saves and restores the GL state it touches
 * (glstate.c) so the host's render loop is unaffected. */
#define _GNU_SOURCE 1 /* dladdr (glibc; bionic declares it always) */
#include "core/ctx.h"
#include "core/gl.h"

#include <dlfcn.h>
#include <string.h>

#ifdef SNELL_WITH_GLX
/* dlsym's object pointer as a function pointer (POSIX guarantees they convert). */
static void find(void *lib, const char *name, void *fn)
{
    void *p = dlsym(lib, name);
    memcpy(fn, &p, sizeof p);
}

/* GLX as the host loaded it (libglvnd's libGLX, else a vendor's libGL):
 * RTLD_NOLOAD takes a library already in the process and loads none. */
static int open_glx(snell__glx *g)
{
    void *lib = dlopen("libGLX.so.0", RTLD_LAZY | RTLD_NOLOAD);
    if (!lib) lib = dlopen("libGL.so.1", RTLD_LAZY | RTLD_NOLOAD);
    if (!lib) return 0;
    find(lib, "glXGetCurrentContext", &g->current);
    find(lib, "glXGetCurrentDisplay", &g->display);
    find(lib, "glXGetCurrentDrawable", &g->draw);
    find(lib, "glXGetCurrentReadDrawable", &g->read);
    find(lib, "glXMakeContextCurrent", &g->make_current);
    find(lib, "glXGetProcAddressARB", &g->proc);
    if (g->current && g->display && g->draw && g->read && g->make_current && g->proc && g->current()) {
        g->lib = lib;
        return 1;
    }
    dlclose(lib);
    memset(g, 0, sizeof *g);
    return 0;
}
#else
static int open_glx(snell__glx *g) { (void)g; return 0; }
#endif

snell_status snell__platform_open_external(snell_ctx *ctx, snell_platform *p)
{
    p->owns_context = 0;
    p->owns_display = 0;
    p->context = eglGetCurrentContext();
    p->display = eglGetCurrentDisplay();
    p->surface = eglGetCurrentSurface(EGL_DRAW);
    if (p->context != EGL_NO_CONTEXT) return SNELL_OK;
    if (open_glx(&p->glx)) {
        p->context = p->glx.current();
        return SNELL_OK;
    }
    /* Made some other way: GL answering is all that can be known of it. */
    if (!glGetString(GL_VERSION))
        return snell__fail(ctx, SNELL_E_EGL, "EXTERNAL backend: no GL context is current on this thread");
    p->foreign = 1;
    p->context = p;
    return SNELL_OK;
}

void *snell__platform_current(const snell_platform *p)
{
#ifdef SNELL_WITH_GLX
    if (p->glx.current) return p->glx.current();
#endif
    if (p->foreign) return glGetString(GL_VERSION) ? p->context : NULL;
    return eglGetCurrentContext();
}

int snell__platform_surface_size(const snell_platform *p, int size[2])
{
    EGLDisplay dpy = eglGetCurrentDisplay();
    EGLSurface s = eglGetCurrentSurface(EGL_DRAW);
    EGLint w = 0, h = 0;
    if (p->glx.current || dpy == EGL_NO_DISPLAY || s == EGL_NO_SURFACE) return 0;
    if (!eglQuerySurface(dpy, s, EGL_WIDTH, &w) || !eglQuerySurface(dpy, s, EGL_HEIGHT, &h)) return 0;
    size[0] = w, size[1] = h;
    return 1;
}

snell__gl_fn snell__platform_proc(const snell_platform *p, const char *name)
{
#ifdef SNELL_WITH_GLX
    snell__gl_fn fn = NULL;
    const GLubyte *(GL_APIENTRY *probe)(GLenum) = glGetString;
    Dl_info info;
    void *lib, *addr;
    if (p->glx.proc) return p->glx.proc((const unsigned char *)name);
    if (!p->foreign) return eglGetProcAddress(name);
    /* The library that exports glGetString exports the rest of GLES. */
    memcpy(&addr, &probe, sizeof addr);
    if (!dladdr(addr, &info) || !(lib = dlopen(info.dli_fname, RTLD_LAZY | RTLD_NOLOAD))) return NULL;
    find(lib, name, &fn);
    dlclose(lib);
    return fn;
#else
    /* Without GLX support (the device preset) a foreign context's functions
     * come from EGL's look-up too: libglvnd's and Mesa's answer for any API. */
    (void)p;
    return eglGetProcAddress(name);
#endif
}
