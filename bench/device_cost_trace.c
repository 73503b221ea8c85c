/* SPDX-License-Identifier: MIT */
/* device_cost_trace.c — a GL call trace for bench/device_cost.py (issue 46 item 2).
 *
 * Linked into a copy of snell-render with -Wl,--wrap= for the GL calls below and
 * snell_render (bench/device_cost.sh builds it): nothing in src/ changes. It writes
 * lines starting "@@" on stderr, so that they interleave with a Mesa driver's own
 * shader statistics and disassembly there:
 *
 *   @@LINK+ P / @@LINK- P      around glLinkProgram of program P (a driver's compile at link sits between)
 *   @@DRAW+ P ... / @@DRAW- P  around every draw (a driver's variant compile at draw sits between):
 *                              viewport, the draw framebuffer's colour bytes per pixel (all draw buffers),
 *                              depth/stencil bytes, depth test and write, blend, and with SNELL_COST_COUNT=1
 *                              the fragments the draw shaded and each source loop's body executions
 *   @@FRAME n                  before the n-th snell_render call
 *   @@BLIT w h                 a glBlitFramebuffer of w x h pixels
 * A draw's "pass" is a render pass as a tiler sees it: it changes at every glBindFramebuffer (draw),
 * attachment change, glDrawBuffers and blit; "cleared 1": a colour clear came before the pass's first draw.
 *
 * SNELL_COST_DUMP=DIR writes every linked program's sources, DIR/pP.vert and DIR/pP.frag, as compiled.
 * SNELL_COST_COUNT=1 (llvmpipe only: it needs GLES 3.1 storage buffers) counts on the real rasteriser
 * (SNELL_COST_COUNT=2: the fragments alone, much faster where loops run long):
 * every fragment shader is compiled as GLSL ES 3.10 with a storage buffer of counters: [0] += 1 at the
 * start of main (early fragment tests where the shader neither discards nor writes depth, as a GPU's early
 * depth test would), [1 + i] += 1 at the start of the i-th loop body of the source (comments stripped;
 * loops whose body is not a braced block are not counted). The draw's counters are read back after it.
 * Counting perturbs timing, never what is drawn. SNELL_COST_RENDERER=NAME: glGetString(GL_RENDERER) says NAME.
 */
#define _POSIX_C_SOURCE 200809L
#include <GLES3/gl31.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SH 4096
#define NCOUNT 64

typedef struct snell_renderer snell_renderer;
typedef struct snell_frame_desc snell_frame_desc;
typedef struct snell_frame_stats snell_frame_stats;
int __real_snell_render(snell_renderer *r, const snell_frame_desc *f, snell_frame_stats *st);

const GLubyte *__real_glGetString(GLenum name);
void __real_glShaderSource(GLuint sh, GLsizei n, const GLchar *const *s, const GLint *len);
void __real_glAttachShader(GLuint p, GLuint sh);
void __real_glLinkProgram(GLuint p);
void __real_glDrawArrays(GLenum mode, GLint first, GLsizei count);
void __real_glBindFramebuffer(GLenum target, GLuint fb);
void __real_glFramebufferTexture2D(GLenum target, GLenum att, GLenum textarget, GLuint tex, GLint level);
void __real_glFramebufferTextureLayer(GLenum target, GLenum att, GLuint tex, GLint level, GLint layer);
void __real_glFramebufferRenderbuffer(GLenum target, GLenum att, GLenum rbtarget, GLuint rb);
void __real_glDrawBuffers(GLsizei n, const GLenum *bufs);
void __real_glClear(GLbitfield mask);
void __real_glClearBufferfv(GLenum buffer, GLint drawbuffer, const GLfloat *value);
void __real_glBlitFramebuffer(GLint a, GLint b, GLint c, GLint d, GLint e, GLint f, GLint g, GLint h, GLbitfield m,
                              GLenum filter);
void __real_glDrawElements(GLenum mode, GLsizei count, GLenum type, const void *idx);

static char *src_of[MAX_SH];   /* original source per shader id */
static GLuint vs_of[MAX_SH], fs_of[MAX_SH];
static int loops_of[MAX_SH];   /* counted loops per fragment shader id / per program */
static int frame_no;
static GLuint counter_buf;
/* A render pass as a tiler sees it: a new one at every change of the draw framebuffer or its attachments;
 * cleared: a clear came before its first draw (nothing to load). */
static unsigned pass_epoch = 1, cleared_epoch;
static int drawn_in_epoch;

static void new_pass(void)
{
    pass_epoch++;
    drawn_in_epoch = 0;
}

void __wrap_glBindFramebuffer(GLenum target, GLuint fb)
{
    if (target != GL_READ_FRAMEBUFFER) new_pass();
    __real_glBindFramebuffer(target, fb);
}

