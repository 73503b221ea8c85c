/* SPDX-License-Identifier: MIT */
/* ref_panels.c — snell_ref_panels: snell_panels.h's model traced in double
 * precision over an RGBA8 image, so that the panels stage's error is a
 * number. The field's gradient is analytic (through the n-norm corners and
 * the smooth union); frost is a separable Gaussian of each shape's read
 * region, made once per shape, not per sample. */
#include "core/core.h"
#include "core/optics.h"
#include "frame/panel_model.h"

#include <math.h>
#include <string.h>

#define REF_PANELS_MAX_SIDE 16384
#define REF_PANELS_MAX_SAMPLES 16

/* A shape: a panel alone or a group merged, drawn where its first member is. */
typedef struct shape {
    const snell__panel *member[SNELL_PANEL_GROUP_MAX];
    int members;
    const snell__panel *m; /* the first member: the material, the height and the shadow */
} shape;

/* Integer pixel rectangle [x0, x1) x [y0, y1). */
typedef struct rect {
    int x0, y0, x1, y1;
} rect;

/* One shape's field at (x, y): d and its gradient. The rectangle with
 * corner radius r and exponent n of snell_panels.h; the gradient of
 * ||max(q, 0)||_n is max(q, 0)^(n-1) / ||.||_n^(n-1) per axis. */
static double box_field(const snell__panel *p, double x, double y, double g[2])
{
    double px = x - p->center[0], py = y - p->center[1];
    double sx = px < 0.0 ? -1.0 : 1.0, sy = py < 0.0 ? -1.0 : 1.0;
    int quadrant = py < 0.0 ? (px < 0.0 ? 0 : 1) : (px < 0.0 ? 3 : 2);
    double r = p->radius[quadrant], n = p->exponent;
    double qx = fabs(px) - ((double)p->half[0] - r), qy = fabs(py) - ((double)p->half[1] - r);
    if (qx > 0.0 || qy > 0.0) {
        double mx = qx > 0.0 ? qx : 0.0, my = qy > 0.0 ? qy : 0.0, big = mx > my ? mx : my;
        double ux = mx / big, uy = my / big, s = pow(pow(ux, n) + pow(uy, n), 1.0 / n);
        /* m_i^(n-1) / ||m||^(n-1) = (u_i / s)^(n-1), scaled by big to stay in range */
        g[0] = sx * pow(ux / s, n - 1.0);
        g[1] = sy * pow(uy / s, n - 1.0);
        return big * s - r;
    }
    if (qx > qy) {
        g[0] = sx, g[1] = 0.0;
        return qx - r;
    }
    g[0] = 0.0, g[1] = sy;
    return qy - r;
}

/* The shape's field: its members merged in order by smin with the group's
 * k; the gradient follows smin's weights (1 - h / 2k on the smaller, h / 2k
 * on the other, h = max(k - |a - b|, 0)). */
static double shape_field(const shape *s, double x, double y, double g[2])
{
    double d = box_field(s->member[0], x, y, g), k = s->m->merge;
    int i;
    for (i = 1; i < s->members; i++) {
        double gb[2], b = box_field(s->member[i], x, y, gb), h = k - fabs(d - b), w;
        if (!(h > 0.0)) {
            if (b < d) d = b, g[0] = gb[0], g[1] = gb[1];
            continue;
        }
        w = h / (2.0 * k); /* the weight of the larger one */
        if (d <= b) {
            g[0] = (1.0 - w) * g[0] + w * gb[0];
            g[1] = (1.0 - w) * g[1] + w * gb[1];
            d = d - h * h / (4.0 * k);
        } else {
            g[0] = w * g[0] + (1.0 - w) * gb[0];
            g[1] = w * g[1] + (1.0 - w) * gb[1];
            d = b - h * h / (4.0 * k);
        }
    }
    return d;
}

/* Height h(s) and the normal's unnormalised (a grad d, b) with a / b = h'(s):
 * both stay finite where the circular profile's slope is infinite (s = 0). */
static double profile(const snell__panel *m, double s, double *a, double *b)
{
    double u, v;
    if (m->bevel <= 0.0f || s >= m->bevel) {
        *a = 0.0, *b = 1.0;
        return m->thickness;
    }
    u = s / m->bevel;
    v = 1.0 - u;
    if (m->profile == SNELL_PANEL_BEVEL_SQUIRCLE) {
        double w = 1.0 - v * v * v * v; /* P = w^(1/4), P' = v^3 w^(-3/4) */
        *a = (double)m->thickness / m->bevel * v * v * v;
        *b = pow(w, 0.75);
        return m->thickness * pow(w, 0.25);
    }
    *a = (double)m->thickness / m->bevel * v; /* P = sqrt(1 - v^2), P' = v / P */
    *b = sqrt(1.0 - v * v);
    return m->thickness * *b;
}

