/* SPDX-License-Identifier: MIT */
/* test_exit_dir — the exit-direction debug output that error measurement
 * relies on. (1) src/core/pack.h and shaders_es/common/pack.glsl agree bit for bit
 * (transform feedback), for the 16+16-bit direction and for the exit target's
 * 16+15 bits and coverage bit, and each encoding's own error is below 1e-4
 * rad (the exit's measured 9.4e-5, the direction's 6.4e-5);
 * (2) SNELL_OUTPUT_EXIT_DIRECTION (float target if available) and the forced
 * RGBA8 fallback reproduce the reference tracer's exit directions for the
 * single-surface method (MATCHED, one interface) on a sphere. The kernel runs
 * at mediump, which Mesa 22's llvmpipe evaluates at reduced (fp16-like)
 * precision in fragment shaders (measured: with the shader at highp the
 * median error is 5e-8 rad; at mediump 2.3e-4 rad). Bounds: median below one
 * fp16 unit roundoff, 2^-11 = 4.9e-4 rad, 99% of glass pixels below 2e-3 rad
 * (silhouette pixels are decided by coverage and may differ), and background
 * pixels (computed at highp) within 1e-3 rad of the view ray; the renderer's
 * coverage (snell_renderer_read_coverage) is empty for the background alone
 * and the reference's hit mask but along the silhouette. */
#include "test_util.h"
#include "core/gl.h"
#include "core/pack.h"
#include "core/program.h"
#include "snell/snell_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 128
#define H 96

static double angle(const float *a, const float *b)
{
    double d = (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
    double la = sqrt((double)a[0] * a[0] + (double)a[1] * a[1] + (double)a[2] * a[2]);
    double lb = sqrt((double)b[0] * b[0] + (double)b[1] * b[1] + (double)b[2] * b[2]);
    d /= la * lb;
    return acos(d > 1 ? 1 : d < -1 ? -1 : d);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Deterministic directions covering the sphere, incl. the octahedron's folds. */
static void test_dir(int i, int n, float d[3])
{
    double z = 1.0 - 2.0 * (i + 0.5) / n, r = sqrt(1 - z * z), phi = i * 2.399963229728653;
    d[0] = (float)(r * cos(phi));
    d[1] = (float)(r * sin(phi));
    d[2] = (float)z;
    if (i % 97 == 0) { d[0] = 0; d[1] = (i & 1) ? 1.0f : -1.0f; d[2] = 0; }
}

/* exit 0: snell_pack_dir_rgba8 (16+16 bits: the G-buffer's and the layers'
 * normals); 1: snell_pack_exit_rgba8 (16+15 bits and the coverage bit: the
 * packed exit-direction target), every other direction marked as glass. */
static void pack_twin(snell_ctx *ctx, int exit)
{
    enum { N = 4096 };
    static const char vs_dir[] = "precision highp float;\n#include \"common/pack.glsl\"\n"
                                 "layout(location = 0) in vec3 a_dir;\nout vec4 o_packed;\n"
                                 "void main() { o_packed = snell_pack_dir_rgba8(a_dir); gl_Position = vec4(0.0); }\n";
    static const char vs_exit[] = "precision highp float;\n#include \"common/pack.glsl\"\n"
                                  "layout(location = 0) in vec3 a_dir;\nout vec4 o_packed;\n"
                                  "void main() { o_packed = snell_pack_exit_rgba8(a_dir, (gl_VertexID & 1) == 1);\n"
                                  "    gl_Position = vec4(0.0); }\n";
    const char *vs = exit ? vs_exit : vs_dir;
    const char *varyings[] = {"o_packed"};
    static float dirs[N][3], out[N][4];
    GLuint prog = 0, vao, vbo, tfb, fbo, rb;
    int i, mismatches = 0, marks = 0;
    double worst = 0;
    void *p;
    for (i = 0; i < N; i++) test_dir(i, N, dirs[i]);
    CHECK_OK(snell__program_build_feedback(ctx, vs, NULL, varyings, 1, &prog));
    if (!prog) return;
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 1, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof dirs, dirs, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, 0);
    glGenBuffers(1, &tfb);
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb);
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, sizeof out, NULL, GL_STATIC_READ);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, tfb);
    glUseProgram(prog);
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, N);
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    p = glMapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, sizeof out, GL_MAP_READ_BIT);
    CHECK(p != NULL, "map");
    if (p) memcpy(out, p, sizeof out);
    glUnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER);
    for (i = 0; i < N; i++) {
        uint8_t c[4], g[4];
        float back[3];
        int k;
        if (exit)
            snell_pack_exit_rgba8(dirs[i], i & 1, c);
        else
            snell_pack_dir_rgba8(dirs[i], c);
        /* The shader writes (byte + 0.25) / 255; both rounding and truncating
         * UNORM8 conversions store the byte. Check the truncating one. */
        for (k = 0; k < 4; k++) g[k] = (uint8_t)(out[i][k] * 255.0f);
        mismatches += memcmp(c, g, 4) != 0;
        if (exit)
            marks += snell_unpack_exit_rgba8(c, back) != (i & 1);
        else
            snell_unpack_dir_rgba8(c, back);
        if (angle(back, dirs[i]) > worst) worst = angle(back, dirs[i]);
    }
    printf("pack twin (%s): %d of %d directions differ between C and GLSL; worst packed error %.3g rad\n",
           exit ? "exit, coverage bit" : "direction", mismatches, N, worst);
    CHECK(mismatches == 0, "%d packed directions differ between C and GLSL", mismatches);
    CHECK(marks == 0, "%d coverage bits not read back as written", marks);
    CHECK(worst < 1e-4, "packed RGBA8 direction error %.3g rad >= 1e-4", worst);
    glDeleteBuffers(1, &tfb);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &rb);
    glDeleteProgram(prog);
}

