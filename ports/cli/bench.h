/* bench.h — snell-bench's shared types, and the one job of each of its files:
 *   snell_bench.c    main: options -> configurations -> context -> timing -> errors -> outputs
 *   bench_options.c  the command line and --help (methods and parameters from the registry)
 *   bench_spec.c     spec expansion: method:key=v1,v2:... -> configurations (cartesian product)
 *   bench_scene.c    scenes (one mesh, or named multi-object scenes) as frames and reference scenes
 *   bench_timing.c   interleaved timing of the configurations of one scene and size
 *   bench_measure.c  one configuration's error against the reference (exit directions, colour)
 *   bench_output.c   JSON, CSV, the Pareto front, the plot's points and the summary table
 *   bench_ref.c      reference images (snell_ref_render) cached on disk      (bench_ref.h)
 *   bench_plot.c     the time-vs-error PNG                                   (bench_plot.h)
 *   bench_timer.c    GL_EXT_disjoint_timer_query                             (bench_timer.h)
 *   bench2d.c        snell-bench --2d, the 2D lightmap benchmarks
 *   bench_env.c      snell-bench --env-lookup, the cube against the dual-paraboloid environment look-up
 * Exit status 0 on success, 1 if a configuration or an output failed, 2 on bad usage. */
#ifndef SNELL_BENCH_H
#define SNELL_BENCH_H

#include "snell/snell.h"
#include "snell/snell_metrics.h"
#include "snell/snell_ref.h"

#include <stdio.h>

#define BENCH_MAX_CONFIGS 4096
#define BENCH_MAX_SPECS 256
#define BENCH_MAX_SCENES 32

/* --------------------------------------------------------------- options */
typedef struct bench_options {
    const char *specs[BENCH_MAX_SPECS];
    int spec_count;
    char scenes[1024], sizes[256]; /* for specs without scene= / size= */
    int frames, warmup;
    const char *out_prefix;
    const char *cache_dir;         /* NULL: no reference cache */
    const char *env;               /* NULL: procedural */
    const char *images_dir;
    int full_interfaces;
    int threads;
    int aa;                        /* --aa S: errors on S x S area-averaged images (1 = pixel centres) */
    const char *plot_y;
    int quiet;
} bench_options;

/* 1: run; 0: bad usage (message printed, exit 2); -1: --help/--list printed (exit 0). */
int bench_parse_options(int argc, char **argv, bench_options *o);
/* 1 if v is an integer in lo..hi (else "snell-bench: KEY=V: want ..." printed). */
int bench_parse_int(const char *key, const char *v, int lo, int hi, int *out);

/* --------------------------------------------------------- configuration */
/* One measured configuration: a method with its parameters on one scene at
 * one image size; every glass object of the scene gets the same material. */
typedef struct bench_config {
    const snell_method_info *method; /* the registry's entry */
    char spec[512];                /* canonical spec, glmark2 style: method:scene=..:size=..:key=value:... */
    char scene[256];               /* mesh (shape name or path) or a multi-object scene name */
    int width, height;
    snell_glass_material glass;    /* method set; parameters by snell_glass_set_param */
    float cam[3];                  /* azimuth, elevation (degrees), distance */
    int cam_set;                   /* camera= given; else the scene's own camera */
    int ref_interfaces;            /* MATCHED reference cap (the method's own) */
    snell_ref_absorption ref_absorb;
    snell_shading shading;         /* shading= (the renderer's; default auto) */
    int ssaa, msaa;                /* ssaa=, msaa=: the renderer's antialiasing, timed and measured (0: none;
                                    * then the measured colour frame uses --aa) */
    float lod;                     /* lod=: glass meshes simplified to this triangle ratio; 1 = the
                                    * original (the default); references always use the original */

    /* results */
    int ok;
    char error[256];
    int frames;
    double t_median, t_min, t_max; /* ms per frame, CPU wall clock, each frame ended by glFinish */
    double gpu_median;             /* ms, GL_EXT_disjoint_timer_query; < 0 if not measured */
    double vs_single;              /* median over rounds of time / time of the single-surface
                                    * configuration of the same scene and size; < 0 if none */
    int pareto;                    /* on the time vs error (plot's y) front of its scene and size */
    int glass_objects, opaque_objects;
    int warnings;                  /* glass objects whose stats warn (method's preconditions fail) */
    const char *encoding;          /* exit-direction storage: "float" or "packed-rgba8" */
    long nan_inf;                  /* non-finite exit-direction pixels (float target only) */
    long exact_fallback_pixels;    /* EXACT: pixels past the node budget in the exit-direction frame, summed
                                    * over the glass objects; -1: not counted (other methods, RGBA8 target) */
    snell_dir_error dir[2];        /* [0] vs MATCHED, [1] vs FULL */
    snell_image_error img[2];      /* whole image */
    snell_image_error img_glass[2];/* pixels that are glass in either mask */
    double ssim_glass[2];          /* snell_metrics_ssim over the same pixels */
    int angles_meaningful;         /* exit-direction angles compared per pixel mean something: a smooth
                                    * built-in shape or scene of them (on a bumpy scan such as the bunny
                                    * they are chaotic: an exit moved by a hair gives a large angle) */
    int ref_cached[2];
} bench_config;

