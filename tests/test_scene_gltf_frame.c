/* SPDX-License-Identifier: MIT */
/* test_scene_gltf_frame — camera-less glTF scenes framed from their bounds
 * (snell_scene_file_frame, issue 28 item 3), on tests/data/scenes
 * (make_scenes.py): framed_large (an opaque sphere of radius 60 at
 * (250, -120, -400)) and framed_small (a tinted glass sphere of radius 0.01
 * at (-3, 7, -12)), each rendered landscape (the vertical field of view
 * binds) and portrait (the horizontal one does).
 *
 * 1. Neither file has a camera (snell_scene_file_camera 0); the framed
 *    camera targets the sphere's centre (1e-4 of its radius) and keeps the
 *    given azimuth, elevation and fov_y.
 * 2. Rendered with and without the object under the framed camera, the
 *    pixels that differ (any channel by more than 6/255) cover 30-90% of the
 *    frame, and none lies on the frame's border (the sphere fits). The
 *    default camera (target at the origin, distance 3.5) sees 0% of either.
 * 3. Refusals: NULL scene or camera, aspect 0 or NaN, a negative fov_y. */
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static const char *scene_path(const char *name)
{
    static char buf[512];
    snprintf(buf, sizeof buf, "%s/scenes/%s", test_data(""), name);
    return buf;
}

/* The fraction of the frame that the scene's objects change, and whether
 * any changed pixel lies on the border. */
static double coverage(snell_ctx *ctx, snell_env *env, const snell_scene_file *s, const snell_camera *cam, int w,
                       int h, int *on_border, const char *png)
{
    static uint8_t with[320 * 320 * 4], without[320 * 320 * 4];
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    long p, n = 0;
    *on_border = 0;
    memset(&rd, 0, sizeof rd);
    rd.width = w;
    rd.height = h;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (!r) return -1.0;
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.camera = *cam;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_rgba(r, without));
    fd.glass = snell_scene_file_glass(s, &fd.glass_count);
    fd.opaque = snell_scene_file_opaque(s, &fd.opaque_count);
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_rgba(r, with));
    if (png) snell_write_png(test_out(png), w, h, with);
    for (p = 0; p < (long)w * h; p++) {
        int k, d = 0;
        for (k = 0; k < 3; k++) d = d > abs(with[4 * p + k] - without[4 * p + k]) ? d : abs(with[4 * p + k] - without[4 * p + k]);
        if (d > 6) {
            long x = p % w, y = p / w;
            n++;
            if (x == 0 || y == 0 || x == w - 1 || y == h - 1) *on_border = 1;
        }
    }
    snell_renderer_destroy(r);
    return (double)n / ((double)w * h);
}

static void check_file(snell_ctx *ctx, snell_env *env, const char *file, const float centre[3], float radius)
{
    static const int sizes[2][2] = {{160, 120}, {120, 160}};
    snell_scene_file *s = NULL;
    snell_camera cam;
    int i, k;
    CHECK_OK_CTX(ctx, snell_scene_load_gltf(ctx, scene_path(file), 0, &s));
    if (!s) return;
    CHECK(snell_scene_file_camera(s, NULL) == 0, "%s has a camera", file);
    for (i = 0; i < 2; i++) {
        int w = sizes[i][0], h = sizes[i][1], border;
        char png[96];
        double f;
        memset(&cam, 0, sizeof cam);
        cam.azimuth = (float)(30.0 * PI / 180.0);
        cam.elevation = (float)(20.0 * PI / 180.0);
        CHECK_OK(snell_scene_file_frame(s, (float)w / (float)h, &cam));
        for (k = 0; k < 3; k++)
            CHECK(fabsf(cam.target[k] - centre[k]) <= 1e-4f * radius, "%s: target[%d] %g, expected %g", file, k,
                  cam.target[k], centre[k]);
        CHECK(cam.fov_y == 0.0f && fabsf(cam.azimuth - (float)(30.0 * PI / 180.0)) < 1e-7f &&
                  fabsf(cam.elevation - (float)(20.0 * PI / 180.0)) < 1e-7f,
              "%s: the direction or field of view changed", file);
        snprintf(png, sizeof png, "scene_gltf_frame_%.*s_%dx%d.png", (int)(strlen(file) - 5), file, w, h);
        f = coverage(ctx, env, s, &cam, w, h, &border, png);
        printf("%s at %dx%d: framed at distance %g (radius %g): the object covers %.1f%% of the frame%s\n", file, w, h,
               cam.distance, radius, 100.0 * f, border ? ", touching its border" : "");
        CHECK(f >= 0.30 && f <= 0.90, "%s at %dx%d: coverage %.3f outside 0.30..0.90", file, w, h, f);
        CHECK(!border, "%s at %dx%d: the object reaches the frame's border", file, w, h);
    }
    /* the default camera that camera-less files got before: nothing of the object in view */
    {
        int border;
        double f;
        memset(&cam, 0, sizeof cam);
        f = coverage(ctx, env, s, &cam, 160, 120, &border, NULL);
        CHECK(f < 0.01, "%s: the default camera sees %.3f of it", file, f);
    }
    snell_scene_file_destroy(s);
}

int main(void)
{
    static const float large_c[3] = {250.0f, -120.0f, -400.0f}, small_c[3] = {-3.0f, 7.0f, -12.0f};
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL;
    snell_camera cam;
    snell_scene_file *s = NULL;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 64);
    if (env) {
        check_file(ctx, env, "framed_large.gltf", large_c, 60.0f);
        check_file(ctx, env, "framed_small.gltf", small_c, 0.01f);
    }
    memset(&cam, 0, sizeof cam);
    CHECK_OK_CTX(ctx, snell_scene_load_gltf(ctx, scene_path("framed_large.gltf"), 0, &s));
    CHECK(snell_scene_file_frame(NULL, 1.0f, &cam) == SNELL_E_INVALID_ARG, "NULL scene");
    CHECK(snell_scene_file_frame(s, 1.0f, NULL) == SNELL_E_INVALID_ARG, "NULL camera");
    CHECK(snell_scene_file_frame(s, 0.0f, &cam) == SNELL_E_INVALID_ARG &&
              strstr(snell_last_error(NULL), "aspect"),
          "aspect 0: %s", snell_last_error(NULL));
    CHECK(snell_scene_file_frame(s, (float)NAN, &cam) == SNELL_E_INVALID_ARG, "aspect NaN");
    cam.fov_y = -0.5f;
    CHECK(snell_scene_file_frame(s, 1.0f, &cam) == SNELL_E_INVALID_ARG && strstr(snell_last_error(NULL), "fov_y"),
          "fov_y -0.5: %s", snell_last_error(NULL));
    snell_scene_file_destroy(s);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
