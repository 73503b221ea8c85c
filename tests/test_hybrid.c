/* SPDX-License-Identifier: MIT */
/* test_hybrid — SNELL_METHOD_HYBRID (issue 50 item 2): the cubemap's doubt
 * mask (hybrid.doubted=show) marks the pixels where the cubemap's exit
 * direction is wrong on a torus (surfaces hidden from the cube's centre)
 * and leaves a sphere's, where it is right, unmarked; the hybrid's image
 * is exact's on the marked pixels and the cubemap's on the others, in
 * whichever shading the suite runs (forward, or screen space with its
 * depth moved and restored: a sphere drawn forward after it stays in
 * front); bad parameters fail with a message. */
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 96
#define WRONG_DEG 5.0 /* the cubemap's exit direction this far from exact's: it is wrong there */
#define CUBE_TOLERANCE 12 /* of 255: the hybrid's cubemap pass against the cubemap alone */

static const uint8_t g_magenta[3] = {255, 0, 255};

static int max_diff(const uint8_t *a, const uint8_t *b)
{
    int k, d = 0;
    for (k = 0; k < 3; k++) d = abs(a[k] - b[k]) > d ? abs(a[k] - b[k]) : d;
    return d;
}

static snell_renderer *g_dirs; /* an exit-direction renderer beside the colour one */

static void render_dirs(snell_ctx *ctx, snell_frame_desc *fd, snell_glass *g, snell_method m, float *xyz)
{
    snell_frame_stats st;
    g->material.method = m;
    CHECK_OK_CTX(ctx, snell_render(g_dirs, fd, &st));
    CHECK_OK(snell_renderer_read_exit_dirs(g_dirs, xyz));
}

static void render(snell_ctx *ctx, snell_renderer *r, snell_frame_desc *fd, snell_glass *g, snell_method m,
                   snell_hybrid_doubted doubted, uint8_t *px)
{
    snell_frame_stats st;
    g->material.method = m;
    g->material.hybrid.doubted = doubted;
    CHECK_OK_CTX(ctx, snell_render(r, fd, &st));
    CHECK(st.glass[0].method_used == m, "drawn with %s, not %s (%s)", snell_method_str(st.glass[0].method_used),
          snell_method_str(m), st.glass[0].reason);
    CHECK_OK(snell_renderer_read_rgba(r, px));
}

/* Renders the shape four ways and checks the mask and the composition;
 * returns the share of wrong pixels the mask marks (recall), and the share
 * of glass pixels marked in *marked_share. */