void __wrap_glFramebufferTexture2D(GLenum target, GLenum att, GLenum textarget, GLuint tex, GLint level)
{
    if (target != GL_READ_FRAMEBUFFER) new_pass();
    __real_glFramebufferTexture2D(target, att, textarget, tex, level);
}

void __wrap_glFramebufferTextureLayer(GLenum target, GLenum att, GLuint tex, GLint level, GLint layer)
{
    if (target != GL_READ_FRAMEBUFFER) new_pass();
    __real_glFramebufferTextureLayer(target, att, tex, level, layer);
}

void __wrap_glFramebufferRenderbuffer(GLenum target, GLenum att, GLenum rbtarget, GLuint rb)
{
    if (target != GL_READ_FRAMEBUFFER) new_pass();
    __real_glFramebufferRenderbuffer(target, att, rbtarget, rb);
}

void __wrap_glDrawBuffers(GLsizei n, const GLenum *bufs)
{
    new_pass();
    __real_glDrawBuffers(n, bufs);
}

void __wrap_glClear(GLbitfield mask)
{
    if (!drawn_in_epoch && (mask & GL_COLOR_BUFFER_BIT)) cleared_epoch = pass_epoch;
    __real_glClear(mask);
}

void __wrap_glClearBufferfv(GLenum buffer, GLint drawbuffer, const GLfloat *value)
{
    if (!drawn_in_epoch && buffer == GL_COLOR) cleared_epoch = pass_epoch;
    __real_glClearBufferfv(buffer, drawbuffer, value);
}

void __wrap_glBlitFramebuffer(GLint a, GLint b, GLint c, GLint d, GLint e, GLint f, GLint g, GLint h, GLbitfield m,
                              GLenum filter)
{
    fprintf(stderr, "@@BLIT %d %d\n", c - a, d - b);
    new_pass();
    __real_glBlitFramebuffer(a, b, c, d, e, f, g, h, m, filter);
}

/* SNELL_COST_COUNT: 0 off, 1 fragments and loop bodies, 2 fragments only (no atomics in loops: fast) */
static int counting(void)
{
    static int c = -1;
    if (c < 0) c = getenv("SNELL_COST_COUNT") ? atoi(getenv("SNELL_COST_COUNT")) : 0;
    return c;
}

/* SNELL_COST_RENDERER: the GL_RENDERER snell sees, so that llvmpipe takes a device's decisions (a tiler's
 * shading, AUTO's device costs) while it counts; with SNELL_DEVICE_PROFILE its limits and formats too. */
const GLubyte *__wrap_glGetString(GLenum name)
{
    const char *r = getenv("SNELL_COST_RENDERER");
    if (name == GL_RENDERER && r && *r) return (const GLubyte *)r;
    return __real_glGetString(name);
}

int __wrap_snell_render(snell_renderer *r, const snell_frame_desc *f, snell_frame_stats *st)
{
    fprintf(stderr, "@@FRAME %d\n", frame_no++);
    return __real_snell_render(r, f, st);
}

/* The source with comments blanked (newlines kept). */
static char *strip_comments(const char *s)
{
    size_t n = strlen(s), i;
    char *o = (char *)malloc(n + 1);
    memcpy(o, s, n + 1);
    for (i = 0; i < n; i++) {
        if (o[i] == '/' && o[i + 1] == '/') {
            while (i < n && o[i] != '\n') o[i++] = ' ';
        } else if (o[i] == '/' && o[i + 1] == '*') {
            o[i] = o[i + 1] = ' ';
            for (i += 2; i < n && !(o[i] == '*' && o[i + 1] == '/'); i++)
                if (o[i] != '\n') o[i] = ' ';
            if (i < n) o[i] = o[i + 1] = ' ', i++;
        }
    }
    return o;
}

static int ident(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }

/* Appends to a growing buffer. */
typedef struct { char *d; size_t n, cap; } buf;
static void put(buf *b, const char *s, size_t n)
{
    if (b->n + n + 1 > b->cap) {
        b->cap = (b->n + n + 1) * 2;
        b->d = (char *)realloc(b->d, b->cap);
    }
    memcpy(b->d + b->n, s, n);
    b->n += n;
    b->d[b->n] = '\0';
}
static void puts_(buf *b, const char *s) { put(b, s, strlen(s)); }

