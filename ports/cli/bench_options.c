/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L /* stat */
/* bench_options.c — snell-bench's command line and --help; the methods and
 * their parameters (with the defaults the library resolves) come from the
 * registry through cli_method.c. */
#include "bench.h"
#include "cli_method.h"
#include "cli_opts.h"
#include "cli_scene.h"
#include "cli_system.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int bench_parse_int(const char *key, const char *v, int lo, int hi, int *out)
{
    char *end;
    long x;
    errno = 0;
    x = strtol(v, &end, 10);
    if (end == v || *end || errno || x < lo || x > hi) {
        fprintf(stderr, "snell-bench: %s=%s: want an integer in %d..%d\n", key, v, lo, hi);
        return 0;
    }
    *out = (int)x;
    return 1;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: snell-bench [options] [-b SPEC]...\n"
            "       snell-bench --compare A.json B.json\n"
            "       snell-bench --budget MS|Nx | --water | --env-lookup | --2d [their options; each has --help]\n"
            "Times refraction methods and measures their error against the CPU reference.\n"
            "With no SPEC: a quick default sweep of every method that renders here.\n\n"
            "  -b, --benchmark SPEC   method[:key=value[,value...]]... (a comma list sweeps); method auto:\n"
            "                         the renderer picks per object; bare SPEC arguments are accepted too\n"
            "  --scenes LIST          scenes for specs without scene= (default sphere,torus,goblet,bunny)\n"
            "  --scene FILE           one scene for specs without scene=, e.g. a glTF scene file\n"
            "  --baseline-scene S     configurations of one size take turns across scenes, and vs_scene\n"
            "                         (the table's xscene) is each one's time over the same spec's on S\n"
            "  --sizes LIST           sizes for specs without size= (default 256x256)\n"
            "  --view M --projection M  the camera as a host gives it (16 comma-separated numbers each,\n"
            "                         column-major, GL clip conventions), for every scene\n"
            "  --frames N             timed frames per configuration (default %d, so that p99 and the\n"
            "                         1%% low are a frame of their own); p50, p95, p99 and 1%% low reported,\n"
            "                         every frame's time in the JSON\n"
            "  --warmup N             untimed frames first (default 3)\n"
            "  --full-interfaces N    interface cap of the FULL reference (default 10)\n"
            "  --threads N            reference tracer threads (default: all CPUs)\n"
            "  --aa S                 colour errors on area-averaged images: the GPU frame with\n"
            "                         ssaa = S, the references with S x S rays a pixel (default 1:\n"
            "                         pixel centres); timing stays the plain frame\n"
            "  --floor-aa S           FULL's own noise floor: the FULL reference at S x S rays against\n"
            "                         the one at --aa's, glass PSNR (e.g. --aa 4 --floor-aa 2)\n"
            "                         (llvmpipe's own threads come from LP_NUM_THREADS, unset: one per\n"
            "                         CPU; reported in the table, JSON and CSV)\n"
            "  --env FILE|procedural  environment: procedural (default), an equirectangular image,\n"
            "                         or six faces given as a pattern with %%s (px nx py ny pz nz;\n"
            "                         %%%% for a %%, no other %%)\n"
            "  -o PREFIX              outputs PREFIX.json, .csv, .png (default snell-bench)\n"
            "  --markdown FILE        also a markdown table per scene and size (what drew each configuration,\n"
            "                         ms, x single, glass PSNR/SSIM vs FULL, Pareto), the plot's link and the\n"
            "                         command (bench/regen.sh makes bench/BENCHMARKS.md of these)\n"
            "  --cache DIR            reference cache (default snell-bench-cache); --no-cache\n"
            "  --images DIR           also write each configuration's colour image and error map\n"
            "  --plot-y WHAT          full-mean (default), full-p99, full-rmse, matched-mean\n"
            "  --list                 methods and their keys (also shown by --help)\n"
            "  --compare A.json B.json  two runs side by side (two boards, two builds): per configuration\n"
            "                         the median and p99 frame time, their ratio and the glass PSNR vs FULL\n"
            "  --budget MS|Nx ...     AUTO by frame budget against its rung table (see --budget --help)\n"
            "  --water ...            the water scene's simulation and rendering timed apart (--water --help)\n"
            "  --env-lookup ...       environment look-ups: cube map vs dual paraboloid (--env-lookup --help)\n"
            "  --2d ...               the 2D lightmap benchmarks (see --2d --help)\n"
            "  -q                     no progress lines\n"
            "  --version              the version and the commit it was built from\n"
            "  -h, --help             this text\n\n"
            "Every JSON records the snell version and commit, GL vendor, renderer and version, the kernel,\n"
            "the board model where the system states it, the vsync mode and the load before and after.\n\n",
            BENCH_DEFAULT_FRAMES);
    fprintf(f,
            "The error is measured against the reference tracer rendering the same scene as the frame\n"
            "drew it: isolate_glass = 1 (light that left a glass object sees the environment and the opaque\n"
            "objects but no other glass object) unless the frame drew the scene layers (glass seen through\n"
            "glass), so the error is the method's own.\n"
            "Then against FULL of the whole scene (glass seen through glass), per class of the reference's first\n"
            "hit (glass, opaque, background, all), beside each glass object drawn alone by the method.\n\n"
            "example: snell-bench -b single:scene=bunny:size=256x256,512x512 -b cubemap:scene=pair:iterations=4,8\n");
    if (f != stdout) return;
    printf("\nkeys of every method:\n");
    bench_spec_help(stdout);
    printf("\nscenes (scene=):\n");
    bench_scene_help(stdout);
    printf("\nmethods (the library's registry) and their keys:\n");
    cli_method_help(stdout, "", "", "");
}