/* "method:k=v:k=v1,v2" plus the options' scene and size lists -> configurations
 * appended to out[*n..]. 0 on a bad spec (message printed). */
int bench_expand_spec(const char *spec, const bench_options *o, bench_config *out, int *n);
/* The keys every method takes, for --help. */
void bench_spec_help(FILE *f);
/* Parameters of the default sweep for a method ("" = its defaults). */
const char *bench_default_sweep(const snell_method_info *m);

/* ---------------------------------------------------------------- scenes */
/* A scene: glass objects (material left zero; each configuration brings its
 * own) and opaque objects, with the camera used when the spec gives none. */
typedef struct bench_scene {
    char name[256];
    int glass_count, opaque_count;
    snell_glass glass[SNELL_MAX_GLASS];
    snell_opaque opaque[SNELL_MAX_OPAQUE];
    float glass_models[SNELL_MAX_GLASS][16], opaque_models[SNELL_MAX_OPAQUE][16];
    int analytic;                  /* built from shapes (smooth, analytic), not a scanned mesh file */
} bench_scene;

/* The scene called name, built on first use: a named multi-object scene
 * (bench_scene_help), "bunny" (glmark2's model) or a shape or mesh file
 * (normalised to the unit sphere, at the origin). */
snell_status bench_scene_get(snell_ctx *ctx, const char *name, const bench_scene **out);
void bench_scene_release_all(void);
/* The camera (azimuth, elevation in degrees, distance) of a scene when the spec has none. */
void bench_scene_camera(const char *name, float cam[3]);
void bench_scene_help(FILE *f);
/* Configuration c on scene s: fills glass[] (the scene's objects with c's material) and *fd. */
void bench_scene_frame(const bench_config *c, const bench_scene *s, const snell_env *env, snell_glass *glass,
                       snell_frame_desc *fd);
/* Level of detail (c->lod < 1): replaces the meshes of glass[0..n) by their
 * simplified copies (snell_mesh_simplify at ratio c->lod, made once per mesh
 * and ratio, reported on stderr). The frame's reference keeps the originals. */
snell_status bench_scene_lod(snell_ctx *ctx, const bench_config *c, snell_glass *glass, int n);
/* Does the method render here? The default sweep skips those that do not. */
int bench_method_works(snell_ctx *ctx, const snell_env *env, const snell_method_info *m);

/* ------------------------------------------------------- timing, errors */
/* Times every configuration: those of one scene and size take turns frame by frame. */
void bench_time_all(snell_ctx *ctx, const snell_env *env, const bench_options *o, bench_config *cs, int n);
/* Renders c's colour and exit-direction images and compares them with the
 * MATCHED and FULL references (isolate_glass = 1). c->ok = 0 on failure. */
void bench_measure(snell_ctx *ctx, const snell_env *env, const char *env_name, const bench_options *o,
                   bench_config *c);
/* Records why c failed ("what: the library's last message"). */
void bench_fail(bench_config *c, const char *what, snell_ctx *ctx);
/* Same scene and image size: compared with each other, timed side by side. */
int bench_same_group(const bench_config *a, const bench_config *b);

/* ---------------------------------------------------------------- output */
typedef struct bench_run_info {
    const char *renderer, *date, *load_before, *load_after;
    int timer;                     /* GL timer queries available */
    /* Another tool writing this JSON (snell-kiosk) names itself and says how
     * it timed; NULL: "snell-bench" and snell-bench's timing. */
    const char *tool, *timing;
    int no_errors;                 /* errors not measured: the error fields are null and the JSON does
                                    * not describe a reference or mask policy */
} bench_run_info;

void bench_mark_pareto(bench_config *cs, int n, const bench_options *o);
int bench_write_json(const char *path, const bench_config *cs, int n, const bench_options *o,
                     const bench_run_info *run);
int bench_write_csv(const char *path, const bench_config *cs, int n);
int bench_write_plot(const char *path, const bench_config *cs, int n, const bench_options *o,
                     const bench_run_info *run);
void bench_print_table(const bench_config *cs, int n);

/* snell-bench --2d (bench2d.c). */
int snell_bench2d_main(int argc, char **argv);
/* snell-bench --env-lookup (bench_env.c). */
int snell_bench_env_main(int argc, char **argv);
/* snell-bench --water (bench_water.c): the water scene's simulation and rendering timed apart. */
int snell_bench_water_main(int argc, char **argv);

#endif
