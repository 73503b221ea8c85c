/* SPDX-License-Identifier: MIT */
/* bench_output.c — what snell-bench writes: PREFIX.json, PREFIX.csv, the
 * points and labels of the time-vs-error plot (drawn by bench_plot.c), the
 * Pareto front per scene and size, and the summary table on stdout. */
#include "bench.h"
#include "bench_plot.h"
#include "cli_system.h"
#include "cli_time.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_MARKERS 8

/* The renderer of this run, kept by bench_write_json (written first) for the
 * CSV and the table, whose calls do not carry the run. */
static char run_renderer[256];


static double resolved_ior(const bench_config *c)
{
    snell_glass_resolved r;
    return snell_glass_defaults(&c->glass, &r) == SNELL_OK ? r.material.ior : NAN;
}


/* The methods of the configurations that were measured, in order of first
 * appearance (at most MAX_MARKERS): the plot's markers and legend, so a
 * legend lists only what was run. Returns the count. */
static int plot_methods(const bench_config *cs, int n, const snell_method_info *out[MAX_MARKERS])
{
    int i, k, count = 0;
    for (i = 0; i < n; i++) {
        if (!cs[i].ok) continue;
        for (k = 0; k < count && out[k] != cs[i].method; k++) {}
        if (k == count && count < MAX_MARKERS) out[count++] = cs[i].method;
    }
    return count;
}

/* The plot's marker of c: its method's place in plot_methods (0 if past it). */
static int plot_marker(const bench_config *c, const snell_method_info *const methods[MAX_MARKERS], int count)
{
    int k;
    for (k = 0; k < count; k++)
        if (methods[k] == c->method) return k;
    return 0;
}

/* ------------------------------------------------------------------ JSON */
static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\') fprintf(f, "\\%c", ch);
        else if (ch < 0x20) fprintf(f, "\\u%04x", ch);
        else fputc(ch, f);
    }
    fputc('"', f);
}

static void json_num(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, "%.6g", v);
    else fprintf(f, "null");
}

static void json_errors(FILE *f, const bench_config *c, int m)
{
    const snell_dir_error *d = &c->dir[m];
    fprintf(f, "{\"mean_deg\": ");
    json_num(f, d->mean_deg);
    fprintf(f, ", \"rms_deg\": ");
    json_num(f, d->rms_deg);
    fprintf(f, ", \"median_deg\": ");
    json_num(f, d->median_deg);
    fprintf(f, ", \"p99_deg\": ");
    json_num(f, d->p99_deg);
    fprintf(f, ", \"max_deg\": ");
    json_num(f, d->max_deg);
    fprintf(f, ", \"frac_above_1deg\": ");
    json_num(f, d->frac_above_1deg);
    fprintf(f, ", \"frac_above_5deg\": ");
    json_num(f, d->frac_above_5deg);
    fprintf(f, ", \"compared\": %ld, \"mask_mismatch\": %ld, \"glass_ref\": %ld, \"glass_test\": %ld", d->compared,
            d->mask_mismatch, d->glass_ref, d->glass_test);
    fprintf(f, ", \"rmse\": ");
    json_num(f, c->img[m].rmse);
    fprintf(f, ", \"psnr_db\": ");
    json_num(f, c->img[m].psnr_db);
    fprintf(f, ", \"rmse_glass\": ");
    json_num(f, c->img_glass[m].rmse);
    fprintf(f, ", \"psnr_glass_db\": ");
    json_num(f, c->img_glass[m].psnr_db);
    fprintf(f, ", \"ssim_glass\": ");
    json_num(f, c->ssim_glass[m]);
    fprintf(f, ", \"reference_cached\": %s}", c->ref_cached[m] ? "true" : "false");
}

static const char *const scene_image_names[3] = {"method", "alone", "reference_isolated"};

