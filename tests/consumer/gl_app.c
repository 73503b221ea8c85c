/* SPDX-License-Identifier: MIT */
/* An app that calls EGL and GLES itself beside snell, its project linking
 * snell::snell alone (find_package in tests/consumer, add_subdirectory in
 * tests/subproject): the target gives it EGL and GLES, so the link needs no
 * library of its own ("DSO missing from command line" otherwise). */
#include <snell/snell.h>
#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <stdio.h>

int main(void)
{
    snell_ctx *ctx = NULL;
    const GLubyte *version;
    int ok;
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK) {
        fprintf(stderr, "gl_app: %s\n", snell_last_error(NULL));
        return 1;
    }
    version = glGetString(GL_VERSION);
    ok = version != NULL && eglGetCurrentContext() != EGL_NO_CONTEXT;
    printf("gl_app %s: %s\n", ok ? "ok" : "FAILED", version ? (const char *)version : "no GL");
    snell_ctx_destroy(ctx);
    return ok ? 0 : 1;
}
