/* SPDX-License-Identifier: MIT */
/* device_cost_glmark2.c — compiles glmark2's refract scene's two programs as glmark2-es2 does, for
 * bench/device_cost.py's anchor (issue 46 item 2): GLSL ES 1.00 with glmark2's precision header, pass 1
 * depth.vert/depth.frag (the back faces' normals into a colour target over a depth texture: the distance
 * map), pass 2 light-refract.vert/.frag with RefractiveIndex and LightSourcePosition as uniforms (as in
 * ../shared/devices/README.md's first measurement). Each program draws one triangle into an RGBA8 target
 * with depth, so that a driver compiling at draw compiles it; markers "@@LINK+ P" / "@@LINK- P name"
 * bracket each program's compile and draw on stderr, between them the driver's own statistics. */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DIR "/usr/share/glmark2/shaders/"

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    long n;
    char *s;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    s = (char *)calloc((size_t)n + 1, 1);
    if (s && fread(s, 1, (size_t)n, f) != (size_t)n) s[0] = '\0';
    fclose(f);
    return s;
}

static GLuint shader(GLenum type, const char *prefix, const char *path)
{
    char *body = slurp(path);
    const char *parts[2];
    GLuint sh = glCreateShader(type);
    GLint ok = 0;
    if (!body) {
        fprintf(stderr, "device_cost_glmark2: cannot read %s\n", path);
        exit(2);
    }
    parts[0] = prefix;
    parts[1] = body;
    glShaderSource(sh, 2, parts, NULL);
    glCompileShader(sh);
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        fprintf(stderr, "device_cost_glmark2: %s: %s\n", path, log);
        exit(2);
    }
    free(body);
    return sh;
}

static void program(const char *name, const char *vs, const char *fs, const char *fs_prefix)
{
    static const char vprefix[] = "#ifdef GL_ES\nprecision highp float;\n#endif\n";
    static const float tri[] = {-1, -1, 0, 3, -1, 0, -1, 3, 0};
    GLuint p = glCreateProgram();
    GLint ok = 0;
    fprintf(stderr, "@@LINK+ %u\n", p);
    glAttachShader(p, shader(GL_VERTEX_SHADER, vprefix, vs));
    glAttachShader(p, shader(GL_FRAGMENT_SHADER, fs_prefix, fs));
    glBindAttribLocation(p, 0, "position");
    glBindAttribLocation(p, 1, "normal");
    glLinkProgram(p);
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        fprintf(stderr, "device_cost_glmark2: link %s failed\n", name);
        exit(2);
    }
    glUseProgram(p);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, tri);
    glEnableVertexAttribArray(0);
    glVertexAttrib3f(1, 0.0f, 0.0f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    fprintf(stderr, "@@LINK- %u %s\n", p, name);
}

int main(void)
{
    static const char fprefix[] = "#ifdef GL_ES\nprecision mediump float;\n#endif\n";
    static const char refract_prefix[] = "#ifdef GL_ES\nprecision mediump float;\n#endif\n"
                                         "uniform float RefractiveIndex;\nuniform vec4 LightSourcePosition;\n";
    static const EGLint cfg_attr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_NONE};
    static const EGLint ctx_attr[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay d = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL) : NULL;
    EGLConfig cfg;
    EGLint n = 0;
    EGLContext c;
    GLuint fbo, tex, depth;
    if (!d || !eglInitialize(d, NULL, NULL) || !eglBindAPI(EGL_OPENGL_ES_API) ||
        !eglChooseConfig(d, cfg_attr, &cfg, 1, &n) || n < 1) {
        fprintf(stderr, "device_cost_glmark2: no surfaceless EGL display\n");
        return 2;
    }
    c = eglCreateContext(d, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (c == EGL_NO_CONTEXT || !eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
        fprintf(stderr, "device_cost_glmark2: no GLES 2 context\n");
        return 2;
    }
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 64, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, 64, 64);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    glViewport(0, 0, 64, 64);
    glEnable(GL_DEPTH_TEST);
    program("glmark2-depth", DIR "depth.vert", DIR "depth.frag", fprefix);
    program("glmark2-refract", DIR "light-refract.vert", DIR "light-refract.frag", refract_prefix);
    eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglTerminate(d);
    return 0;
}
