/* SPDX-License-Identifier: MIT */
/* glfw.c — glass in a GLFW window: a GLES 3.0 context (GLX on X11, EGL on
 * Wayland), snell drawing into its framebuffer.
 *   cc glfw.c $(pkg-config --cflags --libs glfw3 snell) */
#include "glass.h"

#define GLFW_INCLUDE_ES3
#include <GLFW/glfw3.h>
#include <stdio.h>

int main(void)
{
    GLFWwindow *win;
    glass_app g;
    snell_camera cam = {0}; /* stands in for the app's own view and projection */
    float eye[3], view[16], proj[16];
    int w = 640, h = 480;
    if (!glfwInit()) return 1;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
    glfwWindowHint(GLFW_DEPTH_BITS, 24); /* snell depth-tests the glass */
    win = glfwCreateWindow(w, h, "glass", NULL, NULL);
    if (!win) return 1;
    glfwMakeContextCurrent(win);
    glfwGetFramebufferSize(win, &w, &h); /* pixels, not screen units */
    if (!glass_open(&g, w, h)) return 1;
    snell_camera_matrices(&cam, (float)w / (float)h, eye, view, proj);
    while (!glfwWindowShouldClose(win)) {
        glClearColor(0.3f, 0.5f, 0.8f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT); /* ... the app's scene ... */
        if (glass_draw(&g, view, proj) != SNELL_OK) fprintf(stderr, "glass: %s\n", snell_last_error(g.ctx));
        glfwSwapBuffers(win);
        glfwPollEvents();
    }
    glass_close(&g);
    glfwTerminate();
    return 0;
}
