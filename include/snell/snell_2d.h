/* SPDX-License-Identifier: MIT */
/* snell_2d.h — 2D global illumination lightmaps (Brückner 2019): polygon scenes
 * with a simple per-object BSDF, CPU light tracing through a perimeter-SAH BVH,
 * and rasterisation of the light paths into a lightmap (GLES lines or an exact
 * CPU rasteriser). Besides snell.h's conventions: 2D world units, x right, y
 * DOWN, angles from +x; the lightmap covers [view_min, view_max], top row first;
 * a pixel's value is the sum over paths of flux x length inside it, in pixel
 * widths (Brückner eq. 4.2), times exposure; N rays of a light of power P carry
 * P / N each. */
#ifndef SNELL_SNELL_2D_H
#define SNELL_SNELL_2D_H

#include "snell.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct snell_scene2d snell_scene2d;
typedef struct snell_lightmap2d snell_lightmap2d;

/* ------------------------------------------------------------- materials */
/* Brückner 6.2.1.2 BSDF parameters, plus an index of refraction. At a surface
 * hit from outside, the fraction `transmission` enters the object (Schlick
 * Fresnel reflection of that fraction when ior != 1), the rest goes to the BRDF,
 * which absorbs `absorption` and scatters the remainder uniformly in angle within
 * +-diffuse*pi/2 of the mirror direction (eq. 6.1; the lobe is turned to stay
 * above the surface). Inside, light is attenuated as exp(-opaqueness * length)
 * (Beer-Lambert instead of the thesis's linear eq. 6.3, see 7.1.3). */
typedef struct snell_material2d {
    float transmission;   /* t in [0,1] */
    float opaqueness;     /* o >= 0, per world unit */
    float diffuse;        /* d in [0,1]: 0 = mirror, 1 = scatter over the half circle */
    float absorption;     /* a in [0,1] */
    float ior;            /* index of refraction; 0 = 1 (transmitted light goes straight) */
    float color[3];       /* multiplies reflected and transmitted light; all zero = white */
    float smooth_angle;   /* vertices where the outline turns by less than this get one
                             averaged point normal (smooth); others keep both edge normals
                             (hard). 0 = all hard (Brückner 6.2.1.1) */
} snell_material2d;

/* --------------------------------------------------------------- objects */
typedef struct snell_object2d_desc {
    const float *points;          /* 2 * point_count (x, y), a closed polygon, either winding */
    int point_count;              /* >= 3 */
    snell_material2d material;
    float offset[2];              /* translation added to every point */
} snell_object2d_desc;

/* --------------------------------------------------------------- lights */
typedef enum snell_light2d_type {
    SNELL_LIGHT2D_POINT = 0,  /* from `position`, angles direction +- spread/2 (a spot if spread < 2 pi) */
    SNELL_LIGHT2D_BAR,        /* from random points on position..end, angles normal +- spread/2,
                                 normal = (e.y, -e.x)/|e| with e = end - position (a bar drawn
                                 left to right shines up on screen); see two_sided */
    SNELL_LIGHT2D_BEAM        /* from points on position..end, all along `direction` (sunlight) */
} snell_light2d_type;

typedef struct snell_light2d_desc {
    snell_light2d_type type;
    float position[2];
    float end[2];                 /* BAR, BEAM: the other end of the emitting segment */
    float direction;              /* POINT: cone centre; BEAM: beam direction (radians) */
    float spread;                 /* POINT: full cone angle, 0 = 2 pi; BAR: 0 = pi */
    int two_sided;                /* BAR: emit from both sides of the segment */
    float power;                  /* total flux; 0 = the light is off (skipped at no cost) */
    float color[3];               /* all zero = white */
    int rays;                     /* rays per frame; 0 = 25000 */
} snell_light2d_desc;

/* ---------------------------------------------------------------- scene */
/* A scene owns its objects, lights and BVH (rebuilt lazily when objects change).
 * ctx may be NULL (errors then go to snell_last_error(NULL)). */
snell_status snell_scene2d_create(snell_ctx *ctx, snell_scene2d **out);
void snell_scene2d_destroy(snell_scene2d *scene);

/* Adds an object (points copied); *id receives its index (may be NULL). */
snell_status snell_scene2d_add_object(snell_scene2d *scene, const snell_object2d_desc *desc, int *id);
/* Loads an object's polygon from a CSV file: one point "x,y" per line (Brückner
 * 6.2.1); an optional non-numeric header line and '#' comments are allowed. */
snell_status snell_scene2d_add_object_csv(snell_scene2d *scene, const char *path,
                                          const snell_material2d *material, const float offset[2],
                                          int *id);
