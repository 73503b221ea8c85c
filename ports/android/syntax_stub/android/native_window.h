/* SPDX-License-Identifier: MIT */
/* SYNTAX-CHECK STUB, not part of any build: Debian's Android header packages
 * lack <android/native_window.h> (and <android/rect.h>), which the NDK has.
 * These are the NDK's declarations of what the port and <android/
 * native_activity.h> use, as the NDK documents them (API level 9 and later);
 * an NDK build uses the NDK's own header instead. */
#ifndef SNELL_SYNTAX_STUB_ANDROID_NATIVE_WINDOW_H
#define SNELL_SYNTAX_STUB_ANDROID_NATIVE_WINDOW_H

#include <stdint.h>
#include <sys/cdefs.h>

__BEGIN_DECLS

/* <android/rect.h> */
typedef struct ARect {
    int32_t left;
    int32_t top;
    int32_t right;
    int32_t bottom;
} ARect;

enum ANativeWindow_LegacyFormat {
    WINDOW_FORMAT_RGBA_8888 = 1,
    WINDOW_FORMAT_RGBX_8888 = 2,
    WINDOW_FORMAT_RGB_565 = 4
};

struct ANativeWindow;
typedef struct ANativeWindow ANativeWindow;

void ANativeWindow_acquire(ANativeWindow *window);
void ANativeWindow_release(ANativeWindow *window);
int32_t ANativeWindow_getWidth(ANativeWindow *window);
int32_t ANativeWindow_getHeight(ANativeWindow *window);
int32_t ANativeWindow_getFormat(ANativeWindow *window);
int32_t ANativeWindow_setBuffersGeometry(ANativeWindow *window, int32_t width, int32_t height, int32_t format);

__END_DECLS

#endif
