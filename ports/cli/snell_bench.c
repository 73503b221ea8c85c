/* SPDX-License-Identifier: MIT */
/* snell-bench — time vs error of the refraction methods (issue 3).
 *
 * Runs scenes x methods x parameters; for each configuration it times the
 * median of N frames after warm-up (each frame ended by glFinish, plus
 * GL_EXT_disjoint_timer_query when the context has it; the configurations of
 * one scene and size take turns frame by frame, so a shared machine's drift
 * hits all of them alike and ratios to single-surface are per round), renders
 * the exit directions (SNELL_OUTPUT_EXIT_DIRECTION) and compares them and the
 * colour image with the CPU reference of the same scene (snell_ref, MATCHED
 * with the method's max_interfaces and FULL, isolate_glass = 1), cached on
 * disk. Writes PREFIX.json, PREFIX.csv and PREFIX.png (time vs error, Pareto
 * front). Configurations are written glmark2 style: -b method:key=value:key=v1,v2
 * (a comma list sweeps); methods and their keys are the library's registry.
 * With no arguments: a quick default sweep. main reads as the pipeline; each
 * stage has its own file (bench.h). */
#define _POSIX_C_SOURCE 200809L /* localtime */
#include "bench.h"
#include "bench_timer.h"
#include "cli_input.h"
#include "cli_scene.h"
#include "cli_system.h"
#include "cli_time.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Default sweep: every method of the registry that renders here, with the
 * parameters bench_default_sweep names. 0 on a bad spec. */
static int default_sweep(snell_ctx *ctx, const snell_env *env, const bench_options *o, bench_config *cs, int *n)
{
    int i;
    for (i = 0; i < snell_method_count(); i++) {
        const snell_method_info *m = snell_method_info_at(i);
        const char *params = bench_default_sweep(m);
        char spec[512];
        if (!bench_method_works(ctx, env, m)) continue;
        snprintf(spec, sizeof spec, "%s%s%s", m->name, *params ? ":" : "", params);
        if (!bench_expand_spec(spec, o, cs, n)) return 0;
    }
    return 1;
}

/* Errors of every configuration, with a progress line each. Returns the failures. */
static int measure_all(snell_ctx *ctx, const snell_env *env, const bench_options *o, bench_config *cs, int n,
                       double t_start)
{
    int i, failed = 0;
    for (i = 0; i < n; i++) {
        bench_config *c = &cs[i];
        if (!o->quiet) fprintf(stderr, "[%d/%d] %s\n", i + 1, n, c->spec);
        bench_measure(ctx, env, o->env ? o->env : "procedural", o, c);
        if (!c->ok) {
            failed++;
            fprintf(stderr, "[%d/%d] %s FAILED: %s\n", i + 1, n, c->spec, c->error);
        } else if (!o->quiet) {
            /* The table's figures, labelled as there: colour over the glass
             * pixels (the whole frame beside it, named), exit-direction
             * angles only where they mean something (bench_print_table). */
            char timer[64] = "", angles[160];
            if (c->gpu_median >= 0) snprintf(timer, sizeof timer, " (GL timer query %.2f ms)", c->gpu_median);
            if (c->angles_meaningful)
                snprintf(angles, sizeof angles, "exit direction vs MATCHED(%d) mean %.3g deg, vs FULL mean %.3g deg, "
                         ">1deg %.1f%%, >5deg %.1f%%", c->ref_interfaces, c->dir[0].mean_deg, c->dir[1].mean_deg,
                         100.0 * c->dir[1].frac_above_1deg, 100.0 * c->dir[1].frac_above_5deg);
            else
                snprintf(angles, sizeof angles, "exit direction - (per-pixel angles are chaotic on this mesh)");
            fprintf(stderr,
                    "[%d/%d] %.2f ms/frame (p95 %.2f, worst %.2f)%s; %s; glass PSNR vs FULL %.2f dB (whole frame %.2f dB); NaN/Inf %ld; "
                    "%.0f s elapsed\n",
                    i + 1, n, c->t_median, c->t_p95, c->t_max, timer, angles, c->img_glass[1].psnr_db, c->img[1].psnr_db, c->nan_inf,
                    (cli_now_ms() - t_start) / 1000.0);
            if (c->floor_glass.pixels)
                fprintf(stderr, "[%d/%d] FULL's noise floor: FULL at %dx%d rays against %dx%d, glass PSNR %.2f dB\n",
                        i + 1, n, o->floor_aa, o->floor_aa, o->aa, o->aa, c->floor_glass.psnr_db);
        }
    }
    return failed;
}

/* The command line, for the markdown page that shows what it measured:
 * arguments with characters a shell reads quoted in single quotes. */
static void command_line(int argc, char **argv, char *out, size_t n)
{
    size_t len = 0;
    int i;
    out[0] = '\0';
    for (i = 0; i < argc && len < n; i++) {
        const char *a = i ? argv[i] : "snell-bench";
        int quote = !*a || strpbrk(a, " \t\"'$`\\*?[]{}()<>|&;~#!") != NULL;
        len += (size_t)snprintf(out + len, n - len, "%s%s%s%s", i ? " " : "", quote ? "'" : "", a, quote ? "'" : "");
    }
}

