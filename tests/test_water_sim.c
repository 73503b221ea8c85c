/* SPDX-License-Identifier: MIT */
/* test_water_sim.c — the CPU water simulation (src/water/water_sim.c): the
 * stability limit against a numerical scan of the stencil's symbol, 100,000
 * steps at the clamped step bounded and volume-conserving, the same run past
 * the limit blowing up (so the limit is where the derivation puts it),
 * damping settling the surface and the settled surface skipping its steps,
 * bitwise determinism, and refused input. */
#include "snell/snell_water.h"
#include "test_util.h"
#include "water/water.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Largest |lambda(a, b)| of the 8-neighbour operator over a 721^2 scan of
 * wave numbers: the derivation says 4 + 4 sqrt 2 at (0, pi). */
static double symbol_max(void)
{
    double best = 0.0, w = 1.0 / sqrt(2.0);
    int i, j, m = 720;
    for (i = 0; i <= m; i++)
        for (j = 0; j <= m; j++) {
            double a = 3.14159265358979323846 * i / m, b = 3.14159265358979323846 * j / m;
            double l = 2.0 * (cos(a) + cos(b) - 2.0) + w * (2.0 * cos(a + b) + 2.0 * cos(a - b) - 4.0);
            if (-l > best) best = -l;
        }
    return best;
}

static float max_dev(const float *h, int n, double mean)
{
    float m = 0.0f;
    int i;
    for (i = 0; i < n * n; i++)
        if (!(fabsf(h[i] - (float)mean) <= m)) m = fabsf(h[i] - (float)mean); /* NaN propagates */
    return m;
}

/* 100,000 undamped steps of courant * limit on a 64^2 grid after one drop:
 * returns the largest deviation seen (sampled every 1000 steps) and the
 * volume drift relative to the drop's volume. */
static float long_run(double courant_factor, double *drift_rel, double *drop_volume)
{
    snell_water *w = NULL;
    snell_water_desc d = {.grid = 64, .damping = -1.0f, .sim = SNELL_WATER_SIM_CPU};
    double v0 = 0.0, v1 = 0.0, vrest = 0.0;
    float worst = 0.0f, dt, k;
    int s;
    if (snell_water_create(NULL, &d, &w) != SNELL_OK) return -1.0f;
    snell_water_volume(w, &vrest);
    snell_water_drop(w, 0.3f, -0.2f, 0.25f, -0.05f);
    snell_water_volume(w, &v0);
    *drop_volume = fabs(v0 - vrest);
    dt = (float)(courant_factor * SNELL_WATER_COURANT_LIMIT * w->dx / w->d.wave_speed);
    k = w->d.wave_speed * w->d.wave_speed * dt / (w->dx * w->dx);
    for (s = 0; s < 100000; s++) {
        snell__water_cpu_step(w->h, w->v, w->n, k, dt, 1.0f);
        if (s % 1000 == 999) {
            float m = max_dev(w->h, w->n, w->mean);
            if (!(m <= worst)) worst = m; /* NaN propagates */
            if (!(m < 1e3f)) break;
        }
    }
    snell_water_volume(w, &v1);
    *drift_rel = fabs(v1 - v0) / *drop_volume;
    snell_water_destroy(w);
    return worst;
}

