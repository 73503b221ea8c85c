/* SPDX-License-Identifier: MIT */
/* glass.h — what every recipe here shares: glass drawn into the framebuffer
 * the app has bound, in the app's current GLES 3.0 context (made by SDL2,
 * GLFW, Qt, Android's GLSurfaceView or EGL on GBM), by snell's EXTERNAL
 * backend. docs/integrating.md "Recipes" shows each; tests/apphost.cmake
 * compiles those whose toolkit is installed. */
#ifndef RECIPE_GLASS_H
#define RECIPE_GLASS_H

#include <snell/snell.h>
#include <string.h>

typedef struct glass_app {
    snell_ctx *ctx;
    snell_mesh *mesh;
    snell_env *env;
    snell_renderer *r;
} glass_app;

/* With the app's context current, once (and again when the window's size changes). */
static int glass_open(glass_app *g, int width, int height)
{
    snell_ctx_desc cd;
    snell_shape_desc sd;
    snell_env_desc ed;
    snell_renderer_desc rd;
    memset(g, 0, sizeof *g);
    memset(&cd, 0, sizeof cd), memset(&sd, 0, sizeof sd), memset(&ed, 0, sizeof ed), memset(&rd, 0, sizeof rd);
    cd.backend = SNELL_BACKEND_EXTERNAL; /* the app's context, current now */
    sd.shape = SNELL_SHAPE_SPHERE;
    ed.face_size = 64;
    rd.width = width, rd.height = height, rd.target = SNELL_TARGET_BOUND_FRAMEBUFFER;
    return snell_ctx_create(&cd, &g->ctx) == SNELL_OK && snell_mesh_create_shape(g->ctx, &sd, &g->mesh) == SNELL_OK &&
           snell_env_create(g->ctx, &ed, &g->env) == SNELL_OK &&
           snell_renderer_create(g->ctx, &rd, &g->r) == SNELL_OK;
}

/* Each frame, after the app drew its scene into the bound framebuffer
 * (colour and depth): the glass over it, the app's frame refracted. */
static snell_status glass_draw(glass_app *g, const float view[16], const float projection[16])
{
    snell_glass glass;
    snell_backdrop backdrop;
    snell_frame_desc fd;
    memset(&glass, 0, sizeof glass), memset(&backdrop, 0, sizeof backdrop), memset(&fd, 0, sizeof fd);
    glass.mesh = g->mesh;
    backdrop.source = SNELL_BACKDROP_COPY_BOUND; /* the app's frame behind the glass */
    fd.glass = &glass, fd.glass_count = 1, fd.env = g->env, fd.backdrop = &backdrop;
    fd.depth = SNELL_DEPTH_TEST; /* the app's depth hides the glass behind its objects */
    fd.draw_background = SNELL_BACKGROUND_NONE; /* the app's scene stays where there is no glass */
    fd.camera.kind = SNELL_CAMERA_MATRICES;
    memcpy(fd.camera.view, view, sizeof fd.camera.view);
    memcpy(fd.camera.projection, projection, sizeof fd.camera.projection);
    return snell_render(g->r, &fd, NULL);
}

static void glass_close(glass_app *g)
{
    snell_renderer_destroy(g->r);
    snell_env_destroy(g->env);
    snell_mesh_destroy(g->mesh);
    snell_ctx_destroy(g->ctx);
}

#endif
