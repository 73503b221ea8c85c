/* SPDX-License-Identifier: MIT */
/* kiosk.h — snell-kiosk's files and their one job each:
 *   snell_kiosk.c    main: options -> display -> GBM/EGL -> snell (EXTERNAL) -> frames -> teardown
 *   kiosk_options.c  the command line and --help
 *   kiosk_panels.c   glass panels over the scene or over a slideshow of pictures
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

#include "cli_panels.h"
#include "kms_display.h"

#define KIOSK_MAX_SPECS 64
#define KIOSK_MAX_SLIDES 64
#define KIOSK_DEFAULT_SLIDE_S 8.0
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
    const char *panels_file;   /* --panels FILE: glass panels over what is shown (docs/panels.md) */
    cli_panels panels;         /* its panels, read with the options */
    const char *slides[KIOSK_MAX_SLIDES]; /* --slide IMAGE: pictures under the panels instead of the scene */
    int slide_count;
    int config_slides;         /* as config_specs, for --slide */
    double slide_s;            /* --slide-seconds: how long each picture stays */
} kiosk_options;

/* The panels of a frame and the picture beneath them (kiosk_panels.c). */
typedef struct kiosk_panels {
    const kiosk_options *o;
    snell_panels_under under;  /* TEXTURE with draw = 1 over a slide */
    unsigned texture;          /* the slide's GL texture, 0 without slides */
    int slide;                 /* the slide in the texture, -1 before the first */
} kiosk_panels;

/* Starts the panels of o (nothing without --panels) in the current context. */
void kiosk_panels_open(kiosk_panels *kp, const kiosk_options *o);
/* The frame at t_s seconds since the first: the panels over fd's scene, or
 * with slides a frame of panels only over the picture due at t_s (read and
 * uploaded when it comes on). 0 with the reason in msg. */
int kiosk_panels_frame(kiosk_panels *kp, double t_s, snell_frame_desc *fd, char *msg, size_t n);
void kiosk_panels_close(kiosk_panels *kp);

/* 1: run; 0: bad usage (message printed, exit 2); -1: --help printed (exit 0). */
int kiosk_parse_options(int argc, char **argv, kiosk_options *o);

#endif
