/* SPDX-License-Identifier: MIT */
/* ref_trace.c — the double-precision CPU reference tracer (snell_ref.h): the
 * MATCHED chain and the FULL Whitted tree through a scene of glass and opaque
 * objects (ref_scene.c), camera rays, the pthread image loop and light paths.
 * Optics are the shared kernel of optics.h (Unger 2.1: Snell with TIR, mirror
 * reflection, Fresnel - MATCHED: Schlick, as the kernels; FULL: the exact
 * unpolarised reflectance - Beer-Lambert, the thin slab); the chain follows
 * Unger 4.1 with exact ray casts in place of the cubemap binary search. Pixels
 * are the centre ray or the mean of an S x S grid (params.samples). */
#define _POSIX_C_SOURCE 200809L
#include "ref/ref_trace.h"
#include "ref/ref_scene.h"
#include "frame/camera.h"
#include "frame/env.h"
#include "core/optics.h"

#include <math.h>
#include <pthread.h>
#include <string.h>
#include <unistd.h>

/* A branch whose throughput (largest channel) falls below this ends with an
 * env lookup in its direction instead of being traced further (FULL: every
 * branch; MATCHED: the side branches, never the chain the path records). The
 * error is below MIN_WEIGHT * (difference of two radiances <= 1) per pruned
 * branch, far under half an 8-bit step (1/510). */
#define MIN_WEIGHT 1e-5

/* Parameters with defaults resolved. */
typedef struct optics {
    snell_ref_mode mode;
    int max_if;
    snell_ref_absorption absorb;
    int isolate;
    unsigned terms; /* MATCHED: snell_ref_terms */
    const snell_env *env;
    snell_ref_env_fn env_fn;
    void *env_user;
    int samples; /* S: S x S rays per pixel */
    int channel; /* the colour channel whose IOR the glass has on this trace (ref_glass.ior_rgb) */
    int disperses; /* some glass object's channels have different IORs: a trace per channel */
    const snell__ref_surroundings *sur; /* MATCHED: NULL, air and the environment (ref_trace.h) */
    const snell__ref_medium *first;     /* with sur: the medium a ray starting off every surface is in */
} optics;

/* ------------------------------------------------------------ vectors */


static double max3(const double w[3])
{
    return w[0] > w[1] ? (w[0] > w[2] ? w[0] : w[2]) : (w[1] > w[2] ? w[1] : w[2]);
}

static void env_rgb(const optics *op, const double d[3], double rgb[3])
{
    if (op->env_fn)
        op->env_fn(d, rgb, op->env_user);
    else
        snell_env_sample_d(op->env, d, rgb);
}

/* What a ray in air sees after `depth` interfaces. excl: a glass object it
 * must not see (MATCHED: the one it leaves); home: the first glass object the
 * path met, -1 none yet (MATCHED passes excl: any object left counts). */
static ref_view air_view(const optics *op, int depth, int excl, int home)
{
    ref_view v;
    v.medium = -1;
    v.excl = excl;
    if (depth >= op->max_if) /* no interface can be processed any more */
        v.glass = REF_SEE_NONE;
    else if (op->isolate && home >= 0)
        v.glass = op->mode == SNELL_REF_FULL ? home : REF_SEE_NONE;
    else
        v.glass = REF_SEE_ALL;
    return v;
}

static ref_view inside_view(int medium)
{
    ref_view v;
    v.medium = medium;
    v.glass = REF_SEE_NONE;
    v.excl = -1;
    return v;
}

/* The smooth normal at s turned to face the ray d; returns cos_i >= 0. */
static double facing(const ref_surf *s, const double d[3], double n[3])
{
    double nd = snell__ref_dot3(s->n, d);
    int k;
    for (k = 0; k < 3; k++) n[k] = nd > 0.0 ? -s->n[k] : s->n[k];
    return nd > 0.0 ? nd : -nd;
}

/* Glass object g's IOR on this trace: its channel's (dispersion; green is ior itself). */
static double ior_of(const optics *op, const ref_glass *g)
{
    return g->ior_rgb[op->channel];
}

/* Cycles' threshold (ensure_valid_reflection): a mirror direction may be as
 * shallow as the incoming ray (0.9 of its height over the plane), at most
 * this high (radians, about). */
#define VALID_REFLECTION_HEIGHT 0.01

/* FULL: the normal an interface of a triangle mesh refracts and reflects
 * about, cos_i = dot(n, -d) > 0; ngf: the plane's normal turned to face the
 * ray. The smooth (shading) normal is not the surface: near a silhouette or
 * a sharp crease (the bunny's base) it can face away from a ray that the
 * triangle itself faces. Flipping it by its own sign (facing(): the kernels'
 * rule, which MATCHED keeps) then treats a ray entering the glass as one
 * grazing the far side: the refracted ray bends back out through the plane it
 * entered, the reflection goes into the glass, each with the medium the
 * tracer records for the other side. Here the plane says which side the ray
 * is on, the smooth normal is turned with it, and where the mirror direction
 * about it would not stay on the ray's side it is bent towards the plane's
 * normal, in the plane of the two, just enough that the mirror direction's
 * height over the plane is VALID_REFLECTION_HEIGHT (or 0.9 of the incoming
 * ray's, if lower): Cycles' rule (ensure_valid_reflection, after the Iray
 * system's; Keller et al. 2017), so that both tracers follow one model.
 * The bent normal n' = x X + z ngf (X: the unit part of n normal to ngf,
 * x^2 + z^2 = 1) with mirror height 2 (n'.I) z - I.z = h, I = -d, gives
 * z^2 = (c +- b) / 2a with a = I.x^2 + I.z^2, b = sqrt(I.x^2 (a - h^2)),
 * c = a + h I.z (squaring admits spurious roots: those whose mirror height
 * is not positive are dropped, of two good ones the lower is the smaller
 * bend); no root: the plane's normal. */
