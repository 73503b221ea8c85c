/* SPDX-License-Identifier: MIT */
/* test_optics_twin — src/core/optics.h and shaders_es/common/optics.glsl must agree.
 * The GLSL runs in a vertex shader whose outputs are captured with transform
 * feedback (core GLES 3.0, exact float32 results, no float render target
 * needed). Both are also checked against the double-precision twin.
 * Inputs: incidence angles 0..89.999 deg (grazing included), eta both into
 * denser (entry) and thinner (exit, where TIR happens) media, IOR 1.0001..4.
 * The thin-wall slab (snell_opt_thin_slab / snell_thin_slab) on its own grid
 * (incidence cosines 1..0 and negative, IOR 0.75..4, thickness 0..3,
 * absorption none to strong), also against its analytic cases: without
 * absorption rs + ts = 1 and rs = 2R / (1 + R), R = Schlick at one face; with
 * it, the sum of the bounce series computed term by term. The exact
 * unpolarised Fresnel reflectance (snell_opt_fresnel_exact /
 * snell_fresnel_exact) against its angle form and its physical properties
 * (reciprocity, Brewster's angle, grazing, critical angle); no reflection at
 * matched indices in either model. The per-channel refraction of a
 * dispersive material (snell_opt_refract_rgb / snell_refract_rgb) on a grid
 * of its own. (The channels' IORs themselves, snell_opt_ior_rgb, are
 * computed on the CPU only: test_dispersion.) */
#include "test_util.h"
#include "core/gl.h"
#include "core/optics.h"
#include "core/program.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char vs[] =
    "precision highp float;\n"
    "#include \"common/optics.glsl\"\n"
    "layout(location = 0) in vec3 a_i;\n"
    "layout(location = 1) in vec3 a_n;\n"
    "layout(location = 2) in vec4 a_p; // eta, n1, n2, path length\n"
    "out vec4 o_t;   // refracted dir, refracted? 1 : 0\n"
    "out vec4 o_r;   // reflected dir, Schlick(n1 -> n2)\n"
    "out vec4 o_bl;  // Beer-Lambert for sigma (0.1, 0.5, 2.0), exact Fresnel(n1 -> n2)\n"
    "void main() {\n"
    "    vec3 t;\n"
    "    bool ok = snell_refract(a_i, a_n, a_p.x, t);\n"
    "    o_t = vec4(t, ok ? 1.0 : 0.0);\n"
    "    o_r = vec4(snell_reflect(a_i, a_n), snell_fresnel_schlick(-dot(a_i, a_n), a_p.y, a_p.z));\n"
    "    o_bl = vec4(snell_beer_lambert(vec3(0.1, 0.5, 2.0), a_p.w), snell_fresnel_exact(-dot(a_i, a_n), a_p.y, a_p.z));\n"
    "    gl_Position = vec4(0.0);\n"
    "}\n";

typedef struct input { float i[3], n[3], p[4]; } input;

static const double angles_deg[] = {0, 1, 10, 30, 41.8, 45, 48.6, 60, 75, 85, 89, 89.9, 89.99, 89.999};
static const double iors[] = {1.0, 1.0001, 1.33, 1.5, 2.42, 4.0};

/* The unpolarised dielectric reflectance in the angle form of the Fresnel
 * equations (Born & Wolf 1.5 (21a)): Rs = sin^2(ti - tt) / sin^2(ti + tt),
 * Rp = tan^2(ti - tt) / tan^2(ti + tt), at normal incidence their common
 * limit ((n1 - n2) / (n1 + n2))^2; 1 beyond the critical angle, 0 at matched
 * indices. Written apart from optics.h's cosine form to check it. */
static double fresnel_angles(double cos_i, double n1, double n2)
{
    double ti = acos(fabs(cos_i) < 1.0 ? fabs(cos_i) : 1.0), st = n1 / n2 * sin(ti), tt, a, b;
    if (n1 == n2) return 0.0;
    if (st >= 1.0) return 1.0;
    if (ti < 1e-7) return ((n1 - n2) / (n1 + n2)) * ((n1 - n2) / (n1 + n2));
    tt = asin(st);
    a = sin(ti - tt) / sin(ti + tt);
    b = tan(ti - tt) / tan(ti + tt);
    return 0.5 * (a * a + b * b);
}

