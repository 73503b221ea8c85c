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
    printf("%-8s centre (%.3f %.3f %.3f) radius %.3f hidden %.4f closed %d convex %d inside %d (%d samples)\n", name,
           a->centre[0], a->centre[1], a->centre[2], a->radius, a->hidden_fraction, a->closed, a->convex, a->inside,
           a->samples);
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
        CHECK(a.hidden_fraction > 0.35f, "torus: at least 41%% is hidden from any centre, got %g", a.hidden_fraction);
        snell_mesh_destroy(m);
    }

    m = shape(NULL, SNELL_SHAPE_GOBLET);
    if (m) {
        CHECK_OK(snell_mesh_analyze(m, &a));
        print("goblet", &a);
        CHECK(!a.convex, "goblet is not convex");
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
        /* The ears are thin sheets: a ray from a centre off their plane
         * crosses both of their sides, so some surface is always hidden. */
        CHECK(a.hidden_fraction > 0.0f && a.inside, "bunny: hidden %g inside %d", a.hidden_fraction, a.inside);
        snell_mesh_destroy(m);
    }
    return test_finish();
}