static double interface_normal(const ref_surf *s, const double d[3], double n[3], double ngf[3])
{
    double I[3] = {-d[0], -d[1], -d[2]}, side = snell__ref_dot3(s->ng, I) >= 0.0 ? 1.0 : -1.0;
    double h, cos_n, nz, X[3], ix, iz, a, b, c, z2[2], best = -1.0;
    int k, j;
    for (k = 0; k < 3; k++) {
        ngf[k] = side * s->ng[k];
        n[k] = side * s->n[k];
    }
    iz = snell__ref_dot3(ngf, I);
    h = fmin(0.9 * iz, VALID_REFLECTION_HEIGHT);
    cos_n = snell__ref_dot3(n, I);
    nz = snell__ref_dot3(n, ngf);
    if (2.0 * cos_n * nz - iz >= h) return cos_n; /* the mirror direction's height is enough */
    for (k = 0; k < 3; k++) X[k] = n[k] - nz * ngf[k];
    if (!snell__ref_normalize3(X)) { /* n along ngf: nothing to bend towards */
        memcpy(n, ngf, 3 * sizeof(double));
        return iz;
    }
    ix = snell__ref_dot3(I, X);
    a = ix * ix + iz * iz;
    b = sqrt(fmax(ix * ix * (a - h * h), 0.0));
    c = a + h * iz;
    z2[0] = 0.5 * (c + b) / a;
    z2[1] = 0.5 * (c - b) / a;
    for (j = 0; j < 2; j++) {
        double z, x, height;
        if (!(z2[j] > 1e-10 && z2[j] <= 1.0 + 1e-10)) continue;
        z = sqrt(fmin(z2[j], 1.0));
        x = sqrt(fmax(1.0 - z * z, 0.0));
        height = 2.0 * (x * ix + z * iz) * z - iz;
        if (!(height > 1e-10)) continue;
        if (best < 0.0 || height < best) {
            best = height;
            for (k = 0; k < 3; k++) n[k] = x * X[k] + z * ngf[k];
        }
    }
    if (best < 0.0) memcpy(n, ngf, 3 * sizeof(double));
    return snell__ref_dot3(n, I);
}

/* The reflectance of an interface in the mode's model: FULL the exact
 * unpolarised dielectric Fresnel (what real glass and Cycles do), MATCHED the
 * kernels' Schlick. Both are 0 at matched indices. */
static double fresnel(const optics *op, double c, double n1, double n2)
{
    return op->mode == SNELL_REF_FULL || (op->terms & SNELL_REF_TERM_EXACT_FRESNEL)
               ? snell_optd_fresnel_exact(c, n1, n2) : snell_optd_fresnel_schlick(c, n1, n2);
}

/* A thin wall at incidence cosine c: slab reflectance rs, transmittance ts
 * (the mode's Fresnel at both faces), and the refracted chord through it. */
static double slab(const optics *op, const ref_glass *g, double c, double rs[3], double ts[3])
{
    double ior = ior_of(op, g), s2 = (1.0 - c * c) / (ior * ior), ct = sqrt(1.0 - (s2 < 1.0 ? s2 : 1.0));
    snell_optd_thin_slab_model(c, ior, g->sigma, g->thickness, op->mode == SNELL_REF_FULL, rs, ts);
    return g->thickness / (ct > 1e-6 ? ct : 1e-6);
}

/* ------------------------------------------------------------ light path */

static void path_point(snell_ref_path *path, const double p[3], snell_ref_event ev, int object)
{
    int i = path->interfaces;
    if (i >= SNELL_REF_MAX_INTERFACES) return; /* cannot happen: max_if <= SNELL_REF_MAX_INTERFACES */
    path->interfaces = i + 1;
    memcpy(path->points[i + 1], p, 3 * sizeof(double));
    path->events[i + 1] = ev;
    path->objects[i + 1] = object;
}

/* The first hit of the view ray (depth 0) fills the path's summary. */
static void first_hit(snell_ref_path *path, int depth, int found, const ref_surf *s)
{
    if (!path || depth != 0) return;
    path->first_object = found ? s->object : -1;
    path->hit = found && s->object >= 0;
}

/* ------------------------------------------------------------ MATCHED */

/* The GPU model, generalised to a scene: a ray in air (m_air) takes the
 * radiance of what it meets first: the environment, an opaque object, the
 * receiver plane (snell_ref_set_receiver's; not in the water's
 * surroundings, whose own faces end the rays there), or a glass object j,
 * where C = F env'(R) + (1-F) tint T L (solid; L from the refracted chain
 * inside, m_inside) or rs env'(R) + ts tint L (thin wall; L straight on
 * through). env' is again m_air from that surface, which never
 * sees j itself (the GPU draws one surface of j per pixel and looks up an
 * environment j is not in). w: throughput, for pruning side branches; path:
 * the chain being recorded (the refracted/transmitted branch), or NULL. */
static void m_inside(const snell_ref *r, const optics *op, int j, const double p[3], const double t1[3], uint32_t prim,
                     int depth, int split, const double w[3], snell_ref_path *path, double *len, double L[3]);

static void m_surface(const snell_ref *r, const optics *op, const snell__ref_medium *med, const double d[3], int found,
                      const ref_surf *sp, int depth, int reentry, const double w[3], snell_ref_path *path,
                      double rgb[3]);

/* A ray in air from o along d. excl: the glass object it leaves, unseen;
 * reenter (SNELL_REF_TERM_REENTRY, the chain's rays only): it sees excl
 * again, and meeting it re-enters it wholly. */
static void m_air(const snell_ref *r, const optics *op, const double o[3], const double d[3], uint32_t prim, int excl,
                  int reenter, int depth, const double w[3], snell_ref_path *path, double rgb[3])
{
    ref_view v = air_view(op, depth, reenter ? -1 : excl, excl);
    ref_surf s;
    int found, k;
    /* the medium it travels in (with surroundings): where it starts, or at the surface it leaves */
    const snell__ref_medium *med = !op->sur ? NULL : prim == SNELL__BVH_NONE ? op->first : op->sur->at(op->sur->user, o);
    if (!path && max3(w) < MIN_WEIGHT) {
        if (!med || !med->meet(op->sur->user, o, d, HUGE_VAL, rgb)) env_rgb(op, d, rgb);
        return;
    }
    if (reenter && op->isolate && v.glass == REF_SEE_NONE && depth < op->max_if) v.glass = excl;
    found = snell__ref_hit(r, o, d, prim, &v, &s);
    if (!op->sur && snell__ref_plane_hit(r, o, d, found ? s.t : HUGE_VAL, rgb)) { /* the receiver plane first */
        first_hit(path, depth, 0, &s);
        if (path) memcpy(path->exit_dir, d, 3 * sizeof(double));
        return;
    }
    first_hit(path, depth, found, &s);
    reenter = reenter && found && s.object == excl;
    if (med) {
        if (med->meet(op->sur->user, o, d, found ? s.t : HUGE_VAL, rgb)) {
            if (path) memcpy(path->exit_dir, d, 3 * sizeof(double));
            return;
        }
        if (found) { /* through the ambient medium to the object */
            double wa[3];
            for (k = 0; k < 3; k++) wa[k] = w[k] * exp(-med->sigma[k] * s.t);
            m_surface(r, op, med, d, found, &s, depth, reenter, wa, path, rgb);
            for (k = 0; k < 3; k++) rgb[k] *= exp(-med->sigma[k] * s.t);
            return;
        }
    }
    m_surface(r, op, med, d, found, &s, depth, reenter, w, path, rgb);
}

