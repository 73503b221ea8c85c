/* SPDX-License-Identifier: MIT */
/* test_caustics_env — the glass sees the opaque objects lit through its
 * dynamic environment (issue 27; scene layers off: render/env_dynamic.c
 * draws them with caustics_opaque.frag, common/opaque_lit.glsl, as the view
 * does). A cube behind a sphere of IOR 1.001, lit by a light whose sphere
 * shadow and caustic fall beside it (test_caustics_seen's scene), every
 * method, through a cube map, dual-paraboloid maps made from it and maps
 * rendered straight.
 *
 * The bound, derived: an environment map is seen from the sphere's centre,
 * so a pixel shows what the ray parallel to its view ray through the centre
 * meets, not what the view ray meets (parallax, up to 0.6 of the radius
 * here). Compared are the pixels where both rays meet the cube's face
 * towards the camera 0.2 inside its edges (an environment texel there is
 * 0.05 wide, 64 a face; the straight-rendered maps draw the face's edges
 * straight where the projection bends them), a flat face the directional
 * light lights evenly (the sphere's shadow falls beside the cube): both
 * show its one colour, wherever on the face. Inside 60% of the radius
 * Schlick's reflectance at IOR 1.001 is below F0 + 0.2^5 = 3.2e-4 per
 * surface (0.17 of a level over two), a ray turns by about 0.001 of its
 * angle of incidence (it stays on the face), and the environment's RGBA8
 * texel holds the view's own 8-bit value: every pixel within 1 level (a
 * rounding) of the frame without the sphere. With the cube drawn unlit in
 * the environment (as before) the same pixels are the cube of a frame
 * without a light, which the check must tell apart: checked here on every
 * pixel compared (more than 8 levels apart), and by passing NULL for the
 * lighting in stages.c: every method and look-up then failed on all 930
 * pixels (68 levels at most).
 *
 * Then one renderer over frames: the environment is re-rendered when the
 * light moves, when the light's maps are remade for another reason (the
 * receiver's map size), when the light goes; it is reused (and the
 * caustics' maps too) while the light is still, the camera moving; the
 * frame after the light went is the bytes of a renderer that never had
 * one. Checked: with the lighting left out of env_dynamic.c's changed()
 * the three re-render checks, the brighter face and those bytes fail;
 * re-rendering every lit frame fails the reuse checks. */
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 160
#define H 120
#define MARGIN 0.2f   /* world units inside the face's edges (face half side 1.2) */
#define INNER 0.6f    /* of the sphere's radius 1 */
#define FACE_Z (-1.8f)

static const float k_place[16] = {1.2f, 0, 0, 0, 0, 1.2f, 0, 0, 0, 0, 1.2f, 0, 0, 0, -3.0f, 1};

static void render(snell_ctx *ctx, const snell_frame_desc *fd, snell_method m, snell_env_lookup lookup,
                   uint8_t *rgba, float *dirs)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc f = *fd;
    snell_glass g;
    snell_frame_stats s;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.output = dirs ? SNELL_OUTPUT_EXIT_DIRECTION : SNELL_OUTPUT_COLOR;
    rd.shading = test_shading();
    rd.env_lookup = lookup;
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r) return;
    if (f.glass_count) {
        g = f.glass[0];
        g.material.method = m;
        f.glass = &g;
    }
    CHECK_OK_CTX(ctx, snell_render(r, &f, &s));
    if (f.glass_count && f.opaque_count)
        CHECK(s.glass[0].env_updated && s.glass[0].env_paraboloid == (lookup >= SNELL_ENV_LOOKUP_DUAL_PARABOLOID),
              "%s: the sphere saw no dynamic environment of its look-up", snell_method_str(m));
    if (dirs) CHECK_OK(snell_renderer_read_exit_dirs(r, dirs));
    else CHECK_OK(snell_renderer_read_rgba(r, rgba));
    snell_renderer_destroy(r);
}

/* Whether the ray from o along d meets the plane z = FACE_Z inside the face, MARGIN in from its edges. */
static int on_face(const float o[3], const float d[3])
{
    float t = (FACE_Z - o[2]) / d[2], x = o[0] + t * d[0], y = o[1] + t * d[1];
    return t > 0.0f && fabsf(x) < 1.2f - MARGIN && fabsf(y) < 1.2f - MARGIN;
}

/* The pixels compared (above), from the view rays (exit directions of a frame without glass). */
static int compared(const snell_frame_desc *fd, const float *rays, uint8_t *mask)
{
    static const float centre[3] = {0, 0, 0};
    float eye[3], view[16], proj[16];
    int k, n = 0;
    snell_camera_matrices(&fd->camera, (float)W / H, eye, view, proj);
    for (k = 0; k < W * H; k++) {
        const float *d = rays + 3 * k;
        /* the view ray's distance from the sphere's centre */
        float t = -(eye[0] * d[0] + eye[1] * d[1] + eye[2] * d[2]);
        float q[3] = {eye[0] + t * d[0], eye[1] + t * d[1], eye[2] + t * d[2]};
        float b = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        n += mask[k] = b < INNER && on_face(eye, d) && on_face(centre, d);
    }
    return n;
}

