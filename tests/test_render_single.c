/* test_render_single — the single-surface kernel on a glass sphere, against
 * pixels derived independently on the CPU: camera rays through pixel centres,
 * brute-force closest hit on the same triangles (double precision), the
 * barycentric-interpolated normal, the double optics twin, and the same
 * environment texels sampled bilinearly. Tolerance: 99% of pixels within
 * 3/255 on every channel and mean error below 0.5/255; the rest are the
 * silhouette (coverage at a triangle edge) and cube seams (GL filters across
 * faces, the CPU sampler clamps inside one face). */
#include "test_util.h"
#include "core/optics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 160
#define H 120

typedef struct scene {
    const float *pos, *nrm;
    const uint32_t *idx;
    uint32_t nt;
    float scale, offset[3];
} scene;

/* Moller-Trumbore; returns t > 0 and barycentrics (u, v) of the closest hit. */
static int closest_hit(const scene *s, const double o[3], const double d[3], double *t_out, uint32_t *tri,
                       double *bu, double *bv)
{
    uint32_t t;
    int hit = 0;
    *t_out = 1e30;
    for (t = 0; t < s->nt; t++) {
        double p[3][3], e1[3], e2[3], pv[3], tv[3], qv[3], det, u, v, tt;
        int j, c;
        for (j = 0; j < 3; j++)
            for (c = 0; c < 3; c++) p[j][c] = (double)s->pos[3 * s->idx[3 * t + j] + c] * s->scale + s->offset[c];
        for (c = 0; c < 3; c++) { e1[c] = p[1][c] - p[0][c]; e2[c] = p[2][c] - p[0][c]; tv[c] = o[c] - p[0][c]; }
        pv[0] = d[1] * e2[2] - d[2] * e2[1]; pv[1] = d[2] * e2[0] - d[0] * e2[2]; pv[2] = d[0] * e2[1] - d[1] * e2[0];
        det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
        if (fabs(det) < 1e-14) continue;
        u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
        if (u < 0 || u > 1) continue;
        qv[0] = tv[1] * e1[2] - tv[2] * e1[1]; qv[1] = tv[2] * e1[0] - tv[0] * e1[2]; qv[2] = tv[0] * e1[1] - tv[1] * e1[0];
        v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
        if (v < 0 || u + v > 1) continue;
        tt = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
        if (tt > 1e-9 && tt < *t_out) { *t_out = tt; *tri = t; *bu = u; *bv = v; hit = 1; }
    }
    return hit;
}