/* Properties any correct Fresnel reflectance has, independent of the formula:
 * reciprocity R(ti, n1 -> n2) = R(tt, n2 -> n1), Rp = 0 at Brewster's angle
 * (R = Rs / 2 there), R -> 1 at grazing incidence, R = 1 from the critical
 * angle on. */
static void exact_fresnel_properties(void)
{
    int m, a, bad = 0;
    for (m = 0; m < (int)(sizeof iors / sizeof *iors); m++) {
        double n = iors[m], tb = atan(n), tt = atan(1.0 / n), rs = sin(tb - tt) / sin(tb + tt), crit;
        if (n == 1.0) {
            bad += snell_optd_fresnel_exact(0.3, 1.0, 1.0) != 0.0 || snell_optd_fresnel_schlick(0.3, 1.0, 1.0) != 0.0;
            continue;
        }
        bad += fabs(snell_optd_fresnel_exact(cos(tb), 1.0, n) - 0.5 * rs * rs) > 1e-14;
        bad += fabs(snell_optd_fresnel_exact(cos(tt), n, 1.0) - 0.5 * rs * rs) > 1e-14; /* Brewster inside */
        bad += fabs(snell_optd_fresnel_exact(1e-12, 1.0, n) - 1.0) > 1e-8;
        crit = asin(1.0 / n);
        bad += snell_optd_fresnel_exact(cos(crit + 1e-6), n, 1.0) != 1.0;
        for (a = 0; a < 90; a++) {
            double ti = a * SNELL_PI / 180.0, ttr = asin(sin(ti) / n);
            double r1 = snell_optd_fresnel_exact(cos(ti), 1.0, n), r2 = snell_optd_fresnel_exact(cos(ttr), n, 1.0);
            bad += fabs(r1 - r2) > 1e-11 || fabs(r1 - fresnel_angles(cos(ti), 1.0, n)) > 1e-11;
        }
    }
    CHECK(bad == 0, "%d exact-Fresnel properties fail (reciprocity, Brewster, grazing, critical angle, angle form)",
          bad);
}

/* The slab in GLSL, one input per vertex. */
static const char slab_vs[] = "precision highp float;\n"
                              "#include \"common/optics.glsl\"\n"
                              "layout(location = 0) in vec4 a_p;     // cos_i, ior, thickness\n"
                              "layout(location = 1) in vec3 a_sigma;\n"
                              "out vec4 o_rs;\n"
                              "out vec4 o_ts;\n"
                              "void main() {\n"
                              "    vec3 rs, ts;\n"
                              "    snell_thin_slab(a_p.x, a_p.y, a_sigma, a_p.z, rs, ts);\n"
                              "    o_rs = vec4(rs, 0.0);\n"
                              "    o_ts = vec4(ts, 0.0);\n"
                              "    gl_Position = vec4(0.0);\n"
                              "}\n";

typedef struct slab_input {
    float p[4], sigma[3];
} slab_input;

static const double slab_cos[] = {1, 0.999, 0.9, 0.7, 0.5, 0.3, 0.1, 0.01, 1e-3, 1e-5, 0, -0.6};
static const double slab_ior[] = {0.75, 1.0001, 1.33, 1.5, 2.42, 4.0};
static const double slab_thick[] = {0, 0.01, 0.5, 3};
static const double slab_sigma[][3] = {{0, 0, 0}, {0.1, 0.5, 2.0}, {5, 20, 0.01}};

/* rs, ts of the slab as the sum of its bounce series (reflected: R, then
 * (1-R)^2 R ti^2 (R ti)^(2k); transmitted: (1-R)^2 ti (R ti)^(2k)), term by
 * term; only where R ti <= 0.9 (200 terms leave < 1e-18). */
