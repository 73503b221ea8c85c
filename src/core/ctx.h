/* SPDX-License-Identifier: MIT */
/* ctx.h — the context: allocator, logging, the platform backend that owns (or
 * borrows) the EGL context, GL capabilities probed once, and saved GL state. */
#ifndef SNELL_CTX_H
#define SNELL_CTX_H

#include "core/core.h"
#include "core/platform.h"
#include "core/profile.h"
#include "core/device_cost.h"

struct snell_ctx {
    snell_alloc alloc;
    snell_log_fn log;
    void *log_user;
    snell_backend backend;          /* the one in use after fallbacks */
    snell_platform platform;
    char gl_renderer[128];
    char *gl_extensions;            /* space-separated, with a leading and trailing space */
    const snell__profile *profile;  /* the device profile in force, NULL none (profile.c) */
    int limit[SNELL__LIMITS];       /* the GL context's limits, lowered to the profile's */
    int limit_raw[SNELL__LIMITS];   /* the GL context's own */
    const char *profile_trace;      /* SNELL_PROFILE_TRACE: a file each profile-bound answer is appended to */
    const snell__device_cost *cost; /* the GPU's method costs, NULL: the rung tables' (device_cost.h) */
    int has_khr_debug;              /* asked where a log callback would get its messages (ctx.c) */
    int light_fixed;                /* snell__light_fixed's answer: 0 not asked yet, 1 yes, -1 no */
    int debug_installed;
    void *host_debug[2];            /* the KHR_debug callback and user pointer snell's replaced */
    char last_error[1024];
    int fragment_mediump;           /* shader precision policy (program.c): 0 unknown, 1 mediump, -1 highp */
    char precision_reason[96];
    size_t memory_budget;           /* resolved, never 0 (snell_ctx_desc.memory_budget; core.h) */
    /* Lifetime: the caller's handle and every object made with the context
     * (or drawn in it: a CPU-only mesh) hold a reference. snell_ctx_destroy
     * releases the GL context at once and the handle's reference; the struct
     * (allocator, messages) lives until the last object is destroyed. */
    int refs;
    int destroyed;                  /* snell_ctx_destroy was called: GL calls must not reach it */
    void *gl_context;               /* the context it draws in (owned or the host's; snell__platform_current) */
    /* The most any program given units here asked for (frame/textures.c):
     * samplers, and uniform vectors counted without packing (a mat4 is 4,
     * a float 1), each with the program that asked. test_units checks them
     * against GLES 3.0's minimums. */
    struct {
        int programs, samplers, vectors;
        char samplers_of[48], vectors_of[48];
    } census;
    /* Tests only: sees each shader's final source (stage: GL_VERTEX_SHADER
     * or GL_FRAGMENT_SHADER) before it is compiled (program.c). */
    void (*on_source)(snell_ctx *ctx, unsigned stage, const char *source);
    void *on_source_user;
};

/* An object takes (retain) and gives back (release) a reference; ctx may be
 * NULL. The last release of a destroyed context frees it. */
void snell__ctx_retain(snell_ctx *ctx);
void snell__ctx_release(snell_ctx *ctx);

/* SNELL_OK if ctx is alive and its GL context is current on this thread, else
 * SNELL_E_INVALID_ARG with a message starting with who. For calls that draw or
 * create GL objects: drawing in whatever context happens to be current gives
 * misleading GL errors or touches another context's objects. */
snell_status snell__ctx_check_current(snell_ctx *ctx, const char *who);

/* 1 where no blendable 32-bit float target exists: light maps in RGB10_A2
 * (light_map.h). Asked at first use, so only what uses light maps asks. */
int snell__light_fixed(snell_ctx *ctx);

/* Destroy paths: snell__gl_scope_enter returns 1 when GL deletions reach
 * ctx's own GL context (current already, or an owned one made current for the
 * moment); otherwise 0, with no context current until snell__gl_scope_leave,
 * so GL calls made meanwhile are ignored (the context is gone, or an EXTERNAL
 * one that is not current: its objects stay with it). leave puts back
 * whatever was current before. */
typedef struct snell__gl_scope {
    EGLDisplay display, used_display; /* a GLX host's: its Display */
    EGLSurface draw, read;
    EGLContext context;               /* a GLX host's: its GLXContext */
    const snell__glx *glx;            /* the context's GLX calls, NULL: EGL */
    unsigned long glx_draw, glx_read;
    int switched;
} snell__gl_scope;
int snell__gl_scope_enter(snell_ctx *ctx, snell__gl_scope *s);
void snell__gl_scope_leave(const snell__gl_scope *s);

#endif
