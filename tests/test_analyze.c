/* test_analyze — snell_mesh_analyze (src/mesh_analyze.c): closed/convex
 * flags, the cubemap centre and the hidden fraction on shapes whose answers
 * follow from their geometry:
 *  - sphere, cube: closed, convex, star-shaped about any interior point, so
 *    hidden_fraction = 0 and the centre is inside (near the origin, where the
 *    volume centroid is);
 *  - torus (R = 1, r = 0.4): closed, not convex; from a point inside the tube
 *    at ring angle 0, a straight segment stays in the solid only to ring
 *    angles |phi| with 1 - cos(phi/2) <= r, i.e. |phi| <= 2 acos(0.6) = 106
 *    degrees, so at least (360 - 2*106)/360 = 41% of the surface (area is
 *    uniform in phi) is hidden from any centre; the vertex average (the hole
 *    centre) is outside and must not be chosen: the centre lies in the tube;
 *  - goblet (thin bowl wall): a ray from any point off the wall crosses
 *    both of its sides, so nearly all of the bowl is hidden: above AUTO's
 *    threshold (0.6, renderer.c);
 *  - an open mesh: closed = convex = inside = 0; bad input gives a status. */
#include "test_util.h"

#include <math.h>
#include <string.h>

static snell_mesh *shape(snell_ctx *ctx, snell_shape s)
{
    snell_shape_desc d;
    snell_mesh *m = NULL;
    memset(&d, 0, sizeof d);
    d.shape = s;
    CHECK_OK(snell_mesh_create_shape(ctx, &d, &m));
    return m;
}

static void print(const char *name, const snell_mesh_analysis *a)
{
    printf("%-8s centre (%.3f %.3f %.3f) radius %.3f inner %.3f hidden %.4f closed %d convex %d inside %d (%d samples)\n", name,
           a->centre[0], a->centre[1], a->centre[2], a->radius, a->inner_radius, a->hidden_fraction, a->closed, a->convex, a->inside,
           a->samples);
}

/* Distance from p to a triangle by a different route than the library's
 * Voronoi-region test: projection into the plane when it falls inside, else
 * the nearest of the three clamped edge distances. */
static double seg_dist2(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], t, d2 = 0.0, l2 = 0.0;
    int k;
    for (k = 0; k < 3; k++) {
        ab[k] = b[k] - a[k];
        ap[k] = p[k] - a[k];
        l2 += ab[k] * ab[k];
    }
    t = l2 > 0.0 ? (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / l2 : 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    for (k = 0; k < 3; k++) d2 += (ap[k] - t * ab[k]) * (ap[k] - t * ab[k]);
    return d2;
}

