/* SPDX-License-Identifier: MIT */
/* An SDL2 app as a new user writes it (issue 48): SDL's default GLES 3.0
 * context (on X11 made through GLX, not EGL) and its window framebuffer (depth
 * 24, no stencil), a scene of its own and a GL error of its own left pending.
 * Glass goes in with the EXTERNAL backend, the app's depth tested and its
 * frame copied as the backdrop; each frame the glass must be drawn, the
 * app's pixels kept around it and its pending error still there after.
 * Run under xvfb-run (tests/host.cmake); exit 77 without a display. */
#include <SDL2/SDL.h>
#include <snell/snell.h>

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <stdio.h>
#include <string.h>

#define W 96
#define H 72
#define FRAMES 3

static int g_fail;
#define CHECK(c, ...) do { if (!(c)) { printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); g_fail++; } } while (0)

/* The app's scene: a red left half, a blue right half, depth cleared to 1. */
static void app_draw(void)
{
    glViewport(0, 0, W, H);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, W / 2, H);
    glClearColor(0.8f, 0.1f, 0.1f, 1.0f);
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glScissor(W / 2, 0, W - W / 2, H);
    glClearColor(0.1f, 0.1f, 0.8f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
}

static void read(uint8_t *px)
{
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
}

int main(void)
{
    static uint8_t before[W * H * 4], after[W * H * 4];
    SDL_Window *win;
    SDL_GLContext glc;
    snell_ctx *ctx = NULL;
    snell_mesh *mesh = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_ctx_desc cd;
    snell_shape_desc sd;
    snell_env_desc ed;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_glass g;
    snell_backdrop bd;
    GLint depth = 0, stencil = -1;
    int frame;
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        printf("SKIP: SDL_Init: %s\n", SDL_GetError());
        return 77;
    }
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_ES);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 0);
    SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 24);
    win = SDL_CreateWindow("snell in SDL2", 0, 0, W, H, SDL_WINDOW_OPENGL);
    glc = win ? SDL_GL_CreateContext(win) : NULL;
    if (!glc) {
        printf("SKIP: no GLES 3.0 window: %s\n", SDL_GetError());
        return 77;
    }
    printf("SDL video driver %s, GL %s, EGL context current: %s\n", SDL_GetCurrentVideoDriver(),
           (const char *)glGetString(GL_VERSION), eglGetCurrentContext() != EGL_NO_CONTEXT ? "yes" : "no (GLX)");
    glGetIntegerv(GL_DEPTH_BITS, &depth);
    glGetIntegerv(GL_STENCIL_BITS, &stencil);
    CHECK(depth >= 16 && stencil == 0, "window framebuffer depth %d stencil %d: the case is depth, no stencil", depth,
          stencil);
    while (glGetError() != GL_NO_ERROR) {}

    memset(&cd, 0, sizeof cd);
    memset(&sd, 0, sizeof sd);
    memset(&ed, 0, sizeof ed);
    memset(&rd, 0, sizeof rd);
    cd.backend = SNELL_BACKEND_EXTERNAL;
    ed.face_size = 16;
    rd.width = W, rd.height = H, rd.target = SNELL_TARGET_BOUND_FRAMEBUFFER;
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK || snell_mesh_create_shape(ctx, &sd, &mesh) != SNELL_OK ||
        snell_env_create(ctx, &ed, &env) != SNELL_OK || snell_renderer_create(ctx, &rd, &r) != SNELL_OK) {
        printf("FAIL: setting up snell in the SDL2 context: %s %s\n", snell_last_error(NULL), snell_last_error(ctx));
        return 1;
    }
    for (frame = 0; frame < FRAMES; frame++) {
        int changed = 0, i;
        snell_status st;
        GLenum e1, e2;
        app_draw();
        read(before);
        glEnable(0x1234); /* the app's own mistake: GL_INVALID_ENUM, left pending */
        memset(&fd, 0, sizeof fd);
        memset(&g, 0, sizeof g);
        memset(&bd, 0, sizeof bd);
        g.mesh = mesh;
        fd.glass = &g, fd.glass_count = 1, fd.env = env;
        fd.camera.azimuth = 0.3f * (float)frame;
        fd.depth = SNELL_DEPTH_TEST;
        fd.draw_background = -1;
        bd.source = SNELL_BACKDROP_COPY_BOUND;
        fd.backdrop = &bd;
        st = snell_render(r, &fd, NULL);
        CHECK(st == SNELL_OK, "frame %d: %s", frame, snell_last_error(ctx));
        e1 = glGetError();
        e2 = glGetError();
        CHECK(e1 == GL_INVALID_ENUM && e2 == GL_NO_ERROR, "frame %d: the app's pending error 0x%x came back as 0x%x, "
              "then 0x%x", frame, GL_INVALID_ENUM, e1, e2);
        read(after);
        for (i = 0; i < W * H; i++) changed += memcmp(before + 4 * i, after + 4 * i, 4) != 0;
        CHECK(memcmp(before + 4 * (H / 2 * W + W / 2), after + 4 * (H / 2 * W + W / 2), 4) != 0,
              "frame %d: no glass at the centre", frame);
        CHECK(memcmp(before, after, 4) == 0 && memcmp(before + 4 * (W * H - 1), after + 4 * (W * H - 1), 4) == 0,
              "frame %d: the app's corners were painted over", frame);
        CHECK(changed > W * H / 20 && changed < W * H / 2, "frame %d: %d of %d pixels changed", frame, changed, W * H);
        printf("frame %d: glass on %d of %d pixels\n", frame, changed, W * H);
        SDL_GL_SwapWindow(win);
    }
    CHECK(snell_ctx_make_current(ctx) == SNELL_OK, "the app's context is snell's: %s", snell_last_error(ctx));
    /* Objects destroyed after their context: the app's context stays current. */
    snell_ctx_destroy(ctx);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
    CHECK(glGetString(GL_VERSION) != NULL, "the app's context is current after the late destroys");
    CHECK(glGetError() == GL_NO_ERROR, "GL error left after the destroys");
    SDL_GL_DeleteContext(glc);
    SDL_DestroyWindow(win);
    SDL_Quit();
    printf("%s\n", g_fail ? "FAILED" : "ok");
    return g_fail ? 1 : 0;
}
