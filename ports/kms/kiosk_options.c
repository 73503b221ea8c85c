/* SPDX-License-Identifier: MIT */
/* kiosk_options.c — snell-kiosk's command line. */
#define _POSIX_C_SOURCE 200809L /* close */
#include "kiosk.h"
#include "bench.h"
#include "cli_input.h"
#include "cli_opts.h"
#include "cli_system.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage: snell-kiosk [options]\n"
            "Refractive glass full screen on a DRM/KMS display, no window system: GBM + EGL, one frame per\n"
            "page flip (vsync), drawn by libsnell inside the kiosk's own GLES context (EXTERNAL backend,\n"
            "bound framebuffer). Stop with Ctrl-C or SIGTERM: the display gets back what it showed before.\n\n"
            "  -b SPEC             what to show, as snell-bench names a configuration:\n"
            "                      METHOD[:scene=S][:camera=AZ,EL,DIST][:ior=N][:KEY=V]... (snell-bench --list);\n"
            "                      default cubemap:scene=sphere. With --bench, repeatable, comma lists sweep\n"
            "  --device PATH       the DRM card (default: the first /dev/dri/card* with KMS resources and a\n"
            "                      connected display; a Pi 4's v3d card has none, its vc4 card does)\n"
            "  --dri-dir DIR       where to look for card* (default /dev/dri)\n"
            "  --connector ID      connector id (default: the first connected, else the first unknown)\n"
            "  --mode WxH[@R]      display mode (default: the connector's preferred mode)\n"
            "  --atomic            show frames by atomic commits (default: legacy page flips; the kiosk\n"
            "                      reports whether the driver has atomic modesetting)\n"
            "  --spin DEG          camera azimuth step per frame, degrees (default 0.5; 0 with --bench)\n"
            "  --budget MS         show mode: AUTO by frame budget (snell_frame_desc.budget_ms): each AUTO object\n"
            "                      drawn by the best configuration that holds MS a frame; the reports say which.\n"
            "                      Every configuration is built and timed first (snell_renderer_warm)\n"
            "  --frames N          stop after N frames (default: run until SIGINT/SIGTERM; --bench: %d)\n"
            "  --hold              after the last frame keep it on screen until SIGINT/SIGTERM\n"
            "  --report S          print frames per second every S seconds (default 5; 0: at the end only)\n"
            "  --bench             time each -b configuration (default: every method on scene=bunny) for\n"
            "                      --warmup then --frames frames; glmark2-style lines, snell-bench's JSON\n"
            "  --vsync on|off      --bench: on (default) times frames reaching the screen by page flips, capped\n"
            "                      at the refresh rate; off draws them offscreen at the display's size, each\n"
            "                      ended by glFinish, as snell-bench times (the JSON says which)\n"
            "  --warmup N          benchmark warm-up frames (default 5)\n"
            "  --json FILE         benchmark JSON (default snell-kiosk.json)\n"
            "  --config FILE       options from FILE, one a line as written here ('--spin 0.25', '-b SPEC');\n"
            "                      '#' starts a comment; options after --config override it\n"
            "  --panels FILE       glass panels over what is shown, one a line as snell-render --panels reads\n"
            "                      them: key=value fields of snell_panel, pixels of the display from its\n"
            "                      bottom-left corner (docs/panels.md)\n"
            "  --slide IMAGE       with --panels: a picture (PNG) under the panels instead of the scene,\n"
            "                      stretched over the display; repeat for a slideshow (at most %d)\n"
            "  --slide-seconds S   how long each picture stays (default %g)\n"
            "  --preview FILE      no display: draw the configured scene's first frame offscreen at the\n"
            "                      --mode size (default 1920x1080) into the PNG FILE, after the same checks\n"
            "  --version           the version and the commit it was built from\n"
            "  -h, --help          this text\n"
            "Exit status: 0, 1 on failure, 2 on bad usage, %d when the display went away while showing,\n"
            "%d when there is no DRM/KMS display (a service restarts on both: docs/kiosk.md \"As a service\").\n",
            BENCH_DEFAULT_FRAMES, KIOSK_MAX_SLIDES, KIOSK_DEFAULT_SLIDE_S, KIOSK_EXIT_DISPLAY_LOST, KIOSK_EXIT_NO_DISPLAY);
}

