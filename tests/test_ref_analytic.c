/* SPDX-License-Identifier: MIT */
/* test_ref_analytic — the reference tracer against closed forms.
 *
 * (a) Sphere. The geometry is the tracer's analytic sphere (ref_trace.h), so
 *     the tracer's own vector optics (optics.h) are compared with the scalar
 *     closed form, not with a tessellation: a ray at impact parameter h from
 *     the centre enters at theta_i = asin(h/r), refracts to theta_t =
 *     asin(sin(theta_i)/n) (Unger eq. 2), crosses the chord 2 r cos(theta_t)
 *     and leaves deviated by 2 (theta_i - theta_t) towards the centre line,
 *     in the plane of d and the centre. Exit direction within 1e-6 rad (the
 *     issue's bound; double precision gives ~1e-14), entry/exit points within
 *     1e-9, 2 interfaces, colour = F + (1-F) exp(-sigma chord) (white env),
 *     and FULL mode equal to the closed Whitted series
 *     F + (1-F)^2 a sum_k (F a)^k, a = exp(-sigma chord).
 * (b) Slab. A mesh box (flat faces, exact axis normals) scaled to a slab of
 *     thickness 1; rays through the two big faces leave parallel to the
 *     incoming direction (within 1e-6 rad) with the lateral offset
 *     t sin(theta_i - theta_t) / cos(theta_t).
 * (c) TIR. A right isosceles (Porro) prism, rays entering the hypotenuse at
 *     normal incidence: at 45 degrees on each leg sin 45 > 1/1.5, so two total
 *     internal reflections and the ray leaves reversed after 4 interfaces with
 *     an inside length of exactly 2 (for every entry point); with n = 1.3
 *     (sin 45 < 1/1.3) it refracts out at the first leg (2 interfaces); the
 *     cap at 3 and 2 interfaces ends inside as documented.
 * Scenes (expected values composed from the closed forms above, a smooth
 * direction-dependent environment so that directions count):
 * (d) two exact spheres, the chain through both (MATCHED; isolate_glass
 *     hides the second); (e) two spheres on an axis: MATCHED's reflection
 *     ping-pong between them and FULL's 1D two-layer stack; (e') a sphere
 *     nested in another is unseen from inside; (f) absorption to the
 *     bounding sphere of the object entered (two cubes); (g) two mesh slabs:
 *     MATCHED, FULL and isolated closed forms, and the same two slabs as one
 *     object (MATCHED never sees the object it leaves); (h) a thin wall:
 *     the slab series in MATCHED (front faces only) and FULL (two walls);
 *     (i) opaque objects seen directly: opaque.frag's colour for the world
 *     normal of a sheared, scaled model, grey default, open quad from behind;
 *     (j) an opaque wall seen through a glass slab, MATCHED and FULL. */
#include "test_util.h"
#include "ref/ref_trace.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void white(const double dir[3], double rgb[3], void *user)
{
    (void)dir;
    (void)user;
    rgb[0] = rgb[1] = rgb[2] = 1.0;
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Angle between two directions, accurate for small angles. */
static double angle(const double a[3], const double b[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return atan2(sqrt(dot(c, c)), dot(a, b));
}

static double dist(const double a[3], const double b[3])
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(dot(d, d));
}

/* MATCHED's Fresnel (the kernels'), air into n. */
static double schlick(double cos_i, double n)
{
    double r0 = (1 - n) / (1 + n), m = 1 - cos_i;
    r0 *= r0;
    return r0 + (1 - r0) * m * m * m * m * m;
}

/* FULL's Fresnel, air into n: the unpolarised mean of the Fresnel equations
 * in their angle form, Rs = sin^2(ti - tt) / sin^2(ti + tt), Rp = tan^2(ti -
 * tt) / tan^2(ti + tt) (optics.h uses the cosine form). Equal from either
 * side of the interface (reciprocity), so F inside equals F outside. */
static double fresnel(double cos_i, double n)
{
    double ti = acos(cos_i), tt, a, b;
    if (ti < 1e-7) return ((n - 1) / (n + 1)) * ((n - 1) / (n + 1));
    tt = asin(sin(ti) / n);
    a = sin(ti - tt) / sin(ti + tt);
    b = tan(ti - tt) / tan(ti + tt);
    return 0.5 * (a * a + b * b);
}

/* Sets glass object i's material (ior; absorption per unit length s0..s2 via
 * the glTF form; tint; thin-wall thickness) and returns in sig (if not NULL)
 * the per-unit absorption the material resolves to (snell_glass_defaults);
 * returns its first channel. */
static double set_glass(snell_ref *ref, int i, double ior, double s0, double s1, double s2, double t0, double t1,
                        double t2, double thickness, double sig[3])
{
    snell_glass_material m;
    snell_glass_resolved res;
    float sg[3];
    memset(&m, 0, sizeof m);
    m.ior = (float)ior;
    sg[0] = (float)s0;
    sg[1] = (float)s1;
    sg[2] = (float)s2;
    snell_glass_set_absorption(&m, sg);
    m.tint[0] = (float)t0;
    m.tint[1] = (float)t1;
    m.tint[2] = (float)t2;
    m.thickness = (float)thickness;
    CHECK_OK(snell_ref_set_material(ref, i, &m));
    CHECK_OK(snell_glass_defaults(&m, &res));
    if (sig) {
        sig[0] = res.absorption[0];
        sig[1] = res.absorption[1];
        sig[2] = res.absorption[2];
    }
    return res.absorption[0];
}

/* A reference of one glass mesh (default material) with a model matrix. */
static snell_ref *one_glass(const snell_mesh *m, const float *model)
{
    snell_glass g;
    snell_ref_desc rd;
    snell_ref *ref = NULL;
    memset(&g, 0, sizeof g);
    memset(&rd, 0, sizeof rd);
    g.mesh = m;
    g.model = model;
    rd.glass = &g;
    rd.glass_count = 1;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    return ref;
}

static void sphere_tests(void)
{
    const double c[3] = {0.2, -0.1, 0.3}, r = 0.8;
    /* The tracer takes a float IOR: the closed form uses the same value. */
    const double iors[3] = {1.5, (double)1.33f, (double)2.4f};
    snell_ref *ref = NULL;
    snell_ref_params p;
    int ii, tested = 0, bad_dir = 0, bad_pts = 0, bad_count = 0, bad_col = 0, bad_full = 0;
    double worst = 0.0, worst_pt = 0.0;
    CHECK_OK(snell__ref_create_sphere(NULL, c, r, &ref));
    if (!ref) return;
    memset(&p, 0, sizeof p);
    p.env_fn = white;
    for (ii = 0; ii < 3; ii++) {
        int gx, gy, eyes;
        double sig = set_glass(ref, 0, iors[ii], 0.7, 0.7, 0.7, 1, 1, 1, 0.0, NULL);
        for (eyes = 0; eyes < 2; eyes++)
            for (gy = 0; gy < 41; gy++)
                for (gx = 0; gx < 41; gx++) {
                    /* eyes 0: parallel rays along a tilted direction; 1: rays
                     * from one eye point (perspective). */
                    double o[3], d[3], oc[3], perp[3], h, e[3], ti, tt, dev, want[3], t1, P1[3], T1[3], P2[3], chord, F,
                        a, col, full, series = 0.0, fa;
                    snell_ref_path path;
                    int k, q;
                    double u = (gx - 20) / 20.0 * 1.05 * r, v = (gy - 20) / 20.0 * 1.05 * r;
                    if (eyes == 0) {
                        double dd[3] = {0.3, -0.2, -1.0}, ax[3] = {1, 0, 0.3}, ay[3] = {0, 1, -0.2};
                        double l = sqrt(dot(dd, dd));
                        for (k = 0; k < 3; k++) {
                            d[k] = dd[k] / l;
                            o[k] = c[k] - 4.0 * d[k] + u * ax[k] / sqrt(1.09) + v * ay[k] / sqrt(1.04);
                        }
                    } else {
                        double eye[3] = {1.0, 2.0, 3.5};
                        for (k = 0; k < 3; k++) o[k] = eye[k];
                        d[0] = c[0] + u - eye[0];
                        d[1] = c[1] + v - eye[1];
                        d[2] = c[2] - eye[2];
                        {
                            double l = sqrt(dot(d, d));
                            for (k = 0; k < 3; k++) d[k] /= l;
                        }
                    }
                    for (k = 0; k < 3; k++) oc[k] = o[k] - c[k];
                    for (k = 0; k < 3; k++) perp[k] = oc[k] - dot(oc, d) * d[k];
                    h = sqrt(dot(perp, perp));
                    p.mode = SNELL_REF_MATCHED;
                    CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
                    if (h >= r * 0.9999) {
                        if (h > r * 1.0001 && path.hit) bad_count++;
                        continue;
                    }
                    tested++;
                    /* Closed form. e: unit vector from the centre line to the ray. */
                    for (k = 0; k < 3; k++) e[k] = h > 0 ? perp[k] / h : 0.0;
                    ti = asin(h / r);
                    tt = asin(sin(ti) / iors[ii]);
                    dev = 2.0 * (ti - tt);
                    for (k = 0; k < 3; k++) want[k] = cos(dev) * d[k] - sin(dev) * e[k];
                    t1 = -dot(oc, d) - sqrt(r * r - h * h);
                    for (k = 0; k < 3; k++) {
                        P1[k] = o[k] + t1 * d[k];
                        T1[k] = cos(ti - tt) * d[k] - sin(ti - tt) * e[k];
                    }
                    chord = 2.0 * r * cos(tt);
                    for (k = 0; k < 3; k++) P2[k] = P1[k] + chord * T1[k];
                    if (path.interfaces != 2 || path.events[1] != SNELL_REF_EVENT_REFRACT ||
                        path.events[2] != SNELL_REF_EVENT_REFRACT || path.ended_inside || !path.hit)
                        bad_count++;
                    {
                        double ang = angle(path.exit_dir, want);
                        if (ang > worst) worst = ang;
                        if (ang > 1e-6) bad_dir++;
                    }
                    if (path.interfaces == 2) {
                        double e1 = dist(path.points[1], P1), e2 = dist(path.points[2], P2);
                        double ep = e1 > e2 ? e1 : e2;
                        if (ep > worst_pt) worst_pt = ep;
                        if (ep > 1e-9 || fabs(path.inside_length - chord) > 1e-9) bad_pts++;
                    }
                    /* MATCHED colour with a white environment. */
                    F = schlick(cos(ti), iors[ii]);
                    a = exp(-sig * chord);
                    col = F + (1 - F) * a;
                    for (q = 0; q < 3; q++)
                        if (fabs(path.rgb[q] - col) > 1e-9 || fabs(path.fresnel - F) > 1e-12) {
                            if (bad_col < 3)
                                fprintf(stderr, "h/r %.4f n %.3f: rgb %.12f want %.12f, F %.12f want %.12f\n", h / r,
                                        iors[ii], path.rgb[q], col, path.fresnel, F);
                            bad_col++;
                        }
                    /* Single-surface configuration: absorption to the bounding
                     * sphere (= the sphere) gives the same colour. */
                    p.max_interfaces = 1;
                    p.absorption_model = SNELL_REF_ABSORB_BOUNDING_SPHERE;
                    CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
                    if (path.interfaces != 1 || angle(path.exit_dir, T1) > 1e-9 || !path.ended_inside ||
                        fabs(path.rgb[0] - col) > 1e-9 || fabs(path.inside_length - chord) > 1e-9)
                        bad_col++;
                    p.max_interfaces = 0;
                    p.absorption_model = SNELL_REF_ABSORB_PATH;
                    /* FULL: the Whitted series with the exact Fresnel F,
                     * equal inside and outside (reciprocity). Terms below
                     * 1e-5 are pruned (ref_trace.c), so compare to 1e-4. */
                    if (h < 0.8 * r) {
                        p.mode = SNELL_REF_FULL;
                        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
                        F = fresnel(cos(ti), iors[ii]);
                        fa = F * a;
                        for (k = 0; k < 8; k++) series += pow(fa, k);
                        full = F + (1 - F) * (1 - F) * a * series;
                        if (fabs(path.rgb[0] - full) > 1e-4 || path.interfaces != 2) bad_full++;
                    }
                }
    }
    printf("sphere: %d rays, worst exit-direction error %.3g rad, worst point error %.3g\n", tested, worst,
           worst_pt);
    CHECK(tested > 2000, "only %d rays hit the sphere", tested);
    CHECK(bad_dir == 0, "%d exit directions off the closed form by > 1e-6 rad (worst %.3g)", bad_dir, worst);
    CHECK(bad_pts == 0, "%d entry/exit points or chords off the closed form", bad_pts);
    CHECK(bad_count == 0, "%d rays with a wrong interface count or events", bad_count);
    CHECK(bad_col == 0, "%d MATCHED colours off the closed form", bad_col);
    CHECK(bad_full == 0, "%d FULL colours off the Whitted series", bad_full);
    snell_ref_destroy(ref);
}

static void slab_tests(void)
{
    snell_shape_desc sd;
    snell_mesh *cube = NULL;
    snell_ref *ref = NULL;
    snell_ref_params p;
    /* Box [-1,1]^3 scaled to 6 x 6 x 1: the slab -0.5 <= z <= 0.5. */
    float model[16] = {3, 0, 0, 0, 0, 3, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1};
    int i, tested = 0, bad = 0;
    double worst = 0.0, worst_off = 0.0;
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &cube));
    if (!cube) return;
    ref = one_glass(cube, model);
    if (!ref) {
        snell_mesh_destroy(cube);
        return;
    }
    memset(&p, 0, sizeof p);
    p.env_fn = white;
    for (i = 0; i < 400; i++) {
        double n = (i % 2) ? 1.5 : (double)1.7f;
        double th = (i / 20) * (1.4 / 19.0), ph = (i % 20) * (2 * 3.14159265358979 / 20);
        double d[3] = {sin(th) * cos(ph), sin(th) * sin(ph), -cos(th)};
        double target[3] = {0.37 * cos(i * 0.7), 0.41 * sin(i * 1.3), 0.5}, o[3], tt, off, cr[3], seg[3];
        snell_ref_path path;
        int k;
        set_glass(ref, 0, n, 0, 0, 0, 1, 1, 1, 0.0, NULL);
        for (k = 0; k < 3; k++) o[k] = target[k] - 3.0 * d[k];
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        tested++;
        tt = asin(sin(th) / n);
        if (path.interfaces != 2 || path.ended_inside || fabs(path.points[1][2] - 0.5) > 1e-12 ||
            fabs(path.points[2][2] + 0.5) > 1e-12) {
            bad++;
            continue;
        }
        {
            double a = angle(path.exit_dir, d);
            if (a > worst) worst = a;
            if (a > 1e-6) bad++;
        }
        for (k = 0; k < 3; k++) seg[k] = path.points[2][k] - path.points[1][k];
        cr[0] = seg[1] * d[2] - seg[2] * d[1];
        cr[1] = seg[2] * d[0] - seg[0] * d[2];
        cr[2] = seg[0] * d[1] - seg[1] * d[0];
        off = sqrt(dot(cr, cr));
        {
            double want = 1.0 * sin(th - tt) / cos(tt);
            if (fabs(off - want) > worst_off) worst_off = fabs(off - want);
            if (fabs(off - want) > 1e-9) bad++;
            if (fabs(path.inside_length - 1.0 / cos(tt)) > 1e-9) bad++;
        }
    }
    printf("slab: %d rays, worst exit-direction error %.3g rad, worst lateral offset error %.3g\n", tested, worst,
           worst_off);
    CHECK(bad == 0, "%d slab rays off the closed form", bad);
    snell_ref_destroy(ref);
    snell_mesh_destroy(cube);
}

