/* SPDX-License-Identifier: MIT */
/* lm2d_contour.c — image -> polygon without OpenCV (Brückner A.5): marching
 * squares on the alpha channel (sub-pixel by linear interpolation), the
 * longest closed contour, Ramer-Douglas-Peucker simplification, CSV output. */
#include "core/core.h"
#include "snell/snell_2d.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct grid {
    const uint8_t *rgba;
    int w, h;            /* image size; samples are (w+2) x (h+2) with a transparent border */
    int thr;
} grid;

static int alpha_at(const grid *g, int i, int j)
{
    if (i < 1 || j < 1 || i > g->w || j > g->h) return 0;
    return g->rgba[4 * ((size_t)(j - 1) * (size_t)g->w + (size_t)(i - 1)) + 3];
}

/* Sample (i, j) sits at pixel centre (i - 0.5, j - 0.5). Edge ids: horizontal
 * edge (i,j)-(i+1,j) = j*(w+2)+i; vertical (i,j)-(i,j+1) = nh + j*(w+2)+i. */
static void edge_point(const grid *g, int id, float p[2])
{
    int W = g->w + 2, nh = W * (g->h + 2), vert = id >= nh, k = vert ? id - nh : id;
    int i = k % W, j = k / W, i2 = vert ? i : i + 1, j2 = vert ? j + 1 : j;
    float a0 = (float)alpha_at(g, i, j), a1 = (float)alpha_at(g, i2, j2), t = 0.5f;
    if (a1 != a0) t = ((float)g->thr - 0.5f - a0) / (a1 - a0); /* threshold between integer levels */
    if (t < 0.0f) t = 0.0f;
    if (t > 1.0f) t = 1.0f;
    p[0] = (float)i - 0.5f + t * (float)(i2 - i);
    p[1] = (float)j - 0.5f + t * (float)(j2 - j);
}

/* Ramer-Douglas-Peucker's work bound: distance tests over the whole outline.
 * Each split scans its chain, so a chain that splits off a little at a time
 * costs up to (points)^2. Blobs need ~log2 of the points kept per point
 * (4096^2 images: a disc 13, a 12-lobed flower 16, a 40-pointed star 28); a
 * spiral outline needs ~(its turns) per point and grows with the image.
 * Past the bound (128 per point, several times a star's) the chains still
 * waiting keep all their points (the outline stays exact, only less
 * simplified) and a warning says so (bench/notes/code.md, "lm2d_contour.c"). */
#define RDP_WORK_BASE 16777216.0 /* 2^24 */
#define RDP_WORK_PER_POINT 128.0

/* RDP on the open chain pts[a..b] (indices into a closed list), marking kept
 * points; *work counts the distance tests, and once it passes limit every
 * point of the chains not yet split is kept. Returns the points kept so. */
static int rdp(const float *pts, int n, int a, int b, float eps, uint8_t *keep, int *stack, double *work,
               double limit)
{
    int sp = 0, unsimplified = 0;
    stack[sp++] = a;
    stack[sp++] = b;
    while (sp) {
        int e = stack[--sp], s = stack[--sp], k, best = -1;
        if (*work > limit) {
            for (k = s + 1; k < e; k++) {
                unsimplified += !keep[k % n];
                keep[k % n] = 1;
            }
            continue;
        }
        *work += (double)(e - s);
        float ax = pts[2 * (s % n)], ay = pts[2 * (s % n) + 1], bx = pts[2 * (e % n)], by = pts[2 * (e % n) + 1];
        float dx = bx - ax, dy = by - ay, l = sqrtf(dx * dx + dy * dy), dmax = eps;
        for (k = s + 1; k < e; k++) {
            float px = pts[2 * (k % n)] - ax, py = pts[2 * (k % n) + 1] - ay;
            float dist = l > 0.0f ? fabsf(px * dy - py * dx) / l : sqrtf(px * px + py * py);
            if (dist > dmax) {
                dmax = dist;
                best = k;
            }
        }
        if (best >= 0) {
            keep[best % n] = 1;
            stack[sp++] = s;
            stack[sp++] = best;
            stack[sp++] = best;
            stack[sp++] = e;
        }
    }
    return unsimplified;
}

