/* SPDX-License-Identifier: MIT */
/* test_caustics_seen_ref.c — the glass seeing the lit receiver plane against
 * the reference (issue 27): snell_ref_set_receiver makes the reference's
 * view rays meet the plane, lit by the reference's own traced
 * light map (ref_plane.c), as the GPU's view and its glass kernels
 * (SNELL_RECEIVER, common/receiver.glsl) show the stage's map. A glass
 * sphere (radius 1, IOR 1.5) 0.3 over the plane, seen from 57 degrees
 * above, under a directional light 22 degrees off vertical, away from the
 * camera: its shadow and its caustic (the plane short of the ball lens's
 * focus: a bright disc in the shadow) lie under and behind it and are seen
 * through it; then a standing torus (not convex: its photons and the exact
 * method's rays by the BVH). Per method: the GPU frame against the
 * reference (MATCHED, the method's interface cap) over the glass pixels
 * whose refracted chain leaves towards the plane (PSNR), and over the
 * plane's own pixels; those glass pixels must include the caustic
 * (brighter than the lit plane) and the shadow (darker), and the reference
 * without the plane (the environment there) must fail the bound. Writes
 * caustics_seen_ref_<scene>_<method>_gpu.png and _ref.png. */
#include "test_util.h"
#include "core/ctx.h"
#include "core/light_map.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 128
#define N (W * W)
/* The lit plane's green: albedo 0.8 times the light's 0.6 at cosine 1 / |(0.1, -1, -0.4)| */
#define LIT 0.4438

typedef struct scene {
    const char *name;
    snell_frame_desc fd;
    snell_glass g;
    snell_ref *ref, *bare; /* with the plane (snell_ref_set_receiver), and without */
    double eye[3];
} scene;

typedef struct reference {
    uint8_t rgba[N * 4];
    float rgb[N * 3], view[N * 3];
    uint8_t hit[N];
    int16_t object[N];
} reference;

/* The reference's image of the scene in the given mode with max_if interfaces. */
static void ref_image(const scene *s, const snell_ref *ref, snell_ref_mode mode, int max_if, reference *out)
{
    snell_ref_params p;
    snell_ref_output o;
    test_ref_params(&s->fd, W, W, max_if, &p);
    p.mode = mode;
    memset(&o, 0, sizeof o);
    o.rgb = out->rgb, o.exit_dir = out->view, o.hit = out->hit, o.object = out->object;
    CHECK_OK(snell_ref_render(ref, &p, &o));
    snell_ref_rgb_to_rgba8(out->rgb, W, W, out->rgba);
}

/* Pixel k and its four neighbours all set in m. */
static int inner(const uint8_t *m, int k)
{
    int x = k % W, y = k / W;
    return m[k] && x > 0 && y > 0 && x < W - 1 && y < W - 1 && m[k - 1] && m[k + 1] && m[k - W] && m[k + W];
}

/* Whether the ray o + t d meets the plane's square from above. */
static int meets_plane(const scene *s, const double o[3], const float *d)
{
    const snell_receiver *rc = &s->fd.receiver;
    double t = (rc->height - o[1]) / d[1];
    return d[1] < 0.0f && o[1] > rc->height && fabs(o[0] + t * d[0] - rc->center[0]) < rc->extent &&
           fabs(o[2] + t * d[2] - rc->center[1]) < rc->extent;
}

/* The scene's masks, found without the reference's plane: glass pixels
 * whose refracted chain leaves towards the plane (snell_ref_trace_pixel of
 * the reference without it: the path's last point and exit direction),
 * and the plane's own pixels (the view ray, the exit direction of a pixel
 * that meets no object), each away from edges. Counts the caustic and
 * shadow pixels among the first (the green channel of r, the reference
 * with the plane, above 1.3 / below 0.3 times the lit plane's, LIT). */
static void masks(const scene *s, int max_if, const reference *r, uint8_t *seen, uint8_t *plane, int *caustic,
                  int *shadow)
{
    static uint8_t glass[N], chain[N], flat[N];
    static snell_ref_path path;
    snell_ref_params p;
    int k;
    test_ref_params(&s->fd, W, W, max_if, &p);
    for (k = 0; k < N; k++) {
        float d[3];
        glass[k] = r->hit[k];
        chain[k] = 0;
        if (glass[k] && snell_ref_trace_pixel(s->bare, &p, k % W, k / W, &path) == SNELL_OK) {
            d[0] = (float)path.exit_dir[0], d[1] = (float)path.exit_dir[1], d[2] = (float)path.exit_dir[2];
            chain[k] = meets_plane(s, path.points[path.interfaces], d);
        }
        flat[k] = r->object[k] == -1 && meets_plane(s, s->eye, r->view + 3 * k);
    }
    *caustic = *shadow = 0;
    for (k = 0; k < N; k++) {
        seen[k] = inner(glass, k) && chain[k];
        plane[k] = inner(flat, k);
        if (!seen[k]) continue;
        *caustic += r->rgb[3 * k + 1] > 1.3 * LIT;
        *shadow += r->rgb[3 * k + 1] < 0.3 * LIT;
    }
}

