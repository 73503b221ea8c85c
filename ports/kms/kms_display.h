/* SPDX-License-Identifier: MIT */
/* kms_display.h — snell-kiosk's DRM side (libdrm): the card, connector, mode
 * and CRTC it drives (chosen by kms_select.c from what the card reports), the
 * primary plane's formats and modifiers, the CRTC as it was before (restored
 * at the end), framebuffers, the modeset, legacy page flips and their events. */
#ifndef SNELL_KMS_DISPLAY_H
#define SNELL_KMS_DISPLAY_H

#include "kms_select.h"

#include <stddef.h>
#include <stdint.h>
#include <xf86drm.h>
#include <drm_fourcc.h>
#include <xf86drmMode.h>

#define KMS_MAX_FORMATS 128
#define KMS_MAX_MODIFIERS 64

typedef struct kms_display {
    int fd;
    char path[256];
    uint32_t connector_id, crtc_id, plane_id;
    int crtc_index;
    drmModeModeInfo mode;
    drmModeCrtc *saved;          /* the CRTC as we found it (what the console showed) */
    int atomic;                  /* the kernel accepts DRM_CLIENT_CAP_ATOMIC (probed and reported) */
    int use_atomic;              /* frames are shown by atomic commits (asked for); else by the legacy
                                  * SetCrtc and PageFlip, which every KMS driver has */
    uint32_t mode_blob;          /* atomic: the mode as a property blob */
    struct {                     /* atomic: property ids */
        uint32_t conn_crtc_id, crtc_mode_id, crtc_active, fb_id, crtc_id, src_x, src_y, src_w, src_h, crtc_x,
            crtc_y, crtc_w, crtc_h;
    } prop;
    uint32_t formats[KMS_MAX_FORMATS]; /* the primary plane's formats */
    int format_count;
    uint32_t in_formats_blob;    /* the plane's IN_FORMATS property (formats x modifiers), 0 if none */
    int monotonic_events;        /* DRM_CAP_TIMESTAMP_MONOTONIC: flip events are stamped with CLOCK_MONOTONIC */
    kms_mode_info modes[64];     /* the connector's modes (messages) */
    int mode_count;
    char connector_name[32];     /* "HDMI-A-1" */
    void (*on_flip)(void *user, double t_s); /* set during kms_display_wait */
    void *on_flip_user;
} kms_display;

/* What to open: all zero = the first card under /dev/dri with KMS resources
 * and a usable connector, its first connected connector, the preferred mode. */
typedef struct kms_display_request {
    const char *dri_dir;         /* where to look for card* (NULL = /dev/dri) */
    const char *device;          /* this card only (NULL = probe) */
    uint32_t connector_id;       /* 0 = the first connected */
    kms_mode_request mode;       /* zero = preferred */
    int atomic;                  /* show frames by atomic commits (KMS_OPEN_FAILED where there are none) */
} kms_display_request;

typedef enum kms_open_result {
    KMS_OPEN_OK = 0,
    KMS_OPEN_NO_DISPLAY,         /* no DRM card with KMS resources and a usable connector: nothing to
                                  * show on (the kiosk exits with the skip code) */
    KMS_OPEN_FAILED              /* a card is there but cannot be used (permissions, no such mode, ...) */
} kms_open_result;

/* Opens and chooses; msg says what was chosen (OK) or why not. */
kms_open_result kms_display_open(kms_display *d, const kms_display_request *req, char *msg, size_t n);
/* The modifiers the primary plane takes for format (IN_FORMATS); 0 if it
 * lists none (then the buffers are allocated without modifiers). */
int kms_display_modifiers(const kms_display *d, uint32_t format, uint64_t *out, int max);
/* The connector's modes, for messages: "1920x1080@60* 1280x720@60 ..." (* preferred). */
void kms_display_mode_list(const kms_display *d, char *out, size_t n);

/* A framebuffer for a buffer object's planes: with modifiers
 * (drmModeAddFB2WithModifiers) when modifier is valid, else drmModeAddFB2,
 * else the old drmModeAddFB (XRGB8888 only). 0 on failure (errno set). */
uint32_t kms_display_add_fb(const kms_display *d, int width, int height, uint32_t format, int planes,
                            const uint32_t handles[4], const uint32_t strides[4], const uint32_t offsets[4],
                            uint64_t modifier);
/* Sets the mode with framebuffer fb (the first frame). 0 on success, else -errno. */
int kms_display_modeset(kms_display *d, uint32_t fb);
/* Queues a flip to fb at the next vblank, with an event (legacy or atomic,
 * nonblocking). 0 or -errno. */
int kms_display_page_flip(kms_display *d, uint32_t fb);
/* Waits up to timeout_ms for DRM events and calls on_flip(user, t) for each
 * flip event (t: the vblank's time stamp, seconds). 1 if events were handled,
 * 0 on timeout, -1 on error, -2 if a signal interrupted the wait. */
int kms_display_wait(kms_display *d, int timeout_ms, void (*on_flip)(void *user, double t_s), void *user);
/* Puts the saved CRTC back (framebuffer, position, mode) and checks it took:
 * 1 if the CRTC reads back with the saved framebuffer; msg says what happened. */
int kms_display_restore(kms_display *d, char *msg, size_t n);
/* Reads the driven connector again (after a failure): 1 with *connection and
 * *mode_count, 0 if it cannot be read (the card or the connector is gone). */
int kms_display_recheck(const kms_display *d, int *connection, int *mode_count);
void kms_display_close(kms_display *d);

#endif
