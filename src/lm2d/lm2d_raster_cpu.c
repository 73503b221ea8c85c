/* SPDX-License-Identifier: MIT */
/* lm2d_raster_cpu.c — exact length-weighted rasterisation of path segments
 * (eq. 4.2) in pixel space, threaded over row bands. A segment is walked along
 * its major axis in 32.32 fixed point (an integer add per unit, the same cells
 * from any band's start); bands of fixed height, one thread each, segments in
 * list order: bitwise the same image for any thread count. More:
 * docs/ARCHITECTURE.md, "Design notes by file". */
#include "lm2d/lm2d_raster_cpu.h"

#include <math.h>
#include <string.h>

#if defined(__GNUC__)
#define LM2D_ALWAYS_INLINE static inline __attribute__((always_inline))
#define LM2D_PREFETCH(p)                                                                                               \
    do {                                                                                                               \
        __builtin_prefetch(p);                                                                                         \
        __builtin_prefetch((const char *)(p) + 64);                                                                    \
    } while (0)
#else
#define LM2D_ALWAYS_INLINE static inline
#define LM2D_PREFETCH(p) ((void)(p))
#endif

/* floor for |v| < 2^31 (coordinates here are clipped to the image first) */
static inline int ifloor(double v)
{
    int i = (int)v;
    return i - (v < (double)i);
}

/* Fixed point for minor coordinates in [-FIX_BIAS, 2^14 + FIX_BIAS] px, biased
 * so they stay positive (the shift is then a floor). */
#define FIX_BIAS 16
#define FIX_ONE 4294967296.0 /* 2^32 */

static inline int64_t fix(double v) { return (int64_t)((v + (double)FIX_BIAS) * FIX_ONE + 0.5); }
static inline int fix_cell(int64_t v) { return (int)(v >> 32) - FIX_BIAS; }
static inline int64_t fix_of_cell(int c) { return (int64_t)(c + FIX_BIAS) * (int64_t)4294967296LL; }

/* A segment ready to walk: major axis u (x, or y when swap), minor v. */
typedef struct seg {
    double u0, inv;        /* start and 1/du: segment parameter t = (u - u0) inv */
    double L;              /* length per major unit (pixel widths) */
    double invM;           /* major units per fixed-point minor unit (0 if M = 0) */
    double ua, ub;         /* clipped major range */
    int64_t M;             /* minor step per major unit, fixed point (|M| <= 2^32) */
    int64_t vo, va, vb;    /* fixed-point minor coordinate at u = ka, ua, ub */
    float a[3], b[3];      /* scale * c0, scale * (c1 - c0): value per pixel width at t is a + b t */
    int ka, kb;            /* first and last major unit touched */
    int16_t b0, b1;        /* bands that may hold cells (b0 > b1: none) */
    uint8_t swap, flat;    /* y-major; constant flux (b = 0) */
} seg;

typedef struct band {
    float *img;            /* LM2D_RASTER_PX floats per pixel */
    int w, r0, r1;         /* image width; rows [r0, r1) belong to this band */
    int screen;
} band;

/* One cell's share: l pixel widths at segment parameter t (flat: b = 0, t unused). */
LM2D_ALWAYS_INLINE void put(float *px, const float a[4], const float b[4], double l, double t, const int screen,
                            const int flat)
{
    float fl = (float)l, ft = (float)t, v[4];
    int i;
    for (i = 0; i < 4; i++) v[i] = flat ? fl * a[i] : fl * (a[i] + b[i] * ft);
    if (!screen)
        for (i = 0; i < 4; i++) px[i] += v[i];
    else
        for (i = 0; i < 4; i++) px[i] *= 1.0f - (v[i] < 1.0f ? v[i] : 1.0f);
}

/* The cell at major unit k, minor cell mi, if in the band (x-major: mi is a
 * row, k a column; swap (y-major): k is a row of the band, mi a column). */
#define CELL(mi, l, t)                                                                                                 \
    do {                                                                                                               \
        int mi_ = (mi);                                                                                                \
        if (swap) {                                                                                                    \
            if ((unsigned)mi_ < (unsigned)w)                                                                           \
                put(img + LM2D_RASTER_PX * ((size_t)k * (size_t)w + (size_t)mi_), a, b, l, t, screen, flat);          \
        } else if (mi_ >= r0 && mi_ < r1) {                                                                            \
            put(img + LM2D_RASTER_PX * ((size_t)mi_ * (size_t)w + (size_t)k), a, b, l, t, screen, flat);              \
        }                                                                                                              \
    } while (0)

