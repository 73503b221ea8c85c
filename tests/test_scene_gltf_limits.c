/* SPDX-License-Identifier: MIT */
/* test_scene_gltf_limits — glTF scenes beyond the frame's object limits and
 * the objects' node names (issue 28 item 4), on tests/data/scenes
 * (make_scenes.py says what each holds; the expected values are read off it).
 *
 * 1. many_opaque: 100 opaque cubes (100 distinct primitives, three colours,
 *    materials "red", "green", "blue" taken in turn) and a glass sphere
 *    "lens": loads as 1 glass object and 3 opaque ones, one per colour, with
 *    the node transforms baked in (identity model, 34 / 33 / 33 cubes of 12
 *    triangles), named "34 nodes of 'red'" ..., the glass one "lens".
 *    snell_scene_file_frame's target is the centre of all objects' bounds
 *    (0.8, 0, 0): the grid spans x -2.4..2.4 and the lens reaches x = 4.
 * 2. Rendered with its camera: at the projected centre of each cube's front
 *    face the pixel is of its material's colour (its channel 40/255 above the
 *    others), and at the middle of each gap between four cubes it is the
 *    background of the same frame without objects (within 6/255).
 * 3. glass_33: refused with SNELL_E_LIMIT and a message naming 33 and 32.
 * 4. 65 opaque triangles in 65 colours (built in memory): more colours than
 *    SNELL_MAX_OPAQUE, refused with SNELL_E_LIMIT naming 65.
 * 5. Unmerged scenes keep one object per node: glass_row's unnamed nodes are
 *    "node 0".."node 3"; an index out of range has no name. */
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 192
#define H 192

static const char *scene_path(const char *name)
{
    static char buf[512];
    snprintf(buf, sizeof buf, "%s/scenes/%s", test_data(""), name);
    return buf;
}

/* World point -> pixel (top row first) under the camera; 0 if behind it. */
static int project(const snell_camera *cam, const float p[3], int *x, int *y)
{
    float eye[3], view[16], proj[16], v[4], c[4];
    int i, k;
    snell_camera_matrices(cam, (float)W / (float)H, eye, view, proj);
    for (i = 0; i < 4; i++) v[i] = view[i] * p[0] + view[4 + i] * p[1] + view[8 + i] * p[2] + view[12 + i];
    for (i = 0; i < 4; i++)
        for (c[i] = 0.0f, k = 0; k < 4; k++) c[i] += proj[4 * k + i] * v[k];
    if (!(c[3] > 0.0f)) return 0;
    *x = (int)floorf((c[0] / c[3] * 0.5f + 0.5f) * W);
    *y = (int)floorf((1.0f - (c[1] / c[3] * 0.5f + 0.5f)) * H);
    return *x >= 0 && *x < W && *y >= 0 && *y < H;
}

