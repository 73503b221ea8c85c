/* SPDX-License-Identifier: MIT */
/* snell_shaderdb — snell's programs and profiles against the GL driver it
 * runs on; made for Mesa's real GPU drivers over drm-shim
 * (bench/device_shaders.sh, shared/devices/env.sh), which compile with the
 * GPU's own compiler but draw nothing. Not a test: a tool (built with the
 * tests, it uses internals: the profile table and the precision policy).
 *
 *   snell-shaderdb limits [PROFILE]   the driver's value of every limit and
 *       extension of core/profile.c; with PROFILE, each one the profile
 *       promises beyond the driver (exit 1 if any)
 *   snell-shaderdb compile DIR HASH...   each DIR/<hash>.vert + .frag pair
 *       as tests dump them (SNELL_TEST_GLSL_DUMP), compiled, linked and drawn
 *       once
 *
 * compile writes everything, its own lines and the driver's statistics, to
 * stderr (stdout is made the same stream), unbuffered, so each program's
 * statistics fall between its "@shaderdb begin" and "@shaderdb end" lines:
 * drivers compile at link (freedreno's first variants) or at the first draw
 * (v3d, panfrost: the variant of the draw's state), so each program is drawn
 * and glFinish()ed before its end line. Drivers that report through KHR_debug
 * (freedreno's FD_MESA_DEBUG=shaderdb) land there too, as "@shaderdb debug"
 * lines: synchronous where Gallium's threaded context is off
 * (GALLIUM_THREAD=0, which bench/device_shaders.sh sets). */
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"

#include <EGL/egl.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAX_TARGETS 8

static void usage(void)
{
    fprintf(stderr, "usage: snell-shaderdb limits [PROFILE] | snell-shaderdb compile DIR HASH...\n");
    exit(2);
}

static int has_extension(const char *name)
{
    GLint n = 0, i;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (i = 0; i < n; i++)
        if (strcmp((const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i), name) == 0) return 1;
    return 0;
}

static int limits(const char *profile_name)
{
    const snell__profile *p = NULL;
    int i, over = 0;
    for (i = 0; profile_name && i < snell__profile_count; i++)
        if (strcmp(profile_name, snell__profiles[i].name) == 0) p = &snell__profiles[i];
    if (profile_name && !p) {
        fprintf(stderr, "snell-shaderdb: no device profile \"%s\" in core/profile.c\n", profile_name);
        return 2;
    }
    printf("renderer %s\n", (const char *)glGetString(GL_RENDERER));
    for (i = 0; i < SNELL__LIMITS; i++) {
        GLint v = 0;
        glGetIntegerv(snell__limit_enum[i], &v);
        printf("limit %s %d", snell_limit_str((snell_limit)i), (int)v);
        if (p) printf(" profile %d%s", p->limit[i], p->limit[i] > v ? " OVER" : "");
        printf("\n");
        over += p && p->limit[i] > v;
    }
    for (i = 0; i < SNELL__PROFILE_EXTS; i++) {
        int has = has_extension(snell__profile_ext[i]);
        printf("extension %s %s", snell__profile_ext[i], has ? "yes" : "no");
        if (p) printf(" profile %s%s", p->ext >> i & 1 ? "yes" : "no", p->ext >> i & 1 && !has ? " OVER" : "");
        printf("\n");
        over += p && p->ext >> i & 1 && !has;
    }
    if (p) printf("%s: %d promise(s) beyond the driver\n", p->name, over);
    return over ? 1 : 0;
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    long n;
    char *s = NULL;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (s = (char *)malloc((size_t)n + 1)) != NULL) {
        if (fread(s, 1, (size_t)n, f) != (size_t)n) {
            free(s);
            s = NULL;
        } else {
            s[n] = '\0';
        }
    }
    fclose(f);
    return s;
}

/* The dump holds the precision snell chose where it ran (highp on llvmpipe);
 * the device's own policy (core/program.c) replaces it. */
