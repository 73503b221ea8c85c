/* SPDX-License-Identifier: MIT */
/* profile.c — the device profiles' table (see profile.h) and the limit check.
 * Each value comes from the source named beside it; where no driver source
 * states a value, the profile keeps the GLES 3.0 minimum ("min"), so a
 * profile is never more generous than its device. ctest device_profiles
 * checks the three with open drivers against what those report
 * (bench/device_shaders.sh --profiles). */
#include "core/profile.h"
#include "core/ctx.h"
#include "core/gl.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char snell__profile_ext[SNELL__PROFILE_EXTS][31] = {
    "GL_EXT_color_buffer_float", "GL_EXT_color_buffer_half_float", "GL_EXT_float_blend",
    "GL_EXT_disjoint_timer_query", "GL_KHR_debug", "GL_OES_texture_float_linear",
};
#define CBF 1
#define TIMER 8
#define DEBUG 16
#define FLOAT_LINEAR 32

const unsigned short snell__limit_enum[SNELL__LIMITS] = {
    GL_MAX_TEXTURE_SIZE, GL_MAX_CUBE_MAP_TEXTURE_SIZE, GL_MAX_ARRAY_TEXTURE_LAYERS, GL_MAX_RENDERBUFFER_SIZE,
    GL_MAX_SAMPLES, GL_MAX_TEXTURE_IMAGE_UNITS, GL_MAX_FRAGMENT_UNIFORM_VECTORS, GL_MAX_VERTEX_UNIFORM_VECTORS,
    GL_MAX_VARYING_VECTORS, GL_MAX_DRAW_BUFFERS,
};

/* Columns: texture, cube, array layers, renderbuffer, samples, fragment
 * units, fragment and vertex uniform vectors, varying vectors, draw buffers.
 * Mesa paths are files of github.com/mesa3d/mesa; Mesa's GL front end sets
 * the renderbuffer size to the texture size and caps 2D and cube sizes at
 * 1 << (MAX_TEXTURE_LEVELS 15 - 1), and enables KHR_debug on every driver. */
const snell__profile snell__profiles[] = {
    /* OpenGL ES 3.0.6 spec, 6.2 state tables "Implementation Dependent
     * Values" and the vertex, fragment and aggregate "Shader Limits": the
     * minimum every GLES 3.0 device has; no extension. */
    {"gles30-min", 0, {2048, 2048, 256, 2048, 4, 16, 224, 256, 15, 4}},
    /* Raspberry Pi 4 (V3D 4.2; the Pi 5's 7.1 has as much or more), Mesa
     * v3d: src/broadcom/common/v3d_limits.h V3D_MAX_IMAGE_DIMENSION 4096,
     * V3D_MAX_ARRAY_LAYERS 2048, V3D_MAX_SAMPLES 4,
     * V3D_OPENGL_MAX_TEXTURE_SAMPLERS 16, V3D_MAX_FS_INPUTS / 4 varyings,
     * V3D_MAX_RENDER_TARGETS(42) 4, as Mesa 22.3.6 over drm-shim reports;
     * uniform vectors min. */
    {"rpi-v3d", DEBUG, {4096, 4096, 2048, 4096, 4, 16, 224, 256, 16, 4}},
    /* Mali G52 / G31 (Bifrost, arch 7), Mesa panfrost: pan_screen.c
     * panfrost_init_screen_caps max_texture_array_layers 2048,
     * max_varyings 32 (arch < 9), max_render_targets 8 (has_mrt),
     * texture_float_linear; 2D, cube and renderbuffer 8192: Mesa 22.3.6
     * over drm-shim reports 8192 on both GPUs (the newer Mesa named here
     * allows 16384; a device's driver may be as old as 22.3); samples,
     * units, uniform vectors min. */
    {"mali-bifrost", DEBUG | FLOAT_LINEAR, {8192, 8192, 2048, 8192, 4, 16, 224, 256, 32, 8}},
    /* Adreno 6xx, Mesa freedreno: freedreno_screen.c fd_init_screen_caps
     * max_texture_2d_size 16384, max_texture_cube_levels 15,
     * query_time_elapsed (a6xx with the kernel's max_freq:
     * EXT_disjoint_timer_query); array layers 256: Mesa 22.3.6 over
     * drm-shim reports 256 on Adreno 618, 630 and 660 (the newer Mesa
     * named here allows 2048; a device's driver may be as old as 22.3);
     * samples, units, uniform vectors, varyings, draw buffers min. */
    {"adreno-6xx", DEBUG | TIMER, {16384, 16384, 256, 16384, 4, 16, 224, 256, 15, 4}},
    /* PowerVR Rogue: no open GLES driver to read; Imagination's "PowerVR
     * Supported Extensions, OpenGL ES and EGL" (SDK REL_4.0) lists
     * GL_EXT_color_buffer_float; every limit min. */
    {"powervr-rogue", CBF, {2048, 2048, 256, 2048, 4, 16, 224, 256, 15, 4}},
};
const int snell__profile_count = (int)(sizeof snell__profiles / sizeof snell__profiles[0]);

const char *snell_limit_str(snell_limit which)
{
    /* one string, the names after each other: no table of pointers to relocate */
    const char *p = "texture_size\0cube_size\0array_layers\0renderbuffer_size\0samples\0fragment_units\0"
                    "fragment_vectors\0vertex_vectors\0varyings\0draw_buffers";
    int i;
    if ((unsigned)which >= SNELL_LIMIT_COUNT) return "unknown";
    for (i = 0; i < (int)which; i++) p += strlen(p) + 1;
    return p;
}

void snell__profile_trace(const snell_ctx *ctx, const char *fmt, ...)
{
    va_list ap;
    FILE *f;
    if (!ctx->profile_trace || !(f = fopen(ctx->profile_trace, "a"))) return;
    va_start(ap, fmt);
    vfprintf(f, fmt, ap);
    va_end(ap);
    fputc('\n', f);
    fclose(f);
}

int snell__ctx_fits(const snell_ctx *ctx, int which, int value)
{
    snell__profile_trace(ctx, "check %d %d %d", which, value, ctx->limit_raw[which]);
    return value <= ctx->limit[which];
}

snell_status snell__ctx_limit(snell_ctx *ctx, int which, int value, const char *what)
{
    if (snell__ctx_fits(ctx, which, value)) return SNELL_OK;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "%s %d: over the %s %d (profile %s)", what, value,
                       snell_limit_str((snell_limit)which), ctx->limit[which], ctx->profile ? ctx->profile->name : "none");
}

void snell_ctx_limits(const snell_ctx *ctx, snell_device_limits *out)
{
    int i;
    if (!out) return;
    if (ctx) {
        char raw[SNELL__LIMITS * 12] = "";
        for (i = 0; i < SNELL__LIMITS; i++) snprintf(raw + strlen(raw), sizeof raw - strlen(raw), " %d", ctx->limit_raw[i]);
        snell__profile_trace(ctx, "limits%s", raw);
    }
    out->profile = ctx && ctx->profile ? ctx->profile->name : "none";
    out->cost_model = ctx && ctx->cost ? ctx->cost->name : "reference";
    for (i = 0; i < SNELL_LIMIT_COUNT; i++) out->limit[i] = ctx ? ctx->limit[i] : 0;
}
