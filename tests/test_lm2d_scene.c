/* SPDX-License-Identifier: MIT */
/* test_lm2d_scene.c — CSV and text scene loading: good files load, malformed
 * ones fail with SNELL_E_PARSE/IO/INVALID_ARG and a message naming the line;
 * edge normals point outward for either winding; hard vs smooth point normals. */
#include "lm2d/lm2d_scene.h"
#include "test_util.h"

#include <math.h>
#include <string.h>

static void expect_fail(const char *file, snell_status want, const char *needle)
{
    snell_scene2d *s = (snell_scene2d *)1;
    snell_status st = snell_scene2d_load(NULL, test_data(file), &s, NULL, NULL);
    const char *msg = snell_last_error(NULL);
    CHECK(st == want, "%s: got %s (%s), want %s", file, snell_status_str(st), msg, snell_status_str(want));
    CHECK(s == NULL, "%s: out not cleared on failure", file);
    CHECK(!needle || strstr(msg, needle), "%s: message \"%s\" lacks \"%s\"", file, msg, needle);
}

static void expect_csv_fail(const char *file, snell_status want)
{
    snell_scene2d *s;
    snell_material2d m;
    snell_status st;
    memset(&m, 0, sizeof m);
    CHECK_OK(snell_scene2d_create(NULL, &s));
    st = snell_scene2d_add_object_csv(s, test_data(file), &m, NULL, NULL);
    CHECK(st == want, "%s: got %s (%s), want %s", file, snell_status_str(st), snell_last_error(NULL),
          snell_status_str(want));
    CHECK(snell_scene2d_object_count(s) == 0, "%s: object added despite the error", file);
    snell_scene2d_destroy(s);
}

/* Outward normals: from the polygon centre, every edge normal points away. */
static void check_outward(snell_scene2d *s, const char *what)
{
    int i, bad = 0;
    CHECK_OK(lm2d_scene_prepare(s));
    for (i = 0; i < s->n_edges; i++) {
        const lm2d_edge *e = &s->edges[i];
        const lm2d_object *o = &s->objs[e->obj];
        float cx = 0.5f * (o->bmin[0] + o->bmax[0]), cy = 0.5f * (o->bmin[1] + o->bmax[1]);
        float mx = 0.5f * (e->p1[0] + e->p2[0]) - cx, my = 0.5f * (e->p1[1] + e->p2[1]) - cy;
        if (mx * e->ng[0] + my * e->ng[1] <= 0.0f) bad++;
        if (fabsf(e->ng[0] * e->ng[0] + e->ng[1] * e->ng[1] - 1.0f) > 1e-5f) bad++;
    }
    CHECK(bad == 0, "%s: %d edges with inward or non-unit normals", what, bad);
}