static char *with_precision(const char *src, int mediump)
{
    static const char key[] = "#define SNELL_MEDIUMP ";
    const char *p = strstr(src, key), *rest = NULL;
    size_t head;
    char *out;
    if (!p || !(rest = strchr(p, '\n'))) p = rest = src + strlen(src); /* no policy line: as it is */
    head = (size_t)(p - src);
    if (!(out = (char *)malloc(strlen(src) + sizeof key + 8))) return NULL;
    memcpy(out, src, head);
    if (p != rest) head += (size_t)sprintf(out + head, "%s%s", key, mediump ? "mediump" : "highp");
    strcpy(out + head, rest);
    return out;
}

/* One line: newlines of a driver's text become " | ". */
static void print_line(const char *kind, const char *what, const char *log)
{
    fprintf(stderr, "@shaderdb %s %s", kind, what);
    for (; *log; log++) {
        if (*log != '\n') fputc(*log, stderr);
        else if (log[1]) fputs(" | ", stderr);
    }
    fputc('\n', stderr);
}

static void print_error(const char *hash, const char *what, const char *log)
{
    char head[128];
    snprintf(head, sizeof head, "%s %s: ", hash, what);
    print_line("error", head, log);
}

static void GL_APIENTRY on_debug(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                 const GLchar *msg, const void *user)
{
    (void)source, (void)type, (void)id, (void)severity, (void)length, (void)user;
    print_line("debug", "", msg);
}

static GLuint compile_stage(const char *hash, GLenum type, const char *src)
{
    GLuint sh = glCreateShader(type);
    GLint ok = 0;
    glShaderSource(sh, 1, &src, NULL);
    glCompileShader(sh);
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = "";
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        print_error(hash, type == GL_VERTEX_SHADER ? "vertex compile" : "fragment compile", log);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

/* A draw validates only with each sampler on its own unit (a 2D and a cube
 * sampler on unit 0 fail it): one unit per sampler, in order. */
static void give_units(GLuint prog)
{
    static const GLenum samplers[] = {
        GL_SAMPLER_2D, GL_SAMPLER_3D, GL_SAMPLER_CUBE, GL_SAMPLER_2D_SHADOW, GL_SAMPLER_2D_ARRAY,
        GL_SAMPLER_2D_ARRAY_SHADOW, GL_SAMPLER_CUBE_SHADOW, GL_INT_SAMPLER_2D, GL_INT_SAMPLER_3D,
        GL_INT_SAMPLER_CUBE, GL_INT_SAMPLER_2D_ARRAY, GL_UNSIGNED_INT_SAMPLER_2D, GL_UNSIGNED_INT_SAMPLER_3D,
        GL_UNSIGNED_INT_SAMPLER_CUBE, GL_UNSIGNED_INT_SAMPLER_2D_ARRAY,
    };
    GLint n = 0, i, unit = 0;
    glGetProgramiv(prog, GL_ACTIVE_UNIFORMS, &n);
    for (i = 0; i < n; i++) {
        char name[256];
        GLint size = 0, k;
        GLenum type = 0;
        size_t t = 0;
        glGetActiveUniform(prog, (GLuint)i, sizeof name, NULL, &size, &type, name);
        while (t < sizeof samplers / sizeof samplers[0] && samplers[t] != type) t++;
        if (t == sizeof samplers / sizeof samplers[0]) continue;
        if (strchr(name, '[')) *strchr(name, '[') = '\0';
        for (k = 0; k < size; k++) {
            char element[300];
            snprintf(element, sizeof element, size > 1 ? "%s[%d]" : "%s", name, (int)k);
            glUniform1i(glGetUniformLocation(prog, element), unit++);
        }
    }
}

/* Compiles, links and draws one program; 0 if the driver refused it. */
static int program(const char *dir, const char *hash, int mediump)
{
    char path[1100];
    char *src[2] = {NULL, NULL};
    GLuint sh[2] = {0, 0}, prog = 0;
    GLint ok = 0;
    int i;
    for (i = 0; i < 2; i++) {
        char *text;
        snprintf(path, sizeof path, "%s/%s.%s", dir, hash, i ? "frag" : "vert");
        if (!(text = read_text(path)) || !(src[i] = with_precision(text, mediump))) {
            fprintf(stderr, "@shaderdb error %s read: cannot read %s\n", hash, path);
            free(text);
            free(src[0]);
            return 0;
        }
        free(text);
    }
    prog = glCreateProgram();
    fprintf(stderr, "@shaderdb begin %s GLSL%u\n", hash, prog);
    sh[0] = compile_stage(hash, GL_VERTEX_SHADER, src[0]);
    sh[1] = sh[0] ? compile_stage(hash, GL_FRAGMENT_SHADER, src[1]) : 0;
    free(src[0]);
    free(src[1]);
    if (sh[1]) {
        glAttachShader(prog, sh[0]);
        glAttachShader(prog, sh[1]);
        glBindAttribLocation(prog, 0, "a_position"); /* as core/program.c links */
        glBindAttribLocation(prog, 1, "a_normal");
        glLinkProgram(prog);
        glGetProgramiv(prog, GL_LINK_STATUS, &ok);
        if (!ok) {
            char log[4096] = "";
            glGetProgramInfoLog(prog, sizeof log, NULL, log);
            print_error(hash, "link", log);
        } else {
            glUseProgram(prog);
            give_units(prog);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glFinish();
            glUseProgram(0);
        }
    }
    glDeleteShader(sh[0]);
    glDeleteShader(sh[1]);
    glDeleteProgram(prog);
    fprintf(stderr, "@shaderdb end %s %s\n", hash, ok ? "ok" : "failed");
    return ok;
}

/* Targets for every draw buffer the driver has: each program's outputs land
 * on an RGBA8 target, as they would on the host's framebuffer. */
static void targets(void)
{
    GLuint fbo, tex[MAX_TARGETS];
    GLenum bufs[MAX_TARGETS];
    GLint n = 0, i;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &n);
    if (n > MAX_TARGETS) n = MAX_TARGETS;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenTextures(n, tex);
    for (i = 0; i < n; i++) {
        glBindTexture(GL_TEXTURE_2D, tex[i]);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, 4, 4);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)i, GL_TEXTURE_2D, tex[i], 0);
        bufs[i] = GL_COLOR_ATTACHMENT0 + (GLenum)i;
    }
    glDrawBuffers(n, bufs);
    glViewport(0, 0, 4, 4);
    glClear(GL_COLOR_BUFFER_BIT); /* the driver's own clear shaders before the first program */
    glFinish();
}

