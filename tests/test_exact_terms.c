/* SPDX-License-Identifier: MIT */
/* test_exact_terms — exact's FULL-model terms (material.exact.fresnel,
 * inner_fresnel, reentry) against the MATCHED reference with the same
 * snell_ref_terms, on a sphere, a torus seen through its hole and a goblet,
 * with absorption: the mean colour difference over the glass pixels below
 * 1/255, while the plain kernel's differs from that reference by several
 * times as much where the term matters (measured: 0.1-0.4/255 against
 * 0.7-13/255); with every term, closer to FULL than the plain kernel. */
#include "test_util.h"

#include <math.h>
#include <string.h>

#define W 64
#define H 64
#define INTERFACES 10

typedef struct terms_case {
    const char *name;
    snell_fresnel_model fresnel;
    snell_inner_fresnel inner;
    snell_exact_reentry reentry;
    unsigned ref_terms;
    unsigned matters;   /* bits 1 << snell_shape where the plain kernel is far from this model */
} terms_case;

static const terms_case g_cases[] = {
    /* Schlick's error is largest on the sphere's grazing rim */
    {"fresnel=exact", SNELL_FRESNEL_EXACT, SNELL_INNER_FRESNEL_OFF, SNELL_EXACT_REENTRY_OFF, SNELL_REF_TERM_EXACT_FRESNEL,
     1u << SNELL_SHAPE_SPHERE},
    {"inner_fresnel=on", SNELL_FRESNEL_SCHLICK, SNELL_INNER_FRESNEL_ON, SNELL_EXACT_REENTRY_OFF,
     SNELL_REF_TERM_INNER_REFLECTION, ~0u},
    /* convex: nothing to re-enter; the goblet's bowl and stem: much */
    {"reentry=on", SNELL_FRESNEL_SCHLICK, SNELL_INNER_FRESNEL_OFF, SNELL_EXACT_REENTRY_ON, SNELL_REF_TERM_REENTRY,
     1u << SNELL_SHAPE_GOBLET},
    {"all", SNELL_FRESNEL_EXACT, SNELL_INNER_FRESNEL_ON, SNELL_EXACT_REENTRY_ON, SNELL_REF_TERMS_ALL, ~0u},
};

/* The reference's colour for fd: MATCHED with terms (or FULL), isolated. */
static void reference(snell_ctx *ctx, const snell_frame_desc *fd, snell_ref_mode mode, unsigned terms,
                      uint8_t *px, uint8_t *hit)
{
    static float rgb[W * H * 3], dirs[W * H * 3];
    snell_ref *ref = NULL;
    snell_ref_params p;
    CHECK_OK(test_ref_create(ctx, fd, &ref));
    if (!ref) return;
    test_ref_params(fd, W, H, INTERFACES, &p);
    p.mode = mode;
    p.terms = terms;
    p.isolate_glass = 1;
    CHECK_OK(test_ref_render(ref, &p, rgb, dirs, hit));
    snell_ref_rgb_to_rgba8(rgb, W, H, px);
    snell_ref_destroy(ref);
}

/* Mean |difference| per channel over the pixels the reference calls glass, in 1/255. */
static double mean_diff(const uint8_t *a, const uint8_t *b, const uint8_t *hit, int *count)
{
    double sum = 0.0;
    int i, k, n = 0;
    for (i = 0; i < W * H; i++) {
        if (!hit[i]) continue;
        n++;
        for (k = 0; k < 3; k++) sum += fabs((double)a[4 * i + k] - b[4 * i + k]) / 3.0;
    }
    *count = n;
    return n ? sum / n : 0.0;
}

static void render(snell_ctx *ctx, snell_renderer *r, const snell_frame_desc *fd, uint8_t *px)
{
    snell_frame_stats st;
    CHECK_OK_CTX(ctx, snell_render(r, fd, &st));
    CHECK(st.glass[0].method_used == SNELL_METHOD_EXACT, "drawn with exact (%s)", st.glass[0].reason);
    CHECK_OK(snell_renderer_read_rgba(r, px));
}

static void check_shape(snell_ctx *ctx, snell_renderer *r, snell_env *env, snell_shape shape, const char *name,
                        float elevation)
{
    static uint8_t hit[W * H], ref_px[W * H * 4], px[W * H * 4], plain[W * H * 4], full_px[W * H * 4];
    const float sigma[3] = {0.6f, 0.25f, 0.05f};
    snell_shape_desc sd;
    snell_mesh *mesh = NULL;
    snell_frame_desc fd;
    snell_glass g;
    size_t c;
    int n;
    memset(&sd, 0, sizeof sd);
    sd.shape = shape;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    if (!mesh) return;
    test_frame_one(&fd, &g, mesh, env);
    g.material.method = SNELL_METHOD_EXACT;
    g.material.exact.max_interfaces = INTERFACES;
    snell_glass_set_absorption(&g.material, sigma);
    fd.camera.elevation = elevation;
    fd.camera.distance = 3.0f;
    render(ctx, r, &fd, plain);
    for (c = 0; c < sizeof g_cases / sizeof *g_cases; c++) {
        const terms_case *tc = &g_cases[c];
        double d, d_plain;
        g.material.exact.fresnel = tc->fresnel;
        g.material.exact.inner_fresnel = tc->inner;
        g.material.exact.reentry = tc->reentry;
        reference(ctx, &fd, SNELL_REF_MATCHED, tc->ref_terms, ref_px, hit);
        render(ctx, r, &fd, px);
        d = mean_diff(px, ref_px, hit, &n);
        d_plain = mean_diff(plain, ref_px, hit, &n);
        printf("%s, %s: mean colour difference %.3f/255 over %d pixels (the plain kernel %.3f/255)\n", name, tc->name,
               d, n, d_plain);
        CHECK(n > 400 && d < 1.0, "%s, %s: mean colour difference %g/255", name, tc->name, d);
        /* where the term changes the image, the plain kernel is far from its model */
        if (tc->matters & (1u << shape))
            CHECK(d_plain > 3.0 * d + 0.3, "%s, %s: the term changes too little (%g/255 without it)", name, tc->name,
                  d_plain);
        if (tc->ref_terms == SNELL_REF_TERMS_ALL) {
            double d_full, d_full_plain;
            reference(ctx, &fd, SNELL_REF_FULL, 0, full_px, hit);
            d_full = mean_diff(px, full_px, hit, &n);
            d_full_plain = mean_diff(plain, full_px, hit, &n);
            printf("%s: against FULL %.3f/255 with every term, %.3f/255 without\n", name, d_full, d_full_plain);
            CHECK(d_full < d_full_plain, "%s: every term must bring exact closer to FULL (%g against %g/255)", name,
                  d_full, d_full_plain);
        }
    }
    snell_mesh_destroy(mesh);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_renderer *r;
    snell_env *env;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 128);
    r = test_renderer(ctx, W, H);
    if (env && r) {
        check_shape(ctx, r, env, SNELL_SHAPE_SPHERE, "sphere", 0.35f);
        check_shape(ctx, r, env, SNELL_SHAPE_TORUS, "torus", 1.2f);
        check_shape(ctx, r, env, SNELL_SHAPE_GOBLET, "goblet", 0.5f);
    }
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
