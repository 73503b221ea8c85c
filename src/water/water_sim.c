/* SPDX-License-Identifier: MIT */
/* water_sim.c — the water surface object and its CPU simulation (Dachsbacher
 * 2002, "Berechnung der Wasseroberflaeche"): heights on a grid of nodes, per node
 * a force from the height differences to its eight neighbours (the diagonal ones
 * times 1/sqrt 2), integrated into velocity and then into height (symplectic
 * Euler), explicit in dt, c and dx, with damping and reflecting walls.
 * Stable for c dt / dx <= 1 / sqrt(1 + sqrt 2) (SNELL_WATER_COURANT_LIMIT, with
 * walls too), volume conserved; the von Neumann analysis:
 * docs/ARCHITECTURE.md, "Design notes by file". */
#include "water/water.h"
#include "core/ctx.h"
#include "core/gl.h"

#include <math.h>
#include <string.h>

static int finite_nonneg(float v)
{
    return isfinite(v) && v >= 0.0f;
}

static snell_status resolve(const snell_ctx *ctx, const snell_water_desc *in, snell_water_desc *d)
{
    int k;
    *d = in ? *in : (snell_water_desc){0};
    if (d->grid == 0) d->grid = 128;
    if (d->grid < SNELL_WATER_MIN_GRID || d->grid > SNELL_WATER_MAX_GRID)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "water: grid %d outside %d..%d", d->grid, SNELL_WATER_MIN_GRID,
                           SNELL_WATER_MAX_GRID);
#define CHECK(field, lo, hi)                                                                                      \
    if (!finite_nonneg(d->field) || (d->field != 0.0f && (d->field < (lo) || d->field > (hi))))                  \
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "water: " #field " %g: 0 (default) or %g..%g", (double)d->field, \
                           (double)(lo), (double)(hi));
    CHECK(width, 1e-3, 1e3)
    CHECK(depth, 1e-4, 1e3)
    CHECK(rim, 0.0, 1e3)
    CHECK(wave_speed, 1e-4, 1e4)
    CHECK(ior, 1.0, 4.0)
    CHECK(attenuation_distance, 1e-4, 1e6)
    CHECK(tile_size, 1e-4, 1e3)
    CHECK(settle_threshold, 1e-9, 1.0)
#undef CHECK
    if (!isfinite(d->damping) || d->damping > 1e3)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "water: damping %g: < 0 (none), 0 (default) or up to 1000 per second",
                           (double)d->damping);
    for (k = 0; k < 3; k++)
        if (!finite_nonneg(d->attenuation_color[k]) || d->attenuation_color[k] > 1.0f)
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "water: attenuation_color[%d] %g outside 0..1", k,
                               (double)d->attenuation_color[k]);
    if (d->light_map != 0 && (d->light_map < 16 || d->light_map > 2048))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "water: light_map %d outside 16..2048 (0 = 256)", d->light_map);
    if ((unsigned)d->sim > SNELL_WATER_SIM_GPU)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "water: sim %d unknown", (int)d->sim);
    if (d->width == 0.0f) d->width = 2.0f;
    if (d->depth == 0.0f) d->depth = 0.8f;
    if (d->rim == 0.0f) d->rim = 0.1f * d->depth;
    if (d->wave_speed == 0.0f) d->wave_speed = 0.6f;
    if (d->damping == 0.0f) d->damping = 0.4f;
    if (d->damping < 0.0f) d->damping = 0.0f;
    if (d->ior == 0.0f) d->ior = 1.333f;
    if (d->attenuation_color[0] == 0.0f && d->attenuation_color[1] == 0.0f && d->attenuation_color[2] == 0.0f) {
        d->attenuation_color[0] = 0.55f;
        d->attenuation_color[1] = 0.80f;
        d->attenuation_color[2] = 0.85f;
    }
    if (d->attenuation_distance == 0.0f) d->attenuation_distance = 1.5f;
    if (d->tile_size == 0.0f) d->tile_size = d->width / 8.0f;
    if (d->settle_threshold == 0.0f) d->settle_threshold = 1e-5f * d->width;
    /* AUTO: on llvmpipe a GPU step costs many CPU steps (bench/BENCHMARKS.md
     * "Water"): on software GL the CPU simulates. */
    if (d->sim == SNELL_WATER_SIM_AUTO)
        d->sim = ctx && !snell__software_rasteriser(snell_ctx_gl_renderer(ctx)) ? SNELL_WATER_SIM_GPU
                                                                                : SNELL_WATER_SIM_CPU;
    if (d->sim == SNELL_WATER_SIM_GPU && !ctx)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "water: the GPU simulation needs a context");
    return SNELL_OK;
}