/* Right isosceles prism: cross-section (x, z) hypotenuse (-1,0)-(1,0) on top,
 * right angle at (0,-1); extruded over -2 <= y <= 2. Flat faces. */
static snell_mesh *make_prism(void)
{
    const double s = sqrt(0.5);
    /* 5 faces; per face its vertices (CCW seen from outside) and normal. */
    static const float quads[3][4][3] = {
        {{-1, -2, 0}, {1, -2, 0}, {1, 2, 0}, {-1, 2, 0}},    /* top (hypotenuse), normal +z */
        {{1, -2, 0}, {0, -2, -1}, {0, 2, -1}, {1, 2, 0}},    /* leg x > 0, normal (1,0,-1)/sqrt2 */
        {{0, -2, -1}, {-1, -2, 0}, {-1, 2, 0}, {0, 2, -1}}}; /* leg x < 0, normal (-1,0,-1)/sqrt2 */
    float pos[18 * 3], nrm[18 * 3];
    uint32_t idx[8 * 3];
    const float qn[3][3] = {{0, 0, 1}, {(float)s, 0, (float)-s}, {(float)-s, 0, (float)-s}};
    int f, k, nv = 0, nt = 0;
    snell_mesh_desc md;
    snell_mesh *m = NULL;
    for (f = 0; f < 3; f++) {
        for (k = 0; k < 4; k++) {
            memcpy(pos + 3 * (nv + k), quads[f][k], sizeof(float) * 3);
            memcpy(nrm + 3 * (nv + k), qn[f], sizeof(float) * 3);
        }
        idx[3 * nt] = nv; idx[3 * nt + 1] = nv + 1; idx[3 * nt + 2] = nv + 2; nt++;
        idx[3 * nt] = nv; idx[3 * nt + 1] = nv + 2; idx[3 * nt + 2] = nv + 3; nt++;
        nv += 4;
    }
    for (f = 0; f < 2; f++) { /* end caps y = -2 (normal -y) and y = +2 (normal +y) */
        float y = f ? 2.0f : -2.0f;
        float tri[3][3] = {{-1, 0, 0}, {1, 0, 0}, {0, 0, -1}};
        for (k = 0; k < 3; k++) {
            pos[3 * (nv + k)] = tri[k][0];
            pos[3 * (nv + k) + 1] = y;
            pos[3 * (nv + k) + 2] = tri[k][2];
            nrm[3 * (nv + k)] = 0;
            nrm[3 * (nv + k) + 1] = f ? 1.0f : -1.0f;
            nrm[3 * (nv + k) + 2] = 0;
        }
        idx[3 * nt] = nv; idx[3 * nt + 1] = nv + (f ? 1 : 2); idx[3 * nt + 2] = nv + (f ? 2 : 1); nt++;
        nv += 3;
    }
    memset(&md, 0, sizeof md);
    md.positions = pos;
    md.normals = nrm;
    md.indices = idx;
    md.vertex_count = (uint32_t)nv;
    md.triangle_count = (uint32_t)nt;
    CHECK_OK(snell_mesh_create(NULL, &md, &m));
    return m;
}