snell_status snell_contour2d_from_alpha(snell_ctx *ctx, const uint8_t *rgba, int width, int height, int threshold,
                                        float epsilon, float **points, int *count)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    grid g;
    int W, H, nh, ne, i, j, best_start = -1, best_len = 0, n, m, far = 0, k;
    int32_t *next;
    uint8_t *seen, *keep;
    float *pts, *out, fd = -1.0f;
    int *stack;
    if (!rgba || !points || !count || width < 1 || height < 1)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "contour2d: NULL argument or empty image");
    *points = NULL;
    *count = 0;
    if (width > 16384 || height > 16384)
        return snell__fail(ctx, SNELL_E_LIMIT, "contour2d: image %dx%d larger than 16384", width, height);
    if (threshold < 1 || threshold > 255) threshold = 128;
    if (epsilon == 0.0f) epsilon = 0.5f;
    if (!(epsilon > 0.0f)) return snell__fail(ctx, SNELL_E_INVALID_ARG, "contour2d: epsilon must be > 0");
    g.rgba = rgba;
    g.w = width;
    g.h = height;
    g.thr = threshold;
    W = width + 2;
    H = height + 2;
    nh = W * H;
    ne = 2 * nh;
    next = (int32_t *)snell__malloc(al, (size_t)ne * sizeof *next);
    seen = (uint8_t *)snell__calloc(al, (size_t)ne, 1);
    if (!next || !seen) {
        snell__free(al, next);
        snell__free(al, seen);
        return snell__fail(ctx, SNELL_E_NOMEM, "contour2d: out of memory");
    }
    for (i = 0; i < ne; i++) next[i] = -1;
    /* Cells between samples (i,j) (i+1,j) (i+1,j+1) (i,j+1), corners a b c d in
     * screen-clockwise order, edges e_k from corner k to k+1: T R B L. A segment
     * runs from the edge where a run of inside corners ends to the edge where it
     * began; the neighbour sees the same edge reversed, so the pieces chain.
     * Saddles are resolved as two separate corners. */
    for (j = 0; j + 1 < H; j++) {
        for (i = 0; i + 1 < W; i++) {
            int f[4], e[4], c;
            f[0] = alpha_at(&g, i, j) >= threshold;
            f[1] = alpha_at(&g, i + 1, j) >= threshold;
            f[2] = alpha_at(&g, i + 1, j + 1) >= threshold;
            f[3] = alpha_at(&g, i, j + 1) >= threshold;
            if (f[0] == f[1] && f[1] == f[2] && f[2] == f[3]) continue;
            e[0] = j * W + i;
            e[1] = nh + j * W + i + 1;
            e[2] = (j + 1) * W + i;
            e[3] = nh + j * W + i;
            for (c = 0; c < 4; c++) {
                if (f[c] && !f[(c + 1) & 3]) {
                    int s = c;
                    while (f[(s + 3) & 3]) s = (s + 3) & 3;
                    next[e[c]] = e[(s + 3) & 3];
                }
            }
        }
    }
    /* the longest loop is the outline (holes and specks are dropped, like RETR_EXTERNAL) */
    for (i = 0; i < ne; i++) {
        int len = 0, cur = i;
        if (next[i] < 0 || seen[i]) continue;
        while (cur >= 0 && !seen[cur]) {
            seen[cur] = 1;
            cur = next[cur];
            len++;
        }
        if (len > best_len) {
            best_len = len;
            best_start = i;
        }
    }
    snell__free(al, seen);
    if (best_start < 0 || best_len < 3) {
        snell__free(al, next);
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "contour2d: no region with alpha >= %d in the image", threshold);
    }
    n = best_len;
    pts = (float *)snell__malloc(al, (size_t)n * 2 * sizeof(float));
    keep = (uint8_t *)snell__calloc(al, (size_t)n, 1);
    stack = (int *)snell__malloc(al, (size_t)(4 * n + 8) * sizeof(int));
    if (!pts || !keep || !stack) {
        snell__free(al, next);
        snell__free(al, pts);
        snell__free(al, keep);
        snell__free(al, stack);
        return snell__fail(ctx, SNELL_E_NOMEM, "contour2d: out of memory");
    }
    for (k = 0, j = best_start; k < n; k++, j = next[j]) edge_point(&g, j, pts + 2 * k);
    snell__free(al, next);
    /* closed RDP: split at point 0 and the point farthest from it */
    for (k = 1; k < n; k++) {
        float dx = pts[2 * k] - pts[0], dy = pts[2 * k + 1] - pts[1], dd = dx * dx + dy * dy;
        if (dd > fd) {
            fd = dd;
            far = k;
        }
    }
    keep[0] = keep[far] = 1;
    {
        double work = 0.0, limit = RDP_WORK_BASE + RDP_WORK_PER_POINT * (double)n;
        int raw = rdp(pts, n, 0, far, epsilon, keep, stack, &work, limit);
        raw += rdp(pts, n, far, n, epsilon, keep, stack, &work, limit);
        if (raw)
            snell__log(ctx, SNELL_LOG_WARN,
                       "contour2d: the simplification stopped at its work bound (%.0f distance tests for an outline "
                       "of %d points): %d points kept unsimplified",
                       limit, n, raw);
    }
    for (k = 0, m = 0; k < n; k++) m += keep[k];
    out = (float *)snell__malloc(al, (size_t)m * 2 * sizeof(float));
    if (!out) {
        snell__free(al, pts);
        snell__free(al, keep);
        snell__free(al, stack);
        return snell__fail(ctx, SNELL_E_NOMEM, "contour2d: out of memory");
    }
    for (k = 0, m = 0; k < n; k++)
        if (keep[k]) {
            out[2 * m] = pts[2 * k];
            out[2 * m + 1] = pts[2 * k + 1];
            m++;
        }
    snell__free(al, pts);
    snell__free(al, keep);
    snell__free(al, stack);
    if (m < 3) {
        snell__free(al, out);
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "contour2d: outline collapses to %d points at epsilon %g", m,
                           (double)epsilon);
    }
    *points = out;
    *count = m;
    return SNELL_OK;
}

void snell_contour2d_free(snell_ctx *ctx, float *points) { snell__free(snell__ctx_alloc(ctx), points); }

snell_status snell_contour2d_write_csv(const char *path, const float *points, int count)
{
    FILE *f;
    int i;
    if (!path || !points || count < 1) return snell__fail(NULL, SNELL_E_INVALID_ARG, "contour2d_write_csv: bad argument");
    f = fopen(path, "w");
    if (!f) return snell__fail(NULL, SNELL_E_IO, "cannot write \"%s\": %s", path, strerror(errno));
    for (i = 0; i < count; i++) fprintf(f, "%.9g,%.9g\n", (double)points[2 * i], (double)points[2 * i + 1]);
    if (fclose(f) != 0) return snell__fail(NULL, SNELL_E_IO, "error writing \"%s\"", path);
    return SNELL_OK;
}
