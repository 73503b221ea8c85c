/* SPDX-License-Identifier: MIT */
/* kms_select.h — snell-kiosk's choices as plain functions on plain data (no
 * libdrm, so they are unit-tested on made-up resources): the card, the
 * connector, the mode (preferred or --mode WxH@R), the CRTC, and the GBM
 * format whose EGL config has it as native visual id. */
#ifndef SNELL_KMS_SELECT_H
#define SNELL_KMS_SELECT_H

#include <stddef.h>
#include <stdint.h>

/* Connector states, numbered as libdrm's drmModeConnection. */
#define KMS_CONNECTED 1
#define KMS_DISCONNECTED 2
#define KMS_UNKNOWN 3 /* the driver cannot tell (some VGA, virtual and DSI outputs): worth a try */

typedef struct kms_mode_info {
    int width, height;
    int refresh;   /* Hz (drmModeModeInfo.vrefresh) */
    int preferred; /* DRM_MODE_TYPE_PREFERRED */
} kms_mode_info;

typedef struct kms_connector_info {
    uint32_t id;
    int connection;            /* KMS_CONNECTED, KMS_DISCONNECTED, KMS_UNKNOWN */
    uint32_t encoder_id;       /* the encoder driving it now, 0 = none */
    const uint32_t *encoders;  /* the encoders that can drive it */
    int encoder_count;
    const kms_mode_info *modes;
    int mode_count;
} kms_connector_info;

typedef struct kms_encoder_info {
    uint32_t id;
    uint32_t crtc_id;          /* the CRTC it feeds now, 0 = none */
    uint32_t possible_crtcs;   /* bit i: it can be fed by crtcs[i] of the resources */
} kms_encoder_info;

/* One card's KMS resources (drmModeGetResources and what it lists). */
typedef struct kms_resources_info {
    const kms_connector_info *connectors;
    int connector_count;
    const kms_encoder_info *encoders;
    int encoder_count;
    const uint32_t *crtcs;
    int crtc_count;
} kms_resources_info;

/* What probing /dev/dri/cardN found. */
typedef struct kms_card_probe {
    int opened;                /* open() succeeded */
    int has_resources;         /* drmModeGetResources returned non-NULL: a display controller,
                                * not a render-only GPU (a Pi 4's v3d is one card, vc4 another) */
    int usable_connectors;     /* connected or unknown connectors with at least one mode */
} kms_card_probe;

/* The card to drive: the first that opened, has KMS resources and a usable
 * connector; -1 if none. */
int kms_pick_card(const kms_card_probe *cards, int n);

/* 1 if the connector may show a picture: connected, or unknown (kmscube and
 * raylib accept unknown ones too), with at least one mode. */
int kms_connector_usable(const kms_connector_info *c);

/* After showing a frame failed (a modeset, flip or event wait): 1 if the
 * display went away — the card is gone (err -ENODEV) or the connector, read
 * again, is missing (now NULL), not connected or without modes — else 0 (a
 * failure of the kiosk's own). err is the failing call's -errno, 0 if none. */
int kms_display_gone(int err, const kms_connector_info *now);

/* Index of the connector to use: want_id's (if it is usable), else the first
 * connected one with modes, else the first unknown one with modes; -1 if none. */
int kms_pick_connector(const kms_resources_info *r, uint32_t want_id);

/* A requested mode; zero fields are "any". */
typedef struct kms_mode_request {
    int width, height, refresh;
} kms_mode_request;

/* "WxH" or "WxH@R" (R in Hz) into *out; 1 on success, 0 for anything else. */
int kms_parse_mode(const char *s, kms_mode_request *out);

/* Index of the connector's mode to set, -1 if none fits. With a request
 * (width and height nonzero): a mode of that size, at refresh R when given
 * (else the highest refresh of that size). Without: the preferred mode, else
 * the largest (ties: the highest refresh). */
int kms_pick_mode(const kms_connector_info *c, const kms_mode_request *req);

/* The CRTC to drive connector c, as in kmscube: the one its current encoder
 * feeds, else the first CRTC one of its encoders can be fed by. Returns the
 * CRTC id (0 if none) and its index in r->crtcs in *index (the bit of
 * possible_crtcs, needed to find its primary plane). */
uint32_t kms_pick_crtc(const kms_resources_info *r, const kms_connector_info *c, int *index);

/* The GBM format and EGL config to render with: the first of formats[0..nf)
 * (in order of preference) that one of the configs has as native visual id
 * (EGL_NATIVE_VISUAL_ID: on GBM, the config's DRM format). Returns the
 * config's index in visual_ids[0..nc) and the format's index in *format; -1
 * if no config matches any format. */
int kms_pick_config(const int32_t *visual_ids, int nc, const uint32_t *formats, int nf, int *format);

#endif
