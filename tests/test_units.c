/* SPDX-License-Identifier: MIT */
/* test_units — texture units and uniforms are bound per program
 * (frame/textures.h): frames that switch every kernel hook on, for every
 * method of the registry in both shadings, build programs that stay inside
 * what GLES 3.0 guarantees (16 fragment samplers, 224 fragment uniform
 * vectors, counted without packing over both stages), read back from each
 * program after linking; a program that samples more textures than the
 * context has fails when it is built, naming them. The glass panels'
 * programs too: over the frame with frost, over a texture, over an
 * external one where the context has them. */
#include "test_util.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"
#include "frame/glass_program.h"
#include "frame/textures.h"
#include "snell/snell_water.h"

#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/stat.h>

#define W 48
#define H 48

static const float k_place[3][16] = {
    {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, -0.5f, 0.1f, 0, 1},
    {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0.5f, 0.1f, 0, 1},
    {0.3f, 0, 0, 0, 0, 0.3f, 0, 0, 0, 0, 0.3f, 0, 0, -0.2f, -0.8f, 1},
};

/* Everything at once: two glass objects (the scene layers) and an opaque
 * one, water (CPU or GPU heights), a light with a receiver plane (the lit
 * plane and opaque objects), dispersion and absorption on one object, the
 * host's scene behind the glass (a backdrop with colour and depth); each
 * method of the registry forced on both, in the given shading (one renderer,
 * so the stages' own programs are built once). */