/* A unit [lo, hi] of major index k whose minor coordinate goes from vlo to vhi
 * (fixed point): one cell, or two split where it crosses the minor boundary
 * (|difference| 1; 2 only through rounding, the middle cell then gets nothing). */
#define UNIT(lo, hi, vlo, vhi)                                                                                         \
    do {                                                                                                               \
        int rlo_ = fix_cell(vlo), rhi_ = fix_cell(vhi);                                                                \
        if (rlo_ == rhi_) {                                                                                            \
            CELL(rlo_, ((hi) - (lo)) * L, (0.5 * ((lo) + (hi)) - u0) * inv);                                           \
        } else {                                                                                                       \
            double c_ = (lo) + (double)(fix_of_cell(rlo_ > rhi_ ? rlo_ : rhi_) - (vlo)) * invM;                        \
            c_ = c_ > (lo) ? (c_ < (hi) ? c_ : (hi)) : (lo);                                                           \
            CELL(rlo_, (c_ - (lo)) * L, (0.5 * ((lo) + c_) - u0) * inv);                                               \
            CELL(rhi_, ((hi) - c_) * L, (0.5 * (c_ + (hi)) - u0) * inv);                                               \
        }                                                                                                              \
    } while (0)

/* Walks segment s over major units [k0, k1] (already limited to the band).
 * swap, screen and flat are constants in every caller. */
LM2D_ALWAYS_INLINE void walk_major(const band *bd, const seg *s, const int swap, const int screen, const int flat,
                                   int k0, int k1)
{
    const float a[4] = {s->a[0], s->a[1], s->a[2], 0.0f}, b[4] = {s->b[0], s->b[1], s->b[2], 0.0f};
    const double u0 = s->u0, inv = s->inv, L = s->L, invM = s->invM;
    const int64_t M = s->M;
    float *const img = bd->img;
    const int w = bd->w, r0 = bd->r0, r1 = bd->r1, ka = s->ka, kb = s->kb;
    int k = k0;
    if (k == ka) { /* first unit: starts at ua */
        double hi = ka == kb ? s->ub : (double)(ka + 1);
        int64_t vhi = ka == kb ? s->vb : s->vo + M;
        UNIT(s->ua, hi, s->va, vhi);
        k++;
    }
    if (k <= k1 && k < kb) { /* whole units [k, k + 1] */
        const float fL = (float)L, aL[4] = {fL * a[0], fL * a[1], fL * a[2], 0.0f}; /* = put(.., L, ..) when flat */
        const size_t stride = LM2D_RASTER_PX * (size_t)w;
        int kend = k1 < kb - 1 ? k1 : kb - 1, r, in;
        int64_t v = s->vo + (int64_t)(k - ka) * M;
        float *line; /* swap: row k; else row r (row r0 while r is outside the band) */
        r = fix_cell(v);
        in = swap ? (unsigned)r < (unsigned)w : r >= r0 && r < r1;
        line = img + (swap ? (size_t)k : (size_t)(in ? r : r0)) * stride;
        for (; k <= kend; k++) {
            int64_t vn = v + M;
            int rn = fix_cell(vn);
            if (rn == r) { /* the common case: the whole unit in one cell */
                if (in) {
                    float *px = line + LM2D_RASTER_PX * (size_t)(swap ? r : k);
                    if (flat && !screen) {
                        px[0] += aL[0];
                        px[1] += aL[1];
                        px[2] += aL[2];
                        px[3] += aL[3];
                    } else {
                        put(px, a, b, L, ((double)k + 0.5 - u0) * inv, screen, flat);
                    }
                }
            } else {
                double kd = (double)k, c = kd + (double)(fix_of_cell(rn > r ? rn : r) - v) * invM;
                c = c > kd ? (c < kd + 1.0 ? c : kd + 1.0) : kd;
                CELL(r, (c - kd) * L, (0.5 * (kd + c) - u0) * inv);
                CELL(rn, (kd + 1.0 - c) * L, (0.5 * (c + kd + 1.0) - u0) * inv);
                r = rn;
                in = swap ? (unsigned)r < (unsigned)w : r >= r0 && r < r1;
                if (!swap) line = img + (size_t)(in ? r : r0) * stride;
            }
            v = vn;
            if (swap) line += stride;
        }
    }
    if (k <= k1 && k == kb && kb > ka) { /* last unit: ends at ub */
        int64_t v = s->vo + (int64_t)(kb - ka) * M;
        UNIT((double)kb, s->ub, v, s->vb);
    }
}
#undef CELL
#undef UNIT