static void test_many_opaque(snell_ctx *ctx, snell_env *env)
{
    static const char *const names[3] = {"34 nodes of 'red'", "33 nodes of 'green'", "33 nodes of 'blue'"};
    static uint8_t px[W * H * 4], bg[W * H * 4];
    snell_scene_file *s = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_frame_stats st;
    snell_camera cam;
    const snell_glass *g;
    const snell_opaque *o;
    int ng = 0, no = 0, i, k, colour_ok = 0, gap_ok = 0, gaps = 0;
    CHECK_OK_CTX(ctx, snell_scene_load_gltf(ctx, scene_path("many_opaque.gltf"), 0, &s));
    if (!s) return;
    g = snell_scene_file_glass(s, &ng);
    o = snell_scene_file_opaque(s, &no);
    CHECK(ng == 1 && no == 3 && g && o, "many_opaque: %d glass, %d opaque objects (expected 1 and 3)", ng, no);
    if (ng != 1 || no != 3) goto out;
    CHECK(!strcmp(snell_scene_file_glass_name(s, 0), "lens"), "glass name '%s'", snell_scene_file_glass_name(s, 0));
    for (i = 0; i < 3; i++) {
        unsigned tris = snell_mesh_triangle_count(o[i].mesh);
        CHECK(!strcmp(snell_scene_file_opaque_name(s, i), names[i]), "opaque %d name '%s', expected '%s'", i,
              snell_scene_file_opaque_name(s, i), names[i]);
        CHECK(tris == (i == 0 ? 34u : 33u) * 12u, "opaque %d: %u triangles", i, tris);
        CHECK(fabsf(o[i].color[i] - 0.9f) < 1e-6f && fabsf(o[i].color[(i + 1) % 3] - 0.1f) < 1e-6f,
              "opaque %d colour (%g %g %g)", i, o[i].color[0], o[i].color[1], o[i].color[2]);
        for (k = 0; k < 16; k++)
            CHECK(!o[i].model || o[i].model[k] == (k % 5 == 0 ? 1.0f : 0.0f), "opaque %d model[%d] %g", i, k,
                  o[i].model[k]);
    }
    memset(&cam, 0, sizeof cam);
    CHECK_OK(snell_scene_file_frame(s, 1.0f, &cam));
    CHECK(fabsf(cam.target[0] - 0.8f) < 1e-4f && fabsf(cam.target[1]) < 1e-4f && fabsf(cam.target[2]) < 1e-4f,
          "framed target (%g %g %g), expected (0.8 0 0)", cam.target[0], cam.target[1], cam.target[2]);

    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    if (!r) goto out;
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    CHECK(snell_scene_file_camera(s, &fd.camera) == 1, "many_opaque has no camera");
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_rgba(r, bg));
    fd.glass = g;
    fd.glass_count = ng;
    fd.opaque = o;
    fd.opaque_count = no;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
    CHECK_OK(snell_renderer_read_rgba(r, px));
    snell_write_png(test_out("scene_gltf_many_opaque.png"), W, H, px);
    CHECK(st.opaque_drawn == 3, "opaque drawn %d", st.opaque_drawn);
    for (i = 0; i < 100; i++) {
        int row = i / 10, col = i % 10, c = i % 3, x, y;
        float p[3];
        const uint8_t *q;
        p[0] = -2.25f + 0.5f * (float)col;
        p[1] = -2.25f + 0.5f * (float)row;
        p[2] = 0.15f;
        if (!project(&fd.camera, p, &x, &y)) {
            CHECK(0, "cube %d projects outside the frame", i);
            continue;
        }
        q = px + 4 * ((long)y * W + x);
        if (q[c] > q[(c + 1) % 3] + 40 && q[c] > q[(c + 2) % 3] + 40)
            colour_ok++;
        else
            fprintf(stderr, "cube %d (colour %d) at pixel (%d, %d): %d %d %d\n", i, c, x, y, q[0], q[1], q[2]);
        if (row < 9 && col < 9) {
            long a;
            p[0] += 0.25f;
            p[1] += 0.25f;
            p[2] = 0.0f;
            if (!project(&fd.camera, p, &x, &y)) continue;
            a = 4 * ((long)y * W + x);
            gaps++;
            if (abs(px[a] - bg[a]) <= 6 && abs(px[a + 1] - bg[a + 1]) <= 6 && abs(px[a + 2] - bg[a + 2]) <= 6)
                gap_ok++;
            else
                fprintf(stderr, "gap after cube %d at pixel (%d, %d): %d %d %d, background %d %d %d\n", i, x, y,
                        px[a], px[a + 1], px[a + 2], bg[a], bg[a + 1], bg[a + 2]);
        }
    }
    printf("many_opaque: %d of 100 cube centres in their colour, %d of %d gaps background\n", colour_ok, gap_ok, gaps);
    CHECK(colour_ok == 100, "%d of 100 cubes in their material's colour", colour_ok);
    CHECK(gaps == 81 && gap_ok == gaps, "%d of %d gaps are background", gap_ok, gaps);
out:
    snell_renderer_destroy(r);
    snell_scene_file_destroy(s);
}

