/* SPDX-License-Identifier: MIT */
/* bench.h — snell-bench's shared types, and the one job of each of its files:
 *   snell_bench.c    main: options -> configurations -> context -> timing -> errors -> outputs
 *   bench_options.c  the command line and --help (methods and parameters from the registry)
 *   bench_spec.c     spec expansion: method:key=v1,v2:... -> configurations (cartesian product)
 *   bench_scene.c    scenes (one mesh, or named multi-object scenes) as frames and reference scenes
 *   bench_timing.c   interleaved timing of the configurations of one scene and size
 *   bench_measure.c  one configuration's error against the reference (exit directions, colour)
 *   bench_classes.c  errors per object class (glass, opaque, background, all) of the reference's first hit
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
/* Timed frames by default: 100, so that the 99th percentile and the 1% low are not the worst frame. */
#define BENCH_DEFAULT_FRAMES 100

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
    int floor_aa;                  /* --floor-aa S: FULL's own noise floor, its S x S rays against --aa's (0: none) */
    const char *plot_y;
    int quiet;
    /* --baseline-scene S: the configurations of one size take turns frame by
     * frame whatever their scene, and vs_scene is each one's time over that of
     * the same spec on scene S (NULL: groups of one scene, no vs_scene) */
    const char *baseline_scene;
    const char *markdown;          /* --markdown FILE: bench_write_markdown (NULL: none) */
    float view[16], projection[16]; /* --view / --projection: the host's camera for every scene */
    int view_given, projection_given;
} bench_options;

/* 1: run; 0: bad usage (message printed, exit 2); -1: --help/--list printed (exit 0). */
int bench_parse_options(int argc, char **argv, bench_options *o);
/* 1 if v is an integer in lo..hi (else "snell-bench: KEY=V: want ..." printed). */
int bench_parse_int(const char *key, const char *v, int lo, int hi, int *out);

/* ------------------------------------------------------- object classes */
/* What a pixel's view ray meets first in the reference (snell_ref_output.object:
 * glass i -> i, opaque j -> -2 - j, nothing -> -1), and the whole image;
 * GLASS_THROUGH is the part of GLASS where other glass shows: the pixels
 * whose whole-scene reference colour differs from the isolated reference's
 * (each object alone). GLASS, OPAQUE and BACKGROUND partition ALL. */
typedef enum bench_class {
    BENCH_CLASS_GLASS = 0,
    BENCH_CLASS_GLASS_THROUGH,
    BENCH_CLASS_OPAQUE,
    BENCH_CLASS_BACKGROUND,
    BENCH_CLASS_ALL,
    BENCH_CLASS_COUNT
} bench_class;

/* "glass", "glass_through_glass", "opaque", "background", "all" */
extern const char *const bench_class_names[BENCH_CLASS_COUNT];

/* The colour error of one class of pixels. */
typedef struct bench_class_error {
    snell_image_error img;         /* RMSE/PSNR over the class's pixels (img.pixels: how many) */
    double ssim;                   /* snell_metrics_ssim over the same pixels */
} bench_class_error;

/* The class of a first-hit object id (GLASS, OPAQUE or BACKGROUND). */
bench_class bench_class_of(int16_t object);
/* The error of test against ref (RGBA8, w x h) over each class of the ids
 * object[] (the reference's); through: nonzero where glass shows other glass
 * (NULL: nowhere); mask: w * h bytes of scratch. SNELL_OK or the metrics'
 * status. */
snell_status bench_class_errors(const uint8_t *test, const uint8_t *ref, const int16_t *object,
                                const uint8_t *through, int w, int h, uint8_t *mask,
                                bench_class_error out[BENCH_CLASS_COUNT]);

/* The results of one image (the method's, or each glass object drawn alone)
 * against the FULL reference of the whole scene. */