/* m_air's ray d at what it met (found: s, else nothing); reentry: the chain
 * meets the glass it left again (SNELL_REF_TERM_REENTRY): no Fresnel there. */
static void m_surface(const snell_ref *r, const optics *op, const snell__ref_medium *med, const double d[3], int found,
                      const ref_surf *sp, int depth, int reentry, const double w[3], snell_ref_path *path,
                      double rgb[3])
{
    const ref_surf s = *sp;
    const ref_glass *g;
    double n[3], c, refl[3] = {0, 0, 0}, rdir[3], wr[3], wt[3], amb = med ? med->ior : 1.0;
    int k;
    if (!found || s.object < 0) {
        if (found)
            snell__ref_shade_opaque(r, -2 - s.object, &s, rgb);
        else
            env_rgb(op, d, rgb);
        if (path) memcpy(path->exit_dir, d, 3 * sizeof(double));
        return;
    }
    g = &r->glass[s.object];
    c = facing(&s, d, n);
    snell_optd_reflect(d, n, rdir);
    snell__ref_normalize3(rdir);
    if (g->thin) {
        double rs[3], ts[3], L[3], chord = slab(op, g, c, rs, ts);
        if (path) {
            if (path->interfaces == 0) path->fresnel = (rs[0] + rs[1] + rs[2]) / 3.0;
            path_point(path, s.p, SNELL_REF_EVENT_REFRACT, s.object);
            path->inside_length += chord;
        }
        for (k = 0; k < 3; k++) {
            wr[k] = w[k] * rs[k];
            wt[k] = w[k] * ts[k] * g->tint[k];
        }
        m_air(r, op, s.p, rdir, s.prim, s.object, 0, depth + 1, wr, NULL, refl);
        m_air(r, op, s.p, d, s.prim, s.object, 0, depth + 1, wt, path, L);
        for (k = 0; k < 3; k++) rgb[k] = rs[k] * refl[k] + ts[k] * g->tint[k] * L[k];
    } else {
        double F = fresnel(op, c, amb, ior_of(op, g)), t1[3], L[3], len = 0.0, dist, T;
        int tir = !snell_optd_refract(d, n, amb / ior_of(op, g), t1);
        if (tir) F = 1.0; /* IOR < 1 at a grazing angle */
        if (reentry && !tir) F = 0.0;
        if (path) {
            if (path->interfaces == 0) path->fresnel = F;
            path_point(path, s.p, tir ? SNELL_REF_EVENT_TIR : SNELL_REF_EVENT_REFRACT, s.object);
        }
        if (tir) { /* the chain goes on along the reflection */
            m_air(r, op, s.p, rdir, s.prim, s.object, reentry, depth + 1, w, path, rgb);
            return;
        }
        snell__ref_normalize3(t1);
        for (k = 0; k < 3; k++) {
            wr[k] = w[k] * F;
            wt[k] = w[k] * (1.0 - F) * g->tint[k];
        }
        if (F > 0.0) m_air(r, op, s.p, rdir, s.prim, s.object, 0, depth + 1, wr, NULL, refl);
        m_inside(r, op, s.object, s.p, t1, s.prim, depth + 1, !reentry, wt, path, &len, L);
        dist = 0.0;
        if (op->absorb == SNELL_REF_ABSORB_BOUNDING_SPHERE) {
            /* Distance from the entry along t1 to the exit of j's bounding sphere (single.frag). */
            double oc[3] = {s.p[0] - g->bs_c[0], s.p[1] - g->bs_c[1], s.p[2] - g->bs_c[2]};
            double b = snell__ref_dot3(oc, t1), cc = snell__ref_dot3(oc, oc) - g->bs_r * g->bs_r, disc = b * b - cc;
            dist = -b + sqrt(disc > 0.0 ? disc : 0.0);
            if (!(dist > 0.0)) dist = 0.0;
        } else {
            dist = len;
        }
        for (k = 0; k < 3; k++) {
            T = g->has_sigma ? exp(-g->sigma[k] * dist) : 1.0;
            rgb[k] = F * refl[k] + (1.0 - F) * g->tint[k] * T * L[k];
        }
    }
}

int snell__ref_inside(const snell_ref *r, int j, double ior, const snell__ref_surroundings *sur, int max_if,
                      double pos[3], double dir[3], uint32_t *prim, int *depth, double *len, ref_surf *s,
                      double *cos_out, double refl[3], snell_ref_path *path)
{
    ref_view v = inside_view(j);
    for (;;) {
        double n[3], out[3];
        if (!snell__ref_hit(r, pos, dir, *prim, &v, s)) return SNELL__REF_OPEN;
        *len += s->t;
        if (path) path->inside_length += s->t;
        if (s->object < 0) return SNELL__REF_OPAQUE;
        memcpy(pos, s->p, 3 * sizeof(double));
        *prim = s->prim;
        if (*depth >= max_if) return SNELL__REF_CAP;
        *cos_out = facing(s, dir, n);
        ++*depth;
        if (!snell_optd_refract(dir, n, ior / (sur ? sur->at(sur->user, s->p)->ior : 1.0), out)) {
            snell_optd_reflect(dir, n, out);
            snell__ref_normalize3(out);
            if (path) path_point(path, s->p, SNELL_REF_EVENT_TIR, j);
            memcpy(dir, out, 3 * sizeof(double));
            continue;
        }
        snell__ref_normalize3(out);
        if (refl) {
            snell_optd_reflect(dir, n, refl);
            snell__ref_normalize3(refl);
        }
        if (path) path_point(path, s->p, SNELL_REF_EVENT_REFRACT, j);
        memcpy(dir, out, 3 * sizeof(double));
        return SNELL__REF_OUT;
    }
}

