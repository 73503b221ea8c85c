/* SPDX-License-Identifier: MIT */
/* kms_gpu.h — snell-kiosk's rendering side: a GBM device on the display's
 * card, a scanout surface in the first of XRGB8888/ARGB8888 that the primary
 * plane takes and an EGL config has as native visual id, allocated with the
 * plane's modifiers where it lists them (else plain gbm_surface_create), an
 * EGL window surface and GLES 3.0 context on it, and one framebuffer per
 * buffer object (made on first use, removed with the buffer). */
#ifndef SNELL_KMS_GPU_H
#define SNELL_KMS_GPU_H

#include "kms_display.h"

#include <EGL/egl.h>
#include <gbm.h>

typedef struct kms_gpu {
    struct gbm_device *gbm;
    struct gbm_surface *surface;
    uint32_t format;           /* DRM/GBM fourcc of the surface */
    int modifier_count;        /* the plane's modifiers for format (IN_FORMATS) */
    int with_modifiers;        /* the surface was allocated with them */
    int width, height;
    EGLDisplay dpy;
    EGLConfig config;
    EGLContext ctx;
    EGLSurface surf;
} kms_gpu;

/* Sets all of it up on d's card at d's mode size and makes the context
 * current. 1 on success; msg says what was made, or what failed. */
int kms_gpu_open(kms_gpu *g, const kms_display *d, char *msg, size_t n);
/* After eglSwapBuffers: the new front buffer, locked, and its framebuffer
 * in *fb. NULL on failure (msg says why). */
struct gbm_bo *kms_gpu_lock_front(kms_gpu *g, const kms_display *d, uint32_t *fb, char *msg, size_t n);
void kms_gpu_release(kms_gpu *g, struct gbm_bo *bo);
/* EGL surface and context, then the GBM surface (its buffers and their
 * framebuffers) and device. The display must no longer show them. */
void kms_gpu_close(kms_gpu *g);
/* "XR24" */
void kms_fourcc_str(uint32_t format, char out[5]);

#endif