/* What lies beneath, read as the GPU reads an RGBA8 texture: bilinear at
 * (x, y) in the frame's pixels, edges clamped; img covers r (4 floats a
 * pixel, 0..1), which holds every texel the shape can reach. */
static double bilinear(const float *img, rect r, int width, int height, double x, double y, int c)
{
    double fx = x - 0.5, fy = y - 0.5, ax, ay;
    double ix = floor(fx), iy = floor(fy);
    int x0, x1, y0, y1, rw = r.x1 - r.x0;
    ax = fx - ix, ay = fy - iy;
    ix = ix < -1.0 ? -1.0 : ix > width ? width : ix; /* far landings: clamped before the cast */
    iy = iy < -1.0 ? -1.0 : iy > height ? height : iy;
    x0 = (int)ix, y0 = (int)iy, x1 = x0 + 1, y1 = y0 + 1;
#define CLAMP_TO(v, lo, hi) ((v) < (lo) ? (lo) : (v) > (hi) ? (hi) : (v))
    x0 = CLAMP_TO(x0, 0, width - 1), x1 = CLAMP_TO(x1, 0, width - 1);
    y0 = CLAMP_TO(y0, 0, height - 1), y1 = CLAMP_TO(y1, 0, height - 1);
    x0 = CLAMP_TO(x0, r.x0, r.x1 - 1) - r.x0, x1 = CLAMP_TO(x1, r.x0, r.x1 - 1) - r.x0;
    y0 = CLAMP_TO(y0, r.y0, r.y1 - 1) - r.y0, y1 = CLAMP_TO(y1, r.y0, r.y1 - 1) - r.y0;
#undef CLAMP_TO
    {
        double a = img[4 * ((size_t)y0 * rw + x0) + c], b = img[4 * ((size_t)y0 * rw + x1) + c];
        double e = img[4 * ((size_t)y1 * rw + x0) + c], f = img[4 * ((size_t)y1 * rw + x1) + c];
        return (1.0 - ay) * ((1.0 - ax) * a + ax * b) + ay * ((1.0 - ax) * e + ax * f);
    }
}

/* The colour of one sample inside the shape (d < 0): refraction into the
 * slab per channel, what lies beneath where each ray lands, tint, Fresnel
 * and the rim light. */
static void glass_sample(const shape *s, const float *img, rect r, int width, int height, double x, double y,
                         double d, const double g[2], double rgb[3])
{
    const snell__panel *m = s->m;
    static const double down[3] = {0.0, 0.0, -1.0};
    double a, b, len, n[3], h = profile(m, -d, &a, &b), ior[3], refl[3], spec;
    int c;
    n[0] = a * g[0], n[1] = a * g[1], n[2] = b;
    len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    n[0] /= len, n[1] /= len, n[2] /= len;
    snell_optd_reflect(down, n, refl);
    spec = refl[0] * m->light[0] + refl[1] * m->light[1] + refl[2] * m->light[2];
    spec = spec > 0.0 ? spec * spec * spec * spec : 0.0;
    snell_optd_ior_rgb(m->ior, m->dispersion, ior);
    for (c = 0; c < 3; c++) {
        double t[3], F = snell_optd_fresnel_exact(n[2], 1.0, ior[c]), under, v;
        snell_optd_refract(down, n, 1.0 / ior[c], t); /* into a denser medium: never total */
        under = bilinear(img, r, width, height, x + h * t[0] / -t[2], y + h * t[1] / -t[2], c);
        under += (m->tint[c] - under) * m->tint[3];
        v = (1.0 - F) * under + F * m->rim * spec;
        rgb[c] = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    }
}

/* The pixels the shape may change (its members' bounds) and those its rays
 * may read (grown by the farthest landing, h sqrt(ior^2 - 1) for the
 * bluest index, and a texel), both clipped to the frame. 0 if culled. */
