/* SPDX-License-Identifier: MIT */
/* video_under — MediaPlayer -> Surface -> SurfaceTexture -> external texture (video_under.h). */
#include "video_under.h"

#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h> /* GL_TEXTURE_EXTERNAL_OES; after gl3.h, whose types it uses */
#include <android/log.h>
#include <string.h>

#define LOGI(...) __android_log_print(ANDROID_LOG_INFO, "snell", __VA_ARGS__)
#define LOGE(...) __android_log_print(ANDROID_LOG_ERROR, "snell", __VA_ARGS__)

/* A pending Java exception: logged and cleared; 1 if there was one. */
static int threw(JNIEnv *env, const char *what)
{
    if (!(*env)->ExceptionCheck(env)) return 0;
    (*env)->ExceptionDescribe(env); /* to the log, with its message */
    (*env)->ExceptionClear(env);
    LOGE("video: %s threw", what);
    return 1;
}

/* new CLASS(args) as a global reference, NULL on failure. */
static jobject make(JNIEnv *env, const char *cls, const char *sig, jvalue *args)
{
    jclass c = (*env)->FindClass(env, cls);
    jmethodID init = c ? (*env)->GetMethodID(env, c, "<init>", sig) : NULL;
    jobject local = init ? (*env)->NewObjectA(env, c, init, args) : NULL, global = NULL;
    if (!threw(env, cls) && local) global = (*env)->NewGlobalRef(env, local);
    if (local) (*env)->DeleteLocalRef(env, local);
    if (c) (*env)->DeleteLocalRef(env, c);
    return global;
}

/* obj.name(args) returning an object (local reference) or nothing; 0 if it threw. */
static int call(JNIEnv *env, jobject obj, const char *name, const char *sig, jvalue *args, jobject *result)
{
    jclass c = (*env)->GetObjectClass(env, obj);
    jmethodID m = (*env)->GetMethodID(env, c, name, sig);
    (*env)->DeleteLocalRef(env, c);
    if (!m || threw(env, name)) return 0;
    if (result)
        *result = (*env)->CallObjectMethodA(env, obj, m, args);
    else
        (*env)->CallVoidMethodA(env, obj, m, args);
    return !threw(env, name);
}

static jlong call_long(JNIEnv *env, jobject obj, const char *name)
{
    jclass c = (*env)->GetObjectClass(env, obj);
    jmethodID m = (*env)->GetMethodID(env, c, name, "()J");
    jlong r = m ? (*env)->CallLongMethod(env, obj, m) : -1;
    (*env)->DeleteLocalRef(env, c);
    return threw(env, name) ? -1 : r;
}

int video_under_start(video_under *v, ANativeActivity *activity, const char *asset)
{
    JNIEnv *env = NULL;
    jobject assets = NULL, afd = NULL, fd = NULL;
    jvalue a[3];
    jstring name;
    int ok = 0;
    memset(v, 0, sizeof *v);
    if ((*activity->vm)->AttachCurrentThread(activity->vm, &env, NULL) != JNI_OK) return 0;
    v->env = env;
    /* the texture the SurfaceTexture fills: external, sampled with a linear filter */
    glGenTextures(1, &v->texture);
    glBindTexture(GL_TEXTURE_EXTERNAL_OES, v->texture);
    glTexParameteri(GL_TEXTURE_EXTERNAL_OES, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_EXTERNAL_OES, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glBindTexture(GL_TEXTURE_EXTERNAL_OES, 0);
    /* AssetManager.openFd: the asset's file, offset and length inside the APK */
    name = (*env)->NewStringUTF(env, asset);
    a[0].l = name;
    if (!call(env, activity->clazz, "getAssets", "()Landroid/content/res/AssetManager;", NULL, &assets) || !assets ||
        !call(env, assets, "openFd", "(Ljava/lang/String;)Landroid/content/res/AssetFileDescriptor;", a, &afd) ||
        !afd || !call(env, afd, "getFileDescriptor", "()Ljava/io/FileDescriptor;", NULL, &fd) || !fd) {
        LOGI("video: no asset %s (stored uncompressed): the panels lie over the glass scene", asset);
        goto done;
    }
    a[0].i = (jint)v->texture;
    if (!(v->texture_object = make(env, "android/graphics/SurfaceTexture", "(I)V", a))) goto done;
    a[0].l = v->texture_object;
    if (!(v->surface = make(env, "android/view/Surface", "(Landroid/graphics/SurfaceTexture;)V", a))) goto done;
    if (!(v->player = make(env, "android/media/MediaPlayer", "()V", NULL))) goto done;
    a[0].l = fd;
    a[1].j = call_long(env, afd, "getStartOffset");
    a[2].j = call_long(env, afd, "getLength");
    if (!call(env, v->player, "setDataSource", "(Ljava/io/FileDescriptor;JJ)V", a, NULL)) goto done;
    a[0].l = v->surface;
    if (!call(env, v->player, "setSurface", "(Landroid/view/Surface;)V", a, NULL)) goto done;
    a[0].z = JNI_TRUE;
    if (!call(env, v->player, "setLooping", "(Z)V", a, NULL) || !call(env, v->player, "prepare", "()V", NULL, NULL) ||
        !call(env, v->player, "start", "()V", NULL, NULL))
        goto done;
    v->matrix = (jfloatArray)(*env)->NewGlobalRef(env, (*env)->NewFloatArray(env, 16));
    ok = v->matrix != NULL;
    if (ok) LOGI("video: %s playing into external texture %u", asset, v->texture);
done:
    if (afd) call(env, afd, "close", "()V", NULL, NULL);
    if (fd) (*env)->DeleteLocalRef(env, fd);
    if (afd) (*env)->DeleteLocalRef(env, afd);
    if (assets) (*env)->DeleteLocalRef(env, assets);
    (*env)->DeleteLocalRef(env, name);
    if (!ok) video_under_stop(v);
    return ok;
}

int video_under_frame(video_under *v, snell_panels_under *under)
{
    JNIEnv *env = v->env;
    if (!v->player) return 0;
    /* the newest decoded frame into the texture (this thread's current context) */
    if (!call(env, v->texture_object, "updateTexImage", "()V", NULL, NULL)) return 0;
    {
        jvalue a[1];
        a[0].l = v->matrix;
        if (!call(env, v->texture_object, "getTransformMatrix", "([F)V", a, NULL)) return 0;
    }
    memset(under, 0, sizeof *under);
    under->source = SNELL_PANELS_UNDER_EXTERNAL;
    under->texture = v->texture;
    under->draw = 1; /* the video drawn over the frame first, the panels over it */
    (*env)->GetFloatArrayRegion(env, v->matrix, 0, 16, under->uv_transform); /* column-major, as snell wants */
    return !threw(env, "GetFloatArrayRegion");
}

void video_under_stop(video_under *v)
{
    JNIEnv *env = v->env;
    if (env) {
        if (v->player) call(env, v->player, "release", "()V", NULL, NULL);
        if (v->surface) call(env, v->surface, "release", "()V", NULL, NULL);
        if (v->texture_object) call(env, v->texture_object, "release", "()V", NULL, NULL);
        if (v->player) (*env)->DeleteGlobalRef(env, v->player);
        if (v->surface) (*env)->DeleteGlobalRef(env, v->surface);
        if (v->texture_object) (*env)->DeleteGlobalRef(env, v->texture_object);
        if (v->matrix) (*env)->DeleteGlobalRef(env, v->matrix);
    }
    if (v->texture) glDeleteTextures(1, &v->texture); /* after a context loss the dead context ignores it */
    memset(v, 0, sizeof *v);
}
