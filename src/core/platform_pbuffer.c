/* SPDX-License-Identifier: MIT */
/* platform_pbuffer.c — a 1x1 pbuffer surface on the first display that
 * initialises: EGL_EXT_platform_device (NVIDIA and Mesa headless), then the
 * default display (Android, Raspberry Pi), then Mesa's surfaceless platform. */
#include "core/ctx.h"

#ifndef EGL_PLATFORM_DEVICE_EXT
#define EGL_PLATFORM_DEVICE_EXT 0x313F
#endif
#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

typedef EGLBoolean (*query_devices_fn)(EGLint, void **, EGLint *);

static EGLDisplay device_display(void)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    query_devices_fn query;
    void *devices[4];
    EGLint n = 0;
    if (!client || !snell__egl_has_extension(client, "EGL_EXT_platform_device")) return EGL_NO_DISPLAY;
    query = (query_devices_fn)eglGetProcAddress("eglQueryDevicesEXT");
    if (!query || !query(4, devices, &n) || n < 1) return EGL_NO_DISPLAY;
    return snell__egl_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[0]);
}

static int try_display(snell_platform *p, EGLDisplay d)
{
    EGLint major, minor;
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor)) return 0;
    p->display = d;
    p->owns_display = 1;
    snell__egl_display_ref(p->display);
    return 1;
}

snell_status snell__platform_open_pbuffer(snell_ctx *ctx, snell_platform *p, int debug)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!try_display(p, device_display()) && !try_display(p, eglGetDisplay(EGL_DEFAULT_DISPLAY)) &&
        !(client && snell__egl_has_extension(client, "EGL_MESA_platform_surfaceless") &&
          try_display(p, snell__egl_platform_display(EGL_PLATFORM_SURFACELESS_MESA, NULL))))
        return snell__fail(ctx, SNELL_E_EGL, "no EGL display could be initialised (device, default, surfaceless): %s",
                           snell__egl_error_str(eglGetError()));
    return snell__egl_make_context(ctx, p, EGL_PBUFFER_BIT, 1, debug);
}