static int shape_rects(const shape *s, int width, int height, rect *draw, rect *read, double *reach)
{
    double box[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY}, ior[3], nmax, grow;
    int i;
    for (i = 0; i < s->members; i++) {
        float b[4];
        snell__panel_bounds(s->member[i], b);
        box[0] = b[0] < box[0] ? b[0] : box[0], box[1] = b[1] < box[1] ? b[1] : box[1];
        box[2] = b[2] > box[2] ? b[2] : box[2], box[3] = b[3] > box[3] ? b[3] : box[3];
    }
    box[0] = floor(box[0] < 0.0 ? 0.0 : box[0]), box[1] = floor(box[1] < 0.0 ? 0.0 : box[1]);
    box[2] = ceil(box[2] > width ? width : box[2]), box[3] = ceil(box[3] > height ? height : box[3]);
    if (!(box[0] < box[2] && box[1] < box[3])) return 0;
    draw->x0 = (int)box[0], draw->y0 = (int)box[1], draw->x1 = (int)box[2], draw->y1 = (int)box[3];
    snell_optd_ior_rgb(s->m->ior, s->m->dispersion, ior);
    nmax = ior[0] > ior[2] ? ior[0] : ior[2];
    nmax = nmax > ior[1] ? nmax : ior[1];
    *reach = (double)s->m->thickness * sqrt(nmax * nmax - 1.0);
    grow = ceil(*reach) + 2.0;
    read->x0 = draw->x0 - grow < 0.0 ? 0 : draw->x0 - (int)grow;
    read->y0 = draw->y0 - grow < 0.0 ? 0 : draw->y0 - (int)grow;
    read->x1 = draw->x1 + grow > width ? width : draw->x1 + (int)grow;
    read->y1 = draw->y1 + grow > height ? height : draw->y1 + (int)grow;
    return 1;
}

/* img over r: the frame as it stands (0..1), blurred by a Gaussian of sigma
 * frost cut at 3 sigma (weights normalised, edges of the frame clamped),
 * horizontally into tmp over r's columns and rows grown by the kernel, then
 * vertically. */
static void capture(const uint8_t *frame, int width, int height, rect r, double sigma, float *img, float *tmp)
{
    int radius = sigma > 0.0 ? (int)floor(3.0 * sigma) : 0, rw = r.x1 - r.x0, x, y, k, c;
    int ty0 = r.y0 - radius < 0 ? 0 : r.y0 - radius, ty1 = r.y1 + radius > height ? height : r.y1 + radius;
    double w[3 * 64 + 1], sum = 0.0;
    if (radius == 0) {
        for (y = r.y0; y < r.y1; y++)
            for (x = r.x0; x < r.x1; x++)
                for (c = 0; c < 4; c++)
                    img[4 * ((size_t)(y - r.y0) * rw + (x - r.x0)) + c] =
                        frame[4 * ((size_t)y * width + x) + c] / 255.0f;
        return;
    }
    for (k = 0; k <= radius; k++) sum += (k ? 2.0 : 1.0) * (w[k] = exp(-0.5 * k * k / (sigma * sigma)));
    for (k = 0; k <= radius; k++) w[k] /= sum;
    for (y = ty0; y < ty1; y++)
        for (x = r.x0; x < r.x1; x++)
            for (c = 0; c < 4; c++) {
                double v = 0.0;
                for (k = -radius; k <= radius; k++) {
                    int xs = x + k < 0 ? 0 : x + k >= width ? width - 1 : x + k;
                    v += w[k < 0 ? -k : k] * frame[4 * ((size_t)y * width + xs) + c];
                }
                tmp[4 * ((size_t)(y - ty0) * rw + (x - r.x0)) + c] = (float)(v / 255.0);
            }
    for (y = r.y0; y < r.y1; y++)
        for (x = r.x0; x < r.x1; x++)
            for (c = 0; c < 4; c++) {
                double v = 0.0;
                for (k = -radius; k <= radius; k++) {
                    int ys = y + k < 0 ? 0 : y + k >= height ? height - 1 : y + k;
                    v += w[k < 0 ? -k : k] * tmp[4 * ((size_t)(ys - ty0) * rw + (x - r.x0)) + c];
                }
                img[4 * ((size_t)(y - r.y0) * rw + (x - r.x0)) + c] = (float)v;
            }
}

/* One shape over the frame (in place: each pixel of draw is read once,
 * before it is written; the rays read img, the capture made before). */
static void draw_shape(const shape *s, uint8_t *frame, int width, int height, int samples, rect draw, rect read,
                       const float *img)
{
    const snell__panel *m = s->m;
    double opacity = m->shadow[1], radius = m->shadow[0], inv = 1.0 / ((double)samples * samples);
    int x, y, i, j, c;
    for (y = draw.y0; y < draw.y1; y++)
        for (x = draw.x0; x < draw.x1; x++) {
            uint8_t *px = frame + 4 * ((size_t)y * width + x);
            double sum[3] = {0.0, 0.0, 0.0};
            for (j = 0; j < samples; j++)
                for (i = 0; i < samples; i++) {
                    double sx = x + (i + 0.5) / samples, sy = y + (j + 0.5) / samples, g[2], rgb[3];
                    double d = shape_field(s, sx, sy, g), keep = 1.0;
                    if (d < 0.0) {
                        glass_sample(s, img, read, width, height, sx, sy, d, g, rgb);
                        for (c = 0; c < 3; c++) sum[c] += rgb[c];
                        continue;
                    }
                    if (opacity > 0.0) {
                        double gs[2], ds = shape_field(s, sx - m->shadow[2], sy - m->shadow[3], gs);
                        double t = radius > 0.0 ? ds / radius : (ds < 0.0 ? 0.0 : 1.0);
                        t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
                        keep = 1.0 - opacity * (1.0 - t) * (1.0 - t);
                    }
                    for (c = 0; c < 3; c++) sum[c] += keep * px[c] / 255.0;
                }
            for (c = 0; c < 3; c++) px[c] = (uint8_t)floor(sum[c] * inv * 255.0 + 0.5);
        }
}

