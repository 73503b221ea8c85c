/* SPDX-License-Identifier: MIT */
/* kms_gbm.c — glass on a bare display (no X, no Wayland): EGL on a GBM
 * surface of the DRM device; snell draws into its framebuffer. Putting each
 * buffer on screen (drmModeAddFB2, drmModeSetCrtc, page flips) is the app's
 * KMS code: ports/kms (snell-kiosk) has all of it.
 *   cc kms_gbm.c $(pkg-config --cflags --libs gbm egl snell) */
#define _POSIX_C_SOURCE 200809L /* O_CLOEXEC */
#include "glass.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <fcntl.h>
#include <gbm.h>
#include <stdio.h>

int main(void)
{
    const EGLint config_attrs[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT,
                                   EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                   EGL_DEPTH_SIZE, 24, /* snell depth-tests the glass */
                                   EGL_NATIVE_VISUAL_ID, GBM_FORMAT_XRGB8888, EGL_NONE};
    const EGLint context_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    const int w = 1920, h = 1080; /* the connector's mode */
    int fd = open("/dev/dri/card0", O_RDWR | O_CLOEXEC), frame;
    struct gbm_device *gbm = fd >= 0 ? gbm_create_device(fd) : NULL;
    struct gbm_surface *gs;
    EGLDisplay dpy;
    EGLConfig config;
    EGLSurface surface;
    EGLContext context;
    EGLint n = 0;
    glass_app g;
    snell_camera cam = {0}; /* stands in for the app's own view and projection */
    float eye[3], view[16], proj[16];
    if (!gbm) return 1;
    dpy = eglGetPlatformDisplay(EGL_PLATFORM_GBM_KHR, gbm, NULL);
    if (!eglInitialize(dpy, NULL, NULL) || !eglBindAPI(EGL_OPENGL_ES_API) ||
        !eglChooseConfig(dpy, config_attrs, &config, 1, &n) || n < 1)
        return 1;
    gs = gbm_surface_create(gbm, w, h, GBM_FORMAT_XRGB8888, GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    surface = eglCreatePlatformWindowSurface(dpy, config, gs, NULL);
    context = eglCreateContext(dpy, config, EGL_NO_CONTEXT, context_attrs);
    if (!eglMakeCurrent(dpy, surface, surface, context) || !glass_open(&g, w, h)) return 1;
    snell_camera_matrices(&cam, (float)w / (float)h, eye, view, proj);
    for (frame = 0; frame < 600; frame++) {
        struct gbm_bo *bo;
        glClearColor(0.3f, 0.5f, 0.8f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT); /* ... the app's scene ... */
        if (glass_draw(&g, view, proj) != SNELL_OK) fprintf(stderr, "glass: %s\n", snell_last_error(g.ctx));
        eglSwapBuffers(dpy, surface);
        bo = gbm_surface_lock_front_buffer(gs); /* ... scan it out (drmModePageFlip), then: */
        gbm_surface_release_buffer(gs, bo);
    }
    glass_close(&g);
    return 0;
}