int main(void)
{
    double lmax = symbol_max(), drift, drop_vol;
    float worst;
    {
        double limit = 2.0 / sqrt(lmax);
        CHECK(fabs(lmax - (4.0 + 4.0 * sqrt(2.0))) < 1e-9, "max |lambda| %.12f, derived 4 + 4 sqrt 2", lmax);
        CHECK(fabs(limit - SNELL_WATER_COURANT_LIMIT) < 1e-9, "limit %.12f vs SNELL_WATER_COURANT_LIMIT %.12f", limit,
              SNELL_WATER_COURANT_LIMIT);
    }
    /* At the clamp (0.99 of the limit), no damping: bounded, volume kept. */
    worst = long_run(SNELL_WATER_COURANT_SAFETY, &drift, &drop_vol);
    printf("at %.2f of the limit: max |h - mean| over 100000 steps %.6g (drop amplitude 0.05), volume drift %.3g of "
           "the drop's %.4g\n",
           SNELL_WATER_COURANT_SAFETY, worst, drift, drop_vol);
    CHECK(worst > 0.0f && worst <= 0.05f, "deviation %g: bounded by the drop's amplitude 0.05", worst);
    /* Measured 7.3e-4 of the drop's volume (2e-6 world units^3, 6e-7 of the
     * water's): float rounding leaves sum v a random walk that h integrates.
     * Bound 5e-3 of the drop's volume, headroom for other compilers. */
    CHECK(drift < 5e-3, "volume drift %g of the drop's volume (bound 5e-3)", drift);
    /* Just past the limit the highest mode grows: the derivation's limit is the real one. */
    worst = long_run(1.02, &drift, &drop_vol);
    printf("at 1.02 of the limit: max |h - mean| %.6g\n", worst);
    CHECK(!(worst < 1e3f), "1.02x the limit should blow up (max deviation %g)", worst);

    /* The API clamps dt; damping settles the surface; a settled one skips. */
    {
        snell_water *w = NULL, *w2 = NULL;
        snell_water_desc d = {.grid = 64, .damping = 3.0f, .sim = SNELL_WATER_SIM_CPU};
        snell_water_stats st;
        float *h1 = (float *)malloc(64 * 64 * sizeof(float)), *h2 = (float *)malloc(64 * 64 * sizeof(float));
        int calls = 0;
        CHECK_OK(snell_water_create(NULL, &d, &w));
        CHECK_OK(snell_water_create(NULL, &d, &w2));
        CHECK_OK(snell_water_step(w, 0.0f, 1, &st));
        CHECK(st.skipped_settled == 1 && st.steps_run == 0, "a new flat surface is settled: skipped %d", st.skipped_settled);
        CHECK_OK(snell_water_drop(w, 0.0f, 0.0f, 0.2f, 0.04f));
        CHECK_OK(snell_water_drop(w2, 0.0f, 0.0f, 0.2f, 0.04f));
        CHECK_OK(snell_water_step(w, 10.0f, 1, &st));
        CHECK(st.dt_clamped == 1 && fabsf(st.dt - snell_water_dt_limit(w)) < 1e-9f, "dt %g clamped to %g", st.dt,
              snell_water_dt_limit(w));
        CHECK(st.steps_run == 1 && !st.settled, "one step run, not settled");
        do {
            CHECK_OK(snell_water_step(w, 0.0f, 60, &st));
            calls++;
        } while (!st.settled && calls < 2000);
        printf("settled after %d calls of 60 steps at damping 3/s (max deviation %g)\n", calls, st.max_deviation);
        CHECK(st.settled && st.max_deviation < d.width * 1e-5f + 2e-5f, "settles under damping: %d", st.settled);
        CHECK_OK(snell_water_step(w, 0.0f, 60, &st));
        CHECK(st.skipped_settled == 1 && st.steps_run == 0, "settled and undisturbed: skipped");
        CHECK_OK(snell_water_drop(w, 0.5f, 0.5f, 0.1f, -0.01f));
        CHECK_OK(snell_water_step(w, 0.0f, 1, &st));
        CHECK(st.steps_run == 1, "a drop wakes it");
        /* Determinism: the same calls, the same bits. */
        {
            snell_water *a = NULL, *b = NULL;
            int i;
            snell_water_create(NULL, &d, &a);
            snell_water_create(NULL, &d, &b);
            snell_water_drop(a, 0.1f, 0.2f, 0.3f, 0.02f);
            snell_water_drop(b, 0.1f, 0.2f, 0.3f, 0.02f);
            for (i = 0; i < 5; i++) {
                snell_water_step(a, 0.0f, 100, NULL);
                snell_water_step(b, 0.0f, 100, NULL);
            }
            snell_water_read_heights(a, h1);
            snell_water_read_heights(b, h2);
            CHECK(memcmp(h1, h2, 64 * 64 * sizeof(float)) == 0, "two runs differ");
            snell_water_destroy(a);
            snell_water_destroy(b);
        }
        /* Walls reflect: a drop next to the x = -w/2 wall sends a wave back. */
        {
            snell_water *a = NULL;
            int i, j;
            float far_side = 0.0f;
            snell_water_create(NULL, &(snell_water_desc){.grid = 64, .damping = -1.0f, .sim = SNELL_WATER_SIM_CPU}, &a);
            snell_water_drop(a, -0.9f, 0.0f, 0.1f, 0.05f);
            /* c = 0.6: the front reaches the wall at once and is back past x = -0.3 after ~1.5 s */
            for (i = 0; i < 90; i++) snell_water_step(a, 0.0f, 2, NULL);
            snell_water_read_heights(a, h1);
            for (j = 0; j < 64; j++)
                for (i = 0; i < 8; i++) far_side = fmaxf(far_side, fabsf(h1[j * 64 + i]));
            CHECK(far_side > 1e-4f, "energy stays next to the wall it reflects from: %g", far_side);
            snell_water_destroy(a);
        }
        snell_water_destroy(w);
        snell_water_destroy(w2);
        free(h1);
        free(h2);
    }
    /* Refused input. */
    {
        snell_water *w = NULL;
        CHECK(snell_water_create(NULL, &(snell_water_desc){.grid = 63}, &w) == SNELL_E_INVALID_ARG, "grid 63");
        CHECK(snell_water_create(NULL, &(snell_water_desc){.grid = 513}, &w) == SNELL_E_INVALID_ARG, "grid 513");
        CHECK(snell_water_create(NULL, &(snell_water_desc){.wave_speed = NAN}, &w) == SNELL_E_INVALID_ARG, "NaN speed");
        CHECK(snell_water_create(NULL, &(snell_water_desc){.sim = SNELL_WATER_SIM_GPU}, &w) == SNELL_E_INVALID_ARG,
              "GPU without a context");
        CHECK(w == NULL, "no water on failure");
        CHECK_OK(snell_water_create(NULL, &(snell_water_desc){.grid = 64}, &w));
        CHECK(snell_water_drop(w, 5.0f, 0.0f, 0.1f, 0.01f) == SNELL_E_INVALID_ARG, "drop outside");
        CHECK(snell_water_drop(w, 0.0f, 0.0f, 0.001f, 0.01f) == SNELL_E_INVALID_ARG, "radius below a node");
        CHECK(snell_water_drop(w, 0.0f, 0.0f, 0.1f, 1.0f) == SNELL_E_INVALID_ARG, "amplitude beyond half the depth");
        CHECK(snell_water_step(w, 0.0f, -1, NULL) == SNELL_E_INVALID_ARG, "negative steps");
        printf("%s\n", snell_last_error(NULL));
        snell_water_destroy(w);
    }
    return test_finish();
}