snell_status snell_ref_panels(const snell_panel *panels, int count, const uint8_t *under, int width, int height,
                              int samples, uint8_t *out)
{
    const snell_alloc *al = snell__ctx_alloc(NULL);
    snell__panel *resolved = NULL;
    float *img = NULL, *tmp = NULL;
    size_t img_size = 0, tmp_size = 0, bytes;
    char msg[256];
    int i, j, pass;

    if (!under || !out || width < 1 || height < 1 || width > REF_PANELS_MAX_SIDE || height > REF_PANELS_MAX_SIDE)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ref_panels: under and out required, width and height "
                           "1..%d", REF_PANELS_MAX_SIDE);
    if (samples < 0 || samples > REF_PANELS_MAX_SAMPLES)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ref_panels: samples %d outside 0..%d", samples,
                           REF_PANELS_MAX_SAMPLES);
    bytes = (size_t)width * (size_t)height * 4;
    if (out < under + bytes && under < out + bytes)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ref_panels: out overlaps under");
    if (count < 0 || count > SNELL_MAX_PANELS || (count > 0 && !panels))
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ref_panels: %d panels (0..%d, panels required)", count,
                           SNELL_MAX_PANELS);
    if (samples == 0) samples = 8;
    if (count > 0 && !(resolved = (snell__panel *)snell__calloc(al, (size_t)count, sizeof *resolved)))
        return snell__fail(NULL, SNELL_E_NOMEM, "snell_ref_panels: out of memory");
    if (count > 0 && snell__panels_resolve(panels, count, resolved, msg, sizeof msg)) {
        snell__free(al, resolved);
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ref_panels: %s", msg);
    }
    memcpy(out, under, bytes);
    /* Pass 0 sizes the captures (the largest shape's), pass 1 draws. */
    for (pass = 0; pass < 2; pass++) {
        if (pass == 1 && img_size > 0) {
            img = (float *)snell__calloc(al, img_size, 4 * sizeof(float));
            tmp = tmp_size ? (float *)snell__calloc(al, tmp_size, 4 * sizeof(float)) : NULL;
            if (!img || (tmp_size && !tmp)) {
                snell__free(al, img), snell__free(al, tmp), snell__free(al, resolved);
                return snell__fail(NULL, SNELL_E_NOMEM, "snell_ref_panels: out of memory for a %zu-pixel capture",
                                   img_size);
            }
        }
        for (i = 0; i < count; i++) {
            shape s;
            rect draw, read;
            double reach;
            int first = 1, radius;
            for (j = 0; j < i && resolved[i].group; j++)
                if (resolved[j].group == resolved[i].group) first = 0;
            if (!first) continue;
            s.members = 0;
            s.m = &resolved[i];
            for (j = i; j < count && s.members < SNELL_PANEL_GROUP_MAX; j++)
                if (j == i || (resolved[i].group && resolved[j].group == resolved[i].group))
                    s.member[s.members++] = &resolved[j];
            if (!shape_rects(&s, width, height, &draw, &read, &reach)) continue;
            radius = s.m->frost > 0.0f ? (int)floor(3.0 * s.m->frost) : 0;
            if (pass == 0) {
                size_t area = (size_t)(read.x1 - read.x0) * (size_t)(read.y1 - read.y0);
                size_t rows = (size_t)(read.y1 - read.y0) + 2 * (size_t)radius;
                size_t tarea = radius ? (size_t)(read.x1 - read.x0) * rows : 0;
                img_size = area > img_size ? area : img_size;
                tmp_size = tarea > tmp_size ? tarea : tmp_size;
                continue;
            }
            capture(out, width, height, read, s.m->frost, img, tmp);
            draw_shape(&s, out, width, height, samples, draw, read, img);
        }
    }
    snell__free(al, img);
    snell__free(al, tmp);
    snell__free(al, resolved);
    return SNELL_OK;
}
