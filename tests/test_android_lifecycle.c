/* SPDX-License-Identifier: MIT */
/* test_android_lifecycle — ports/android/lifecycle.c, the rules for what the
 * Android port makes and destroys on each activity event. (1) Scenarios with
 * the actions the rules say, written out: start, pause/resume keeping the
 * context, the window going while paused, a context loss with and without a
 * window, destroy with the window still there and events after it. (2) A
 * model check: 200,000 random event sequences executed against a simulated
 * EGL/snell world that counts what exists, checking after every step that
 * nothing is made twice or destroyed while absent, that a surface exists
 * exactly while a window does, that a context's GL objects are made once per
 * context and only with a current surface, that nothing exists after destroy,
 * and that a frame is drawn exactly when resumed with a surface. */
#include "test_util.h"
#include "lifecycle.h"

#include <stdint.h>
#include <stdio.h>

#define A_CTX LIFECYCLE_CREATE_CONTEXT
#define A_SURF LIFECYCLE_CREATE_SURFACE
#define A_GL LIFECYCLE_CREATE_GL_OBJECTS
#define D_SURF LIFECYCLE_DESTROY_SURFACE
#define D_GL LIFECYCLE_DESTROY_GL_OBJECTS
#define D_CTX LIFECYCLE_DESTROY_CONTEXT

typedef struct step {
    lifecycle_event ev;
    unsigned want;  /* actions */
    int render;     /* lifecycle_should_render after it */
} step;

static void scenario(const char *name, const step *steps, int n, unsigned want_generation)
{
    lifecycle_state s;
    int i;
    lifecycle_init(&s);
    for (i = 0; i < n; i++) {
        unsigned got = lifecycle_step(&s, steps[i].ev);
        CHECK(got == steps[i].want, "%s, step %d (%s): actions 0x%x, want 0x%x", name, i,
              lifecycle_event_str(steps[i].ev), got, steps[i].want);
        CHECK(lifecycle_should_render(&s) == steps[i].render, "%s, step %d (%s): render %d", name, i,
              lifecycle_event_str(steps[i].ev), lifecycle_should_render(&s));
    }
    CHECK(s.generation == want_generation, "%s: %u contexts made, want %u", name, s.generation, want_generation);
}