/* Beer-Lambert through glass g over length len, per channel. */
static void transmittance(const ref_glass *g, double len, double T[3])
{
    int k;
    for (k = 0; k < 3; k++) T[k] = g->has_sigma ? exp(-g->sigma[k] * len) : 1.0;
}

/* SNELL_REF_TERM_INNER_REFLECTION: what the chain's internal reflection at
 * its first exit sees, from p along refl inside j after the chain's length
 * len: on to its own exit (total reflections followed, the cap counted on
 * from the split), where it all leaves into what it sees without j;
 * absorbed over len and its own length. */
static void m_inner(const snell_ref *r, const optics *op, int j, const double p[3], const double refl[3],
                    uint32_t prim, int depth, double len, const double w[3], double L[3])
{
    const ref_glass *g = &r->glass[j];
    double pos[3], dir[3], wo[3], T[3], cos_out;
    ref_surf s;
    int k;
    memcpy(pos, p, sizeof pos);
    memcpy(dir, refl, sizeof dir);
    if (snell__ref_inside(r, j, ior_of(op, g), op->sur, op->max_if, pos, dir, &prim, &depth, &len, &s, &cos_out, NULL,
                          NULL) == SNELL__REF_OPAQUE) {
        snell__ref_shade_opaque(r, -2 - s.object, &s, L);
        return;
    }
    transmittance(g, len, T);
    for (k = 0; k < 3; k++) wo[k] = w[k] * T[k];
    m_air(r, op, pos, dir, prim, j, 0, depth, wo, NULL, L);
    for (k = 0; k < 3; k++) L[k] *= T[k];
}

/* The refracted chain inside solid glass object j from p along t1
 * (snell__ref_inside), and L what the outgoing ray sees (m_air, j unseen).
 * At the cap, or with no surface ahead (open mesh), the ray leaves
 * unrefracted through the next surface. *len: the path length inside. An
 * opaque object inside the glass ends the chain with its colour. With
 * SNELL_REF_TERM_INNER_REFLECTION and split (the chain's first glass), its
 * exit into air transmits 1 - F and the reflection F adds m_inner's light:
 * L then holds both absorbed, and *len is 0. */
static void m_inside(const snell_ref *r, const optics *op, int j, const double p[3], const double t1[3], uint32_t prim,
                     int depth, int split, const double w[3], snell_ref_path *path, double *len, double L[3])
{
    const ref_glass *g = &r->glass[j];
    double pos[3], dir[3], wo[3], T[3], refl[3], cos_out, F, inner[3];
    ref_surf s;
    int k, end, reenter = (op->terms & SNELL_REF_TERM_REENTRY) != 0;
    memcpy(pos, p, sizeof pos);
    memcpy(dir, t1, sizeof dir);
    *len = 0.0;
    end = snell__ref_inside(r, j, ior_of(op, g), op->sur, op->max_if, pos, dir, &prim, &depth, len, &s, &cos_out,
                            refl, path);
    if (path && end != SNELL__REF_OUT) path->ended_inside = 1;
    if (end == SNELL__REF_OPAQUE) { /* an opaque object in the glass */
        if (path) memcpy(path->exit_dir, dir, 3 * sizeof(double));
        snell__ref_shade_opaque(r, -2 - s.object, &s, L);
        return;
    }
    transmittance(g, *len, T);
    for (k = 0; k < 3; k++) wo[k] = w[k] * T[k];
    m_air(r, op, pos, dir, prim, j, reenter, depth, wo, path, L);
    if (!split || !(op->terms & SNELL_REF_TERM_INNER_REFLECTION) || end != SNELL__REF_OUT) return;
    F = fresnel(op, cos_out, ior_of(op, g), 1.0);
    for (k = 0; k < 3; k++) wo[k] *= F;
    m_inner(r, op, j, pos, refl, prim, depth, *len, wo, inner);
    for (k = 0; k < 3; k++) L[k] = (1.0 - F) * L[k] * T[k] + F * inner[k];
    *len = 0.0;
}

/* ------------------------------------------------------------ FULL */

/* A leaf of the Whitted tree: radiance col reached with throughput w by a
 * branch of probability prob (below). */
static void leaf(const double w[3], double prob, const double col[3], double acc[3], double acc2[3])
{
    int k;
    for (k = 0; k < 3; k++) acc[k] += w[k] * col[k];
    if (acc2)
        for (k = 0; k < 3; k++) acc2[k] += w[k] * w[k] / prob * col[k] * col[k];
}

/* Whitted recursion. medium: the solid glass object the ray is in, -1 air;
 * home: the first glass object of the path (what isolate_glass still shows);
 * w: throughput of this ray; adds its radiance contribution to acc; depth:
 * interfaces already processed on this branch. prob: the probability with
 * which a path tracer that picks one branch per interface by its Fresnel
 * weight (reflection with F, refraction with 1 - F, as Cycles' sharp Glass
 * BSDF does; a thin wall by its mean rs against mean ts) follows this branch;
 * acc2 (NULL: not wanted) sums that tracer's second moment, w^2 / prob * L^2
 * per leaf, so that its per-sample variance is acc2 - acc^2. */
