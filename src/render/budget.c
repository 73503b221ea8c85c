/* SPDX-License-Identifier: MIT */
/* budget.c — AUTO by frame budget: the rung table, each object's ladder,
 * and the controller (see budget.h). */
#include "render/budget.h"
#include "render/glass_scale.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The rungs AUTO by budget chooses from are the methods' own
 * (snell__method.rungs, frame/method.h), so a method reaches the ladder from
 * its registry entry. They are numbered in registry order, every method's
 * full-resolution rungs first, then the scaled ones (synthetic devices in
 * test_budget.c skew each rung's cost by its index). */
static const snell__rung *rung_walk(int want, int *count)
{
    int pass, i, k, n = 0;
    for (pass = 0; pass < 2; pass++)
        for (i = 0; i < snell_method_count(); i++) {
            const snell__method *m = snell__method_get(snell_method_info_at(i)->method);
            for (k = 0; k < m->rung_count && n < SNELL__BUDGET_MAX_RUNGS; k++) {
                if ((m->rungs[k].scale > 1) != pass) continue;
                if (n++ == want) return &m->rungs[k];
            }
        }
    if (count) *count = n;
    return NULL;
}

/* The cost of a frame without glass, in units (single's frame drawing the
 * target full of glass is 1 + BASE_UNITS): background, opaque objects. */
#define BASE_UNITS 0.25
#define HEADROOM 0.95    /* plans aim at this share of the budget */
#define OVER 1.05        /* a measured frame above this share of it is over */
#define HOLD_FRAMES 6    /* after a change, no step up for this many frames */
#define BACKOFF_MIN 30u  /* frames a plan found over budget is barred, at first */
#define BACKOFF_MAX 480u
#define PROBE_REACH 2.0  /* a probe considers steps predicted within this many times the aim ... */
#define PROBE_REACH_CALIBRATED (1.05 / HEADROOM) /* ... or within 105% of the budget once the costs were measured */
#define LEARN_RUNG 0.6   /* weight of the newest frame in a learned cost, times its share of the frame */

int snell_budget_rung_count(void)
{
    int n = 0;
    rung_walk(-1, &n);
    return n;
}

const snell_budget_rung *snell_budget_rung_at(int i) { return i >= 0 ? rung_walk(i, NULL) : NULL; }

/* A rung's parameters as snell-bench writes them after a space: " param=value:more", "" for none. */
static void rung_params(const snell__rung *g, char *buf, size_t n)
{
    *buf = '\0';
    if (g->param) snprintf(buf, n, " %s=%d%s%s", g->param, g->value, g->more ? ":" : "", g->more ? g->more : "");
}

void snell__rung_name(const snell__rung *g, char *buf, size_t n)
{
    char params[128], scale[24] = "";
    rung_params(g, params, sizeof params);
    if (g->scale > 1) snprintf(scale, sizeof scale, " scale=%d", g->scale);
    snprintf(buf, n, "%s%s%s", snell_method_str(g->method), params, scale);
}

snell_status snell__rung_apply(const snell__rung *g, snell_glass_material *m)
{
    char all[128], *p, *eq, *end;
    if (!g || !m) return SNELL_E_INVALID_ARG;
    m->method = g->method;
    m->scale = g->scale > 1 ? (float)g->scale : 1.0f;
    rung_params(g, all, sizeof all);
    /* each "name=value" up to the next ':' */
    for (p = all + (*all == ' '); *p; p = end) {
        end = p + strcspn(p, ":");
        if (*end) *end++ = '\0';
        eq = strchr(p, '=');
        if (!eq) return SNELL_E_INVALID_ARG;
        *eq = '\0';
        if (snell_glass_set_param(m, g->method, p, eq + 1) != SNELL_OK) return SNELL_E_INVALID_ARG;
    }
    return SNELL_OK;
}

int snell__budget_class(const snell_mesh_analysis *an, const snell_glass_resolved *glass)
{
    const snell__method *cube = snell__method_get(SNELL_METHOD_CUBEMAP);
    char why[SNELL_REASON_SIZE];
    if (!an || !an->closed) return 3;
    if (an->convex) return 0;
    return cube && cube->fit && cube->fit(an, glass, why, sizeof why) == SNELL__FIT_ADEQUATE ? 1 : 2;
}

float snell__rung_cost(const snell__device_cost *dev, const snell__rung *g, int cls)
{
    float base = 0.0f, on_dev = dev ? dev->cost[g->method][cls] : 0.0f;
    int i, n = snell__rung_count();
    /* the device's cost of the method's default rung; its other rungs keep their ratios to it */
    for (i = 0; i < n && on_dev > 0.0f; i++) {
        const snell__rung *h = snell__rung_at(i);
        if (h->method == g->method && !h->param && h->scale <= 1) base = h->cost[cls];
    }
    return base > 0.0f ? g->cost[cls] * on_dev / base : g->cost[cls];
}

void snell__budget_ladder(const snell_mesh_analysis *an, const snell_glass_resolved *glass, float quality_floor_db,
                          const snell__device_cost *dev, int (*usable)(void *user, snell_method m), void *user,
                          snell__budget_object *out)
{
    float cost[SNELL__BUDGET_MAX_RUNGS];
    int i, j, count = snell__rung_count();
    out->n = 0;
    out->cls = snell__budget_class(an, glass);
    out->floor = 0;
    out->fixed_cost = 1.0f;
    for (i = 0; i < count && i < SNELL__BUDGET_MAX_RUNGS; i++) cost[i] = snell__rung_cost(dev, snell__rung_at(i), out->cls);
    for (i = 0; i < count; i++) {
        const snell__rung *g = snell__rung_at(i);
        const snell__method *m = snell__method_get(g->method);
        char why[SNELL_REASON_SIZE];
        if (!m || g->db[out->cls] <= 0.0f || !usable(user, g->method) || g->scale > snell__glass_scale_max(m)) continue;
        if (m->fit && m->fit(an, glass, why, sizeof why) == SNELL__FIT_FAILS) continue;
        /* Pareto: drop every rung this one beats (cheaper or as cheap, and better or as good). */
        for (j = 0; j < out->n;) {
            const snell__rung *h = snell__rung_at(out->ladder[j]);
            if (cost[i] <= cost[out->ladder[j]] && g->db[out->cls] >= h->db[out->cls]) {
                memmove(&out->ladder[j], &out->ladder[j + 1], sizeof(int) * (size_t)(out->n - j - 1));
                out->n--;
            } else
                j++;
        }
        for (j = 0; j < out->n; j++) {
            const snell__rung *h = snell__rung_at(out->ladder[j]);
            if (cost[out->ladder[j]] <= cost[i] && h->db[out->cls] >= g->db[out->cls]) break; /* beaten */
        }
        if (j < out->n) continue;
        /* insert in cost order (the Pareto front is then in PSNR order too) */
        for (j = out->n; j > 0 && cost[out->ladder[j - 1]] > cost[i]; j--) out->ladder[j] = out->ladder[j - 1];
        out->ladder[j] = i;
        out->n++;
    }
    for (j = 0; j < out->n; j++) {
        const snell__rung *g = snell__rung_at(out->ladder[j]);
        out->cost[j] = cost[out->ladder[j]];
        out->db[j] = g->db[out->cls];
    }
    if (quality_floor_db > 0.0f) {
        out->floor = out->n > 0 ? out->n - 1 : 0; /* none reaches it: the best there is */
        for (j = 0; j < out->n; j++)
            if (out->db[j] >= quality_floor_db) {
                out->floor = j;
                break;
            }
    }
}

void snell__budget_reset(snell__budget *b)
{
    int i;
    memset(b, 0, sizeof *b);
    b->last_ms = -1.0;
    b->backoff = BACKOFF_MIN;
    b->probe_every = BACKOFF_MIN;
    for (i = 0; i < SNELL_MAX_GLASS; i++) b->plan[i] = b->last_plan_rung[i] = -1;
}

static double rung_cost(const snell__budget_object *o, int k)
{
    return o->n == 0 ? o->fixed_cost : o->cost[k];
}

static double rung_db(const snell__budget_object *o, int k) { return o->db[k]; }

/* A plan in the table's units (what bars compare; device independent). */
static double plan_units(const snell__budget_object *obj, int n, const int plan[])
{
    double u = BASE_UNITS;
    int i;
    for (i = 0; i < n; i++) u += obj[i].area * rung_cost(&obj[i], obj[i].n ? plan[i] : 0);
    return u;
}

/* ms per unit of rung r of the table: learned on this device, else the learned rungs' mean, a little
 * optimistic (OPTIMISM) so that a rung the table prices near the aim is tried once and then known,
 * rather than never tried: one probe frame may run over, then it is measured. */
#define OPTIMISM 0.9
static double rung_k(const snell__budget *b, int r)
{
    return b->rung_ms[r] > 0.0 ? b->rung_ms[r] : OPTIMISM * b->ms_per_unit;
}

static double object_ms(const snell__budget *b, const snell__budget_object *o, int k)
{
    if (!o->n) return o->area * o->fixed_cost * b->ms_per_unit;
    return o->area * o->cost[k] * rung_k(b, o->ladder[k]);
}

/* A plan's predicted ms on this device. */
static double plan_ms(const snell__budget *b, const snell__budget_object *obj, int n, const int plan[])
{
    double ms = b->base_ms;
    int i;
    for (i = 0; i < n; i++) ms += object_ms(b, &obj[i], plan[i]);
    return ms;
}

static double plan_quality(const snell__budget_object *obj, int n, const int plan[])
{
    double q = 0.0, a = 0.0;
    int i;
    for (i = 0; i < n; i++)
        if (obj[i].n) {
            q += obj[i].area * rung_db(&obj[i], plan[i]);
            a += obj[i].area;
        }
    return a > 0.0 ? q / a : 0.0;
}

/* The prediction of a measured plan (rungs and units per object) with today's estimates. */
static double measured_plan_ms(const snell__budget *b, const int rung[], const float units[], double fixed,
                               double part[])
{
    double ms = b->base_ms + fixed * b->ms_per_unit;
    int i, r;
    for (i = 0; i < SNELL_MAX_GLASS; i++)
        if ((r = rung[i]) >= 0) {
            if (part) part[r] += units[i] * rung_k(b, r);
            ms += units[i] * rung_k(b, r);
        }
    return ms;
}

/* The mean ms per unit of the rungs learned so far, 0 if none. */
static double learned_mean(const snell__budget *b)
{
    double sum = 0.0;
    int r, m = 0;
    for (r = 0; r < SNELL__BUDGET_MAX_RUNGS; r++)
        if (b->rung_ms[r] > 0.0) sum += b->rung_ms[r], m++;
    return m ? sum / m : 0.0;
}

static double clampd(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }

void snell__budget_observe(snell__budget *b, double ms)
{
    double pred, part[SNELL__BUDGET_MAX_RUNGS] = {0};
    int i, r, changed = 0, learned = 0;
    if (!(ms > 0.0) || !(b->last_units > 0.0)) return;
    b->last_ms = ms;
    if (b->first_use) {
        b->prev_valid = 0; /* a first draw's builds (programs, bakes) say nothing of its cost */
        return;
    }
    b->fresh = 1;
    if (b->ms_per_unit <= 0.0) {
        /* The first frame: no split is known; the table's base share, every rung drawn at the mean. */
        b->ms_per_unit = ms / b->last_units;
        b->base_ms = BASE_UNITS * b->ms_per_unit;
        for (i = 0; i < SNELL_MAX_GLASS; i++)
            if (b->last_plan_rung[i] >= 0) b->rung_ms[b->last_plan_rung[i]] = b->ms_per_unit;
    } else {
        pred = measured_plan_ms(b, b->last_plan_rung, b->last_area, b->last_fixed, part);
        for (i = 0; i < SNELL_MAX_GLASS && b->prev_valid; i++) changed |= b->prev_rung[i] != b->last_plan_rung[i];
        if (changed) {
            /* A new plan beside the last one measured: the difference of the two frames is what the
             * rungs new to this plan cost more than the prediction said (the base cancels). */
            double prev_pred = measured_plan_ms(b, b->prev_rung, b->prev_area, b->prev_fixed, NULL);
            double d = (ms - b->prev_ms) - (pred - prev_pred), fresh_part = 0.0;
            unsigned char fresh[SNELL__BUDGET_MAX_RUNGS] = {0};
            for (i = 0; i < SNELL_MAX_GLASS; i++)
                if ((r = b->last_plan_rung[i]) >= 0 && r != b->prev_rung[i] && !fresh[r]) {
                    fresh[r] = 1;
                    fresh_part += part[r];
                }
            for (r = 0; r < SNELL__BUDGET_MAX_RUNGS && fresh_part > 0.0; r++)
                if (fresh[r]) {
                    b->rung_ms[r] = rung_k(b, r) * clampd((fresh_part + d) / fresh_part, 0.25, 4.0);
                    learned = 1;
                }
        }
        if (!learned) {
            /* The same plan again: the error goes to the base and each rung by its share of the prediction. */
            double rho = ms / pred;
            b->base_ms *= pow(rho, LEARN_RUNG * b->base_ms / pred);
            for (r = 0; r < SNELL__BUDGET_MAX_RUNGS; r++)
                if (part[r] > 0.0) b->rung_ms[r] = rung_k(b, r) * pow(rho, LEARN_RUNG * part[r] / pred);
        }
        /* the mean that stands in for rungs not drawn yet */
        if (learned_mean(b) > 0.0) b->ms_per_unit = learned_mean(b);
    }
    b->prev_valid = 1;
    b->prev_ms = ms;
    b->prev_fixed = b->last_fixed;
    memcpy(b->prev_rung, b->last_plan_rung, sizeof b->prev_rung);
    memcpy(b->prev_area, b->last_area, sizeof b->prev_area);
}

/* Greedy: from every object on its floor rung, the step up that buys the
 * most area-weighted PSNR per ms, while the plan fits limit_ms and stays
 * below the bar (in table units). */
static void best_plan(const snell__budget *b, const snell__budget_object *obj, int n, double limit_ms, int plan[])
{
    int i;
    double ms, units;
    for (i = 0; i < n; i++) plan[i] = obj[i].n ? obj[i].floor : -1;
    ms = plan_ms(b, obj, n, plan);
    units = plan_units(obj, n, plan);
    for (;;) {
        int pick = -1;
        double best = 0.0, dms_pick = 0.0, du_pick = 0.0;
        for (i = 0; i < n; i++) {
            double dms, du, dq, gain;
            if (!obj[i].n || plan[i] + 1 >= obj[i].n) continue;
            dms = object_ms(b, &obj[i], plan[i] + 1) - object_ms(b, &obj[i], plan[i]);
            du = obj[i].area * (rung_cost(&obj[i], plan[i] + 1) - rung_cost(&obj[i], plan[i]));
            dq = obj[i].area * (rung_db(&obj[i], plan[i] + 1) - rung_db(&obj[i], plan[i]));
            if (ms + dms > limit_ms) continue;
            if (b->blocked_until > b->frame && units + du >= b->blocked_units) continue;
            gain = dq / (dms > 1e-9 ? dms : 1e-9);
            if (gain > best) {
                best = gain;
                pick = i;
                dms_pick = dms;
                du_pick = du;
            }
        }
        if (pick < 0) break;
        plan[pick]++;
        ms += dms_pick;
        units += du_pick;
    }
}

/* Every plan when there are few (the product of the ladders' lengths up to
 * EXHAUSTIVE): the best quality that fits limit_ms and the bar, the cheaper
 * of equals. Returns 0 (plan untouched) when there are too many. */
#define EXHAUSTIVE 4096
static int exhaustive_plan(const snell__budget *b, const snell__budget_object *obj, int n, double limit_ms, int plan[])
{
    int i, k[SNELL_MAX_GLASS], found = 0;
    double combos = 1.0, best_q = -1.0, best_ms = 0.0;
    for (i = 0; i < n; i++) {
        k[i] = obj[i].n ? obj[i].floor : -1;
        if (obj[i].n) combos *= (double)(obj[i].n - obj[i].floor);
    }
    if (combos > EXHAUSTIVE) return 0;
    for (;;) {
        double ms = plan_ms(b, obj, n, k), q = plan_quality(obj, n, k);
        int fits = ms <= limit_ms && !(b->blocked_until > b->frame && plan_units(obj, n, k) >= b->blocked_units);
        /* the first (floor) plan stands when nothing fits */
        if (!found || (fits && (q > best_q + 1e-9 || (q > best_q - 1e-9 && ms < best_ms)))) {
            memcpy(plan, k, sizeof(int) * (size_t)n);
            best_q = fits ? q : -1.0;
            best_ms = ms;
            found = 1;
        }
        for (i = 0; i < n; i++) { /* the next plan, odometer order */
            if (!obj[i].n) continue;
            if (++k[i] < obj[i].n) break;
            k[i] = obj[i].floor;
        }
        if (i == n) break;
    }
    return 1;
}

/* The best plan within limit_ms: every plan when they are few, else greedy. */
static void choose_plan(const snell__budget *b, const snell__budget_object *obj, int n, double limit_ms, int plan[])
{
    if (!exhaustive_plan(b, obj, n, limit_ms, plan)) best_plan(b, obj, n, limit_ms, plan);
}

int snell__budget_plan(snell__budget *b, const snell__budget_object *obj, int n, float budget_ms, int plan[],
                       double *predicted_ms, char *why, size_t why_size)
{
    int i, changed = 0, probed = 0, same_objects = 1;
    int cur[SNELL_MAX_GLASS] = {0}; /* n of them set below; zeroed so that no compiler sees a read of an unset one */
    int over = b->fresh && b->last_ms > OVER * budget_ms;
    b->fresh = 0;
    snell__why(why, why_size, "unchanged");
    /* The current plan carried over (clamped to each ladder). */
    for (i = 0; i < n; i++) {
        cur[i] = obj[i].n ? b->plan[i] : -1;
        if (obj[i].n && (cur[i] < obj[i].floor || cur[i] >= obj[i].n)) {
            cur[i] = obj[i].floor;
            same_objects = 0;
        }
    }
    if (b->ms_per_unit <= 0.0) {
        /* Nothing measured yet: start on the floor and measure it. */
        for (i = 0; i < n; i++) plan[i] = obj[i].n ? obj[i].floor : -1;
        snell__why(why, why_size, "nothing measured yet: every object on its lowest allowed rung, to measure it");
        changed = b->frame == 0;
        for (i = 0; i < n && !changed; i++) changed = plan[i] != cur[i];
    } else {
        double cur_ms = plan_ms(b, obj, n, cur), new_ms, new_q, cur_q = plan_quality(obj, n, cur);
        if (over) {
            /* Measured over budget: bar plans as dear as this one, longer each time. */
            b->blocked_units = b->last_units;
            b->blocked_until = b->frame + b->backoff;
            b->backoff = b->backoff * 2 > BACKOFF_MAX ? BACKOFF_MAX : b->backoff * 2;
            b->within_since = b->frame + 1;
        } else if (b->frame - b->within_since >= 2 * BACKOFF_MIN && b->backoff > BACKOFF_MIN) {
            b->backoff /= 2; /* a long stretch within budget forgives */
            b->within_since = b->frame;
        }
        choose_plan(b, obj, n, HEADROOM * budget_ms, plan);
        new_ms = plan_ms(b, obj, n, plan);
        new_q = plan_quality(obj, n, plan);
        if (!over && same_objects && new_ms > cur_ms && b->frame < b->hold_until && cur_ms <= budget_ms) {
            memcpy(plan, cur, sizeof(int) * (size_t)n); /* hold: the last change is still being measured */
            snell__why(why, why_size, "holding for %u frames after a change", b->hold_until - b->frame);
        } else if (!over && same_objects && new_ms > cur_ms && new_q <= cur_q) {
            memcpy(plan, cur, sizeof(int) * (size_t)n); /* dearer and no better */
        } else if (!over && same_objects && new_ms < cur_ms && cur_ms <= budget_ms && new_q < cur_q) {
            /* predicted within the budget though above the aim: kept (the band from the aim, 95% of the budget, to the budget is the
             * hysteresis). Only against a worse plan: one both cheaper and better is taken (a rung
             * learned dear under load can predict a better rung not drawn yet as the cheaper) */
            memcpy(plan, cur, sizeof(int) * (size_t)n);
            snell__why(why, why_size, "kept: %.2f ms predicted, within the budget's %.2f", cur_ms, (double)budget_ms);
        }
        for (i = 0; i < n && !changed; i++) changed = plan[i] != cur[i];
        if (b->probing && !changed) {
            /* the last probe's plan held within the budget: probes come back to their first pace */
            b->probing = 0;
            b->probe_every = BACKOFF_MIN;
        } else if (b->probing && (over || new_ms < cur_ms)) {
            /* over, or measured above the budget and stepped back from: the step does not fit, and
             * trying it again at the same pace is an oscillation */
            b->probing = 0;
            b->probe_every = b->probe_every * 2 > BACKOFF_MAX ? BACKOFF_MAX : b->probe_every * 2;
        }
        if (!changed && !over && same_objects && b->frame - b->last_change >= b->probe_every &&
            b->blocked_until <= b->frame) {
            /* Held long enough: try the best single step up among those predicted within PROBE_REACH
             * times the aim (within the budget once calibrated). The prediction splits the frame into base and rungs by the table's units
             * until a change of plan measures the split; a step is how it is measured. */
            int step[SNELL_MAX_GLASS], pick = -1;
            double best = 0.0, reach = (b->calibrated ? PROBE_REACH_CALIBRATED : PROBE_REACH) * HEADROOM * budget_ms;
            memcpy(step, cur, sizeof(int) * (size_t)n);
            for (i = 0; i < n; i++)
                if (obj[i].n && cur[i] + 1 < obj[i].n) {
                    double dq = obj[i].area * (rung_db(&obj[i], cur[i] + 1) - rung_db(&obj[i], cur[i]));
                    step[i] = cur[i] + 1;
                    if (dq > best && plan_ms(b, obj, n, step) <= reach &&
                        !(b->blocked_until > b->frame && plan_units(obj, n, step) >= b->blocked_units))
                        best = dq, pick = i;
                    step[i] = cur[i];
                }
            if (pick >= 0) {
                plan[pick] = cur[pick] + 1;
                changed = probed = 1;
                b->probing = 1;
                snell__why(why, why_size, "probing one step up after %u frames held", b->probe_every);
            }
        }
        new_ms = plan_ms(b, obj, n, plan);
        if (probed)
            ; /* said above */
        else if (changed || over)
            snell__why(why, why_size, "%s: last frame %.2f ms, this plan %.2f ms predicted%s",
                       !changed ? "over budget, nothing cheaper allowed" : over ? "over budget, stepped down"
                       : new_q > cur_q ? "stepped up" : "stepped down",
                       b->last_ms, new_ms, b->blocked_until > b->frame ? " (plans as dear as one found over are barred)" : "");
        else if (!strcmp(why, "unchanged"))
            snell__why(why, why_size, "unchanged: last frame %.2f ms, this plan %.2f ms predicted", b->last_ms, new_ms);
    }
    if (changed) {
        b->hold_until = b->frame + HOLD_FRAMES;
        b->last_change = b->frame;
    }
    for (i = 0; i < SNELL_MAX_GLASS; i++) {
        b->plan[i] = i < n ? plan[i] : -1;
        b->last_plan_rung[i] = i < n && obj[i].n ? obj[i].ladder[plan[i]] : -1;
        b->last_area[i] = i < n && obj[i].n ? (float)(obj[i].area * rung_cost(&obj[i], plan[i])) : 0.0f;
    }
    b->first_use = 0;
    for (i = 0; i < n; i++)
        if (obj[i].n && !b->drawn[obj[i].ladder[plan[i]]]) {
            b->first_use = 1;
            b->drawn[obj[i].ladder[plan[i]]] = 1;
        }
    b->last_fixed = 0.0;
    for (i = 0; i < n; i++)
        if (!obj[i].n) b->last_fixed += obj[i].area * obj[i].fixed_cost;
    b->last_units = plan_units(obj, n, plan);
    *predicted_ms = b->ms_per_unit > 0.0 ? plan_ms(b, obj, n, plan) : -1.0;
    b->frame++;
    return changed;
}

int snell__budget_calibrate(snell__budget *b, const snell__budget_object *obj, int n,
                            double (*measure)(void *user, const int *plan), void *user)
{
    double base, m0, ms, floor_units = 0.0, k_floor, num[SNELL__BUDGET_MAX_RUNGS] = {0}, den[SNELL__BUDGET_MAX_RUNGS] = {0};
    int plan[SNELL_MAX_GLASS], i, k, r, frames = 2;
    unsigned char built[SNELL__BUDGET_MAX_RUNGS];
    memcpy(built, b->drawn, sizeof built); /* what was drawn before stays built */
    snell__budget_reset(b);
    memcpy(b->drawn, built, sizeof built);
    if (!((base = measure(user, NULL)) > 0.0)) return -1;
    for (i = 0; i < n; i++) {
        plan[i] = obj[i].n ? obj[i].floor : -1;
        floor_units += obj[i].area * rung_cost(&obj[i], obj[i].n ? plan[i] : 0);
    }
    if (!((m0 = measure(user, plan)) > 0.0)) return -1;
    /* The glass's share of the floor frame; at least a twentieth of it, as a frame's noise can
     * measure the base above a frame of small objects. */
    k_floor = floor_units > 1e-6 ? (m0 - base > 0.05 * m0 ? m0 - base : 0.05 * m0) / floor_units : m0;
    for (i = 0; i < n; i++)
        if (obj[i].n) {
            r = obj[i].ladder[obj[i].floor];
            num[r] += obj[i].area * rung_cost(&obj[i], obj[i].floor) * k_floor;
            den[r] += obj[i].area * rung_cost(&obj[i], obj[i].floor);
        }
    /* One object a step up at a time: what it costs above the floor frame is its rung's. */
    for (i = 0; i < n; i++)
        for (k = obj[i].floor + 1; k < obj[i].n; k++) {
            double u_floor = obj[i].area * rung_cost(&obj[i], obj[i].floor), u = obj[i].area * rung_cost(&obj[i], k);
            plan[i] = k;
            ms = measure(user, plan);
            plan[i] = obj[i].floor;
            if (!(ms > 0.0)) return -1;
            frames++;
            r = obj[i].ladder[k];
            num[r] += ms - m0 + u_floor * k_floor;
            den[r] += u;
        }
    for (r = 0; r < SNELL__BUDGET_MAX_RUNGS; r++)
        if (den[r] > 1e-9) {
            /* the table's order of costs is kept within a factor 4 of the floor's ms per unit */
            b->rung_ms[r] = clampd(num[r] / den[r], 0.25 * k_floor, 4.0 * k_floor);
            b->drawn[r] = 1;
        }
    b->ms_per_unit = learned_mean(b) > 0.0 ? learned_mean(b) : k_floor;
    b->base_ms = base;
    b->calibrated = 1;
    return frames;
}