static void tir_tests(void)
{
    snell_mesh *prism = make_prism();
    snell_ref *ref = NULL;
    snell_ref_params p;
    int i, bad4 = 0, bad3 = 0, bad2 = 0, bad13 = 0, badfull = 0;
    if (!prism) return;
    ref = one_glass(prism, NULL);
    if (!ref) {
        snell_mesh_destroy(prism);
        return;
    }
    memset(&p, 0, sizeof p);
    p.env_fn = white;
    for (i = 0; i < 60; i++) {
        /* Entry points away from the apex line x = 0 and the rims x = +-1. */
        double x0 = (i % 2 ? 1 : -1) * (0.05 + 0.9 * (i / 2) / 29.0), y0 = -1.5 + 3.0 * i / 59.0;
        double o[3] = {x0, y0, 2.0}, d[3] = {0, 0, -1}, up[3] = {0, 0, 1}, side[3] = {x0 > 0 ? -1 : 1, 0, 0};
        snell_ref_path path;
        double sig = set_glass(ref, 0, 1.5, 0.25, 0, 0, 1, 1, 1, 0.0, NULL);
        p.mode = SNELL_REF_MATCHED;
        p.max_interfaces = 0;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        if (path.interfaces != 4 || path.events[1] != SNELL_REF_EVENT_REFRACT ||
            path.events[2] != SNELL_REF_EVENT_TIR || path.events[3] != SNELL_REF_EVENT_TIR ||
            path.events[4] != SNELL_REF_EVENT_REFRACT || path.ended_inside || angle(path.exit_dir, up) > 1e-9 ||
            fabs(path.points[4][0] + x0) > 1e-9 || fabs(path.inside_length - 2.0) > 1e-9 ||
            fabs(path.rgb[0] - (0.04 + 0.96 * exp(-sig * 2.0))) > 1e-9 || fabs(path.rgb[1] - 1.0) > 1e-9)
            bad4++;
        p.max_interfaces = 3; /* cap after the second TIR: leaves upwards from inside */
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        if (path.interfaces != 3 || !path.ended_inside || angle(path.exit_dir, up) > 1e-9 ||
            fabs(path.inside_length - 2.0) > 1e-9)
            bad3++;
        p.max_interfaces = 2; /* cap after the first TIR: leaves sideways */
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        if (path.interfaces != 2 || !path.ended_inside || angle(path.exit_dir, side) > 1e-9 ||
            fabs(path.inside_length - (1.0 + fabs(x0))) > 1e-9)
            bad2++;
        /* n = 1.3: sin 45 < 1/1.3, refracted out of the first leg at
         * theta = asin(1.3 sin 45) from the leg normal. */
        set_glass(ref, 0, 1.3, 0.25, 0, 0, 1, 1, 1, 0.0, NULL);
        p.max_interfaces = 0;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        {
            double s = sqrt(0.5), nx = x0 > 0 ? s : -s, th = asin((double)1.3f * s);
            /* Leg normal n = (nx, 0, -s); in the plane, tangent u = (-s*sgn, 0, -s)... take the
             * component of d along the leg (pointing away from the normal side) */
            double nl[3] = {nx, 0, -s}, tan_[3], want[3];
            int k;
            double dn = dot(d, nl);
            for (k = 0; k < 3; k++) tan_[k] = d[k] - dn * nl[k];
            {
                double l = sqrt(dot(tan_, tan_));
                for (k = 0; k < 3; k++) want[k] = cos(th) * nl[k] + sin(th) * tan_[k] / l;
            }
            if (path.interfaces != 2 || path.events[2] != SNELL_REF_EVENT_REFRACT || path.ended_inside ||
                angle(path.exit_dir, want) > 1e-6)
                bad13++;
        }
        /* FULL, white env, no absorption: energy 1; dominant branch = the TIR chain. */
        p.mode = SNELL_REF_FULL;
        set_glass(ref, 0, 1.5, 0, 0, 0, 1, 1, 1, 0.0, NULL);
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        if (path.interfaces != 4 || path.events[2] != SNELL_REF_EVENT_TIR || fabs(path.rgb[0] - 1.0) > 1e-12)
            badfull++;
    }
    CHECK(bad4 == 0, "%d prism rays without the predicted 2 TIRs (4 interfaces, inside length 2)", bad4);
    CHECK(bad3 == 0, "%d prism rays with a wrong cap at 3 interfaces", bad3);
    CHECK(bad2 == 0, "%d prism rays with a wrong cap at 2 interfaces", bad2);
    CHECK(bad13 == 0, "%d prism rays (n = 1.3) not refracted out at the first leg", bad13);
    CHECK(badfull == 0, "%d prism rays wrong in FULL mode", badfull);
    snell_ref_destroy(ref);
    snell_mesh_destroy(prism);
}

/* ------------------------------------------------------------ scenes */

/* A smooth environment that tells directions apart (every channel 0.15..0.95). */
static void sky(const double d[3], double rgb[3], void *user)
{
    (void)user;
    rgb[0] = 0.55 + 0.25 * d[0] + 0.1 * d[2];
    rgb[1] = 0.5 + 0.3 * d[1];
    rgb[2] = 0.6 - 0.3 * d[2];
}

static void unit(double v[3])
{
    double l = sqrt(dot(v, v));
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
}

/* Mirror direction of unit d at unit normal n. */
static void mirror(const double d[3], const double n[3], double r[3])
{
    double k = 2.0 * dot(d, n);
    int i;
    for (i = 0; i < 3; i++) r[i] = d[i] - k * n[i];
}

/* The closed-form passage of the ray o + t d (unit d) through the sphere
 * (c, rad) of index n (as in (a)): entry P1, refracted T1, exit P2, exit
 * direction out, mirror direction R at P1, chord and incidence cosine.
 * 0 if the ray misses, nearly grazes (1e-4 of the radius) or the sphere is behind. */
typedef struct pass {
    double P1[3], T1[3], P2[3], out[3], R[3], chord, cos_i;
} pass;

static int sphere_pass(const double o[3], const double d[3], const double c[3], double rad, double n, pass *ps)
{
    double oc[3], perp[3], e[3], nrm[3], b, h, ti, tt, t1, dev;
    int k;
    for (k = 0; k < 3; k++) oc[k] = o[k] - c[k];
    b = dot(oc, d);
    for (k = 0; k < 3; k++) perp[k] = oc[k] - b * d[k];
    h = sqrt(dot(perp, perp));
    if (h >= rad * 0.9999) return 0;
    t1 = -b - sqrt(rad * rad - h * h);
    if (!(t1 > 1e-6)) return 0;
    for (k = 0; k < 3; k++) e[k] = h > 0 ? perp[k] / h : 0.0;
    ti = asin(h / rad);
    tt = asin(sin(ti) / n);
    dev = 2.0 * (ti - tt);
    for (k = 0; k < 3; k++) {
        ps->P1[k] = o[k] + t1 * d[k];
        ps->T1[k] = cos(ti - tt) * d[k] - sin(ti - tt) * e[k];
        ps->out[k] = cos(dev) * d[k] - sin(dev) * e[k];
        nrm[k] = (ps->P1[k] - c[k]) / rad;
    }
    ps->chord = 2.0 * rad * cos(tt);
    for (k = 0; k < 3; k++) ps->P2[k] = ps->P1[k] + ps->chord * ps->T1[k];
    mirror(d, nrm, ps->R);
    ps->cos_i = cos(ti);
    return 1;
}

/* 1 if the ray o + t d, t > 0, comes within 1.0001 radii of the sphere (c, rad). */
static int near_sphere(const double o[3], const double d[3], const double c[3], double rad)
{
    double oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]}, b = dot(oc, d), perp[3];
    int k;
    for (k = 0; k < 3; k++) perp[k] = oc[k] - b * d[k];
    if (dot(oc, oc) <= rad * rad * 1.0002) return 1;
    return b < 0.0 && dot(perp, perp) < rad * rad * 1.0002;
}

/* (d) Two exact spheres, B behind A: the MATCHED chain enters A, leaves it,
 * enters B and leaves B; each object its own IOR, absorption and tint. With
 * the smooth `sky` environment C = F_A sky(R_A) + (1-F_A) tint_A a_A L, L =
 * F_B sky(R_B) + (1-F_B) tint_B a_B sky(out_B) when the ray leaving A meets
 * B, else sky(out_A); a = exp(-sigma chord). Rays whose mirror branches meet
 * the other sphere are left out (their closed form has more terms); those
 * that meet B must be many. isolate_glass: L = sky(out_A) always, 2
 * interfaces. Points, exit directions, object of every point, colour. */