/* The counting variant of a fragment shader's source; *loops: loop bodies counted. */
static char *instrument(const char *orig, int *loops)
{
    char *s = strip_comments(orig);
    buf b = {0, 0, 0};
    size_t n = strlen(s), i = 0, decl_at = 0;
    int nl = 0, early = !strstr(s, "discard") && !strstr(s, "gl_FragDepth");
    char tmp[160];
    const char *v = strstr(s, "#version 300 es");
    const char *p;
    /* the declarations go after the last #extension line (or the #version line) */
    for (p = s; (p = strstr(p, "#extension")) != NULL; p++) decl_at = (size_t)(p - s);
    if (!decl_at && v) decl_at = (size_t)(v - s);
    while (decl_at < n && s[decl_at] != '\n') decl_at++;
    if (decl_at < n) decl_at++;
    while (i < n) {
        if (i == decl_at) {
            puts_(&b, "layout(std430, binding = 0) buffer SnellCostCounts { highp uint snell_cost_c[64]; };\n");
            if (early) puts_(&b, "layout(early_fragment_tests) in;\n");
        }
        if (v && s + i == v) {
            puts_(&b, "#version 310 es");
            i += strlen("#version 300 es");
            continue;
        }
        if ((!i || !ident(s[i - 1])) && (!strncmp(s + i, "for", 3) || !strncmp(s + i, "while", 5))) {
            size_t k = i + (s[i] == 'f' ? 3 : 5), j;
            int depth = 0;
            while (k < n && (s[k] == ' ' || s[k] == '\t' || s[k] == '\n')) k++;
            if (k < n && s[k] == '(' && !ident(s[i + (s[i] == 'f' ? 3 : 5)])) {
                for (j = k; j < n; j++) {
                    if (s[j] == '(') depth++;
                    else if (s[j] == ')' && --depth == 0) break;
                }
                for (j++; j < n && (s[j] == ' ' || s[j] == '\t' || s[j] == '\n'); j++) {}
                if (j < n && s[j] == '{' && nl + 1 < NCOUNT && counting() == 1) {
                    put(&b, s + i, j + 1 - i);
                    snprintf(tmp, sizeof tmp, " atomicAdd(snell_cost_c[%d], 1u);", ++nl);
                    puts_(&b, tmp);
                    i = j + 1;
                    continue;
                }
            }
        }
        if (!strncmp(s + i, "void main", 9)) {
            const char *brace = strchr(s + i, '{');
            if (brace) {
                size_t j = (size_t)(brace - s);
                put(&b, s + i, j + 1 - i);
                puts_(&b, " atomicAdd(snell_cost_c[0], 1u);");
                i = j + 1;
                continue;
            }
        }
        put(&b, s + i, 1);
        i++;
    }
    free(s);
    *loops = nl;
    return b.d;
}

void __wrap_glShaderSource(GLuint sh, GLsizei n, const GLchar *const *s, const GLint *len)
{
    buf b = {0, 0, 0};
    GLint type = 0;
    GLsizei i;
    for (i = 0; i < n; i++) put(&b, s[i], len && len[i] >= 0 ? (size_t)len[i] : strlen(s[i]));
    if (sh < MAX_SH) {
        free(src_of[sh]);
        src_of[sh] = strdup(b.d ? b.d : "");
    }
    glGetShaderiv(sh, GL_SHADER_TYPE, &type);
    if (counting() && type == GL_FRAGMENT_SHADER && b.d && strstr(b.d, "#version 300 es")) {
        int loops = 0;
        char *ins = instrument(b.d, &loops);
        const GLchar *one = ins;
        if (sh < MAX_SH) loops_of[sh] = loops;
        __real_glShaderSource(sh, 1, &one, NULL);
        free(ins);
    } else if (counting() && b.d && strstr(b.d, "#version 300 es")) {
        char *v = strstr(b.d, "#version 300 es");
        const GLchar *one = b.d;
        memcpy(v, "#version 310 es", 15); /* a program's shaders share one version */
        __real_glShaderSource(sh, 1, &one, NULL);
    } else {
        __real_glShaderSource(sh, n, s, len);
    }
    free(b.d);
}

void __wrap_glAttachShader(GLuint p, GLuint sh)
{
    GLint type = 0;
    glGetShaderiv(sh, GL_SHADER_TYPE, &type);
    if (p < MAX_SH) {
        if (type == GL_FRAGMENT_SHADER) fs_of[p] = sh;
        else vs_of[p] = sh;
    }
    __real_glAttachShader(p, sh);
}

static void dump(GLuint p, GLuint sh, const char *ext)
{
    const char *dir = getenv("SNELL_COST_DUMP");
    char path[512];
    FILE *f;
    if (!dir || !sh || sh >= MAX_SH || !src_of[sh]) return;
    snprintf(path, sizeof path, "%s/p%u.%s", dir, p, ext);
    if ((f = fopen(path, "w")) != NULL) {
        fputs(src_of[sh], f);
        fclose(f);
    }
}

