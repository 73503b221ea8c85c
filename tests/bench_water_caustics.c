/* SPDX-License-Identifier: MIT */
/* bench_water_caustics.c — the frame cost of the water's caustics (issue
 * 27 item 4): two identical CPU-simulated waters with the same drops, one
 * drawn without a light, one under a directional light (the floor's light
 * map remade every frame: the surface moves every frame), the two frames
 * taking turns each round (which goes first alternates). The simulation
 * steps are not timed (the same for both). Prints the median frame times
 * and the median of the per-round ratios lit / dark. A tool, not a test
 * (glFinish per frame). */
#include "core/gl.h"
#include "core/core.h"
#include "snell/snell.h"
#include "snell/snell_water.h"
#include "cli_time.h" /* ports/cli: the median the ports use */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    int size = argc > 1 ? atoi(argv[1]) : 512, rounds = argc > 2 ? atoi(argv[2]) : 15;
    int grid = argc > 3 ? atoi(argv[3]) : 128, map = argc > 4 ? atoi(argv[4]) : 256, i, k;
    snell_ctx *ctx = NULL;
    snell_env *env = NULL;
    snell_water *w[2] = {NULL, NULL};
    snell_renderer *r[2] = {NULL, NULL};
    snell_renderer_desc rd;
    snell_env_desc ed;
    snell_water_desc wd;
    snell_frame_desc fd[2];
    double *t[2], *ratio;
    static const char *names[2] = {"dark", "lit"};
    if (rounds < 1 || rounds > 1000 || size < 16 || grid < 64 || grid > 512 || map < 16 || map > 2048) {
        fprintf(stderr, "usage: bench_water_caustics [SIZE [ROUNDS [GRID [MAP]]]]\n");
        return 2;
    }
    memset(&rd, 0, sizeof rd);
    memset(&ed, 0, sizeof ed);
    memset(&wd, 0, sizeof wd);
    rd.width = rd.height = size;
    wd.grid = grid;
    wd.light_map = map;
    wd.sim = SNELL_WATER_SIM_CPU;
    wd.damping = -1.0f; /* no damping: the surface keeps moving */
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK || snell_env_create(ctx, &ed, &env) != SNELL_OK) {
        fprintf(stderr, "bench_water_caustics: %s\n", snell_last_error(ctx));
        return 1;
    }
    for (k = 0; k < 2; k++) {
        if (snell_water_create(ctx, &wd, &w[k]) != SNELL_OK || snell_renderer_create(ctx, &rd, &r[k]) != SNELL_OK ||
            snell_water_drop(w[k], 0.3f, 0.2f, 0.15f, -0.05f) != SNELL_OK ||
            snell_water_drop(w[k], -0.4f, -0.3f, 0.1f, -0.04f) != SNELL_OK) {
            fprintf(stderr, "bench_water_caustics: %s\n", snell_last_error(ctx));
            return 1;
        }
        memset(&fd[k], 0, sizeof fd[k]);
        fd[k].env = env;
        fd[k].water = w[k];
        fd[k].camera.azimuth = 0.52f, fd[k].camera.elevation = 0.61f, fd[k].camera.distance = 3.6f;
        fd[k].camera.target[1] = -0.2f;
    }
    fd[1].light.type = SNELL_LIGHT_DIRECTIONAL;
    fd[1].light.direction[0] = 0.3f, fd[1].light.direction[1] = -1.0f, fd[1].light.direction[2] = 0.2f;
    for (k = 0; k < 2; k++) t[k] = (double *)calloc((size_t)rounds, sizeof(double));
    ratio = (double *)calloc((size_t)rounds, sizeof(double));
    if (!t[0] || !t[1] || !ratio) return 1;
    for (i = -1; i < rounds; i++) { /* round -1 warms every program and target up */
        int o;
        for (k = 0; k < 2; k++)
            if (snell_water_step(w[k], 1.0f / 120.0f, 2, NULL) != SNELL_OK) {
                fprintf(stderr, "bench_water_caustics: %s\n", snell_last_error(ctx));
                return 1;
            }
        for (o = 0; o < 2; o++) {
            snell_frame_stats st;
            double t0;
            k = (o + i + 1) % 2; /* which goes first alternates */
            glFinish();
            t0 = snell__now_ms();
            if (snell_render(r[k], &fd[k], &st) != SNELL_OK) {
                fprintf(stderr, "bench_water_caustics: %s\n", snell_last_error(ctx));
                return 1;
            }
            glFinish();
            if (i >= 0) t[k][i] = snell__now_ms() - t0;
            if (k == 1 && !strstr(st.caustics_reason, "water floor: made")) {
                fprintf(stderr, "bench_water_caustics: lit frame: %s\n", st.caustics_reason);
                return 1;
            }
        }
    }
    for (i = 0; i < rounds; i++) ratio[i] = t[1][i] / t[0][i];
    printf("bench_water_caustics: %dx%d, %d rounds, %dx%d water grid (CPU simulation, moving every frame), %dx%d "
           "floor light map remade every lit frame\n", size, size, rounds, grid, grid, map, map);
    for (k = 0; k < 2; k++) printf("  %-5s median %.2f ms\n", names[k], cli_median(t[k], rounds));
    printf("  lit/dark median ratio %.3f\n", cli_median(ratio, rounds));
    for (k = 0; k < 2; k++) {
        snell_renderer_destroy(r[k]);
        snell_water_destroy(w[k]);
    }
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return 0;
}
