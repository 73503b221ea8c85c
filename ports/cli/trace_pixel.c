/* SPDX-License-Identifier: MIT */
/* trace_pixel.c — `snell-render --trace-pixel X,Y`: the reference light paths
 * of chosen pixels (snell_ref_trace_pixel; Unger 4.2.2) through the whole
 * scene (every glass and opaque object; paths may pass from one glass object
 * into another), drawn as lines over the scene seen from a second camera (the
 * first one turned 90 degrees about the target and raised), and written as
 * JSON. FULL (the Whitted tree's dominant branch) and MATCHED (the GPU
 * kernels' refracted chain, 10 interfaces) are both traced. Public API only. */
#include "render.h"
#include "snell/snell_ref.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct view2 {
    float view[16], proj[16];
    int w, h;
    uint8_t *px;
} view2;

static void put(view2 *v, int x, int y, const uint8_t c[3])
{
    uint8_t *p;
    if (x < 0 || y < 0 || x >= v->w || y >= v->h) return;
    p = v->px + 4 * ((size_t)y * v->w + x);
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
}

/* World point -> clip space (column-major matrices). */
static void to_clip(const view2 *v, const double p[3], double c[4])
{
    double e[4];
    int i;
    for (i = 0; i < 4; i++)
        e[i] = v->view[i] * p[0] + v->view[4 + i] * p[1] + v->view[8 + i] * p[2] + v->view[12 + i];
    for (i = 0; i < 4; i++) c[i] = v->proj[i] * e[0] + v->proj[4 + i] * e[1] + v->proj[8 + i] * e[2] + v->proj[12 + i] * e[3];
}

/* A world-space segment, clipped to w > small (in front of the camera), drawn 2 px wide. */
static void segment(view2 *v, const double a[3], const double b[3], const uint8_t c[3])
{
    double ca[4], cb[4], t0 = 0.0, t1 = 1.0, eps = 1e-6;
    double x0, y0, x1, y1, len;
    int k, n;
    to_clip(v, a, ca);
    to_clip(v, b, cb);
    if (ca[3] <= eps && cb[3] <= eps) return;
    if (ca[3] <= eps) t0 = (eps - ca[3]) / (cb[3] - ca[3]);
    if (cb[3] <= eps) t1 = (eps - ca[3]) / (cb[3] - ca[3]);
    {
        double pa[4], pb[4];
        for (k = 0; k < 4; k++) {
            pa[k] = ca[k] + t0 * (cb[k] - ca[k]);
            pb[k] = ca[k] + t1 * (cb[k] - ca[k]);
        }
        /* NDC -> pixels, y = 0 at the top */
        x0 = (pa[0] / pa[3] * 0.5 + 0.5) * v->w;
        y0 = (0.5 - pa[1] / pa[3] * 0.5) * v->h;
        x1 = (pb[0] / pb[3] * 0.5 + 0.5) * v->w;
        y1 = (0.5 - pb[1] / pb[3] * 0.5) * v->h;
    }
    len = fmax(fabs(x1 - x0), fabs(y1 - y0));
    if (!isfinite(len)) return;
    if (len > 8.0 * (v->w + v->h)) len = 8.0 * (v->w + v->h); /* far off-screen: enough samples */
    n = (int)ceil(len) + 1;
    for (k = 0; k <= n; k++) {
        double t = (double)k / n, x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
        int ix = (int)floor(x), iy = (int)floor(y);
        put(v, ix, iy, c);
        put(v, ix + 1, iy, c);
        put(v, ix, iy + 1, c);
        put(v, ix + 1, iy + 1, c);
    }
}

static const char *event_name(snell_ref_event e)
{
    switch (e) {
    case SNELL_REF_EVENT_EYE: return "eye";
    case SNELL_REF_EVENT_REFRACT: return "refract";
    case SNELL_REF_EVENT_REFLECT: return "reflect";
    default: return "tir";
    }
}

static void json_path(FILE *f, const snell_ref_path *p)
{
    int i;
    fprintf(f, "{\"hit\": %d, \"first_object\": %d, \"interfaces\": %d, \"objects\": [", p->hit, p->first_object,
            p->interfaces);
    for (i = 0; i <= p->interfaces; i++) fprintf(f, "%s%d", i ? ", " : "", p->objects[i]);
    fprintf(f, "], \"points\": [");
    for (i = 0; i <= p->interfaces; i++)
        fprintf(f, "%s[%.9g, %.9g, %.9g]", i ? ", " : "", p->points[i][0], p->points[i][1], p->points[i][2]);
    fprintf(f, "], \"events\": [");
    for (i = 0; i <= p->interfaces; i++) fprintf(f, "%s\"%s\"", i ? ", " : "", event_name(p->events[i]));
    fprintf(f, "], \"exit_dir\": [%.9g, %.9g, %.9g], \"ended_inside\": %d, \"fresnel\": %.6g, \"inside_length\": %.9g, "
               "\"rgb\": [%.6g, %.6g, %.6g]}",
            p->exit_dir[0], p->exit_dir[1], p->exit_dir[2], p->ended_inside, p->fresnel, p->inside_length, p->rgb[0],
            p->rgb[1], p->rgb[2]);
}

