/* SPDX-License-Identifier: MIT */
/* test_ref_progress.c — snell_ref_params.progress (issue 28 item 7): on a
 * render long enough to report (an exact sphere, FULL, area samples), the
 * callback is called with fractions in (0, 1] that never decrease, at most
 * every ~100 ms before the end, never two at once, and exactly once with 1.0,
 * as the last call; the image is bitwise the one rendered without it; no
 * callback (NULL) is called on a failed render. No GL. */
#define _POSIX_C_SOURCE 200809L
#include "ref/ref_trace.h"
#include "test_util.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_CALLS 4096

typedef struct record {
    int calls, ones, overlap, busy;
    double frac[MAX_CALLS], at_ms[MAX_CALLS];
} record;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static void on_progress(double done, void *user)
{
    record *r = (record *)user;
    if (r->busy) r->overlap++;
    r->busy = 1;
    if (r->calls < MAX_CALLS) {
        r->frac[r->calls] = done;
        r->at_ms[r->calls] = now_ms();
    }
    r->calls++;
    r->ones += done == 1.0;
    r->busy = 0;
}

static void sky(const double d[3], double rgb[3], void *user)
{
    (void)user;
    rgb[0] = 0.5 + 0.5 * d[1];
    rgb[1] = 0.3 + 0.2 * d[0];
    rgb[2] = 0.8 - 0.3 * d[2];
}

int main(void)
{
    const double c[3] = {0.0, 0.0, 0.0};
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_ref_output out;
    static record rec;
    float *with = NULL, *without = NULL;
    int size = 96, samples = 2, attempt, i;
    double t0, elapsed = 0.0, min_gap = 1e30;
    CHECK_OK(snell__ref_create_sphere(NULL, c, 1.0, &ref));
    if (!ref) return test_finish();
    memset(&p, 0, sizeof p);
    p.mode = SNELL_REF_FULL;
    p.env_fn = sky;
    p.camera.distance = 3.0f;
    p.threads = 2;
    memset(&out, 0, sizeof out);
    /* Grow the work until a render takes 0.6 s (at least 5 reporting intervals). */
    for (attempt = 0; attempt < 6; attempt++) {
        free(with);
        with = (float *)malloc((size_t)size * size * 3 * sizeof(float));
        if (!with) break;
        memset(&rec, 0, sizeof rec);
        p.width = p.height = size;
        p.samples = samples;
        p.progress = on_progress;
        p.progress_user = &rec;
        out.rgb = with;
        t0 = now_ms();
        CHECK_OK(snell_ref_render(ref, &p, &out));
        elapsed = now_ms() - t0;
        if (elapsed >= 600.0) break;
        if (samples < SNELL_REF_MAX_SAMPLES && samples < 8) samples *= 2;
        else size *= 2;
    }
    CHECK(with != NULL, "out of memory");
    if (!with) return test_finish();
    printf("render %dx%d, %d x %d samples: %.0f ms, %d progress calls\n", size, size, samples, samples, elapsed,
           rec.calls);
    CHECK(rec.calls >= 1 && rec.calls <= MAX_CALLS, "%d calls", rec.calls);
    CHECK(rec.ones == 1, "1.0 reported %d times", rec.ones);
    CHECK(rec.calls >= 1 && rec.frac[rec.calls - 1] == 1.0, "the last call reported %g, not 1",
          rec.calls ? rec.frac[rec.calls - 1] : -1.0);
    CHECK(rec.overlap == 0, "%d calls overlapped another", rec.overlap);
    for (i = 0; i < rec.calls && i < MAX_CALLS; i++) {
        CHECK(rec.frac[i] > 0.0 && rec.frac[i] <= 1.0, "call %d reported %g", i, rec.frac[i]);
        if (i > 0) CHECK(rec.frac[i] >= rec.frac[i - 1], "call %d went back: %g after %g", i, rec.frac[i], rec.frac[i - 1]);
        if (i > 0 && i < rec.calls - 1 && rec.at_ms[i] - rec.at_ms[i - 1] < min_gap)
            min_gap = rec.at_ms[i] - rec.at_ms[i - 1];
    }
    /* At most every 100 ms before the end: intermediate calls <= elapsed / 100. */
    CHECK(rec.calls - 1 <= (int)(elapsed / 100.0) + 1, "%d intermediate calls in %.0f ms", rec.calls - 1, elapsed);
    if (rec.calls > 2) CHECK(min_gap >= 99.0, "two intermediate calls %.1f ms apart", min_gap);
    /* A render of 0.6 s or more reports before its end. */
    if (elapsed >= 600.0) CHECK(rec.calls >= 3, "only %d calls in %.0f ms", rec.calls, elapsed);
    else printf("note: the render took only %.0f ms; intermediate reports not required\n", elapsed);

    /* The same image without a callback, bitwise. */
    without = (float *)malloc((size_t)size * size * 3 * sizeof(float));
    CHECK(without != NULL, "out of memory");
    if (without) {
        p.progress = NULL;
        p.progress_user = NULL;
        out.rgb = without;
        CHECK_OK(snell_ref_render(ref, &p, &out));
        CHECK(!memcmp(with, without, (size_t)size * size * 3 * sizeof(float)), "the callback changed the image");
    }

    /* A render refused before it starts reports nothing. */
    memset(&rec, 0, sizeof rec);
    p.progress = on_progress;
    p.progress_user = &rec;
    p.threads = -1;
    CHECK(snell_ref_render(ref, &p, &out) == SNELL_E_INVALID_ARG, "threads -1 accepted");
    CHECK(rec.calls == 0, "a refused render reported %d times", rec.calls);

    free(with);
    free(without);
    snell_ref_destroy(ref);
    return test_finish();
}