static void two_sphere_tests(void)
{
    const double cen[6] = {0.0, 0.0, 0.0, 0.35, -0.2, -2.6}, rad[2] = {0.8, 0.9}, eye[3] = {0.2, 0.3, 4.0};
    const double ior[2] = {1.5, (double)1.7f};
    static const float tint[2][3] = {{1, 0.9f, 0.8f}, {0.7f, 1, 0.9f}}; /* the material's float values */
    double sig[2][3];
    snell_ref *ref = NULL;
    snell_ref_params p;
    int gx, gy, tested = 0, both = 0, bad = 0, bad_iso = 0, bad_path = 0;
    double worst = 0.0;
    CHECK_OK(snell__ref_create_spheres(NULL, 2, cen, rad, &ref));
    if (!ref) return;
    set_glass(ref, 0, ior[0], 0.3, 0.6, 0.1, tint[0][0], tint[0][1], tint[0][2], 0.0, sig[0]);
    set_glass(ref, 1, ior[1], 0.5, 0.2, 0.9, tint[1][0], tint[1][1], tint[1][2], 0.0, sig[1]);
    memset(&p, 0, sizeof p);
    p.env_fn = sky;
    for (gy = 0; gy < 45; gy++)
        for (gx = 0; gx < 45; gx++) {
            double d[3] = {(gx - 22) / 22.0 * 0.82 - eye[0], (gy - 22) / 22.0 * 0.82 - eye[1], -eye[2]};
            double want[3], iso[3], eA[3], eB[3], eR[3], eRB[3], FA, FB = 0.0;
            pass a, b;
            snell_ref_path path;
            int k, hitsB;
            unit(d);
            if (!sphere_pass(eye, d, cen, rad[0], ior[0], &a)) continue;
            if (near_sphere(a.P1, a.R, cen + 3, rad[1])) continue;
            hitsB = sphere_pass(a.P2, a.out, cen + 3, rad[1], ior[1], &b);
            if (!hitsB && near_sphere(a.P2, a.out, cen + 3, rad[1])) continue; /* grazes B */
            if (hitsB && (near_sphere(b.P1, b.R, cen, rad[0]) || near_sphere(b.P2, b.out, cen, rad[0]))) continue;
            tested++;
            both += hitsB;
            FA = schlick(a.cos_i, ior[0]);
            sky(a.R, eR, NULL);
            sky(a.out, eA, NULL);
            if (hitsB) {
                FB = schlick(b.cos_i, ior[1]);
                sky(b.R, eRB, NULL);
                sky(b.out, eB, NULL);
            }
            for (k = 0; k < 3; k++) {
                double aA = exp(-sig[0][k] * a.chord), L;
                L = hitsB ? FB * eRB[k] + (1 - FB) * tint[1][k] * exp(-sig[1][k] * b.chord) * eB[k] : eA[k];
                want[k] = FA * eR[k] + (1 - FA) * tint[0][k] * aA * L;
                iso[k] = FA * eR[k] + (1 - FA) * tint[0][k] * aA * eA[k];
            }
            p.isolate_glass = 0;
            CHECK_OK(snell_ref_trace_ray(ref, &p, eye, d, &path));
            for (k = 0; k < 3; k++) {
                if (fabs(path.rgb[k] - want[k]) > worst) worst = fabs(path.rgb[k] - want[k]);
                if (fabs(path.rgb[k] - want[k]) > 1e-9) bad++;
            }
            if (path.interfaces != (hitsB ? 4 : 2) || !path.hit || path.first_object != 0 || path.objects[0] != -1 ||
                path.objects[1] != 0 || path.objects[2] != 0 || dist(path.points[1], a.P1) > 1e-9 ||
                dist(path.points[2], a.P2) > 1e-9 || path.ended_inside ||
                angle(path.exit_dir, hitsB ? b.out : a.out) > 1e-9 ||
                fabs(path.inside_length - a.chord - (hitsB ? b.chord : 0.0)) > 1e-9)
                bad_path++;
            if (hitsB && (path.objects[3] != 1 || path.objects[4] != 1 || dist(path.points[3], b.P1) > 1e-9 ||
                          dist(path.points[4], b.P2) > 1e-9 || path.events[3] != SNELL_REF_EVENT_REFRACT))
                bad_path++;
            p.isolate_glass = 1;
            CHECK_OK(snell_ref_trace_ray(ref, &p, eye, d, &path));
            for (k = 0; k < 3; k++)
                if (fabs(path.rgb[k] - iso[k]) > 1e-9) bad_iso++;
            if (path.interfaces != 2 || angle(path.exit_dir, a.out) > 1e-9) bad_iso++;
        }
    printf("two spheres: %d rays, %d through both, worst colour error %.3g\n", tested, both, worst);
    CHECK(tested > 800 && both > 300, "only %d rays (%d through both spheres)", tested, both);
    CHECK(bad == 0, "%d MATCHED colours through two spheres off the closed form", bad);
    CHECK(bad_path == 0, "%d paths through two spheres off the closed form", bad_path);
    CHECK(bad_iso == 0, "%d isolate_glass rays see the second sphere", bad_iso);
    snell_ref_destroy(ref);
}

/* (e) Two exact spheres on the z axis, a ray along it (normal incidence,
 * F = ((n-1)/(n+1))^2 at all four surfaces, a = exp(-sigma 2 r)). MATCHED:
 * the reflection at B's front meets A's back, whose reflection meets B again:
 * X = [F_B (1-F_A) t_A a_A env(+z) + (1-F_B) t_B a_B env(-z)] / (1 - F_A F_B)
 * is the radiance arriving at B, and C = F_A env(+z) + (1-F_A) t_A a_A X.
 * FULL: the 1D stack of two layers, each R = F + (1-F)^2 t F a^2 / (1 - F^2
 * a^2), T = (1-F)^2 t a / (1 - F^2 a^2) (tint t at each entering refraction):
 * C = T_A T_B / (1 - R_A R_B) env(-z) + (R_A + T_A^2 R_B / (1 - R_A R_B)) env(+z).
 * isolate_glass: A alone. The ping-pong is cut where a branch's weight falls
 * below 1e-5 (ref_trace.c): MATCHED within 2e-5 (1e-9 isolated), FULL 1e-4. */
static void axis_tests(void)
{
    const double cen[6] = {0, 0, 0, 0, 0, -3.0}, rad[2] = {0.8, 0.6}, o[3] = {0, 0, 5}, d[3] = {0, 0, -1},
                 up[3] = {0, 0, 1};
    const double ior[2] = {1.5, (double)2.4f};
    static const float tint[2][3] = {{1, 0.9f, 0.8f}, {0.7f, 1, 0.9f}};
    double sig[2][3], env_d[3], env_u[3];
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_ref_path path;
    int k, iso;
    CHECK_OK(snell__ref_create_spheres(NULL, 2, cen, rad, &ref));
    if (!ref) return;
    set_glass(ref, 0, ior[0], 0.3, 0.6, 0.1, tint[0][0], tint[0][1], tint[0][2], 0.0, sig[0]);
    set_glass(ref, 1, ior[1], 0.5, 0.2, 0.9, tint[1][0], tint[1][1], tint[1][2], 0.0, sig[1]);
    sky(d, env_d, NULL);
    sky(up, env_u, NULL);
    memset(&p, 0, sizeof p);
    p.env_fn = sky;
    p.max_interfaces = SNELL_REF_MAX_INTERFACES;
    for (iso = 0; iso < 2; iso++) {
        double m_want[3], f_want[3], worst = 0.0;
        for (k = 0; k < 3; k++) {
            double F[2], a[2], R[2], T[2], X;
            int i;
            for (i = 0; i < 2; i++) {
                F[i] = (ior[i] - 1) * (ior[i] - 1) / ((ior[i] + 1) * (ior[i] + 1));
                a[i] = exp(-sig[i][k] * 2.0 * rad[i]);
                R[i] =
                    F[i] + (1 - F[i]) * (1 - F[i]) * tint[i][k] * F[i] * a[i] * a[i] / (1 - F[i] * F[i] * a[i] * a[i]);
                T[i] = (1 - F[i]) * (1 - F[i]) * tint[i][k] * a[i] / (1 - F[i] * F[i] * a[i] * a[i]);
            }
            if (iso) {
                m_want[k] = F[0] * env_u[k] + (1 - F[0]) * tint[0][k] * a[0] * env_d[k];
                f_want[k] = T[0] * env_d[k] + R[0] * env_u[k];
            } else {
                X = (F[1] * (1 - F[0]) * tint[0][k] * a[0] * env_u[k] + (1 - F[1]) * tint[1][k] * a[1] * env_d[k]) /
                    (1 - F[0] * F[1]);
                m_want[k] = F[0] * env_u[k] + (1 - F[0]) * tint[0][k] * a[0] * X;
                f_want[k] = T[0] * T[1] / (1 - R[0] * R[1]) * env_d[k] +
                            (R[0] + T[0] * T[0] * R[1] / (1 - R[0] * R[1])) * env_u[k];
            }
        }
        p.isolate_glass = iso;
        p.mode = SNELL_REF_MATCHED;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        for (k = 0; k < 3; k++)
            CHECK(fabs(path.rgb[k] - m_want[k]) < (iso ? 1e-9 : 2e-5),
                  "axis MATCHED isolate %d channel %d: %.12f, want %.12f", iso, k, path.rgb[k], m_want[k]);
        CHECK(path.interfaces == (iso ? 2 : 4) && angle(path.exit_dir, d) < 1e-12, "axis MATCHED path: %d interfaces",
              path.interfaces);
        p.mode = SNELL_REF_FULL;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        for (k = 0; k < 3; k++) {
            if (fabs(path.rgb[k] - f_want[k]) > worst) worst = fabs(path.rgb[k] - f_want[k]);
            CHECK(fabs(path.rgb[k] - f_want[k]) < 1e-4, "axis FULL isolate %d channel %d: %.9f, want %.9f", iso, k,
                  path.rgb[k], f_want[k]);
        }
        CHECK(path.interfaces == (iso ? 2 : 4) && path.objects[3 - 2 * iso] == 1 - iso, "axis FULL path: %d interfaces",
              path.interfaces);
        printf("axis, isolate %d: FULL off the 1D stack by %.3g\n", iso, worst);
    }
    snell_ref_destroy(ref);
}

/* (e') Overlap: sphere B (r 0.3) nested inside sphere A (r 1), both at the
 * origin, a ray along the axis. Objects are taken to be disjoint: inside A,
 * B's surfaces are passed unseen, so the path is A's alone (entry z = 1, exit
 * z = -1, inside length 2, colour F env(+z) + (1-F) t a env(-z) in MATCHED),
 * in both modes. */
static void nested_tests(void)
{
    const double cen[6] = {0, 0, 0, 0, 0, 0}, rad[2] = {1.0, 0.3}, o[3] = {0, 0, 5}, d[3] = {0, 0, -1},
                 up[3] = {0, 0, 1};
    double sig[3], eu[3], ed[3], F = 0.04;
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_ref_path path;
    int mode, k;
    CHECK_OK(snell__ref_create_spheres(NULL, 2, cen, rad, &ref));
    if (!ref) return;
    set_glass(ref, 0, 1.5, 0.3, 0.6, 0.1, 1, 1, 1, 0.0, sig);
    set_glass(ref, 1, 2.0, 5.0, 5.0, 5.0, 0.5, 0.5, 0.5, 0.0, NULL);
    sky(up, eu, NULL);
    sky(d, ed, NULL);
    memset(&p, 0, sizeof p);
    p.env_fn = sky;
    for (mode = 0; mode < 2; mode++) {
        p.mode = mode ? SNELL_REF_FULL : SNELL_REF_MATCHED;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        CHECK(path.interfaces == 2 && path.objects[1] == 0 && path.objects[2] == 0 &&
                  fabs(path.points[1][2] - 1.0) < 1e-12 && fabs(path.points[2][2] + 1.0) < 1e-12 &&
                  fabs(path.inside_length - 2.0) < 1e-12,
              "mode %d: the nested sphere is seen from inside (%d interfaces)", mode, path.interfaces);
        if (mode == 0)
            for (k = 0; k < 3; k++)
                CHECK(fabs(path.rgb[k] - (F * eu[k] + (1 - F) * exp(-sig[k] * 2.0) * ed[k])) < 1e-12,
                      "nested, channel %d: %.12f", k, path.rgb[k]);
    }
    snell_ref_destroy(ref);
}