static void whitted(const snell_ref *r, const optics *op, const double o[3], const double d[3], uint32_t prim,
                    int medium, int home, int depth, const double w_in[3], double prob, double acc[3], double acc2[3])
{
    double w[3] = {w_in[0], w_in[1], w_in[2]}, n[3], ngf[3], c, dir_r[3], dir_t[3], col[3], wr[3], wt[3];
    ref_view v = medium >= 0 ? inside_view(medium) : air_view(op, depth, -1, home);
    const ref_glass *g;
    ref_surf s;
    int k, found = max3(w) >= MIN_WEIGHT && snell__ref_hit(r, o, d, prim, &v, &s);
    if (medium < 0 && max3(w) >= MIN_WEIGHT && snell__ref_plane_hit(r, o, d, found ? s.t : HUGE_VAL, col)) {
        leaf(w, prob, col, acc, acc2); /* the receiver plane first */
        return;
    }
    if (!found) {
        env_rgb(op, d, col);
        leaf(w, prob, col, acc, acc2);
        return;
    }
    if (medium >= 0 && r->glass[medium].has_sigma)
        for (k = 0; k < 3; k++) w[k] *= exp(-r->glass[medium].sigma[k] * s.t);
    if (s.object < 0) {
        snell__ref_shade_opaque(r, -2 - s.object, &s, col);
        leaf(w, prob, col, acc, acc2);
        return;
    }
    if (depth >= op->max_if) { /* cap (only met inside): leaves through this surface in its direction */
        whitted(r, op, s.p, d, s.prim, -1, home, depth, w, prob, acc, acc2);
        return;
    }
    g = &r->glass[s.object];
    if (home < 0) home = s.object;
    c = interface_normal(&s, d, n, ngf);
    snell_optd_reflect(d, n, dir_r);
    snell__ref_normalize3(dir_r);
    if (g->thin) { /* every wall is a slab: reflected, or straight through */
        double rs[3], ts[3];
        double pr;
        slab(op, g, c, rs, ts);
        pr = (rs[0] + rs[1] + rs[2]) / (rs[0] + rs[1] + rs[2] + ts[0] + ts[1] + ts[2] + 1e-300);
        for (k = 0; k < 3; k++) {
            wr[k] = w[k] * rs[k];
            wt[k] = w[k] * ts[k] * g->tint[k];
        }
        if (pr > 0.0) whitted(r, op, s.p, dir_r, s.prim, -1, home, depth + 1, wr, prob * pr, acc, acc2);
        if (pr < 1.0) whitted(r, op, s.p, d, s.prim, -1, home, depth + 1, wt, prob * (1.0 - pr), acc, acc2);
    } else {
        int in = medium == s.object, tir;
        double n1 = in ? ior_of(op, g) : 1.0, n2 = in ? 1.0 : ior_of(op, g), F = fresnel(op, c, n1, n2);
        tir = !snell_optd_refract(d, n, n1 / n2, dir_t);
        if (tir) F = 1.0;
        if (F > 0.0) {
            for (k = 0; k < 3; k++) wr[k] = w[k] * F;
            whitted(r, op, s.p, dir_r, s.prim, medium, home, depth + 1, wr, prob * F, acc, acc2);
        }
        if (!tir && F < 1.0) {
            /* The refracted ray is in the medium on the side of the plane it
             * goes to: leaving at a grazing angle about a bent normal it can
             * stay inside (entering, it always crosses). */
            int crosses = snell__ref_dot3(dir_t, ngf) < 0.0, next = crosses ? (in ? -1 : s.object) : medium;
            for (k = 0; k < 3; k++) wt[k] = w[k] * (1.0 - F) * (in || !crosses ? 1.0 : g->tint[k]);
            snell__ref_normalize3(dir_t);
            whitted(r, op, s.p, dir_t, s.prim, next, home, depth + 1, wt, prob * (1.0 - F), acc, acc2);
        }
    }
}

/* The dominant branch of the Whitted tree (at every interface the branch of
 * larger Fresnel weight, refraction on a tie), as a path. */
static void full_walk(const snell_ref *r, const optics *op, const double o[3], const double d[3], snell_ref_path *path)
{
    double pos[3], dir[3];
    uint32_t prim = SNELL__BVH_NONE;
    int medium = -1, home = -1, depth = 0;
    memcpy(pos, o, sizeof pos);
    memcpy(dir, d, sizeof dir);
    for (;;) {
        ref_view v = medium >= 0 ? inside_view(medium) : air_view(op, depth, -1, home);
        const ref_glass *g;
        double n[3], ngf[3], c, out[3];
        snell_ref_event ev;
        ref_surf s;
        int found = snell__ref_hit(r, pos, dir, prim, &v, &s);
        if (medium < 0 && snell__ref_plane_hit(r, pos, dir, found ? s.t : HUGE_VAL, NULL)) found = 0; /* ends there */
        first_hit(path, depth, found, &s);
        if (!found) break;
        if (medium >= 0) path->inside_length += s.t;
        if (s.object < 0 || depth >= op->max_if) break; /* opaque: ends there; cap: leaves in its direction */
        g = &r->glass[s.object];
        if (home < 0) home = s.object;
        c = interface_normal(&s, dir, n, ngf);
        if (g->thin) {
            double rs[3], ts[3], chord = slab(op, g, c, rs, ts);
            if (depth == 0) path->fresnel = (rs[0] + rs[1] + rs[2]) / 3.0;
            if (rs[0] + rs[1] + rs[2] > ts[0] + ts[1] + ts[2]) {
                snell_optd_reflect(dir, n, out);
                ev = SNELL_REF_EVENT_REFLECT;
            } else {
                memcpy(out, dir, sizeof out);
                ev = SNELL_REF_EVENT_REFRACT;
                path->inside_length += chord;
            }
        } else {
            int in = medium == s.object;
            double n1 = in ? ior_of(op, g) : 1.0, n2 = in ? 1.0 : ior_of(op, g), F = fresnel(op, c, n1, n2);
            if (!snell_optd_refract(dir, n, n1 / n2, out)) {
                ev = SNELL_REF_EVENT_TIR;
                F = 1.0;
            } else if (F > 1.0 - F) {
                snell_optd_reflect(dir, n, out);
                ev = SNELL_REF_EVENT_REFLECT;
            } else {
                ev = SNELL_REF_EVENT_REFRACT;
                if (snell__ref_dot3(out, ngf) < 0.0) medium = in ? -1 : s.object; /* as whitted() */
            }
            if (depth == 0) path->fresnel = F;
        }
        snell__ref_normalize3(out);
        path_point(path, s.p, ev, s.object);
        memcpy(pos, s.p, sizeof pos);
        memcpy(dir, out, sizeof dir);
        prim = s.prim;
        depth++;
    }
    memcpy(path->exit_dir, dir, 3 * sizeof(double));
    path->ended_inside = medium >= 0;
}