static void write_pair(const char *scene_name, const char *method, const uint8_t *gpu, const uint8_t *ref)
{
    char path[96];
    snprintf(path, sizeof path, "caustics_seen_ref_%s_%s_gpu.png", scene_name, method);
    snell_write_png(test_out(path), W, W, gpu);
    snprintf(path, sizeof path, "caustics_seen_ref_%s_%s_ref.png", scene_name, method);
    snell_write_png(test_out(path), W, W, ref);
}

/* A PSNR bound db (float light maps) for an RGB10_A2 map (no float colour
 * target), over the pixels of mask: each share s (direct light or photon, in
 * steps of 1/1023 of the range) is stored as floor(s + u), u uniform, an
 * error of mean 0 and variance f (1 - f) <= s (f its fraction), so a texel
 * summing m holds it with variance at most m / 1023 (units of the range),
 * its bilinear read no more; shown through glass (transmittance and albedo
 * <= 1) as irradiance = SNELL__LIGHT_RANGE times the map, a pixel's variance
 * is at most SNELL__LIGHT_RANGE / 1023 times its shown value, bounded by the
 * reference's pixel: that adds to the squared error db allows. Magnified
 * through the lens, the map's noise is what the format costs here. */
static double fixed_db(snell_ctx *ctx, double db, const reference *r, const uint8_t *mask)
{
    double mean = 0.0;
    int k, n = 0, c;
    if (!snell__light_fixed(ctx)) return db;
    for (k = 0; k < N; k++)
        if (mask[k])
            for (c = 0, n++; c < 3; c++) mean += fmin(1.0, r->rgb[3 * k + c]);
    mean /= 3.0 * (n > 0 ? n : 1);
    return -10.0 * log10(pow(10.0, -db / 10.0) + SNELL__LIGHT_RANGE * mean / 1023.0);
}

typedef struct bound {
    snell_method method;
    int max_if; /* the reference's interface cap for it */
    double seen, plane; /* PSNR bounds (dB) */
} bound;

/* The scene's GPU frames by each method of `b` against the references. */
static void compare(snell_ctx *ctx, snell_renderer *rend, scene *s, const bound *b, int count)
{
    static reference with, bare;
    static uint8_t gpu[N * 4], seen[N], plane[N];
    int i, max_if = 0, caustic = 0, shadow = 0;
    for (i = 0; i < count; i++) {
        const char *name = snell_method_info_of(b[i].method)->name;
        int n_seen, n_plane;
        double db_seen, db_plane, db_bare;
        if (b[i].max_if != max_if) {
            max_if = b[i].max_if;
            ref_image(s, s->bare, SNELL_REF_MATCHED, max_if, &bare);
            ref_image(s, s->ref, SNELL_REF_MATCHED, max_if, &with);
            masks(s, max_if, &with, seen, plane, &caustic, &shadow);
        }
        s->g.material.method = b[i].method;
        CHECK_OK_CTX(ctx, snell_render(rend, &s->fd, NULL));
        CHECK_OK_CTX(ctx, snell_renderer_read_rgba(rend, gpu));
        write_pair(s->name, name, gpu, with.rgba);
        db_seen = test_psnr_mask(gpu, with.rgba, seen, N, &n_seen);
        db_plane = test_psnr_mask(gpu, with.rgba, plane, N, &n_plane);
        db_bare = test_psnr_mask(gpu, bare.rgba, seen, N, &n_seen);
        printf("%s, %s: %d glass pixels see the plane (%d in the caustic, %d in the shadow): %.2f dB against the "
               "reference (%.2f without its plane); %d plane pixels: %.2f dB\n",
               s->name, name, n_seen, caustic, shadow, db_seen, db_bare, n_plane, db_plane);
        /* single's one refraction looks at the plane in front of the shadow, lit */
        CHECK(n_seen > 400 && (max_if == 1 || (caustic > 20 && shadow > 20)),
              "%s %s: %d pixels see the plane, %d caustic, %d shadow", s->name, name, n_seen, caustic, shadow);
        {
            double want_seen = fixed_db(ctx, b[i].seen, &with, seen), want_plane = fixed_db(ctx, b[i].plane, &with, plane);
            if (snell__light_fixed(ctx))
                printf("  with an RGB10_A2 light map's rounding: at least %.2f dB through the glass, %.2f on the plane "
                       "(the float leg checks %.1f, %.1f)\n", want_seen, want_plane, b[i].seen, b[i].plane);
            CHECK(db_seen >= want_seen, "%s %s: the plane through the glass %.2f dB < %.2f", s->name, name, db_seen,
                  want_seen);
            CHECK(db_plane >= want_plane && n_plane > 2000, "%s %s: the plane %.2f dB < %.2f over %d pixels", s->name,
                  name, db_plane, want_plane, n_plane);
            /* the bound fails by 5 dB at least where the reference does not see the plane */
            CHECK(db_bare <= want_seen - 5.0, "%s %s: the reference without its plane is %.2f dB from the GPU", s->name,
                  name, db_bare);
        }
    }
}

