/* SPDX-License-Identifier: MIT */
/* kms_gpu.c — GBM device and surface, EGL on them, framebuffers of buffer
 * objects (kms_gpu.h). The format/config choice is kms_pick_config's. */
#include "kms_gpu.h"

#include <EGL/eglext.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Preferred first: the display has no use for alpha. */
static const uint32_t g_formats[] = {GBM_FORMAT_XRGB8888, GBM_FORMAT_ARGB8888};
#define FORMAT_COUNT 2
#define MAX_CONFIGS 256

void kms_fourcc_str(uint32_t format, char out[5])
{
    int i;
    for (i = 0; i < 4; i++) out[i] = (char)((format >> (8 * i)) & 0xff);
    out[4] = '\0';
}

static int plane_takes(const kms_display *d, uint32_t format)
{
    int i;
    if (!d->format_count) return 1; /* no plane information: let the modeset decide */
    for (i = 0; i < d->format_count; i++)
        if (d->formats[i] == format) return 1;
    return 0;
}

/* EGL config (depth buffer: snell's passes test depth in the bound
 * framebuffer) and GBM format, matched by native visual id. */
static int choose_config(kms_gpu *g, const kms_display *d, char *msg, size_t n)
{
    static const EGLint attrs[] = {EGL_SURFACE_TYPE,
                                   EGL_WINDOW_BIT,
                                   EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_ES3_BIT,
                                   EGL_RED_SIZE,
                                   8,
                                   EGL_GREEN_SIZE,
                                   8,
                                   EGL_BLUE_SIZE,
                                   8,
                                   EGL_DEPTH_SIZE,
                                   16,
                                   EGL_NONE};
    EGLConfig configs[MAX_CONFIGS];
    int32_t visual[MAX_CONFIGS];
    uint32_t formats[FORMAT_COUNT];
    EGLint count = 0, i;
    int nf = 0, f, pick;
    if (!eglChooseConfig(g->dpy, attrs, configs, MAX_CONFIGS, &count) || count < 1) {
        snprintf(msg, n, "no EGL config for a GLES 3 window with RGB8 and depth (EGL error 0x%x)", eglGetError());
        return 0;
    }
    for (i = 0; i < count; i++)
        if (!eglGetConfigAttrib(g->dpy, configs[i], EGL_NATIVE_VISUAL_ID, &visual[i])) visual[i] = 0;
    for (f = 0; f < FORMAT_COUNT; f++)
        if (plane_takes(d, g_formats[f])) formats[nf++] = g_formats[f];
    if ((pick = kms_pick_config(visual, count, formats, nf, &f)) < 0) {
        snprintf(msg, n,
                 "none of %d EGL configs has XRGB8888 or ARGB8888 (that the primary plane takes) as its "
                 "native visual",
                 (int)count);
        return 0;
    }
    g->config = configs[pick];
    g->format = formats[f];
    return 1;
}

/* The plane's modifiers when it lists them; plain gbm_surface_create when
 * it does not or the driver refuses them (kms_swrast: dumb buffers). */
