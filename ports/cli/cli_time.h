/* cli_time.h — the ports' one clock: monotonic wall time in milliseconds and
 * the median of a sample (snell-render --frames, snell-bench 3D and --2d). */
#ifndef SNELL_CLI_TIME_H
#define SNELL_CLI_TIME_H

/* CLOCK_MONOTONIC in ms (arbitrary origin; differences only). */
double cli_now_ms(void);
/* Median of v[0..n), n >= 1; sorts v in place (so v[0], v[n-1] are min, max). */
double cli_median(double *v, int n);

#endif