static int set_list(char *dst, size_t n, const char *opt, const char *v)
{
    if (strlen(v) >= n || !*v) {
        fprintf(stderr, "snell-bench: bad %s '%s'\n", opt, v);
        return 0;
    }
    strcpy(dst, v);
    return 1;
}

static int add_spec(bench_options *o, const char *spec)
{
    if (o->spec_count == BENCH_MAX_SPECS) {
        fprintf(stderr, "snell-bench: more than %d specs\n", BENCH_MAX_SPECS);
        return 0;
    }
    o->specs[o->spec_count++] = spec;
    return 1;
}

/* An option with a value. 1 handled, 0 bad value, -1 unknown. */
static int value_option(const char *a, const char *v, bench_options *o)
{
    if (!strcmp(a, "-b") || !strcmp(a, "--benchmark")) return add_spec(o, v);
    if (!strcmp(a, "--scenes")) return set_list(o->scenes, sizeof o->scenes, a, v);
    if (!strcmp(a, "--scene")) {
        if (strchr(v, ',')) {
            fprintf(stderr, "snell-bench: --scene '%s': one scene (a comma separates scenes in --scenes)\n", v);
            return 0;
        }
        return set_list(o->scenes, sizeof o->scenes, a, v);
    }
    if (!strcmp(a, "--baseline-scene")) {
        if (!*v) return fprintf(stderr, "snell-bench: --baseline-scene needs a scene\n"), 0;
        o->baseline_scene = v;
        return 1;
    }
    if (!strcmp(a, "--sizes")) return set_list(o->sizes, sizeof o->sizes, a, v);
    if (!strcmp(a, "--view") || !strcmp(a, "--projection")) {
        float *m = a[2] == 'v' ? o->view : o->projection;
        const char *s = v;
        char *end;
        int k;
        for (k = 0; k < 16; k++, s = end + (k < 16)) {
            m[k] = strtof(s, &end);
            if (end == s || !isfinite(m[k]) || *end != (k < 15 ? ',' : '\0'))
                return fprintf(stderr, "snell-bench: %s '%s': 16 comma-separated finite numbers\n", a, v), 0;
        }
        *(a[2] == 'v' ? &o->view_given : &o->projection_given) = 1;
        return 1;
    }
    if (!strcmp(a, "--frames")) return bench_parse_int(a, v, 1, 100000, &o->frames);
    if (!strcmp(a, "--warmup")) return bench_parse_int(a, v, 0, 100000, &o->warmup);
    if (!strcmp(a, "--full-interfaces")) return bench_parse_int(a, v, 1, SNELL_REF_MAX_INTERFACES, &o->full_interfaces);
    if (!strcmp(a, "--threads")) return bench_parse_int(a, v, 0, SNELL_REF_MAX_THREADS, &o->threads);
    if (!strcmp(a, "--aa")) return bench_parse_int(a, v, 1, SNELL_MAX_SSAA, &o->aa);
    if (!strcmp(a, "--floor-aa")) return bench_parse_int(a, v, 1, SNELL_REF_MAX_SAMPLES, &o->floor_aa);
    if (!strcmp(a, "--env")) {
        char why[160];
        if (!cli_env_spec_check(v, why, sizeof why)) {
            fprintf(stderr, "snell-bench: %s '%s': %s; only %%s (the face: px nx py ny pz nz) and %%%% (a %%) may "
                            "follow a %%\n", a, v, why);
            return 0;
        }
        o->env = strcmp(v, "procedural") ? v : NULL;
    } else if (!strcmp(a, "-o")) o->out_prefix = v;
    else if (!strcmp(a, "--markdown")) o->markdown = v;
    else if (!strcmp(a, "--cache")) o->cache_dir = v;
    else if (!strcmp(a, "--images")) o->images_dir = v;
    else if (!strcmp(a, "--plot-y")) {
        if (strcmp(v, "full-mean") && strcmp(v, "full-p99") && strcmp(v, "full-rmse") && strcmp(v, "matched-mean")) {
            fprintf(stderr, "snell-bench: --plot-y wants full-mean|full-p99|full-rmse|matched-mean, got '%s'\n", v);
            return 0;
        }
        o->plot_y = v;
    } else return -1;
    return 1;
}

