/* SPDX-License-Identifier: MIT */
/* program.c — shader assembly (#include of embedded chunks), compile, link,
 * with the info log carried into the error message. */
#include "core/program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/shaders_embedded.h"

#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define MAX_INCLUDES 16

/* The table programs are built from: the embedded (stripped) one, or the
 * readable one test_shader_strip sets. Programs already built keep theirs. */
static const snell_shader_file *g_shader_table = snell_shader_files;

void snell__shader_table_set(const snell_shader_file *table) { g_shader_table = table ? table : snell_shader_files; }

/* Unpacks tools/shader_pack.c's stream (LZ77 coded by an adaptive binary
 * range coder; the format and the model's layout are described there and
 * must match); 0 if it does not fill the output exactly (never reads or
 * writes outside either). */
enum { /* the model: 11-bit probabilities, offsets into lz_probs */
    LZ_IS_MATCH = 0, LZ_IS_REP = 3, LZ_LIT = 6, LZ_LEN = LZ_LIT + 8 * 256, LZ_SLOT = LZ_LEN + 2 * 274,
    LZ_EXTRA = LZ_SLOT + 4 * 64, LZ_PROBS = LZ_EXTRA + 48 * 24
};
typedef struct lz_dec {
    const unsigned char *in;
    size_t n, i;
    uint32_t range, code;
    uint16_t p[LZ_PROBS];
} lz_dec;

static unsigned lz_bit(lz_dec *d, unsigned k)
{
    uint16_t *p = &d->p[k];
    uint32_t bound = (d->range >> 11) * *p;
    unsigned bit = d->code >= bound;
    if (bit) {
        d->code -= bound;
        d->range -= bound;
        *p = (uint16_t)(*p - (*p >> 5));
    } else {
        d->range = bound;
        *p = (uint16_t)(*p + ((2048 - *p) >> 5));
    }
    if (d->range < 1u << 24) { /* past the end reads zeros; the caller checks i */
        d->range <<= 8;
        d->code = d->code << 8 | (d->i < d->n ? d->in[d->i] : 0);
        d->i++;
    }
    return bit;
}

/* An nbits-bit value, most significant bit first, each bit's probability
 * picked by the bits above it (a bit tree at p[1 .. 2^nbits)). */
static unsigned lz_tree(lz_dec *d, unsigned k, int nbits)
{
    unsigned m = 1;
    while (nbits-- > 0) m = m << 1 | lz_bit(d, k + m);
    return m;
}

/* A match length - 2: 0..7, 8..15 or 16..271 (choice bits at k, k + 1). */
static unsigned lz_len(lz_dec *d, unsigned k)
{
    if (!lz_bit(d, k)) return lz_tree(d, k + 2, 3) - 8;
    if (!lz_bit(d, k + 1)) return lz_tree(d, k + 10, 3);
    return lz_tree(d, k + 18, 8) - 256 + 16;
}

static int lz_unpack(const unsigned char *in, size_t n, char *out, size_t size)
{
    static lz_dec d; /* 11 KB of model: once per process, under pthread_once */
    size_t o = 0, rep0 = 0;
    unsigned state = 0, k;
    d.in = in, d.n = n, d.i = 0, d.range = 0xFFFFFFFFu, d.code = 0;
    for (k = 0; k < LZ_PROBS; k++) d.p[k] = 1024;
    for (k = 0; k < 5; k++) d.code = d.code << 8 | (d.i < n ? in[d.i] : 0), d.i++;
    while (o < size) {
        size_t len;
        if (!lz_bit(&d, LZ_IS_MATCH + state)) { /* a literal, in the context of the byte before */
            out[o] = (char)(lz_tree(&d, LZ_LIT + (o ? (unsigned char)out[o - 1] >> 5 : 0) * 256, 8) - 256);
            o++;
            state = 0;
            continue;
        }
        if (lz_bit(&d, LZ_IS_REP + state)) { /* the last match's distance again */
            len = lz_len(&d, LZ_LEN + 274) + 2;
            state = 2;
        } else {
            unsigned slot, dist;
            int nb;
            len = lz_len(&d, LZ_LEN) + 2;
            slot = lz_tree(&d, LZ_SLOT + (len < 5 ? (unsigned)len - 2 : 3) * 64, 6) - 64;
            dist = slot;
            if (slot >= 4) {
                if (slot >= 48) return 0;
                nb = (int)(slot >> 1) - 1;
                dist = (2 | (slot & 1)) << nb;
                while (nb-- > 0) dist += lz_bit(&d, LZ_EXTRA + slot * 24 + (unsigned)nb) << nb;
            }
            rep0 = (size_t)dist + 1;
            state = 1;
        }
        if (rep0 == 0 || rep0 > o || len > size - o) return 0;
        for (; len > 0; len--, o++) out[o] = out[o - rep0]; /* overlapping copies repeat */
    }
    return d.i <= n;
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

/* Inserts s at pos: what comes after moves on. */
static void buf_insert(text_buf *b, size_t pos, const char *s, size_t n)
{
    size_t tail = b->len - pos;
    buf_append(b, s, n); /* grows it */
    if (b->failed) return;
    memmove(b->data + pos + n, b->data + pos, tail);
    memcpy(b->data + pos, s, n);
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
    size_t mark;
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
    mark = b.len;
    if (defines) buf_append(&b, defines, strlen(defines));
    if (!b.failed && expand(ctx, &b, src, seen, &n_seen)) {
        snell__free(b.al, b.data);
        *st = SNELL_E_GL;
        return NULL;
    }
    /* only a program that reads light maps asks for their format */
    if (!b.failed && ctx && strstr(b.data + mark, "SNELL_LIGHT_RANGE") && snell__light_fixed(ctx)) {
        static const char fixed[] = "#define SNELL_LIGHT_RANGE 8.0\n"; /* SNELL__LIGHT_RANGE, core/light_map.h */
        buf_insert(&b, mark, fixed, sizeof fixed - 1);
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
