/* SPDX-License-Identifier: MIT */
/* kms_flip.h — snell-kiosk's page-flip state machine, with no DRM in it: the
 * buffer on screen, the one queued for the next vblank, what submitting a new
 * one takes (a modeset for the first, a page flip after, a wait while one is
 * queued), which buffer a completed flip frees, and the count of frames shown
 * and flips completed. Buffers are opaque (gbm_bo in the kiosk). */
#ifndef SNELL_KMS_FLIP_H
#define SNELL_KMS_FLIP_H

typedef enum kms_flip_step {
    KMS_STEP_MODESET = 0, /* nothing of ours on screen yet: drmModeSetCrtc */
    KMS_STEP_PAGE_FLIP,   /* drmModePageFlip with an event */
    KMS_STEP_WAIT         /* a flip is queued: wait for its event first (legacy flips queue one) */
} kms_flip_step;

typedef struct kms_flip {
    void *shown;          /* on screen now; NULL before the modeset */
    void *queued;         /* flip queued to it, NULL if none */
    long frames;          /* buffers that reached the screen: the modeset's and each completed flip's */
    long flips;           /* completed page flips */
    long refused;         /* calls the machine refused (a bug in the caller; stays 0) */
} kms_flip;

void kms_flip_init(kms_flip *f);
/* What putting a new buffer on screen takes now. */
kms_flip_step kms_flip_next(const kms_flip *f);
/* buf was set by a modeset (only as KMS_STEP_MODESET says): it is shown now.
 * Returns 0 (refused) if a modeset was not the next step. */
int kms_flip_modeset_done(kms_flip *f, void *buf);
/* A page flip to buf was queued (drmModePageFlip returned 0). Returns 0
 * (refused, nothing changed) if a flip was not the next step, or buf is NULL
 * or the buffer shown. */
int kms_flip_queued(kms_flip *f, void *buf);
/* The queued flip's event arrived: its buffer is shown. Returns the buffer
 * that left the screen (for the caller to release), NULL with *ok = 0 if no
 * flip was queued (a stray event). */
void *kms_flip_complete(kms_flip *f, int *ok);
/* 1 while a flip is queued: teardown waits for its event before it restores
 * the previous CRTC and releases the buffers (shown, and queued if any). */
int kms_flip_pending(const kms_flip *f);

#endif