/* One image of c->whole[] against the whole-scene reference, per class. */
static void json_scene_image(FILE *f, const bench_scene_error *e)
{
    const snell_dir_error *d = &e->dir;
    int k;
    fprintf(f, "{");
    for (k = 0; k < BENCH_CLASS_COUNT; k++) {
        const bench_class_error *ce = &e->cls[k];
        fprintf(f, "\"%s\": {\"pixels\": %ld, \"rmse\": ", bench_class_names[k], ce->img.pixels);
        json_num(f, ce->img.rmse);
        fprintf(f, ", \"psnr_db\": ");
        /* identical pixels: +inf dB, which JSON cannot write; rmse 0 says it */
        json_num(f, ce->img.psnr_db);
        fprintf(f, ", \"mean_abs\": ");
        json_num(f, ce->img.mean_abs);
        fprintf(f, ", \"max_abs\": %d, \"ssim\": ", ce->img.max_abs);
        json_num(f, ce->ssim);
        fprintf(f, "}, ");
    }
    fprintf(f, "\"exit_dir_glass\": {\"mean_deg\": ");
    json_num(f, d->mean_deg);
    fprintf(f, ", \"median_deg\": ");
    json_num(f, d->median_deg);
    fprintf(f, ", \"p99_deg\": ");
    json_num(f, d->p99_deg);
    fprintf(f, ", \"frac_above_5deg\": ");
    json_num(f, d->frac_above_5deg);
    fprintf(f, ", \"compared\": %ld, \"mask_mismatch\": %ld}}", d->compared, d->mask_mismatch);
}

static void json_whole_scene(FILE *f, const bench_config *c)
{
    int k;
    fprintf(f, ",\n     \"whole_scene\": {\"reference\": ");
    json_str(f, "FULL with isolate_glass = 0 (glass seen through glass); classes by the reference's first hit");
    for (k = 0; k < 3; k++) {
        fprintf(f, ",\n       \"%s\": ", scene_image_names[k]);
        json_scene_image(f, &c->whole[k]);
    }
    fprintf(f, "}");
}

/* A string, or null where it is empty (the system did not say). */
static void json_str_or_null(FILE *f, const char *s)
{
    if (s && *s) json_str(f, s);
    else fprintf(f, "null");
}

/* What two boards' runs are compared by: the build, the GL driver, the
 * kernel and board (cli_system.h), the vsync mode and the load. */
static void json_system(FILE *f, const bench_run_info *run)
{
    const cli_system *s = run->system;
    fprintf(f, ",\n  \"snell\": {\"version\": ");
    json_str(f, s->version);
    fprintf(f, ", \"commit\": ");
    json_str(f, s->commit);
    fprintf(f, "},\n  \"gl\": {\"vendor\": ");
    json_str(f, s->gl_vendor);
    fprintf(f, ", \"renderer\": ");
    json_str(f, s->gl_renderer);
    fprintf(f, ", \"version\": ");
    json_str(f, s->gl_version);
    fprintf(f, "},\n  \"system\": {\"kernel\": ");
    json_str(f, s->kernel);
    fprintf(f, ", \"board\": ");
    json_str_or_null(f, s->board);
    fprintf(f, ", \"board_from\": ");
    json_str_or_null(f, s->board_from);
    fprintf(f, "}");
}

static void json_header(FILE *f, const bench_options *o, const bench_run_info *run)
{
    char why[64];
    int lp = cli_llvmpipe_threads(run_renderer, why, sizeof why);
    fprintf(f, "{\n  \"tool\": ");
    json_str(f, run->tool ? run->tool : "snell-bench");
    fprintf(f, ",\n  \"date\": ");
    json_str(f, run->date);
    if (run->system) json_system(f, run);
    fprintf(f, ",\n  \"vsync\": ");
    json_str(f, run->vsync ? run->vsync : "off: offscreen frames, each ended by glFinish");
    fprintf(f, ",\n  \"gl_renderer\": ");
    json_str(f, run->renderer);
    if (lp >= 0) fprintf(f, ",\n  \"llvmpipe_threads\": %d", lp);
    else fprintf(f, ",\n  \"llvmpipe_threads\": null");
    fprintf(f, ",\n  \"llvmpipe_threads_from\": ");
    json_str(f, why);
    if (run->limits) { /* what the run could use: the device profile (SNELL_DEVICE_PROFILE) and its limits */
        int k;
        fprintf(f, ",\n  \"device_profile\": ");
        json_str(f, run->limits->profile);
        fprintf(f, ",\n  \"cost_model\": ");
        json_str(f, run->limits->cost_model);
        fprintf(f, ",\n  \"device_limits\": {");
        for (k = 0; k < SNELL_LIMIT_COUNT; k++)
            fprintf(f, "%s\"%s\": %d", k ? ", " : "", snell_limit_str((snell_limit)k), run->limits->limit[k]);
        fprintf(f, "}");
    }
    fprintf(f, ",\n  \"timer_query\": %s,\n  \"timing\": ", run->timer ? "true" : "false");
    json_str(f, run->timing ? run->timing
                            : "median of frames after warm-up; each frame = snell_render + glFinish (CPU wall clock); "
                              "the configurations of one scene and size take turns frame by frame; vs_single = median "
                              "over rounds of the ratio to the single-surface configuration's frame of the same round");
    fprintf(f, ",\n  \"frames\": %d,\n  \"warmup\": %d,\n  \"full_interfaces\": %d,\n  \"area_samples\": %d,"
               "\n  \"loadavg_before\": ",
            o->frames, o->warmup, o->full_interfaces, o->aa);
    json_str(f, run->load_before);
    fprintf(f, ",\n  \"loadavg_after\": ");
    json_str(f, run->load_after);
    if (!run->no_errors) {
        fprintf(f, ",\n  \"mask_policy\": ");
        json_str(f, "angles over pixels that are glass in both the reference hit mask and the method's coverage; "
                    "mismatches counted, not compared");
        fprintf(f, ",\n  \"reference\": ");
        json_str(f, "snell_ref of the same scene, as the frame drew it: with isolate_glass = 1 (light that left a "
                    "glass object sees the environment and the opaque objects but no other glass object) where the "
                    "renderer drew each glass object over its own environment, with isolate_glass = 0 where it drew "
                    "the scene layers (reference_isolate_glass per result), so the error is the method's own; "
                    "whole_scene: against FULL with isolate_glass = 0 in any case");
    }
    fprintf(f, ",\n  \"results\": [\n");
}