static int parse_long(const char *opt, const char *v, long lo, long hi, long *out)
{
    char *end;
    long x;
    errno = 0;
    x = strtol(v, &end, 10);
    if (errno || end == v || *end || x < lo || x > hi) {
        fprintf(stderr, "snell-kiosk: %s %s: want an integer %ld..%ld\n", opt, v, lo, hi);
        return 0;
    }
    *out = x;
    return 1;
}

static int parse_double(const char *opt, const char *v, double lo, double hi, double *out)
{
    char *end;
    double x;
    errno = 0;
    x = strtod(v, &end);
    if (errno || end == v || *end || !isfinite(x) || x < lo || x > hi) {
        fprintf(stderr, "snell-kiosk: %s %s: want a number %g..%g\n", opt, v, lo, hi);
        return 0;
    }
    *out = x;
    return 1;
}

/* Options with a value; 1 taken, 0 bad value (message printed), -1 unknown. */
static int value_option(const char *a, const char *v, kiosk_options *o)
{
    long l;
    double x;
    if (!strcmp(a, "-b")) {
        if (o->spec_count == KIOSK_MAX_SPECS)
            return fprintf(stderr, "snell-kiosk: more than %d -b\n", KIOSK_MAX_SPECS), 0;
        o->specs[o->spec_count++] = v;
    } else if (!strcmp(a, "--device")) {
        o->display.device = v;
    } else if (!strcmp(a, "--dri-dir")) {
        o->display.dri_dir = v;
    } else if (!strcmp(a, "--connector")) {
        if (!parse_long(a, v, 1, 0xffffffffL, &l)) return 0;
        o->display.connector_id = (uint32_t)l;
    } else if (!strcmp(a, "--mode")) {
        if (!kms_parse_mode(v, &o->display.mode))
            return fprintf(stderr, "snell-kiosk: --mode %s: want WxH or WxH@R (e.g. 1920x1080@60)\n", v), 0;
    } else if (!strcmp(a, "--spin")) {
        if (!parse_double(a, v, -360.0, 360.0, &x)) return 0;
        o->spin_deg = (float)x;
    } else if (!strcmp(a, "--budget")) {
        if (!parse_double(a, v, 0.1, 1e6, &x)) return 0;
        o->budget_ms = (float)x;
    } else if (!strcmp(a, "--frames")) {
        if (!parse_long(a, v, 1, 1000000000L, &o->frames)) return 0;
    } else if (!strcmp(a, "--report")) {
        if (!parse_double(a, v, 0.0, 86400.0, &o->report_s)) return 0;
    } else if (!strcmp(a, "--warmup")) {
        if (!parse_long(a, v, 0, 100000, &l)) return 0;
        o->warmup = (int)l;
    } else if (!strcmp(a, "--json")) {
        o->json = v;
    } else if (!strcmp(a, "--panels")) {
        char why[512];
        cli_panels_free(&o->panels); /* a later --panels replaces the file's */
        if (!cli_panels_read(v, &o->panels, why, sizeof why))
            return fprintf(stderr, "snell-kiosk: --panels %s\n", why), 0;
        o->panels_file = v;
    } else if (!strcmp(a, "--slide")) {
        char why[128], safe[256];
        int fd;
        if (o->slide_count == KIOSK_MAX_SLIDES)
            return fprintf(stderr, "snell-kiosk: more than %d --slide\n", KIOSK_MAX_SLIDES), 0;
        if ((fd = cli_open_input(v, why, sizeof why)) < 0) /* found now, not when it comes on */
            return fprintf(stderr, "snell-kiosk: --slide %s: %s\n", cli_safe(v, safe, sizeof safe), why), 0;
        close(fd);
        o->slides[o->slide_count++] = v;
    } else if (!strcmp(a, "--slide-seconds")) {
        if (!parse_double(a, v, 0.1, 86400.0, &o->slide_s)) return 0;
    } else if (!strcmp(a, "--preview")) {
        o->preview = v;
    } else if (!strcmp(a, "--vsync")) {
        if (strcmp(v, "on") && strcmp(v, "off"))
            return fprintf(stderr, "snell-kiosk: --vsync %s: on or off\n", v), 0;
        o->vsync_off = !strcmp(v, "off");
    } else {
        return -1;
    }
    return 1;
}