static double tri_dist(const double p[3], double v[3][3])
{
    double e1[3], e2[3], n[3], w[3], nn, s, t, u, d, best;
    int k;
    for (k = 0; k < 3; k++) {
        e1[k] = v[1][k] - v[0][k];
        e2[k] = v[2][k] - v[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (nn > 0.0) {
        double c1[3], c2[3];
        for (k = 0; k < 3; k++) w[k] = p[k] - v[0][k];
        d = (w[0] * n[0] + w[1] * n[1] + w[2] * n[2]) / nn;     /* signed distance / |n| */
        for (k = 0; k < 3; k++) w[k] -= d * n[k];                /* projected, relative to v0 */
        c1[0] = w[1] * e2[2] - w[2] * e2[1];                     /* barycentrics by area ratios */
        c1[1] = w[2] * e2[0] - w[0] * e2[2];
        c1[2] = w[0] * e2[1] - w[1] * e2[0];
        c2[0] = e1[1] * w[2] - e1[2] * w[1];
        c2[1] = e1[2] * w[0] - e1[0] * w[2];
        c2[2] = e1[0] * w[1] - e1[1] * w[0];
        s = (c1[0] * n[0] + c1[1] * n[1] + c1[2] * n[2]) / nn;
        t = (c2[0] * n[0] + c2[1] * n[1] + c2[2] * n[2]) / nn;
        u = 1.0 - s - t;
        if (s >= 0.0 && t >= 0.0 && u >= 0.0) return fabs(d) * sqrt(nn);
    }
    best = seg_dist2(p, v[0], v[1]);
    best = fmin(best, seg_dist2(p, v[1], v[2]));
    best = fmin(best, seg_dist2(p, v[2], v[0]));
    return sqrt(best);
}

/* inner_radius must be the distance from the centre to the nearest surface
 * point, rounded down (the ball it describes must not hold any surface). */
static void check_inner_radius(const char *name, const snell_mesh *m, const snell_mesh_analysis *a)
{
    const float *pos = snell_mesh_positions(m);
    const uint32_t *idx = snell_mesh_indices(m);
    double c[3] = {a->centre[0], a->centre[1], a->centre[2]}, best = HUGE_VAL, v[3][3];
    uint32_t t;
    int j, k;
    for (t = 0; t < snell_mesh_triangle_count(m); t++) {
        for (j = 0; j < 3; j++)
            for (k = 0; k < 3; k++) v[j][k] = pos[3 * idx[3 * t + j] + k];
        best = fmin(best, tri_dist(c, v));
    }
    CHECK(a->inner_radius <= best && a->inner_radius >= best * (1.0 - 1e-6),
          "%s: inner radius %.9g, nearest surface at %.9g", name, a->inner_radius, best);
}

int main(void)
{
    snell_mesh_analysis a;
    snell_mesh *m;
    int k;
    const char *names[2] = {"sphere", "cube"};

    for (k = 0; k < 2; k++) {
        m = shape(NULL, k == 0 ? SNELL_SHAPE_SPHERE : SNELL_SHAPE_CUBE);
        if (!m) continue;
        CHECK_OK(snell_mesh_analyze(m, &a));
        print(names[k], &a);
        CHECK(a.closed && a.convex && a.inside, "%s must be closed, convex, centre inside", names[k]);
        CHECK(a.hidden_fraction == 0.0f, "%s is star-shaped: hidden %g", names[k], a.hidden_fraction);
        CHECK(sqrtf(a.centre[0] * a.centre[0] + a.centre[1] * a.centre[1] + a.centre[2] * a.centre[2]) < 0.05f,
              "%s centre should be the volume centroid (origin)", names[k]);
        CHECK(a.radius >= 0.99f && a.radius <= (k ? 1.75f : 1.01f), "%s radius %g", names[k], a.radius);
        check_inner_radius(names[k], m, &a);
        /* The cube's faces are at the half edge, its corners sqrt(3) times as far. */
        if (k == 1) CHECK(fabsf(a.inner_radius * 1.7320508f - a.radius) < 1e-5f, "cube inner radius %g", a.inner_radius);
        snell_mesh_destroy(m);
    }

    m = shape(NULL, SNELL_SHAPE_TORUS);
    if (m) {
        float ring;
        CHECK_OK(snell_mesh_analyze(m, &a));
        print("torus", &a);
        CHECK(a.closed && !a.convex && a.inside, "torus: closed, not convex, centre inside");
        ring = sqrtf(a.centre[0] * a.centre[0] + a.centre[2] * a.centre[2]);
        CHECK(sqrtf((ring - 1.0f) * (ring - 1.0f) + a.centre[1] * a.centre[1]) < 0.4f,
              "torus centre must lie in the tube (ring distance %g)", ring);
        check_inner_radius("torus", m, &a);
        CHECK(a.hidden_fraction > 0.35f, "torus: at least 41%% is hidden from any centre, got %g", a.hidden_fraction);
        snell_mesh_destroy(m);
    }

    m = shape(NULL, SNELL_SHAPE_GOBLET);
    if (m) {
        CHECK_OK(snell_mesh_analyze(m, &a));
        print("goblet", &a);
        CHECK(!a.convex, "goblet is not convex");
        check_inner_radius("goblet", m, &a);
        CHECK(a.hidden_fraction > 0.6f, "goblet must be reported as not star-shaped (hidden %g)", a.hidden_fraction);
        snell_mesh_destroy(m);
    }

    {
        /* A tetrahedron without its base: open. */
        static const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
        static const uint32_t idx[] = {0, 2, 1, 0, 1, 3, 0, 3, 2};
        snell_mesh_desc d;
        memset(&d, 0, sizeof d);
        d.positions = pos;
        d.indices = idx;
        d.vertex_count = 4;
        d.triangle_count = 3;
        m = NULL;
        CHECK_OK(snell_mesh_create(NULL, &d, &m));
        if (m) {
            CHECK_OK(snell_mesh_analyze(m, &a));
            print("open", &a);
            CHECK(!a.closed && !a.convex && !a.inside, "open mesh: closed %d convex %d inside %d", a.closed, a.convex,
                  a.inside);
            snell_mesh_destroy(m);
        }
    }
    {
        /* Zero area: every triangle degenerate. */
        static const float pos[] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
        static const uint32_t idx[] = {0, 1, 2};
        snell_mesh_desc d;
        memset(&d, 0, sizeof d);
        d.positions = pos;
        d.indices = idx;
        d.vertex_count = 3;
        d.triangle_count = 1;
        m = NULL;
        CHECK_OK(snell_mesh_create(NULL, &d, &m));
        if (m) {
            snell_status st = snell_mesh_analyze(m, &a);
            CHECK(st == SNELL_E_INVALID_ARG, "zero-area mesh: %s", snell_status_str(st));
            CHECK(strstr(snell_last_error(NULL), "area") != NULL, "message: %s", snell_last_error(NULL));
            snell_mesh_destroy(m);
        }
    }
    CHECK(snell_mesh_analyze(NULL, &a) == SNELL_E_INVALID_ARG, "NULL mesh");

    if (snell_mesh_load_obj(NULL, "/usr/share/glmark2/models/bunny.obj", &m) == SNELL_OK) {
        CHECK_OK(snell_mesh_normalize(m, 1.0f));
        CHECK_OK(snell_mesh_analyze(m, &a));
        print("bunny", &a);
        check_inner_radius("bunny", m, &a);
        /* The ears are thin sheets: a ray from a centre off their plane
         * crosses both of their sides, so some surface is always hidden. */
        CHECK(a.hidden_fraction > 0.0f && a.inside, "bunny: hidden %g inside %d", a.hidden_fraction, a.inside);
        snell_mesh_destroy(m);
    }
    return test_finish();
}
