/* SPDX-License-Identifier: MIT */
/* budget_stage.c — the budget stage: measures the last frame (the GPU's
 * timer query where there is one, else a fence),
 * gives every AUTO glass object its ladder and the controller's rung
 * (budget.c), and writes the rung into the object's resolved material so
 * that the glass stage draws it as an explicit method. */
#include "render/stages.h"
#include "render/budget.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "mesh/mesh.h"
#include "render/gbuffer.h"

#include <math.h>
#include <string.h>

static const char *const g_class_names[SNELL__BUDGET_CLASSES] = {
    "a convex", "a closed concave (cubemap-served)", "a closed concave (deep)", "an open or non-manifold"};

/* The stage's state: the controller and what measures the frames. */
typedef struct budget_state {
    snell_ctx *ctx;                            /* its renderer's */
    snell__budget ctl;                         /* AUTO by budget's controller (budget.h) */
    snell__budget_object obj[SNELL_MAX_GLASS]; /* this frame's ladders */
    char note[SNELL_MAX_GLASS][192];           /* each object's rung and why (snell__object.budget_note) */
    void *fence;                               /* GLsync after the last budget frame, NULL none */
    double start_ms, done_ms;                  /* that frame's start; its completion seen (-1 not yet) */
    double cpu_ms;                             /* that frame's time inside snell_render */
    unsigned query;                            /* its GL_TIME_ELAPSED_EXT query (0: none made yet) */
    int timer;                                 /* EXT_disjoint_timer_query: 0 not probed, 1 yes, -1 no */
    int query_state;                           /* 1 running in this frame, 2 ended (read next frame), 0 */
    const int *force;                          /* snell_renderer_warm: the plan to draw (ladder index per
                                                * object), NULL: the controller's */
} budget_state;

static budget_state *budget_of(const snell_renderer *r)
{
    return (budget_state *)snell__renderer_stage_state(r, &snell__stage_budget);
}

static int stage_wanted(const snell__frame *f, const void *state)
{
    (void)state;
    return f->fd->budget_ms > 0.0f;
}

/* A method may be on a ladder if its GL state can be made here (user: the services). */
static int usable(void *user, snell_method id)
{
    const snell__services *sv = (const snell__services *)user;
    void *state = NULL;
    return sv->method_state(sv->user, snell__method_get(id), &state) == SNELL_OK;
}

/* The GPU's own clock (EXT_disjoint_timer_query): a
 * TIME_ELAPSED query around the frame's commands, read at the next frame
 * once its fence has passed, so it never stalls. It counts the GPU's time
 * only, not a host's work between frames that the fence is seen late by.
 * Not while a host's own TIME_ELAPSED query runs (they cannot nest), nor
 * across a disjoint event (a clock change: the result is meaningless). */
static void timer_begin(snell_ctx *ctx, budget_state *bs)
{
    GLint running = 0, disjoint;
    if (!bs->timer) bs->timer = snell_ctx_has_gl_extension(ctx, "GL_EXT_disjoint_timer_query") ? 1 : -1;
    if (bs->timer < 0) return;
    glGetQueryiv(GL_TIME_ELAPSED_EXT, GL_CURRENT_QUERY_EXT, &running);
    if (running) return;
    if (!bs->query) glGenQueries(1, &bs->query);
    glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint); /* reading clears it */
    glBeginQuery(GL_TIME_ELAPSED_EXT, bs->query);
    bs->query_state = 1;
}

/* The ended query's ms, or -1: none, not yet available, disjoint, or 4.3 s
 * and more (the 32-bit read's limit; the fence's clock measures those). */
static double timer_read(budget_state *bs)
{
    GLuint ready = 0, ns = 0;
    GLint disjoint = 1;
    if (bs->query_state != 2) return -1.0;
    bs->query_state = 0;
    glGetQueryObjectuiv(bs->query, GL_QUERY_RESULT_AVAILABLE, &ready);
    if (!ready) return -1.0;
    glGetQueryObjectuiv(bs->query, GL_QUERY_RESULT, &ns);
    glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
    return disjoint || ns == 0xFFFFFFFFu ? -1.0 : ns * 1e-6;
}

/* A frame's ms as the budget counts it: the GPU timer's, or snell_render's
 * own CPU time where that was longer (a frame cannot come faster than it
 * is issued); the fence's clock (wall: start to completion seen) without
 * the timer, or where the timer reads more than that clock (a driver's
 * bogus first query: llvmpipe's reads hours). clock: 2 GPU timer, 1 wall. */
