/* SPDX-License-Identifier: MIT */
/* kiosk.h — snell-kiosk's files and their one job each:
 *   snell_kiosk.c    main: options -> display -> GBM/EGL -> snell (EXTERNAL) -> frames -> teardown
 *   kiosk_options.c  the command line and --help
 *   kms_display.c    the DRM card, mode, CRTC, framebuffers, page flips, restore (kms_display.h)
 *   kms_gpu.c        GBM surface and EGL context on the card (kms_gpu.h)
 *   kms_select.c     which card, connector, mode, CRTC, format: plain functions (kms_select.h)
 *   kms_flip.c       the page-flip state machine: plain functions (kms_flip.h)
 * The scene is a snell-bench configuration (method:scene=..:camera=..:key=value),
 * built with snell-bench's own code; --bench writes snell-bench's JSON.
 * Exit status 0, 1 on failure, 2 on bad usage, 3 when the display went away
 * while showing, 77 when there is no display (a supervisor restarts on 3 and 77). */
#ifndef SNELL_KIOSK_H
#define SNELL_KIOSK_H

#include "kms_display.h"

#define KIOSK_MAX_SPECS 64
#define KIOSK_EXIT_NO_DISPLAY 77 /* ctest's SKIP_RETURN_CODE in this project */
#define KIOSK_EXIT_DISPLAY_LOST 3

typedef struct kiosk_options {
    const char *specs[KIOSK_MAX_SPECS];
    int spec_count;
    kms_display_request display;
    float spin_deg;            /* camera azimuth step per frame */
    float budget_ms;           /* show mode: snell_frame_desc.budget_ms (0 = none) */
    long frames;               /* 0: until SIGINT/SIGTERM (show mode) */
    int hold;                  /* keep the last frame on screen until a signal */
    double report_s;           /* FPS report period, 0 = at the end only */
    int bench;
    int vsync_off;             /* --vsync off: --bench draws offscreen, each frame ended by glFinish, not capped
                                * by the refresh (default: page-flipped frames at vblank) */
    int warmup;
    const char *json;
    const char *preview;       /* --preview FILE: draw offscreen to this PNG, no display */
    int config_specs;          /* the -b in spec_count came from --config (a -b after it replaces them) */
} kiosk_options;

/* 1: run; 0: bad usage (message printed, exit 2); -1: --help printed (exit 0). */
int kiosk_parse_options(int argc, char **argv, kiosk_options *o);

#endif