static void json_result(FILE *f, const bench_config *c)
{
    int n;
    fprintf(f, "    {\"spec\": ");
    json_str(f, c->spec);
    fprintf(f, ", \"method\": ");
    json_str(f, c->method->name);
    fprintf(f, ", \"scene\": ");
    json_str(f, c->scene);
    fprintf(f, ", \"width\": %d, \"height\": %d, \"ior\": ", c->width, c->height);
    json_num(f, resolved_ior(c));
    fprintf(f, ", \"ok\": %s", c->ok ? "true" : "false");
    if (!c->ok) {
        fprintf(f, ", \"error\": ");
        json_str(f, c->error);
        fprintf(f, "}");
        return;
    }
    fprintf(f, ", \"glass_objects\": %d, \"opaque_objects\": %d, \"warnings\": %d, \"angles_meaningful\": %s",
            c->glass_objects, c->opaque_objects, c->warnings, c->angles_meaningful ? "true" : "false");
    fprintf(f, ", \"scene_layers\": %d, \"reference_isolate_glass\": %s", c->scene_layers,
            c->layers_drawn ? "false" : "true");
    if (c->passes > 0) /* timed by snell-bench (snell-kiosk times its own way) */
        fprintf(f, ", \"passes\": %d, \"scene_layer_passes\": %d, \"scene_layers_used\": %d", c->passes,
                c->layer_passes, c->layers_used);
    if (c->whole_measured) {
        int k;
        fprintf(f, ", \"methods_used\": [");
        for (k = 0; k < c->glass_objects; k++) fprintf(f, "%s\"%s\"", k ? ", " : "", snell_method_str(c->methods_used[k]));
        fprintf(f, "]");
    }
    fprintf(f, ", \"time_ms\": {\"median\": ");
    json_num(f, c->t_median);
    fprintf(f, ", \"p95\": ");
    json_num(f, c->t_p95);
    fprintf(f, ", \"p99\": ");
    json_num(f, c->t_p99);
    fprintf(f, ", \"low_1pct\": ");
    json_num(f, c->t_low1);
    fprintf(f, ", \"min\": ");
    json_num(f, c->t_min);
    fprintf(f, ", \"max\": ");
    json_num(f, c->t_max);
    fprintf(f, ", \"gpu_median\": ");
    json_num(f, c->gpu_median >= 0 ? c->gpu_median : NAN);
    fprintf(f, "}, \"frames_ms\": [");
    for (n = 0; c->frame_ms && n < c->frames; n++) {
        if (n) fprintf(f, n % 16 ? ", " : ",\n       ");
        fprintf(f, "%.4g", c->frame_ms[n]);
    }
    fprintf(f, "], \"vs_single\": ");
    json_num(f, c->vs_single >= 0 ? c->vs_single : NAN);
    fprintf(f, ", \"pareto\": %s, \"exit_dir_encoding\": ", c->pareto ? "true" : "false");
    json_str(f, c->encoding);
    fprintf(f, ", \"nan_inf\": %ld, \"counters\": {", c->nan_inf);
    for (n = 0; n < c->method->counter_count && n < SNELL_MAX_METHOD_COUNTERS; n++) {
        fprintf(f, "%s", n ? ", " : "");
        json_str(f, c->method->counters[n].name);
        fprintf(f, ": ");
        json_num(f, c->counters[n] >= 0 ? (double)c->counters[n] : NAN);
    }
    fprintf(f, "}");
    fprintf(f, ", \"matched_interfaces\": %d,\n     \"vs_matched\": ", c->ref_interfaces);
    json_errors(f, c, 0);
    fprintf(f, ",\n     \"vs_full\": ");
    json_errors(f, c, 1);
    if (c->vs_scene >= 0) {
        fprintf(f, ", \"vs_scene\": ");
        json_num(f, c->vs_scene);
    }
    if (c->whole_measured) json_whole_scene(f, c);
    fprintf(f, "}");
}