#define WALK_VARIANT(name, swap, screen, flat)                                                                        \
    static void name(const band *bd, const seg *s, int k0, int k1) { walk_major(bd, s, swap, screen, flat, k0, k1); }
WALK_VARIANT(walk_x_add, 0, 0, 0)
WALK_VARIANT(walk_x_add_flat, 0, 0, 1)
WALK_VARIANT(walk_y_add, 1, 0, 0)
WALK_VARIANT(walk_y_add_flat, 1, 0, 1)
WALK_VARIANT(walk_x_screen, 0, 1, 0)
WALK_VARIANT(walk_x_screen_flat, 0, 1, 1)
WALK_VARIANT(walk_y_screen, 1, 1, 0)
WALK_VARIANT(walk_y_screen_flat, 1, 1, 1)
#undef WALK_VARIANT

typedef void (*walk_fn)(const band *, const seg *, int, int);
static const walk_fn walks[2][2][2] = {/* [swap][screen][flat] */
                                       {{walk_x_add, walk_x_add_flat}, {walk_x_screen, walk_x_screen_flat}},
                                       {{walk_y_add, walk_y_add_flat}, {walk_y_screen, walk_y_screen_flat}}};

/* The units of s inside band bd, and its walk. */
static void seg_band(const band *bd, const seg *s)
{
    int k0 = s->ka, k1 = s->kb;
    if (s->swap) {
        if (k0 < bd->r0) k0 = bd->r0;
        if (k1 > bd->r1 - 1) k1 = bd->r1 - 1;
    } else {
        /* columns of the image (clipping leaves ua, ub within rounding of [0, width]) */
        if (k0 < 0) k0 = 0;
        if (k1 > bd->w - 1) k1 = bd->w - 1;
    }
    if (!s->swap && s->M != 0) {
        /* columns where the row is within the band, one of slack on each side */
        double e0 = (double)s->ka + (double)(fix_of_cell(bd->r0 - 1) - s->vo) * s->invM;
        double e1 = (double)s->ka + (double)(fix_of_cell(bd->r1 + 1) - s->vo) * s->invM;
        double lo = e0 < e1 ? e0 : e1, hi = e0 < e1 ? e1 : e0;
        if (lo - 1.0 > (double)k0) k0 = ifloor(lo - 1.0);
        if (hi + 1.0 < (double)k1) k1 = ifloor(hi + 1.0);
    }
    if (k0 <= k1) walks[s->swap][bd->screen][s->flat](bd, s, k0, k1);
}

/* One axis of Liang-Barsky: narrows [*a, *b] to where p + t d lies in
 * [0, extent]; id = 1/d (d != 0). 0 if the segment misses when d is 0. */
static int clip_axis(double p, double d, double id, double extent, double *a, double *b)
{
    double t0, t1;
    if (d == 0.0) return !(p < 0.0 || p > extent);
    t0 = -p * id;
    t1 = (extent - p) * id;
    if (t0 > t1) {
        double t = t0;
        t0 = t1;
        t1 = t;
    }
    *a = t0 > *a ? t0 : *a;
    *b = t1 < *b ? t1 : *b;
    return 1;
}

/* Liang-Barsky: the parameter range of p + t d, t in [0,1], inside [0,w] x [0,h];
 * idx, idy = 1/dx, 1/dy (0 where d is 0). */
static int clip_unit(double px, double py, double dx, double dy, double idx, double idy, double w, double h,
                     double *ta, double *tb)
{
    double a = 0.0, b = 1.0;
    if (!clip_axis(px, dx, idx, w, &a, &b) || !clip_axis(py, dy, idy, h, &a, &b)) return 0;
    if (!(a < b)) return 0;
    *ta = a;
    *tb = b;
    return 1;
}

/* Walk parameters of path q in pixel space (sx, sy: pixels per world unit);
 * b0 > b1 when nothing of it is inside the image. */
