/* SPDX-License-Identifier: MIT */
/* platform_surfaceless.c — headless EGL without any window system:
 * EGL_MESA_platform_surfaceless display, EGL_KHR_surfaceless_context when
 * available, else a 1x1 pbuffer on the same display. */
#include "core/ctx.h"

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

snell_status snell__platform_open_surfaceless(snell_ctx *ctx, snell_platform *p, int debug)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const char *exts;
    EGLint major = 0, minor = 0;

    if (!client || !snell__egl_has_extension(client, "EGL_MESA_platform_surfaceless"))
        return snell__fail(ctx, SNELL_E_UNSUPPORTED,
                           "EGL client extension EGL_MESA_platform_surfaceless is not available");
    p->display = snell__egl_platform_display(EGL_PLATFORM_SURFACELESS_MESA, NULL);
    if (p->display == EGL_NO_DISPLAY)
        return snell__fail(ctx, SNELL_E_EGL, "eglGetPlatformDisplay(SURFACELESS_MESA) failed: %s",
                           snell__egl_error_str(eglGetError()));
    if (!eglInitialize(p->display, &major, &minor))
        return snell__fail(ctx, SNELL_E_EGL, "eglInitialize on the surfaceless display failed: %s",
                           snell__egl_error_str(eglGetError()));
    p->owns_display = 1;
    snell__egl_display_ref(p->display);
    exts = eglQueryString(p->display, EGL_EXTENSIONS);
    if (snell__egl_has_extension(exts, "EGL_KHR_surfaceless_context"))
        return snell__egl_make_context(ctx, p, 0, 0, debug);
    snell__log(ctx, SNELL_LOG_INFO, "EGL_KHR_surfaceless_context missing: using a pbuffer");
    return snell__egl_make_context(ctx, p, EGL_PBUFFER_BIT, 1, debug);
}
