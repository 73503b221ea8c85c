/* SPDX-License-Identifier: MIT */
/* test_shader — the program builder: embedded chunks resolve, and compile and
 * link failures come back as SNELL_E_GL with the driver's info log. */
#include "test_util.h"
#include "core/gl.h"
#include "core/program.h"

#include <string.h>

static const char vs_ok[] = "precision highp float;\nin vec3 a_position;\nvoid main() { gl_Position = vec4(a_position, 1.0); }\n";
static const char fs_ok[] = "precision mediump float;\n#include \"common/optics.glsl\"\nout vec4 o;\n"
                            "void main() { vec3 t; snell_refract(vec3(0,0,-1), vec3(0,0,1), 0.5, t); o = vec4(t, 1.0); }\n";
static const char fs_bad[] = "precision mediump float;\nout vec4 o;\nvoid main() { o = vec4(undeclared_thing, 1.0); }\n";
static const char fs_missing[] = "precision mediump float;\n#include \"common/nope.glsl\"\nout vec4 o;\nvoid main() { o = vec4(1.0); }\n";
static const char fs_link_bad[] = "precision mediump float;\nin vec3 v_never_written;\nout vec4 o;\nvoid main() { o = vec4(v_never_written, 1.0); }\n";

int main(void)
{
    snell_ctx *ctx = test_ctx();
    unsigned prog = 0;
    snell_status st;
    if (!ctx) SKIP("no GL context");

    CHECK(snell__shader_source("common/optics.glsl") != NULL, "optics chunk embedded");
    CHECK(snell__shader_source("does/not/exist.glsl") == NULL, "unknown path");

    CHECK_OK(snell__program_build_src(ctx, vs_ok, fs_ok, "#define UNUSED 1\n", &prog));
    CHECK(prog != 0, "program");
    glDeleteProgram(prog);

    st = snell__program_build_src(ctx, vs_ok, fs_bad, NULL, &prog);
    CHECK(st == SNELL_E_GL, "compile failure status %s", snell_status_str(st));
    CHECK(strstr(snell_last_error(ctx), "fragment shader compile failed") != NULL, "message: %s", snell_last_error(ctx));
    CHECK(strstr(snell_last_error(ctx), "undeclared_thing") != NULL, "info log missing: %s", snell_last_error(ctx));

    st = snell__program_build_src(ctx, vs_ok, fs_missing, NULL, &prog);
    CHECK(st == SNELL_E_GL && strstr(snell_last_error(ctx), "common/nope.glsl"), "missing chunk: %s", snell_last_error(ctx));

    st = snell__program_build_src(ctx, vs_ok, fs_link_bad, NULL, &prog);
    CHECK(st == SNELL_E_GL && strstr(snell_last_error(ctx), "link failed"), "link failure: %s", snell_last_error(ctx));

    st = snell__program_build(ctx, "object.vert", "missing.frag", NULL, &prog);
    CHECK(st == SNELL_E_GL && strstr(snell_last_error(ctx), "missing.frag"), "missing file: %s", snell_last_error(ctx));

    /* The precision policy: SNELL_MEDIUMP is defined in every program (a
     * shader that uses it compiles), highp on software rasterisers (they
     * emulate fp16 mediump, slower than highp) unless the fp16 study build. */
    {
        static const char fs_policy[] = "precision SNELL_MEDIUMP float;\nout vec4 o;\nvoid main() { o = vec4(1.0); }\n";
        const char *why = snell_ctx_precision(ctx);
        int software = strstr(snell_ctx_gl_renderer(ctx), "llvmpipe") || strstr(snell_ctx_gl_renderer(ctx), "softpipe");
        CHECK_OK(snell__program_build_src(ctx, vs_ok, fs_policy, NULL, &prog));
        glDeleteProgram(prog);
        printf("precision policy: %s\n", why);
#ifdef SNELL_FP16_EMULATION
        CHECK(snell__ctx_fragment_mediump(ctx) == 1 && strncmp(why, "mediump", 7) == 0, "fp16 build: %s", why);
#else
        if (software) CHECK(snell__ctx_fragment_mediump(ctx) == 0 && strncmp(why, "highp", 5) == 0, "software: %s", why);
#endif
        CHECK(strncmp(why, "highp", 5) == 0 || strncmp(why, "mediump", 7) == 0, "policy named: %s", why);
    }

    /* Every embedded vertex/fragment pair the renderer uses builds. */
    CHECK_OK(snell__program_build(ctx, "object.vert", "single.frag", NULL, &prog));
    glDeleteProgram(prog);
    CHECK_OK(snell__program_build(ctx, "object.vert", "single.frag", "#define SNELL_THIN 1\n", &prog));
    glDeleteProgram(prog);
    CHECK_OK(snell__program_build(ctx, "object.vert", "opaque.frag", NULL, &prog));
    glDeleteProgram(prog);
    CHECK_OK(snell__program_build(ctx, "skybox.vert", "skybox.frag", NULL, &prog));
    glDeleteProgram(prog);
    CHECK_OK(snell__program_build(ctx, "object.vert", "gbuffer.frag", NULL, &prog));
    glDeleteProgram(prog);
    CHECK_OK(snell__program_build(ctx, "screen.vert", "single.frag", "#define SNELL_SCREEN_SPACE 1\n#define SNELL_ABSORB 1\n", &prog));
    glDeleteProgram(prog);

    snell_ctx_destroy(ctx);
    return test_finish();
}
