/* SPDX-License-Identifier: MIT */
/* gl_count.h — GL objects alive in the current context, counted by name
 * (glIs* over every name handed out so far): textures, buffers, framebuffers,
 * renderbuffers, vertex arrays, samplers, programs and shaders. Mesa hands
 * out names in increasing order without reusing them, so the range is found
 * by asking for one more name of each kind (then deleted). */
#ifndef SNELL_TEST_GL_COUNT_H
#define SNELL_TEST_GL_COUNT_H

#include <GLES3/gl3.h>
#include <stdio.h>

typedef struct gl_counts {
    int textures, buffers, framebuffers, renderbuffers, vertex_arrays, samplers, programs, shaders;
} gl_counts;

/* One past the highest name of each kind handed out so far. */
static inline GLuint gl_count_name_limit(void)
{
    GLuint n[7], top = 0;
    int i;
    glGenTextures(1, &n[0]);
    glGenBuffers(1, &n[1]);
    glGenFramebuffers(1, &n[2]);
    glGenRenderbuffers(1, &n[3]);
    glGenVertexArrays(1, &n[4]);
    glGenSamplers(1, &n[5]);
    n[6] = glCreateShader(GL_VERTEX_SHADER); /* shaders and programs share names */
    for (i = 0; i < 7; i++)
        if (n[i] > top) top = n[i];
    glDeleteTextures(1, &n[0]);
    glDeleteBuffers(1, &n[1]);
    glDeleteFramebuffers(1, &n[2]);
    glDeleteRenderbuffers(1, &n[3]);
    glDeleteVertexArrays(1, &n[4]);
    glDeleteSamplers(1, &n[5]);
    glDeleteShader(n[6]);
    return top + 64;
}

static inline gl_counts gl_count_objects(void)
{
    gl_counts c = {0, 0, 0, 0, 0, 0, 0, 0};
    GLuint n, limit = gl_count_name_limit();
    for (n = 1; n < limit; n++) {
        c.textures += glIsTexture(n) == GL_TRUE;
        c.buffers += glIsBuffer(n) == GL_TRUE;
        c.framebuffers += glIsFramebuffer(n) == GL_TRUE;
        c.renderbuffers += glIsRenderbuffer(n) == GL_TRUE;
        c.vertex_arrays += glIsVertexArray(n) == GL_TRUE;
        c.samplers += glIsSampler(n) == GL_TRUE;
        c.programs += glIsProgram(n) == GL_TRUE;
        c.shaders += glIsShader(n) == GL_TRUE;
    }
    return c;
}

static inline int gl_counts_equal(const gl_counts *a, const gl_counts *b)
{
    return a->textures == b->textures && a->buffers == b->buffers && a->framebuffers == b->framebuffers &&
           a->renderbuffers == b->renderbuffers && a->vertex_arrays == b->vertex_arrays &&
           a->samplers == b->samplers && a->programs == b->programs && a->shaders == b->shaders;
}

static inline int gl_counts_total(const gl_counts *c)
{
    return c->textures + c->buffers + c->framebuffers + c->renderbuffers + c->vertex_arrays + c->samplers +
           c->programs + c->shaders;
}

static inline void gl_counts_print(FILE *f, const char *label, const gl_counts *c)
{
    fprintf(f, "%s: %d textures, %d buffers, %d framebuffers, %d renderbuffers, %d vertex arrays, %d samplers, "
               "%d programs, %d shaders\n",
            label, c->textures, c->buffers, c->framebuffers, c->renderbuffers, c->vertex_arrays, c->samplers,
            c->programs, c->shaders);
}

#endif
