/* SPDX-License-Identifier: MIT */
/* sdl2.c — glass in an SDL2 window. SDL makes the GLES 3.0 context (on X11
 * through GLX, elsewhere EGL); snell draws into its window framebuffer.
 *   cc sdl2.c $(pkg-config --cflags --libs sdl2 snell) */
#include "glass.h"

#include <SDL2/SDL.h>
#include <GLES3/gl3.h>

int main(void)
{
    SDL_Window *win;
    glass_app g;
    snell_camera cam = {0}; /* stands in for the app's own view and projection */
    float eye[3], view[16], proj[16];
    int running = 1;
    SDL_Init(SDL_INIT_VIDEO);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_ES);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 0);
    SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 24); /* snell depth-tests the glass */
    win = SDL_CreateWindow("glass", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, 640, 480, SDL_WINDOW_OPENGL);
    if (!win || !SDL_GL_CreateContext(win) || !glass_open(&g, 640, 480)) return 1;
    snell_camera_matrices(&cam, 640.0f / 480.0f, eye, view, proj);
    while (running) {
        SDL_Event e;
        while (SDL_PollEvent(&e)) running &= e.type != SDL_QUIT;
        glClearColor(0.3f, 0.5f, 0.8f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT); /* ... the app's scene ... */
        if (glass_draw(&g, view, proj) != SNELL_OK) SDL_Log("glass: %s", snell_last_error(g.ctx));
        SDL_GL_SwapWindow(win);
    }
    glass_close(&g);
    SDL_Quit();
    return 0;
}
