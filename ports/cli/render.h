/* SPDX-License-Identifier: MIT */
/* render.h — the parts of snell-render: its command line read as a scene
 * (render_args.c), the reference light paths of --trace-pixel (trace_pixel.c),
 * glass panels (render_panels.c) and the 2D lightmap mode --2d (render2d.c);
 * main is snell_render.c. */
#ifndef SNELL_RENDER_H
#define SNELL_RENDER_H

#include "snell/snell.h"
#include "cli_panels.h"

#include <stdio.h>

/* One object of the command line's scene. */
typedef struct render_object {
    const char *mesh;              /* shape name ("sphere", "shape:sphere") or OBJ/glTF file */
    float place[4];                /* --place x, y, z, uniform scale */
    int placed;                    /* 0: identity model (NULL), as without --place */
    snell_glass_material material; /* glass objects */
    float color[3];                /* opaque objects; zero = the library's grey */
    /* method parameters given for it (--NAME V, --param [METHOD.]NAME=V), so that one its
     * --method does not have is refused rather than ignored; method: AUTO when not qualified */
    struct {
        char name[32];
        snell_method method;
    } given[16];
    int given_count;
} render_object;

typedef struct render_options {
    /* Glass options given before the first --mesh: every --mesh starts from a
     * copy of it; with no --mesh it is the scene's one glass object (a sphere). */
    render_object base;
    render_object glass[SNELL_MAX_GLASS];
    int glass_count;               /* --mesh given; 0 = the default scene (base) */
    render_object opaque[SNELL_MAX_OPAQUE];
    int opaque_count;              /* --opaque MESH given */
    int orbit;                     /* --opaque N: N cubes orbiting the origin, moving each frame */
    const char *env;               /* NULL or "procedural": the built-in sky */
    const char *out;
    int width, height;
    float az_deg, el_deg, dist, fov_deg;
    snell_backend backend;
    int frames;                    /* >1: time the frames and print the median */
    snell_shading shading;         /* --shading */
    snell_env_lookup env_lookup;   /* --env-lookup */
    int ssaa, msaa;                /* --ssaa S, --msaa N (snell_renderer_desc) */
    int refine;                    /* --refine N: the mean of N still frames (snell_renderer_desc.refine) */
    int scene_layers;              /* --scene-layers N|auto|off (snell_frame_desc.scene_layers) */
    int normalize;                 /* fit each mesh into the unit sphere before placing it */
    int stats;                     /* --stats: frame and per-object statistics on stdout */
    int verbose;                   /* -v: the same on stderr, and the library's INFO messages */
    int trace_xy[32];              /* --trace-pixel X,Y (repeatable, up to 16) */
    int trace_count;
    const char *scene_file;        /* --scene: a glTF scene instead of --mesh/--opaque */
    int camera_given;              /* --camera was given (it overrides a scene file's camera) */
    int fov_given;                 /* --fov was given (it overrides a scene file camera's) */
    float view[16], projection[16]; /* --view, --projection: the camera as matrices (both or neither) */
    int view_given, projection_given;
    snell_light light;             /* --light, --photons (snell_frame_desc.light) */
    snell_receiver receiver;       /* --floor, --floor-map (snell_frame_desc.receiver) */
    int size_given;                /* --size was given (else --under's image gives it) */
    const char *panels_file;       /* --panels FILE: glass panels over the frame (cli_panels.h) */
    cli_panels panels;             /* its panels, read while parsing */
    const char *under_file;        /* --under IMAGE: the picture beneath the panels, as a GL texture */
    int reference;                 /* --reference: snell_ref_panels' image beside -o */
} render_options;

/* Parses argv into *o. 1: render; 0: bad usage (message printed: exit 2);
 * -1: --help was printed (exit 0). */
int render_parse_args(int argc, char **argv, render_options *o);
void render_usage(FILE *f);

/* --panels, --under, --reference (render_panels.c). */
typedef struct render_panels {
    snell_panels_under under;      /* TEXTURE with draw = 1 when --under is given */
    unsigned texture;              /* the picture's GL texture, 0 without --under */
    uint8_t *image;                /* the picture, bottom row first (snell_image_read's) */
    uint8_t *plain;                /* --reference without --under: the frame drawn without panels */
    int width, height;
} render_panels;
/* --under: reads the picture, makes its texture (the frame takes its size
 * unless --size was given). 0 on failure (message printed). */
int render_panels_open(snell_ctx *ctx, render_options *o, render_panels *p);
/* The panels into the frame; with --under a frame of panels only. */
void render_panels_frame(const render_options *o, const render_panels *p, snell_frame_desc *fd);
/* --reference without --under: draws fd without its panels and keeps that
 * frame, what lies beneath them. 0 on failure. */
int render_panels_plain(snell_ctx *ctx, snell_renderer *r, const render_options *o, render_panels *p,
                        const snell_frame_desc *fd);
/* --reference: snell_ref_panels over what lay beneath, into -o's name with
 * _reference.png. 0 on failure. */
int render_panels_reference(const render_options *o, const render_panels *p);
void render_panels_close(render_panels *p);

/* snell-render --water ... (render_water.c). */
int snell_render_water_main(int argc, char **argv);

/* snell-render --2d ... (render2d.c). */
int snell_render2d_main(int argc, char **argv);

/* --trace-pixel (trace_pixel.c): renders the frame from a second camera,
 * traces each pixel through the whole scene with the reference tracer and
 * writes <out_png without .png>_trace.png and _trace.json. 0 on success,
 * 1 on a runtime failure, 2 for a pixel outside the image. */
int snell_render_trace_pixels(snell_ctx *ctx, const snell_frame_desc *frame, int width, int height, const int *xy,
                              int count, const char *out_png);

#endif
