/* SPDX-License-Identifier: MIT */
/* snell_activity — the NativeActivity entry point (ANativeActivity_onCreate):
 * glass on an ANativeWindow through EGL, in the host-context mode a phone app
 * uses (snell's EXTERNAL backend drawing into the window's framebuffer).
 *
 * The activity's callbacks come on the main thread; drawing happens on a
 * thread of its own with an ALooper (the shape of the NDK's
 * android_native_app_glue): each callback writes a command into a pipe that
 * the looper watches and waits until the render thread has run it, so a
 * window's EGL surface is gone before onNativeWindowDestroyed returns. What a
 * command makes or destroys is lifecycle.c's decision, what the GL objects
 * are made from is glass_scene.c's CPU data: the APK's assets
 * (assets/glass.glb or glass.obj, assets/environment.png or .hdr; a sphere
 * and the procedural sky without them) are read once, at the thread's start.
 * A context loss (EGL_CONTEXT_LOST from eglSwapBuffers) makes the context
 * and the GL objects again from that data. Dragging turns the camera.
 * Glass panels lie over the frame: over a video, assets/panels.mp4 played
 * into a SurfaceTexture's external texture (video_under.c, through JNI),
 * or without that asset over the glass scene.
 *
 * Syntax-checked for aarch64-linux-android24 (syntax_check.sh); not built
 * with an NDK here (docs/android.md). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, pipe under -std=c99 */
#include "glass_scene.h"
#include "lifecycle.h"
#include "video_under.h"

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <android/asset_manager.h>
#include <android/input.h>
#include <android/log.h>
#include <android/looper.h>
#include <android/native_activity.h>
#include <android/native_window.h>
#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define LOG_TAG "snell"
#define LOGI(...) __android_log_print(ANDROID_LOG_INFO, LOG_TAG, __VA_ARGS__)
#define LOGE(...) __android_log_print(ANDROID_LOG_ERROR, LOG_TAG, __VA_ARGS__)

enum { LOOPER_ID_COMMAND = 1, LOOPER_ID_INPUT = 2 };

typedef enum command_kind { COMMAND_LIFECYCLE, COMMAND_INPUT_QUEUE } command_kind;

typedef struct command {
    command_kind kind;
    lifecycle_event event;  /* COMMAND_LIFECYCLE */
    ANativeWindow *window;  /* with LIFECYCLE_WINDOW_CREATED */
    AInputQueue *queue;     /* COMMAND_INPUT_QUEUE: the new queue, NULL when it goes */
} command;

typedef struct app {
    ANativeActivity *activity;
    pthread_t thread;
    pthread_mutex_t mutex;
    pthread_cond_t cond;
    int pipe_fd[2];       /* [0] read by the render thread's looper, [1] written by callbacks */
    unsigned posted;      /* commands written (main thread) */
    unsigned done;        /* commands run (render thread); callbacks wait for theirs */
    int exited;           /* the render thread has left its loop */
    /* render thread only */
    ALooper *looper;
    AInputQueue *input;
    ANativeWindow *window; /* acquired while it exists */
    lifecycle_state life;
    EGLDisplay display;
    EGLConfig config;
    EGLContext context;
    EGLSurface surface;
    glass_scene scene;
    video_under video;     /* the video under the panels, per context; not started without the asset */
    int jni_attached;      /* the render thread is attached to the VM (video_under_start) */
    struct timespec start;
    float drag_x;          /* pointer x at the last move, pixels */
    int dragging;
} app;

/* ---------------------------------------------------------------- EGL */

static const char *egl_error_str(EGLint e)
{
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "EGL error";
    }
}