typedef struct bench_scene_error {
    bench_class_error cls[BENCH_CLASS_COUNT];
    snell_dir_error dir;           /* exit directions over glass pixels (masks as in bench_measure) */
} bench_scene_error;

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
    unsigned ref_terms;            /* MATCHED reference's snell_ref_terms (the method's model) */
    snell_shading shading;         /* shading= (the renderer's; default auto) */
    int ssaa, msaa;                /* ssaa=, msaa=: the renderer's antialiasing, timed and measured (0: none;
                                    * then the measured colour frame uses --aa) */
    int refine;                    /* refine=N: the measured colour frame is the mean of N still frames
                                    * (snell_renderer_desc.refine), without ssaa; 0: none */
    float lod;                     /* lod=: glass meshes simplified to this triangle ratio; 1 = the
                                    * original (the default); references always use the original */
    int scene_layers;              /* layers=: snell_frame_desc.scene_layers (0 auto, -1 off, 2..8) */
    float spin;                    /* spin=: degrees of camera azimuth added every timed frame (0: a still
                                    * scene, whose frames may reuse what the last one drew); errors are
                                    * measured on the unmoved frame */
    snell_method object_methods[SNELL_MAX_GLASS]; /* methods=: glass object i's method (AUTO allowed), */
    int object_method_count;       /* for i < object_method_count; the others take glass.method */

    /* results */
    int ok;
    char error[256];
    int frames;
    double t_median, t_p95, t_min, t_max; /* ms per frame, CPU wall clock, each frame ended by glFinish */
    double t_p99, t_low1;          /* 99th percentile; "1% low": the mean of the slowest 1% of frames (at
                                    * least one), the stutter a median hides */
    double *frame_ms;              /* every timed frame in the order drawn (frames of them; malloc'd, freed by
                                    * bench_configs_free), written to the JSON so that runs can be re-summarised */
    double gpu_median;             /* ms, GL_EXT_disjoint_timer_query; < 0 if not measured */
    double vs_single;              /* median over rounds of time / time of the single-surface
                                    * configuration of the same scene and size; < 0 if none */
    int pareto;                    /* on the time vs error (plot's y) front of its scene and size */
    int glass_objects, opaque_objects;
    int warnings;                  /* glass objects whose stats warn (method's preconditions fail) */
    snell_method methods_used[SNELL_MAX_GLASS]; /* what drew each glass object (the measured frame's stats) */
    int passes;                    /* GL draw passes of the frame after warm-up (snell_frame_stats.passes), */
    int layer_passes, layers_used; /* of which scene-layer peels, and the layers that held something */
    int layers_drawn;              /* the measured frame drew the scene layers (glass seen through glass):
                                    * then the MATCHED and FULL comparisons are with isolate_glass = 0 */
    const char *encoding;          /* exit-direction storage: "float" or "packed-rgba8" */
    long nan_inf;                  /* non-finite exit-direction pixels (float target only) */
    long counters[SNELL_MAX_METHOD_COUNTERS]; /* the method's counters (snell_method_info.counters) in the
                                    * exit-direction frame, summed over the glass objects it drew; -1: not counted */
    snell_dir_error dir[2];        /* [0] vs MATCHED, [1] vs FULL */
    snell_image_error img[2];      /* whole image */
    snell_image_error img_glass[2];/* pixels that are glass in either mask */
    snell_image_error floor_glass; /* --floor-aa: the FULL reference at that many rays against the one at --aa's,
                                    * over the glass pixels (floor_glass.pixels 0: not measured) */
    double ssim_glass[2];          /* snell_metrics_ssim over the same pixels */
    int angles_meaningful;         /* exit-direction angles compared per pixel mean something: a smooth
                                    * built-in shape or scene of them (on a bumpy scan such as the bunny
                                    * they are chaotic: an exit moved by a hair gives a large angle) */
    int ref_cached[2];
    /* Against the FULL reference of the whole scene (isolate_glass = 0: glass
     * seen through glass), per object class: [0] the method's frame, [1] each
     * glass object drawn alone by the method over the environment and the
     * opaque objects (one frame per object, composed back to front by the
     * renderer's draw order; with one glass object, the frame itself), [2] the
     * reference itself with isolate_glass = 1 (each object alone, exact). */
    int whole_measured;            /* 0: not measured (failed, or a tool that times only) */
    bench_scene_error whole[3];
    double vs_scene;               /* --baseline-scene: median over rounds of time / time of the same spec on
                                    * that scene; < 0 if none */
} bench_config;

/* The tool whose name a spec's error messages begin with ("snell-bench";
 * snell-kiosk sets its own). */
extern const char *bench_prog;
/* "method:k=v:k=v1,v2" plus the options' scene and size lists -> configurations
 * appended to out[*n..]. 0 on a bad spec (message printed). */
int bench_expand_spec(const char *spec, const bench_options *o, bench_config *out, int *n);
/* A method's registry entry, or the bench's own entry for auto (no parameters). */
const snell_method_info *bench_method_info(snell_method m);
/* The keys every method takes, for --help. */
void bench_spec_help(FILE *f);
/* The same keys by index (0 .. bench_spec_key_count() - 1; NULL past the end), so that a
 * test can walk every key the parser accepts (tests/test_bench_keys.c). */