int bench_write_json(const char *path, const bench_config *cs, int n, const bench_options *o,
                     const bench_run_info *run)
{
    FILE *f;
    int i;
    snprintf(run_renderer, sizeof run_renderer, "%s", run->renderer ? run->renderer : "");
    f = fopen(path, "w");
    if (!f) return 0;
    json_header(f, o, run);
    for (i = 0; i < n; i++) {
        json_result(f, &cs[i]);
        fprintf(f, "%s\n", i + 1 < n ? "," : "");
    }
    {
        const snell_method_info *methods[MAX_MARKERS];
        int k, count = plot_methods(cs, n, methods);
        fprintf(f, "  ],\n  \"plot_methods\": [");
        for (k = 0; k < count; k++) fprintf(f, "%s\"%s\"", k ? ", " : "", methods[k]->name);
        fprintf(f, "]\n}\n");
    }
    return fclose(f) == 0;
}

/* ------------------------------------------------------------------- CSV */
#define CSV_MODE_FIELDS 14
#define CSV_SCENE_FIELDS (1 + 3 * (2 * BENCH_CLASS_COUNT + 2)) /* vs_scene, then per image of c->whole[] */

static void csv_num(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, ",%.6g", v);
    else fprintf(f, ",");
}

static void csv_errors(FILE *f, const bench_config *c, int m)
{
    const snell_dir_error *d = &c->dir[m];
    csv_num(f, d->mean_deg);
    csv_num(f, d->rms_deg);
    csv_num(f, d->median_deg);
    csv_num(f, d->p99_deg);
    csv_num(f, d->max_deg);
    csv_num(f, d->frac_above_1deg);
    csv_num(f, d->frac_above_5deg);
    fprintf(f, ",%ld,%ld", d->compared, d->mask_mismatch);
    csv_num(f, c->img[m].rmse);
    csv_num(f, c->img[m].psnr_db);
    csv_num(f, c->img_glass[m].rmse);
    csv_num(f, c->img_glass[m].psnr_db);
    csv_num(f, c->ssim_glass[m]);
}

/* PSNR with identical pixels written as inf (csv_num leaves non-finite values empty). */
static void csv_psnr(FILE *f, double v)
{
    if (isinf(v) && v > 0) fprintf(f, ",inf");
    else csv_num(f, v);
}

static void csv_scene(FILE *f, const bench_config *c)
{
    int k, m;
    csv_num(f, c->vs_scene >= 0 ? c->vs_scene : NAN);
    for (m = 0; m < 3; m++) {
        const bench_scene_error *e = &c->whole[m];
        for (k = 0; k < BENCH_CLASS_COUNT; k++) {
            if (!c->whole_measured) {
                fprintf(f, ",,");
                continue;
            }
            csv_psnr(f, e->cls[k].img.psnr_db);
            csv_num(f, e->cls[k].ssim);
        }
        csv_num(f, c->whole_measured ? e->dir.mean_deg : NAN);
        csv_num(f, c->whole_measured ? e->dir.p99_deg : NAN);
    }
}