static int compile_all(snell_ctx *ctx, const char *dir, char **hashes, int n)
{
    int i, failed = 0, mediump = snell__ctx_fragment_mediump(ctx);
    dup2(2, 1); /* drivers that print to stdout land in order too */
    setvbuf(stderr, NULL, _IONBF, 0);
    fprintf(stderr, "@shaderdb device %s\n@shaderdb precision %s\n", (const char *)glGetString(GL_RENDERER),
            snell_ctx_precision(ctx));
    {
        PFNGLDEBUGMESSAGECALLBACKKHRPROC cb =
            (PFNGLDEBUGMESSAGECALLBACKKHRPROC)eglGetProcAddress("glDebugMessageCallbackKHR");
        PFNGLDEBUGMESSAGECONTROLKHRPROC control =
            (PFNGLDEBUGMESSAGECONTROLKHRPROC)eglGetProcAddress("glDebugMessageControlKHR");
        if (cb && control) {
            control(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, NULL, GL_TRUE); /* notifications too */
            glEnable(GL_DEBUG_OUTPUT_KHR);
            glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR);
            cb(on_debug, NULL);
        }
    }
    targets();
    for (i = 0; i < n; i++) failed += !program(dir, hashes[i], mediump);
    fprintf(stderr, "@shaderdb done %d programs, %d failed\n", n, failed);
    return failed ? 1 : 0;
}

int main(int argc, char **argv)
{
    snell_ctx *ctx = NULL;
    snell_ctx_desc d;
    int rc;
    if (argc < 2 || (strcmp(argv[1], "limits") == 0 ? argc > 3 : strcmp(argv[1], "compile") != 0 || argc < 4))
        usage();
    /* the driver's own limits and extensions, never a profile's */
    memset(&d, 0, sizeof d);
    d.device_profile = "";
    if (snell_ctx_create(&d, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-shaderdb: no GL context: %s\n", snell_last_error(NULL));
        return 2;
    }
    rc = strcmp(argv[1], "limits") == 0 ? limits(argc == 3 ? argv[2] : NULL) : compile_all(ctx, argv[2], argv + 3, argc - 3);
    snell_ctx_destroy(ctx);
    return rc;
}