/* FULL mode sees the plane too (the Whitted tree's rays in air): the
 * sphere's FULL image against its MATCHED one over the glass pixels that see
 * the plane (they differ by the exact Fresnel and FULL's inner
 * reflections), and without the plane far from it; the plane's own pixels
 * the same in both. */
static void full_sees(scene *s)
{
    static reference matched, full, full_bare;
    static uint8_t seen[N], plane[N];
    int n_seen, n_plane, caustic, shadow;
    double db, db_bare, db_plane;
    ref_image(s, s->ref, SNELL_REF_MATCHED, 8, &matched);
    ref_image(s, s->ref, SNELL_REF_FULL, 8, &full);
    ref_image(s, s->bare, SNELL_REF_FULL, 8, &full_bare);
    masks(s, 8, &matched, seen, plane, &caustic, &shadow);
    db = test_psnr_mask(full.rgba, matched.rgba, seen, N, &n_seen);
    db_bare = test_psnr_mask(full_bare.rgba, matched.rgba, seen, N, &n_seen);
    db_plane = test_psnr_mask(full.rgba, matched.rgba, plane, N, &n_plane);
    printf("%s, FULL against MATCHED: %.2f dB over the %d glass pixels that see the plane (%.2f without it), %.2f dB "
           "over the plane\n",
           s->name, db, n_seen, db_bare, db_plane);
    /* measured 29.4 dB, without the plane 5.1 */
    CHECK(db >= 27.0 && db_bare <= 10.0 && db_plane >= 60.0, "FULL: %.2f dB (%.2f without the plane), plane %.2f dB",
          db, db_bare, db_plane);
}

static void scene_init(scene *s, const char *name, const snell_mesh *mesh, const float *model, snell_env *env)
{
    float eye[3], view[16], proj[16];
    test_frame_one(&s->fd, &s->g, mesh, env);
    s->name = name;
    s->g.model = model;
    s->g.material.ior = 1.5f;
    s->fd.camera.azimuth = 0.0f, s->fd.camera.elevation = 1.0f, s->fd.camera.distance = 5.0f;
    s->fd.camera.fov_y = 0.8f;
    s->fd.light.type = SNELL_LIGHT_DIRECTIONAL;
    s->fd.light.direction[0] = 0.1f, s->fd.light.direction[1] = -1.0f, s->fd.light.direction[2] = -0.4f;
    s->fd.light.color[0] = s->fd.light.color[1] = s->fd.light.color[2] = 0.6f;
    s->fd.receiver.height = -0.7f;
    s->fd.receiver.center[1] = -1.0f;
    s->fd.receiver.extent = 2.5f;
    s->fd.receiver.albedo[0] = 0.9f, s->fd.receiver.albedo[1] = 0.8f, s->fd.receiver.albedo[2] = 0.6f;
    s->fd.receiver.map_size = 128;
    snell_camera_matrices(&s->fd.camera, 1.0f, eye, view, proj);
    s->eye[0] = eye[0], s->eye[1] = eye[1], s->eye[2] = eye[2];
    CHECK_OK(test_ref_create(NULL, &s->fd, &s->bare));
    CHECK_OK(test_ref_create(NULL, &s->fd, &s->ref));
    if (s->ref) CHECK_OK(snell_ref_set_receiver(s->ref, &s->fd.light, &s->fd.receiver, 1024));
}