/* One message for an output that was not written, with the system's reason. 0. */
static int write_failed(const char *path)
{
    fprintf(stderr, "snell-bench: cannot write '%s': %s\n", path, errno ? strerror(errno) : "write failed");
    return 0;
}

/* PREFIX.json, .csv, .png (and --markdown). 1 if all were written. */
static int write_outputs(const bench_config *cs, int n, const bench_options *o, const bench_run_info *run,
                         const char *command)
{
    char path[1200];
    int ok = 1;
    snprintf(path, sizeof path, "%s.json", o->out_prefix);
    errno = 0;
    if (!bench_write_json(path, cs, n, o, run)) ok = write_failed(path);
    snprintf(path, sizeof path, "%s.csv", o->out_prefix);
    errno = 0;
    if (!bench_write_csv(path, cs, n)) ok = write_failed(path);
    snprintf(path, sizeof path, "%s.png", o->out_prefix);
    errno = 0;
    if (!bench_write_plot(path, cs, n, o, run)) ok = write_failed(path);
    errno = 0;
    if (o->markdown && !bench_write_markdown(o->markdown, cs, n, o, run, command)) ok = write_failed(o->markdown);
    return ok;
}

int main(int argc, char **argv)
{
    static bench_options o;
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_env *env = NULL;
    bench_config *cs = NULL;
    bench_run_info run;
    cli_system sys;
    snell_device_limits limits;
    int i, n = 0, rc = 0, timer;
    char load_before[64], load_after[64], date[64];
    static char command[8192];
    double t_start = cli_now_ms();
    time_t now = time(NULL);

    if (!cli_args_clean("snell-bench", argc, argv)) return 2;
    for (i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--compare")) return snell_bench_compare_main(argc, argv);
        else if (!strcmp(argv[i], "--2d")) return snell_bench2d_main(argc, argv);
        else if (!strcmp(argv[i], "--env-lookup")) return snell_bench_env_main(argc, argv);
        else if (!strcmp(argv[i], "--water")) return snell_bench_water_main(argc, argv);
        else if (!strcmp(argv[i], "--budget")) return snell_bench_budget_main(argc, argv);
    if ((i = bench_parse_options(argc, argv, &o)) <= 0) return i < 0 ? 0 : 2;
    cs = (bench_config *)calloc(BENCH_MAX_CONFIGS, sizeof *cs);
    if (!cs) return fprintf(stderr, "snell-bench: out of memory\n"), 1;
    for (i = 0; i < o.spec_count; i++)
        if (!bench_expand_spec(o.specs[i], &o, cs, &n)) {
            free(cs);
            return 2;
        }

    memset(&cd, 0, sizeof cd);
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-bench: cannot create a GL context: %s\n", snell_last_error(NULL));
        free(cs);
        return 1;
    }
    if (cli_env_open(ctx, o.env, &env) != SNELL_OK) {
        fprintf(stderr, "snell-bench: environment: %s\n", snell_last_error(ctx));
        rc = 1;
        goto done;
    }
    if (o.spec_count == 0 && !default_sweep(ctx, env, &o, cs, &n)) {
        rc = 2;
        goto done;
    }
    memset(&run, 0, sizeof run);
    cli_system_read(&sys);
    run.system = &sys;
    run.renderer = snell_ctx_gl_renderer(ctx);
    snell_ctx_limits(ctx, &limits);
    run.limits = &limits;
    timer = bench_timer_init(ctx);
    run.timer = timer > 0;
    cli_loadavg(load_before, sizeof load_before);
    strftime(date, sizeof date, "%Y-%m-%d %H:%M", localtime(&now));
    run.date = date;
    run.load_before = load_before;
    run.load_after = load_after;
    if (!o.quiet) {
        fprintf(stderr, "snell-bench: %d configuration(s) on %s; load %s\n", n, run.renderer, load_before);
        fprintf(stderr, "snell-bench: GL_EXT_disjoint_timer_query %s\n",
                timer > 0   ? "present: GPU times reported too"
                : timer < 0 ? "present, but not used on a software rasteriser, where it is no GPU time (the "
                              "rasteriser is CPU threads): times are CPU wall clock of render + glFinish"
                            : "not available: times are CPU wall clock of render + glFinish only");
    }
    bench_time_all(ctx, env, &o, cs, n);
    if (measure_all(ctx, env, &o, cs, n, t_start) > 0 || bench_image_failures) rc = 1;
    cli_loadavg(load_after, sizeof load_after);
    bench_mark_pareto(cs, n, &o);
    command_line(argc, argv, command, sizeof command);
    i = write_outputs(cs, n, &o, &run, command);
    if (!i) rc = 1;
    bench_print_table(cs, n);
    if (i) printf("wrote %s.json, %s.csv, %s.png (%.1f s)\n", o.out_prefix, o.out_prefix, o.out_prefix,
           (cli_now_ms() - t_start) / 1000.0);
done:
    bench_configs_free(cs, n);
    bench_scene_release_all();
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    free(cs);
    return rc;
}
