/* SPDX-License-Identifier: MIT */
/* bench_floor — issue 10's frame floor measured the way the frame is made:
 * the screen-space frame of one glass mesh split into its three necessary
 * parts, each timed alone (ended by glFinish) right after a full frame left
 * every resource in place: the G-buffer pass (the mesh with a trivial
 * shader, vertex-cache ordered), the kernel at full-block pixel rate (its
 * full-screen pass, depth-tested to the covered pixels) and the background.
 * floor = their sum; the frame's excess over it is what the stage itself
 * costs (clears, state, CPU). Parts and frames take turns, medians of N
 * rounds. Not a test: a tool (built with the tests, it uses internals).
 *
 * usage: bench_floor MESH|sphere METHOD [SIZE] [ROUNDS]   e.g. bench_floor bunny.obj cubemap 512 61
 * (sphere: 256 x 128 segments, dense enough that AUTO would shade it in screen space) */
#include "core/gl.h"
#include "frame/env.h"
#include "render/caustics.h"
#include "render/renderer.h"
#include "render/stages.h"
#include "cli_time.h" /* ports/cli: the median the ports use */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    snell_ctx *ctx = NULL;
    snell_mesh *mesh = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_env_desc ed;
    snell_glass g;
    snell_frame_desc fd;
    snell_frame_stats st;
    snell_method method;
    int size = argc > 3 ? atoi(argv[3]) : 512, rounds = argc > 4 ? atoi(argv[4]) : 61, i, k;
    double *t[4];
    const char *names[4] = {"frame", "G-buffer pass (trivial shader)", "kernel (full blocks)", "background"};
    if (argc < 3 || snell_method_from_str(argv[2], &method) != SNELL_OK || method == SNELL_METHOD_AUTO ||
        size < 16 || rounds < 3) {
        fprintf(stderr, "usage: bench_floor MESH METHOD [SIZE] [ROUNDS]\n");
        return 2;
    }
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK ||
        (strcmp(argv[1], "sphere") == 0
             ? snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_SPHERE, 256, 128}, &mesh)
             : snell_mesh_load(ctx, argv[1], &mesh)) != SNELL_OK ||
        snell_mesh_normalize(mesh, 1.0f) != SNELL_OK) {
        fprintf(stderr, "bench_floor: %s\n", snell_last_error(ctx));
        return 1;
    }
    memset(&ed, 0, sizeof ed);
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = size;
    rd.shading = SNELL_SHADING_SCREEN;
    if (snell_env_create(ctx, &ed, &env) != SNELL_OK || snell_renderer_create(ctx, &rd, &r) != SNELL_OK) {
        fprintf(stderr, "bench_floor: %s\n", snell_last_error(ctx));
        return 1;
    }
    memset(&g, 0, sizeof g);
    g.mesh = mesh;
    g.material.method = method;
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass = &g;
    fd.glass_count = 1;
    fd.camera.distance = 3.5f;
    fd.camera.azimuth = 0.5236f; /* snell-bench's one-mesh camera: 30 / 20 degrees */
    fd.camera.elevation = 0.3491f;
    for (k = 0; k < 4; k++) t[k] = (double *)calloc((size_t)rounds, sizeof(double));
    for (i = 0; i < 5; i++) snell_render(r, &fd, &st); /* warm-up: programs, bake, upload */
    if (!r->scene.drawn || !r->scene.obj[0].screen_space) {
        fprintf(stderr, "bench_floor: the object is not shaded in screen space\n");
        return 1;
    }
    for (i = 0; i < rounds; i++) {
        snell__object *o = &r->scene.obj[0];
        mat4 rot, vp;
        double t0;
        glFinish();
        t0 = snell__now_ms();
        snell_render(r, &fd, &st);
        glFinish();
        t[0][i] = snell__now_ms() - t0;
        /* The parts, in the state the frame left (its target bound, the
         * G-buffer textures bound), with the depth cleared as a frame
         * starts, so the G-buffer pass shades what it shades in a frame and
         * leaves the glass depth for the kernel's test and the background. */
        glBindFramebuffer(GL_FRAMEBUFFER, r->sv.fbo);
        glViewport(0, 0, size, size);
        glDepthMask(GL_TRUE);
        glClear(GL_DEPTH_BUFFER_BIT);
        glFinish();
        t0 = snell__now_ms();
        {
            /* the G-buffer stage's state begins with its G-buffer (render/gbuffer.c) */
            snell__gbuffer *gb = (snell__gbuffer *)snell__renderer_stage_state(r, &snell__stage_gbuffer);
            snell__gbuffer_draw(ctx, gb, &r->scene.view, &o, 1, r->sv.depth_rb, st.glass);
        }
        glFinish();
        t[1][i] = snell__now_ms() - t0;
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_CUBE_MAP, o->env_texture);
        glEnable(GL_DEPTH_TEST);
        t0 = snell__now_ms();
        o->method->draw(ctx, o->method_state, &r->scene.view, o, st.glass);
        glFinish();
        t[2][i] = snell__now_ms() - t0;
        glm_mat4_copy(r->scene.view.view, rot);
        rot[3][0] = rot[3][1] = rot[3][2] = 0.0f;
        glm_mat4_mul(r->scene.view.proj, rot, vp);
        glBindTexture(GL_TEXTURE_CUBE_MAP, env->texture);
        t0 = snell__now_ms();
        snell__composite_background(ctx, &r->comp, r->sv.out, (const float *)vp);
        glFinish();
        t[3][i] = snell__now_ms() - t0;
    }
    {
        double m[4], floor_ms;
        for (k = 0; k < 4; k++) m[k] = cli_median(t[k], rounds);
        floor_ms = m[1] + m[2] + m[3];
        printf("%s, %s, %dx%d, %d rounds, %s\n", argv[1], argv[2], size, size, rounds, snell_ctx_gl_renderer(ctx));
        for (k = 0; k < 4; k++) printf("  %-32s %8.3f ms\n", names[k], m[k]);
        printf("  %-32s %8.3f ms\n  frame / floor                    %8.3f\n", "floor (sum of the three)", floor_ms,
               m[0] / floor_ms);
    }
    for (k = 0; k < 4; k++) free(t[k]);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
    snell_ctx_destroy(ctx);
    return 0;
}