static void seg_setup(seg *s, const lm2d_path *q, const lm2d_raster_view *v, double sx, double sy, float scale)
{
    double x0 = ((double)q->x0 - v->lo[0]) * sx, y0 = ((double)q->y0 - v->lo[1]) * sy;
    double x1 = ((double)q->x1 - v->lo[0]) * sx, y1 = ((double)q->y1 - v->lo[1]) * sy;
    double dx = x1 - x0, dy = y1 - y0, idx, idy, ta, tb, u0, v0, du, dv, iu, m, ya, yb, hmax;
    int k;
    s->b0 = 1;
    s->b1 = 0;
    if (!(dx != 0.0 || dy != 0.0)) return; /* also NaN */
    idx = dx != 0.0 ? 1.0 / dx : 0.0;
    idy = dy != 0.0 ? 1.0 / dy : 0.0;
    if (!clip_unit(x0, y0, dx, dy, idx, idy, (double)v->width, (double)v->height, &ta, &tb)) return;
    s->swap = fabs(dx) < fabs(dy);
    u0 = s->swap ? y0 : x0;
    v0 = s->swap ? x0 : y0;
    du = s->swap ? dy : dx;
    dv = s->swap ? dx : dy;
    iu = s->swap ? idy : idx;
    m = dv * iu;
    s->u0 = u0;
    s->inv = iu;
    s->L = sqrt(dx * dx + dy * dy) * fabs(iu);
    s->ua = u0 + ta * du;
    s->ub = u0 + tb * du;
    if (s->ua > s->ub) {
        double t = s->ua;
        s->ua = s->ub;
        s->ub = t;
    }
    s->M = (int64_t)(m * FIX_ONE + (m >= 0.0 ? 0.5 : -0.5));
    s->invM = s->M != 0 ? 1.0 / (double)s->M : 0.0;
    s->ka = ifloor(s->ua);
    s->kb = ifloor(s->ub);
    if ((double)s->kb == s->ub && s->kb > s->ka) s->kb--; /* the unit starting at ub is empty */
    s->vo = fix(v0 + ((double)s->ka - u0) * m); /* fixed by the segment, whichever band walks it */
    s->va = fix(v0 + (s->ua - u0) * m);
    s->vb = fix(v0 + (s->ub - u0) * m);
    for (k = 0; k < 3; k++) {
        s->a[k] = scale * q->c0[k];
        s->b[k] = scale * (q->c1[k] - q->c0[k]);
    }
    s->flat = s->b[0] == 0.0f && s->b[1] == 0.0f && s->b[2] == 0.0f; /* constant flux: most paths (in air) */
    /* bands: rows of the clipped y extent, one of slack for rounding */
    ya = y0 + ta * dy;
    yb = y0 + tb * dy;
    if (ya > yb) {
        double t = ya;
        ya = yb;
        yb = t;
    }
    hmax = (double)(v->height - 1);
    ya = ya - 1.0 > 0.0 ? ya - 1.0 : 0.0;
    yb = yb + 1.0 < hmax ? yb + 1.0 : hmax;
    s->b0 = (int16_t)((int)ya / LM2D_RASTER_BAND);
    s->b1 = (int16_t)((int)yb / LM2D_RASTER_BAND);
}

/* ------------------------------------------------------------ binning */
/* Segments are numbered across the lists (g = base[list] + index); each band
 * gets the numbers of the segments that may touch it, in increasing order. */
struct lm2d_raster_bins {
    const snell_alloc *al;
    seg *segs;           /* per segment number: walk parameters */
    size_t cap_segs;
    uint32_t *entries;   /* band b: entries[start[b] .. start[b + 1]) */
    size_t cap_entries;
    uint32_t *start;     /* n_bands + 1 */
    uint32_t *cursor;    /* threads * n_bands: per-thread counts, then fill positions */
    uint32_t *base;      /* n_src + 1 */
    size_t cap_start, cap_cursor, cap_base;
    size_t limit;        /* most bytes of segs and entries (0: none) */
};

size_t lm2d_raster_bins_bytes(size_t segments)
{
    size_t per = sizeof(seg) + sizeof(uint32_t);
    if (segments > ((size_t)-1 - 64) / 2 / per) return (size_t)-1;
    return (segments + segments / 4 + 64) * per;
}

void lm2d_raster_bins_limit(lm2d_raster_bins *bins, size_t bytes) { bins->limit = bytes; }

snell_status lm2d_raster_bins_create(const snell_ctx *ctx, const snell_alloc *al, lm2d_raster_bins **out)
{
    *out = (lm2d_raster_bins *)snell__calloc(al, 1, sizeof **out);
    if (!*out) return snell__fail(ctx, SNELL_E_NOMEM, "lightmap2d: out of memory");
    (*out)->al = al;
    return SNELL_OK;
}

void lm2d_raster_bins_destroy(lm2d_raster_bins *b)
{
    if (!b) return;
    snell__free(b->al, b->segs);
    snell__free(b->al, b->entries);
    snell__free(b->al, b->start);
    snell__free(b->al, b->cursor);
    snell__free(b->al, b->base);
    snell__free(b->al, b);
}