int main(void)
{
    snell_scene2d *s;
    float view[4];
    int size[2];
    snell_object2d_desc od;
    float ccw[8] = {0, 0, 10, 0, 10, 10, 0, 10}, cw[8] = {0, 0, 0, 10, 10, 10, 10, 0};
    /* octagon-ish circle for smooth normals */
    float circle[2 * 32];
    int i;

    /* good scenes */
    CHECK_OK(snell_scene2d_load(NULL, test_data("lm2d/shadow.txt"), &s, view, size));
    if (s) {
        CHECK(snell_scene2d_object_count(s) == 2 && snell_scene2d_light_count(s) == 1, "shadow.txt: %d objects, %d lights",
              snell_scene2d_object_count(s), snell_scene2d_light_count(s));
        CHECK(size[0] == 256 && size[1] == 256 && view[2] == 256.0f, "shadow.txt: size/view not parsed");
        CHECK(s->objs[1].bmin[0] == 108.0f && s->objs[1].bmax[1] == 160.0f, "inline polygon bounds");
        CHECK(s->lights[0].d.type == SNELL_LIGHT2D_BAR && s->lights[0].d.rays == 40000, "bar light not parsed");
        check_outward(s, "shadow.txt");
        snell_scene2d_destroy(s);
    }
    CHECK_OK(snell_scene2d_load(NULL, test_data("lm2d/prism.txt"), &s, NULL, NULL));
    if (s) {
        CHECK(fabsf(s->objs[0].mat.ior - 1.5f) < 1e-6f && s->objs[0].mat.transmission == 1.0f, "prism material");
        CHECK(s->objs[0].n == 3, "triangle.csv: comment line not skipped (%d points)", s->objs[0].n);
        snell_scene2d_destroy(s);
    }
    /* malformed scenes: status and a message with the file:line */
    expect_fail("lm2d/bad_directive.txt", SNELL_E_PARSE, "bad_directive.txt:2");
    /* the key is not quoted (issue 40 item 4: messages show no file content), its place is */
    expect_fail("lm2d/bad_key.txt", SNELL_E_PARSE, "unknown object key (word 11");
    expect_fail("lm2d/bad_csv_ref.txt", SNELL_E_PARSE, "bad_number.csv:3");
    expect_fail("lm2d/bad_missing.txt", SNELL_E_IO, "does_not_exist.csv");
    expect_fail("lm2d/bad_range.txt", SNELL_E_INVALID_ARG, "bad_range.txt:1");
    expect_fail("lm2d/bad_light.txt", SNELL_E_PARSE, "light type");
    expect_fail("lm2d/bad_size.txt", SNELL_E_PARSE, "size");
    expect_fail("lm2d/bad_rays.txt", SNELL_E_PARSE, "integer");
    expect_fail("lm2d/no_such_scene.txt", SNELL_E_IO, "no_such_scene");
    /* malformed CSV */
    expect_csv_fail("lm2d/bad_number.csv", SNELL_E_PARSE);
    expect_csv_fail("lm2d/bad_two_points.csv", SNELL_E_PARSE);
    expect_csv_fail("lm2d/bad_separator.csv", SNELL_E_PARSE);
    expect_csv_fail("lm2d/bad_inf.csv", SNELL_E_PARSE);
    expect_csv_fail("lm2d/bad_empty.csv", SNELL_E_PARSE);
    expect_csv_fail("lm2d/bad_degenerate.csv", SNELL_E_INVALID_ARG);
    /* in-memory CSV with NUL bytes and huge numbers */
    {
        const snell_alloc *al = snell__ctx_alloc(NULL);
        float *pts;
        int n;
        CHECK(lm2d_parse_csv(NULL, al, "0,0\n1,0\0\n1,1\n", 13, "mem", &pts, &n) == SNELL_E_PARSE, "NUL accepted");
        CHECK(lm2d_parse_csv(NULL, al, "0,0\n1e40,0\n1,1\n", 15, "mem", &pts, &n) == SNELL_E_PARSE, "1e40 accepted");
        CHECK_OK(lm2d_parse_csv(NULL, al, "x;y\r\n0;0\r\n1;0\r\n1;1\r\n", 20, "mem", &pts, &n));
        CHECK(n == 3, "CRLF/semicolon CSV: %d points", n);
        snell__free(al, pts);
    }

    /* either winding gives outward normals */
    CHECK_OK(snell_scene2d_create(NULL, &s));
    memset(&od, 0, sizeof od);
    od.points = ccw;
    od.point_count = 4;
    CHECK_OK(snell_scene2d_add_object(s, &od, NULL));
    od.points = cw;
    od.offset[0] = 50;
    CHECK_OK(snell_scene2d_add_object(s, &od, NULL));
    check_outward(s, "ccw + cw squares");
    /* hard corners keep the edge normal at both ends */
    CHECK(s->edges[0].n1[0] == s->edges[0].ng[0] && s->edges[0].n2[1] == s->edges[0].ng[1], "hard vertex merged");
    snell_scene2d_destroy(s);

    /* smooth: a 32-gon with smooth_angle 30 deg gets averaged point normals */
    CHECK_OK(snell_scene2d_create(NULL, &s));
    for (i = 0; i < 32; i++) {
        circle[2 * i] = 100.0f + 50.0f * cosf(6.2831853f * (float)i / 32.0f);
        circle[2 * i + 1] = 100.0f + 50.0f * sinf(6.2831853f * (float)i / 32.0f);
    }
    od.points = circle;
    od.point_count = 32;
    od.offset[0] = 0;
    od.material.smooth_angle = 30.0f * 3.14159265f / 180.0f;
    CHECK_OK(snell_scene2d_add_object(s, &od, NULL));
    CHECK_OK(lm2d_scene_prepare(s));
    {
        /* point normal at vertex 1 = radial direction */
        const lm2d_edge *e = &s->edges[0];
        float rx = cosf(6.2831853f / 32.0f), ry = sinf(6.2831853f / 32.0f);
        CHECK(fabsf(e->n2[0] - rx) < 1e-4f && fabsf(e->n2[1] - ry) < 1e-4f, "smooth point normal (%g,%g) vs radial (%g,%g)",
              (double)e->n2[0], (double)e->n2[1], (double)rx, (double)ry);
        CHECK(e->n2[0] == s->edges[1].n1[0] && e->n2[1] == s->edges[1].n1[1], "smooth vertex has two different normals");
    }
    /* API misuse */
    CHECK(snell_scene2d_set_object_offset(s, 5, ccw) == SNELL_E_INVALID_ARG, "bad object id accepted");
    {
        snell_light2d_desc L;
        memset(&L, 0, sizeof L);
        L.type = SNELL_LIGHT2D_BAR;
        CHECK(snell_scene2d_add_light(s, &L, NULL) == SNELL_E_INVALID_ARG, "zero-length bar accepted");
        L.type = (snell_light2d_type)7;
        CHECK(snell_scene2d_add_light(s, &L, NULL) == SNELL_E_INVALID_ARG, "unknown light type accepted");
        L.type = SNELL_LIGHT2D_POINT;
        L.power = -1;
        CHECK(snell_scene2d_add_light(s, &L, NULL) == SNELL_E_INVALID_ARG, "negative power accepted");
    }
    od.point_count = 2;
    CHECK(snell_scene2d_add_object(s, &od, NULL) == SNELL_E_INVALID_ARG, "2-point polygon accepted");
    snell_scene2d_destroy(s);
    return test_finish();
}