static double check_shape(snell_ctx *ctx, snell_renderer *r, snell_env *env, snell_shape shape, const char *name,
                          float elevation, double *marked_share)
{
    static uint8_t cube[W * H * 4], exact[W * H * 4], show[W * H * 4], hybrid[W * H * 4], sky[W * H * 4];
    static float cube_dir[W * H * 3], exact_dir[W * H * 3];
    snell_shape_desc sd;
    snell_mesh *mesh = NULL;
    snell_frame_desc fd;
    snell_glass g;
    snell_frame_stats st;
    static uint8_t is_glass[W * H];
    int i, glass = 0, marked = 0, wrong = 0, wrong_marked = 0, off_exact = 0, off_cube = 0, near_cube = 0;
    memset(&sd, 0, sizeof sd);
    sd.shape = shape;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    *marked_share = 0.0;
    if (!mesh) return 0.0;
    test_frame_one(&fd, &g, mesh, env);
    /* the cubemap alone as the hybrid draws it: its cap, and the MATCHED
     * model exact computes (no inner Fresnel) */
    g.material.cubemap.max_interfaces = g.material.hybrid.max_interfaces = 4;
    g.material.cubemap.inner_fresnel = SNELL_INNER_FRESNEL_OFF;
    fd.camera.elevation = elevation;
    fd.camera.distance = 3.0f;
    render(ctx, r, &fd, &g, SNELL_METHOD_CUBEMAP, SNELL_HYBRID_DOUBTED_DEFAULT, cube);
    render(ctx, r, &fd, &g, SNELL_METHOD_EXACT, SNELL_HYBRID_DOUBTED_DEFAULT, exact);
    render(ctx, r, &fd, &g, SNELL_METHOD_HYBRID, SNELL_HYBRID_DOUBTED_SHOW, show);
    render(ctx, r, &fd, &g, SNELL_METHOD_HYBRID, SNELL_HYBRID_DOUBTED_EXACT, hybrid);
    render_dirs(ctx, &fd, &g, SNELL_METHOD_CUBEMAP, cube_dir);
    render_dirs(ctx, &fd, &g, SNELL_METHOD_EXACT, exact_dir);
    fd.glass_count = 0; /* the sky alone: the glass pixels are those any method changes */
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
    CHECK_OK(snell_renderer_read_rgba(r, sky));
    for (i = 0; i < W * H; i++)
        is_glass[i] = max_diff(cube + 4 * i, sky + 4 * i) || max_diff(exact + 4 * i, sky + 4 * i) ||
                      max_diff(hybrid + 4 * i, sky + 4 * i);
    for (i = 0; i < W * H; i++) {
        const uint8_t *c = cube + 4 * i, *e = exact + 4 * i, *s = show + 4 * i, *h = hybrid + 4 * i;
        int is_marked = max_diff(s, g_magenta) == 0 && max_diff(c, g_magenta) != 0;
        int x = i % W, y = i / W;
        /* the silhouette's pixels apart: exact's eye ray through the pixel
         * centre and the rasterised surface part there whatever the exit */
        int edge = x == 0 || y == 0 || x == W - 1 || y == H - 1 || !is_glass[i - 1] || !is_glass[i + 1] ||
                   !is_glass[i - W] || !is_glass[i + W];
        if (!is_glass[i]) continue;
        glass++;
        marked += is_marked;
        if (!edge && test_dir_angle(cube_dir + 3 * i, exact_dir + 3 * i) * (180.0 / 3.14159265358979) > WRONG_DEG) {
            wrong++;
            wrong_marked += is_marked;
        }
        if (is_marked) off_exact += max_diff(h, e) > 1;
        else {
            /* the same search in another program: float contraction may
             * differ by an ulp, a few levels where the sky is sharp */
            off_cube += max_diff(h, c) > CUBE_TOLERANCE;
            near_cube += max_diff(h, c) > 1;
        }
    }
    printf("%s: %d glass pixels, %d marked, %d where the cubemap is wrong (> %g deg off exact), %d of them marked; "
           "the hybrid off exact on %d marked pixels, off the cubemap on %d others (%d by more than 1/255)\n",
           name, glass, marked, wrong, WRONG_DEG, wrong_marked, off_exact, off_cube, near_cube);
    CHECK(glass > 300, "%s: only %d glass pixels", name, glass);
    CHECK(off_exact == 0, "%s: the hybrid differs from exact on %d of its %d marked pixels", name, off_exact, marked);
    CHECK(off_cube == 0, "%s: the hybrid differs from the cubemap on %d unmarked pixels", name, off_cube);
    snell_mesh_destroy(mesh);
    *marked_share = glass ? (double)marked / glass : 0.0;
    return wrong ? (double)wrong_marked / wrong : 1.0;
}

/* Shading chosen per object (the suite's AUTO run): the torus by the
 * hybrid on the G-buffer (screen space), a sphere in its hole drawn forward
 * after it, in front of the torus's far side. Every pixel must be the frame
 * with the cubemap's torus or the one with exact's: where the hybrid left
 * its doubted pixels' depth at the near plane, the sphere would vanish. */