static int create_surface(kms_gpu *g, const kms_display *d, char *msg, size_t n)
{
    uint64_t mods[KMS_MAX_MODIFIERS];
    char fcc[5];
    g->modifier_count = kms_display_modifiers(d, g->format, mods, KMS_MAX_MODIFIERS);
    if (g->modifier_count > 0)
        g->surface = gbm_surface_create_with_modifiers(g->gbm, (uint32_t)g->width, (uint32_t)g->height, g->format, mods,
                                                       (unsigned)g->modifier_count);
    g->with_modifiers = g->surface != NULL;
    if (!g->surface)
        g->surface = gbm_surface_create(g->gbm, (uint32_t)g->width, (uint32_t)g->height, g->format,
                                        GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    kms_fourcc_str(g->format, fcc);
    if (!g->surface)
        snprintf(msg, n, "gbm_surface_create %dx%d %s failed: %s", g->width, g->height, fcc, strerror(errno));
    return g->surface != NULL;
}

int kms_gpu_open(kms_gpu *g, const kms_display *d, char *msg, size_t n)
{
    static const EGLint ctx_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    char fcc[5];
    memset(g, 0, sizeof *g);
    g->dpy = EGL_NO_DISPLAY;
    g->ctx = EGL_NO_CONTEXT;
    g->surf = EGL_NO_SURFACE;
    g->width = d->mode.hdisplay;
    g->height = d->mode.vdisplay;
    if (!(g->gbm = gbm_create_device(d->fd))) return snprintf(msg, n, "gbm_create_device failed"), 0;
    g->dpy = eglGetPlatformDisplay(EGL_PLATFORM_GBM_KHR, g->gbm, NULL);
    if (g->dpy == EGL_NO_DISPLAY || !eglInitialize(g->dpy, NULL, NULL))
        return snprintf(msg, n, "no EGL display on GBM (EGL error 0x%x)", eglGetError()), 0;
    if (!eglBindAPI(EGL_OPENGL_ES_API) || !choose_config(g, d, msg, n) || !create_surface(g, d, msg, n)) return 0;
    g->ctx = eglCreateContext(g->dpy, g->config, EGL_NO_CONTEXT, ctx_attrs);
    if (g->ctx == EGL_NO_CONTEXT) return snprintf(msg, n, "no GLES 3 context (EGL error 0x%x)", eglGetError()), 0;
    g->surf = eglCreatePlatformWindowSurface(g->dpy, g->config, g->surface, NULL);
    if (g->surf == EGL_NO_SURFACE)
        return snprintf(msg, n, "no EGL window surface on GBM (EGL error 0x%x)", eglGetError()), 0;
    if (!eglMakeCurrent(g->dpy, g->surf, g->surf, g->ctx))
        return snprintf(msg, n, "eglMakeCurrent failed (EGL error 0x%x)", eglGetError()), 0;
    kms_fourcc_str(g->format, fcc);
    snprintf(msg, n, "GBM surface %dx%d %s, %s; EGL %s", g->width, g->height, fcc,
             g->with_modifiers   ? "allocated with the plane's modifiers"
             : g->modifier_count ? "plain (the driver refused the plane's modifiers)"
                                 : "plain (the plane lists no modifiers)",
             eglQueryString(g->dpy, EGL_VERSION));
    return 1;
}

/* A buffer object's framebuffer, kept as its user data. */
typedef struct bo_fb {
    int fd;
    uint32_t id;
} bo_fb;

static void destroy_fb(struct gbm_bo *bo, void *data)
{
    bo_fb *f = (bo_fb *)data;
    (void)bo;
    if (f->id) drmModeRmFB(f->fd, f->id);
    free(f);
}

struct gbm_bo *kms_gpu_lock_front(kms_gpu *g, const kms_display *d, uint32_t *fb, char *msg, size_t n)
{
    struct gbm_bo *bo = gbm_surface_lock_front_buffer(g->surface);
    bo_fb *f;
    uint32_t handles[4] = {0}, strides[4] = {0}, offsets[4] = {0};
    int i, planes;
    if (!bo) return snprintf(msg, n, "gbm_surface_lock_front_buffer failed (no buffer free?)"), (struct gbm_bo *)NULL;
    if ((f = (bo_fb *)gbm_bo_get_user_data(bo)) != NULL) {
        *fb = f->id;
        return bo;
    }
    planes = gbm_bo_get_plane_count(bo);
    for (i = 0; i < planes && i < 4; i++) {
        handles[i] = gbm_bo_get_handle_for_plane(bo, i).u32;
        strides[i] = gbm_bo_get_stride_for_plane(bo, i);
        offsets[i] = gbm_bo_get_offset(bo, i);
    }
    f = (bo_fb *)calloc(1, sizeof *f);
    if (!f) {
        gbm_surface_release_buffer(g->surface, bo);
        return snprintf(msg, n, "out of memory"), (struct gbm_bo *)NULL;
    }
    f->fd = d->fd;
    f->id = kms_display_add_fb(d, g->width, g->height, g->format, planes, handles, strides, offsets,
                               g->with_modifiers ? gbm_bo_get_modifier(bo) : DRM_FORMAT_MOD_INVALID);
    if (!f->id) {
        snprintf(msg, n, "cannot make a framebuffer of a %dx%d buffer: %s", g->width, g->height, strerror(errno));
        free(f);
        gbm_surface_release_buffer(g->surface, bo);
        return NULL;
    }
    gbm_bo_set_user_data(bo, f, destroy_fb);
    *fb = f->id;
    return bo;
}

void kms_gpu_release(kms_gpu *g, struct gbm_bo *bo)
{
    if (bo) gbm_surface_release_buffer(g->surface, bo);
}

void kms_gpu_close(kms_gpu *g)
{
    if (g->dpy != EGL_NO_DISPLAY) {
        eglMakeCurrent(g->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (g->surf != EGL_NO_SURFACE) eglDestroySurface(g->dpy, g->surf);
        if (g->ctx != EGL_NO_CONTEXT) eglDestroyContext(g->dpy, g->ctx);
        eglTerminate(g->dpy);
    }
    if (g->surface) gbm_surface_destroy(g->surface);
    if (g->gbm) gbm_device_destroy(g->gbm);
    memset(g, 0, sizeof *g);
    g->dpy = EGL_NO_DISPLAY;
}