static int egl_create_context(app *a)
{
    static const EGLint config_attrs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE, EGL_WINDOW_BIT,
                                          EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                          EGL_DEPTH_SIZE, 24, EGL_NONE};
    static const EGLint context_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLint n = 0;
    a->display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (a->display == EGL_NO_DISPLAY || !eglInitialize(a->display, NULL, NULL)) {
        LOGE("eglInitialize: %s", egl_error_str(eglGetError()));
        return 0;
    }
    if (!eglChooseConfig(a->display, config_attrs, &a->config, 1, &n) || n < 1) {
        LOGE("no EGL config for GLES 3 with RGB888 and a 24-bit depth buffer");
        return 0;
    }
    a->context = eglCreateContext(a->display, a->config, EGL_NO_CONTEXT, context_attrs);
    if (a->context == EGL_NO_CONTEXT) {
        LOGE("eglCreateContext (GLES 3): %s", egl_error_str(eglGetError()));
        return 0;
    }
    LOGI("EGL context %u made", a->life.generation);
    return 1;
}

static int egl_create_surface(app *a)
{
    EGLint format = 0;
    /* the window's buffers in the config's own format, so no conversion happens */
    eglGetConfigAttrib(a->display, a->config, EGL_NATIVE_VISUAL_ID, &format);
    ANativeWindow_setBuffersGeometry(a->window, 0, 0, format);
    a->surface = eglCreateWindowSurface(a->display, a->config, a->window, NULL);
    if (a->surface == EGL_NO_SURFACE) {
        LOGE("eglCreateWindowSurface: %s", egl_error_str(eglGetError()));
        return 0;
    }
    if (!eglMakeCurrent(a->display, a->surface, a->surface, a->context)) {
        LOGE("eglMakeCurrent: %s", egl_error_str(eglGetError()));
        return 0;
    }
    return 1;
}

static void surface_size(const app *a, int *w, int *h)
{
    EGLint ew = 0, eh = 0;
    eglQuerySurface(a->display, a->surface, EGL_WIDTH, &ew);
    eglQuerySurface(a->display, a->surface, EGL_HEIGHT, &eh);
    *w = ew > 0 ? ew : 1;
    *h = eh > 0 ? eh : 1;
}

/* Runs lifecycle_step's actions in lifecycle.h's order. 0 if one failed. */
static int run_actions(app *a, unsigned act)
{
    int w, h;
    if (act & LIFECYCLE_DESTROY_SURFACE) {
        eglMakeCurrent(a->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroySurface(a->display, a->surface);
        a->surface = EGL_NO_SURFACE;
    }
    /* With no context current snell skips the GL deletes (after a loss there
     * is nothing to delete; otherwise the context's destruction frees them). */
    if (act & LIFECYCLE_DESTROY_GL_OBJECTS) {
        video_under_stop(&a->video);
        glass_scene_destroy_gl(&a->scene);
    }
    if (act & LIFECYCLE_DESTROY_CONTEXT) {
        eglDestroyContext(a->display, a->context);
        eglTerminate(a->display);
        a->context = EGL_NO_CONTEXT;
        a->display = EGL_NO_DISPLAY;
    }
    if ((act & LIFECYCLE_CREATE_CONTEXT) && !egl_create_context(a)) return 0;
    if ((act & LIFECYCLE_CREATE_SURFACE) && !egl_create_surface(a)) return 0;
    if (act & LIFECYCLE_CREATE_GL_OBJECTS) {
        surface_size(a, &w, &h);
        if (glass_scene_create_gl(&a->scene, w, h) != SNELL_OK) {
            LOGE("%s", a->scene.error);
            return 0;
        }
        LOGI("scene made in context %u (%dx%d, %s)", a->life.generation, w, h, snell_ctx_gl_renderer(a->scene.ctx));
        /* the video's texture belongs to this context: started again with it */
        video_under_start(&a->video, a->activity, "panels.mp4");
        a->jni_attached = 1;
    }
    return 1;
}

static void step(app *a, lifecycle_event ev)
{
    if (!run_actions(a, lifecycle_step(&a->life, ev))) {
        /* Nothing to draw with: say so and close rather than show a black window. */
        LOGE("cannot draw after %s: finishing the activity", lifecycle_event_str(ev));
        ANativeActivity_finish(a->activity);
    }
}

/* ------------------------------------------------------------- frames */

static double seconds_since(const struct timespec *t0)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)(t.tv_sec - t0->tv_sec) + (t.tv_nsec - t0->tv_nsec) * 1e-9;
}