/* The long options; each value is its index + 256, so that its name gives value_option the option. */
static const struct option g_long[] = {
    {"benchmark", required_argument, NULL, 256},       {"scenes", required_argument, NULL, 257},
    {"scene", required_argument, NULL, 258},           {"baseline-scene", required_argument, NULL, 259},
    {"sizes", required_argument, NULL, 260},           {"frames", required_argument, NULL, 261},
    {"warmup", required_argument, NULL, 262},          {"full-interfaces", required_argument, NULL, 263},
    {"threads", required_argument, NULL, 264},         {"aa", required_argument, NULL, 265},
    {"env", required_argument, NULL, 266},             {"markdown", required_argument, NULL, 267},
    {"cache", required_argument, NULL, 268},           {"images", required_argument, NULL, 269},
    {"plot-y", required_argument, NULL, 270},          {"no-cache", no_argument, NULL, 271},
    {"list", no_argument, NULL, 272},                  {"version", no_argument, NULL, 273},
    {"view", required_argument, NULL, 274},            {"projection", required_argument, NULL, 275},
    {"floor-aa", required_argument, NULL, 276},
    {"help", no_argument, NULL, 'h'},                  {NULL, 0, NULL, 0}};

int bench_parse_options(int argc, char **argv, bench_options *o)
{
    int c;
    memset(o, 0, sizeof *o);
    snprintf(o->scenes, sizeof o->scenes, "sphere,torus,goblet,bunny");
    snprintf(o->sizes, sizeof o->sizes, "256x256");
    o->frames = BENCH_DEFAULT_FRAMES;
    o->warmup = 3;
    o->out_prefix = "snell-bench";
    o->cache_dir = "snell-bench-cache";
    o->full_interfaces = 10;
    o->aa = 1;
    o->plot_y = "full-mean";
    if (cli_wants_help(argc, argv)) { /* --help wherever it is */
        usage(stdout);
        return -1;
    }
    cli_opts_reset();
    while ((c = cli_getopt("snell-bench", "--help", argc, argv, "b:o:qh", g_long)) != -1) {
        char name[40];
        if (c == '?') return 0;
        if (c == 'q') o->quiet = 1;
        else if (c == 271) o->cache_dir = NULL;
        else if (c == 272) {
            usage(stdout);
            return -1;
        } else if (c == 273) {
            cli_print_version("snell-bench");
            return -1;
        } else {
            if (c >= 256) snprintf(name, sizeof name, "--%s", g_long[c - 256].name);
            else snprintf(name, sizeof name, "-%c", c);
            if (value_option(name, optarg, o) <= 0) return 0;
        }
    }
    for (; optind < argc; optind++) /* bare SPEC arguments */
        if (!add_spec(o, argv[optind])) return 0;
    if (o->view_given != o->projection_given)
        return fprintf(stderr, "snell-bench: --view and --projection go together\n"), 0;
    if (o->view_given) bench_scene_set_matrices(o->view, o->projection);
    if (o->images_dir) {
        /* refused before a run that would write none of them */
        struct stat sb;
        errno = 0;
        if (stat(o->images_dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
            fprintf(stderr, "snell-bench: --images '%s' is not a directory (%s)\n", o->images_dir,
                    errno ? strerror(errno) : "not a directory");
            return 0;
        }
    }
    return 1;
}