int bench_write_csv(const char *path, const bench_config *cs, int n)
{
    FILE *f = fopen(path, "w");
    char why[64];
    int i, m, lp = cli_llvmpipe_threads(run_renderer, why, sizeof why);
    if (!f) return 0;
    fprintf(f, "spec,method,scene,width,height,ior,ok,time_median_ms,time_p95_ms,time_p99_ms,time_low_1pct_ms,"
               "time_min_ms,time_max_ms,gpu_median_ms,"
               "vs_single,pareto,exit_dir_encoding,nan_inf,glass_objects,opaque_objects,warnings");
    for (m = 0; m < 2; m++) {
        const char *p = m ? "full" : "matched";
        fprintf(f, ",%s_mean_deg,%s_rms_deg,%s_median_deg,%s_p99_deg,%s_max_deg,%s_frac_above_1deg,"
                   "%s_frac_above_5deg,%s_compared,%s_mask_mismatch,%s_rmse,%s_psnr_db,%s_rmse_glass,"
                   "%s_psnr_glass_db,%s_ssim_glass",
                p, p, p, p, p, p, p, p, p, p, p, p, p, p);
    }
    fprintf(f, ",vs_scene");
    for (m = 0; m < 3; m++) {
        int k;
        for (k = 0; k < BENCH_CLASS_COUNT; k++)
            fprintf(f, ",scene_%s_%s_psnr_db,scene_%s_%s_ssim", scene_image_names[m], bench_class_names[k],
                    scene_image_names[m], bench_class_names[k]);
        fprintf(f, ",scene_%s_glass_mean_deg,scene_%s_glass_p99_deg", scene_image_names[m], scene_image_names[m]);
    }
    fprintf(f, ",error,llvmpipe_threads\n");
    for (i = 0; i < n; i++) {
        const bench_config *c = &cs[i];
        fprintf(f, "\"%s\",%s,\"%s\",%d,%d,%g,%d", c->spec, c->method->name, c->scene, c->width, c->height,
                resolved_ior(c), c->ok);
        if (c->ok) {
            csv_num(f, c->t_median);
            csv_num(f, c->t_p95);
            csv_num(f, c->t_p99);
            csv_num(f, c->t_low1);
            csv_num(f, c->t_min);
            csv_num(f, c->t_max);
            csv_num(f, c->gpu_median >= 0 ? c->gpu_median : NAN);
            csv_num(f, c->vs_single >= 0 ? c->vs_single : NAN);
            fprintf(f, ",%d,%s,%ld,%d,%d,%d", c->pareto, c->encoding, c->nan_inf, c->glass_objects, c->opaque_objects,
                    c->warnings);
            for (m = 0; m < 2; m++) csv_errors(f, c, m);
            csv_scene(f, c);
            fprintf(f, ",");
        } else {
            /* 14 empty fields from time_median_ms to warnings, the error fields, then the error */
            for (m = 0; m < 14 + 2 * CSV_MODE_FIELDS + CSV_SCENE_FIELDS + 1; m++) fputc(',', f);
            fprintf(f, "\"%s\"", c->error);
        }
        if (lp >= 0) fprintf(f, ",%d\n", lp);
        else fprintf(f, ",\n");
    }
    return fclose(f) == 0;
}

/* ---------------------------------------------------------- plot, Pareto */
static double plot_value(const bench_config *c, const char *what)
{
    if (!strcmp(what, "full-p99")) return c->dir[1].p99_deg;
    if (!strcmp(what, "full-rmse")) return c->img_glass[1].rmse;
    if (!strcmp(what, "matched-mean")) return c->dir[0].mean_deg;
    return c->dir[1].mean_deg;
}

/* cs[i].pareto: not dominated in (median time, plot's error) by another
 * configuration of the same scene and size. */
void bench_mark_pareto(bench_config *cs, int n, const bench_options *o)
{
    size_t m = (size_t)(n > 0 ? n : 1);
    bench_plot_point *pts = (bench_plot_point *)calloc(m, sizeof *pts);
    int *front = (int *)calloc(m, sizeof(int)), *at = (int *)calloc(m, sizeof(int));
    int i, j, count = 0;
    for (i = 0; i < n; i++) cs[i].pareto = 0;
    if (pts && front && at) {
        for (i = 0; i < n; i++) {
            if (!cs[i].ok) continue;
            for (j = 0; j < i && !(cs[j].ok && bench_same_group(&cs[j], &cs[i])); j++) {}
            pts[count].group = j; /* first configuration of the group */
            pts[count].x = cs[i].t_median;
            pts[count].y = plot_value(&cs[i], o->plot_y);
            at[count++] = i;
        }
        bench_pareto(pts, count, front);
        for (i = 0; i < count; i++) cs[at[i]].pareto = front[i];
    }
    free(pts);
    free(front);
    free(at);
}

static const char *y_label(const char *what)
{
    if (!strcmp(what, "full-p99")) return "99th percentile exit-direction error vs FULL reference [deg]";
    if (!strcmp(what, "full-rmse")) return "RMSE of glass pixels vs FULL reference [8-bit units]";
    if (!strcmp(what, "matched-mean")) return "mean exit-direction error vs MATCHED reference [deg]";
    return "mean exit-direction error vs FULL reference [deg]";
}

/* Label of a point: the width when sizes differ, then the method and its
 * own keys (scene and size lead the canonical spec): the method by name, as
 * a marker alone is hard to tell apart among six. */
