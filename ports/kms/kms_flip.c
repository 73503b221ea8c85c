/* SPDX-License-Identifier: MIT */
/* kms_flip.c — the page-flip state machine (kms_flip.h). */
#include "kms_flip.h"

#include <stddef.h>

void kms_flip_init(kms_flip *f)
{
    f->shown = f->queued = NULL;
    f->frames = f->flips = f->refused = 0;
}

kms_flip_step kms_flip_next(const kms_flip *f)
{
    if (!f->shown) return KMS_STEP_MODESET;
    return f->queued ? KMS_STEP_WAIT : KMS_STEP_PAGE_FLIP;
}

int kms_flip_modeset_done(kms_flip *f, void *buf)
{
    if (kms_flip_next(f) != KMS_STEP_MODESET || !buf) return f->refused++, 0;
    f->shown = buf;
    f->frames++;
    return 1;
}

int kms_flip_queued(kms_flip *f, void *buf)
{
    if (kms_flip_next(f) != KMS_STEP_PAGE_FLIP || !buf || buf == f->shown) return f->refused++, 0;
    f->queued = buf;
    return 1;
}

void *kms_flip_complete(kms_flip *f, int *ok)
{
    void *old = f->shown;
    if (!f->queued) {
        f->refused++;
        *ok = 0;
        return NULL;
    }
    f->shown = f->queued;
    f->queued = NULL;
    f->frames++;
    f->flips++;
    *ok = 1;
    return old;
}

int kms_flip_pending(const kms_flip *f) { return f->queued != NULL; }