static double frame_ms(budget_state *bs, double wall, double cpu, int *clock)
{
    double gpu = timer_read(bs);
    *clock = gpu >= 0.0 && gpu <= wall + 1.0 ? 2 : 1;
    return *clock == 1 ? wall : gpu > cpu ? gpu : cpu;
}

/* The last budget frame's time, once the GPU finished it (waits for it if
 * it has not: a frame still running at the next one's start is over). */
static void collect(budget_state *bs, snell_frame_stats *s)
{
    GLsync fence = (GLsync)bs->fence;
    if (!fence) return;
    if (bs->done_ms < 0.0) {
        GLenum w = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000ull);
        if (w == GL_ALREADY_SIGNALED || w == GL_CONDITION_SATISFIED) bs->done_ms = snell__now_ms();
    }
    if (bs->done_ms >= 0.0)
        snell__budget_observe(&bs->ctl, frame_ms(bs, bs->done_ms - bs->start_ms, bs->cpu_ms,
                                                   &s->budget_clock));
    bs->query_state = 0;
    glDeleteSync(fence);
    bs->fence = NULL;
}

static void stage_destroy(snell_ctx *ctx, void *state)
{
    budget_state *bs = (budget_state *)state;
    (void)ctx;
    if (bs->fence) glDeleteSync((GLsync)bs->fence);
    if (bs->query) glDeleteQueries(1, &bs->query);
    bs->fence = NULL;
    bs->query = 0;
    bs->query_state = 0;
    snell__budget_reset(&bs->ctl);
}

/* The GPU is known to be done (after glFinish or a read-back): the frame's end time if still open. */
static void gpu_done(void *state)
{
    budget_state *bs = (budget_state *)state;
    if (bs->fence && bs->done_ms < 0.0 &&
        glClientWaitSync((GLsync)bs->fence, 0, 0) != GL_TIMEOUT_EXPIRED)
        bs->done_ms = snell__now_ms();
}

/* After the frame (drawn: it succeeded): the GPU timer query ended, a
 * fence to measure it by (budget frames only), or the controller reset
 * when the frame has no budget. */
static void frame_end(snell__frame *f, void *state, snell_status st)
{
    budget_state *bs = (budget_state *)state;
    int drawn = st == SNELL_OK;
    if (bs->query_state == 1) {
        glEndQuery(GL_TIME_ELAPSED_EXT);
        bs->query_state = drawn ? 2 : 0;
    }
    if (!drawn || bs->force) return; /* warming: measured by snell_renderer_warm */
    if (!(f->fd->budget_ms > 0.0f)) {
        if (bs->ctl.frame) stage_destroy(f->sv->ctx, bs); /* budget off: start afresh when it returns */
        return;
    }
    if (bs->fence) glDeleteSync((GLsync)bs->fence);
    bs->fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    bs->start_ms = f->start_ms;
    bs->cpu_ms = snell__now_ms() - f->start_ms;
    bs->done_ms = -1.0;
}

