/* SPDX-License-Identifier: MIT */
/* render2d.c — `snell-render --2d`: a 2D scene file -> lightmap PNG, optionally
 * multiplied onto an albedo image (Brückner A.3); and `--contour`: an image's
 * alpha outline -> polygon CSV (A.5). Public API only (+ stb_image, file-local). */
#include "snell/snell.h"
#include "snell/snell_2d.h"
#include "cli_opts.h"

#include <math.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


int snell_render2d_main(int argc, char **argv);

/* Whole-string numbers only: "--passes abc" is an error, not 0. */
static int arg_int(const char *opt, const char *v, long lo, long hi, int *out)
{
    char *end;
    long x;
    errno = 0;
    x = strtol(v, &end, 10);
    if (end == v || *end || errno || x < lo || x > hi) {
        fprintf(stderr, "snell-render --2d: %s wants an integer in %ld..%ld, got '%s'\n", opt, lo, hi, v);
        return 0;
    }
    *out = (int)x;
    return 1;
}

static int arg_float(const char *opt, const char *v, float lo, float hi, float *out)
{
    char *end;
    float x;
    errno = 0;
    x = strtof(v, &end);
    if (end == v || *end || errno || !(x >= lo && x <= hi)) {
        fprintf(stderr, "snell-render --2d: %s wants a number in %g..%g, got '%s'\n", opt, lo, hi, v);
        return 0;
    }
    *out = x;
    return 1;
}