static snell_mesh *cube_mesh(void)
{
    snell_shape_desc sd;
    snell_mesh *m = NULL;
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &m));
    return m;
}

/* Model of the cube [-1,1]^3 scaled by (sx, sy, sz) and moved to (tx, ty, tz). */
static void box_model(float m[16], double sx, double sy, double sz, double tx, double ty, double tz)
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = (float)sx;
    m[5] = (float)sy;
    m[10] = (float)sz;
    m[12] = (float)tx;
    m[13] = (float)ty;
    m[14] = (float)tz;
    m[15] = 1.0f;
}

/* (f) Absorption to the bounding sphere of the object entered: two glass
 * cubes of half-size s (0.6 and 1.1) side by side, rays straight down onto
 * the top face at (x, y) from the centre: the sphere is the cube's (centre,
 * radius sqrt(3) s), so d = s + sqrt(3 s^2 - x^2 - y^2) (computed with the
 * radius reported, whose float rounding is ~1e-7) and, at one
 * interface, C = F env(+z) + (1-F) t exp(-sigma d) env(-z) (PATH: d = 2 s). */
static void bsphere_tests(void)
{
    snell_mesh *cube = cube_mesh();
    float models[2][16];
    const double s[2] = {(double)0.6f, (double)1.1f}, c[2][3] = {{-2.0, 0.0, 0.0}, {2.0, (double)0.3f, -0.5}};
    double bc[2][3], br[2], sig[2][3], env_d[3], env_u[3], down[3] = {0, 0, -1}, up[3] = {0, 0, 1};
    snell_glass g[2];
    snell_ref_desc rd;
    snell_ref *ref = NULL;
    snell_ref_params p;
    int i, j, bad = 0, bad_path = 0;
    if (!cube) return;
    memset(g, 0, sizeof g);
    memset(&rd, 0, sizeof rd);
    for (i = 0; i < 2; i++) {
        box_model(models[i], s[i], s[i], s[i], c[i][0], c[i][1], c[i][2]);
        g[i].mesh = cube;
        g[i].model = models[i];
    }
    rd.glass = g;
    rd.glass_count = 2;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    if (!ref) {
        snell_mesh_destroy(cube);
        return;
    }
    for (i = 0; i < 2; i++) {
        /* The mesh's radius is a float: the colours below use the sphere reported. */
        snell_ref_bounding_sphere(ref, i, bc[i], &br[i]);
        CHECK(dist(bc[i], c[i]) < 1e-12 && fabs(br[i] - sqrt(3.0) * s[i]) < 1e-6,
              "glass %d: bounding sphere (%g %g %g) %g", i, bc[i][0], bc[i][1], bc[i][2], br[i]);
    }
    set_glass(ref, 0, 1.5, 0.3, 0.6, 0.1, 1, 0.9, 0.8, 0.0, sig[0]);
    set_glass(ref, 1, 1.7, 0.5, 0.2, 0.9, 0.7, 1, 0.9, 0.0, sig[1]);
    sky(down, env_d, NULL);
    sky(up, env_u, NULL);
    memset(&p, 0, sizeof p);
    p.env_fn = sky;
    p.max_interfaces = 1;
    for (i = 0; i < 2; i++)
        for (j = 0; j < 50; j++) {
            double x = s[i] * 0.9 * cos(j * 0.9) * (j % 7) / 6.0, y = s[i] * 0.9 * sin(j * 1.3) * ((j + 3) % 5) / 4.0;
            double o[3] = {c[i][0] + x, c[i][1] + y, c[i][2] + s[i] + 2.0}, n = i ? (double)1.7f : 1.5;
            double F = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
            static const float tint[2][3] = {{1, 0.9f, 0.8f}, {0.7f, 1, 0.9f}};
            double q[3] = {o[0] - bc[i][0], o[1] - bc[i][1], c[i][2] + s[i] - bc[i][2]}, dbs;
            snell_ref_path path;
            int k, model;
            dbs = q[2] + sqrt(q[2] * q[2] - (dot(q, q) - br[i] * br[i])); /* from q along -z to the sphere */
            for (model = 0; model < 2; model++) {
                p.absorption_model = model ? SNELL_REF_ABSORB_BOUNDING_SPHERE : SNELL_REF_ABSORB_PATH;
                CHECK_OK(snell_ref_trace_ray(ref, &p, o, down, &path));
                for (k = 0; k < 3; k++) {
                    double want =
                        F * env_u[k] + (1 - F) * tint[i][k] * exp(-sig[i][k] * (model ? dbs : 2 * s[i])) * env_d[k];
                    if (fabs(path.rgb[k] - want) > 1e-9) bad++;
                }
                if (path.interfaces != 1 || path.first_object != i || !path.ended_inside ||
                    fabs(path.inside_length - 2 * s[i]) > 1e-9)
                    bad_path++;
            }
        }
    CHECK(bad == 0, "%d colours with the wrong object's bounding sphere or path length", bad);
    CHECK(bad_path == 0, "%d single-interface paths wrong", bad_path);
    snell_ref_destroy(ref);
    snell_mesh_destroy(cube);
}

/* Slab of index n, thickness th, absorption sig, tint t at incidence theta
 * (one channel): MATCHED's entry reflectance F_out (Schlick), and as the FULL
 * tree sums it, reflectance R and transmittance T of the slab with every
 * inner bounce, the exact F at both faces (equal inside: reciprocity),
 * a = exp(-sig th / cos theta_t). */
static void solid_slab(double cos_i, double n, double th, double sig, double t, double *F_out, double *a_out, double *R,
                       double *T)
{
    double F = fresnel(cos_i, n), st = sqrt(1 - cos_i * cos_i) / n, a = exp(-sig * th / sqrt(1 - st * st));
    *F_out = schlick(cos_i, n);
    *a_out = a;
    *R = F + (1 - F) * (1 - F) * t * F * a * a / (1 - F * F * a * a);
    *T = (1 - F) * (1 - F) * t * a / (1 - F * F * a * a);
}

/* (g) Two glass slabs (mesh boxes 20 x 20, thickness 0.5 and 0.75, a gap of
 * 0.75; each its own n, sigma, tint), rays at 0..30 degrees: every surface is
 * met at theta, the chain leaves parallel to d, reflections leave along R.
 * MATCHED: B's front reflection enters A from behind and A's back reflection
 * goes to B again: X = [F_B (1-F_A) t_A a_A env(R) + (1-F_B) t_B a_B env(d)]
 * / (1 - F_A F_B), C = F_A env(R) + (1-F_A) t_A a_A X. FULL: the two-layer
 * stack T_A T_B / (1 - R_A R_B) env(d) + (R_A + T_A^2 R_B / (1 - R_A R_B))
 * env(R). isolate_glass: slab A alone (F_A env(R) + (1-F_A) t_A a_A env(d);
 * FULL R_A env(R) + T_A env(d)). Paths: 4 interfaces on the four planes,
 * objects 0 0 1 1, inside length th_A / cos + th_B / cos. */