static snell_status stage_run(snell__frame *f, void *state)
{
    const snell__services *sv = f->sv;
    budget_state *bs = (budget_state *)state;
    snell__scene *sc = f->sc;
    snell_frame_stats *s = f->s;
    int plan[SNELL_MAX_GLASS];
    int i, drawn[SNELL_MAX_GLASS] = {0};
    double predicted = -1.0;
    if (!bs->force) collect(bs, s);
    timer_begin(sv->ctx, bs);
    for (i = 0; i < sc->drawn; i++) drawn[sc->order[i]] = 1;
    for (i = 0; i < sc->count; i++) {
        snell__object *o = &sc->obj[i];
        snell__budget_object *b = &bs->obj[i];
        const snell_glass_material *g = &o->glass->material;
        const snell_mesh_analysis *an = NULL;
        memset(b, 0, sizeof *b);
        if (!drawn[i]) continue; /* culled or passes through: costs nothing */
        snell__object_project(&sc->view, o);
        b->area = 0.785398f * (float)o->scissor[2] * (float)o->scissor[3] / ((float)sv->width * (float)sv->height);
        if (b->area > 1.0f) b->area = 1.0f;
        if (snell__mesh_analysis(o->mesh, &an) != SNELL_OK) an = NULL; /* cached on the mesh */
        if (g->method == SNELL_METHOD_AUTO && g->thickness <= 0.0f)
            snell__budget_ladder(an, o->glass, f->fd->quality_floor_db, sv->ctx->cost, usable, (void *)sv, b);
        if (b->n == 0) {
            /* drawn as asked (or single for a thin wall): its table cost, else single's */
            snell_method m = g->thickness > 0.0f || g->method == SNELL_METHOD_AUTO ? SNELL_METHOD_SINGLE : g->method;
            int k, cls = snell__budget_class(an, o->glass), n = snell__rung_count();
            b->fixed_cost = 1.0f;
            for (k = 0; k < n; k++) {
                const snell__rung *g = snell__rung_at(k);
                if (g->method == m && !g->param && g->scale <= 1) b->fixed_cost = snell__rung_cost(sv->ctx->cost, g, cls);
            }
        }
    }
    if (bs->force) {
        /* snell_renderer_warm draws the plan it measures */
        for (i = 0; i < sc->count; i++) {
            const snell__budget_object *b = &bs->obj[i];
            plan[i] = !b->n ? -1 : bs->force[i] < b->floor ? b->floor : bs->force[i] >= b->n ? b->n - 1
                                                                                                    : bs->force[i];
        }
        snell__why(s->budget_reason, sizeof s->budget_reason, "warming: measuring the rungs on this device");
    } else
        s->budget_changed = snell__budget_plan(&bs->ctl, bs->obj, sc->count, f->fd->budget_ms, plan,
                                               &predicted, s->budget_reason, sizeof s->budget_reason);
    s->budget_ms = f->fd->budget_ms;
    s->budget_first_use = bs->ctl.first_use;
    s->budget_measured_ms = bs->ctl.last_ms;
    s->budget_predicted_ms = predicted;
    for (i = 0; i < sc->count; i++) {
        const snell__budget_object *b = &bs->obj[i];
        snell__object *o = &sc->obj[i];
        const snell__rung *g;
        char name[96];
        if (!b->n || plan[i] < 0) continue;
        g = snell__rung_at(b->ladder[plan[i]]);
        /* The frame's resolved copy of the material (scene.c): the rung draws it as an explicit method,
         * at the rung's scale (the material's own is the rung's to choose, as its method is). */
        snell__rung_name(g, name, sizeof name);
        (void)snell__rung_apply(g, &sc->glass[i].material); /* the table's rungs apply (test_budget) */
        snprintf(bs->note[i], sizeof bs->note[i], "%s (rung %d of %d, %.1f dB predicted for %s mesh)",
                 name, plan[i] + 1, b->n, (double)g->db[b->cls], g_class_names[b->cls]);
        o->budget_note = bs->note[i];
    }
    return SNELL_OK;
}

/* snell_renderer_warm's measurements: the frame drawn with a forced plan. */
typedef struct warm_state {
    snell_renderer *r;
    const snell_frame_desc *fd;
    snell_frame_desc bare;          /* the frame without its glass objects */
    int frames;
    int bare_drawn;
    double cpu_ms;                  /* the last frame's time inside snell_render */
    snell_status st;
} warm_state;

static snell_status warm_draw(warm_state *w, const snell_frame_desc *fd)
{
    double t0 = snell__now_ms();
    snell_status st = snell_render(w->r, fd, NULL);
    w->cpu_ms = snell__now_ms() - t0;
    w->frames++;
    if (st != SNELL_OK && w->st == SNELL_OK) w->st = st;
    return st;
}

/* Draws the plan once to build what it needs when a rung is new to this
 * renderer, then three times timed (glFinish on both sides; the GPU timer
 * where there is one, as the frames it plans for): the median,
 * as one frame of a shared machine can take several times another and a
 * rung priced too dear here is never tried later. */