static void slab_series(double r, double ti, double *rs, double *ts)
{
    double q = r * r * ti * ti, term = 1.0;
    int k;
    *rs = r;
    *ts = 0.0;
    for (k = 0; k < 200; k++) {
        *rs += (1 - r) * (1 - r) * r * ti * ti * term;
        *ts += (1 - r) * (1 - r) * ti * term;
        term *= q;
    }
}

static void thin_slab_twin(snell_ctx *ctx)
{
    enum {
        NC = sizeof slab_cos / sizeof *slab_cos,
        NR = sizeof slab_ior / sizeof *slab_ior,
        NT = sizeof slab_thick / sizeof *slab_thick,
        NS = sizeof slab_sigma / sizeof *slab_sigma,
        N = NC * NR * NT * NS
    };
    const char *varyings[] = {"o_rs", "o_ts"};
    static slab_input in[N];
    static float out[2][N][4];
    GLuint prog = 0, vao, vbo, tfb[2], fbo, rb;
    int k, c, analytic = 0, series = 0, nonfinite = 0;
    char first_nonfinite[256] = "";
    double max_twin = 0, max_c = 0, max_an = 0, max_series = 0;
    CHECK_OK(snell__program_build_feedback(ctx, slab_vs, NULL, varyings, 2, &prog));
    if (!prog) return;
    k = 0;
    for (int a = 0; a < NC; a++)
        for (int m = 0; m < NR; m++)
            for (int t = 0; t < NT; t++)
                for (int sg = 0; sg < NS; sg++) {
                    in[k].p[0] = (float)slab_cos[a];
                    in[k].p[1] = (float)slab_ior[m];
                    in[k].p[2] = (float)slab_thick[t];
                    in[k].p[3] = 0.0f;
                    for (c = 0; c < 3; c++) in[k].sigma[c] = (float)slab_sigma[sg][c];
                    k++;
                }
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof in, in, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(slab_input), (void *)offsetof(slab_input, p));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(slab_input), (void *)offsetof(slab_input, sigma));
    glGenBuffers(2, tfb);
    for (c = 0; c < 2; c++) {
        glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb[c]);
        glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, sizeof out[c], NULL, GL_STATIC_READ);
        glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, (GLuint)c, tfb[c]);
    }
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 1, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    glUseProgram(prog);
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, N);
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    for (c = 0; c < 2; c++) {
        void *p;
        glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb[c]);
        p = glMapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, sizeof out[c], GL_MAP_READ_BIT);
        CHECK(p != NULL, "map slab feedback buffer %d", c);
        if (p) memcpy(out[c], p, sizeof out[c]);
        glUnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER);
    }
    CHECK(glGetError() == GL_NO_ERROR, "GL error (slab)");

    for (k = 0; k < N; k++) {
        const slab_input *q = &in[k];
        double sd[3], rsd[3], tsd[3], cd = q->p[0], iord = q->p[1], thd = q->p[2];
        double R = snell_optd_fresnel_schlick(fabs(cd), 1.0, iord);
        float rsf[3], tsf[3];
        for (c = 0; c < 3; c++) sd[c] = q->sigma[c];
        snell_opt_thin_slab(q->p[0], q->p[1], q->sigma, q->p[2], rsf, tsf);
        snell_optd_thin_slab(cd, iord, sd, thd, rsd, tsd);
        for (c = 0; c < 3; c++) {
            const double gl_rs = out[0][k][c], gl_ts = out[1][k][c];
            int fin = isfinite(gl_rs) && isfinite(gl_ts) && isfinite(rsf[c]) && isfinite(tsf[c]) && isfinite(rsd[c]) &&
                      isfinite(tsd[c]);
            if (!fin && !nonfinite++)
                snprintf(first_nonfinite, sizeof first_nonfinite,
                         "cos %g, ior %g, thickness %g, sigma %g: GL rs %g ts %g, C %g %g, double %g %g", cd, iord, thd,
                         sd[c], gl_rs, gl_ts, rsf[c], tsf[c], rsd[c], tsd[c]);
            if (!fin) continue;
            /* Physical: reflected and transmitted parts are shares of the light. */
            CHECK(gl_rs >= 0 && gl_ts >= 0 && gl_rs + gl_ts <= 1.0 + 2e-5 && rsd[c] + tsd[c] <= 1.0 + 1e-12,
                  "slab input %d comp %d: rs %g + ts %g outside [0, 1]", k, c, gl_rs, gl_ts);
            /* Twin: GL and C float against double. rs and ts are polynomials
             * and a quotient in Schlick's R, in [0, 1]: the Fresnel twin's
             * absolute tolerance 2e-5 (above). */
            {
                double eg = fmax(fabs(gl_rs - rsd[c]), fabs(gl_ts - tsd[c]));
                double ec = fmax(fabs(rsf[c] - rsd[c]), fabs(tsf[c] - tsd[c]));
                max_twin = fmax(max_twin, eg);
                max_c = fmax(max_c, ec);
                CHECK(eg <= 2e-5 && ec <= 2e-5,
                      "slab input %d (cos %g, ior %g, thickness %g, sigma %g) comp %d: GL rs %.7g ts %.7g, "
                      "C %.7g %.7g, double %.7g %.7g",
                      k, cd, iord, thd, sd[c], c, gl_rs, gl_ts, rsf[c], tsf[c], rsd[c], tsd[c]);
            }
            /* Analytic, no absorption (sigma 0 or thickness 0): ti = 1, so
             * rs = R + (1-R)^2 R / (1 - R^2) = 2R / (1 + R), ts = 1 - rs. */
            if (!(q->sigma[c] > 0.0f && q->p[2] > 0.0f)) {
                double want = 2.0 * R / (1.0 + R);
                double e = fmax(fmax(fabs(gl_rs - want), fabs(gl_rs + gl_ts - 1.0)),
                                fmax(fabs(rsf[c] - want), fabs(rsf[c] + tsf[c] - 1.0)));
                max_an = fmax(max_an, e);
                analytic++;
                CHECK(e <= 2e-5 && fabs(rsd[c] - want) <= 1e-10 && fabs(rsd[c] + tsd[c] - 1.0) <= 1e-10,
                      "slab input %d comp %d: no absorption: rs GL %.7g C %.7g double %.12g, want 2R/(1+R) = %.12g; "
                      "rs + ts GL %.7g double %.12g",
                      k, c, gl_rs, rsf[c], rsd[c], want, gl_rs + gl_ts, rsd[c] + tsd[c]);
            } else {
                /* Absorbing: the bounce series term by term, with the chord
                 * thickness / cos_t (Snell at the first face). */
                double s2 = (1.0 - cd * cd) / (iord * iord), ct = sqrt(1.0 - fmin(s2, 1.0));
                double ti = exp(-sd[c] * thd / fmax(ct, 1e-6)), rs_s, ts_s;
                if (R * ti <= 0.9) {
                    slab_series(R, ti, &rs_s, &ts_s);
                    max_series = fmax(max_series, fmax(fabs(rsd[c] - rs_s), fabs(tsd[c] - ts_s)));
                    series++;
                    CHECK(fabs(rsd[c] - rs_s) <= 1e-12 && fabs(tsd[c] - ts_s) <= 1e-12 && fabs(gl_rs - rs_s) <= 2e-5 &&
                              fabs(gl_ts - ts_s) <= 2e-5,
                          "slab input %d comp %d: series rs %.12g ts %.12g vs double %.12g %.12g, GL %.7g %.7g", k, c,
                          rs_s, ts_s, rsd[c], tsd[c], gl_rs, gl_ts);
                }
            }
        }
    }
    /* Where Schlick's R is 1 (exactly grazing incidence, or beyond the
     * critical angle of an IOR below 1) without absorption, the closed form
     * is 0/0; the slab then reflects everything: rs = 1, ts = 0. */
    CHECK(nonfinite == 0, "%d slab results not finite, e.g. %s", nonfinite, first_nonfinite);
    CHECK(analytic > N / 4 && series > N / 4, "the slab grid must exercise both cases (%d, %d)", analytic, series);
    printf("thin slab: %d inputs x 3 channels, %d analytic, %d series, %d not finite; max |GL - double| %.3g, "
           "|C - double| %.3g, analytic %.3g, series %.3g\n",
           N, analytic, series, nonfinite, max_twin, max_c, max_an, max_series);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &rb);
    glDeleteBuffers(2, tfb);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(prog);
}

