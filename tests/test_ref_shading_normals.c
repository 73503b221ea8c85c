/* SPDX-License-Identifier: MIT */
/* test_ref_shading_normals — FULL where a mesh's smooth (shading) normal and
 * its triangle's plane disagree about which way the surface faces (issue 15:
 * along the Stanford bunny's base, whose sharp crease the smooth normals
 * round off, FULL against Blender Cycles had a systematic 3.7/255).
 *
 * The mesh: a cube [-1,1]^3 of 4 x 4 quads a face with shared vertices and
 * the smooth normals snell_mesh_create computes (test_smooth_cube), so the
 * normals of the outer ring of quads lean towards the neighbouring faces as
 * the bunny's base's do.
 * Rays from above graze its top face (the plane y = 1) near the edge z = 1,
 * travelling towards +z: there the interpolated normal leans so far towards
 * +z that it faces away from the ray (checked here from the mesh's own
 * normals), although the plane faces it. Whatever normal the optics bend
 * light about, light entering through the top face's plane from above that
 * is reflected must leave above it, and light that is transmitted must go
 * into the glass, below it; a tracer that flips the smooth normal by its own
 * sign (the kernels' rule, which MATCHED keeps) does the opposite there:
 *
 * (a) the colour, one interface (max_interfaces 1: both branches then look
 *     the environment up in their direction), in a world that is red above
 *     the horizontal and green below: red = F (the reflected share), green =
 *     1 - F (the transmitted share), F the Fresnel weight the path reports
 *     for that interface;
 * (b) the dominant path (snell_ref_trace_ray) with every interface:
 *     everywhere on a grid of rays over the cube from four sides, a segment
 *     of the path is inside the cube ([-1,1]^3, tested from the points
 *     themselves) after an entry from air, reflections and total internal
 *     reflections keep the side they came from, the path crosses the surface
 *     nowhere but at its points, and it never ends inside without a cap
 *     (points on the cube's edges, a tie between two planes, are not judged). */
#include "test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define EPS_COLOUR 1e-12

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Red above the horizontal, green below. */
static void split_world(const double dir[3], double rgb[3], void *user)
{
    (void)user;
    rgb[0] = dir[1] > 0.0 ? 1.0 : 0.0;
    rgb[1] = dir[1] < 0.0 ? 1.0 : 0.0;
    rgb[2] = 0.0;
}

/* The mesh's smooth normal at point p of the top face (y = 1): the
 * barycentric mix of its triangle's vertex normals, as the tracer takes it. */
static int top_normal(const snell_mesh *m, const double p[3], double n[3])
{
    const float *pos = snell_mesh_positions(m), *nrm = snell_mesh_normals(m);
    const uint32_t *idx = snell_mesh_indices(m);
    uint32_t t, nt = snell_mesh_triangle_count(m);
    for (t = 0; t < nt; t++) {
        const float *a = pos + 3 * idx[3 * t], *b = pos + 3 * idx[3 * t + 1], *c = pos + 3 * idx[3 * t + 2];
        double den, l0, l1, l2;
        int k;
        if (a[1] != 1.0f || b[1] != 1.0f || c[1] != 1.0f) continue;
        /* barycentrics in the (x, z) plane */
        den = (double)(b[2] - c[2]) * (a[0] - c[0]) + (double)(c[0] - b[0]) * (a[2] - c[2]);
        l0 = ((double)(b[2] - c[2]) * (p[0] - c[0]) + (double)(c[0] - b[0]) * (p[2] - c[2])) / den;
        l1 = ((double)(c[2] - a[2]) * (p[0] - c[0]) + (double)(a[0] - c[0]) * (p[2] - c[2])) / den;
        l2 = 1.0 - l0 - l1;
        if (l0 < -1e-12 || l1 < -1e-12 || l2 < -1e-12) continue;
        for (k = 0; k < 3; k++)
            n[k] = l0 * nrm[3 * idx[3 * t] + k] + l1 * nrm[3 * idx[3 * t + 1] + k] + l2 * nrm[3 * idx[3 * t + 2] + k];
        return 1;
    }
    return 0;
}

static int inside_cube(const double p[3])
{
    return fabs(p[0]) < 1.0 && fabs(p[1]) < 1.0 && fabs(p[2]) < 1.0;
}

/* On one of the cube's edges, where two planes meet: a ray entering one
 * there can leave the other at once, and which plane the tracer's triangle
 * test picks is a tie. */
static int on_edge(const double p[3])
{
    return (fabs(fabs(p[0]) - 1.0) < 1e-9) + (fabs(fabs(p[1]) - 1.0) < 1e-9) + (fabs(fabs(p[2]) - 1.0) < 1e-9) >= 2;
}