static void frames_all(snell_ctx *ctx, snell_shading shading, int gpu_water, int paraboloid)
{
    snell_mesh *sphere = NULL, *cube = NULL;
    snell_env *env = NULL;
    snell_water *water = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd = {.width = W, .height = H, .shading = shading};
    snell_glass g[2];
    snell_opaque op;
    snell_frame_desc fd;
    snell_backdrop bd;
    snell_status st;
    GLuint tex[2];
    int i, k;
    memset(g, 0, sizeof g);
    memset(&bd, 0, sizeof bd);
    glGenTextures(2, tex);
    glBindTexture(GL_TEXTURE_2D, tex[0]);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, 8, 8);
    glBindTexture(GL_TEXTURE_2D, tex[1]);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT24, 8, 8);
    glBindTexture(GL_TEXTURE_2D, 0);
    bd.color_texture = tex[0], bd.depth_texture = tex[1], bd.width = bd.height = 8;
    memset(&op, 0, sizeof op);
    memset(&fd, 0, sizeof fd);
    if (paraboloid) rd.env_lookup = SNELL_ENV_LOOKUP_DUAL_PARABOLOID;
    st = snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE}, &sphere);
    if (st == SNELL_OK) st = snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_CUBE}, &cube);
    if (st == SNELL_OK) st = snell_env_create(ctx, &(snell_env_desc){.face_size = 32}, &env);
    if (st == SNELL_OK)
        st = snell_water_create(ctx,
                                &(snell_water_desc){.grid = 64, .sim = gpu_water ? SNELL_WATER_SIM_GPU : SNELL_WATER_SIM_CPU},
                                &water);
    if (st == SNELL_OK) st = snell_renderer_create(ctx, &rd, &r);
    CHECK_OK(st);
    for (k = 0; k < 2; k++) {
        g[k].mesh = sphere;
        g[k].model = k_place[k];
        g[k].material.ior = 1.5f;
    }
    g[1].material.dispersion = 1.0f;
    g[1].material.attenuation_color[0] = 0.5f, g[1].material.attenuation_color[1] = 0.8f;
    g[1].material.attenuation_color[2] = 1.0f, g[1].material.attenuation_distance = 1.0f;
    op.mesh = cube;
    op.model = k_place[2];
    fd.env = env;
    fd.glass = g;
    fd.glass_count = 2;
    fd.opaque = &op;
    fd.opaque_count = 1;
    fd.water = water;
    fd.camera.distance = 3.0f;
    fd.camera.elevation = 0.5f;
    fd.light.type = SNELL_LIGHT_DIRECTIONAL;
    fd.light.direction[0] = 0.3f, fd.light.direction[1] = -1.0f, fd.light.direction[2] = 0.2f;
    fd.light.photons = 16;
    fd.receiver.height = -0.9f;
    fd.receiver.extent = 3.0f;
    fd.receiver.map_size = 32;
    fd.backdrop = &bd;
    for (i = 0; st == SNELL_OK && i < (paraboloid ? 1 : snell_method_count()); i++) { /* paraboloid: AUTO alone */
        snell_method m = paraboloid ? SNELL_METHOD_AUTO : snell_method_info_at(i)->method;
        g[0].material.method = g[1].material.method = m;
        CHECK(snell_render(r, &fd, NULL) == SNELL_OK, "%s, %s: %s", snell_method_str(m),
              shading == SNELL_SHADING_SCREEN ? "screen" : "forward", snell_last_error(ctx));
    }
    if (st == SNELL_OK) {
        /* the program cache: bounded, and the same frame again builds nothing */
        snell_frame_stats a, b;
        GLuint mark;
        GLint units = 0, bound = 0;
        int u, changed = 0;
        /* the units the frame reports are the ones it bound on: a marker on
         * every unit (nothing restores them in a context snell owns) stays
         * where the frame did not bind */
        glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
        units = units < 32 ? units : 32;
        glGenTextures(1, &mark);
        for (u = 0; u < units; u++) {
            glActiveTexture((GLenum)(GL_TEXTURE0 + u));
            glBindTexture(GL_TEXTURE_2D, mark);
        }
        glActiveTexture(GL_TEXTURE0);
        CHECK(snell_render(r, &fd, &a) == SNELL_OK && snell_render(r, &fd, &b) == SNELL_OK, "%s",
              snell_last_error(ctx));
        for (u = 0; u < units; u++) {
            glActiveTexture((GLenum)(GL_TEXTURE0 + u));
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
            changed += bound != (GLint)mark;
        }
        glActiveTexture(GL_TEXTURE0);
        glDeleteTextures(1, &mark);
        printf("%s frame: %d texture units used, %d of the %d units' 2D bindings changed\n",
               shading == SNELL_SHADING_SCREEN ? "screen" : "forward", b.texture_units, changed, (int)units);
        CHECK(b.texture_units >= 1 && b.texture_units <= 16 && changed <= b.texture_units && a.texture_units ==
              b.texture_units, "texture units: %d and %d reported, %d changed", a.texture_units, b.texture_units,
              changed);
        CHECK(a.programs > 0 && a.programs <= SNELL__PROGRAM_CACHE && a.programs_built >= a.programs,
              "program cache: %d held, %d built", a.programs, a.programs_built);
        CHECK(b.programs_built == a.programs_built && b.programs == a.programs && b.program_bytes == a.program_bytes,
              "program cache: a repeated frame built %d programs", b.programs_built - a.programs_built);
    }
    snell_renderer_destroy(r);
    glDeleteTextures(2, tex);
    snell_water_destroy(water);
    snell_env_destroy(env);
    snell_mesh_destroy(cube);
    snell_mesh_destroy(sphere);
}