static double warm_measure(void *user, const int *plan)
{
    warm_state *w = user;
    snell_renderer *r = w->r;
    budget_state *bs = budget_of(r);
    const snell_frame_desc *fd = plan ? w->fd : &w->bare;
    double t0, ms[3], t;
    int i, clock, fresh = !plan ? !w->bare_drawn : 0;
    if (plan) {
        bs->force = plan;
        for (i = 0; i < w->fd->glass_count; i++)
            if (bs->obj[i].n && plan[i] >= 0 && !bs->ctl.drawn[bs->obj[i].ladder[plan[i]]]) {
                bs->ctl.drawn[bs->obj[i].ladder[plan[i]]] = 1; /* built below */
                fresh = 1;
            }
    }
    w->bare_drawn = 1;
    if (fresh && warm_draw(w, fd) != SNELL_OK) return -1.0;
    for (i = 0; i < 3; i++) {
        glFinish();
        t0 = snell__now_ms();
        if (warm_draw(w, fd) != SNELL_OK) return -1.0;
        glFinish();
        ms[i] = frame_ms(bs, snell__now_ms() - t0, w->cpu_ms, &clock); /* the clock frames are measured by */
    }
    if (ms[0] > ms[1]) t = ms[0], ms[0] = ms[1], ms[1] = t;
    if (ms[1] > ms[2]) t = ms[1], ms[1] = ms[2], ms[2] = t;
    if (ms[0] > ms[1]) t = ms[0], ms[0] = ms[1], ms[1] = t;
    return ms[1];
}

snell_status snell_renderer_warm(snell_renderer *r, const snell_frame_desc *fd, snell_warm_stats *stats)
{
    warm_state w;
    snell_warm_stats out;
    budget_state *bs;
    int floor_plan[SNELL_MAX_GLASS], i, n;
    double t0 = snell__now_ms();
    memset(&out, 0, sizeof out);
    if (stats) *stats = out;
    if (!r || !fd)
        return snell__fail(r ? budget_of(r)->ctx : NULL, SNELL_E_INVALID_ARG,
                           "snell_renderer_warm: renderer and frame required");
    bs = budget_of(r);
    memset(&w, 0, sizeof w);
    w.r = r, w.fd = fd, w.bare = *fd, w.st = SNELL_OK;
    w.bare.glass = NULL, w.bare.glass_count = 0;
    if (fd->budget_ms > 0.0f) {
        /* The floor plan first: it builds the ladders (bs->obj) the calibration walks. */
        for (i = 0; i < SNELL_MAX_GLASS; i++) floor_plan[i] = -1;
        snell__budget_reset(&bs->ctl);
        bs->force = floor_plan;
        if (warm_draw(&w, fd) == SNELL_OK) {
            snell__budget_object obj[SNELL_MAX_GLASS];
            n = fd->glass_count;
            memcpy(obj, bs->obj, sizeof(snell__budget_object) * (size_t)n);
            for (i = 0; i < n; i++)
                if (obj[i].n) bs->ctl.drawn[obj[i].ladder[obj[i].floor]] = 1; /* built by that frame */
            if (snell__budget_calibrate(&bs->ctl, obj, n, warm_measure, &w) > 0) {
                for (i = 0; i < SNELL__BUDGET_MAX_RUNGS; i++) out.rungs += bs->ctl.rung_ms[i] > 0.0;
                out.base_ms = bs->ctl.base_ms;
            }
        }
        bs->force = NULL;
        if (w.st != SNELL_OK) snell__budget_reset(&bs->ctl);
    } else {
        warm_draw(&w, fd);
    }
    if (w.st == SNELL_OK) glFinish();
    out.frames = w.frames;
    out.ms = snell__now_ms() - t0;
    if (stats) *stats = out;
    return w.st;
}

static snell_status stage_create(snell__services *sv, const snell_renderer_desc *d, void *state)
{
    (void)d;
    ((budget_state *)state)->ctx = sv->ctx;
    snell__budget_reset(&((budget_state *)state)->ctl);
    return SNELL_OK;
}

/* The frame's budget_ms and quality floor. */
static snell_status stage_validate(const snell__services *sv, const snell_frame_desc *fd)
{
    snell_ctx *ctx = sv->ctx;
    if (!isfinite(fd->budget_ms) || fd->budget_ms < 0.0f || fd->budget_ms > 1e6f)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "budget_ms %g: 0 (none) or a finite time up to 1e6 ms",
                           (double)fd->budget_ms);
    if (!isfinite(fd->quality_floor_db) || fd->quality_floor_db < 0.0f || fd->quality_floor_db > 100.0f)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "quality_floor_db %g outside 0..100", (double)fd->quality_floor_db);
    return SNELL_OK;
}

const snell__stage snell__stage_budget = {
    .name = "budget",
    .state_size = sizeof(budget_state),
    .create = stage_create,
    .destroy = stage_destroy,
    .validate = stage_validate,
    .wanted = stage_wanted,
    .run = stage_run,
    .frame_end = frame_end,
    .gpu_done = gpu_done,
};