snell_status snell_water_create(snell_ctx *ctx, const snell_water_desc *desc, snell_water **out)
{
    snell_water *w;
    snell_status st;
    snell_water_desc d;
    size_t nodes;
    int k;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_water_create: out is NULL");
    *out = NULL;
    if ((st = resolve(ctx, desc, &d)) != SNELL_OK) return st;
    if (ctx && (st = snell__ctx_check_current(ctx, "snell_water_create")) != SNELL_OK) return st;
    w = (snell_water *)snell__calloc(snell__ctx_alloc(ctx), 1, sizeof *w);
    if (!w) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for the water");
    w->alloc = *snell__ctx_alloc(ctx);
    w->ctx = ctx;
    w->d = d;
    w->n = d.grid;
    w->dx = d.width / (float)(d.grid - 1);
    w->dt_limit = (float)(SNELL_WATER_COURANT_SAFETY * SNELL_WATER_COURANT_LIMIT * w->dx / d.wave_speed);
    for (k = 0; k < 3; k++)
        w->sigma[k] = -logf(d.attenuation_color[k] > 1e-6f ? d.attenuation_color[k] : 1e-6f) / d.attenuation_distance;
    nodes = (size_t)w->n * (size_t)w->n;
    w->h = (float *)snell__calloc(&w->alloc, nodes, sizeof(float));
    w->v = (float *)snell__calloc(&w->alloc, nodes, sizeof(float));
    w->settled = 1;
    if (!w->h || !w->v) {
        snell_water_destroy(w);
        return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for a %dx%d water grid", w->n, w->n);
    }
    if (ctx) snell__ctx_retain(ctx);
    if (d.sim == SNELL_WATER_SIM_GPU && (st = snell__water_gpu_create(w)) != SNELL_OK) {
        snell_water_destroy(w);
        return st;
    }
    *out = w;
    return SNELL_OK;
}

void snell_water_destroy(snell_water *w)
{
    snell_ctx *ctx;
    if (!w) return;
    ctx = w->ctx;
    if (ctx) {
        snell__gl_scope sc;
        snell__gl_scope_enter(ctx, &sc);
        snell__water_gpu_destroy(w);
        snell__water_draw_release(w);
        snell__gl_scope_leave(&sc);
    }
    snell__free(&w->alloc, w->h);
    snell__free(&w->alloc, w->v);
    snell__free(&w->alloc, w->reduce_px);
    snell__free(&w->alloc, w);
    if (ctx) snell__ctx_release(ctx);
}

void snell_water_get_desc(const snell_water *w, snell_water_desc *out)
{
    if (w && out) *out = w->d;
}

float snell_water_dx(const snell_water *w)
{
    return w ? w->dx : 0.0f;
}

float snell_water_dt_limit(const snell_water *w)
{
    return w ? w->dt_limit : 0.0f;
}

float snell__water_bell(float r, float radius, float amplitude)
{
    if (!(r < radius)) return 0.0f;
    return amplitude * 0.5f * (1.0f + cosf(3.14159265f * r / radius));
}

snell_status snell_water_drop(snell_water *w, float x, float z, float radius, float amplitude)
{
    float half;
    if (!w) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_water_drop: water is NULL");
    half = 0.5f * w->d.width;
    if (!isfinite(x) || !isfinite(z) || fabsf(x) > half || fabsf(z) > half)
        return snell__fail(w->ctx, SNELL_E_INVALID_ARG, "snell_water_drop: point (%g, %g) outside the container |x|, |z| <= %g",
                           (double)x, (double)z, (double)half);
    if (!isfinite(radius) || radius < w->dx || radius > w->d.width)
        return snell__fail(w->ctx, SNELL_E_INVALID_ARG, "snell_water_drop: radius %g outside %g (one node) .. %g",
                           (double)radius, (double)w->dx, (double)w->d.width);
    if (!isfinite(amplitude) || fabsf(amplitude) > 0.5f * w->d.depth)
        return snell__fail(w->ctx, SNELL_E_INVALID_ARG, "snell_water_drop: amplitude %g outside +-%g (half the depth)",
                           (double)amplitude, 0.5 * w->d.depth);
    if (w->d.sim == SNELL_WATER_SIM_GPU) {
        snell_status st = snell__ctx_check_current(w->ctx, "snell_water_drop");
        if (st != SNELL_OK) return st;
    }
    {
        /* The added volume is the same sum on both simulations (to rounding). */
        double added = 0.0;
        int i, j, i0, i1, j0, j1;
        /* only the nodes within the bell's square (the profile is 0 beyond radius) */
        i0 = (int)floorf((x - radius + half) / w->dx);
        i1 = (int)ceilf((x + radius + half) / w->dx);
        j0 = (int)floorf((z - radius + half) / w->dx);
        j1 = (int)ceilf((z + radius + half) / w->dx);
        i0 = i0 < 0 ? 0 : i0;
        j0 = j0 < 0 ? 0 : j0;
        i1 = i1 > w->n - 1 ? w->n - 1 : i1;
        j1 = j1 > w->n - 1 ? w->n - 1 : j1;
        for (j = j0; j <= j1; j++)
            for (i = i0; i <= i1; i++) {
                float px = -half + (float)i * w->dx, pz = -half + (float)j * w->dx;
                float b = snell__water_bell(sqrtf((px - x) * (px - x) + (pz - z) * (pz - z)), radius, amplitude);
                if (w->d.sim == SNELL_WATER_SIM_CPU) w->h[(size_t)j * w->n + i] += b;
                added += b;
            }
        w->mean += added / ((double)w->n * w->n);
    }
    if (w->d.sim == SNELL_WATER_SIM_GPU) {
        snell_status st = snell__water_gpu_drop(w, x, z, radius, amplitude);
        if (st != SNELL_OK) return st;
    }
    w->settled = 0;
    w->cpu_dev_known = 0; /* a settle check from before the drop says nothing now */
    w->version++;
    return SNELL_OK;
}

