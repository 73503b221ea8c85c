/* SPDX-License-Identifier: MIT */
/* test_util.h — tiny test harness: CHECK counts failures and keeps going,
 * test_finish() prints "N passed, N failed" and returns the exit code,
 * SKIP exits 77 (ctest's skip code) with the reason. */
#ifndef SNELL_TEST_UTIL_H
#define SNELL_TEST_UTIL_H

#include "snell/snell.h"
#include "snell/snell_ref.h"
#include "snell/snell_metrics.h"
#include <EGL/egl.h>
#include <stdio.h>

extern int test_passed, test_failed;

#define CHECK(cond, ...)                                                  \
    do {                                                                  \
        if (cond) {                                                       \
            test_passed++;                                                \
        } else {                                                          \
            test_failed++;                                                \
            fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                 \
            fprintf(stderr, "\n");                                        \
        }                                                                 \
    } while (0)

#define CHECK_OK(call)                                                    \
    do {                                                                  \
        snell_status st_ = (call);                                        \
        CHECK(st_ == SNELL_OK, "%s: %s", snell_status_str(st_), snell_last_error(NULL)); \
    } while (0)

/* The same for a call on a context: the message is the context's. */
#define CHECK_OK_CTX(ctx, call)                                                         \
    do {                                                                                \
        snell_status st_ = (call);                                                      \
        CHECK(st_ == SNELL_OK, "%s: %s", snell_status_str(st_), snell_last_error(ctx)); \
    } while (0)

#define SKIP(...)                                                         \
    do {                                                                  \
        printf("SKIP: ");                                                 \
        printf(__VA_ARGS__);                                              \
        printf("\n");                                                     \
        return 77;                                                        \
    } while (0)

int test_finish(void);
/* Path of a file under tests/data (static buffer). */
const char *test_data(const char *name);
/* Path for an output file in the test's build directory (static buffer). */
const char *test_out(const char *name);
/* Writes n bytes to path: 1 if every byte was written and the file closed. */
int test_write_file(const char *path, const void *data, size_t n);
/* The whole file in a fresh malloc'd buffer, its size in *n; NULL (and *n 0) on failure. */
unsigned char *test_read_file(const char *path, size_t *n);
/* Reference parameters that match frame fd rendered at w x h: MATCHED mode
 * with the given interface cap, the frame's environment and camera (the
 * materials come from the reference's scene: test_ref_create). */
void test_ref_params(const snell_frame_desc *fd, int w, int h, int max_interfaces, snell_ref_params *p);
/* A reference tracer over frame fd's scene (its glass objects with their
 * materials, and its opaque objects). Materials are copied: after changing
 * fd's, call snell_ref_set_material (or create the reference again). */
snell_status test_ref_create(snell_ctx *ctx, const snell_frame_desc *fd, snell_ref **out);
/* fd = a frame of one glass object g (mesh, model NULL, zero material) in env. */
void test_frame_one(snell_frame_desc *fd, snell_glass *g, const snell_mesh *mesh, const snell_env *env);
/* The cube [-1,1]^3 of quads x quads squares a face (1..16), its surface's
 * grid points shared between faces, counter-clockwise seen from outside, with
 * the smooth normals snell_mesh_create computes: its edges are creases that
 * the normals round off, as a scanned mesh's sharp features. NULL on failure. */
snell_mesh *test_smooth_cube(int quads);
/* snell_ref_render with these outputs (rgb required; exit_dir, hit optional). */
snell_status test_ref_render(const snell_ref *ref, const snell_ref_params *p, float *rgb, float *exit_dir,
                             uint8_t *hit);
/* The renderer shading the tests run with: SNELL_TEST_SHADING=forward|screen
 * (ctest registers the render tests once per path with SHADINGS), else AUTO. */
snell_shading test_shading(void);
/* Factor for wall-clock bounds: SNELL_TEST_TIME_SCALE (set for tests run
 * through an emulator, tests/CMakeLists.txt), else 1. */
double test_time_scale(void);
/* Makes a GLES 3 context the way a host app would (surfaceless Mesa display,
 * no surface) and makes it current: 1 on success. For EXTERNAL-backend tests. */
int test_host_context(EGLDisplay *dpy, EGLContext *ctx);
/* A headless context (default backend) or NULL, message printed. */
snell_ctx *test_ctx(void);
/* Writes every program's final sources built in ctx into dir (see test_util.c). */
void test_glsl_dump(snell_ctx *ctx, const char *dir);
/* The procedural sky environment (snell_env_desc zero but face_size) on ctx,
 * or NULL with the failure counted (CHECK_OK). */
snell_env *test_sky(snell_ctx *ctx, int face_size);
/* A renderer of width x height, the rest of its description zero, or NULL
 * with the failure counted. */
snell_renderer *test_renderer(snell_ctx *ctx, int width, int height);
/* The reference of frame fd at w x h in mode with the interface cap, each
 * glass object alone (isolate_glass): its exit directions and hit mask. 1 if
 * traced; failures counted (CHECK_OK). */
int test_ref_dirs(snell_ctx *ctx, const snell_frame_desc *fd, int w, int h, snell_ref_mode mode, int interfaces,
                  float *dirs, uint8_t *hit);
/* Exit directions test against ref over the pixels mask covers (w x h,
 * snell_metrics_dir_error), the call's failure and any non-finite direction
 * counted as failures. */
snell_dir_error test_dir_error(const float *test, const float *ref, const uint8_t *mask, int w, int h);
/* The mesh, moved by t (NULL: not moved), in Blender's frame (x, y, z) ->
 * (x, -z, y) as tests/scripts/cycles_*.py read it: vertex and triangle
 * counts, positions, normals, triangles (uint32, float32, little endian as
 * written). flip reverses the winding: Cycles tells entering from leaving by
 * the geometric normal, counter-clockwise outward; the reference by the
 * medium it tracks. 1 on success. */
int test_write_blender_mesh(const snell_mesh *m, const double t[3], const char *path, int flip);

/* The angle in radians between directions a and b (any lengths): atan2 of
 * |a x b| and a.b stays accurate for tiny angles, where acos of a float dot
 * product bottoms out near 3e-4 rad. */
double test_dir_angle(const float a[3], const float b[3]);
/* Receivers' light maps (the caustics tests): n texels of rgb irradiance, a
 * with stride_a floats a texel, b with 3. The PSNR (dB) of the two shown as
 * albedo * irradiance clamped to 0..1; and an n x n map written as that PNG
 * (test_out(name)), row 0 of the image the far edge (z largest). */
double test_light_map_psnr(const float *a, int stride_a, const float *b, int n, float albedo);
/* The flux of a light map's green channel: n texels of stride floats, each texel x texel (world area). */
double test_light_map_flux(const float *v, int stride, int n, double texel);
/* The flux (green, texel side texel) of the reference's light map ref_rgb (3
 * floats a texel) above what ctx's light maps hold: 0 with float maps; an
 * RGB10_A2 map (no float colour target) saturates at SNELL__LIGHT_RANGE
 * times the light, so a focus loses up to this much of the light through glass. */
double test_light_map_excess(snell_ctx *ctx, const float *ref_rgb, int n, double texel);
void test_write_light_map(const char *name, const float *v, int stride, int n, float albedo);
/* The PSNR (dB) of two RGBA8 images of n pixels over the pixels where mask
 * is set (their rgb); their count in *count. 999 where they agree. */
double test_psnr_mask(const uint8_t *a, const uint8_t *b, const uint8_t *mask, int n, int *count);

#endif
