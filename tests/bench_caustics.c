/* SPDX-License-Identifier: MIT */
/* bench_caustics.c — the caustics stage's frame cost (issue 27): a glass
 * sphere (or MESH: torus, or an OBJ file fitted in the unit sphere) over a
 * receiver under a directional light, four frames taking turns each round:
 * without light ("off"), with it and nothing moved (the light map reused),
 * and with the light nudged every frame (the light map made again), its
 * photons by the stage's own choice ("made": the BVH for a mesh that is not
 * convex) and by the depth maps' one crossing alone ("maps",
 * caustics.maps_only). Prints the median frame times and the medians of the
 * per-round ratios against "off", and made against maps. With OPAQUE 1, an
 * opaque box stands on the receiver beside the glass in all of them (lit
 * with the light: the caustic map in the light's frame, photons stopped by
 * it, its shadows). A tool, not a test (glFinish per frame). */
#include "core/gl.h"
#include "core/core.h"
#include "snell/snell.h"
#include "render/caustics.h" /* caustics.maps_only */
#include "render/stages.h"
#include "cli_time.h" /* ports/cli: the median the ports use */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    int size = argc > 1 ? atoi(argv[1]) : 512, rounds = argc > 2 ? atoi(argv[2]) : 15;
    int photons = argc > 3 ? atoi(argv[3]) : 256, map = argc > 4 ? atoi(argv[4]) : 256, i, k;
    int opaque = argc > 5 ? atoi(argv[5]) : 0;
    const char *mesh = argc > 6 ? argv[6] : "sphere";
    float box[16] = {0.6f, 0, 0, 0, 0, 0.3f, 0, 0, 0, 0, 0.6f, 0, 1.5f, -0.7f, 0, 1};
    snell_shape_desc bd = {SNELL_SHAPE_CUBE, 0, 0};
    snell_mesh *cube = NULL;
    snell_opaque op;
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_mesh *sphere = NULL;
    snell_env *env = NULL;
    snell_renderer *r[4] = {NULL, NULL, NULL, NULL}; /* one each: a renderer keeps one light map */
    snell_renderer_desc rd;
    snell_env_desc ed;
    snell_shape_desc sd = {SNELL_SHAPE_SPHERE, 0, 0};
    snell_frame_desc fd;
    snell_glass g;
    double *t[4], *ratio[4];
    static const char *names[4] = {"off", "reused", "made", "maps"};
    if (rounds < 1 || rounds > 1000 || size < 16 || photons < 16 || map < 16 || opaque < 0 || opaque > 1) {
        fprintf(stderr, "usage: bench_caustics [SIZE [ROUNDS [PHOTONS [MAP [OPAQUE 0|1 [sphere|torus|FILE.obj]]]]]]\n");
        return 2;
    }
    memset(&cd, 0, sizeof cd);
    memset(&rd, 0, sizeof rd);
    memset(&ed, 0, sizeof ed);
    rd.width = rd.height = size;
    sd.shape = strcmp(mesh, "torus") == 0 ? SNELL_SHAPE_TORUS : SNELL_SHAPE_SPHERE;
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK) return 1;
    if (strcmp(mesh, "sphere") != 0 && strcmp(mesh, "torus") != 0) {
        if (snell_mesh_load(ctx, mesh, &sphere) == SNELL_OK) snell_mesh_normalize(sphere, 1.0f);
    } else {
        snell_mesh_create_shape(ctx, &sd, &sphere);
    }
    if (!sphere || snell_env_create(ctx, &ed, &env) != SNELL_OK || snell_renderer_create(ctx, &rd, &r[0]) != SNELL_OK ||
        snell_renderer_create(ctx, &rd, &r[1]) != SNELL_OK || snell_renderer_create(ctx, &rd, &r[2]) != SNELL_OK ||
        snell_renderer_create(ctx, &rd, &r[3]) != SNELL_OK || snell_mesh_create_shape(ctx, &bd, &cube) != SNELL_OK) {
        fprintf(stderr, "bench_caustics: %s\n", snell_last_error(ctx));
        return 1;
    }
    memset(&g, 0, sizeof g);
    g.mesh = sphere;
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass = &g;
    fd.glass_count = 1;
    memset(&op, 0, sizeof op);
    op.mesh = cube, op.model = box;
    fd.opaque = &op, fd.opaque_count = opaque;
    fd.camera.azimuth = 0.5f, fd.camera.elevation = 0.6f, fd.camera.distance = 6.0f, fd.camera.fov_y = 0.8f;
    snell__renderer_caustics(r[3])->maps_only = 1;
    for (k = 0; k < 4; k++) t[k] = (double *)calloc((size_t)rounds, sizeof(double));
    for (k = 0; k < 4; k++) ratio[k] = (double *)calloc((size_t)rounds, sizeof(double));
    for (i = -1; i < rounds; i++) /* round -1 warms every program and target up */
        for (k = 0; k < 4; k++) {
            snell_frame_desc f = fd;
            double t0;
            snell_frame_stats st;
            if (k > 0) {
                f.light.type = SNELL_LIGHT_DIRECTIONAL;
                f.light.direction[0] = 0.4f, f.light.direction[1] = -1.0f;
                f.light.direction[2] = k >= 2 ? 0.001f * (float)(i + 2) : 0.0f; /* made: moved every frame */
                f.light.photons = photons;
                f.receiver.height = -1.0f, f.receiver.extent = 3.0f, f.receiver.map_size = map;
            }
            t0 = snell__now_ms();
            if (snell_render(r[k], &f, &st) != SNELL_OK) {
                fprintf(stderr, "bench_caustics: %s\n", snell_last_error(ctx));
                return 1;
            }
            glFinish();
            if (i >= 0) t[k][i] = snell__now_ms() - t0;
            if (i >= 0 && k > 0 && st.caustics_reused != (k == 1)) {
                fprintf(stderr, "bench_caustics: frame %s: %s\n", names[k], st.caustics_reason);
                return 1;
            }
        }
    for (i = 0; i < rounds; i++) {
        for (k = 0; k < 3; k++) ratio[k][i] = t[k + 1][i] / t[0][i];
        ratio[3][i] = t[2][i] / t[3][i];
    }
    printf("bench_caustics: %s, %dx%d, %d rounds, %d^2 photons, %d^2 light map%s\n", mesh, size, size, rounds, photons,
           map, opaque ? ", an opaque box (lit: caustic map in the light's frame)" : "");
    for (k = 0; k < 4; k++) printf("  %-7s median %.2f ms\n", names[k], cli_median(t[k], rounds));
    printf("  reused/off median ratio %.3f, made/off median ratio %.3f, maps/off median ratio %.3f, made/maps median "
           "ratio %.3f\n", cli_median(ratio[0], rounds), cli_median(ratio[1], rounds), cli_median(ratio[2], rounds),
           cli_median(ratio[3], rounds));
    for (k = 0; k < 4; k++) snell_renderer_destroy(r[k]);
    snell_env_destroy(env);
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(cube);
    snell_ctx_destroy(ctx);
    return 0;
}
