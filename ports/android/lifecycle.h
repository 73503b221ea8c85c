/* SPDX-License-Identifier: MIT */
/* lifecycle — what the Android port creates and destroys, and when, as a plain
 * state machine with no Android or EGL types, so the host's ctest runs it.
 *
 * An activity's native window can appear and disappear at any point (after
 * onPause, during onDestroy, several times while paused); the EGL context
 * can be lost (EGL_CONTEXT_LOST from eglSwapBuffers after a power event).
 * lifecycle_step() takes one such event and returns the actions to run now,
 * in the order of enum lifecycle_action's values. What survives what:
 *   window destroyed       the window surface only; context and GL objects stay
 *                          (a paused app keeps its baked cubemaps)
 *   context lost           context and every GL object (snell's context,
 *                          renderer, environment, meshes' GPU copies): made
 *                          again from the CPU data (asset bytes, decoded
 *                          images, scene settings), which is never dropped
 *   activity destroyed     everything, once; events after it change nothing */
#ifndef SNELL_ANDROID_LIFECYCLE_H
#define SNELL_ANDROID_LIFECYCLE_H

typedef enum lifecycle_event {
    LIFECYCLE_START,
    LIFECYCLE_RESUME,
    LIFECYCLE_PAUSE,
    LIFECYCLE_STOP,
    LIFECYCLE_WINDOW_CREATED,
    LIFECYCLE_WINDOW_DESTROYED,
    LIFECYCLE_CONTEXT_LOST,
    LIFECYCLE_DESTROY,
    LIFECYCLE_EVENT_COUNT
} lifecycle_event;

/* Bits of lifecycle_step's result, to be run in this order (teardown first,
 * then creation: a lost context is torn down before its replacement is made). */
typedef enum lifecycle_action {
    LIFECYCLE_DESTROY_SURFACE = 1 << 0,    /* eglMakeCurrent off it, eglDestroySurface */
    LIFECYCLE_DESTROY_GL_OBJECTS = 1 << 1, /* snell objects and snell_ctx (after a loss the
                                            * dead context ignores the deletes) */
    LIFECYCLE_DESTROY_CONTEXT = 1 << 2,    /* eglDestroyContext, eglTerminate */
    LIFECYCLE_CREATE_CONTEXT = 1 << 3,     /* eglInitialize, config, context */
    LIFECYCLE_CREATE_SURFACE = 1 << 4,     /* eglCreateWindowSurface, eglMakeCurrent */
    LIFECYCLE_CREATE_GL_OBJECTS = 1 << 5   /* snell_ctx (EXTERNAL) and the scene from CPU data */
} lifecycle_action;

typedef struct lifecycle_state {
    int resumed;          /* between onResume and onPause */
    int window;           /* the native window exists (created, not yet destroyed) */
    int context;          /* an EGL context exists */
    int surface;          /* a window surface exists (implies window and context) */
    int gl_objects;       /* snell's objects exist in the context */
    int destroyed;        /* onDestroy ran: nothing is made again */
    unsigned generation;  /* contexts made so far: a loss makes the next one */
} lifecycle_state;

/* All zero: before onCreate's first event. */
void lifecycle_init(lifecycle_state *s);
/* Applies one event to s and returns the lifecycle_action bits to run.
 * Unknown events change nothing and return 0. */
unsigned lifecycle_step(lifecycle_state *s, lifecycle_event ev);
/* Nonzero when a frame may be drawn and swapped now. */
int lifecycle_should_render(const lifecycle_state *s);
const char *lifecycle_event_str(lifecycle_event ev);

#endif