static void check_mixed_shading(snell_ctx *ctx, snell_renderer *r, snell_env *env)
{
    static uint8_t cube[W * H * 4], exact[W * H * 4], hybrid[W * H * 4];
    static const float place[16] = {0.45f, 0, 0, 0, 0, 0.45f, 0, 0, 0, 0, 0.45f, 0, 0, 0.1f, 0, 1};
    snell_shape_desc sd;
    snell_mesh *torus = NULL, *sphere = NULL;
    snell_frame_desc fd;
    snell_glass g[2];
    snell_frame_stats st;
    int i, off = 0;
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_TORUS;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &torus));
    sd.shape = SNELL_SHAPE_SPHERE;
    sd.segments = 12; /* large triangles: AUTO draws it forward */
    sd.rings = 6;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &sphere));
    if (!torus || !sphere) return;
    test_frame_one(&fd, &g[0], torus, env);
    memset(&g[1], 0, sizeof g[1]);
    g[1].mesh = sphere;
    g[1].model = place;
    g[1].material.method = SNELL_METHOD_SINGLE;
    fd.glass_count = 2;
    fd.camera.elevation = 0.8f;
    fd.camera.distance = 3.0f;
    g[0].material.cubemap.max_interfaces = 4;
    g[0].material.cubemap.inner_fresnel = SNELL_INNER_FRESNEL_OFF;
    render(ctx, r, &fd, &g[0], SNELL_METHOD_CUBEMAP, SNELL_HYBRID_DOUBTED_DEFAULT, cube);
    render(ctx, r, &fd, &g[0], SNELL_METHOD_EXACT, SNELL_HYBRID_DOUBTED_DEFAULT, exact);
    g[0].material.method = SNELL_METHOD_HYBRID;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, &st));
    CHECK_OK(snell_renderer_read_rgba(r, hybrid));
    CHECK(st.glass[0].screen_space && !st.glass[1].screen_space, "the torus in screen space (%d), the sphere "
          "forward (%d)", st.glass[0].screen_space, st.glass[1].screen_space);
    for (i = 0; i < W * H; i++) {
        const uint8_t *h = hybrid + 4 * i;
        off += max_diff(h, cube + 4 * i) > CUBE_TOLERANCE && max_diff(h, exact + 4 * i) > 1;
    }
    printf("mixed shading: %d pixels neither the cubemap's frame nor exact's\n", off);
    CHECK(off == 0, "mixed shading: %d pixels neither the cubemap's frame nor exact's", off);
    snell_mesh_destroy(torus);
    snell_mesh_destroy(sphere);
}

static void check_bad_params(void)
{
    snell_glass_material m;
    snell_glass_resolved out;
    memset(&m, 0, sizeof m);
    m.method = SNELL_METHOD_HYBRID;
    m.hybrid.doubt = 1001;
    CHECK(snell_glass_defaults(&m, &out) == SNELL_E_INVALID_ARG, "hybrid.doubt = 1001 accepted");
    m.hybrid.doubt = 0;
    CHECK(snell_glass_set_param(&m, SNELL_METHOD_HYBRID, "doubted", "maybe") == SNELL_E_INVALID_ARG,
          "hybrid.doubted = maybe accepted");
    CHECK_OK(snell_glass_set_param(&m, SNELL_METHOD_HYBRID, "doubted", "show"));
    CHECK_OK(snell_glass_defaults(&m, &out));
    CHECK(out.material.hybrid.doubt == SNELL_HYBRID_DEFAULT_DOUBT, "default doubt %d", out.material.hybrid.doubt);
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_env *env;
    double recall, share_torus, share_sphere;
    if (!ctx) SKIP("no GL context");
    check_bad_params();
    env = test_sky(ctx, 128);
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.shading = test_shading();
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r));
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &g_dirs));
    if (env && r && g_dirs) {
        /* the sphere: star-shaped about its centre, no total reflection at
         * its exit; the cubemap is right everywhere and doubts nowhere */
        check_shape(ctx, r, env, SNELL_SHAPE_SPHERE, "sphere", 0.35f, &share_sphere);
        CHECK(share_sphere < 0.01, "sphere: %.1f%% of the glass marked", 100.0 * share_sphere);
        /* the torus from 46 degrees up: its far side's inner ring is hidden
         * from the cube's centre, in the near side's tube (measured: 96% of
         * the wrong pixels marked, 37% of the glass; seen edge-on, el 0,
         * only 14%: a path that crosses a hidden surface between an entry
         * and an exit the cube holds is not doubted) */
        recall = check_shape(ctx, r, env, SNELL_SHAPE_TORUS, "torus", 0.8f, &share_torus);
        printf("torus: the mask marks %.0f%% of the wrong pixels, %.0f%% of the glass\n", 100.0 * recall,
               100.0 * share_torus);
        CHECK(recall > 0.8, "torus: the mask marks only %.0f%% of the pixels the cubemap gets wrong", 100.0 * recall);
        CHECK(share_torus < 0.6, "torus: the mask marks %.0f%% of the glass", 100.0 * share_torus);
        if (rd.shading == SNELL_SHADING_AUTO) check_mixed_shading(ctx, r, env);
    }
    snell_renderer_destroy(r);
    snell_renderer_destroy(g_dirs);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