static int max_diff(const uint8_t *a, const uint8_t *b)
{
    int c, m = 0;
    for (c = 0; c < 3; c++)
        if (abs(a[c] - b[c]) > m) m = abs(a[c] - b[c]);
    return m;
}

/* Every method through each look-up: the compared pixels within 1 level of
 * the frame without the sphere, all more than 8 from the unlit cube. */
static void seen_lit(snell_ctx *ctx, const snell_frame_desc *fd, const uint8_t *mask, int n)
{
    static const snell_env_lookup lookups[3] = {SNELL_ENV_LOOKUP_CUBE, SNELL_ENV_LOOKUP_DUAL_PARABOLOID,
                                                SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT};
    static const char *const names[3] = {"cube", "paraboloid", "paraboloid direct"};
    static uint8_t with[W * H * 4], without[W * H * 4], unlit[W * H * 4];
    snell_frame_desc bare = *fd, dark = *fd;
    int l, i, k;
    bare.glass_count = 0;
    dark.light.type = SNELL_LIGHT_NONE;
    for (l = 0; l < 3; l++) {
        render(ctx, &bare, SNELL_METHOD_AUTO, lookups[l], without, NULL);
        for (i = 0; i < snell_method_count(); i++) {
            const snell_method_info *mi = snell_method_info_at(i);
            int off = 0, worst = 0, apart = 0;
            render(ctx, fd, mi->method, lookups[l], with, NULL);
            render(ctx, &dark, mi->method, lookups[l], unlit, NULL);
            for (k = 0; k < W * H; k++) {
                int dk;
                if (!mask[k]) continue;
                dk = max_diff(with + 4 * k, without + 4 * k);
                off += dk > 1;
                if (dk > worst) worst = dk;
                apart += max_diff(unlit + 4 * k, without + 4 * k) > 8;
            }
            if (mi->method == SNELL_METHOD_CUBEMAP && l == 0) {
                snell_write_png(test_out("caustics_env_with.png"), W, H, with);
                snell_write_png(test_out("caustics_env_without.png"), W, H, without);
                snell_write_png(test_out("caustics_env_unlit.png"), W, H, unlit);
            }
            printf("%s, %s: of %d pixels %d differ by more than 1 level from the frame without the sphere (at most "
                   "%d); %d differ by more than 8 unlit\n", mi->name, names[l], n, off, worst, apart);
            CHECK(off == 0, "%s, %s: %d of %d pixels differ by more than 1 (at most %d)", mi->name, names[l], off, n,
                  worst);
            CHECK(apart == n, "%s, %s: only %d of %d pixels tell the unlit cube apart", mi->name, names[l], apart, n);
        }
    }
}

static char g_updates[16]; /* env_updated of the frames of reuse(), in order */

/* One frame of r: its stats and image. */
static void frame(snell_renderer *r, const snell_frame_desc *fd, snell_frame_stats *s, uint8_t *rgba)
{
    CHECK_OK(snell_render(r, fd, s));
    CHECK_OK(snell_renderer_read_rgba(r, rgba));
    g_updates[strlen(g_updates)] = s->glass[0].env_updated ? '1' : '0';
}

static int updated(const snell_frame_stats *s) { return s->glass[0].env_updated; }
static int reused(const snell_frame_stats *s)
{
    return !s->glass[0].env_updated && (s->glass[0].skipped & SNELL_SKIP_ENV_UPDATE);
}