/* A program that samples 17 textures fails when its units are given. */
static void too_many_samplers(snell_ctx *ctx)
{
    static const char vs[] = "in vec4 a;\nvoid main() { gl_Position = a; }\n";
    char fs[2048] = "precision highp float;\nout vec4 o;\n";
    unsigned prog = 0;
    snell__samplers s;
    snell_status st;
    int i;
    for (i = 0; i < 17; i++) snprintf(fs + strlen(fs), sizeof fs - strlen(fs), "uniform sampler2D u_t%d;\n", i);
    strcat(fs, "void main() { o = vec4(0.0)");
    for (i = 0; i < 17; i++) snprintf(fs + strlen(fs), sizeof fs - strlen(fs), " + texture(u_t%d, vec2(0.5))", i);
    strcat(fs, "; }\n");
    st = snell__program_build_src(ctx, vs, fs, NULL, &prog);
    if (st != SNELL_OK) {
        /* a compiler may refuse it itself: then the context's limit held at link */
        printf("17 samplers refused at link: %s\n", snell_last_error(ctx));
        return;
    }
    st = snell__samplers_assign(ctx, prog, "seventeen.frag", &s);
    CHECK(st == SNELL_E_UNSUPPORTED, "17 samplers: %s, expected SNELL_E_UNSUPPORTED", snell_status_str(st));
    CHECK(strstr(snell_last_error(ctx), "seventeen.frag") && strstr(snell_last_error(ctx), "u_t16"),
          "the message names the program and its samplers: %s", snell_last_error(ctx));
    glDeleteProgram(prog);
}

/* Two samplers get different units, each set in the program. */
static void units_given(snell_ctx *ctx)
{
    static const char vs[] = "in vec4 a;\nvoid main() { gl_Position = a; }\n";
    static const char fs[] = "precision highp float;\nuniform sampler2D u_a;\nuniform highp usampler2D u_b;\n"
                             "uniform samplerCube u_unused;\nout vec4 o;\n"
                             "void main() { o = texture(u_a, vec2(0.5)) + vec4(texture(u_b, vec2(0.5))); }\n";
    unsigned prog = 0;
    snell__samplers s;
    GLint ua = -1, ub = -1;
    CHECK_OK(snell__program_build_src(ctx, vs, fs, NULL, &prog));
    CHECK_OK(snell__samplers_assign(ctx, prog, "two.frag", &s));
    CHECK(s.count == 2, "%d samplers, expected 2 (an unused one takes no unit)", s.count);
    glGetUniformiv(prog, glGetUniformLocation(prog, "u_a"), &ua);
    glGetUniformiv(prog, glGetUniformLocation(prog, "u_b"), &ub);
    CHECK(ua == snell__samplers_unit(&s, "u_a") && ub == snell__samplers_unit(&s, "u_b") && ua != ub && ua >= 0 &&
              ub >= 0,
          "units u_a %d, u_b %d", ua, ub);
    CHECK(snell__samplers_unit(&s, "u_unused") == -1, "an inactive sampler has no unit");
    glDeleteProgram(prog);
}

/* An earlier run's sources (of an older build) would be validated with these. */
static void clear_dump(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char path[1400];
    while (d && (e = readdir(d)) != NULL)
        if (strstr(e->d_name, ".vert") || strstr(e->d_name, ".frag")) {
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            remove(path);
        }
    if (d) closedir(d);
}

/* Every program of the panels stage (render/panels_stage.c): each source
 * of what lies beneath, with and without dispersion. */
static void frames_panels(snell_ctx *ctx)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd = {.width = W, .height = H};
    snell_panel p[2];
    snell_panels_under u;
    snell_frame_desc fd;
    GLuint tex[2];
    int k;
    memset(p, 0, sizeof p);
    memset(&u, 0, sizeof u);
    memset(&fd, 0, sizeof fd);
    glGenTextures(2, tex);
    glBindTexture(GL_TEXTURE_2D, tex[0]);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, 8, 8);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindTexture(GL_TEXTURE_EXTERNAL_OES, tex[1]); /* an external texture's name, nothing in it */
    glBindTexture(GL_TEXTURE_EXTERNAL_OES, 0);
    glGetError(); /* without the extension the bind fails: that source is not built */
    /* apart, without shadows: no overlap, so a texture is read directly */
    p[0].center[0] = p[0].center[1] = 10.0f, p[0].size[0] = p[0].size[1] = 8.0f, p[0].shadow[0] = -1.0f;
    p[1] = p[0], p[1].center[0] = 36.0f, p[1].dispersion = 1.0f;
    fd.draw_background = SNELL_BACKGROUND_NONE, fd.panels = p, fd.panel_count = 2, fd.panels_under = &u;
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    for (k = 0; r && k < 3; k++) {
        if (k == 2 && !snell_ctx_has_gl_extension(ctx, "GL_OES_EGL_image_external_essl3")) break;
        u.source = (snell_panels_under_source)k, u.texture = tex[k == 2], u.draw = 1;
        p[0].frost = k == 0 ? 2.0f : 0.0f;
        CHECK(snell_render(r, &fd, NULL) == SNELL_OK, "panels over source %d: %s", k, snell_last_error(ctx));
    }
    snell_renderer_destroy(r);
    glDeleteTextures(2, tex);
}