/* 65 opaque triangles, each in its own colour: one buffer (a data: URI). */
static char *many_colours_gltf(int n)
{
    size_t cap = 4096 + (size_t)n * 160, len = 0;
    char *j = (char *)malloc(cap);
    int i;
    if (!j) return NULL;
    len += (size_t)snprintf(j + len, cap - len,
                            "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"buffers\":[{\"byteLength\":36,\"uri\":"
                            "\"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}],"
                            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"accessors\":[{\"bufferView\":0,"
                            "\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]}],"
                            "\"meshes\":[");
    for (i = 0; i < n; i++)
        len += (size_t)snprintf(j + len, cap - len, "%s{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":%d}]}",
                                i ? "," : "", i);
    len += (size_t)snprintf(j + len, cap - len, "],\"materials\":[");
    for (i = 0; i < n; i++)
        len += (size_t)snprintf(j + len, cap - len, "%s{\"pbrMetallicRoughness\":{\"baseColorFactor\":[%g,0.5,0.5,1]}}",
                                i ? "," : "", (double)i / n);
    len += (size_t)snprintf(j + len, cap - len, "],\"nodes\":[");
    for (i = 0; i < n; i++)
        len += (size_t)snprintf(j + len, cap - len, "%s{\"mesh\":%d,\"translation\":[%d,0,0]}", i ? "," : "", i, i);
    len += (size_t)snprintf(j + len, cap - len, "],\"scenes\":[{\"nodes\":[");
    for (i = 0; i < n; i++) len += (size_t)snprintf(j + len, cap - len, "%s%d", i ? "," : "", i);
    snprintf(j + len, cap - len, "]}]}");
    return j;
}

static void test_refusals(snell_ctx *ctx)
{
    snell_scene_file *s = NULL;
    char *j;
    snell_status st = snell_scene_load_gltf(ctx, scene_path("glass_33.gltf"), 0, &s);
    printf("glass_33: %s: %s\n", snell_status_str(st), snell_last_error(ctx));
    CHECK(st == SNELL_E_LIMIT && !s && strstr(snell_last_error(ctx), "33 glass objects") &&
              strstr(snell_last_error(ctx), "limit of 32"),
          "glass_33: %s: %s", snell_status_str(st), snell_last_error(ctx));
    snell_scene_file_destroy(s);
    s = NULL;
    j = many_colours_gltf(SNELL_MAX_OPAQUE + 1);
    CHECK(j != NULL, "out of memory");
    if (!j) return;
    st = snell_scene_load_gltf_mem(ctx, j, strlen(j), &s);
    printf("%d opaque colours: %s: %s\n", SNELL_MAX_OPAQUE + 1, snell_status_str(st), snell_last_error(ctx));
    CHECK(st == SNELL_E_LIMIT && !s && strstr(snell_last_error(ctx), "65 opaque objects"),
          "65 colours: %s: %s", snell_status_str(st), snell_last_error(ctx));
    snell_scene_file_destroy(s);
    s = NULL;
    free(j);
    /* at the limit: 64 colours load as 64 objects, not merged */
    j = many_colours_gltf(SNELL_MAX_OPAQUE);
    if (!j) return;
    CHECK_OK_CTX(ctx, snell_scene_load_gltf_mem(ctx, j, strlen(j), &s));
    {
        int no = 0;
        snell_scene_file_opaque(s, &no);
        CHECK(no == SNELL_MAX_OPAQUE && !strcmp(snell_scene_file_opaque_name(s, 63), "node 63"),
              "64 colours: %d objects, the last named '%s'", no, snell_scene_file_opaque_name(s, 63));
    }
    snell_scene_file_destroy(s);
    free(j);
}

static void test_names(snell_ctx *ctx)
{
    snell_scene_file *s = NULL;
    int i;
    CHECK_OK_CTX(ctx, snell_scene_load_gltf(ctx, scene_path("glass_row.gltf"), 0, &s));
    if (!s) return;
    for (i = 0; i < 3; i++) {
        char want[24];
        snprintf(want, sizeof want, "node %d", i);
        CHECK(!strcmp(snell_scene_file_glass_name(s, i), want), "glass %d name '%s'", i,
              snell_scene_file_glass_name(s, i));
    }
    CHECK(!strcmp(snell_scene_file_opaque_name(s, 0), "node 3"), "opaque name '%s'", snell_scene_file_opaque_name(s, 0));
    CHECK(!snell_scene_file_glass_name(s, 3) && !snell_scene_file_glass_name(s, -1) &&
              !snell_scene_file_opaque_name(s, 1) && !snell_scene_file_glass_name(NULL, 0),
          "a name out of range");
    snell_scene_file_destroy(s);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_env *env = NULL;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 64);
    if (env) test_many_opaque(ctx, env);
    test_refusals(ctx);
    test_names(ctx);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