void __wrap_glLinkProgram(GLuint p)
{
    fprintf(stderr, "@@LINK+ %u\n", p);
    __real_glLinkProgram(p);
    fprintf(stderr, "@@LINK- %u loops %d\n", p, p < MAX_SH && fs_of[p] < MAX_SH ? loops_of[fs_of[p]] : 0);
    if (p < MAX_SH) {
        dump(p, vs_of[p], "vert");
        dump(p, fs_of[p], "frag");
        if (fs_of[p] < MAX_SH) loops_of[p] = loops_of[fs_of[p]];
    }
}

/* Bytes per pixel of one attachment of the draw framebuffer. */
static int attachment_bytes(GLenum att)
{
    GLint type = GL_NONE, sz[6] = {0, 0, 0, 0, 0, 0}, i, sum = 0;
    static const GLenum q[6] = {GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, GL_FRAMEBUFFER_ATTACHMENT_GREEN_SIZE,
                                GL_FRAMEBUFFER_ATTACHMENT_BLUE_SIZE, GL_FRAMEBUFFER_ATTACHMENT_ALPHA_SIZE,
                                GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE};
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type == GL_NONE) return 0;
    for (i = 0; i < 6; i++) {
        if ((att == GL_DEPTH_ATTACHMENT && i != 4) || (att == GL_STENCIL_ATTACHMENT && i != 5)) continue;
        if (att != GL_DEPTH_ATTACHMENT && att != GL_STENCIL_ATTACHMENT && i >= 4) continue;
        glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, att, q[i], &sz[i]);
        sum += sz[i];
    }
    return (sum + 7) / 8;
}

static void draw_begin(const char *kind, GLenum mode, GLsizei count)
{
    GLint prog = 0, vp[4] = {0, 0, 0, 0}, fbo = 0, i, color = 0, nbuf = 0, dt, dm, bl, obj = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    glGetIntegerv(GL_VIEWPORT, vp);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    if (fbo) {
        for (i = 0; i < 4; i++) {
            GLint db = GL_NONE;
            glGetIntegerv(GL_DRAW_BUFFER0 + i, &db);
            if (db >= GL_COLOR_ATTACHMENT0 && db < GL_COLOR_ATTACHMENT0 + 8) {
                color += attachment_bytes((GLenum)db);
                nbuf++;
            }
        }
        glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                              GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &obj);
    } else {
        color = 4;
        nbuf = 1;
    }
    dt = glIsEnabled(GL_DEPTH_TEST);
    glGetIntegerv(GL_DEPTH_WRITEMASK, &dm);
    bl = glIsEnabled(GL_BLEND);
    fprintf(stderr, "@@DRAW+ %d %s mode %u count %d fbo %d tex %d vp %d %d color_bytes %d buffers %d depth_bytes %d "
            "stencil_bytes %d depth_test %d depth_write %d blend %d pass %u cleared %d\n",
            prog, kind, mode, count, fbo, obj, vp[2], vp[3], color, nbuf,
            fbo ? attachment_bytes(GL_DEPTH_ATTACHMENT) : 0, fbo ? attachment_bytes(GL_STENCIL_ATTACHMENT) : 0, dt,
            dm, bl, pass_epoch, cleared_epoch == pass_epoch);
    drawn_in_epoch = 1;
    if (counting()) {
        static GLuint zero[NCOUNT];
        if (!counter_buf) {
            glGenBuffers(1, &counter_buf);
            glBindBuffer(GL_SHADER_STORAGE_BUFFER, counter_buf);
            glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof zero, zero, GL_DYNAMIC_READ);
        }
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, counter_buf);
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, zero);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, counter_buf);
    }
}

static void draw_end(void)
{
    GLint prog = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    if (counting() && counter_buf) {
        const GLuint *c;
        int i, n = prog < MAX_SH ? loops_of[prog] : 0;
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, counter_buf);
        c = (const GLuint *)glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, NCOUNT * sizeof(GLuint), GL_MAP_READ_BIT);
        if (c) {
            fprintf(stderr, "@@COUNT %d fragments %u loops", prog, c[0]);
            for (i = 1; i <= n; i++) fprintf(stderr, " %u", c[i]);
            fprintf(stderr, "\n");
            glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
        }
    }
    fprintf(stderr, "@@DRAW- %d\n", prog);
}

void __wrap_glDrawArrays(GLenum mode, GLint first, GLsizei count)
{
    draw_begin("arrays", mode, count);
    __real_glDrawArrays(mode, first, count);
    draw_end();
}

void __wrap_glDrawElements(GLenum mode, GLsizei count, GLenum type, const void *idx)
{
    draw_begin("elements", mode, count);
    __real_glDrawElements(mode, count, type, idx);
    draw_end();
}
