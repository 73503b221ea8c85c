/* SPDX-License-Identifier: MIT */
/* glsl_dump_preload.c — LD_PRELOAD into any program using snell (snell-render,
 * snell-bench): with SNELL_GLSL_DUMP=DIR every program it links is written as
 * DIR/<hash>.vert + .frag, the form of the tests' SNELL_TEST_GLSL_DUMP
 * (tests/test_util.c), for bench/device_shaders.sh --defaults. With
 * SNELL_GLSL_DUMP_RENDERER=S glGetString(GL_RENDERER) says S, so that snell
 * takes that GPU's decisions (core/device_cost.c) on another driver. */
#define _GNU_SOURCE
#include <GLES3/gl3.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_IDS 4096

static char *g_source[MAX_IDS];        /* each shader's source, by shader name */
static GLuint g_vert[MAX_IDS], g_frag[MAX_IDS]; /* each program's attached shaders */

static void *real(const char *name)
{
    void *f = dlsym(RTLD_NEXT, name);
    if (!f) {
        fprintf(stderr, "glsl_dump_preload: no %s after this library\n", name);
        abort();
    }
    return f;
}

GL_APICALL const GLubyte *GL_APIENTRY glGetString(GLenum name)
{
    static const GLubyte *(GL_APIENTRY * next)(GLenum);
    const char *renderer = getenv("SNELL_GLSL_DUMP_RENDERER");
    if (!next) *(void **)&next = real("glGetString");
    if (name == GL_RENDERER && renderer && *renderer) return (const GLubyte *)renderer;
    return next(name);
}

GL_APICALL void GL_APIENTRY glShaderSource(GLuint shader, GLsizei count, const GLchar *const *string,
                                           const GLint *length)
{
    static void(GL_APIENTRY * next)(GLuint, GLsizei, const GLchar *const *, const GLint *);
    size_t n = 0, at = 0;
    GLsizei i;
    if (!next) *(void **)&next = real("glShaderSource");
    next(shader, count, string, length);
    if (shader >= MAX_IDS) return;
    for (i = 0; i < count; i++) n += length && length[i] >= 0 ? (size_t)length[i] : strlen(string[i]);
    free(g_source[shader]);
    if (!(g_source[shader] = (char *)malloc(n + 1))) return;
    for (i = 0; i < count; i++) {
        size_t k = length && length[i] >= 0 ? (size_t)length[i] : strlen(string[i]);
        memcpy(g_source[shader] + at, string[i], k);
        at += k;
    }
    g_source[shader][n] = '\0';
}

GL_APICALL void GL_APIENTRY glAttachShader(GLuint program, GLuint shader)
{
    static void(GL_APIENTRY * next)(GLuint, GLuint);
    GLint type = 0;
    if (!next) *(void **)&next = real("glAttachShader");
    next(program, shader);
    glGetShaderiv(shader, GL_SHADER_TYPE, &type);
    if (program >= MAX_IDS) return;
    if (type == GL_VERTEX_SHADER) g_vert[program] = shader;
    if (type == GL_FRAGMENT_SHADER) g_frag[program] = shader;
}

/* test_util.c's name: FNV-1a over the vertex source, then the fragment's. */
static unsigned long long fnv64(unsigned long long h, const char *s)
{
    for (; *s; s++) h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return h;
}

static void write_file(const char *dir, unsigned long long h, const char *ext, const char *text)
{
    char path[1024];
    FILE *f;
    snprintf(path, sizeof path, "%s/%016llx.%s", dir, h, ext);
    if (!(f = fopen(path, "w")) || fputs(text, f) < 0 || fclose(f) != 0)
        fprintf(stderr, "glsl_dump_preload: cannot write %s\n", path);
}

GL_APICALL void GL_APIENTRY glLinkProgram(GLuint program)
{
    static void(GL_APIENTRY * next)(GLuint);
    const char *dir = getenv("SNELL_GLSL_DUMP");
    const char *vs, *fs;
    GLint ok = 0;
    if (!next) *(void **)&next = real("glLinkProgram");
    next(program);
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!dir || !*dir || !ok || program >= MAX_IDS || g_vert[program] >= MAX_IDS || g_frag[program] >= MAX_IDS)
        return;
    vs = g_source[g_vert[program]];
    fs = g_source[g_frag[program]];
    if (!vs || !fs) return;
    write_file(dir, fnv64(fnv64(14695981039346656037ull, vs), fs), "vert", vs);
    write_file(dir, fnv64(fnv64(14695981039346656037ull, vs), fs), "frag", fs);
}