/* Is a an option that takes a value (value_option's)? */
static int takes_value(const char *a)
{
    static const char *const names[] = {"-b",       "--device", "--dri-dir", "--connector", "--mode",
                                        "--spin",   "--frames", "--report",  "--warmup",    "--json",
                                        "--budget", "--preview", "--vsync", "--panels", "--slide",
                                        "--slide-seconds"};
    size_t k;
    for (k = 0; k < sizeof names / sizeof *names; k++)
        if (!strcmp(a, names[k])) return 1;
    return 0;
}

/* One option, from the command line or a --config file (from_config): 1
 * taken (*used_value: its value was v), 0 bad (message printed). */
static int one_option(const char *a, const char *v, int from_config, kiosk_options *o, int *spin_set, int *used_value)
{
    int r;
    *used_value = 0;
    if (!strcmp(a, "--hold")) {
        o->hold = 1;
    } else if (!strcmp(a, "--bench")) {
        o->bench = 1;
    } else if (!strcmp(a, "--atomic")) {
        o->display.atomic = 1;
    } else if (!strcmp(a, "--config") && from_config) {
        fprintf(stderr, "snell-kiosk: --config inside a --config file\n");
        return 0;
    } else if (!takes_value(a)) {
        fprintf(stderr, "snell-kiosk: unknown option '%s'; see --help\n", a);
        return 0;
    } else if (!v) {
        fprintf(stderr, "snell-kiosk: %s needs a value; see --help\n", a);
        return 0;
    } else {
        if (!strcmp(a, "-b") && !from_config && o->config_specs) /* the command line's scene replaces the file's */
            o->spec_count = o->config_specs = 0;
        if (!strcmp(a, "--slide") && !from_config && o->config_slides) /* and its slides */
            o->slide_count = o->config_slides = 0;
        if ((r = value_option(a, v, o)) < 0) {
            fprintf(stderr, "snell-kiosk: unknown option '%s'; see --help\n", a);
            return 0;
        }
        if (!r) return 0;
        if (!strcmp(a, "-b") && from_config) o->config_specs++;
        if (!strcmp(a, "--slide") && from_config) o->config_slides++;
        *spin_set |= !strcmp(a, "--spin");
        *used_value = 1;
    }
    return 1;
}

/* --config FILE: each line "OPTION [VALUE]", as on the command line; blank
 * lines and '#' comments skipped. The text is kept for the process's life:
 * -b and the other string options point into it. */
static int read_config(const char *path, kiosk_options *o, int *spin_set)
{
    char *text, *line, *next, why[128], safe[256];
    size_t size;
    int n = 0, used;
    if (!(text = cli_read_input(path, 65536, &size, why, sizeof why))) {
        fprintf(stderr, "snell-kiosk: --config %s: %s\n", cli_safe(path, safe, sizeof safe), why);
        return 0;
    }
    for (line = text; line; line = next) {
        char *a, *v, *end;
        n++;
        next = strchr(line, '\n');
        if (next) *next++ = 0;
        if ((end = strchr(line, '#'))) *end = 0;
        a = line + strspn(line, " \t\r");
        end = a + strlen(a);
        while (end > a && strchr(" \t\r", end[-1])) *--end = 0;
        if (!*a) continue;
        if (cli_has_control(a)) { /* it would be echoed below, or be a path or a scene's name */
            fprintf(stderr, "snell-kiosk: --config %s line %d: a control character\n",
                    cli_safe(path, safe, sizeof safe), n);
            return 0;
        }
        v = a + strcspn(a, " \t");
        if (*v) {
            *v++ = 0;
            v += strspn(v, " \t");
        }
        if (!one_option(a, *v ? v : NULL, 1, o, spin_set, &used) || (*v && !used)) {
            if (*v && !used) fprintf(stderr, "snell-kiosk: %s takes no value\n", a);
            fprintf(stderr, "snell-kiosk: in %s line %d\n", cli_safe(path, safe, sizeof safe), n);
            return 0; /* text stays allocated: o may point into it; the kiosk exits */
        }
    }
    return 1;
}

