/* SPDX-License-Identifier: MIT */
/* video_under — a video from the APK's assets played into a SurfaceTexture
 * whose GL_TEXTURE_EXTERNAL_OES lies under the glass panels: Java's
 * MediaPlayer and SurfaceTexture through JNI (the NativeActivity has no Java
 * code of its own). Lives as long as one EGL context; render thread only. */
#ifndef SNELL_ANDROID_VIDEO_UNDER_H
#define SNELL_ANDROID_VIDEO_UNDER_H

#include <android/native_activity.h>
#include <jni.h>
#include <snell/snell.h>

typedef struct video_under {
    JNIEnv *env; /* the render thread's, attached to the VM */
    jobject texture_object; /* android.graphics.SurfaceTexture (global reference) */
    jobject surface; /* android.view.Surface over it */
    jobject player; /* android.media.MediaPlayer */
    jfloatArray matrix; /* getTransformMatrix's 16 floats */
    unsigned texture; /* the GL_TEXTURE_EXTERNAL_OES name */
} video_under;

/* Starts asset (e.g. "panels.mp4", stored uncompressed) playing in a loop
 * into a new external texture of the current context. 0 when the asset is
 * absent or the player refuses it (logged, nothing left behind). */
int video_under_start(video_under *v, ANativeActivity *activity, const char *asset);
/* Latches the newest video frame and describes it as what lies under the
 * panels (EXTERNAL, drawn first, uv_transform = the SurfaceTexture's). */
int video_under_frame(video_under *v, snell_panels_under *under);
/* Stops the player and frees the texture (a no-op when not started). */
void video_under_stop(video_under *v);

#endif