/* Grows *p to hold n elements of `size` bytes, with headroom so a frame with a
 * few more paths than the last does not allocate. */
static int grow(const snell_alloc *al, void **p, size_t *cap, size_t n, size_t size)
{
    void *q;
    size_t c;
    int ok = 1;
    if (n <= *cap) return 1;
    c = n + n / 4 + 64;
    snell__mul_size(c, size, &ok);
    if (!ok) return 0;
    q = snell__realloc(al, *p, c * size);
    if (!q) return 0;
    *p = q;
    *cap = c;
    return 1;
}

typedef struct job {
    const lm2d_raster_src *src;
    int n_src;
    const lm2d_raster_view *v;
    double sx, sy;
    float scale;
    int screen, clear, n_bands, threads;
    float *img;
    lm2d_raster_bins *bins;   /* NULL: every band sets up and tests every segment */
    uint32_t n_seg;
    int next;                 /* next band to take (atomic) */
} job;

/* The list and index of segment number g, from a guess li (numbers only increase). */
static const lm2d_path *path_of(const job *j, uint32_t g, int *li)
{
    while (g >= j->bins->base[*li + 1]) (*li)++;
    return j->src[*li].paths + (g - j->bins->base[*li]);
}

/* Pass 1 (count: sets segments up and counts them per band) or 2 (fill) over
 * this thread's share of the segment numbers. */
static void bin_pass(int t, int T, void *arg, int fill)
{
    job *j = (job *)arg;
    lm2d_raster_bins *bs = j->bins;
    uint32_t g0 = (uint32_t)((uint64_t)j->n_seg * (uint64_t)t / (uint64_t)T);
    uint32_t g1 = (uint32_t)((uint64_t)j->n_seg * (uint64_t)(t + 1) / (uint64_t)T), g;
    uint32_t *cur = bs->cursor + (size_t)t * (size_t)j->n_bands;
    int li = 0, b;
    if (!fill)
        for (b = 0; b < j->n_bands; b++) cur[b] = 0;
    for (g = g0; g < g1; g++) {
        seg *s = &bs->segs[g];
        if (!fill) seg_setup(s, path_of(j, g, &li), j->v, j->sx, j->sy, j->scale);
        for (b = s->b0; b <= s->b1; b++) {
            if (fill) bs->entries[cur[b]++] = g;
            else cur[b]++;
        }
    }
}

static void count_job(int t, int T, void *arg) { bin_pass(t, T, arg, 0); }
static void fill_job(int t, int T, void *arg) { bin_pass(t, T, arg, 1); }

static void run_band(const job *j, int b)
{
    const lm2d_raster_view *v = j->v;
    band bd;
    bd.img = j->img;
    bd.w = v->width;
    bd.r0 = b * LM2D_RASTER_BAND;
    bd.r1 = bd.r0 + LM2D_RASTER_BAND < v->height ? bd.r0 + LM2D_RASTER_BAND : v->height;
    bd.screen = j->screen;
    if (j->clear) {
        float *p = j->img + LM2D_RASTER_PX * (size_t)bd.r0 * (size_t)v->width;
        float *e = j->img + LM2D_RASTER_PX * (size_t)bd.r1 * (size_t)v->width;
        if (!j->screen) memset(p, 0, (size_t)(e - p) * sizeof(float));
        else
            while (p < e) *p++ = 1.0f;
    }
    if (j->bins) {
        const uint32_t *e = j->bins->entries + j->bins->start[b], *end = j->bins->entries + j->bins->start[b + 1];
        for (; e < end; e++) {
            /* a band's segments are scattered over the frame's setups: fetch ahead,
             * or each segment costs a cache miss (bench/notes/code.md) */
            if (e + 4 < end) LM2D_PREFETCH(&j->bins->segs[e[4]]);
            seg_band(&bd, &j->bins->segs[*e]);
        }
    } else {
        int li;
        size_t i;
        for (li = 0; li < j->n_src; li++)
            for (i = 0; i < j->src[li].n; i++) {
                seg s;
                seg_setup(&s, &j->src[li].paths[i], v, j->sx, j->sy, j->scale);
                if (b >= s.b0 && b <= s.b1) seg_band(&bd, &s);
            }
    }
}