static void draw_frame(app *a)
{
    snell_panels_under under;
    int w, h;
    EGLint err;
    surface_size(a, &w, &h);
    if (glass_scene_resize(&a->scene, w, h) != SNELL_OK) {
        LOGE("%s", a->scene.error);
        return;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    /* the panels over the video's newest frame, or over the glass scene */
    if (glass_scene_draw_panels(&a->scene, seconds_since(&a->start),
                                video_under_frame(&a->video, &under) ? &under : NULL) != SNELL_OK)
        LOGE("%s", a->scene.error);
    if (eglSwapBuffers(a->display, a->surface)) return;
    err = eglGetError();
    if (err == EGL_CONTEXT_LOST) {
        LOGI("EGL context lost: making context and scene again from the kept assets");
        step(a, LIFECYCLE_CONTEXT_LOST);
    } else {
        LOGE("eglSwapBuffers: %s", egl_error_str(err));
    }
}

/* -------------------------------------------------------------- input */

static void handle_motion(app *a, const AInputEvent *ev)
{
    int32_t action = AMotionEvent_getAction(ev) & AMOTION_EVENT_ACTION_MASK;
    float x = AMotionEvent_getX(ev, 0);
    if (action == AMOTION_EVENT_ACTION_DOWN) {
        a->dragging = 1;
    } else if (action == AMOTION_EVENT_ACTION_MOVE && a->dragging && a->scene.width > 0) {
        /* a full-width drag turns the camera half a turn */
        a->scene.camera.azimuth += (x - a->drag_x) / (float)a->scene.width * 3.14159265f;
    } else if (action == AMOTION_EVENT_ACTION_UP || action == AMOTION_EVENT_ACTION_CANCEL) {
        a->dragging = 0;
    }
    a->drag_x = x;
}

static void drain_input(app *a)
{
    AInputEvent *ev = NULL;
    while (a->input && AInputQueue_getEvent(a->input, &ev) >= 0) {
        int handled = 0;
        if (AInputQueue_preDispatchEvent(a->input, ev)) continue; /* the IME took it */
        if (AInputEvent_getType(ev) == AINPUT_EVENT_TYPE_MOTION) {
            handle_motion(a, ev);
            handled = 1;
        }
        AInputQueue_finishEvent(a->input, ev, handled);
    }
}

/* ----------------------------------------------------- render thread */

/* The asset's bytes (AASSET_MODE_BUFFER: mapped, not copied), or NULL if absent. */
static AAsset *open_asset(app *a, const char *const names[], const void **bytes, size_t *size)
{
    int i;
    for (i = 0; names[i]; i++) {
        AAsset *asset = AAssetManager_open(a->activity->assetManager, names[i], AASSET_MODE_BUFFER);
        if (!asset) continue;
        *bytes = AAsset_getBuffer(asset);
        *size = (size_t)AAsset_getLength(asset);
        if (*bytes) {
            LOGI("asset %s: %zu bytes", names[i], *size);
            return asset;
        }
        AAsset_close(asset);
    }
    *bytes = NULL;
    *size = 0;
    return NULL;
}

static int load_assets(app *a)
{
    static const char *const gltf[] = {"glass.glb", "glass.gltf", NULL};
    static const char *const obj[] = {"glass.obj", NULL};
    static const char *const env[] = {"environment.png", "environment.hdr", NULL};
    const void *mesh_bytes, *env_bytes;
    size_t mesh_size, env_size;
    glass_mesh_format format = GLASS_MESH_GLTF;
    AAsset *mesh = open_asset(a, gltf, &mesh_bytes, &mesh_size), *image;
    snell_status st;
    if (!mesh) {
        mesh = open_asset(a, obj, &mesh_bytes, &mesh_size);
        format = GLASS_MESH_OBJ;
    }
    image = open_asset(a, env, &env_bytes, &env_size);
    /* glass_scene copies and decodes: the assets close right after */
    st = glass_scene_init(&a->scene, mesh_bytes, mesh_size, format, env_bytes, env_size);
    if (mesh) AAsset_close(mesh);
    if (image) AAsset_close(image);
    if (st != SNELL_OK) LOGE("assets: %s", a->scene.error);
    return st == SNELL_OK;
}

static void run_command(app *a)
{
    command c;
    ssize_t n = read(a->pipe_fd[0], &c, sizeof c);
    if (n != (ssize_t)sizeof c) {
        LOGE("command pipe: read %zd bytes: %s", n, strerror(errno));
        return;
    }
    if (c.kind == COMMAND_INPUT_QUEUE) {
        if (a->input) AInputQueue_detachLooper(a->input);
        a->input = c.queue;
        if (a->input) AInputQueue_attachLooper(a->input, a->looper, LOOPER_ID_INPUT, NULL, NULL);
    } else {
        if (c.event == LIFECYCLE_WINDOW_CREATED) {
            if (a->window) ANativeWindow_release(a->window);
            ANativeWindow_acquire(c.window);
            a->window = c.window;
        }
        step(a, c.event);
        if (c.event == LIFECYCLE_WINDOW_DESTROYED && a->window) {
            ANativeWindow_release(a->window);
            a->window = NULL;
        }
    }
    pthread_mutex_lock(&a->mutex);
    a->done++;
    pthread_cond_broadcast(&a->cond);
    pthread_mutex_unlock(&a->mutex);
}

static void *render_thread(void *arg)
{
    app *a = (app *)arg;
    clock_gettime(CLOCK_MONOTONIC, &a->start);
    lifecycle_init(&a->life);
    a->looper = ALooper_prepare(ALOOPER_PREPARE_ALLOW_NON_CALLBACKS);
    ALooper_addFd(a->looper, a->pipe_fd[0], LOOPER_ID_COMMAND, ALOOPER_EVENT_INPUT, NULL, NULL);
    if (!load_assets(a)) ANativeActivity_finish(a->activity);
    while (!a->life.destroyed) {
        /* block while there is nothing to draw; poll while drawing */
        int ident = ALooper_pollOnce(lifecycle_should_render(&a->life) ? 0 : -1, NULL, NULL, NULL);
        if (ident == LOOPER_ID_COMMAND) run_command(a);
        else if (ident == LOOPER_ID_INPUT) drain_input(a);
        if (lifecycle_should_render(&a->life)) draw_frame(a);
    }
    if (a->input) AInputQueue_detachLooper(a->input);
    if (a->window) ANativeWindow_release(a->window);
    video_under_stop(&a->video);
    glass_scene_free(&a->scene);
    if (a->jni_attached) (*a->activity->vm)->DetachCurrentThread(a->activity->vm);
    ALooper_removeFd(a->looper, a->pipe_fd[0]);
    pthread_mutex_lock(&a->mutex);
    a->exited = 1;
    pthread_cond_broadcast(&a->cond);
    pthread_mutex_unlock(&a->mutex);
    return NULL;
}

/* ------------------------------------------- main-thread callbacks */

/* Hands c to the render thread and waits until it has run it. */
static void post(ANativeActivity *activity, command c)
{
    app *a = (app *)activity->instance;
    unsigned seq;
    pthread_mutex_lock(&a->mutex);
    if (a->exited) {
        pthread_mutex_unlock(&a->mutex);
        return;
    }
    seq = ++a->posted;
    if (write(a->pipe_fd[1], &c, sizeof c) != (ssize_t)sizeof c) {
        LOGE("command pipe: %s", strerror(errno));
        a->posted--;
        pthread_mutex_unlock(&a->mutex);
        return;
    }
    while (a->done < seq && !a->exited) pthread_cond_wait(&a->cond, &a->mutex);
    pthread_mutex_unlock(&a->mutex);
}

static void post_event(ANativeActivity *activity, lifecycle_event ev, ANativeWindow *window)
{
    command c;
    memset(&c, 0, sizeof c);
    c.kind = COMMAND_LIFECYCLE;
    c.event = ev;
    c.window = window;
    post(activity, c);
}

static void post_queue(ANativeActivity *activity, AInputQueue *queue)
{
    command c;
    memset(&c, 0, sizeof c);
    c.kind = COMMAND_INPUT_QUEUE;
    c.queue = queue;
    post(activity, c);
}

static void on_start(ANativeActivity *activity) { post_event(activity, LIFECYCLE_START, NULL); }
static void on_resume(ANativeActivity *activity) { post_event(activity, LIFECYCLE_RESUME, NULL); }
static void on_pause(ANativeActivity *activity) { post_event(activity, LIFECYCLE_PAUSE, NULL); }
static void on_stop(ANativeActivity *activity) { post_event(activity, LIFECYCLE_STOP, NULL); }

static void on_window_created(ANativeActivity *activity, ANativeWindow *window)
{
    post_event(activity, LIFECYCLE_WINDOW_CREATED, window);
}

static void on_window_destroyed(ANativeActivity *activity, ANativeWindow *window)
{
    (void)window;
    post_event(activity, LIFECYCLE_WINDOW_DESTROYED, NULL);
}

static void on_input_queue_created(ANativeActivity *activity, AInputQueue *queue) { post_queue(activity, queue); }

static void on_input_queue_destroyed(ANativeActivity *activity, AInputQueue *queue)
{
    (void)queue;
    post_queue(activity, NULL);
}

static void on_destroy(ANativeActivity *activity)
{
    app *a = (app *)activity->instance;
    post_event(activity, LIFECYCLE_DESTROY, NULL);
    pthread_join(a->thread, NULL);
    close(a->pipe_fd[0]);
    close(a->pipe_fd[1]);
    pthread_cond_destroy(&a->cond);
    pthread_mutex_destroy(&a->mutex);
    free(a);
    activity->instance = NULL;
}

/* The scene's settings are its defaults and the assets: nothing to save. */
static void *on_save_instance_state(ANativeActivity *activity, size_t *out_size)
{
    (void)activity;
    *out_size = 0;
    return NULL;
}

JNIEXPORT void ANativeActivity_onCreate(ANativeActivity *activity, void *saved_state, size_t saved_state_size)
{
    app *a = (app *)calloc(1, sizeof *a);
    (void)saved_state;
    (void)saved_state_size;
    if (!a || pipe(a->pipe_fd) != 0) {
        LOGE("cannot start: %s", a ? strerror(errno) : "out of memory");
        free(a);
        ANativeActivity_finish(activity);
        return;
    }
    a->activity = activity;
    a->display = EGL_NO_DISPLAY;
    a->context = EGL_NO_CONTEXT;
    a->surface = EGL_NO_SURFACE;
    pthread_mutex_init(&a->mutex, NULL);
    pthread_cond_init(&a->cond, NULL);
    activity->instance = a;
    activity->callbacks->onStart = on_start;
    activity->callbacks->onResume = on_resume;
    activity->callbacks->onPause = on_pause;
    activity->callbacks->onStop = on_stop;
    activity->callbacks->onDestroy = on_destroy;
    activity->callbacks->onNativeWindowCreated = on_window_created;
    activity->callbacks->onNativeWindowDestroyed = on_window_destroyed;
    activity->callbacks->onInputQueueCreated = on_input_queue_created;
    activity->callbacks->onInputQueueDestroyed = on_input_queue_destroyed;
    activity->callbacks->onSaveInstanceState = on_save_instance_state;
    if (pthread_create(&a->thread, NULL, render_thread, a) != 0) {
        LOGE("cannot start the render thread");
        activity->instance = NULL;
        close(a->pipe_fd[0]);
        close(a->pipe_fd[1]);
        free(a);
        ANativeActivity_finish(activity);
    }
}