/* The step as the GPU's water_step.frag computes it, term for term in the
 * same order (the CPU/GPU agreement test relies on it). Velocities of the
 * whole grid first (from the old heights), then the heights. */
void snell__water_cpu_step(float *h, float *v, int n, float k, float dt, float damp)
{
    int i, j;
    for (j = 0; j < n; j++) {
        const float *row = h + (size_t)j * n;
        const float *up = j > 0 ? row - n : NULL, *dn = j + 1 < n ? row + n : NULL;
        for (i = 0; i < n; i++) {
            float c = row[i], fa = 0.0f, fd = 0.0f;
            int l = i > 0, r = i + 1 < n;
            if (l) fa += row[i - 1] - c;
            if (r) fa += row[i + 1] - c;
            if (up) fa += up[i] - c;
            if (dn) fa += dn[i] - c;
            if (up && l) fd += up[i - 1] - c;
            if (up && r) fd += up[i + 1] - c;
            if (dn && l) fd += dn[i - 1] - c;
            if (dn && r) fd += dn[i + 1] - c;
            v[(size_t)j * n + i] = (v[(size_t)j * n + i] + k * (fa + SNELL__WATER_INV_SQRT2 * fd)) * damp;
        }
    }
    for (i = 0; i < n * n; i++) h[i] = h[i] + dt * v[i];
}

void snell__water_cpu_deviation(const snell_water *w, float *dev_h, float *dev_v)
{
    float mh = 0.0f, mv = 0.0f, mean = (float)w->mean;
    size_t i, nodes = (size_t)w->n * (size_t)w->n;
    for (i = 0; i < nodes; i++) {
        float a = fabsf(w->h[i] - mean), b = fabsf(w->v[i]);
        if (a > mh) mh = a;
        if (b > mv) mv = b;
    }
    *dev_h = mh;
    *dev_v = mv * w->dx / w->d.wave_speed;
}