static void two_slab_tests(void)
{
    snell_mesh *cube = cube_mesh();
    float models[2][16];
    const double th[2] = {0.5, 0.75}, top[2] = {0.5, -0.75}, ior[2] = {1.5, (double)1.7f}; /* exact in float */
    static const float tint[2][3] = {{0.9f, 1, 0.8f}, {1, 0.85f, 0.95f}};
    double sig[2][3], worst_m = 0.0, worst_f = 0.0;
    snell_glass g[2];
    snell_ref_desc rd;
    snell_ref *ref = NULL;
    snell_ref_params p;
    int i, bad_m = 0, bad_f = 0, bad_path = 0, bad_iso = 0;
    if (!cube) return;
    memset(g, 0, sizeof g);
    memset(&rd, 0, sizeof rd);
    for (i = 0; i < 2; i++) {
        box_model(models[i], 10, 10, th[i] / 2, 0, 0, top[i] - th[i] / 2);
        g[i].mesh = cube;
        g[i].model = models[i];
    }
    rd.glass = g;
    rd.glass_count = 2;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    if (!ref) {
        snell_mesh_destroy(cube);
        return;
    }
    set_glass(ref, 0, ior[0], 0.4, 0.1, 0.8, tint[0][0], tint[0][1], tint[0][2], 0.0, sig[0]);
    set_glass(ref, 1, ior[1], 0.2, 0.7, 0.3, tint[1][0], tint[1][1], tint[1][2], 0.0, sig[1]);
    memset(&p, 0, sizeof p);
    p.env_fn = sky;
    p.max_interfaces = SNELL_REF_MAX_INTERFACES;
    for (i = 0; i < 200; i++) {
        double th_i = (i / 20) * (0.52 / 9.0), ph = (i % 20) * (2 * 3.14159265358979 / 20);
        double d[3] = {sin(th_i) * cos(ph), sin(th_i) * sin(ph), -cos(th_i)}, R[3] = {d[0], d[1], -d[2]};
        double target[3] = {0.4 * cos(i * 0.7), 0.4 * sin(i * 1.3), top[0]}, o[3], eR[3], eD[3];
        double m_want[3], f_want[3], m_iso[3], f_iso[3], len = 0.0;
        snell_ref_path path;
        int k, q;
        for (k = 0; k < 3; k++) o[k] = target[k] - 3.0 * d[k];
        sky(R, eR, NULL);
        sky(d, eD, NULL);
        for (q = 0; q < 2; q++) len += th[q] / sqrt(1 - sin(th_i) * sin(th_i) / (ior[q] * ior[q]));
        for (k = 0; k < 3; k++) {
            double F[2], a[2], Rs[2], Ts[2], X;
            for (q = 0; q < 2; q++)
                solid_slab(cos(th_i), ior[q], th[q], sig[q][k], tint[q][k], &F[q], &a[q], &Rs[q], &Ts[q]);
            X = (F[1] * (1 - F[0]) * tint[0][k] * a[0] * eR[k] + (1 - F[1]) * tint[1][k] * a[1] * eD[k]) /
                (1 - F[0] * F[1]);
            m_want[k] = F[0] * eR[k] + (1 - F[0]) * tint[0][k] * a[0] * X;
            f_want[k] = Ts[0] * Ts[1] / (1 - Rs[0] * Rs[1]) * eD[k] +
                        (Rs[0] + Ts[0] * Ts[0] * Rs[1] / (1 - Rs[0] * Rs[1])) * eR[k];
            m_iso[k] = F[0] * eR[k] + (1 - F[0]) * tint[0][k] * a[0] * eD[k];
            f_iso[k] = Rs[0] * eR[k] + Ts[0] * eD[k];
        }
        p.mode = SNELL_REF_MATCHED;
        p.isolate_glass = 0;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        for (k = 0; k < 3; k++) {
            if (fabs(path.rgb[k] - m_want[k]) > worst_m) worst_m = fabs(path.rgb[k] - m_want[k]);
            if (fabs(path.rgb[k] - m_want[k]) > 2e-5) bad_m++;
        }
        if (path.interfaces != 4 || fabs(path.points[1][2] - top[0]) > 1e-12 ||
            fabs(path.points[2][2] - (top[0] - th[0])) > 1e-12 || fabs(path.points[3][2] - top[1]) > 1e-12 ||
            fabs(path.points[4][2] - (top[1] - th[1])) > 1e-12 || path.objects[1] != 0 || path.objects[2] != 0 ||
            path.objects[3] != 1 || path.objects[4] != 1 || angle(path.exit_dir, d) > 1e-9 ||
            fabs(path.inside_length - len) > 1e-9 || path.first_object != 0)
            bad_path++;
        p.mode = SNELL_REF_FULL;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        for (k = 0; k < 3; k++) {
            if (fabs(path.rgb[k] - f_want[k]) > worst_f) worst_f = fabs(path.rgb[k] - f_want[k]);
            if (fabs(path.rgb[k] - f_want[k]) > 2e-5) bad_f++;
        }
        if (path.interfaces != 4 || path.objects[3] != 1 || angle(path.exit_dir, d) > 1e-9) bad_path++;
        p.isolate_glass = 1;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        for (k = 0; k < 3; k++)
            if (fabs(path.rgb[k] - f_iso[k]) > 2e-5) bad_iso++;
        if (path.interfaces != 2) bad_iso++;
        p.mode = SNELL_REF_MATCHED;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        for (k = 0; k < 3; k++)
            if (fabs(path.rgb[k] - m_iso[k]) > 1e-9) bad_iso++;
        if (path.interfaces != 2) bad_iso++;
    }
    printf("two slabs: worst MATCHED error %.3g, FULL error %.3g\n", worst_m, worst_f);
    {
        /* The same two slabs as ONE glass object (one mesh of both boxes, slab
         * A's material): MATCHED never sees the object it leaves (the GPU
         * draws one surface of it per pixel), so C = F env(R) + (1-F) t a
         * env(d) after 2 interfaces; FULL meets all four surfaces (the stack
         * of two equal layers). */
        uint32_t nv = snell_mesh_vertex_count(cube), nt = snell_mesh_triangle_count(cube), v, t;
        float *pos = (float *)malloc(sizeof(float) * 6 * nv), *nrm = (float *)malloc(sizeof(float) * 6 * nv);
        uint32_t *idx = (uint32_t *)malloc(sizeof(uint32_t) * 6 * nt);
        snell_mesh_desc md;
        snell_mesh *two = NULL;
        snell_ref *r1 = NULL;
        int q, k, bad1 = 0;
        for (q = 0; q < 2; q++) {
            for (v = 0; v < nv; v++)
                for (k = 0; k < 3; k++) {
                    pos[3 * (q * nv + v) + k] =
                        snell_mesh_positions(cube)[3 * v + k] * models[q][5 * k] + models[q][12 + k];
                    nrm[3 * (q * nv + v) + k] = snell_mesh_normals(cube)[3 * v + k];
                }
            for (t = 0; t < 3 * nt; t++) idx[q * 3 * nt + t] = snell_mesh_indices(cube)[t] + (uint32_t)q * nv;
        }
        memset(&md, 0, sizeof md);
        md.positions = pos;
        md.normals = nrm;
        md.indices = idx;
        md.vertex_count = 2 * nv;
        md.triangle_count = 2 * nt;
        CHECK_OK(snell_mesh_create(NULL, &md, &two));
        free(pos);
        free(nrm);
        free(idx);
        if (two) r1 = one_glass(two, NULL);
        if (r1) {
            set_glass(r1, 0, ior[0], 0.4, 0.1, 0.8, tint[0][0], tint[0][1], tint[0][2], 0.0, NULL);
            for (i = 0; i < 40; i++) {
                double th_i = (i / 8) * (0.5 / 4.0), ph = (i % 8) * 0.8;
                double d[3] = {sin(th_i) * cos(ph), sin(th_i) * sin(ph), -cos(th_i)}, R[3] = {d[0], d[1], -d[2]};
                double o[3] = {0.3 * cos(i * 0.7) - 3.0 * d[0], 0.3 * sin(i * 1.3) - 3.0 * d[1], top[0] - 3.0 * d[2]};
                double eR[3], eD[3], F, a, Rs, Ts, Fb, ab, Rb, Tb;
                snell_ref_path path;
                sky(R, eR, NULL);
                sky(d, eD, NULL);
                p.isolate_glass = 0;
                p.mode = SNELL_REF_MATCHED;
                CHECK_OK(snell_ref_trace_ray(r1, &p, o, d, &path));
                for (k = 0; k < 3; k++) {
                    solid_slab(cos(th_i), ior[0], th[0], sig[0][k], tint[0][k], &F, &a, &Rs, &Ts);
                    if (fabs(path.rgb[k] - (F * eR[k] + (1 - F) * tint[0][k] * a * eD[k])) > 1e-9) bad1++;
                }
                if (path.interfaces != 2) bad1++;
                p.mode = SNELL_REF_FULL;
                CHECK_OK(snell_ref_trace_ray(r1, &p, o, d, &path));
                for (k = 0; k < 3; k++) {
                    solid_slab(cos(th_i), ior[0], th[0], sig[0][k], tint[0][k], &F, &a, &Rs, &Ts);
                    solid_slab(cos(th_i), ior[0], th[1], sig[0][k], tint[0][k], &Fb, &ab, &Rb, &Tb);
                    if (fabs(path.rgb[k] -
                             (Ts * Tb / (1 - Rs * Rb) * eD[k] + (Rs + Ts * Ts * Rb / (1 - Rs * Rb)) * eR[k])) > 5e-5)
                        bad1++;
                }
                if (path.interfaces != 4) bad1++;
            }
        }
        CHECK(r1 && bad1 == 0, "%d rays through one object of two slabs wrong", bad1);
        snell_ref_destroy(r1);
        snell_mesh_destroy(two);
    }
    CHECK(bad_m == 0, "%d MATCHED colours through two slabs off the closed form", bad_m);
    CHECK(bad_f == 0, "%d FULL colours through two slabs off the two-layer stack", bad_f);
    CHECK(bad_path == 0, "%d paths through two slabs wrong", bad_path);
    CHECK(bad_iso == 0, "%d isolate_glass colours see the second slab", bad_iso);
    snell_ref_destroy(ref);
    snell_mesh_destroy(cube);
}

/* (h) A thin wall: the box of (b) with material thickness 0.05, n 1.5, rgb
 * absorption and tint. The slab's rs and ts are summed here bounce by bounce
 * (r = Schlick at theta for MATCHED, the exact Fresnel for FULL, a = exp(-sigma 0.05 / cos theta_t): ts = sum (1-r)^2
 * a (r a)^(2k), rs = r + sum (1-r)^2 r a^2 (r a)^(2k)). MATCHED: C = rs
 * env(R) + ts t env(d), the box's back faces unseen, 1 interface. FULL: both
 * walls are slabs, T_w = ts t: C = T_w^2 / (1 - rs^2) env(d) + (rs + T_w^2
 * rs / (1 - rs^2)) env(R), 2 interfaces straight through. */
