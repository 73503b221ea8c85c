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
 *     cap at 3 and 2 interfaces ends inside as documented. */
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

static double schlick(double cos_i, double n)
{
    double r0 = (1 - n) / (1 + n), m = 1 - cos_i;
    r0 *= r0;
    return r0 + (1 - r0) * m * m * m * m * m;
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
        p.glass.ior = (float)iors[ii];
        for (eyes = 0; eyes < 2; eyes++)
            for (gy = 0; gy < 41; gy++)
                for (gx = 0; gx < 41; gx++) {
                    /* eyes 0: parallel rays along a tilted direction; 1: rays
                     * from one eye point (perspective). */
                    double o[3], d[3], oc[3], perp[3], h, e[3], ti, tt, dev, want[3], t1, P1[3], T1[3], P2[3],
                        chord, F, a, col, sig = (double)0.7f, full, series = 0.0, fa;
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
                    p.glass.absorption[0] = p.glass.absorption[1] = p.glass.absorption[2] = (float)sig;
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
                    /* FULL: the Whitted series; F inside equals F outside
                     * (Schlick uses the larger angle). Terms below 1e-5 are
                     * pruned (ref_trace.c), so compare to 1e-4. */
                    if (h < 0.8 * r) {
                        p.mode = SNELL_REF_FULL;
                        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
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
    snell_ref_desc rd;
    snell_ref_params p;
    /* Box [-1,1]^3 scaled to 6 x 6 x 1: the slab -0.5 <= z <= 0.5. */
    float model[16] = {3, 0, 0, 0, 0, 3, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1};
    int i, tested = 0, bad = 0;
    double worst = 0.0, worst_off = 0.0;
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_CUBE;
    CHECK_OK(snell_mesh_create_shape(NULL, &sd, &cube));
    if (!cube) return;
    memset(&rd, 0, sizeof rd);
    rd.mesh = cube;
    rd.model = model;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
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
        p.glass.ior = (float)n;
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
    snell_ref_desc rd;
    snell_ref_params p;
    int i, bad4 = 0, bad3 = 0, bad2 = 0, bad13 = 0, badfull = 0;
    if (!prism) return;
    memset(&rd, 0, sizeof rd);
    rd.mesh = prism;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
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
        p.mode = SNELL_REF_MATCHED;
        p.glass.ior = 1.5f;
        p.glass.absorption[0] = 0.25f;
        p.max_interfaces = 0;
        CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
        if (path.interfaces != 4 || path.events[1] != SNELL_REF_EVENT_REFRACT ||
            path.events[2] != SNELL_REF_EVENT_TIR || path.events[3] != SNELL_REF_EVENT_TIR ||
            path.events[4] != SNELL_REF_EVENT_REFRACT || path.ended_inside || angle(path.exit_dir, up) > 1e-9 ||
            fabs(path.points[4][0] + x0) > 1e-9 || fabs(path.inside_length - 2.0) > 1e-9 ||
            fabs(path.rgb[0] - (0.04 + 0.96 * exp(-0.25 * 2.0))) > 1e-9 || fabs(path.rgb[1] - 1.0) > 1e-9)
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
        p.glass.ior = 1.3f;
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
        p.glass.ior = 1.5f;
        p.glass.absorption[0] = 0.0f;
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

int main(void)
{
    sphere_tests();
    slab_tests();
    tir_tests();
    return test_finish();
}