/* Moves an object (thesis 6.2.1 translation); marks lights whose paths it can affect. */
snell_status snell_scene2d_set_object_offset(snell_scene2d *scene, int id, const float offset[2]);
snell_status snell_scene2d_add_light(snell_scene2d *scene, const snell_light2d_desc *desc, int *id);
/* Replaces a light's parameters; only this light is re-traced next frame. */
snell_status snell_scene2d_set_light(snell_scene2d *scene, int id, const snell_light2d_desc *desc);

/* Loads a text scene (format in tests/data/lm2d/README.md and lm2d_scene.c):
 *   # comment
 *   view X0 Y0 X1 Y1          size W H
 *   object FILE.csv [key value ...]       polygon X Y X Y X Y ... [; key value ...]
 *   light point|bar|beam [key value ...]
 * CSV paths are relative to the scene file and must stay inside its folder
 * (no absolute paths, no ../ or links out of it). "view"/"size" are returned through
 * view (float[4], may be NULL) and size (int[2], may be NULL); absent = zeros. */
snell_status snell_scene2d_load(snell_ctx *ctx, const char *path, snell_scene2d **out,
                                float view[4], int size[2]);

/* BVH leaf size (edges per leaf, 1..31; 0 = 4). Takes effect at the next frame's rebuild. */
snell_status snell_scene2d_set_bvh_leaf_size(snell_scene2d *scene, int leaf_size);

int snell_scene2d_object_count(const snell_scene2d *scene);
int snell_scene2d_light_count(const snell_scene2d *scene);
int snell_scene2d_edge_count(const snell_scene2d *scene);

/* ------------------------------------------------------------- lightmap */
typedef enum snell_blend2d {
    SNELL_BLEND2D_ADD = 0,    /* glBlendFunc(ONE, ONE): plain sum, eq. 4.2 */
    SNELL_BLEND2D_SCREEN      /* glBlendFunc(ONE, ONE_MINUS_SRC_COLOR) on exposed values:
                                 1 - prod(1 - x), softens bright regions (thesis 6.5.3, eq. 6.5) */
} snell_blend2d;

typedef enum snell_format2d {
    SNELL_FORMAT2D_AUTO = 0,  /* RGBA32F, else RGBA16F, else RGB10_A2 (by extension) */
    SNELL_FORMAT2D_RGBA32F,   /* needs GL_EXT_color_buffer_float and GL_EXT_float_blend */
    SNELL_FORMAT2D_RGBA16F,   /* needs GL_EXT_color_buffer_half_float or _float */
    SNELL_FORMAT2D_RGB10A2,   /* fallback (core ES 3.0): lines pre-exposed, stochastically
                                 rounded to 1/1023 so the sum is unbiased; saturates at 1;
                                 no progressive accumulation */
    SNELL_FORMAT2D_RGBA8      /* the same with 1/255 steps */
} snell_format2d;

/* Who turns the traced paths into the lightmap. GL lines (Brückner 6.5) are
 * cheap on a GPU; a software GL sets up each line serially, where the exact CPU
 * rasteriser on the lightmap's threads is faster and has no line-rule error
 * (bench/notes/code.md, "snell_2d.h"; bench/BENCHMARKS.md). Its image is the
 * same, bit for bit, for any thread count. */
typedef enum snell_raster2d {
    SNELL_RASTER2D_AUTO = 0,  /* CPU without a ctx, with cpu_only, or when GL_RENDERER contains
                                 "llvmpipe", "softpipe" or "swrast" (Mesa's software rasterisers);
                                 GL lines otherwise */
    SNELL_RASTER2D_GL,        /* GL lines; needs a ctx and cpu_only = 0 (else SNELL_E_INVALID_ARG) */
    SNELL_RASTER2D_CPU        /* the exact CPU rasteriser; with a ctx (and not cpu_only) every
                                 frame also uploads the result into the lightmap texture */
} snell_raster2d;

typedef struct snell_lightmap2d_desc {
    int width, height;            /* pixels; 0 = 512 x 512 */
    float view_min[2], view_max[2]; /* world rectangle shown; all zero = [0,width] x [0,height] */
    int max_bounces;              /* interactions per ray after emission; 0 = 8, negative = none */
    int threads;                  /* tracer (and CPU rasteriser) threads; 0 = online CPUs */
    uint64_t seed;                /* RNG seed; same seed and scene = same paths (any thread count) */
    int progressive;              /* nonzero: an unchanged scene traces one more pass per frame
                                     and accumulates; zero: it is traced once and reused */
    snell_blend2d blend;
    snell_format2d format;        /* GPU target; ignored without a ctx */
    float exposure;               /* multiplies the lightmap before display; 0 = 1 */
    int cpu_only;                 /* nonzero: no GL objects (also implied by ctx == NULL) */
    snell_raster2d raster;        /* rasteriser; AUTO picks by the rule above (stats say which, and why) */
} snell_lightmap2d_desc;