static void point_label(const bench_config *c, int several_sizes, char *label, size_t n)
{
    const char *params = strchr(c->spec, ':');
    int k;
    for (k = 0; params && k < 2; k++) params = strchr(params + 1, ':');
    if (several_sizes) snprintf(label, n, "%d %s%s", c->width, c->method->name, params ? params : "");
    else snprintf(label, n, "%s%s", c->method->name, params ? params : "");
}

int bench_write_plot(const char *path, const bench_config *cs, int n, const bench_options *o,
                     const bench_run_info *run)
{
    bench_plot_point *pts = (bench_plot_point *)calloc((size_t)(n > 0 ? n : 1), sizeof *pts);
    char (*labels)[64] = (char (*)[64])calloc((size_t)(n > 0 ? n : 1), 64);
    char groups[BENCH_MAX_SCENES * 8][300];
    const char *scene_names[BENCH_MAX_SCENES], *method_names[MAX_MARKERS];
    const snell_method_info *methods[MAX_MARKERS];
    char subtitle[512];
    int i, k, ngroups = 0, nscenes = 0, nmethods, count = 0, ok, several_sizes = 0;
    bench_plot_desc d;
    if (!pts || !labels) {
        free(pts);
        free(labels);
        return 0;
    }
    nmethods = plot_methods(cs, n, methods); /* the legend: only the methods run */
    for (k = 0; k < nmethods; k++) method_names[k] = methods[k]->name;
    for (i = 1; i < n; i++)
        if (cs[i].width != cs[0].width || cs[i].height != cs[0].height) several_sizes = 1;
    for (i = 0; i < n; i++) {
        const bench_config *c = &cs[i];
        char g[300];
        if (!c->ok) continue;
        for (k = 0; k < nscenes; k++)
            if (!strcmp(scene_names[k], c->scene)) break;
        if (k == nscenes && nscenes < BENCH_MAX_SCENES) scene_names[nscenes++] = c->scene;
        pts[count].color = k;
        snprintf(g, sizeof g, "%s %dx%d", c->scene, c->width, c->height);
        for (k = 0; k < ngroups; k++)
            if (!strcmp(groups[k], g)) break;
        if (k == ngroups && ngroups < (int)(sizeof groups / sizeof *groups)) strcpy(groups[ngroups++], g);
        pts[count].group = k;
        pts[count].marker = plot_marker(c, methods, nmethods);
        pts[count].x = c->t_median;
        pts[count].y = plot_value(c, o->plot_y);
        point_label(c, several_sizes, labels[count], sizeof labels[count]);
        pts[count].label = labels[count];
        count++;
    }
    snprintf(subtitle, sizeof subtitle, "%s; median of %d frames after %d warm-up, glFinish%s; %s; load %s",
             run->renderer, o->frames, o->warmup, run->timer ? " (GL timer query in JSON)" : "",
             run->date, run->load_before);
    memset(&d, 0, sizeof d);
    d.title = "snell-bench: frame time vs error";
    d.subtitle = subtitle;
    d.x_label = several_sizes ? "median frame time [ms]  (labels: image width, method parameters)"
                              : "median frame time [ms]";
    d.y_label = y_label(o->plot_y);
    d.points = pts;
    d.count = count;
    d.color_names = scene_names;
    d.color_count = nscenes;
    d.marker_names = method_names;
    d.marker_count = nmethods;
    ok = bench_plot_write(path, &d) == SNELL_OK;
    free(pts);
    free(labels);
    return ok;
}

