/* SPDX-License-Identifier: MIT */
/* program.c — shader assembly (#include of embedded chunks), compile, link,
 * with the info log carried into the error message. */
#include "core/program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/shaders_embedded.h"

#include <pthread.h>
#include <stdio.h>
#include <string.h>

#define MAX_INCLUDES 16

/* The table programs are built from: the embedded (stripped) one, or the
 * readable one test_shader_strip sets. Programs already built keep theirs. */
static const snell_shader_file *g_shader_table = snell_shader_files;

void snell__shader_table_set(const snell_shader_file *table) { g_shader_table = table ? table : snell_shader_files; }

/* Unpacks tools/shader_pack.c's stream; 0 if it does not fill the output
 * exactly (never reads or writes outside either). */
static int lz_unpack(const unsigned char *in, size_t n, char *out, size_t size)
{
    size_t i = 0, o = 0;
    while (i < n) {
        unsigned token = in[i++];
        size_t lit = token >> 4, len = token & 15, off;
        if (lit == 15)
            do {
                if (i >= n) return 0;
                lit += in[i];
            } while (in[i++] == 255);
        if (lit > n - i || lit > size - o) return 0;
        memcpy(out + o, in + i, lit);
        i += lit, o += lit;
        if (i == n) break; /* the last sequence: literals only */
        if (n - i < 2) return 0;
        off = (size_t)in[i] | (size_t)in[i + 1] << 8;
        i += 2;
        if (len == 15)
            do {
                if (i >= n) return 0;
                len += in[i];
            } while (in[i++] == 255);
        len += 4;
        if (off == 0 || off > o || len > size - o) return 0;
        for (; len > 0; len--, o++) out[o] = out[o - off]; /* overlapping copies repeat */
    }
    return o == size;
}

static pthread_once_t g_unpack_once = PTHREAD_ONCE_INIT;
static int g_unpacked_ok;

static void unpack_embedded(void)
{
    const snell_shader_pack *p = &snell_shader_files_pack;
    g_unpacked_ok = !p->packed || lz_unpack(p->packed, p->packed_size, p->unpacked, p->size);
}

const char *snell__shader_source(const char *path)
{
    const snell_shader_file *f;
    /* Unpacked on the first program a process builds (on any thread): a
     * failure would be a build fault, and every look-up then finds nothing. */
    pthread_once(&g_unpack_once, unpack_embedded);
    if (!g_unpacked_ok && g_shader_table == snell_shader_files) return NULL;
    for (f = g_shader_table; f->path; f++)
        if (strcmp(f->path, path) == 0) return f->source;
    return NULL;
}

/* The table's own copy of a chunk's path (static storage). */
static const char *table_path(const char *source)
{
    const snell_shader_file *f;
    for (f = g_shader_table; f->path; f++)
        if (f->source == source) return f->path;
    return "";
}

typedef struct text_buf {
    const snell_alloc *al;
    char *data;
    size_t len, cap;
    int failed;
} text_buf;

static void buf_append(text_buf *b, const char *s, size_t n)
{
    if (b->failed) return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = (b->cap ? b->cap * 2 : 4096);
        char *p;
        while (cap < b->len + n + 1) cap *= 2;
        p = (char *)snell__realloc(b->al, b->data, cap);
        if (!p) { b->failed = 1; return; }
        b->data = p;
        b->cap = cap;
    }
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = '\0';
}

/* Appends src, replacing `#include "path"` lines by the embedded chunk
 * (each chunk once, nesting allowed). Returns nonzero on a missing chunk. */