typedef struct snell_lightmap2d_stats {
    int traced;                   /* 0: nothing changed, the cached lightmap was reused */
    int lights_traced;            /* lights re-traced this frame */
    int lights_skipped;           /* lights off or unchanged */
    int passes;                   /* accumulated passes in the lightmap */
    uint64_t rays;                /* rays emitted this frame */
    uint64_t paths;               /* path segments rasterised this frame */
    double trace_ms;              /* wall time of the light tracing */
    double trace_cpu_ms;          /* CPU time the calling thread spent tracing (its share of
                                     the rays; all of them with threads = 1); robust to load */
    double raster_ms;             /* wall time of rasterising (GL: issuing the draws; no glFinish;
                                     CPU: all threads, including upload_ms) */
    double upload_ms;             /* CPU rasteriser with a GL texture: converting and uploading it */
    snell_format2d format;        /* accumulation format in use (of the texture, AUTO without GL) */
    snell_raster2d raster;        /* rasteriser in use: SNELL_RASTER2D_GL or SNELL_RASTER2D_CPU */
    int raster_threads;           /* threads the CPU rasteriser runs on (0 with GL lines) */
    char raster_reason[SNELL_REASON_SIZE]; /* why this rasteriser: the request or AUTO's rule */
} snell_lightmap2d_stats;

/* ctx may be NULL: CPU only (trace + exact rasteriser). */
snell_status snell_lightmap2d_create(snell_ctx *ctx, const snell_lightmap2d_desc *desc,
                                     snell_lightmap2d **out);
void snell_lightmap2d_destroy(snell_lightmap2d *lm);

/* Traces what changed in the scene (or one more pass, when progressive) and
 * rasterises into the GPU lightmap (or, without GL, the exact CPU lightmap).
 * GL state changed here is restored (framebuffer, viewport, blend, program,
 * VAO, array buffer, active texture binding). stats may be NULL. */
snell_status snell_lightmap2d_frame(snell_lightmap2d *lm, snell_scene2d *scene,
                                    snell_lightmap2d_stats *stats);

/* The lightmap as linear float RGB (3 * width * height, top row first), exposure
 * and pass normalisation applied. From the GPU target when there is one. */
snell_status snell_lightmap2d_read_rgb(snell_lightmap2d *lm, float *rgb);
/* The same clamped to [0,1] and stored as RGBA8 (alpha 255), top row first. */
snell_status snell_lightmap2d_read_rgba(snell_lightmap2d *lm, uint8_t *rgba);
/* The exact CPU rasterisation (eq. 4.2: each pixel weighted by the length of the
 * segment inside it) of the same paths and passes: the reference for the GPU lines. */
snell_status snell_lightmap2d_read_rgb_exact(snell_lightmap2d *lm, float *rgb);
/* Waits for the GPU to finish the lightmap (glFinish); for timing. */
void snell_lightmap2d_finish(snell_lightmap2d *lm);
/* The GL texture holding the accumulation (0 without GL), for drawing in a host app.
 * Float targets with ADD hold the raw sum: multiply by exposure / passes. SCREEN and
 * the fixed-point fallbacks hold display values (exposure already applied; with the
 * CPU rasteriser also divided by passes). With the CPU rasteriser the texture is
 * refreshed by every frame that traced. */
unsigned snell_lightmap2d_texture(const snell_lightmap2d *lm);

/* Energy bookkeeping of the last traced pass (flux summed over rgb). */
typedef struct snell_energy2d {
    double emitted, absorbed, escaped, capped, rr_killed, rr_gained;
} snell_energy2d;
void snell_lightmap2d_energy(const snell_lightmap2d *lm, snell_energy2d *out);

/* ------------------------------------------------- image -> polygon (A.5) */
/* Outline of the region alpha >= threshold of an RGBA8 image (top row first):
 * marching squares on the alpha channel, the longest closed contour kept, then
 * Ramer-Douglas-Peucker with tolerance epsilon (pixels; 0 = 0.5). Points are in
 * pixel units (x right, y down), written to *points (2 * *count floats,
 * allocated with the ctx allocator, free with snell_contour2d_free). */
snell_status snell_contour2d_from_alpha(snell_ctx *ctx, const uint8_t *rgba, int width, int height,
                                        int threshold, float epsilon, float **points, int *count);
void snell_contour2d_free(snell_ctx *ctx, float *points);
/* Writes points as CSV, one "x,y" per line (the scene's object format). */
snell_status snell_contour2d_write_csv(const char *path, const float *points, int count);

#ifdef __cplusplus
}
#endif
#endif