static void thin_tests(void)
{
    snell_mesh *cube = cube_mesh();
    float model[16];
    snell_ref *ref = NULL;
    snell_ref_params p;
    const double thick = (double)0.05f, n = 1.5;
    static const float tint[3] = {0.9f, 0.8f, 1.0f};
    double sig[3], worst = 0.0;
    int i, bad_m = 0, bad_f = 0, bad_path = 0;
    if (!cube) return;
    box_model(model, 3, 3, 0.5, 0, 0, 0);
    ref = one_glass(cube, model);
    if (!ref) {
        snell_mesh_destroy(cube);
        return;
    }
    set_glass(ref, 0, n, 2.0, 0.5, 4.0, tint[0], tint[1], tint[2], thick, sig);
    memset(&p, 0, sizeof p);
    p.env_fn = sky;
    for (i = 0; i < 200; i++) {
        double th_i = (i / 20) * (0.7 / 9.0), ph = (i % 20) * (2 * 3.14159265358979 / 20);
        double d[3] = {sin(th_i) * cos(ph), sin(th_i) * sin(ph), -cos(th_i)}, R[3] = {d[0], d[1], -d[2]};
        double target[3] = {0.4 * cos(i * 0.7), 0.4 * sin(i * 1.3), 0.5}, o[3], eR[3], eD[3], rs[3], ts[3];
        double ct = sqrt(1 - sin(th_i) * sin(th_i) / (n * n)), r = schlick(cos(th_i), n), rx = fresnel(cos(th_i), n);
        double rs_mean, rsx[3], tsx[3];
        snell_ref_path path;
        int k, q;
        for (k = 0; k < 3; k++) o[k] = target[k] - 3.0 * d[k];
        sky(R, eR, NULL);
        sky(d, eD, NULL);
        for (k = 0; k < 3; k++) {
            double a = exp(-sig[k] * thick / ct), term = 1.0, termx = 1.0;
            ts[k] = tsx[k] = 0.0;
            rs[k] = r;
            rsx[k] = rx;
            for (q = 0; q < 60; q++) {
                ts[k] += (1 - r) * (1 - r) * a * term;
                rs[k] += (1 - r) * (1 - r) * r * a * a * term;
                term *= r * a * r * a;
                tsx[k] += (1 - rx) * (1 - rx) * a * termx;
                rsx[k] += (1 - rx) * (1 - rx) * rx * a * a * termx;
                termx *= rx * a * rx * a;
            }
        }
        rs_mean = (rs[0] + rs[1] + rs[2]) / 3.0;
        p.mode = SNELL_REF_MATCHED;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        for (k = 0; k < 3; k++) {
            double want = rs[k] * eR[k] + ts[k] * tint[k] * eD[k];
            if (fabs(path.rgb[k] - want) > worst) worst = fabs(path.rgb[k] - want);
            if (fabs(path.rgb[k] - want) > 1e-9) bad_m++;
        }
        if (path.interfaces != 1 || path.events[1] != SNELL_REF_EVENT_REFRACT || path.objects[1] != 0 ||
            fabs(path.points[1][2] - 0.5) > 1e-12 || angle(path.exit_dir, d) > 1e-12 ||
            fabs(path.inside_length - thick / ct) > 1e-9 || fabs(path.fresnel - rs_mean) > 1e-9 || path.ended_inside)
            bad_path++;
        p.mode = SNELL_REF_FULL;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        for (k = 0; k < 3; k++) {
            double Tw = tsx[k] * tint[k], want = Tw * Tw / (1 - rsx[k] * rsx[k]) * eD[k] +
                                                 (rsx[k] + Tw * Tw * rsx[k] / (1 - rsx[k] * rsx[k])) * eR[k];
            if (fabs(path.rgb[k] - want) > 2e-5) bad_f++;
        }
        if (path.interfaces != 2 || fabs(path.points[2][2] + 0.5) > 1e-12 || angle(path.exit_dir, d) > 1e-12 ||
            path.events[2] != SNELL_REF_EVENT_REFRACT || fabs(path.inside_length - 2 * thick / ct) > 1e-9)
            bad_path++;
    }
    printf("thin wall: worst MATCHED error %.3g\n", worst);
    CHECK(bad_m == 0, "%d MATCHED thin-wall colours off the slab series", bad_m);
    CHECK(bad_f == 0, "%d FULL thin-wall colours off the two-wall stack", bad_f);
    CHECK(bad_path == 0, "%d thin-wall paths wrong", bad_path);
    snell_ref_destroy(ref);
    snell_mesh_destroy(cube);
}

/* The shading of opaque.frag for unit world normal n. */
static void lit(const double col[3], const double n[3], double out[3])
{
    double L[3] = {0.3, 1.0, 0.2}, l;
    int k;
    unit(L);
    l = 0.5 + 0.5 * dot(n, L);
    for (k = 0; k < 3; k++) out[k] = col[k] * (0.25 + 0.75 * l);
}

/* (i) Opaque objects seen directly: a cube under a sheared, non-uniformly
 * scaled, rotated model (opaque 1, colour (0.9, 0.5, 0.2)) next to a grey
 * default one (opaque 0, colour 0 = 0.8) and a glass cube. Rays aimed at
 * points inside each front-facing triangle (the cube is convex, so that point
 * is the first hit) get the opaque.frag colour for the triangle's geometric
 * world normal (cross product of its world edges, outward), in both modes and
 * with isolate_glass; the path ends there: 0 interfaces, hit 0, first_object
 * -2 - j, exit_dir = the ray. A scene of opaque objects only works too, and
 * an open quad seen from behind is lit with its normal as given (not turned
 * to the viewer). */
static void opaque_direct_tests(void)
{
    snell_mesh *cube = cube_mesh();
    float m1[16] = {0.8f, 0.3f, 0.0f, 0, 0.2f, 1.3f, 0.4f, 0, -0.1f, 0.0f, 0.6f, 0, 0.5f, -0.3f, 0.2f, 1};
    float m0[16], mg[16];
    const double col1[3] = {(double)0.9f, (double)0.5f, (double)0.2f},
                 grey[3] = {(double)0.8f, (double)0.8f, (double)0.8f};
    snell_opaque op[2];
    snell_glass g;
    snell_ref_desc rd;
    snell_ref *ref = NULL, *ref_only = NULL;
    snell_ref_params p;
    uint32_t t;
    int tested = 0, bad = 0, bad_path = 0, pass_i;
    if (!cube) return;
    box_model(m0, 0.5, 0.5, 0.5, -4, 0, 0);
    box_model(mg, 0.5, 0.5, 0.5, 4, 0, 0);
    memset(op, 0, sizeof op);
    memset(&g, 0, sizeof g);
    op[0].mesh = cube;
    op[0].model = m0;
    op[1].mesh = cube;
    op[1].model = m1;
    op[1].color[0] = 0.9f;
    op[1].color[1] = 0.5f;
    op[1].color[2] = 0.2f;
    g.mesh = cube;
    g.model = mg;
    memset(&rd, 0, sizeof rd);
    rd.glass = &g;
    rd.glass_count = 1;
    rd.opaque = op;
    rd.opaque_count = 2;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    rd.glass = NULL;
    rd.glass_count = 0;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref_only));
    if (!ref || !ref_only) {
        snell_ref_destroy(ref);
        snell_ref_destroy(ref_only);
        snell_mesh_destroy(cube);
        return;
    }
    memset(&p, 0, sizeof p);
    p.env_fn = sky;
    for (pass_i = 0; pass_i < 2; pass_i++) {
        const float *M = pass_i ? m1 : m0;
        const double *col = pass_i ? col1 : grey;
        double cw[3] = {M[12], M[13], M[14]};
        for (t = 0; t < snell_mesh_triangle_count(cube); t++) {
            double v[3][3], e1[3], e2[3], n[3], cen[3] = {0, 0, 0}, q[3], o[3], d[3], want[3];
            int j, k, mode;
            for (j = 0; j < 3; j++) {
                const float *a = snell_mesh_positions(cube) + 3 * snell_mesh_indices(cube)[3 * t + j];
                for (k = 0; k < 3; k++) {
                    v[j][k] =
                        (double)M[k] * a[0] + (double)M[4 + k] * a[1] + (double)M[8 + k] * a[2] + (double)M[12 + k];
                    cen[k] += v[j][k] / 3.0;
                }
            }
            for (k = 0; k < 3; k++) {
                e1[k] = v[1][k] - v[0][k];
                e2[k] = v[2][k] - v[0][k];
            }
            n[0] = e1[1] * e2[2] - e1[2] * e2[1];
            n[1] = e1[2] * e2[0] - e1[0] * e2[2];
            n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            unit(n);
            if (dot(n, cen) - dot(n, cw) < 0) /* outward: away from the cube's centre */
                for (k = 0; k < 3; k++) n[k] = -n[k];
            lit(col, n, want);
            for (j = 0; j < 4; j++) {
                double b0 = 0.2 + 0.15 * j, b1 = 0.5 - 0.1 * j, tang[3];
                for (k = 0; k < 3; k++) {
                    q[k] = v[0][k] + b0 * e1[k] + b1 * (v[2][k] - v[0][k]) * 0.5;
                    tang[k] = e1[k] * (j - 1.5) * 0.3;
                    o[k] = q[k] + 2.0 * n[k] + tang[k];
                    d[k] = q[k] - o[k];
                }
                unit(d);
                for (mode = 0; mode < 4; mode++) {
                    snell_ref_path path;
                    const snell_ref *rr = mode == 3 ? ref_only : ref;
                    p.mode = mode & 1 ? SNELL_REF_FULL : SNELL_REF_MATCHED;
                    p.isolate_glass = mode == 2;
                    CHECK_OK(snell_ref_trace_ray(rr, &p, o, d, &path));
                    tested++;
                    for (k = 0; k < 3; k++)
                        if (fabs(path.rgb[k] - want[k]) > 1e-9) {
                            if (bad < 3)
                                fprintf(stderr, "opaque %d tri %u: rgb %.9f want %.9f\n", pass_i, t, path.rgb[k],
                                        want[k]);
                            bad++;
                        }
                    if (path.interfaces != 0 || path.hit || path.first_object != -2 - pass_i ||
                        angle(path.exit_dir, d) > 1e-12)
                        bad_path++;
                }
            }
        }
    }
    {
        /* An open quad (normal +y) seen from below: the normal is not turned
         * to the viewer (opaque.frag uses it as interpolated). */
        static const float qp[12] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1},
                           qn[12] = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
        static const uint32_t qi[6] = {0, 2, 1, 0, 3, 2};
        const double o[3] = {0.1, -2.0, 0.2}, d[3] = {0, 1, 0}, nup[3] = {0, 1, 0};
        double want[3];
        snell_mesh_desc md;
        snell_mesh *quad = NULL;
        snell_opaque q1;
        snell_ref *rq = NULL;
        snell_ref_path path;
        int k;
        memset(&md, 0, sizeof md);
        md.positions = qp;
        md.normals = qn;
        md.indices = qi;
        md.vertex_count = 4;
        md.triangle_count = 2;
        CHECK_OK(snell_mesh_create(NULL, &md, &quad));
        memset(&q1, 0, sizeof q1);
        q1.mesh = quad;
        q1.color[0] = 0.9f;
        q1.color[1] = 0.5f;
        q1.color[2] = 0.2f;
        memset(&rd, 0, sizeof rd);
        rd.opaque = &q1;
        rd.opaque_count = 1;
        if (quad) CHECK_OK(snell_ref_create(NULL, &rd, &rq));
        if (rq) {
            lit(col1, nup, want);
            CHECK_OK(snell_ref_trace_ray(rq, &p, o, d, &path));
            for (k = 0; k < 3; k++)
                CHECK(fabs(path.rgb[k] - want[k]) < 1e-12, "quad from below, channel %d: %.9f want %.9f", k,
                      path.rgb[k], want[k]);
            CHECK(path.first_object == -2, "quad: object %d", path.first_object);
        }
        snell_ref_destroy(rq);
        snell_mesh_destroy(quad);
    }
    printf("opaque: %d rays at faces\n", tested);
    CHECK(tested >= 2 * 12 * 4 * 4, "only %d rays", tested);
    CHECK(bad == 0, "%d opaque colours differ from opaque.frag's", bad);
    CHECK(bad_path == 0, "%d opaque paths wrong (interfaces, hit, object, exit direction)", bad_path);
    snell_ref_destroy(ref);
    snell_ref_destroy(ref_only);
    snell_mesh_destroy(cube);
}