static int expand(snell_ctx *ctx, text_buf *b, const char *src, const char **seen, int *n_seen)
{
    const char *line = src;
    while (*line) {
        const char *end = strchr(line, '\n');
        size_t n = end ? (size_t)(end - line + 1) : strlen(line);
        const char *p = line;
        while (*p == ' ' || *p == '\t') p++;
        if (strncmp(p, "#include", 8) == 0) {
            char path[128];
            const char *q = strchr(p, '"'), *r = q ? strchr(q + 1, '"') : NULL;
            const char *chunk;
            int i, dup = 0;
            if (!q || !r || (size_t)(r - q - 1) >= sizeof path) {
                snell__fail(ctx, SNELL_E_GL, "malformed #include line in shader source");
                return 1;
            }
            memcpy(path, q + 1, (size_t)(r - q - 1));
            path[r - q - 1] = '\0';
            for (i = 0; i < *n_seen; i++) dup |= strcmp(seen[i], path) == 0;
            if (!dup) {
                chunk = snell__shader_source(path);
                if (!chunk || *n_seen >= MAX_INCLUDES) {
                    snell__fail(ctx, SNELL_E_GL, "shader chunk \"%s\" not found", path);
                    return 1;
                }
                seen[(*n_seen)++] = table_path(chunk); /* outlives this frame */
                if (expand(ctx, b, chunk, seen, n_seen)) return 1;
                buf_append(b, "\n", 1);
            }
        } else {
            buf_append(b, line, n);
        }
        line += n;
    }
    return 0;
}

/* "#version 300 es" + defines + FP16 emulation switch + expanded source.
 * NULL on failure, with *st set (SNELL_E_GL for a bad #include, SNELL_E_NOMEM). */
/* The precision policy (docs/ARCHITECTURE.md "Shaders"): SNELL_MEDIUMP is what shaders
 * write for values a GPU with real fp16 holds at mediump. Software
 * rasterisers emulate fp16 for mediump (llvmpipe: slower than highp,
 * bench/BENCHMARKS.md), and a driver whose mediump
 * is as precise as highp gains nothing from it: both get highp. */
static int fragment_mediump(snell_ctx *ctx)
{
    GLint range[2] = {0, 0}, bits = 0;
    const char *software;
    if (!ctx) return 1;
    if (ctx->fragment_mediump) return ctx->fragment_mediump > 0;
#ifdef SNELL_FP16_EMULATION
    ctx->fragment_mediump = 1; /* the study build: mediump as a phone has it */
    snprintf(ctx->precision_reason, sizeof ctx->precision_reason, "mediump: SNELL_FP16_EMULATION build");
    return 1;
#endif
    if ((software = snell__software_rasteriser(ctx->gl_renderer)) != NULL) {
        ctx->fragment_mediump = -1;
        snprintf(ctx->precision_reason, sizeof ctx->precision_reason, "highp: %s emulates mediump in software",
                 software);
        return 0;
    }
    glGetShaderPrecisionFormat(GL_FRAGMENT_SHADER, GL_MEDIUM_FLOAT, range, &bits);
    ctx->fragment_mediump = bits >= 23 ? -1 : 1;
    snprintf(ctx->precision_reason, sizeof ctx->precision_reason, "%s: fragment mediump has %d mantissa bits",
             bits >= 23 ? "highp" : "mediump", (int)bits);
    return ctx->fragment_mediump > 0;
}

const char *snell_ctx_precision(snell_ctx *ctx)
{
    if (!ctx) return "mediump: no context";
    fragment_mediump(ctx);
    return ctx->precision_reason;
}

int snell__ctx_fragment_mediump(snell_ctx *ctx) { return fragment_mediump(ctx); }

static char *assemble(snell_ctx *ctx, const char *defines, const char *src, snell_status *st)
{
    text_buf b;
    const char *seen[MAX_INCLUDES];
    int n_seen = 0;
    static const char header[] = "#version 300 es\n";
    memset(&b, 0, sizeof b);
    b.al = snell__ctx_alloc(ctx);
    buf_append(&b, header, sizeof header - 1);
    {
        const char *policy = fragment_mediump(ctx) ? "#define SNELL_MEDIUMP mediump\n" : "#define SNELL_MEDIUMP highp\n";
        buf_append(&b, policy, strlen(policy));
    }
#ifdef SNELL_FP16_EMULATION
    {
        static const char fp16[] = "#define SNELL_FP16_EMULATION 1\n";
        buf_append(&b, fp16, sizeof fp16 - 1);
    }
#endif
    if (ctx && ctx->light_fixed) {
        static const char fixed[] = "#define SNELL_LIGHT_RANGE 8.0\n"; /* SNELL__LIGHT_RANGE, core/glstate.h */
        buf_append(&b, fixed, sizeof fixed - 1);
    }
    if (defines) buf_append(&b, defines, strlen(defines));
    if (!b.failed && expand(ctx, &b, src, seen, &n_seen)) {
        snell__free(b.al, b.data);
        *st = SNELL_E_GL;
        return NULL;
    }
    if (b.failed) {
        snell__free(b.al, b.data);
        *st = snell__fail(ctx, SNELL_E_NOMEM, "out of memory assembling a shader");
        return NULL;
    }
    *st = SNELL_OK;
    return b.data;
}

