/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, sysconf */
/* cli_time.c — monotonic wall clock, medians and the load average shared by the ports. */
#include "cli_time.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

double cli_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

void cli_loadavg(char *buf, size_t n)
{
    FILE *f = fopen("/proc/loadavg", "r");
    float a = 0, b = 0, c = 0;
    if (f && fscanf(f, "%f %f %f", &a, &b, &c) == 3) snprintf(buf, n, "%.2f %.2f %.2f", a, b, c);
    else snprintf(buf, n, "unknown");
    if (f) fclose(f);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double cli_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double cli_percentile(double *v, int n, double p)
{
    int i = (int)ceil(p * n) - 1;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return v[i < 0 ? 0 : i >= n ? n - 1 : i];
}

int cli_llvmpipe_threads(const char *gl_renderer, char *why, size_t size)
{
    const char *env = getenv("LP_NUM_THREADS");
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    if (!gl_renderer || !strstr(gl_renderer, "llvmpipe")) {
        snprintf(why, size, "not llvmpipe");
        return -1;
    }
    if (env && *env) {
        snprintf(why, size, "LP_NUM_THREADS=%s", env);
        return atoi(env);
    }
    snprintf(why, size, "LP_NUM_THREADS unset: one per CPU");
    return ncpu > 0 ? (int)ncpu : 1;
}