/* One trace of the ray with the glass at op->channel's IOR. */
static void trace_channel(const snell_ref *r, const optics *op, const double o[3], const double d[3], int want_path,
                          snell_ref_path *path, double moment2[3])
{
    static const double one[3] = {1.0, 1.0, 1.0};
    path->hit = 0;
    path->first_object = -1;
    path->interfaces = 0;
    memcpy(path->points[0], o, 3 * sizeof(double));
    path->events[0] = SNELL_REF_EVENT_EYE;
    path->objects[0] = -1;
    memcpy(path->exit_dir, d, 3 * sizeof(double));
    path->ended_inside = 0;
    path->fresnel = 0.0;
    path->inside_length = 0.0;
    if (op->mode == SNELL_REF_MATCHED) {
        m_air(r, op, o, d, SNELL__BVH_NONE, -1, 0, 0, one, path, path->rgb);
    } else {
        path->rgb[0] = path->rgb[1] = path->rgb[2] = 0.0;
        if (moment2) moment2[0] = moment2[1] = moment2[2] = 0.0;
        whitted(r, op, o, d, SNELL__BVH_NONE, -1, -1, 0, one, 1.0, path->rgb, moment2);
        if (want_path) full_walk(r, op, o, d, path);
    }
}

/* Traces one ray (unit d). want_path: the walk is needed (path outputs) even
 * in FULL mode, where the colour comes from the tree. moment2 (FULL only, NULL
 * = not wanted): the second moment of a branch-sampling path tracer (whitted).
 * With a dispersive glass in the scene, per channel: three traces, the glass
 * at the red, green and blue IOR in turn, each giving its own channel of rgb
 * (and moment2); the path is the green trace's. */
static void trace(const snell_ref *r, const optics *op, const double o[3], const double d[3], int want_path,
                  snell_ref_path *path, double moment2[3])
{
    optics per_channel = *op;
    snell_ref_path other;
    double m2[3];
    int c;
    trace_channel(r, op, o, d, want_path, path, moment2);
    if (!op->disperses) return;
    for (c = 0; c < 3; c += 2) {
        per_channel.channel = c;
        trace_channel(r, &per_channel, o, d, 0, &other, moment2 ? m2 : NULL);
        path->rgb[c] = other.rgb[c];
        if (moment2) moment2[c] = m2[c];
    }
}

/* ------------------------------------------------------------ parameters */

static snell_status resolve(const snell_ref *ref, const snell_ref_params *p, optics *op)
{
    const snell_ctx *ctx = ref->ctx;
    int i;
    if (p->mode != SNELL_REF_MATCHED && p->mode != SNELL_REF_FULL)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: unknown mode %d", (int)p->mode);
    if (p->absorption_model != SNELL_REF_ABSORB_PATH && p->absorption_model != SNELL_REF_ABSORB_BOUNDING_SPHERE)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: unknown absorption model %d",
                           (int)p->absorption_model);
    if (p->terms & ~(unsigned)SNELL_REF_TERMS_ALL)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: unknown terms 0x%x", p->terms);
    if (p->terms && p->absorption_model != SNELL_REF_ABSORB_PATH)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: terms need the path's absorption");
    if (p->max_interfaces < 0 || p->max_interfaces > SNELL_REF_MAX_INTERFACES)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: max_interfaces %d outside 0..%d",
                           p->max_interfaces, SNELL_REF_MAX_INTERFACES);
    if (p->samples < 0 || p->samples > SNELL_REF_MAX_SAMPLES)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: samples %d outside 0..%d", p->samples,
                           SNELL_REF_MAX_SAMPLES);
    if (!p->env && !p->env_fn)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: an environment (env or env_fn) is required");
    if (!p->env_fn && !p->env->faces[0])
        return snell__fail(ctx, p->env->borrowed ? SNELL_E_UNSUPPORTED : SNELL_E_INVALID_ARG,
                           "reference: the environment has no CPU faces%s", p->env->borrowed
                               ? " (SNELL_ENV_GL_TEXTURE samples the host's texture on the GPU only: give the "
                                 "reference env_fn or an environment made from images)" : "");
    memset(op, 0, sizeof *op);
    op->mode = p->mode;
    op->max_if = p->max_interfaces ? p->max_interfaces : 10;
    op->absorb = p->absorption_model;
    op->terms = p->mode == SNELL_REF_MATCHED ? p->terms : 0;
    op->isolate = p->isolate_glass != 0;
    op->env = p->env;
    op->env_fn = p->env_fn;
    op->env_user = p->env_user;
    op->samples = p->samples ? p->samples : 1;
    op->channel = 1; /* green: the material's ior */
    for (i = 0; i < ref->glass_count; i++)
        if (ref->glass[i].res.disperses) op->disperses = 1;
    return SNELL_OK;
}

void snell__ref_trace_matched(const snell_ref *ref, const snell_ref_params *params, const snell__ref_surroundings *sur,
                              const snell__ref_medium *first, const double o[3], const double d[3], double rgb[3])
{
    static const double one[3] = {1.0, 1.0, 1.0};
    snell_ref_params p = *params;
    optics op;
    int c;
    p.mode = SNELL_REF_MATCHED;
    if (resolve(ref, &p, &op) != SNELL_OK) { /* the caller validated params: not reached */
        rgb[0] = rgb[1] = rgb[2] = 0.0;
        return;
    }
    op.sur = sur;
    op.first = first;
    m_air(ref, &op, o, d, SNELL__BVH_NONE, -1, 0, 0, one, NULL, rgb);
    if (!op.disperses) return;
    for (c = 0; c < 3; c += 2) {
        double other[3];
        op.channel = c;
        m_air(ref, &op, o, d, SNELL__BVH_NONE, -1, 0, 0, one, NULL, other);
        rgb[c] = other[c];
    }
}

/* ------------------------------------------------------------ camera rays */

/* Gauss-Jordan with partial pivoting; column-major in and out. */
static int invert4(const double m[16], double out[16])
{
    double a[4][8];
    int i, j, k;
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            a[i][j] = m[4 * j + i]; /* row i, column j */
            a[i][4 + j] = i == j ? 1.0 : 0.0;
        }
    for (k = 0; k < 4; k++) {
        int piv = k;
        double f;
        for (i = k + 1; i < 4; i++)
            if (fabs(a[i][k]) > fabs(a[piv][k])) piv = i;
        if (!(fabs(a[piv][k]) > 0.0) || !isfinite(a[piv][k])) return 0;
        if (piv != k)
            for (j = 0; j < 8; j++) {
                double t = a[k][j];
                a[k][j] = a[piv][j];
                a[piv][j] = t;
            }
        f = 1.0 / a[k][k];
        for (j = 0; j < 8; j++) a[k][j] *= f;
        for (i = 0; i < 4; i++)
            if (i != k) {
                double g = a[i][k];
                for (j = 0; j < 8; j++) a[i][j] -= g * a[k][j];
            }
    }
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) out[4 * j + i] = a[i][4 + j];
    for (i = 0; i < 16; i++)
        if (!isfinite(out[i])) return 0;
    return 1;
}