int kiosk_parse_options(int argc, char **argv, kiosk_options *o)
{
    /* the long options by name; one_option takes each as a --config line would give it */
    static const struct option longopts[] = {
        {"device", required_argument, NULL, 256},  {"dri-dir", required_argument, NULL, 257},
        {"connector", required_argument, NULL, 258}, {"mode", required_argument, NULL, 259},
        {"spin", required_argument, NULL, 260},    {"frames", required_argument, NULL, 261},
        {"report", required_argument, NULL, 262},  {"warmup", required_argument, NULL, 263},
        {"json", required_argument, NULL, 264},    {"budget", required_argument, NULL, 265},
        {"preview", required_argument, NULL, 266}, {"vsync", required_argument, NULL, 267},
        {"config", required_argument, NULL, 268},  {"hold", no_argument, NULL, 269},
        {"bench", no_argument, NULL, 270},         {"atomic", no_argument, NULL, 271},
        {"version", no_argument, NULL, 272},       {"panels", required_argument, NULL, 273},
        {"slide", required_argument, NULL, 274},   {"slide-seconds", required_argument, NULL, 275},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    int c, spin_set = 0, used;
    memset(o, 0, sizeof *o);
    o->spin_deg = 0.5f;
    o->report_s = 5.0;
    o->warmup = 5;
    o->json = "snell-kiosk.json";
    o->slide_s = KIOSK_DEFAULT_SLIDE_S;
    if (cli_wants_help(argc, argv)) { /* --help wherever it is */
        usage(stdout);
        return -1;
    }
    cli_opts_reset();
    while ((c = cli_getopt("snell-kiosk", "--help", argc, argv, "b:h", longopts)) != -1) {
        char name[32];
        if (c == '?') return 0;
        if (c == 272) {
            cli_print_version("snell-kiosk");
            return -1;
        }
        if (c >= 256) snprintf(name, sizeof name, "--%s", longopts[c - 256].name);
        else snprintf(name, sizeof name, "-%c", c);
        if (c == 268) {
            if (!read_config(optarg, o, &spin_set)) return 0;
        } else if (!one_option(name, optarg, 0, o, &spin_set, &used)) {
            return 0;
        }
    }
    if (optind < argc) {
        fprintf(stderr, "snell-kiosk: unexpected argument '%s'; see --help\n", argv[optind]);
        return 0;
    }
    if (o->bench && !spin_set) o->spin_deg = 0.0f; /* timed frames of one view, as snell-bench times them */
    if (o->bench && !o->frames) o->frames = BENCH_DEFAULT_FRAMES; /* p99 and the 1% low a frame of their own */
    if (o->vsync_off && !o->bench) {
        fprintf(stderr, "snell-kiosk: --vsync off times --bench offscreen; the kiosk shows frames at vblank\n");
        return 0;
    }
    if (!o->bench && o->spec_count > 1) {
        fprintf(stderr, "snell-kiosk: one -b shows one configuration; several need --bench\n");
        return 0;
    }
    if (o->slide_count && !o->panels_file) {
        fprintf(stderr, "snell-kiosk: --slide shows pictures under glass panels: give --panels FILE\n");
        return 0;
    }
    if (o->bench && o->panels_file) {
        fprintf(stderr, "snell-kiosk: --bench times -b configurations; --panels is for showing them\n");
        return 0;
    }
    if (o->bench && o->preview) {
        fprintf(stderr, "snell-kiosk: --preview draws the one configuration shown; not with --bench\n");
        return 0;
    }
    return 1;
}
