/* SPDX-License-Identifier: MIT */
/* bench_plot.h — the time-vs-error scatter plot of snell-bench as a PNG, and
 * the Pareto front it rings (bench_plot.c). */
#ifndef SNELL_BENCH_PLOT_H
#define SNELL_BENCH_PLOT_H

#include "snell/snell.h"

typedef struct bench_plot_point {
    double x, y;                 /* time (ms), error; y <= 0 is drawn at the floor */
    int group;                   /* Pareto front is computed per group (scene + size) */
    int color;                   /* index into the palette (scene) */
    int marker;                  /* 0 circle, 1 square, 2 triangle, 3 diamond, 4 cross (method) */
    const char *label;           /* short text beside the point, may be NULL */
} bench_plot_point;

typedef struct bench_plot_desc {
    const char *title, *subtitle, *x_label, *y_label;
    const bench_plot_point *points;
    int count;
    const char *const *color_names;   /* legend: color_count names */
    int color_count;
    const char *const *marker_names;  /* legend: marker_count names */
    int marker_count;
} bench_plot_desc;

/* Marks pareto[i] = 1 for the points not dominated within their group
 * (smaller x and y are better). */
void bench_pareto(const bench_plot_point *p, int n, int *pareto);
snell_status bench_plot_write(const char *path, const bench_plot_desc *d);

#endif
