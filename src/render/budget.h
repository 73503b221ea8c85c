/* SPDX-License-Identifier: MIT */
/* budget.h — AUTO by frame budget (snell_frame_desc.budget_ms): each AUTO
 * glass object gets a ladder of rungs (budget.c's table, cut to the Pareto
 * front); a plan puts every object on one rung; the controller learns the
 * device's ms per unit from the frames it measures and picks the plan of the
 * highest predicted PSNR that fits 95% of the budget. The controller is plain C
 * without GL, testable with synthetic frame times (tests/test_budget.c).
 * The cost model and the guards against oscillation: docs/ARCHITECTURE.md,
 * "Design notes by file". */
#ifndef SNELL_BUDGET_H
#define SNELL_BUDGET_H

#include "frame/method.h"
#include "core/device_cost.h"

#define SNELL__BUDGET_CLASSES 4 /* 0 convex, 1 closed concave the cubemap serves, 2 closed concave it does
                                 * not, 3 open, non-manifold or unanalysed */
#define SNELL__BUDGET_MAX_RUNGS 20

/* One configuration of the table (public: snell_budget_rung). */
typedef snell_budget_rung snell__rung;

#define snell__rung_count snell_budget_rung_count
#define snell__rung_at snell_budget_rung_at
/* "peel layers=2", "peel layers=2 scale=2" */
void snell__rung_name(const snell__rung *g, char *buf, size_t n);
/* Writes rung g into m: its method, scale and parameters (m's others stay).
 * SNELL_E_INVALID_ARG if a parameter is refused. */
snell_status snell__rung_apply(const snell__rung *g, snell_glass_material *m);
/* The class of a mesh for the table (analysis may be NULL). */
int snell__budget_class(const snell_mesh_analysis *an, const snell_glass_resolved *glass);

/* One object as the controller sees it. */
typedef struct snell__budget_object {
    int ladder[SNELL__BUDGET_MAX_RUNGS]; /* rung indices, cost and PSNR ascending */
    float cost[SNELL__BUDGET_MAX_RUNGS], db[SNELL__BUDGET_MAX_RUNGS]; /* each ladder rung's, for its class */
    int n;                          /* 0: not budgeted (explicit method, thin wall): fixed_cost counts */
    int cls;
    float area;                     /* 0..1 */
    float fixed_cost;               /* for n == 0: its cost relative to single */
    int floor;                      /* lowest ladder index the quality floor allows */
} snell__budget_object;

typedef struct snell__budget {
    double ms_per_unit;             /* the mean of the learned rungs' ms per unit; 0 until the first frame */
    double base_ms;                 /* learned: the frame's part that no rung changes (opaque objects,
                                     * scene layers, background) */
    double rung_ms[SNELL__BUDGET_MAX_RUNGS]; /* learned ms per unit of each rung of the table, 0 = not yet
                                     * drawn (ms_per_unit stands in): the device's own cost table */
    int last_plan_rung[SNELL_MAX_GLASS]; /* the measured plan's rung (table index) per object, -1 none */
    float last_area[SNELL_MAX_GLASS];   /* its units: area times the rung's cost */
    double last_fixed;              /* its units of fixed-cost objects (explicit methods, thin walls) */
    int prev_valid;                 /* the measured frame preceding it: its plan's rungs and units, its ms */
    int prev_rung[SNELL_MAX_GLASS];
    float prev_area[SNELL_MAX_GLASS];
    double prev_ms, prev_fixed;
    double last_ms;                 /* the last measured frame, -1 none */
    double last_units;              /* the plan it drew, in units */
    double blocked_units;           /* plans of at least this many units are barred ... */
    unsigned blocked_until;         /* ... until this frame */
    unsigned backoff;               /* frames the next bar lasts */
    unsigned frame;                 /* frames planned */
    unsigned hold_until;            /* no step up before this frame */
    unsigned within_since;          /* frame since which the measured frames are within budget */
    int fresh;                      /* 1: last_ms was measured since the last plan */
    unsigned last_change;           /* frame of the last change of plan */
    unsigned probe_every;           /* a plan held this many frames tries one step up predicted over the
                                     * aim (the prediction may be wrong: a frame can only be split into
                                     * base and rungs by drawing another plan); doubles when it fails */
    int probing;                    /* the last change was such a try */
    unsigned char drawn[SNELL__BUDGET_MAX_RUNGS]; /* rungs drawn before on this renderer */
    int first_use;                  /* the last plan draws a rung for the first time: its frame builds
                                     * programs and per-mesh resources, so it is neither learned from
                                     * nor judged over budget */
    int plan[SNELL_MAX_GLASS];      /* ladder index per object of the last plan, -1 none */
    int calibrated;                 /* 1: base and rung costs were measured by snell__budget_calibrate, so
                                     * probes stay within the budget (no step is predicted from the table) */
} snell__budget;

void snell__budget_reset(snell__budget *b);
/* The frame last planned took ms (> 0) on the device. */
void snell__budget_observe(snell__budget *b, double ms);
/* Plans objects[0..n) for budget_ms; writes each object's ladder index into
 * plan[] (-1 for n == 0 objects), the predicted ms (-1 when nothing was
 * measured yet) and why, and returns 1 if the plan changed. */
int snell__budget_plan(snell__budget *b, const snell__budget_object *obj, int n, float budget_ms, int plan[],
                       double *predicted_ms, char *why, size_t why_size);

/* Measures this device before the first planned frame (snell_renderer_warm):
 * measure(user, plan) draws the frame with object i on ladder index plan[i]
 * (plan NULL: the frame without its glass objects) and returns its ms, <= 0
 * when it failed. Draws the frame without glass (the base), every object on
 * its floor, then one object at a time on each rung above it, and seeds the
 * controller with the base and each rung's ms per unit (the units-weighted
 * mean over the objects that drew it), every measured rung counted as drawn.
 * Resets b first, but for its drawn[] (measure may read and set it). Returns the frames measured, or -1 if a measure failed. */
int snell__budget_calibrate(snell__budget *b, const snell__budget_object *obj, int n,
                            double (*measure)(void *user, const int *plan), void *user);

/* A rung's cost over single's for the mesh class on the device (NULL: the
 * table's own): its method's default rung priced by the device's model,
 * the method's other rungs in the table's ratios to it. */
float snell__rung_cost(const snell__device_cost *dev, const snell__rung *g, int cls);

/* Renderer side (budget.c): the ladder of one object (fit per method of the
 * table, methods that failed to build excluded by usable(id)), priced on dev. */
void snell__budget_ladder(const snell_mesh_analysis *an, const snell_glass_resolved *glass, float quality_floor_db,
                          const snell__device_cost *dev, int (*usable)(void *user, snell_method m), void *user,
                          snell__budget_object *out);

#endif