int bench_spec_key_count(void);
const char *bench_spec_key_name(int i);
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
    snell_scene_file *file;        /* a glTF scene file (owns its meshes, models, materials), else NULL */
    int has_camera;                /* the file's camera, used when the spec gives no camera= */
    snell_camera camera;
} bench_scene;

/* The scene called name, built on first use: a named multi-object scene
 * (bench_scene_help), a glTF scene file (.gltf/.glb: snell_scene_load_gltf,
 * its objects, materials and camera), "bunny" (glmark2's model) or a shape or
 * mesh file (normalised to the unit sphere, at the origin). */
snell_status bench_scene_get(snell_ctx *ctx, const char *name, const bench_scene **out);
void bench_scene_release_all(void);
/* 1 if name is a glTF scene file (ends in .gltf or .glb). */
int bench_scene_is_file(const char *name);
/* --view/--projection (snell_render's SNELL_CAMERA_MATRICES): the camera of every
 * configuration's frame and reference, over camera= and a scene file's. */
void bench_scene_set_matrices(const float view[16], const float projection[16]);
/* The camera (azimuth, elevation in degrees, distance) of a scene when the spec has none. */
void bench_scene_camera(const char *name, float cam[3]);
void bench_scene_help(FILE *f);
/* Configuration c on scene s: fills glass[] (the scene's objects with c's
 * material; a scene file's objects keep their own material and take c's
 * method and method parameters) and *fd (a scene file's camera unless c
 * has camera=). */
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
/* c's time summary (median, p95, p99, 1% low, min, max) from the n frame
 * times ms[] in the order drawn, which c keeps (c->frame_ms). 0 out of memory. */
int bench_frame_times(bench_config *c, const double *ms, int n);
/* Frees what the configurations own (their frame times). */
void bench_configs_free(bench_config *cs, int n);

/* ---------------------------------------------------------------- output */
typedef struct bench_run_info {
    const char *renderer, *date, *load_before, *load_after;
    const struct cli_system *system; /* the build, GL driver, kernel and board (cli_system.h); NULL: not written */
    const char *vsync;             /* how frames met the display: "off: ..." offscreen, "on: ..." page-flipped */
    int timer;                     /* GL timer queries available */
    /* Another tool writing this JSON (snell-kiosk) names itself and says how
     * it timed; NULL: "snell-bench" and snell-bench's timing. */
    const char *tool, *timing;
    int no_errors;                 /* errors not measured: the error fields are null and the JSON does
                                    * not describe a reference or mask policy */
    const snell_device_limits *limits; /* the device profile in force and its limits (snell_ctx_limits);
                                        * NULL: not written */
} bench_run_info;

void bench_mark_pareto(bench_config *cs, int n, const bench_options *o);
int bench_write_json(const char *path, const bench_config *cs, int n, const bench_options *o,
                     const bench_run_info *run);
int bench_write_csv(const char *path, const bench_config *cs, int n);
int bench_write_plot(const char *path, const bench_config *cs, int n, const bench_options *o,
                     const bench_run_info *run);
/* --markdown FILE: per scene and size a markdown table (configuration, what
 * drew it, ms/frame, x single, glass PSNR/SSIM vs FULL, Pareto) and the
 * plot's image link (PREFIX.png as -o gave it), then the command. */
int bench_write_markdown(const char *path, const bench_config *cs, int n, const bench_options *o,
                         const bench_run_info *run, const char *command);
/* The summary table, then bench_print_scene_table. */
void bench_print_table(const bench_config *cs, int n);
/* Frame times per configuration: frames, p50, p95, p99, 1% low, worst. */
void bench_print_frame_table(const bench_config *cs, int n);
/* Per object class against the whole-scene reference (configurations with whole_measured). */
void bench_print_scene_table(const bench_config *cs, int n);

/* snell-bench --compare A.json B.json (bench_compare.c): two runs side by side. */
int snell_bench_compare_main(int argc, char **argv);
/* snell-bench --2d (bench2d.c). */
int snell_bench2d_main(int argc, char **argv);
/* snell-bench --env-lookup (bench_env.c). */
int snell_bench_env_main(int argc, char **argv);
/* snell-bench --water (bench_water.c): the water scene's simulation and rendering timed apart. */
int snell_bench_water_main(int argc, char **argv);
/* snell-bench --budget: AUTO by frame budget against its rung table's fixed configurations (bench_budget.c). */
int snell_bench_budget_main(int argc, char **argv);

/* Images of --images that could not be written (bench_measure.c). */
extern int bench_image_failures;

#endif