int main(void)
{
    static scene sph, tor;
    /* PSNR bounds, measured (128 x 128, llvmpipe) less about 2 dB: over the
     * glass pixels that see the plane and over the plane's own. The
     * reference's cap: single the front refraction alone, the two-sided
     * methods two surfaces (all of a sphere's path), exact its default 8.
     * Measured: single 56.8, cubemap 30.9, wyman 13.8 and oliveira 19.2 (the
     * plane, unlike the environment, shows where the exit point is, which
     * they estimate from a distance or two), peel 31.0, exact 51.4, layered
     * 31.3; the plane 52.8 (the stage's 256^2 photons against the
     * reference's 1024^2); the torus by exact 43.2, its plane 46.2 (the
     * sparse photons' moire in its caustic's lines). Against the reference
     * without its plane: 4.8 to 6.7 dB. */
    static const bound sphere_bounds[] = {{SNELL_METHOD_SINGLE, 1, 54.5, 50.5}, {SNELL_METHOD_CUBEMAP, 2, 29.0, 50.5},
                                          {SNELL_METHOD_WYMAN, 2, 12.0, 50.5},  {SNELL_METHOD_OLIVEIRA, 2, 17.0, 50.5},
                                          {SNELL_METHOD_PEEL, 2, 29.0, 50.5},   {SNELL_METHOD_EXACT, 8, 49.0, 50.5},
                                          {SNELL_METHOD_LAYERED, 2, 29.0, 50.5}};
    static const bound torus_bounds[] = {{SNELL_METHOD_EXACT, 8, 41.0, 44.0}};
    float up[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0.6f, 0, 1};
    float standing[16] = {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0.9f, 0, 1}; /* its axis along z */
    snell_ctx *ctx = test_ctx();
    snell_shape_desc sd = {SNELL_SHAPE_SPHERE, 128, 64}, td = {SNELL_SHAPE_TORUS, 96, 48};
    snell_mesh *sphere = NULL, *torus = NULL;
    snell_env *env = NULL;
    snell_renderer *rend = NULL;
    snell_renderer_desc rd;
    if (!ctx) SKIP("no headless GL context");
    env = test_sky(ctx, 64);
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &sd, &sphere));
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &td, &torus));
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = W;
    rd.shading = test_shading();
    CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &rend));
    if (!env || !sphere || !torus || !rend) return test_finish();
    scene_init(&sph, "sphere", sphere, up, env);
    scene_init(&tor, "torus", torus, standing, env);
    if (sph.ref && sph.bare)
        compare(ctx, rend, &sph, sphere_bounds, (int)(sizeof sphere_bounds / sizeof *sphere_bounds));
    if (sph.ref && sph.bare) full_sees(&sph);
    if (tor.ref && tor.bare) compare(ctx, rend, &tor, torus_bounds, 1);
    if (sph.ref && sph.bare) { /* the plane taken away: the reference's images as without it, bit for bit */
        static reference with, bare;
        snell_receiver bad = sph.fd.receiver;
        int k;
        bad.albedo[1] = 1.5f;
        CHECK(snell_ref_set_receiver(sph.ref, &sph.fd.light, &bad, 64) == SNELL_E_INVALID_ARG, "albedo 1.5 accepted");
        ref_image(&sph, sph.ref, SNELL_REF_MATCHED, 2, &with);
        ref_image(&sph, sph.bare, SNELL_REF_MATCHED, 2, &bare);
        CHECK(memcmp(with.rgb, bare.rgb, sizeof with.rgb) == 0, "a refused receiver left a plane");
        /* a plane above the sphere hides it: the paths of both modes end there */
        bad = sph.fd.receiver;
        bad.height = 2.0f, bad.map_size = 16;
        CHECK_OK(snell_ref_set_receiver(sph.ref, &sph.fd.light, &bad, 64));
        for (k = 0; k < 2; k++) {
            static snell_ref_path path;
            const double o[3] = {0.2, 5.0, 0.1}, d[3] = {0.0, -1.0, 0.0};
            snell_ref_params p;
            test_ref_params(&sph.fd, W, W, 8, &p);
            p.mode = k ? SNELL_REF_FULL : SNELL_REF_MATCHED;
            CHECK_OK(snell_ref_trace_ray(sph.ref, &p, o, d, &path));
            CHECK(path.hit == 0 && path.first_object == -1 && path.interfaces == 0,
                  "mode %d: the path under the plane: hit %d, object %d, %d interfaces", k, path.hit, path.first_object,
                  path.interfaces);
        }
        CHECK_OK(snell_ref_set_receiver(sph.ref, NULL, NULL, 0));
        ref_image(&sph, sph.ref, SNELL_REF_MATCHED, 2, &with);
        CHECK(memcmp(with.rgb, bare.rgb, sizeof with.rgb) == 0 && memcmp(with.view, bare.view, sizeof with.view) == 0,
              "the plane taken away changed the image");
    }
    snell_ref_destroy(sph.ref);
    snell_ref_destroy(sph.bare);
    snell_ref_destroy(tor.ref);
    snell_ref_destroy(tor.bare);
    snell_renderer_destroy(rend);
    snell_mesh_destroy(sphere);
    snell_mesh_destroy(torus);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
