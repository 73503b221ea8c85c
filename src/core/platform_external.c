/* SPDX-License-Identifier: MIT */
/* platform_external.c — borrow the caller's current GLES 3.x context. Nothing
 * is created or destroyed; the renderer saves and restores the GL state it
 * touches (glstate.c) so the host's render loop is unaffected. */
#include "core/ctx.h"

snell_status snell__platform_open_external(snell_ctx *ctx, snell_platform *p)
{
    p->context = eglGetCurrentContext();
    p->display = eglGetCurrentDisplay();
    p->surface = eglGetCurrentSurface(EGL_DRAW);
    if (p->context == EGL_NO_CONTEXT)
        return snell__fail(ctx, SNELL_E_EGL,
                           "EXTERNAL backend: no EGL context is current on this thread");
    p->owns_context = 0;
    p->owns_display = 0;
    return SNELL_OK;
}