/* The environment's reuse over frames of one renderer (AUTO: the cubemap method). */
static void reuse(snell_ctx *ctx, const snell_frame_desc *lit, const uint8_t *mask, int n)
{
    static uint8_t a[W * H * 4], b[W * H * 4], moved_view[W * H * 4], never[W * H * 4];
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd = *lit, ref = *lit;
    snell_frame_stats s;
    int k, brighter = 0, same;
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    rd.shading = test_shading();
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!r) return;
    frame(r, &fd, &s, a);
    CHECK(updated(&s) && !s.caustics_reused, "first lit frame: env_updated %d, caustics reused %d", updated(&s),
          s.caustics_reused);
    /* still light, the camera moved: both reused */
    fd.camera.azimuth = 0.05f;
    frame(r, &fd, &s, moved_view);
    CHECK(reused(&s) && s.caustics_reused, "camera moved: env_updated %d, caustics reused %d", updated(&s),
          s.caustics_reused);
    fd.camera = lit->camera;
    frame(r, &fd, &s, b);
    CHECK(reused(&s) && memcmp(a, b, sizeof a) == 0, "still again: env_updated %d, image %s", updated(&s),
          memcmp(a, b, sizeof a) ? "changed" : "same");
    /* the light moved: onto the face more squarely (cosine 0.40 -> 0.48; the
     * sphere's shadow on the face's plane then ends at x = -1.19), the glass
     * sees it brighter */
    fd.light.direction[2] = -0.5f;
    frame(r, &fd, &s, b);
    CHECK(updated(&s) && !s.caustics_reused, "light moved: env_updated %d, caustics reused %d", updated(&s),
          s.caustics_reused);
    for (k = 0; k < W * H; k++) brighter += mask[k] && b[4 * k] > a[4 * k] + 8;
    CHECK(brighter == n, "light moved: %d of %d pixels through the sphere brighter", brighter, n);
    frame(r, &fd, &s, a);
    CHECK(reused(&s) && memcmp(a, b, sizeof a) == 0, "moved light still: env_updated %d", updated(&s));
    /* the maps remade with the light still (another map size: another light frame) */
    fd.receiver.map_size = 96;
    frame(r, &fd, &s, b);
    CHECK(updated(&s) && !s.caustics_reused, "maps remade: env_updated %d, caustics reused %d", updated(&s),
          s.caustics_reused);
    /* the light gone: redrawn as lit from above, and then as a renderer without a light ever draws it */
    fd.light.type = SNELL_LIGHT_NONE;
    frame(r, &fd, &s, a);
    CHECK(updated(&s), "light gone: env_updated %d", updated(&s));
    frame(r, &fd, &s, b);
    CHECK(reused(&s) && memcmp(a, b, sizeof a) == 0, "no light, still: env_updated %d", updated(&s));
    snell_renderer_destroy(r);
    ref.light.type = SNELL_LIGHT_NONE;
    render(ctx, &ref, SNELL_METHOD_AUTO, SNELL_ENV_LOOKUP_AUTO, never, NULL);
    same = memcmp(a, never, sizeof a) == 0;
    CHECK(same, "the frame after the light went differs from a renderer's that never had one");
    printf("reuse: env_updated %s (lit, camera moved, still, light moved, still, maps remade, light gone, still); "
           "the last frame %s\n", g_updates, same ? "byte-identical to one never lit" : "DIFFERS");
}

int main(void)
{
    static float rays[W * H * 3];
    static uint8_t mask[W * H];
    snell_ctx *ctx = test_ctx();
    snell_env *env;
    snell_shape_desc sd;
    snell_mesh *sphere = NULL, *cube = NULL;
    snell_frame_desc fd, bare;
    snell_glass g;
    snell_opaque op;
    int n;
    if (!ctx) SKIP("no GL context");
    env = test_sky(ctx, 128);
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &sphere));
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &cube));
    if (!env || !sphere || !cube) return test_finish();
    test_frame_one(&fd, &g, sphere, env);
    g.material.ior = 1.001f;
    memset(&op, 0, sizeof op);
    op.mesh = cube, op.model = k_place, op.color[0] = 0.9f, op.color[1] = 0.6f, op.color[2] = 0.3f;
    fd.opaque = &op, fd.opaque_count = 1;
    fd.scene_layers = -1; /* the glass sees the cube through its dynamic environment */
    fd.camera.azimuth = 0.0f, fd.camera.elevation = 0.15f, fd.camera.distance = 5.0f;
    /* along (-0.9, -0.2, -0.4): onto the cube's face towards the camera (z =
     * -1.8) at cosine 0.4; the sphere's shadow reaches that plane at x = -4.05
     * (its radius 1), beside the cube (|x| <= 1.2) */
    fd.light.type = SNELL_LIGHT_DIRECTIONAL;
    fd.light.direction[0] = -0.9f, fd.light.direction[1] = -0.2f, fd.light.direction[2] = -0.4f;
    fd.light.color[0] = fd.light.color[1] = fd.light.color[2] = 2.5f;
    bare = fd;
    bare.glass_count = 0;
    render(ctx, &bare, SNELL_METHOD_AUTO, SNELL_ENV_LOOKUP_CUBE, NULL, rays);
    n = compared(&fd, rays, mask);
    printf("%d pixels compared: inside %.0f%% of the sphere's radius, both rays on the face %.1f inside its edges\n", n,
           100.0 * INNER, MARGIN);
    CHECK(n > 500, "only %d pixels to compare", n);
    seen_lit(ctx, &fd, mask, n);
    reuse(ctx, &fd, mask, n);
    snell_mesh_destroy(cube);
    snell_mesh_destroy(sphere);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