int main(void)
{
    snell_ctx *ctx = test_ctx();
    snell_mesh *mesh = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_shape_desc sd;
    snell_env_desc ed;
    snell_frame_stats stats;
    scene s;
    static uint8_t gpu[W * H * 4], cpu[W * H * 4];
    float eye[3], view[16], proj[16], model[16];
    double ior = 1.5, sigma[3] = {0.30, 0.10, 0.05}, tanh_fov;
    int x, y, c, within = 0, hits = 0, mask_mismatch = 0;
    double sum_err = 0.0;
    if (!ctx) SKIP("no GL context");

    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    sd.segments = 48;
    sd.rings = 24;
    memset(&ed, 0, sizeof ed);
    ed.face_size = 256;
    CHECK_OK(snell_mesh_create_shape(ctx, &sd, &mesh));
    CHECK_OK(snell_env_create(ctx, &ed, &env));
    memset(&rd, 0, sizeof rd);
    rd.width = W;
    rd.height = H;
    CHECK_OK(snell_renderer_create(ctx, &rd, &r));
    if (!mesh || !env || !r) return test_finish();

    /* Uniform scale 0.8 and an offset exercise the model and normal matrices. */
    memset(&s, 0, sizeof s);
    s.pos = snell_mesh_positions(mesh);
    s.nrm = snell_mesh_normals(mesh);
    s.idx = snell_mesh_indices(mesh);
    s.nt = snell_mesh_triangle_count(mesh);
    s.scale = 0.8f;
    s.offset[0] = 0.1f; s.offset[1] = -0.05f; s.offset[2] = 0.0f;
    memset(model, 0, sizeof model);
    model[0] = model[5] = model[10] = s.scale;
    model[12] = s.offset[0]; model[13] = s.offset[1]; model[14] = s.offset[2];
    model[15] = 1.0f;

    memset(&fd, 0, sizeof fd);
    fd.glass.method = SNELL_METHOD_SINGLE;
    fd.mesh = mesh;
    fd.env = env;
    fd.model = model;
    fd.glass.ior = (float)ior;
    for (c = 0; c < 3; c++) fd.glass.absorption[c] = (float)sigma[c];
    fd.camera.azimuth = 0.6f;
    fd.camera.elevation = 0.25f;
    fd.camera.distance = 3.0f;
    CHECK_OK(snell_render(r, &fd, &stats));
    CHECK(stats.passes == 2 && !stats.skipped_passthrough, "passes %d", stats.passes);
    CHECK_OK(snell_renderer_read_rgba(r, gpu));

    snell_camera_matrices(&fd.camera, (float)W / H, eye, view, proj);
    tanh_fov = tan(0.5 * 45.0 * 3.14159265358979323846 / 180.0);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            /* View matrix rows are the camera's right, up and backward axes. */
            double ndc_x = (2.0 * (x + 0.5) / W - 1.0) * tanh_fov * W / H;
            double ndc_y = (1.0 - 2.0 * (y + 0.5) / H) * tanh_fov;
            double o[3] = {eye[0], eye[1], eye[2]}, d[3], len, t, bu, bv, rgb[3];
            uint32_t tri;
            uint8_t *px = cpu + 4 * (y * W + x);
            for (c = 0; c < 3; c++) d[c] = ndc_x * view[4 * c] + ndc_y * view[4 * c + 1] - view[4 * c + 2];
            len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (c = 0; c < 3; c++) d[c] /= len;
            if (closest_hit(&s, o, d, &t, &tri, &bu, &bv)) {
                double n[3], p[3], rr[3], tr[3], refl[3], trans[3], bl[3], oc[3], b, cc, path, f, nl;
                const uint32_t *ix = s.idx + 3 * tri;
                hits++;
                for (c = 0; c < 3; c++) {
                    n[c] = (1 - bu - bv) * s.nrm[3 * ix[0] + c] + bu * s.nrm[3 * ix[1] + c] + bv * s.nrm[3 * ix[2] + c];
                    p[c] = o[c] + t * d[c];
                }
                nl = sqrt(snell_optd_dot(n, n));
                for (c = 0; c < 3; c++) n[c] /= nl;
                if (snell_optd_dot(n, d) > 0) for (c = 0; c < 3; c++) n[c] = -n[c];
                snell_optd_reflect(d, n, rr);
                snell_optd_refract(d, n, 1.0 / ior, tr);
                f = snell_optd_fresnel_schlick(-snell_optd_dot(d, n), 1.0, ior);
                for (c = 0; c < 3; c++) oc[c] = p[c] - s.offset[c];
                b = snell_optd_dot(oc, tr);
                cc = snell_optd_dot(oc, oc) - (double)s.scale * s.scale; /* unit sphere mesh, scaled */
                path = -b + sqrt(b * b - cc > 0 ? b * b - cc : 0);
                snell_optd_beer_lambert(sigma, path > 0 ? path : 0, bl);
                snell_env_sample_d(env, rr, refl);
                snell_env_sample_d(env, tr, trans);
                for (c = 0; c < 3; c++) rgb[c] = (1 - f) * trans[c] * bl[c] + f * refl[c];
            } else {
                snell_env_sample_d(env, d, rgb);
            }
            for (c = 0; c < 3; c++) px[c] = (uint8_t)(fmin(fmax(rgb[c], 0), 1) * 255.0 + 0.5);
            px[3] = 255;
        }

    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int worst = 0;
            for (c = 0; c < 3; c++) {
                int e = abs(gpu[4 * (y * W + x) + c] - cpu[4 * (y * W + x) + c]);
                if (e > worst) worst = e;
                sum_err += e;
            }
            within += worst <= 3;
            (void)mask_mismatch;
        }
    printf("%d glass pixels of %d; %.2f%% within 3/255; mean abs error %.3f/255\n", hits, W * H,
           100.0 * within / (W * H), sum_err / (3.0 * W * H));
    CHECK(hits > W * H / 8, "the sphere must cover a good part of the image (%d)", hits);
    CHECK(within >= 0.99 * W * H, "only %d of %d pixels within 3/255", within, W * H);
    CHECK(sum_err / (3.0 * W * H) < 0.5, "mean error %.3f/255", sum_err / (3.0 * W * H));
    snell_write_png(test_out("render_single_gpu.png"), W, H, gpu);
    snell_write_png(test_out("render_single_cpu.png"), W, H, cpu);

    /* IOR 1 without absorption is a pass-through: the glass draw is skipped and
     * the frame equals the background alone. */
    {
        static uint8_t bg[W * H * 4];
        fd.glass.ior = 1.0f;
        memset(fd.glass.absorption, 0, sizeof fd.glass.absorption);
        CHECK_OK(snell_render(r, &fd, &stats));
        CHECK(stats.skipped_passthrough == 1 && stats.passes == 1, "pass-through not skipped");
        CHECK_OK(snell_renderer_read_rgba(r, gpu));
        fd.mesh = NULL;
        CHECK_OK(snell_render(r, &fd, NULL));
        CHECK_OK(snell_renderer_read_rgba(r, bg));
        CHECK(memcmp(bg, gpu, sizeof bg) == 0, "pass-through frame differs from the background");
    }

    /* Invalid frames are refused with a message, not drawn. */
    fd.mesh = mesh;
    fd.glass.ior = -2.0f;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "negative IOR");
    fd.glass.ior = NAN;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "NaN IOR");
    fd.glass.ior = 1.5f;
    fd.env = NULL;
    CHECK(snell_render(r, &fd, NULL) == SNELL_E_INVALID_ARG, "missing env");

    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
    snell_ctx_destroy(ctx);
    return test_finish();
}