snell_status snell__ref_camera_setup(snell_ctx *ctx, const snell_ref_params *p, camera_rays *cr)
{
    float eye[3], view[16], proj[16];
    double vp[16];
    int i, j, k;
    snell_status st;
    if (p->width < 0 || p->height < 0)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: negative image size %dx%d", p->width,
                           p->height);
    cr->w = p->width ? p->width : 512;
    cr->h = p->height ? p->height : 512;
    if (cr->w > SNELL_REF_MAX_SIZE || cr->h > SNELL_REF_MAX_SIZE)
        return snell__fail(ctx, SNELL_E_LIMIT, "reference: image %dx%d exceeds %d pixels a side", cr->w, cr->h,
                           SNELL_REF_MAX_SIZE);
    st = snell__camera_validate(ctx, &p->camera, (float)cr->w / (float)cr->h, "reference");
    if (st != SNELL_OK) return st;
    snell__camera_standard(&p->camera, (float)cr->w / (float)cr->h, eye, view, proj);
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            double s = 0.0;
            for (k = 0; k < 4; k++) s += (double)proj[4 * k + i] * (double)view[4 * j + k];
            vp[4 * j + i] = s;
        }
    for (k = 0; k < 3; k++) cr->eye[k] = eye[k];
    cr->ortho = snell__projection_orthographic(proj);
    if (!invert4(vp, cr->inv) || !isfinite(cr->eye[0]) || !isfinite(cr->eye[1]) || !isfinite(cr->eye[2]))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "reference: camera matrices are singular or not finite");
    return SNELL_OK;
}

static void unproject(const double inv[16], double x, double y, double z, double out[3])
{
    double v[4];
    int i;
    for (i = 0; i < 4; i++) v[i] = inv[i] * x + inv[4 + i] * y + inv[8 + i] * z + inv[12 + i];
    for (i = 0; i < 3; i++) out[i] = v[i] / v[3];
}

/* Ray through the point (fx, fy) of pixel (x, y) (0.5, 0.5: its centre), y =
 * 0 the top row (GL's window row h - 1 - y): direction from the near-plane
 * point to the far-plane point. */
void snell__ref_camera_ray(const camera_rays *cr, int x, int y, double fx, double fy, double org[3], double dir[3])
{
    double nx = 2.0 * ((double)x + fx) / (double)cr->w - 1.0;
    double ny = 1.0 - 2.0 * ((double)y + fy) / (double)cr->h;
    double pn[3], pf[3];
    unproject(cr->inv, nx, ny, -1.0, pn);
    unproject(cr->inv, nx, ny, 1.0, pf);
    dir[0] = pf[0] - pn[0];
    dir[1] = pf[1] - pn[1];
    dir[2] = pf[2] - pn[2];
    snell__ref_normalize3(dir);
    memcpy(org, cr->ortho ? pn : cr->eye, 3 * sizeof *org);
}

/* ------------------------------------------------------------ image loop */

typedef struct job {
    const snell_ref *ref;
    const optics *op;
    const camera_rays *cr;
    const snell_ref_output *out;
    pthread_mutex_t lock;
    int next_row;
    snell__ref_progress progress;
} job;

/* Pixel (x, y)'s colour: the mean over its S x S sub-pixel grid (a box
 * filter; S = 1 the centre ray), and with out->sample_var the per-sample
 * variance of a path tracer sampling the same box and branches (FULL). */
static void pixel_colour(job *jb, int x, int y, size_t i)
{
    const camera_rays *cr = jb->cr;
    const snell_ref_output *out = jb->out;
    int S = jb->op->samples, a, b, k;
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, m2[3], org[3];
    snell_ref_path path;
    for (b = 0; b < S; b++)
        for (a = 0; a < S; a++) {
            double dir[3];
            snell__ref_camera_ray(cr, x, y, (a + 0.5) / S, (b + 0.5) / S, org, dir);
            trace(jb->ref, jb->op, org, dir, 0, &path, out->sample_var ? m2 : NULL);
            for (k = 0; k < 3; k++) {
                sum[k] += path.rgb[k];
                /* MATCHED is deterministic per ray: its second moment is rgb^2. */
                sum2[k] += out->sample_var && jb->op->mode == SNELL_REF_FULL ? m2[k] : path.rgb[k] * path.rgb[k];
            }
        }
    for (k = 0; k < 3; k++) {
        double mean = sum[k] / (S * S), var = sum2[k] / (S * S) - mean * mean;
        out->rgb[3 * i + k] = (float)mean;
        if (out->sample_var) out->sample_var[3 * i + k] = (float)(var > 0.0 ? var : 0.0);
    }
}

static void render_row(job *jb, int y)
{
    const camera_rays *cr = jb->cr;
    const snell_ref_output *out = jb->out;
    int want_path = out->exit_dir || out->interfaces || out->hit || out->object;
    int centre_colour = jb->op->samples == 1 && !out->sample_var;
    snell_ref_path path;
    int x, k;
    for (x = 0; x < cr->w; x++) {
        size_t i = (size_t)y * (size_t)cr->w + (size_t)x;
        double dir[3], org[3];
        if (!centre_colour) pixel_colour(jb, x, y, i);
        if (!centre_colour && !want_path) continue;
        snell__ref_camera_ray(cr, x, y, 0.5, 0.5, org, dir);
        trace(jb->ref, jb->op, org, dir, want_path, &path, NULL);
        if (centre_colour)
            for (k = 0; k < 3; k++) out->rgb[3 * i + k] = (float)path.rgb[k];
        if (out->exit_dir)
            for (k = 0; k < 3; k++) out->exit_dir[3 * i + k] = (float)path.exit_dir[k];
        if (out->interfaces) out->interfaces[i] = (uint8_t)path.interfaces;
        if (out->hit) out->hit[i] = (uint8_t)path.hit;
        if (out->object) out->object[i] = (int16_t)path.first_object;
    }
}