/* (a) Grazing rays onto the top face's edge strip: which way each branch goes. */
static void grazing_colour(const snell_ref *ref, const snell_mesh *mesh)
{
    snell_ref_params p;
    int a, z, facing_away = 0, rays = 0;
    memset(&p, 0, sizeof p);
    p.mode = SNELL_REF_FULL;
    p.max_interfaces = 1;
    p.env_fn = split_world;
    for (a = 1; a <= 6; a++)          /* 1..6 degrees above the plane */
        for (z = 0; z < 5; z++) {     /* hits at z = 0.80 .. 0.96 */
            double el = a * 3.14159265358979323846 / 180.0, zh = 0.80 + 0.04 * z;
            double d[3] = {0.0, -sin(el), cos(el)}, o[3] = {0.13, 1.0 + 2.0 * sin(el), zh - 2.0 * cos(el)}, n[3];
            snell_ref_path path;
            CHECK_OK(snell_ref_trace_ray(ref, &p, o, d, &path));
            CHECK(path.hit && path.interfaces == 1 && fabs(path.points[1][1] - 1.0) < 1e-9,
                  "%d deg, z %.2f: the ray meets the top face (hit %d, %d interfaces, y %.6f)", a, zh, path.hit,
                  path.interfaces, path.points[1][1]);
            if (!path.hit || !top_normal(mesh, path.points[1], n)) continue;
            rays++;
            facing_away += dot3(n, d) > 0.0;
            CHECK(fabs(path.rgb[0] - path.fresnel) < EPS_COLOUR && fabs(path.rgb[1] - (1.0 - path.fresnel)) < EPS_COLOUR &&
                      path.rgb[2] == 0.0,
                  "%d deg, z %.2f (smooth normal . ray %.3f): red %.6f (reflected light above the plane) should be F "
                  "%.6f, green %.6f (transmitted light below it) 1 - F",
                  a, zh, dot3(n, d) / sqrt(dot3(n, n)), path.rgb[0], path.fresnel, path.rgb[1]);
        }
    /* The test is about these rays: most of them meet a smooth normal that faces away. */
    CHECK(rays == 30 && facing_away >= 15, "%d of %d grazing rays meet a smooth normal facing away", facing_away,
          rays);
    printf("(a) %d grazing rays, %d where the smooth normal faces away from the ray\n", rays, facing_away);
}

/* (b) The dominant path's points against the cube's solid, from four sides. */
static void path_sides(const snell_ref *ref)
{
    snell_ref_params p;
    int view, x, y, paths = 0, points = 0;
    memset(&p, 0, sizeof p);
    p.mode = SNELL_REF_FULL;
    p.max_interfaces = SNELL_REF_MAX_INTERFACES;
    p.env_fn = split_world;
    for (view = 0; view < 4; view++)
        for (y = 0; y < 41; y++)
            for (x = 0; x < 41; x++) {
                /* eyes at distance 4 above, beside, below and from a corner; rays through a 41 x 41 grid
                 * spanning the cube's extent seen from there, steep to grazing */
                static const double eyes[4][3] = {{0.3, 4.0, -1.7}, {4.0, 1.4, 0.2}, {0.4, -3.6, 2.1}, {3.0, 3.0, 2.6}};
                const double *e = eyes[view];
                double tgt[3] = {-1.2 + 2.4 * x / 40.0, -1.2 + 2.4 * y / 40.0, 1.2 - 2.4 * ((x + y) % 41) / 40.0}, d[3];
                snell_ref_path path;
                int k, i, in = 0, ok = 1, tie = 0;
                for (k = 0; k < 3; k++) d[k] = tgt[k] - e[k];
                CHECK_OK(snell_ref_trace_ray(ref, &p, e, d, &path));
                if (!path.hit) continue;
                paths++;
                for (i = 1; i <= path.interfaces && ok; i++) {
                    /* the side of each segment after point i, from its midpoint (the last: a step along exit_dir) */
                    double mid[3], after;
                    int ev = path.events[i];
                    for (k = 0; k < 3; k++)
                        mid[k] = i < path.interfaces ? 0.5 * (path.points[i][k] + path.points[i + 1][k])
                                                     : path.points[i][k] + 1e-3 * path.exit_dir[k];
                    after = inside_cube(mid);
                    if (on_edge(path.points[i])) {
                        in = (int)after;
                        tie = 1;
                        continue;
                    }
                    points++;
                    if (!in)
                        ok = (ev == SNELL_REF_EVENT_REFRACT) == (after != 0); /* from air: entered, or stayed out */
                    else if (ev != SNELL_REF_EVENT_REFRACT)
                        ok = after != 0; /* a reflection inside stays inside */
                    CHECK(ok,
                          "view %d ray (%d, %d): interface %d (event %d) %s glass, next segment %s (point %.4f %.4f %.4f)",
                          view, x, y, i, ev, in ? "from" : "outside", after ? "inside" : "outside", path.points[i][0],
                          path.points[i][1], path.points[i][2]);
                    in = (int)after;
                }
                CHECK(!ok || tie || path.ended_inside == (path.interfaces >= SNELL_REF_MAX_INTERFACES && in),
                      "view %d ray (%d, %d): ended inside %d after %d interfaces (last segment inside %d)", view, x, y,
                      path.ended_inside, path.interfaces, in);
            }
    CHECK(paths > 2000, "only %d paths met the cube", paths);
    printf("(b) %d paths, %d interface points checked\n", paths, points);
}

int main(void)
{
    snell_mesh *mesh = test_smooth_cube(4);
    snell_glass g;
    snell_ref_desc rd;
    snell_ref *ref = NULL;
    double top[3] = {0.0, 1.0, 0.0}, n[3];
    CHECK(mesh != NULL, "the smooth cube: %s", snell_last_error(NULL));
    if (!mesh) return test_finish();
    /* Outward normals where the faces are flat: the top face's middle. */
    CHECK(top_normal(mesh, top, n) && n[1] > 0.999999, "smooth normal at the top face's centre (%.6f %.6f %.6f)",
          n[0], n[1], n[2]);
    memset(&g, 0, sizeof g);
    g.mesh = mesh;
    g.material.ior = 1.5f;
    memset(&rd, 0, sizeof rd);
    rd.glass = &g;
    rd.glass_count = 1;
    CHECK_OK(snell_ref_create(NULL, &rd, &ref));
    if (ref) {
        grazing_colour(ref, mesh);
        path_sides(ref);
    }
    snell_ref_destroy(ref);
    snell_mesh_destroy(mesh);
    return test_finish();
}