/* The exit ray is drawn twice the bounding radius of the glass object it leaves. */
static void draw_path(view2 *v, const snell_ref_path *p, const double *radius, int glass_count,
                      const uint8_t in_c[3], const uint8_t out_c[3], const uint8_t eye_c[3])
{
    int i, last = p->objects[p->interfaces];
    double end[3], exit_len = 2.0 * radius[last >= 0 && last < glass_count ? last : 0];
    for (i = 0; i < p->interfaces; i++) segment(v, p->points[i], p->points[i + 1], i == 0 ? eye_c : in_c);
    for (i = 0; i < 3; i++) end[i] = p->points[p->interfaces][i] + exit_len * p->exit_dir[i];
    segment(v, p->points[p->interfaces], end, out_c);
}

int snell_render_trace_pixels(snell_ctx *ctx, const snell_frame_desc *frame, int width, int height, const int *xy,
                              int count, const char *out_png)
{
    static const uint8_t yellow[3] = {255, 220, 0}, red[3] = {230, 30, 30}, green[3] = {0, 200, 60},
                         blue[3] = {40, 120, 255}, cyan[3] = {0, 230, 230}, magenta[3] = {230, 0, 230};
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd2 = *frame;
    snell_ref *ref = NULL;
    snell_ref_desc refd;
    snell_ref_params p;
    view2 v;
    char base[1024], path[1100];
    FILE *json = NULL;
    float eye2[3];
    double radius[SNELL_MAX_GLASS], eye1[3], scene_radius = 0.0;
    int i, rc = 1;
    size_t n;

    memset(&v, 0, sizeof v);
    if (frame->glass_count < 1) {
        fprintf(stderr, "snell-render: --trace-pixel needs a glass object\n");
        return 1;
    }
    for (i = 0; i < count; i++)
        if (xy[2 * i] < 0 || xy[2 * i + 1] < 0 || xy[2 * i] >= width || xy[2 * i + 1] >= height) {
            fprintf(stderr, "snell-render: --trace-pixel %d,%d outside the %dx%d image\n", xy[2 * i], xy[2 * i + 1],
                    width, height);
            return 2;
        }
    n = strlen(out_png);
    snprintf(base, sizeof base, "%.*s", (int)(n > 4 && !strcmp(out_png + n - 4, ".png") ? n - 4 : n), out_png);

    /* Second camera: the first turned 90 degrees about the target, raised 25. */
    fd2.camera.azimuth = frame->camera.azimuth + 1.5707963f;
    fd2.camera.elevation = frame->camera.elevation + 0.436f;
    if (fd2.camera.elevation > 1.4f) fd2.camera.elevation = 1.4f;
    fd2.camera.distance = (frame->camera.distance > 0 ? frame->camera.distance : 3.5f) * 1.4f;
    v.w = width;
    v.h = height;
    snell_camera_matrices(&fd2.camera, (float)width / (float)height, eye2, v.view, v.proj);
    {
        float e1f[3], vw[16], pr[16];
        snell_camera_matrices(&frame->camera, (float)width / (float)height, e1f, vw, pr);
        for (i = 0; i < 3; i++) eye1[i] = e1f[i];
    }
    memset(&rd, 0, sizeof rd);
    rd.width = width;
    rd.height = height;
    v.px = (uint8_t *)malloc((size_t)width * height * 4);
    if (!v.px || snell_renderer_create(ctx, &rd, &r) != SNELL_OK || snell_render(r, &fd2, NULL) != SNELL_OK ||
        snell_renderer_read_rgba(r, v.px) != SNELL_OK) {
        fprintf(stderr, "snell-render: trace view: %s\n", snell_last_error(ctx));
        goto done;
    }
    memset(&refd, 0, sizeof refd);
    refd.glass = frame->glass;
    refd.glass_count = frame->glass_count;
    refd.opaque = frame->opaque;
    refd.opaque_count = frame->opaque_count;
    if (snell_ref_create(ctx, &refd, &ref) != SNELL_OK) {
        fprintf(stderr, "snell-render: reference: %s\n", snell_last_error(ctx));
        goto done;
    }
    for (i = 0; i < frame->glass_count; i++) {
        double c[3];
        snell_ref_bounding_sphere(ref, i, c, &radius[i]);
        if (radius[i] > scene_radius) scene_radius = radius[i];
    }
    memset(&p, 0, sizeof p);
    p.isolate_glass = 0; /* the whole scene: light may pass from glass to glass */
    p.env = frame->env;
    p.camera = frame->camera;
    p.width = width;
    p.height = height;
    p.max_interfaces = 10;

    snprintf(path, sizeof path, "%s_trace.json", base);
    if (!(json = fopen(path, "w"))) {
        fprintf(stderr, "snell-render: cannot write '%s': %s\n", path, strerror(errno));
        goto done;
    }
    fprintf(json, "{\n  \"image\": [%d, %d],\n  \"camera\": {\"eye\": [%.9g, %.9g, %.9g]},\n", width, height, eye1[0],
            eye1[1], eye1[2]);
    fprintf(json, "  \"second_camera\": {\"eye\": [%.9g, %.9g, %.9g], \"azimuth\": %.6g, \"elevation\": %.6g, "
                  "\"distance\": %.6g},\n  \"scene\": {\"glass\": %d, \"opaque\": %d},\n  \"isolate_glass\": %d,\n"
                  "  \"max_interfaces\": %d,\n  \"pixels\": [\n",
            eye2[0], eye2[1], eye2[2], fd2.camera.azimuth, fd2.camera.elevation, fd2.camera.distance,
            frame->glass_count, frame->opaque_count, p.isolate_glass, p.max_interfaces);
    for (i = 0; i < count; i++) {
        snell_ref_path full, matched;
        p.mode = SNELL_REF_FULL;
        if (snell_ref_trace_pixel(ref, &p, xy[2 * i], xy[2 * i + 1], &full) != SNELL_OK) goto trace_fail;
        p.mode = SNELL_REF_MATCHED;
        if (snell_ref_trace_pixel(ref, &p, xy[2 * i], xy[2 * i + 1], &matched) != SNELL_OK) goto trace_fail;
        /* MATCHED under FULL, so that where they agree the FULL colours show */
        draw_path(&v, &matched, radius, frame->glass_count, magenta, cyan, yellow);
        draw_path(&v, &full, radius, frame->glass_count, red, green, yellow);
        fprintf(json, "    {\"x\": %d, \"y\": %d,\n     \"full\": ", xy[2 * i], xy[2 * i + 1]);
        json_path(json, &full);
        fprintf(json, ",\n     \"matched\": ");
        json_path(json, &matched);
        fprintf(json, "}%s\n", i + 1 < count ? "," : "");
        printf("pixel %d,%d: FULL %d interface(s)%s, MATCHED %d interface(s)%s", xy[2 * i], xy[2 * i + 1],
               full.interfaces, full.hit ? "" : " (missed the glass)", matched.interfaces,
               matched.ended_inside ? " (ended inside)" : "");
        if (frame->glass_count > 1 || frame->opaque_count > 0) {
            if (full.first_object >= 0) printf("; first hit glass %d", full.first_object);
            else if (full.first_object <= -2) printf("; first hit opaque %d", -2 - full.first_object);
        }
        printf("\n");
        continue;
    trace_fail:
        fprintf(stderr, "snell-render: trace %d,%d: %s\n", xy[2 * i], xy[2 * i + 1], snell_last_error(ctx));
        goto done;
    }
    fprintf(json, "  ]\n}\n");
    /* the first camera's position as a small blue cross */
    {
        double a[3], b[3];
        int k;
        for (k = 0; k < 3; k++) {
            memcpy(a, eye1, sizeof a);
            memcpy(b, eye1, sizeof b);
            a[k] -= 0.05 * scene_radius;
            b[k] += 0.05 * scene_radius;
            segment(&v, a, b, blue);
        }
    }
    if (fclose(json) != 0) {
        json = NULL;
        fprintf(stderr, "snell-render: cannot write '%s': %s\n", path, strerror(errno));
        goto done;
    }
    json = NULL;
    printf("wrote %s (eye->glass yellow; FULL inside red, out green; MATCHED inside magenta, out cyan)\n", path);
    snprintf(path, sizeof path, "%s_trace.png", base);
    if (snell_write_png(path, width, height, v.px) != SNELL_OK) {
        fprintf(stderr, "snell-render: %s\n", snell_last_error(NULL));
        goto done;
    }
    printf("wrote %s (seen from a second camera)\n", path);
    rc = 0;
done:
    if (json) fclose(json);
    snell_ref_destroy(ref);
    snell_renderer_destroy(r);
    free(v.px);
    return rc;
}