/* (j) An opaque wall (top face z = -2.5, normal +z, colour (0.2, 0.7, 0.4))
 * seen through a glass slab (the box of (b), n 1.5): every ray that leaves the
 * slab downwards ends on the wall with O = its opaque.frag colour. MATCHED:
 * C = F env(R) + (1-F) t a O; FULL: R_slab env(R) + T_slab O (solid_slab);
 * isolate_glass changes nothing (opaque objects stay visible). */
static void opaque_behind_glass_tests(void)
{
    snell_mesh *cube = cube_mesh();
    float mg[16], mw[16];
    const double wall_col[3] = {(double)0.2f, (double)0.7f, (double)0.4f}, up[3] = {0, 0, 1}, n = 1.5;
    static const float tint[3] = {1, 0.9f, 0.8f};
    double sig[3], O[3];
    snell_opaque wall;
    snell_glass g;
    snell_ref_desc rd;
    snell_ref *ref = NULL;
    snell_ref_params p;
    int i, bad_m = 0, bad_f = 0, bad_path = 0;
    if (!cube) return;
    box_model(mg, 3, 3, 0.5, 0, 0, 0);
    box_model(mw, 20, 20, 0.5, 0, 0, -3);
    memset(&wall, 0, sizeof wall);
    memset(&g, 0, sizeof g);
    wall.mesh = cube;
    wall.model = mw;
    wall.color[0] = 0.2f;
    wall.color[1] = 0.7f;
    wall.color[2] = 0.4f;
    g.mesh = cube;
    g.model = mg;
    memset(&rd, 0, sizeof rd);
    rd.glass = &g;
    rd.glass_count = 1;
    rd.opaque = &wall;
    rd.opaque_count = 1;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    if (!ref) {
        snell_mesh_destroy(cube);
        return;
    }
    set_glass(ref, 0, n, 0.3, 0.6, 0.9, tint[0], tint[1], tint[2], 0.0, sig);
    lit(wall_col, up, O);
    memset(&p, 0, sizeof p);
    p.env_fn = sky;
    for (i = 0; i < 200; i++) {
        double th_i = (i / 20) * (0.6 / 9.0), ph = (i % 20) * (2 * 3.14159265358979 / 20);
        double d[3] = {sin(th_i) * cos(ph), sin(th_i) * sin(ph), -cos(th_i)}, R[3] = {d[0], d[1], -d[2]};
        double target[3] = {0.4 * cos(i * 0.7), 0.4 * sin(i * 1.3), 0.5}, o[3], eR[3];
        snell_ref_path path;
        int k, iso;
        for (k = 0; k < 3; k++) o[k] = target[k] - 3.0 * d[k];
        sky(R, eR, NULL);
        for (iso = 0; iso < 2; iso++) {
            p.isolate_glass = iso;
            p.mode = SNELL_REF_MATCHED;
            CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
            for (k = 0; k < 3; k++) {
                double F, a, Rs, Ts;
                solid_slab(cos(th_i), n, 1.0, sig[k], tint[k], &F, &a, &Rs, &Ts);
                if (fabs(path.rgb[k] - (F * eR[k] + (1 - F) * tint[k] * a * O[k])) > 1e-9) bad_m++;
            }
            if (path.interfaces != 2 || path.first_object != 0 || !path.hit || angle(path.exit_dir, d) > 1e-9 ||
                path.ended_inside)
                bad_path++;
            p.mode = SNELL_REF_FULL;
            CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
            for (k = 0; k < 3; k++) {
                double F, a, Rs, Ts;
                solid_slab(cos(th_i), n, 1.0, sig[k], tint[k], &F, &a, &Rs, &Ts);
                if (fabs(path.rgb[k] - (Rs * eR[k] + Ts * O[k])) > 2e-5) bad_f++;
            }
            if (path.interfaces != 2 || angle(path.exit_dir, d) > 1e-9) bad_path++;
        }
    }
    CHECK(bad_m == 0, "%d MATCHED colours of the wall behind glass off the closed form", bad_m);
    CHECK(bad_f == 0, "%d FULL colours of the wall behind glass off the slab series", bad_f);
    CHECK(bad_path == 0, "%d paths to the wall behind glass wrong", bad_path);
    snell_ref_destroy(ref);
    snell_mesh_destroy(cube);
}

/* (k) The FULL model's terms added to MATCHED (snell_ref_params.terms) on the
 * exact sphere, white environment, absorption sig: a ray at incidence
 * cosine ci refracts to cosine ct inside and crosses chords of 2 r ct, every
 * internal reflection keeping the angle. MATCHED: F0 + (1 - F0) e^(-sig L);
 * with the inner reflection the first exit transmits 1 - F1 and F1 crosses
 * a second chord: F0 + (1 - F0) ((1 - F1) e^(-sig L) + F1 e^(-2 sig L)); with
 * the exact Fresnel every F is the unpolarised one (reciprocal: F1 = F0),
 * with Schlick's the exit's is taken at the outside angle (optics.h), so
 * F1 = F0 again. Unknown bits and terms with the chord's absorption are
 * refused. */
static void terms_tests(void)
{
    const double c[3] = {0.0, 0.0, 0.0}, r = 0.7, n = 1.5;
    const unsigned sets[4] = {0u, SNELL_REF_TERM_EXACT_FRESNEL, SNELL_REF_TERM_INNER_REFLECTION,
                              SNELL_REF_TERM_EXACT_FRESNEL | SNELL_REF_TERM_INNER_REFLECTION};
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_ref_path path;
    double sig[3], worst = 0.0;
    int i, k, tested = 0;
    CHECK_OK(snell__ref_create_sphere(NULL, c, r, &ref));
    if (!ref) return;
    set_glass(ref, 0, n, 0.9, 0.9, 0.9, 1, 1, 1, 0.0, sig);
    memset(&p, 0, sizeof p);
    p.env_fn = white;
    p.max_interfaces = 10;
    for (i = 0; i < 4; i++)
        for (k = 0; k < 9; k++) {
            double b = r * k / 10.0, o[3] = {b, 0.0, 3.0}, d[3] = {0.0, 0.0, -1.0};
            double ci = sqrt(1.0 - (b / r) * (b / r)), ct = sqrt(1.0 - (1.0 - ci * ci) / (n * n));
            double F = (sets[i] & SNELL_REF_TERM_EXACT_FRESNEL) ? fresnel(ci, n) : schlick(ci, n);
            double T = exp(-sig[0] * 2.0 * r * ct), want;
            want = (sets[i] & SNELL_REF_TERM_INNER_REFLECTION) ? F + (1 - F) * ((1 - F) * T + F * T * T)
                                                               : F + (1 - F) * T;
            p.terms = sets[i];
            CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
            if (fabs(path.rgb[0] - want) > worst) worst = fabs(path.rgb[0] - want);
            CHECK(fabs(path.rgb[0] - want) < 1e-6, "terms 0x%x, impact %.2f: %.9f, closed form %.9f", sets[i], b,
                  path.rgb[0], want);
            tested++;
        }
    printf("terms: %d rays, worst colour error %.3g\n", tested, worst);
    p.terms = SNELL_REF_TERMS_ALL + 8u;
    CHECK(snell_ref_trace_ray(ref, &p, (const double[3]){0, 0, 3}, (const double[3]){0, 0, -1}, &path) ==
              SNELL_E_INVALID_ARG, "unknown terms refused");
    p.terms = SNELL_REF_TERM_INNER_REFLECTION;
    p.absorption_model = SNELL_REF_ABSORB_BOUNDING_SPHERE;
    CHECK(snell_ref_trace_ray(ref, &p, (const double[3]){0, 0, 3}, (const double[3]){0, 0, -1}, &path) ==
              SNELL_E_INVALID_ARG, "terms with the chord's absorption refused");
    snell_ref_destroy(ref);
}

int main(void)
{
    sphere_tests();
    slab_tests();
    tir_tests();
    two_sphere_tests();
    axis_tests();
    nested_tests();
    bsphere_tests();
    two_slab_tests();
    thin_tests();
    opaque_direct_tests();
    opaque_behind_glass_tests();
    terms_tests();
    return test_finish();
}