static void scenarios(void)
{
    static const step first_start[] = {
        {LIFECYCLE_START, 0, 0},
        {LIFECYCLE_RESUME, 0, 0},
        {LIFECYCLE_WINDOW_CREATED, A_CTX | A_SURF | A_GL, 1},
        {LIFECYCLE_PAUSE, 0, 0},    /* paused: nothing destroyed */
        {LIFECYCLE_RESUME, 0, 1},
    };
    static const step window_gone_while_paused[] = {
        {LIFECYCLE_START, 0, 0},
        {LIFECYCLE_WINDOW_CREATED, A_CTX | A_SURF | A_GL, 0}, /* window before resume */
        {LIFECYCLE_RESUME, 0, 1},
        {LIFECYCLE_PAUSE, 0, 0},
        {LIFECYCLE_STOP, 0, 0},
        {LIFECYCLE_WINDOW_DESTROYED, D_SURF, 0},      /* context and GL objects kept */
        {LIFECYCLE_START, 0, 0},
        {LIFECYCLE_RESUME, 0, 0},                     /* no surface yet */
        {LIFECYCLE_WINDOW_CREATED, A_SURF, 1},        /* only the surface again */
        {LIFECYCLE_WINDOW_DESTROYED, D_SURF, 0},      /* while resumed (e.g. multi-window) */
        {LIFECYCLE_WINDOW_CREATED, A_SURF, 1},
    };
    static const step context_lost[] = {
        {LIFECYCLE_RESUME, 0, 0},
        {LIFECYCLE_WINDOW_CREATED, A_CTX | A_SURF | A_GL, 1},
        {LIFECYCLE_CONTEXT_LOST, D_SURF | D_GL | D_CTX | A_CTX | A_SURF | A_GL, 1}, /* all again, at once */
        {LIFECYCLE_WINDOW_DESTROYED, D_SURF, 0},
        {LIFECYCLE_CONTEXT_LOST, D_GL | D_CTX, 0},    /* no window: made when one comes */
        {LIFECYCLE_CONTEXT_LOST, 0, 0},               /* nothing left to lose */
        {LIFECYCLE_WINDOW_CREATED, A_CTX | A_SURF | A_GL, 1},
    };
    static const step destroy_with_window[] = {
        {LIFECYCLE_RESUME, 0, 0},
        {LIFECYCLE_WINDOW_CREATED, A_CTX | A_SURF | A_GL, 1},
        {LIFECYCLE_DESTROY, D_SURF | D_GL | D_CTX, 0},
        {LIFECYCLE_WINDOW_DESTROYED, 0, 0},           /* after destroy: already gone */
        {LIFECYCLE_WINDOW_CREATED, 0, 0},             /* nothing is made again */
        {LIFECYCLE_RESUME, 0, 0},
        {LIFECYCLE_CONTEXT_LOST, 0, 0},
        {LIFECYCLE_DESTROY, 0, 0},
    };
    static const step destroy_without_window[] = {
        {LIFECYCLE_WINDOW_CREATED, A_CTX | A_SURF | A_GL, 0},
        {LIFECYCLE_WINDOW_DESTROYED, D_SURF, 0},
        {LIFECYCLE_DESTROY, D_GL | D_CTX, 0},
    };
    static const step window_replaced[] = {
        {LIFECYCLE_RESUME, 0, 0},
        {LIFECYCLE_WINDOW_CREATED, A_CTX | A_SURF | A_GL, 1},
        {LIFECYCLE_WINDOW_CREATED, D_SURF | A_SURF, 1}, /* a new window, no destroy of the old one */
    };
    static const step never_a_window[] = {
        {LIFECYCLE_START, 0, 0}, {LIFECYCLE_RESUME, 0, 0}, {LIFECYCLE_CONTEXT_LOST, 0, 0},
        {LIFECYCLE_PAUSE, 0, 0}, {LIFECYCLE_DESTROY, 0, 0},
    };
#define RUN(name, steps, gen) scenario(name, steps, (int)(sizeof steps / sizeof steps[0]), gen)
    RUN("first start", first_start, 1);
    RUN("window gone while paused", window_gone_while_paused, 1);
    RUN("context lost", context_lost, 3);
    RUN("destroy with window", destroy_with_window, 1);
    RUN("destroy without window", destroy_without_window, 1);
    RUN("window replaced", window_replaced, 1);
    RUN("never a window", never_a_window, 0);
#undef RUN
    CHECK(lifecycle_step(&(lifecycle_state){0}, (lifecycle_event)99) == 0, "unknown event");
    CHECK(lifecycle_event_str((lifecycle_event)99) != NULL, "unknown event name");
}

/* ---- model check ----------------------------------------------------------- */

/* What exists, as the port's executor would see it (independent of lifecycle_state). */
typedef struct world {
    int window, resumed, destroyed;
    int context, surface, current;  /* current: the context is current with the window surface */
    int gl_objects;
    unsigned gl_objects_of;         /* the context number the GL objects were made in */
    unsigned contexts;              /* contexts made so far */
} world;

static long g_violations; /* invariant violations over all sequences; the first 10 are printed */

static void expect(world *w, int cond, const char *what, lifecycle_event ev, int seq, int i)
{
    (void)w;
    if (cond) return;
    if (g_violations++ < 10) printf("violation: sequence %d, step %d (%s): %s\n", seq, i, lifecycle_event_str(ev), what);
}