/* The profiles' limits beside the dumped sources, for glsl_check.py and
 * profile_tests.py: a line per profile, its name, its limits in snell_limit's
 * order, then the extensions it has. */
static void write_profiles(const char dir[1024])
{
    char path[1100], text[2048] = "";
    int i, k;
    for (i = 0; i < snell__profile_count; i++) {
        snprintf(text + strlen(text), sizeof text - strlen(text), "%s", snell__profiles[i].name);
        for (k = 0; k < SNELL__LIMITS; k++)
            snprintf(text + strlen(text), sizeof text - strlen(text), " %d", snell__profiles[i].limit[k]);
        for (k = 0; k < SNELL__PROFILE_EXTS; k++)
            if (snell__profiles[i].ext >> k & 1)
                snprintf(text + strlen(text), sizeof text - strlen(text), " %s", snell__profile_ext[k]);
        snprintf(text + strlen(text), sizeof text - strlen(text), "\n");
    }
    snprintf(path, sizeof path, "%s/profiles.txt", dir);
    CHECK(test_write_file(path, text, strlen(text)), "cannot write %s", path);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    static char dump[1024];
    if (!ctx) SKIP("no GL context");
    snprintf(dump, sizeof dump, "%s", test_out("glsl"));
    {
        /* the two test programs here are not snell's (one has 17 samplers) */
        void (*hook)(snell_ctx *, unsigned, const char *) = ctx->on_source;
        ctx->on_source = NULL;
        units_given(ctx);
        too_many_samplers(ctx);
        ctx->on_source = hook;
    }
    /* every program the frames build, its final sources, for the
     * glsl_validate test */
    mkdir(dump, 0755);
    clear_dump(dump);
    test_glsl_dump(ctx, dump); /* here even when SNELL_TEST_GLSL_DUMP collects the other tests' */
    write_profiles(dump);
    memset(&ctx->census, 0, sizeof ctx->census);
    frames_all(ctx, SNELL_SHADING_FORWARD, 0, 0);
    frames_all(ctx, SNELL_SHADING_SCREEN, 1, 0);
    frames_all(ctx, SNELL_SHADING_FORWARD, 0, 1);
    frames_panels(ctx);
    printf("%d programs given units; most samplers %d (%s), most uniform vectors %d (%s)\n", ctx->census.programs,
           ctx->census.samplers, ctx->census.samplers_of, ctx->census.vectors, ctx->census.vectors_of);
    CHECK(ctx->census.programs >= 2 * snell_method_count(), "only %d programs counted", ctx->census.programs);
    CHECK(ctx->census.samplers <= 16, "%s samples %d textures: GLES 3.0 guarantees 16", ctx->census.samplers_of,
          ctx->census.samplers);
    CHECK(ctx->census.samplers >= 10, "the frames should switch the hooks on (%d samplers at most)", ctx->census.samplers);
    CHECK(ctx->census.vectors <= 224, "%s has %d uniform vectors: GLES 3.0 guarantees 224 in the fragment stage",
          ctx->census.vectors_of, ctx->census.vectors);
    snell_ctx_destroy(ctx);
    return test_finish();
}