/* ----------------------------------------------------------------- table */
void bench_print_table(const bench_config *cs, int n)
{
    char why[64];
    int i, xscene = 0, lp = cli_llvmpipe_threads(run_renderer, why, sizeof why);
    for (i = 0; i < n; i++) xscene |= cs[i].ok && cs[i].vs_scene >= 0;
    if (lp >= 0) printf("llvmpipe threads: %d (%s)\n", lp, why);
    printf("%-58s %9s %7s%s %8s %7s %9s %9s %7s %7s %6s %6s\n", "configuration", "ms/frame", "xsingle",
           xscene ? "  xscene" : "", "dB/FULL", "SSIM", "deg/MATCH", "deg/FULL", ">1deg", ">5deg", "NaN", "pareto");
    for (i = 0; i < n; i++) {
        const bench_config *c = &cs[i];
        if (!c->ok) {
            printf("%-58s FAILED: %s\n", c->spec, c->error);
            continue;
        }
        printf("%-58s %9.2f %7.3f", c->spec, c->t_median, c->vs_single);
        if (xscene) printf(" %7.3f", c->vs_scene);
        printf(" %8.2f %7.4f ", c->img_glass[1].psnr_db, c->ssim_glass[1]);
        /* Per-pixel angles only where they mean something (bench.h). */
        if (c->angles_meaningful)
            printf("%9.3g %9.3g %6.1f%% %6.1f%%", c->dir[0].mean_deg, c->dir[1].mean_deg,
                   100.0 * c->dir[1].frac_above_1deg, 100.0 * c->dir[1].frac_above_5deg);
        else
            printf("%9s %9s %7s %7s", "-", "-", "-", "-");
        printf(" %6ld %6s%s\n", c->nan_inf, c->pareto ? "*" : "",
               c->warnings ? "  (method warns: preconditions fail)" : "");
    }
    printf("dB/FULL, SSIM: colour over the glass pixels against the FULL reference (area-averaged with --aa); "
           "deg: mean exit-direction error, '-' on meshes where per-pixel angles are chaotic%s\n",
           xscene ? "; xscene: time over the same spec's on --baseline-scene, frames side by side" : "");
    bench_print_frame_table(cs, n);
    bench_print_scene_table(cs, n);
}

void bench_print_frame_table(const bench_config *cs, int n)
{
    int i, few = 0;
    printf("\nframe times [ms]\n%-58s %7s %9s %9s %9s %9s %9s\n", "configuration", "frames", "p50", "p95", "p99",
           "1% low", "worst");
    for (i = 0; i < n; i++) {
        const bench_config *c = &cs[i];
        if (!c->ok) continue;
        printf("%-58s %7d %9.2f %9.2f %9.2f %9.2f %9.2f\n", c->spec, c->frames, c->t_median, c->t_p95, c->t_p99,
               c->t_low1, c->t_max);
        few |= c->frames < 100;
    }
    printf("1%% low: the mean of the slowest 1%% of frames%s\n",
           few ? "; with fewer than 100 frames it is the worst frame, and p99 too (--frames)" : "");
}

void bench_print_scene_table(const bench_config *cs, int n)
{
    static const char *const rows[3] = {"method", "alone", "ref-alone"};
    int i, k, m, any = 0;
    for (i = 0; i < n; i++) any |= cs[i].ok && cs[i].whole_measured;
    if (!any) return;
    printf("\nwhole scene against FULL with glass seen through glass (isolate_glass = 0), per class of the "
           "reference's first hit: dB SSIM\n");
    printf("%-58s %-9s %15s %15s %15s %15s %15s %9s %9s %7s\n", "configuration", "image", "glass",
           "glass>glass", "opaque", "background", "all", "deg mean", "deg p99", ">5deg");
    for (i = 0; i < n; i++) {
        const bench_config *c = &cs[i];
        if (!c->ok || !c->whole_measured) continue;
        for (m = 0; m < 3; m++) {
            const bench_scene_error *e = &c->whole[m];
            printf("%-58s %-9s", m ? "" : c->spec, rows[m]);
            for (k = 0; k < BENCH_CLASS_COUNT; k++) {
                if (e->cls[k].img.pixels) printf(" %8.2f %6.4f", e->cls[k].img.psnr_db, e->cls[k].ssim);
                else printf(" %15s", "-"); /* no pixel of this class */
            }
            if (c->angles_meaningful)
                printf(" %9.3g %9.3g %6.1f%%\n", e->dir.mean_deg, e->dir.p99_deg, 100.0 * e->dir.frac_above_5deg);
            else
                printf(" %9s %9s %7s\n", "-", "-", "-");
        }
        printf("%-58s %-9s", "", "pixels");
        for (k = 0; k < BENCH_CLASS_COUNT; k++) printf(" %15ld", c->whole[0].cls[k].img.pixels);
        printf("   passes %d (scene-layer peels %d, %d used)\n", c->passes, c->layer_passes, c->layers_used);
    }
    printf("method: the configuration's frame; alone: each glass object drawn alone by the method over the environment "
           "and the opaque objects, composed back to front; ref-alone: the FULL reference with isolate_glass = 1 "
           "(each object alone, exact); glass>glass: the glass pixels where other glass shows (the whole-scene and "
           "isolated references differ); inf dB: identical pixels\n");
}

/* -------------------------------------------------------------- markdown */
/* A scene's markdown table for a page a person reads (bench/BENCHMARKS.md
 * is made of these by bench/regen.sh): per scene and size the configurations
 * with what drew them (with methods=auto: AUTO's pick), the median frame,
 * its ratio to single's, and the colour of the glass pixels against FULL
 * (the dB/FULL and SSIM of the summary table), then the plot. Only what this
 * run measured: the figures a page shows are the ones its command makes. */
