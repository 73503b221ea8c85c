/* SPDX-License-Identifier: MIT */
/* bench_timer.c — GPU frame time with GL_EXT_disjoint_timer_query, when the
 * context has it (llvmpipe advertises it, but its query measures command
 * submission, not the deferred rasterisation: bench/BENCHMARKS.md; the wall
 * clock of render + glFinish is what snell-bench reports). One query in
 * flight at a time: the bench ends every frame with glFinish anyway. */
#include "bench_timer.h"

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>
#include <stddef.h>
#include <string.h>

static PFNGLGENQUERIESEXTPROC p_gen;
static PFNGLBEGINQUERYEXTPROC p_begin;
static PFNGLENDQUERYEXTPROC p_end;
static PFNGLGETQUERYOBJECTUIVEXTPROC p_get_u;
static PFNGLGETQUERYOBJECTUI64VEXTPROC p_get_u64;
static GLuint g_query;
static int g_ok;

/* A software rasteriser's timer query times the calls, not the pixels. */
static int software_rasteriser(const char *renderer)
{
    static const char *const names[] = {"llvmpipe", "softpipe", "SwiftShader", "swrast"};
    size_t k;
    for (k = 0; renderer && k < sizeof names / sizeof *names; k++)
        if (strstr(renderer, names[k])) return 1;
    return 0;
}

int bench_timer_init(snell_ctx *ctx)
{
    g_ok = 0;
    if (!snell_ctx_has_gl_extension(ctx, "GL_EXT_disjoint_timer_query")) return 0;
    if (software_rasteriser(snell_ctx_gl_renderer(ctx))) return -1;
    p_gen = (PFNGLGENQUERIESEXTPROC)eglGetProcAddress("glGenQueriesEXT");
    p_begin = (PFNGLBEGINQUERYEXTPROC)eglGetProcAddress("glBeginQueryEXT");
    p_end = (PFNGLENDQUERYEXTPROC)eglGetProcAddress("glEndQueryEXT");
    p_get_u = (PFNGLGETQUERYOBJECTUIVEXTPROC)eglGetProcAddress("glGetQueryObjectuivEXT");
    p_get_u64 = (PFNGLGETQUERYOBJECTUI64VEXTPROC)eglGetProcAddress("glGetQueryObjectui64vEXT");
    if (!p_gen || !p_begin || !p_end || !p_get_u || !p_get_u64) return 0;
    p_gen(1, &g_query);
    g_ok = g_query != 0;
    return g_ok;
}

void bench_timer_begin(void)
{
    if (g_ok) p_begin(GL_TIME_ELAPSED_EXT, g_query);
}

void bench_timer_end(void)
{
    if (g_ok) p_end(GL_TIME_ELAPSED_EXT);
}

double bench_timer_read(void)
{
    GLuint avail = 0;
    GLuint64 ns = 0;
    GLint disjoint = 0;
    if (!g_ok) return -1.0;
    /* The caller has called glFinish, so the result is available; check anyway. */
    p_get_u(g_query, GL_QUERY_RESULT_AVAILABLE_EXT, &avail);
    if (!avail) return -1.0;
    p_get_u64(g_query, GL_QUERY_RESULT_EXT, &ns);
    glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
    return disjoint ? -1.0 : (double)ns * 1e-6;
}