/* Rows are handed out one at a time through a counter: the pixels do not
 * depend on which thread computes them, so the image is bitwise the same for
 * any thread count. */
static void *worker(void *arg)
{
    job *jb = (job *)arg;
    int y = -1;
    for (;;) {
        pthread_mutex_lock(&jb->lock);
        if (y >= 0) snell__ref_progress_row(&jb->progress); /* row y is done */
        y = jb->next_row++;
        pthread_mutex_unlock(&jb->lock);
        if (y >= jb->cr->h) break;
        render_row(jb, y);
    }
    return NULL;
}

void snell__ref_progress_init(snell__ref_progress *p, const snell_ref_params *params, int rows)
{
    p->fn = params->progress;
    p->user = params->progress_user;
    p->rows = rows > 0 ? rows : 1;
    p->done = 0;
    p->last_ms = p->fn ? snell__now_ms() : 0.0;
}

void snell__ref_progress_row(snell__ref_progress *p)
{
    double now;
    p->done++;
    if (!p->fn || p->done >= p->rows) return; /* the last row: _end() reports 1.0 */
    now = snell__now_ms();
    if (now - p->last_ms < 100.0) return;
    p->last_ms = now;
    p->fn((double)p->done / p->rows, p->user);
}

void snell__ref_progress_end(snell__ref_progress *p)
{
    if (p->fn) p->fn(1.0, p->user);
}

snell_status snell_ref_render(const snell_ref *ref, const snell_ref_params *params, const snell_ref_output *out)
{
    optics op;
    camera_rays cr;
    job jb;
    pthread_t tids[SNELL_REF_MAX_THREADS];
    int nthreads, started = 0, i;
    snell_status st;
    if (!ref || !params || !out || !out->rgb)
        return snell__fail(ref ? ref->ctx : NULL, SNELL_E_INVALID_ARG,
                           "snell_ref_render: ref, params, out and out->rgb are required");
    if ((st = resolve(ref, params, &op)) != SNELL_OK) return st;
    if ((st = snell__ref_camera_setup(ref->ctx, params, &cr)) != SNELL_OK) return st;
    if (params->threads < 0)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_render: threads %d is negative",
                           params->threads);
    nthreads = params->threads;
    if (nthreads == 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        nthreads = n > 0 ? (int)(n < SNELL_REF_MAX_THREADS ? n : SNELL_REF_MAX_THREADS) : 1;
    }
    if (nthreads > SNELL_REF_MAX_THREADS) nthreads = SNELL_REF_MAX_THREADS;
    if (nthreads > cr.h) nthreads = cr.h;
    jb.ref = ref;
    jb.op = &op;
    jb.cr = &cr;
    jb.out = out;
    jb.next_row = 0;
    snell__ref_progress_init(&jb.progress, params, cr.h);
    if (pthread_mutex_init(&jb.lock, NULL) != 0)
        return snell__fail(ref->ctx, SNELL_E_NOMEM, "snell_ref_render: cannot create a mutex");
    /* The calling thread is worker 0; if a thread cannot be started the others
     * (at least this one) simply take more rows. */
    for (i = 1; i < nthreads; i++) {
        if (pthread_create(&tids[started], NULL, worker, &jb) != 0) break;
        started++;
    }
    worker(&jb);
    for (i = 0; i < started; i++) pthread_join(tids[i], NULL);
    pthread_mutex_destroy(&jb.lock);
    snell__ref_progress_end(&jb.progress);
    return SNELL_OK;
}

void snell_ref_rgb_to_rgba8(const float *rgb, int width, int height, uint8_t *rgba)
{
    size_t i, n;
    if (!rgb || !rgba || width <= 0 || height <= 0) return;
    n = (size_t)width * (size_t)height;
    for (i = 0; i < n; i++) {
        int k;
        for (k = 0; k < 3; k++) {
            float v = rgb[3 * i + k];
            v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* also maps NaN to 0 */
            rgba[4 * i + k] = (uint8_t)(v * 255.0f + 0.5f);
        }
        rgba[4 * i + 3] = 255;
    }
}

/* ------------------------------------------------------------ light paths */

snell_status snell_ref_trace_ray(const snell_ref *ref, const snell_ref_params *params, const double org[3],
                                 const double dir[3], snell_ref_path *path)
{
    optics op;
    double d[3];
    snell_status st;
    int k;
    if (!ref || !params || !org || !dir || !path)
        return snell__fail(ref ? ref->ctx : NULL, SNELL_E_INVALID_ARG,
                           "snell_ref_trace_ray: ref, params, org, dir and path are required");
    if ((st = resolve(ref, params, &op)) != SNELL_OK) return st;
    for (k = 0; k < 3; k++) {
        if (!isfinite(org[k]) || !isfinite(dir[k]))
            return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_trace_ray: ray is not finite");
        d[k] = dir[k];
    }
    if (!snell__ref_normalize3(d)) return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_trace_ray: dir is zero");
    trace(ref, &op, org, d, 1, path, NULL);
    return SNELL_OK;
}

snell_status snell_ref_trace_pixel(const snell_ref *ref, const snell_ref_params *params, int x, int y,
                                   snell_ref_path *path)
{
    optics op;
    camera_rays cr;
    double d[3], org[3];
    snell_status st;
    if (!ref || !params || !path)
        return snell__fail(ref ? ref->ctx : NULL, SNELL_E_INVALID_ARG,
                           "snell_ref_trace_pixel: ref, params and path are required");
    if ((st = resolve(ref, params, &op)) != SNELL_OK) return st;
    if ((st = snell__ref_camera_setup(ref->ctx, params, &cr)) != SNELL_OK) return st;
    if (x < 0 || y < 0 || x >= cr.w || y >= cr.h)
        return snell__fail(ref->ctx, SNELL_E_INVALID_ARG, "snell_ref_trace_pixel: pixel (%d, %d) outside %dx%d", x,
                           y, cr.w, cr.h);
    snell__ref_camera_ray(&cr, x, y, 0.5, 0.5, org, d);
    trace(ref, &op, org, d, 1, path, NULL);
    return SNELL_OK;
}