/* The per-channel refraction of the one-path dispersion (snell_refract_rgb /
 * snell_opt_refract_rgb): three directions, three normals and three etas,
 * the channels' IORs of a dispersive material (snell_optd_ior_rgb) entering
 * and leaving, so that some channels are totally reflected where others
 * refract; each channel against optics.h's refraction in double. */
static const char rgb_vs[] = "precision highp float;\n"
                             "#include \"common/optics.glsl\"\n"
                             "layout(location = 0) in vec3 a_i0;\n"
                             "layout(location = 1) in vec3 a_i1;\n"
                             "layout(location = 2) in vec3 a_i2;\n"
                             "layout(location = 3) in vec3 a_n0;\n"
                             "layout(location = 4) in vec3 a_n1;\n"
                             "layout(location = 5) in vec3 a_n2;\n"
                             "layout(location = 6) in vec3 a_eta;\n"
                             "out vec4 o_t0, o_t1, o_t2; // direction, refracted? 1 : 0\n"
                             "void main() {\n"
                             "    mat3 t;\n"
                             "    bvec3 ok = snell_refract_rgb(mat3(a_i0, a_i1, a_i2), mat3(a_n0, a_n1, a_n2), a_eta, t);\n"
                             "    o_t0 = vec4(t[0], ok.x ? 1.0 : 0.0);\n"
                             "    o_t1 = vec4(t[1], ok.y ? 1.0 : 0.0);\n"
                             "    o_t2 = vec4(t[2], ok.z ? 1.0 : 0.0);\n"
                             "    gl_Position = vec4(0.0);\n"
                             "}\n";

