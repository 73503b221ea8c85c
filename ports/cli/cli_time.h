/* SPDX-License-Identifier: MIT */
/* cli_time.h — the ports' one clock: monotonic wall time in milliseconds,
 * the median and percentiles of a sample (snell-render --frames, snell-bench 3D and --2d,
 * snell-kiosk), the load average and how many threads a software renderer
 * times with. */
#ifndef SNELL_CLI_TIME_H
#define SNELL_CLI_TIME_H

#include <stddef.h>

/* The 1, 5 and 15 minute load averages ("0.52 0.61 0.70"), "unknown" if
 * /proc/loadavg cannot be read: what the benchmarks record beside a time. */
void cli_loadavg(char *buf, size_t n);
/* CLOCK_MONOTONIC in ms (arbitrary origin; differences only). */
double cli_now_ms(void);
/* Median of v[0..n), n >= 1; sorts v in place (so v[0], v[n-1] are min, max). */
double cli_median(double *v, int n);
/* The p-quantile of v[0..n) (0 < p <= 1, n >= 1): the smallest value with at
 * least p * n values at or below it (p = 1: the maximum); sorts v in place. */
double cli_percentile(double *v, int n, double p);
/* llvmpipe's rasteriser threads: Mesa reads LP_NUM_THREADS when the context is
 * created; unset, it uses one per CPU (capped by Mesa); 0 rasterises on the
 * calling thread. -1 (and "not llvmpipe") for other renderers (gl_renderer:
 * GL_RENDERER, may be NULL). On this 2-core machine 1 -> 2 threads made the
 * bunny frame 1.56x (single) and 1.62x (cubemap) faster: a kiosk without a GPU
 * should leave it unset or set it to its core count. why: where it comes from. */
int cli_llvmpipe_threads(const char *gl_renderer, char *why, size_t size);

#endif