static void usage(FILE *out)
{
    fprintf(out,
            "usage: snell-render --2d SCENE.txt -o OUT.png [options]\n"
            "       snell-render --2d --contour IMAGE.png -o OUT.csv [--epsilon PX] [--threshold A]\n"
            "options:\n"
            "  --albedo IMG.png     multiply the lightmap onto this image (its size sets the lightmap size)\n"
            "  --size WxH           lightmap size (default: scene 'size', else 512x512)\n"
            "  --exposure E|auto    scale before display; auto: 99th percentile of lit pixels -> 1 (default)\n"
            "  --gamma G            display gamma (default 2.2; 1 = linear lightmap as in the thesis)\n"
            "  --bounces N          interactions per ray (default 8; 0 = direct light only)\n"
            "  --passes N           progressive passes to accumulate (default 1)\n"
            "  --threads N --seed S --blend add|screen --cpu (exact CPU rasteriser, no GL)\n"
            "  --raster auto|gl|cpu  who rasterises the paths (auto: the CPU on software GL, else GL lines)\n"
            "  --format auto|rgba32f|rgba16f|rgb10a2|rgba8\n");
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static int contour_main(const char *in, const char *out, float eps, int thr)
{
    int w, h, n;
    float *pts;
    uint8_t *img = NULL;
    snell_status st = snell_image_read(in, &w, &h, &img);
    if (st != SNELL_OK) {
        fprintf(stderr, "snell-render --2d: %s\n", snell_last_error(NULL));
        return 1;
    }
    st = snell_contour2d_from_alpha(NULL, img, w, h, thr, eps, &pts, &n);
    snell_image_free(img);
    if (st == SNELL_OK) {
        st = snell_contour2d_write_csv(out, pts, n);
        snell_contour2d_free(NULL, pts);
    }
    if (st != SNELL_OK) {
        fprintf(stderr, "snell-render --2d: %s: %s\n", snell_status_str(st), snell_last_error(NULL));
        return 1;
    }
    printf("%s: %d points\n", out, n);
    return 0;
}

int snell_render2d_main(int argc, char **argv)
{
    const char *scene_path = NULL, *out = NULL, *albedo_path = NULL, *contour = NULL;
    float exposure = 0.0f, gamma = 2.2f, eps = 0.0f, view[4];
    static const struct option longopts[] = {
        {"albedo", required_argument, NULL, 256},  {"contour", required_argument, NULL, 257},
        {"epsilon", required_argument, NULL, 258}, {"threshold", required_argument, NULL, 259},
        {"size", required_argument, NULL, 260},    {"exposure", required_argument, NULL, 261},
        {"gamma", required_argument, NULL, 262},   {"bounces", required_argument, NULL, 263},
        {"passes", required_argument, NULL, 264},  {"threads", required_argument, NULL, 265},
        {"seed", required_argument, NULL, 266},    {"blend", required_argument, NULL, 267},
        {"raster", required_argument, NULL, 268},  {"format", required_argument, NULL, 269},
        {"cpu", no_argument, NULL, 270},           {"2d", no_argument, NULL, 271},
        {"help", no_argument, NULL, 'h'},          {NULL, 0, NULL, 0}};
    int i, c, w = 0, h = 0, passes = 1, thr = 128, size[2], aw = 0, ah = 0, rc = 1;
    snell_lightmap2d_desc d;
    snell_ctx *ctx = NULL;
    snell_scene2d *s = NULL;
    snell_lightmap2d *lm = NULL;
    snell_lightmap2d_stats stats;
    snell_status st;
    uint8_t *albedo = NULL, *rgba = NULL;
    float *rgb = NULL, *lum = NULL;
    memset(&d, 0, sizeof d);
    if (cli_wants_help(argc, argv)) { /* --help wherever it is */
        usage(stdout);
        return 0;
    }
    cli_opts_reset();
    while ((c = cli_getopt("snell-render --2d", "--2d --help", argc, argv, "o:h", longopts)) != -1) {
        char a[32];
        const char *v = optarg;
        if (c == '?') return 2;
        if (c >= 256) snprintf(a, sizeof a, "--%s", longopts[c - 256].name);
        else snprintf(a, sizeof a, "-%c", c);
        if (strcmp(a, "--2d") == 0) continue;
        if (strcmp(a, "-o") == 0) out = v;
        else if (strcmp(a, "--albedo") == 0) albedo_path = v;
        else if (strcmp(a, "--contour") == 0) contour = v;
        else if (strcmp(a, "--epsilon") == 0) {
            if (!arg_float(a, v, 0.0f, 1e6f, &eps)) return 2;
        } else if (strcmp(a, "--threshold") == 0) {
            if (!arg_int(a, v, 0, 255, &thr)) return 2;
        } else if (strcmp(a, "--size") == 0) {
            if (sscanf(v, "%dx%d", &w, &h) != 2 || w < 1 || h < 1) {
                fprintf(stderr, "snell-render --2d: --size wants WxH, got '%s'\n", v);
                return 2;
            }
        } else if (strcmp(a, "--exposure") == 0) {
            if (strcmp(v, "auto") == 0) exposure = 0.0f;
            else if (!arg_float(a, v, 1e-30f, 1e30f, &exposure)) return 2;
        } else if (strcmp(a, "--gamma") == 0) {
            if (!arg_float(a, v, 0.01f, 100.0f, &gamma)) return 2;
        } else if (strcmp(a, "--bounces") == 0) {
            int b;
            if (!arg_int(a, v, 0, 1000, &b)) return 2;
            d.max_bounces = b == 0 ? -1 : b;
        } else if (strcmp(a, "--passes") == 0) {
            if (!arg_int(a, v, 1, 100000, &passes)) return 2;
        } else if (strcmp(a, "--threads") == 0) {
            if (!arg_int(a, v, 0, 256, &d.threads)) return 2;
        } else if (strcmp(a, "--seed") == 0) {
            char *end;
            errno = 0;
            d.seed = (uint64_t)strtoull(v, &end, 10);
            if (end == v || *end || errno) {
                fprintf(stderr, "snell-render --2d: --seed wants an unsigned integer, got '%s'\n", v);
                return 2;
            }
        } else if (strcmp(a, "--blend") == 0) {
            if (strcmp(v, "screen") && strcmp(v, "add")) {
                fprintf(stderr, "snell-render --2d: --blend wants add or screen, got '%s'\n", v);
                return 2;
            }
            d.blend = strcmp(v, "screen") == 0 ? SNELL_BLEND2D_SCREEN : SNELL_BLEND2D_ADD;
        } else if (strcmp(a, "--cpu") == 0) {
            d.cpu_only = 1;
        } else if (strcmp(a, "--raster") == 0) {
            if (strcmp(v, "auto") == 0) d.raster = SNELL_RASTER2D_AUTO;
            else if (strcmp(v, "gl") == 0) d.raster = SNELL_RASTER2D_GL;
            else if (strcmp(v, "cpu") == 0) d.raster = SNELL_RASTER2D_CPU;
            else {
                fprintf(stderr, "snell-render --2d: --raster wants auto, gl or cpu, got '%s'\n", v);
                return 2;
            }
        } else if (strcmp(a, "--format") == 0) {
            d.format = strcmp(v, "rgba32f") == 0 ? SNELL_FORMAT2D_RGBA32F
                       : strcmp(v, "rgba16f") == 0 ? SNELL_FORMAT2D_RGBA16F
                       : strcmp(v, "rgb10a2") == 0 ? SNELL_FORMAT2D_RGB10A2
                       : strcmp(v, "rgba8") == 0   ? SNELL_FORMAT2D_RGBA8
                                                   : SNELL_FORMAT2D_AUTO;
            if (d.format == SNELL_FORMAT2D_AUTO && strcmp(v, "auto")) {
                fprintf(stderr, "snell-render --2d: unknown --format '%s'\n", v);
                return 2;
            }
        }
    }
    for (; optind < argc; optind++) { /* the one SCENE */
        if (scene_path) {
            fprintf(stderr, "snell-render --2d: one SCENE, got '%s' and '%s'; see --2d --help\n", scene_path,
                    argv[optind]);
            return 2;
        }
        scene_path = argv[optind];
    }
    if (contour) {
        if (!out) {
            fprintf(stderr, "snell-render --2d: --contour %s needs -o FILE\n", contour);
            return 2;
        }
        return contour_main(contour, out, eps, thr);
    }
    if (!scene_path || !out) {
        fprintf(stderr, "snell-render --2d: needs a SCENE file and -o OUT.png; see --2d --help\n");
        return 2;
    }
    if ((st = snell_scene2d_load(NULL, scene_path, &s, view, size)) != SNELL_OK) {
        fprintf(stderr, "snell-render --2d: %s: %s\n", snell_status_str(st), snell_last_error(NULL));
        return 1;
    }
    if (albedo_path) {
        if (snell_image_read(albedo_path, &aw, &ah, &albedo) != SNELL_OK) {
            fprintf(stderr, "snell-render --2d: albedo: %s\n", snell_last_error(NULL));
            goto done;
        }
        if (!w) {
            w = aw;
            h = ah;
        } else if (w != aw || h != ah) {
            fprintf(stderr, "snell-render --2d: albedo is %dx%d but the lightmap %dx%d\n", aw, ah, w, h);
            goto done;
        }
    }
    if (!w) {
        w = size[0] ? size[0] : 512;
        h = size[1] ? size[1] : 512;
    }
    d.width = w;
    d.height = h;
    if (view[2] > view[0]) {
        d.view_min[0] = view[0];
        d.view_min[1] = view[1];
        d.view_max[0] = view[2];
        d.view_max[1] = view[3];
    }
    d.exposure = exposure > 0.0f && d.blend == SNELL_BLEND2D_SCREEN ? exposure : 1.0f;
    d.progressive = passes > 1;
    if (!d.cpu_only && snell_ctx_create(NULL, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-render --2d: no GL context (%s); using the CPU rasteriser\n", snell_last_error(NULL));
        ctx = NULL;
    }
    if ((st = snell_lightmap2d_create(ctx, &d, &lm)) != SNELL_OK) goto fail;
    for (i = 0; i < passes; i++)
        if ((st = snell_lightmap2d_frame(lm, s, &stats)) != SNELL_OK) goto fail;
    rgb = (float *)malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    lum = (float *)malloc(sizeof(float) * (size_t)w * (size_t)h);
    rgba = (uint8_t *)malloc(4 * (size_t)w * (size_t)h);
    if (!rgb || !lum || !rgba) {
        fprintf(stderr, "snell-render --2d: out of memory\n");
        goto done;
    }
    if ((st = snell_lightmap2d_read_rgb(lm, rgb)) != SNELL_OK) goto fail;
    if (exposure == 0.0f && d.blend == SNELL_BLEND2D_ADD) {
        /* auto exposure: the 99th percentile of lit pixels becomes white */
        size_t n = 0, k;
        for (k = 0; k < (size_t)w * (size_t)h; k++) {
            float m = fmaxf(rgb[3 * k], fmaxf(rgb[3 * k + 1], rgb[3 * k + 2]));
            if (m > 0.0f) lum[n++] = m;
        }
        qsort(lum, n, sizeof(float), cmp_float);
        exposure = n ? 1.0f / lum[(size_t)(0.99 * (double)(n - 1))] : 1.0f;
    } else if (d.blend == SNELL_BLEND2D_SCREEN) {
        exposure = 1.0f; /* already applied inside the blend */
    }
    for (i = 0; i < w * h; i++) {
        int k;
        for (k = 0; k < 3; k++) {
            float v = powf(fminf(fmaxf(rgb[3 * i + k] * exposure, 0.0f), 1.0f), 1.0f / gamma);
            if (albedo) v *= (float)albedo[4 * i + k] / 255.0f; /* A.3: lightmap x texture */
            rgba[4 * i + k] = (uint8_t)(v * 255.0f + 0.5f);
        }
        rgba[4 * i + 3] = albedo ? albedo[4 * i + 3] : 255;
    }
    if ((st = snell_write_png(out, w, h, rgba)) != SNELL_OK) {
        /* a call without a context: its message is the thread's */
        fprintf(stderr, "snell-render --2d: %s: %s\n", snell_status_str(st), snell_last_error(NULL));
        goto done;
    }
    printf("%s: %dx%d, %s, %s, %llu rays, %llu paths, %d pass(es), trace %.1f ms, raster %.1f ms, exposure %.4g\n",
           out, w, h, ctx ? snell_ctx_gl_renderer(ctx) : "no GL",
           stats.raster == SNELL_RASTER2D_GL ? "GL lines" : "CPU exact rasteriser", (unsigned long long)stats.rays,
           (unsigned long long)stats.paths, stats.passes, stats.trace_ms, stats.raster_ms, (double)exposure);
    printf("rasteriser: %s\n", stats.raster_reason);
    rc = 0;
    goto done;
fail:
    fprintf(stderr, "snell-render --2d: %s: %s\n", snell_status_str(st), snell_last_error(ctx));
done:
    free(rgb);
    free(lum);
    free(rgba);
    snell_image_free(albedo);
    snell_lightmap2d_destroy(lm);
    snell_scene2d_destroy(s);
    snell_ctx_destroy(ctx);
    return rc;
}