static void band_job(int t, int T, void *arg)
{
    job *j = (job *)arg;
    (void)t;
    (void)T;
    for (;;) {
        int b = __atomic_fetch_add(&j->next, 1, __ATOMIC_RELAXED);
        if (b >= j->n_bands) break;
        run_band(j, b);
    }
}

/* Sets the segments up and bins them into bands (two passes on the pool:
 * count, then fill at per-thread offsets, so each band's list is in segment
 * order). 0: no bins (more than 2^32 - 2 segments or pairs, or out of memory):
 * the bands then scan. */
static int bin(job *j, lm2d_pool *pool)
{
    lm2d_raster_bins *bs = j->bins;
    uint64_t total = 0, run = 0;
    int i, b, t, T = j->threads;
    for (i = 0; i < j->n_src; i++) total += j->src[i].n;
    if (total >= 0xffffffffu) return 0;
    if (bs->limit && lm2d_raster_bins_bytes((size_t)total) > bs->limit) return 0;
    if (!grow(bs->al, (void **)&bs->base, &bs->cap_base, (size_t)j->n_src + 1, sizeof(uint32_t)) ||
        !grow(bs->al, (void **)&bs->start, &bs->cap_start, (size_t)j->n_bands + 1, sizeof(uint32_t)) ||
        !grow(bs->al, (void **)&bs->cursor, &bs->cap_cursor, (size_t)T * (size_t)j->n_bands, sizeof(uint32_t)) ||
        !grow(bs->al, (void **)&bs->segs, &bs->cap_segs, (size_t)total, sizeof(seg)))
        return 0;
    bs->base[0] = 0;
    for (i = 0; i < j->n_src; i++) bs->base[i + 1] = bs->base[i] + (uint32_t)j->src[i].n;
    j->n_seg = (uint32_t)total;
    if (T > 1) lm2d_pool_run(pool, count_job, j);
    else count_job(0, 1, j);
    for (b = 0; b < j->n_bands; b++) {
        bs->start[b] = (uint32_t)run;
        for (t = 0; t < T; t++) {
            uint32_t *c = &bs->cursor[(size_t)t * (size_t)j->n_bands + (size_t)b], n = *c;
            *c = (uint32_t)run;
            run += n;
        }
        if (run >= 0xffffffffu) return 0;
    }
    bs->start[j->n_bands] = (uint32_t)run;
    if (bs->limit && ((size_t)run + run / 4 + 64) * sizeof(uint32_t) + bs->cap_segs * sizeof(seg) > bs->limit) return 0;
    if (!grow(bs->al, (void **)&bs->entries, &bs->cap_entries, (size_t)run, sizeof(uint32_t))) return 0;
    if (T > 1) lm2d_pool_run(pool, fill_job, j);
    else fill_job(0, 1, j);
    return 1;
}

void lm2d_raster_exact(lm2d_raster_bins *bins, lm2d_pool *pool, const lm2d_raster_src *src, int n_src,
                       const lm2d_raster_view *v, float scale, lm2d_raster_op op, int clear, float *img)
{
    job j;
    memset(&j, 0, sizeof j);
    j.src = src;
    j.n_src = n_src;
    j.v = v;
    j.sx = (double)v->width / ((double)v->hi[0] - v->lo[0]);
    j.sy = (double)v->height / ((double)v->hi[1] - v->lo[1]);
    j.scale = scale;
    j.screen = op == LM2D_RASTER_SCREEN;
    j.clear = clear;
    j.img = img;
    j.n_bands = (v->height + LM2D_RASTER_BAND - 1) / LM2D_RASTER_BAND;
    j.threads = pool ? lm2d_pool_size(pool) : 1;
    j.bins = bins;
    if (bins && !bin(&j, pool)) j.bins = NULL;
    j.next = 0;
    if (j.threads > 1) lm2d_pool_run(pool, band_job, &j);
    else band_job(0, 1, &j);
}

void lm2d_raster_exact_add(const lm2d_path *paths, size_t n, const lm2d_raster_view *v, float scale, float *acc)
{
    lm2d_raster_src s;
    s.paths = paths;
    s.n = n;
    lm2d_raster_exact(NULL, NULL, &s, 1, v, scale, LM2D_RASTER_ADD, 0, acc);
}

void lm2d_raster_exact_screen(const lm2d_path *paths, size_t n, const lm2d_raster_view *v, float scale,
                              float *prod)
{
    lm2d_raster_src s;
    s.paths = paths;
    s.n = n;
    lm2d_raster_exact(NULL, NULL, &s, 1, v, scale, LM2D_RASTER_SCREEN, 0, prod);
}
