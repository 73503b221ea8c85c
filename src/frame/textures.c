/* SPDX-License-Identifier: MIT */
/* textures.c — see textures.h. */
#include "frame/textures.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"

#include <stdio.h>
#include <string.h>

unsigned snell__sampler_hash(const char *name)
{
    unsigned h = 2166136261u; /* FNV-1a */
    for (; *name; name++) h = (h ^ (unsigned char)*name) * 16777619u;
    return h;
}

void snell__textures_publish(snell__textures *ts, const char *name, unsigned target, unsigned texture,
                             unsigned sampler)
{
    unsigned h = snell__sampler_hash(name);
    int i;
    for (i = 0; i < ts->count && ts->t[i].hash != h; i++) {}
    if (i == SNELL__FRAME_TEXTURES) return; /* more names than the table holds: a build-time mistake, see test_units */
    if (i == ts->count) ts->count++;
    ts->t[i].name = name;
    ts->t[i].hash = h;
    ts->t[i].target = target;
    ts->t[i].texture = texture;
    ts->t[i].sampler = sampler;
}

static int is_sampler(GLenum type)
{
    switch (type) {
    case GL_SAMPLER_2D: case GL_SAMPLER_3D: case GL_SAMPLER_CUBE: case GL_SAMPLER_2D_SHADOW:
    case GL_SAMPLER_2D_ARRAY: case GL_SAMPLER_2D_ARRAY_SHADOW: case GL_SAMPLER_CUBE_SHADOW:
    case GL_INT_SAMPLER_2D: case GL_INT_SAMPLER_3D: case GL_INT_SAMPLER_CUBE: case GL_INT_SAMPLER_2D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D: case GL_UNSIGNED_INT_SAMPLER_3D: case GL_UNSIGNED_INT_SAMPLER_CUBE:
    case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY:
        return 1;
    default: return 0;
    }
}

/* Rows of uniform storage a uniform of this type takes, unpacked. */
static int vectors_of(GLenum type)
{
    switch (type) {
    case GL_FLOAT_MAT2: case GL_FLOAT_MAT2x3: case GL_FLOAT_MAT2x4: return 2;
    case GL_FLOAT_MAT3: case GL_FLOAT_MAT3x2: case GL_FLOAT_MAT3x4: return 3;
    case GL_FLOAT_MAT4: case GL_FLOAT_MAT4x2: case GL_FLOAT_MAT4x3: return 4;
    default: return 1;
    }
}

snell_status snell__samplers_assign(snell_ctx *ctx, unsigned prog, const char *what, snell__samplers *s)
{
    GLint n = 0, max_units = ctx->limit[SNELL__LIM_UNITS], current = 0, i;
    char names[512] = "";
    int count = 0, vectors = 0;
    glGetProgramiv(prog, GL_ACTIVE_UNIFORMS, &n);
    if (max_units > SNELL__PROGRAM_SAMPLERS) max_units = SNELL__PROGRAM_SAMPLERS;
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    glUseProgram(prog);
    memset(s, 0, sizeof *s);
    for (i = 0; i < n; i++) {
        char name[64];
        GLint size = 0;
        GLenum type = 0;
        size_t len;
        glGetActiveUniform(prog, (GLuint)i, sizeof name, NULL, &size, &type, name);
        if (!is_sampler(type)) {
            vectors += vectors_of(type) * size;
            continue;
        }
        len = strlen(names);
        snprintf(names + len, sizeof names - len, "%s%s", count ? ", " : "", name);
        if (count < max_units) {
            s->hash[count] = snell__sampler_hash(name);
            glUniform1i(glGetUniformLocation(prog, name), count);
        }
        count++;
    }
    /* the program in use before, unless it was deleted while in use */
    glUseProgram(current && glIsProgram((GLuint)current) ? (GLuint)current : 0);
    ctx->census.programs++;
    if (count > ctx->census.samplers) {
        ctx->census.samplers = count;
        snprintf(ctx->census.samplers_of, sizeof ctx->census.samplers_of, "%s", what);
    }
    if (vectors > ctx->census.vectors) {
        ctx->census.vectors = vectors;
        snprintf(ctx->census.vectors_of, sizeof ctx->census.vectors_of, "%s", what);
    }
    if (!snell__ctx_fits(ctx, SNELL__LIM_UNITS, count) || count > SNELL__PROGRAM_SAMPLERS)
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "%s samples %d textures, more than the %d units the context has: %s",
                           what, count, max_units, names);
    /* counted over both stages: within the fragment limit (GLES 3.0: 224, below
     * the vertex stage's 256; core/profile.c), each stage fits its own */
    if (snell__ctx_limit(ctx, SNELL__LIM_FRAG_VECTORS, vectors, what) != SNELL_OK) return SNELL_E_UNSUPPORTED;
    s->count = count;
    return SNELL_OK;
}

int snell__samplers_unit(const snell__samplers *s, const char *name)
{
    unsigned h = snell__sampler_hash(name);
    int i;
    for (i = 0; i < s->count; i++)
        if (s->hash[i] == h) return i;
    return -1;
}

/* Binds on unit, leaving that unit active. */
static void bind_unit(int unit, unsigned target, unsigned texture, unsigned sampler)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(target, texture);
    if (sampler) glBindSampler((GLuint)unit, sampler);
}

void snell__samplers_bind(const snell__samplers *s, const char *name, unsigned target, unsigned texture,
                          unsigned sampler)
{
    int unit = snell__samplers_unit(s, name);
    if (unit < 0) return;
    bind_unit(unit, target, texture, sampler);
    glActiveTexture(GL_TEXTURE0);
}

void snell__samplers_bind_published(const snell__samplers *s, const snell__textures *ts)
{
    int i, j;
    for (i = 0; i < s->count; i++)
        for (j = 0; j < ts->count; j++)
            if (ts->t[j].hash == s->hash[i]) {
                bind_unit(i, ts->t[j].target, ts->t[j].texture, ts->t[j].sampler);
                break;
            }
    glActiveTexture(GL_TEXTURE0);
}

/* A frame's units scope can follow every unit a program may take. */
typedef char snell__samplers_fit_units[SNELL__PROGRAM_SAMPLERS <= SNELL__UNITS_MAX ? 1 : -1];