static void against_reference(snell_ctx *ctx, snell_output output)
{
    static float gpu[W * H * 3], ref_dir[W * H * 3], rgb[W * H * 3], errs[W * H];
    static double sorted[W * H];
    static uint8_t hit[W * H], cover[W * H];
    snell_mesh *mesh = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_env_desc ed;
    snell_frame_desc fd;
    snell_glass g;
    snell_ref *ref = NULL;
    snell_ref_params p;
    int i, n = 0, below = 0, bg_bad = 0, nbg = 0, bg_cover = 0, cover_diff = 0;
    double bg_sum = 0;
    memset(&ed, 0, sizeof ed);
    ed.face_size = 64;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = output;
    CHECK_OK(snell_mesh_create_shape(ctx, &(snell_shape_desc){SNELL_SHAPE_SPHERE, 64, 32}, &mesh));
    CHECK_OK(snell_env_create(ctx, &ed, &env));
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!mesh || !env || !r) goto done;
    printf("output %d: encoding %s\n", (int)output, snell_renderer_exit_dir_encoding(r));
    if (output == SNELL_OUTPUT_EXIT_DIRECTION_PACKED)
        CHECK(strcmp(snell_renderer_exit_dir_encoding(r), "packed-rgba8") == 0, "forced packing");
    else /* the float target exactly where the driver can render to it (probed, not assumed) */
        CHECK(strcmp(snell_renderer_exit_dir_encoding(r),
                     snell_ctx_has_gl_extension(ctx, "GL_EXT_color_buffer_float") ? "float" : "packed-rgba8") == 0,
              "encoding %s does not follow GL_EXT_color_buffer_float", snell_renderer_exit_dir_encoding(r));
    test_frame_one(&fd, &g, mesh, env);
    g.material.method = SNELL_METHOD_SINGLE;
    g.material.ior = 1.5f;
    fd.camera.azimuth = 0.4f;
    fd.camera.elevation = 0.3f;
    fd.camera.distance = 3.2f;
    fd.glass_count = 0; /* the background alone: nothing covered */
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_coverage(r, cover));
    for (i = 0; i < W * H; i++) bg_cover += cover[i] != 0;
    CHECK(bg_cover == 0, "%d pixels of the background alone covered", bg_cover);
    fd.glass_count = 1;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK(snell_renderer_read_exit_dirs(r, gpu));
    CHECK_OK(snell_renderer_read_coverage(r, cover));
    {
        uint8_t px[4];
        CHECK(snell_renderer_read_rgba(r, px) == SNELL_E_INVALID_ARG, "colour readback of a direction target");
    }

    CHECK_OK(test_ref_create(ctx, &fd, &ref));
    if (!ref) goto done;
    test_ref_params(&fd, W, H, 1, &p);
    {
        snell_status st = test_ref_render(ref, &p, rgb, ref_dir, hit);
        CHECK(st == SNELL_OK, "reference: %s", snell_last_error(ctx));
    }
    for (i = 0; i < W * H; i++) {
        double e = angle(gpu + 3 * i, ref_dir + 3 * i);
        CHECK(isfinite(gpu[3 * i]) && isfinite(gpu[3 * i + 1]) && isfinite(gpu[3 * i + 2]), "NaN at %d", i);
        cover_diff += !cover[i] != !hit[i];
        if (hit[i]) {
            errs[n] = (float)e;
            sorted[n++] = e;
            below += e < 2e-3;
        } else {
            bg_bad += e > 1e-3;
            bg_sum += e;
            nbg++;
        }
    }
    qsort(sorted, (size_t)n, sizeof *sorted, cmp_double);
    printf("  %d glass pixels: median %.3g rad, 99th percentile %.3g rad; background: mean %.3g rad, %d off by > 1e-3\n",
           n, sorted[n / 2], sorted[(int)(n * 0.99)], nbg ? bg_sum / nbg : 0.0, bg_bad);
    CHECK(n > W * H / 10, "sphere covers the image");
    /* Coverage (snell_renderer_read_coverage) is the reference's hit mask but
     * along the silhouette (a triangle edge vs the exact sphere). */
    printf("  coverage: %d pixels differ from the reference's hit mask\n", cover_diff);
    CHECK(cover_diff <= 2 * (W + H), "coverage differs from the reference's in %d pixels", cover_diff);
    CHECK(sorted[n / 2] < 4.9e-4, "median exit-direction error %.3g rad", sorted[n / 2]);
    CHECK(below >= 0.99 * n, "only %d of %d glass pixels below 2e-3 rad", below, n);
    CHECK(bg_bad <= W * H / 100, "%d background pixels are not the view ray", bg_bad);
    (void)errs;
done:
    snell_ref_destroy(ref);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    const char *hidden = getenv("SNELL_TEST_HIDDEN_EXTENSION");
    if (!ctx) SKIP("no GL context");
    /* test_exit_dir_no_float (tests/core.cmake) hides the extension through
     * Mesa's MESA_EXTENSION_OVERRIDE, as on a driver without it, so that the
     * RGBA8 fallback is what EXIT_DIRECTION picks. */
    if (hidden && snell_ctx_has_gl_extension(ctx, hidden)) SKIP("the driver did not hide %s", hidden);
    pack_twin(ctx, 0);
    pack_twin(ctx, 1);
    against_reference(ctx, SNELL_OUTPUT_EXIT_DIRECTION);
    against_reference(ctx, SNELL_OUTPUT_EXIT_DIRECTION_PACKED);
    {
        snell_renderer *r = NULL;
        snell_renderer_desc rd;
        memset(&rd, 0, sizeof rd);
        rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
        rd.target = SNELL_TARGET_BOUND_FRAMEBUFFER;
        CHECK(snell_renderer_create(ctx, &rd, &r) == SNELL_E_INVALID_ARG && !r, "direction output needs offscreen");
    }
    snell_ctx_destroy(ctx);
    return test_finish();
}
