/* bench_common.h — shared between the snell-bench files (snell_bench.c: options,
 * method table, run loop, JSON/CSV; bench_ref.c: cached reference images;
 * bench_plot.c: time-vs-error PNG; bench_timer.c: GL timer queries). */
#ifndef SNELL_BENCH_COMMON_H
#define SNELL_BENCH_COMMON_H

#include "snell/snell.h"
#include "snell/snell_metrics.h"
#include "snell/snell_ref.h"

/* One measured configuration: a method with its parameters on one scene,
 * one image size, one glass. */
typedef struct bench_config {
    const struct bench_method *method;
    char spec[512];              /* canonical spec, glmark2 style: method:key=value:... */
    char scene[256];             /* shape name or mesh path */
    int width, height;
    snell_glass_desc glass;
    float cam[3];                /* azimuth, elevation (degrees), distance */
    int ref_interfaces;          /* MATCHED reference cap (the method's max_interfaces) */
    snell_ref_absorption ref_absorb;

    /* results */
    int ok;
    char error[256];
    int frames;
    double t_median, t_min, t_max; /* ms per frame, CPU wall clock, each frame ended by glFinish */
    double gpu_median;             /* ms, GL_EXT_disjoint_timer_query; < 0 if not measured */
    double vs_single;              /* median over rounds of time / time of the single-surface
                                    * configuration of the same scene and size; < 0 if none */
    int pareto;                    /* on the time vs error (plot's y) front of its scene and size */
    const char *encoding;          /* exit-direction storage: "float" or "packed-rgba8" */
    long nan_inf;                  /* non-finite exit-direction pixels (float target only) */
    snell_dir_error dir[2];        /* [0] vs MATCHED, [1] vs FULL */
    snell_image_error img[2];      /* whole image */
    snell_image_error img_glass[2];/* pixels that are glass in either mask */
    int ref_cached[2];
} bench_config;

/* Reference results of one scene/camera/size/glass/mode, width*height pixels. */
typedef struct bench_ref_image {
    int width, height;
    float *rgb, *exit_dir;
    uint8_t *hit, *rgba;
} bench_ref_image;

/* Renders the reference or loads it from cache_dir (NULL: no cache). key
 * must describe everything the result depends on except the mesh content,
 * whose hash is added here. *cached tells which happened. */
snell_status bench_ref_get(const snell_mesh *mesh, const snell_ref_params *p,
                           const char *cache_dir, const char *key, bench_ref_image *out, int *cached);
void bench_ref_free(bench_ref_image *img);

/* Monotonic wall clock in ms, and the median of v[0..n) (sorts v) (bench_timer.c). */
double bench_now_ms(void);
double bench_median(double *v, int n);
/* snell-bench --2d (bench2d.c). */
int snell_bench2d_main(int argc, char **argv);

/* Time-vs-error plot. */
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

/* GL_EXT_disjoint_timer_query: available? begin/end one query per frame. */
int bench_timer_init(snell_ctx *ctx);
void bench_timer_begin(void);
void bench_timer_end(void);
/* After glFinish: the frame's GPU time in ms, or -1 (disjoint or unavailable). */
double bench_timer_read(void);

#endif