typedef struct rgb_input { float i[3][3], n[3][3], eta[3]; } rgb_input;

static void refract_rgb_twin(snell_ctx *ctx)
{
    static const double rgb_ior[] = {1.33, 1.5, 2.42}, rgb_disp[] = {0.0, 0.36, 1.0, 3.0};
    enum { NA = sizeof angles_deg / sizeof *angles_deg, NR = 3, ND = 4, N = NA * NR * ND * 2 };
    const char *varyings[] = {"o_t0", "o_t1", "o_t2"};
    static rgb_input in[N];
    static float out[3][N][4];
    GLuint prog = 0, vao, vbo, tfb[3], fbo, rb;
    int k = 0, c, j, split = 0;
    double max_err = 0.0;
    CHECK_OK(snell__program_build_feedback(ctx, rgb_vs, NULL, varyings, 3, &prog));
    if (!prog) return;
    for (int a = 0; a < NA; a++)
        for (int m = 0; m < NR; m++)
            for (int d = 0; d < ND; d++)
                for (int leave = 0; leave < 2; leave++) {
                    double n_rgb[3];
                    snell_optd_ior_rgb(rgb_ior[m], rgb_disp[d], n_rgb);
                    for (c = 0; c < 3; c++) {
                        /* each channel's own direction and normal: turned by (c - 1) * 0.01 rad */
                        double th = angles_deg[a] * SNELL_PI / 180.0 + (c - 1) * 0.01, tilt = (c - 1) * 0.01;
                        in[k].i[c][0] = (float)sin(th);
                        in[k].i[c][1] = 0.0f;
                        in[k].i[c][2] = (float)-cos(th);
                        in[k].n[c][0] = (float)sin(tilt);
                        in[k].n[c][1] = 0.0f;
                        in[k].n[c][2] = (float)cos(tilt);
                        in[k].eta[c] = (float)(leave ? n_rgb[c] : 1.0 / n_rgb[c]);
                    }
                    k++;
                }
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof in, in, GL_STATIC_DRAW);
    for (c = 0; c < 3; c++) {
        glEnableVertexAttribArray((GLuint)c);
        glVertexAttribPointer((GLuint)c, 3, GL_FLOAT, GL_FALSE, sizeof(rgb_input),
                              (void *)(offsetof(rgb_input, i) + c * 3 * sizeof(float)));
        glEnableVertexAttribArray((GLuint)(3 + c));
        glVertexAttribPointer((GLuint)(3 + c), 3, GL_FLOAT, GL_FALSE, sizeof(rgb_input),
                              (void *)(offsetof(rgb_input, n) + c * 3 * sizeof(float)));
    }
    glEnableVertexAttribArray(6);
    glVertexAttribPointer(6, 3, GL_FLOAT, GL_FALSE, sizeof(rgb_input), (void *)offsetof(rgb_input, eta));
    glGenBuffers(3, tfb);
    for (c = 0; c < 3; c++) {
        glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb[c]);
        glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, sizeof out[c], NULL, GL_STATIC_READ);
        glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, (GLuint)c, tfb[c]);
    }
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 1, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    glUseProgram(prog);
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, N);
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    for (c = 0; c < 3; c++) {
        void *p;
        glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb[c]);
        p = glMapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, sizeof out[c], GL_MAP_READ_BIT);
        CHECK(p != NULL, "map per-channel feedback buffer %d", c);
        if (p) memcpy(out[c], p, sizeof out[c]);
        glUnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER);
    }
    CHECK(glGetError() == GL_NO_ERROR, "GL error (per-channel refraction)");
    for (k = 0; k < N; k++) {
        float t[3][3];
        int through = snell_opt_refract_rgb((const float(*)[3])in[k].i, (const float(*)[3])in[k].n, in[k].eta, t);
        int split_here = 0;
        for (c = 0; c < 3; c++) {
            double id[3], nd[3], td[3], cos_i, k_disc;
            int okd;
            for (j = 0; j < 3; j++) {
                id[j] = in[k].i[c][j];
                nd[j] = in[k].n[c][j];
            }
            okd = snell_optd_refract(id, nd, (double)in[k].eta[c], td);
            cos_i = -snell_optd_dot(id, nd);
            k_disc = 1.0 - (double)in[k].eta[c] * in[k].eta[c] * (1.0 - cos_i * cos_i);
            split_here += okd;
            if (fabs(k_disc) <= 1e-5) continue; /* the TIR decision within float rounding */
            CHECK(((through >> c) & 1) == okd && (out[c][k][3] != 0.0f) == okd,
                  "per-channel input %d channel %d: refracted C=%d GL=%g double=%d", k, c, (through >> c) & 1,
                  out[c][k][3], okd);
            for (j = 0; j < 3; j++) {
                double tol = 2e-6 + 4e-7 / sqrt(fabs(k_disc)), eg = fabs(out[c][k][j] - td[j]), ec = fabs(t[c][j] - td[j]);
                if (eg > max_err) max_err = eg;
                CHECK(eg <= tol && ec <= tol, "per-channel input %d channel %d comp %d: GL %.9g C %.9g double %.9g", k,
                      c, j, out[c][k][j], t[c][j], td[j]);
            }
        }
        split += split_here == 1 || split_here == 2;
    }
    CHECK(split >= 4, "the grid must have channels refracted where others are totally reflected (%d)", split);
    printf("per-channel refraction: %d inputs x 3 channels, %d with the channels split by TIR; max |GL - double| %.3g\n",
           N, split, max_err);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &rb);
    glDeleteBuffers(3, tfb);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(prog);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    const char *varyings[] = {"o_t", "o_r", "o_bl"};
    enum { NA = sizeof angles_deg / sizeof *angles_deg, NI = sizeof iors / sizeof *iors, N = NA * NI * 2 * 2 };
    input in[N];
    float out[3][N][4];
    GLuint prog = 0, vao, vbo, tfb[3], fbo, rb;
    int k, c, tir_cases = 0, grazing_cases = 0;
    double max_dir_err = 0, max_f_err = 0, max_fx_err = 0, max_bl_err = 0;
    if (!ctx) SKIP("no GL context");
    CHECK_OK(snell__program_build_feedback(ctx, vs, NULL, varyings, 3, &prog));
    if (!prog) return test_finish();

    /* Incidence in the xz-plane, normal +z, ray going down; two normal
     * orientations (axis-aligned and tilted) so rounding differs. */
    k = 0;
    for (int a = 0; a < NA; a++)
        for (int m = 0; m < NI; m++)
            for (int dir = 0; dir < 2; dir++)
                for (int tilt = 0; tilt < 2; tilt++) {
                    double th = angles_deg[a] * SNELL_PI / 180.0, n1 = dir ? iors[m] : 1.0, n2 = dir ? 1.0 : iors[m];
                    double nrm[3] = {0, 0, 1}, inc[3] = {sin(th), 0, -cos(th)};
                    if (tilt) { /* rotate both about the y axis by 0.3 rad */
                        double cr = cos(0.3), sr = sin(0.3), x, z;
                        x = nrm[0] * cr + nrm[2] * sr; z = -nrm[0] * sr + nrm[2] * cr; nrm[0] = x; nrm[2] = z;
                        x = inc[0] * cr + inc[2] * sr; z = -inc[0] * sr + inc[2] * cr; inc[0] = x; inc[2] = z;
                    }
                    for (c = 0; c < 3; c++) { in[k].i[c] = (float)inc[c]; in[k].n[c] = (float)nrm[c]; }
                    in[k].p[0] = (float)(n1 / n2);
                    in[k].p[1] = (float)n1;
                    in[k].p[2] = (float)n2;
                    in[k].p[3] = (float)(0.25 * a);
                    k++;
                }

    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof in, in, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(input), (void *)offsetof(input, i));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(input), (void *)offsetof(input, n));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, sizeof(input), (void *)offsetof(input, p));
    glGenBuffers(3, tfb);
    for (c = 0; c < 3; c++) {
        glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb[c]);
        glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, sizeof out[c], NULL, GL_STATIC_READ);
        glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, (GLuint)c, tfb[c]);
    }
    /* A surfaceless context has no default framebuffer, and draws need a
     * complete one even with rasterisation discarded. */
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 1, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    glUseProgram(prog);
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, N);
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    for (c = 0; c < 3; c++) {
        void *p;
        glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb[c]);
        p = glMapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, sizeof out[c], GL_MAP_READ_BIT);
        CHECK(p != NULL, "map feedback buffer %d", c);
        if (p) memcpy(out[c], p, sizeof out[c]);
        glUnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER);
    }
    CHECK(glGetError() == GL_NO_ERROR, "GL error");

    for (k = 0; k < N; k++) {
        float t[3], r[3], bl[3], sig[3] = {0.1f, 0.5f, 2.0f};
        double id[3], nd[3], td[3], k_disc, cos_i;
        int ok = snell_opt_refract(in[k].i, in[k].n, in[k].p[0], t), okd;
        float f = snell_opt_fresnel_schlick(-snell_opt_dot(in[k].i, in[k].n), in[k].p[1], in[k].p[2]);
        for (c = 0; c < 3; c++) { id[c] = in[k].i[c]; nd[c] = in[k].n[c]; }
        okd = snell_optd_refract(id, nd, (double)in[k].p[0], td);
        cos_i = -snell_optd_dot(id, nd);
        k_disc = 1.0 - (double)in[k].p[0] * in[k].p[0] * (1.0 - cos_i * cos_i);
        snell_opt_reflect(in[k].i, in[k].n, r);
        snell_opt_beer_lambert(sig, in[k].p[3], bl);
        tir_cases += !okd;
        grazing_cases += cos_i < 0.002;
        /* The TIR decision may only differ within float rounding of k = 0. */
        if (fabs(k_disc) > 1e-5) {
            CHECK(ok == okd && (out[0][k][3] != 0.0f) == okd, "input %d: TIR flag C=%d GL=%g double=%d", k, ok,
                  out[0][k][3], okd);
            /* d t / d k ~ 1 / sqrt(k): allow the float rounding of k through the square root. */
            {
                double tol = 2e-6 + 4e-7 / sqrt(fabs(k_disc));
                for (c = 0; c < 3; c++) {
                    double eg = fabs(out[0][k][c] - td[c]), ec = fabs(t[c] - td[c]);
                    if (eg > max_dir_err) max_dir_err = eg;
                    CHECK(eg <= tol && ec <= tol, "input %d comp %d: GL %.9g C %.9g double %.9g (tol %.2g)", k, c,
                          out[0][k][c], t[c], td[c], tol);
                }
            }
        }
        for (c = 0; c < 3; c++) CHECK(fabsf(out[1][k][c] - r[c]) <= 1e-6f, "input %d reflect", k);
        {
            double fd = snell_optd_fresnel_schlick(cos_i, in[k].p[1], in[k].p[2]);
            double ef = fabs(out[1][k][3] - fd);
            if (fabs(k_disc) > 1e-5 && ef > max_f_err) max_f_err = ef;
            if (fabs(k_disc) > 1e-5)
                CHECK(ef <= 2e-5 && fabs(f - fd) <= 2e-5, "input %d Fresnel GL %.7g C %.7g double %.7g", k,
                      out[1][k][3], f, fd);
            CHECK(out[1][k][3] >= 0.0f && out[1][k][3] <= 1.0f, "Fresnel in [0,1]");
        }
        {
            double fd = snell_optd_fresnel_exact(cos_i, in[k].p[1], in[k].p[2]);
            double fc = snell_opt_fresnel_exact(-snell_opt_dot(in[k].i, in[k].n), in[k].p[1], in[k].p[2]);
            double fa = fresnel_angles(cos_i, in[k].p[1], in[k].p[2]);
            double ef = fabs(out[2][k][3] - fd);
            if (fabs(k_disc) > 1e-5 && ef > max_fx_err) max_fx_err = ef;
            if (fabs(k_disc) > 1e-5)
                CHECK(ef <= 2e-5 && fabs(fc - fd) <= 2e-5 && fabs(fd - fa) <= 1e-9,
                      "input %d exact Fresnel GL %.7g C %.7g double %.9g angle form %.9g", k, out[2][k][3], fc, fd, fa);
            CHECK(out[2][k][3] >= 0.0f && out[2][k][3] <= 1.0f, "exact Fresnel in [0,1]");
            if (in[k].p[1] == in[k].p[2])
                CHECK(out[2][k][3] == 0.0f && out[1][k][3] == 0.0f, "input %d: reflection at matched indices", k);
        }
        for (c = 0; c < 3; c++) {
            double e = fabs(out[2][k][c] - bl[c]) / (bl[c] > 1e-30f ? bl[c] : 1.0f);
            if (e > max_bl_err) max_bl_err = e;
            CHECK(e <= 1e-5, "input %d Beer-Lambert %g vs %g", k, out[2][k][c], bl[c]);
        }
    }
    CHECK(tir_cases > 20, "the grid must exercise TIR (%d cases)", tir_cases);
    CHECK(grazing_cases >= 8, "the grid must exercise grazing angles (%d cases)", grazing_cases);
    printf("%d inputs, %d TIR, %d grazing; max |GL - double| direction %.3g, Schlick %.3g, exact Fresnel %.3g, "
           "Beer-Lambert rel %.3g\n",
           N, tir_cases, grazing_cases, max_dir_err, max_f_err, max_fx_err, max_bl_err);
    exact_fresnel_properties();

    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &rb);
    glDeleteBuffers(3, tfb);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(prog);
    thin_slab_twin(ctx);
    refract_rgb_twin(ctx);
    snell_ctx_destroy(ctx);
    return test_finish();
}