static void md_drawn_by(FILE *f, const bench_config *c)
{
    int k, j, first = 1;
    for (k = 0; k < c->glass_objects && k < SNELL_MAX_GLASS; k++) {
        for (j = 0; j < k && c->methods_used[j] != c->methods_used[k]; j++) {}
        if (j < k) continue; /* named once */
        fprintf(f, "%s%s", first ? "" : ", ", snell_method_str(c->methods_used[k]));
        first = 0;
    }
    if (first) fprintf(f, "-");
}

/* The spec less scene= and size= (the section names them). */
static const char *md_config(const bench_config *c, char *buf, size_t n)
{
    const char *p = c->spec;
    size_t len = 0;
    buf[0] = '\0';
    while (p && *p) {
        const char *e = strchr(p, ':');
        size_t k = e ? (size_t)(e - p) : strlen(p);
        if (!(k > 6 && !strncmp(p, "scene=", 6)) && !(k > 5 && !strncmp(p, "size=", 5)) && len + k + 2 < n) {
            if (len) buf[len++] = ':';
            memcpy(buf + len, p, k);
            buf[len += k] = '\0';
        }
        p = e ? e + 1 : NULL;
    }
    return buf;
}

int bench_write_markdown(const char *path, const bench_config *cs, int n, const bench_options *o,
                         const bench_run_info *run, const char *command)
{
    FILE *f = fopen(path, "w");
    char why[64], cfg[512];
    int i, j, lp = cli_llvmpipe_threads(run_renderer, why, sizeof why);
    if (!f) return 0;
    for (i = 0; i < n; i++) {
        int first_of_group = 1, auto_rows = 0;
        for (j = 0; j < i; j++)
            if (bench_same_group(&cs[j], &cs[i])) first_of_group = 0;
        if (!first_of_group) continue;
        fprintf(f, "### %s, %dx%d\n\n", cs[i].scene, cs[i].width, cs[i].height);
        fprintf(f, "%s; %s; load average %s before, %s after; median of %d frames after %d warm-up, each "
                   "ended by glFinish (CPU clock%s); colour %s",
                run->renderer, run->date, run->load_before, run->load_after, o->frames, o->warmup,
                run->timer ? ", GL timer query in the JSON" : "", o->aa > 1 ? "area-averaged, " : "at pixel centres");
        if (o->aa > 1) fprintf(f, "%dx%d rays a pixel (the timed frames without ssaa)", o->aa, o->aa);
        if (lp >= 0) fprintf(f, "; llvmpipe threads %d", lp);
        fprintf(f, ".\n\n| configuration | drawn by | ms/frame | × single | glass PSNR vs FULL [dB] | "
                   "glass SSIM vs FULL | Pareto |\n|---|---|---:|---:|---:|---:|:---:|\n");
        for (j = i; j < n; j++) {
            const bench_config *c = &cs[j];
            if (!bench_same_group(c, &cs[i])) continue;
            auto_rows += c->object_method_count > 0;
            fprintf(f, "| `%s` | ", md_config(c, cfg, sizeof cfg));
            if (!c->ok) {
                fprintf(f, "failed: %s | | | | | |\n", c->error);
                continue;
            }
            md_drawn_by(f, c);
            fprintf(f, " | %.2f | ", c->t_median);
            if (c->vs_single >= 0) fprintf(f, "%.2f", c->vs_single);
            else fprintf(f, "-");
            fprintf(f, " | %.2f | %.4f | %s |%s\n", c->img_glass[1].psnr_db, c->ssim_glass[1], c->pareto ? "*" : "",
                    c->warnings ? " (the method warns: its preconditions fail)" : "");
        }
        fprintf(f, "\n");
        if (auto_rows)
            fprintf(f, "`methods=auto`: AUTO chooses per object (the spec's own method is only the MATCHED "
                       "reference's model); \"drawn by\" is its pick.\n\n");
        fprintf(f, "![frame time vs glass error, %s %dx%d](%s.png)\n\n", cs[i].scene, cs[i].width, cs[i].height,
                o->out_prefix);
    }
    fprintf(f, "Pareto: not beaten in both median time and the plot's error (%s) by another configuration of the "
               "scene and size. Command:\n\n```\n%s\n```\n\n",
            y_label(o->plot_y), command ? command : "snell-bench");
    return fclose(f) == 0;
}