static void execute(world *w, unsigned act, lifecycle_event ev, int seq, int i)
{
    /* in the order lifecycle.h gives */
    if (act & D_SURF) {
        expect(w, w->surface, "surface destroyed while absent", ev, seq, i);
        w->surface = w->current = 0;
    }
    if (act & D_GL) {
        expect(w, w->gl_objects, "GL objects destroyed while absent", ev, seq, i);
        w->gl_objects = 0;
    }
    if (act & D_CTX) {
        expect(w, w->context, "context destroyed while absent", ev, seq, i);
        expect(w, !w->gl_objects, "context destroyed before its GL objects", ev, seq, i);
        w->context = 0;
    }
    if (act & A_CTX) {
        expect(w, !w->context, "a second context", ev, seq, i);
        w->context = 1;
        w->contexts++;
    }
    if (act & A_SURF) {
        expect(w, !w->surface, "a second surface", ev, seq, i);
        expect(w, w->window && w->context, "surface without a window or context", ev, seq, i);
        w->surface = w->current = 1;
    }
    if (act & A_GL) {
        expect(w, !w->gl_objects, "GL objects made twice", ev, seq, i);
        expect(w, w->current, "GL objects made with no current surface", ev, seq, i);
        expect(w, w->gl_objects_of != w->contexts, "GL objects made twice in one context", ev, seq, i);
        w->gl_objects = 1;
        w->gl_objects_of = w->contexts;
    }
}

static void model_check(void)
{
    uint32_t rng = 12345;
    int seq, i, renders = 0, losses_recovered = 0;
    for (seq = 0; seq < 200000; seq++) {
        lifecycle_state s;
        world w = {0};
        lifecycle_init(&s);
        for (i = 0; i < 24; i++) {
            lifecycle_event ev;
            unsigned act;
            int was_lost_with_window;
            rng = rng * 1664525u + 1013904223u;
            ev = (lifecycle_event)((rng >> 16) % LIFECYCLE_EVENT_COUNT);
            /* what the platform itself does on the event, before the port acts */
            if (!w.destroyed) {
                if (ev == LIFECYCLE_WINDOW_CREATED) w.window = 1;
                if (ev == LIFECYCLE_WINDOW_DESTROYED) w.window = 0;
                if (ev == LIFECYCLE_RESUME) w.resumed = 1;
                if (ev == LIFECYCLE_PAUSE) w.resumed = 0;
            }
            was_lost_with_window = ev == LIFECYCLE_CONTEXT_LOST && w.context && w.window && !w.destroyed;
            act = lifecycle_step(&s, ev);
            execute(&w, act, ev, seq, i);
            if (ev == LIFECYCLE_DESTROY) w.destroyed = 1;
            expect(&w, !w.destroyed || (!w.context && !w.surface && !w.gl_objects), "alive after destroy", ev, seq,
                   i);
            expect(&w, w.destroyed || w.surface == w.window, "surface does not follow the window", ev, seq, i);
            expect(&w, !w.surface || w.gl_objects, "a surface without the scene's GL objects", ev, seq, i);
            expect(&w, !w.gl_objects || (w.context && w.gl_objects_of == w.contexts),
                   "GL objects of another context", ev, seq, i);
            expect(&w, lifecycle_should_render(&s) == (w.resumed && w.surface && !w.destroyed),
                   "should_render differs from resumed-with-surface", ev, seq, i);
            if (was_lost_with_window) {
                expect(&w, w.surface && w.gl_objects, "a loss with a window left nothing to draw with", ev, seq, i);
                losses_recovered++;
            }
            renders += lifecycle_should_render(&s);
        }
    }
    printf("model check: 200000 sequences of 24 events, %d frames allowed, %d context losses recovered\n", renders,
           losses_recovered);
    CHECK(g_violations == 0, "%ld invariant violations in the model check", g_violations);
    CHECK(renders > 0 && losses_recovered > 0, "the random sequences reach drawing and recovery");
}

int main(void)
{
    scenarios();
    model_check();
    return test_finish();
}