static snell_status compile(snell_ctx *ctx, GLenum type, const char *defines, const char *src,
                            GLuint *out)
{
    snell_status st;
    char *full = assemble(ctx, defines, src, &st);
    GLuint sh;
    GLint ok = 0;
    if (!full) return st;
    sh = glCreateShader(type);
    glShaderSource(sh, 1, (const GLchar *const *)&full, NULL);
    glCompileShader(sh);
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (ok && ctx && ctx->on_source) ctx->on_source(ctx, type, full); /* what compiled (tests' deliberate errors not) */
    snell__free(snell__ctx_alloc(ctx), full);
    if (!ok) {
        char log[768];
        log[0] = '\0';
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        glDeleteShader(sh);
        return snell__fail(ctx, SNELL_E_GL, "%s shader compile failed: %s",
                           type == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
    }
    *out = sh;
    return SNELL_OK;
}

static snell_status link_program(snell_ctx *ctx, GLuint vs, GLuint fs, const char *const *varyings,
                                 int n_varyings, unsigned *out)
{
    GLuint prog = glCreateProgram();
    GLint ok = 0;
    glAttachShader(prog, vs);
    glAttachShader(prog, fs);
    glBindAttribLocation(prog, 0, "a_position");
    glBindAttribLocation(prog, 1, "a_normal");
    if (n_varyings > 0) glTransformFeedbackVaryings(prog, n_varyings, varyings, GL_SEPARATE_ATTRIBS);
    glLinkProgram(prog);
    glDeleteShader(vs);
    glDeleteShader(fs);
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[768];
        log[0] = '\0';
        glGetProgramInfoLog(prog, sizeof log, NULL, log);
        glDeleteProgram(prog);
        return snell__fail(ctx, SNELL_E_GL, "program link failed: %s", log);
    }
    *out = prog;
    return SNELL_OK;
}

snell_status snell__program_build_src(snell_ctx *ctx, const char *vs_src, const char *fs_src,
                                      const char *defines, unsigned *out_program)
{
    GLuint vs = 0, fs = 0;
    snell_status st;
    if (!vs_src || !fs_src || !out_program)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "program build: missing source");
    st = compile(ctx, GL_VERTEX_SHADER, defines, vs_src, &vs);
    if (st != SNELL_OK) return st;
    st = compile(ctx, GL_FRAGMENT_SHADER, defines, fs_src, &fs);
    if (st != SNELL_OK) {
        glDeleteShader(vs);
        return st;
    }
    return link_program(ctx, vs, fs, NULL, 0, out_program);
}

snell_status snell__program_build(snell_ctx *ctx, const char *vs_path, const char *fs_path,
                                  const char *defines, unsigned *out_program)
{
    const char *vs = snell__shader_source(vs_path), *fs = snell__shader_source(fs_path);
    if (!vs || !fs)
        return snell__fail(ctx, SNELL_E_GL, "embedded shader \"%s\" not found", vs ? fs_path : vs_path);
    return snell__program_build_src(ctx, vs, fs, defines, out_program);
}

snell_status snell__program_build_feedback(snell_ctx *ctx, const char *vs_src, const char *defines,
                                           const char *const *varyings, int n_varyings,
                                           unsigned *out_program)
{
    static const char fs_src[] = "precision mediump float;\nout vec4 o;\nvoid main() { o = vec4(0.0); }\n";
    GLuint vs = 0, fs = 0;
    snell_status st = compile(ctx, GL_VERTEX_SHADER, defines, vs_src, &vs);
    if (st != SNELL_OK) return st;
    st = compile(ctx, GL_FRAGMENT_SHADER, NULL, fs_src, &fs);
    if (st != SNELL_OK) {
        glDeleteShader(vs);
        return st;
    }
    return link_program(ctx, vs, fs, varyings, n_varyings, out_program);
}