snell_status snell_water_step(snell_water *w, float dt, int steps, snell_water_stats *stats)
{
    snell_water_stats s;
    snell_status st = SNELL_OK;
    double t0 = snell__now_ms();
    float k, damp, dev_h = 0.0f, dev_v = 0.0f;
    int n, known = 1;
    memset(&s, 0, sizeof s);
    if (!w) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_water_step: water is NULL");
    if (!isfinite(dt) || steps < 0 || steps > 100000)
        return snell__fail(w->ctx, SNELL_E_INVALID_ARG, "snell_water_step: dt %g not finite or steps %d outside 0..100000",
                           (double)dt, steps);
    if (w->d.sim == SNELL_WATER_SIM_GPU && (st = snell__ctx_check_current(w->ctx, "snell_water_step")) != SNELL_OK)
        return st;
    if (dt <= 0.0f) dt = 1.0f / 60.0f;
    if (dt > w->dt_limit) {
        dt = w->dt_limit;
        s.dt_clamped = 1;
    }
    s.dt = dt;
    n = w->n;
    k = (float)((double)w->d.wave_speed * w->d.wave_speed * dt / ((double)w->dx * w->dx));
    damp = (float)exp(-(double)w->d.damping * dt);
    if (w->settled) {
        s.skipped_settled = steps > 0;
        s.settled = 1;
    } else if (steps > 0) {
        int i;
        if (w->d.sim == SNELL_WATER_SIM_CPU) {
            /* The GPU's rule, so the twins settle on the same call: judged on
             * the state after the previous call (none after a drop). */
            known = w->cpu_dev_known;
            dev_h = w->cpu_dev[0];
            dev_v = w->cpu_dev[1];
            for (i = 0; i < steps; i++) snell__water_cpu_step(w->h, w->v, n, k, dt, damp);
            snell__water_cpu_deviation(w, &w->cpu_dev[0], &w->cpu_dev[1]);
            w->cpu_dev_known = 1;
        } else {
            st = snell__water_gpu_step(w, k, dt, damp, steps);
            if (st == SNELL_OK) st = snell__water_gpu_deviation(w, &dev_h, &dev_v, &known);
        }
        s.steps_run = steps;
        s.max_deviation = known ? dev_h : -1.0f;
        w->settled = st == SNELL_OK && known && dev_h < w->d.settle_threshold && dev_v < w->d.settle_threshold;
        s.settled = w->settled;
        w->version++;
    }
    s.ms = snell__now_ms() - t0;
    if (stats) *stats = s;
    return st;
}

snell_status snell_water_read_heights(snell_water *w, float *heights)
{
    snell_status st;
    if (!w || !heights) return snell__fail(w ? w->ctx : NULL, SNELL_E_INVALID_ARG, "snell_water_read_heights: NULL argument");
    if (w->d.sim == SNELL_WATER_SIM_GPU) {
        if ((st = snell__ctx_check_current(w->ctx, "snell_water_read_heights")) != SNELL_OK) return st;
        if ((st = snell__water_gpu_read(w, w->h, NULL)) != SNELL_OK) return st;
    }
    memcpy(heights, w->h, (size_t)w->n * (size_t)w->n * sizeof(float));
    return SNELL_OK;
}

snell_status snell_water_volume(snell_water *w, double *volume)
{
    snell_status st;
    double sum = 0.0;
    size_t i, nodes;
    if (!w || !volume) return snell__fail(w ? w->ctx : NULL, SNELL_E_INVALID_ARG, "snell_water_volume: NULL argument");
    if (w->d.sim == SNELL_WATER_SIM_GPU) {
        if ((st = snell__ctx_check_current(w->ctx, "snell_water_volume")) != SNELL_OK) return st;
        if ((st = snell__water_gpu_read(w, w->h, NULL)) != SNELL_OK) return st;
    }
    nodes = (size_t)w->n * (size_t)w->n;
    for (i = 0; i < nodes; i++) sum += w->h[i];
    *volume = ((double)w->d.depth + sum / (double)nodes) * (double)w->d.width * w->d.width;
    return SNELL_OK;
}

/* Tiles (seed: "Wassercontainer", the walls and floor of one refraction
 * texture; here procedural): squares of side tile_size from the container's
 * corner, two colours in a checker, grout lines 5% of a tile wide; walls
 * 0.8 as bright as the floor. GLSL twin: shaders_es/common/water_tiles.glsl. */
void snell__water_tile(const snell_water_desc *d, int face, const double p[3], double rgb[3])
{
    static const double light[3] = {0.92, 0.90, 0.82}, dark[3] = {0.20, 0.42, 0.62}, grout[3] = {0.30, 0.30, 0.32};
    double half = 0.5 * d->width, u, v, fu, fv, shade = face == 0 ? 1.0 : 0.8;
    const double *c;
    int k;
    if (face == 0) {
        u = p[0] + half;
        v = p[2] + half;
    } else if (face <= 2) {
        u = p[2] + half;
        v = p[1] + d->depth;
    } else {
        u = p[0] + half;
        v = p[1] + d->depth;
    }
    u /= d->tile_size;
    v /= d->tile_size;
    fu = u - floor(u);
    fv = v - floor(v);
    if (fu < 0.05 || fv < 0.05 || fu > 0.95 || fv > 0.95) c = grout;
    else c = fmod(floor(u) + floor(v), 2.0) != 0.0 ? dark : light;
    for (k = 0; k < 3; k++) rgb[k] = c[k] * shade;
}

void snell_water_tile_color(const snell_water *w, int face, const double p[3], double rgb[3])
{
    if (!w || !p || face < 0 || face > 4) {
        if (rgb) rgb[0] = rgb[1] = rgb[2] = 0.0;
        return;
    }
    snell__water_tile(&w->d, face, p, rgb);
}
