/* SPDX-License-Identifier: MIT */
/* android_glsurfaceview.c — glass in an Android GLSurfaceView: its renderer
 * thread holds the GLES 3.0 context (setEGLContextClientVersion(3), a config
 * with depth), and calls these through JNI from its Renderer:
 *   onSurfaceChanged(gl, w, h) -> GlassView.nativeResize(w, h)
 *   onDrawFrame(gl)            -> GlassView.nativeDraw(view, projection)
 * The context may be lost when the app pauses (setPreserveEGLContextOnPause);
 * a new one comes with onSurfaceCreated: open snell again there. The full
 * NativeActivity port is ports/android. */
#include "glass.h"

#include <GLES3/gl3.h>
#include <jni.h>

static glass_app g_glass;
static int g_open;

JNIEXPORT void JNICALL Java_com_example_glass_GlassView_nativeResize(JNIEnv *env, jclass cls, jint w, jint h)
{
    (void)env, (void)cls;
    if (g_open) glass_close(&g_glass);
    g_open = glass_open(&g_glass, w, h);
}

JNIEXPORT jboolean JNICALL Java_com_example_glass_GlassView_nativeDraw(JNIEnv *env, jclass cls, jfloatArray view,
                                                                       jfloatArray projection)
{
    float v[16], p[16];
    (void)cls;
    if (!g_open) return JNI_FALSE;
    (*env)->GetFloatArrayRegion(env, view, 0, 16, v);
    (*env)->GetFloatArrayRegion(env, projection, 0, 16, p);
    /* ... the app's scene drawn first, into the same framebuffer ... */
    return glass_draw(&g_glass, v, p) == SNELL_OK ? JNI_TRUE : JNI_FALSE;
}
