/* SPDX-License-Identifier: MIT */
/* mesh_shapes.c — procedural test objects: UV sphere, cube, torus, a lathe goblet and a prism.
 * All are closed, wound counter-clockwise seen from outside, with analytic normals. */
#include "mesh/mesh.h"

#include <math.h>
#include <string.h>

#define SHAPE_PI 3.14159265358979323846
#define SHAPE_MAX_SUBDIV 4096
/* The goblet profile is long and has tight bends (rim, foot edge): it gets
 * this many profile samples per requested ring. */
#define GOBLET_SAMPLES_PER_RING 4

/* A point of a lathe profile in the (r, y) half-plane, r >= 0, with its unit
 * outward normal (nr, ny). Profiles run so that the outward normal lies on the
 * right of the direction of travel (r to the right, y up). */
typedef struct profile_pt {
    double r, y, nr, ny;
} profile_pt;

/* ------------------------------------------------------------------ lathe */
/* Revolves a profile around +Y. If closed, the profile wraps (torus); else its
 * first and last points must lie on the axis (r = 0) and become single pole
 * vertices, so the surface is a closed 2-manifold with no seam duplicates.
 * Vertex (k, j) sits at angle u = 2*pi*j/segments: (r cos u, y, -r sin u). */
static snell_status lathe(snell_ctx *ctx, const profile_pt *prof, uint32_t np, int closed, uint32_t seg,
                          snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    uint32_t rings = closed ? np : np - 2; /* rings of seg vertices */
    uint32_t bands = closed ? np : np - 3; /* quad bands between rings */
    uint64_t nv64 = (uint64_t)rings * seg + (closed ? 0 : 2);
    uint64_t nt64 = 2ull * bands * seg + (closed ? 0 : 2ull * seg);
    uint32_t nv, nt, k, j, t = 0, pole0 = 0, pole1 = 0;
    float *pos, *nrm;
    uint32_t *idx;
    double *cu, *su;
    snell_status st;
    if (nv64 > SNELL_MESH_MAX_VERTICES || nt64 > SNELL_MESH_MAX_TRIANGLES)
        return snell__fail(ctx, SNELL_E_LIMIT, "shape too finely tessellated: %llu vertices, %llu triangles",
                           (unsigned long long)nv64, (unsigned long long)nt64);
    nv = (uint32_t)nv64;
    nt = (uint32_t)nt64;
    if ((st = snell__mesh_budget_check(ctx, nv, nt, "shape")) != SNELL_OK) return st;
    pos = (float *)snell__calloc(al, 3 * (size_t)nv, sizeof(float));
    nrm = (float *)snell__calloc(al, 3 * (size_t)nv, sizeof(float));
    idx = (uint32_t *)snell__calloc(al, 3 * (size_t)nt, sizeof(uint32_t));
    cu = (double *)snell__calloc(al, seg, sizeof(double));
    su = (double *)snell__calloc(al, seg, sizeof(double));
    if (!pos || !nrm || !idx || !cu || !su) {
        snell__free(al, pos); snell__free(al, nrm); snell__free(al, idx);
        snell__free(al, cu); snell__free(al, su);
        return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for a shape of %u vertices", nv);
    }
    for (j = 0; j < seg; j++) {
        double u = 2.0 * SHAPE_PI * j / seg;
        cu[j] = cos(u);
        su[j] = sin(u);
    }
    for (k = 0; k < rings; k++) {
        const profile_pt *p = &prof[closed ? k : k + 1];
        for (j = 0; j < seg; j++) {
            size_t v = (size_t)k * seg + j;
            pos[3 * v + 0] = (float)(p->r * cu[j]);
            pos[3 * v + 1] = (float)p->y;
            pos[3 * v + 2] = (float)(-p->r * su[j]);
            nrm[3 * v + 0] = (float)(p->nr * cu[j]);
            nrm[3 * v + 1] = (float)p->ny;
            nrm[3 * v + 2] = (float)(-p->nr * su[j]);
        }
    }
    if (!closed) {
        /* poles: on the axis, normals along the axis (normalised profile normal's y sign) */
        pole0 = rings * seg;
        pole1 = pole0 + 1;
        pos[3 * pole0 + 1] = (float)prof[0].y;
        nrm[3 * pole0 + 1] = prof[0].ny < 0 ? -1.0f : 1.0f;
        pos[3 * pole1 + 1] = (float)prof[np - 1].y;
        nrm[3 * pole1 + 1] = prof[np - 1].ny < 0 ? -1.0f : 1.0f;
    }
#define TRI(a, b, c) (idx[3 * t] = (a), idx[3 * t + 1] = (b), idx[3 * t + 2] = (c), t++)
    /* Quad A=(k,j) B=(k,j+1) C=(k+1,j+1) D=(k+1,j): AB runs toward -z, AD up
     * the profile, so AB x AD points outward (right of the profile) at u = 0. */
    for (k = 0; k < bands; k++) {
        uint32_t k1 = (k + 1) % rings;
        for (j = 0; j < seg; j++) {
            uint32_t j1 = (j + 1) % seg;
            uint32_t a = k * seg + j, b = k * seg + j1, c = k1 * seg + j1, d = k1 * seg + j;
            TRI(a, b, c);
            TRI(a, c, d);
        }
    }
    if (!closed)
        for (j = 0; j < seg; j++) {
            uint32_t j1 = (j + 1) % seg;
            TRI(pole0, j1, j);                                            /* bottom fan */
            TRI((rings - 1) * seg + j, (rings - 1) * seg + j1, pole1);   /* top fan */
        }
#undef TRI
    snell__free(al, cu);
    snell__free(al, su);
    return snell__mesh_adopt(ctx, al, pos, nrm, idx, nv, nt, out);
}

/* ------------------------------------------------------------------ shapes */
static snell_status make_sphere(snell_ctx *ctx, uint32_t seg, uint32_t rings, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    profile_pt *prof = (profile_pt *)snell__calloc(al, rings + 1, sizeof *prof);
    uint32_t k;
    snell_status st;
    if (!prof) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for a sphere");
    /* latitude from the south pole (-pi/2) to the north pole; normal = position */
    for (k = 0; k <= rings; k++) {
        double a = -0.5 * SHAPE_PI + SHAPE_PI * k / rings;
        prof[k].r = prof[k].nr = k == 0 || k == rings ? 0.0 : cos(a);
        prof[k].y = prof[k].ny = k == 0 ? -1.0 : k == rings ? 1.0 : sin(a);
    }
    st = lathe(ctx, prof, rings + 1, 0, seg, out);
    snell__free(al, prof);
    return st;
}

static snell_status make_torus(snell_ctx *ctx, uint32_t seg, uint32_t rings, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    profile_pt *prof = (profile_pt *)snell__calloc(al, rings, sizeof *prof);
    const double R = 1.0, rr = 0.4;
    uint32_t k;
    snell_status st;
    if (!prof) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for a torus");
    /* tube circle around (R, 0), counter-clockwise: outward normal on the right */
    for (k = 0; k < rings; k++) {
        double v = 2.0 * SHAPE_PI * k / rings;
        prof[k].nr = cos(v);
        prof[k].ny = sin(v);
        prof[k].r = R + rr * prof[k].nr;
        prof[k].y = rr * prof[k].ny;
    }
    st = lathe(ctx, prof, rings, 1, seg, out);
    snell__free(al, prof);
    return st;
}

static snell_status make_cube(snell_ctx *ctx, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    float *pos = (float *)snell__calloc(al, 72, sizeof(float));
    float *nrm = (float *)snell__calloc(al, 72, sizeof(float));
    uint32_t *idx = (uint32_t *)snell__calloc(al, 36, sizeof(uint32_t));
    int f, c, k;
    if (!pos || !nrm || !idx) {
        snell__free(al, pos); snell__free(al, nrm); snell__free(al, idx);
        return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for a cube");
    }
    /* Face f has normal axis a = f/2, sign s. Its corners are n + su*u + sv*v
     * with (u, v, n) right-handed, so the quad u,v order is counter-clockwise
     * seen from outside. */
    for (f = 0; f < 6; f++) {
        int a = f / 2;
        float s = (f & 1) ? -1.0f : 1.0f;
        int au = (a + 1) % 3, av = (a + 2) % 3;
        static const float cu[4] = {-1, 1, 1, -1}, cv[4] = {-1, -1, 1, 1};
        for (c = 0; c < 4; c++) {
            float *p = pos + 3 * (4 * f + c), *n = nrm + 3 * (4 * f + c);
            p[a] = s;
            /* for the negative face swap the in-plane axes to keep CCW outside */
            p[au] = s > 0 ? cu[c] : cv[c];
            p[av] = s > 0 ? cv[c] : cu[c];
            for (k = 0; k < 3; k++) n[k] = k == a ? s : 0.0f;
        }
        idx[6 * f + 0] = 4 * f + 0; idx[6 * f + 1] = 4 * f + 1; idx[6 * f + 2] = 4 * f + 2;
        idx[6 * f + 3] = 4 * f + 0; idx[6 * f + 4] = 4 * f + 2; idx[6 * f + 5] = 4 * f + 3;
    }
    return snell__mesh_adopt(ctx, al, pos, nrm, idx, 24, 12, out);
}

/* The prism (a dispersion test object: light entering one face next to the
 * apex and leaving through the other is spread by colour): three rectangular
 * sides and two triangular caps, each with its own vertices and flat normal. */
static snell_status make_prism(snell_ctx *ctx, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    float *pos = (float *)snell__calloc(al, 54, sizeof(float));
    float *nrm = (float *)snell__calloc(al, 54, sizeof(float));
    uint32_t *idx = (uint32_t *)snell__calloc(al, 24, sizeof(uint32_t));
    double cx[3], cz[3];
    uint32_t v = 0, t = 0;
    int i, k;
    if (!pos || !nrm || !idx) {
        snell__free(al, pos); snell__free(al, nrm); snell__free(al, idx);
        return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for a prism");
    }
    /* Corners at 0, 120, 240 degrees from +X towards -Z: counter-clockwise
     * seen from +Y, as the lathe's angle runs (x = cos u, z = -sin u). */
    for (i = 0; i < 3; i++) {
        cx[i] = cos(2.0 * SHAPE_PI * i / 3.0);
        cz[i] = -sin(2.0 * SHAPE_PI * i / 3.0);
    }
    for (i = 0; i < 3; i++) { /* side i from corner i to i + 1: outward normal along their mid-point */
        int j = (i + 1) % 3;
        double mx = 0.5 * (cx[i] + cx[j]), mz = 0.5 * (cz[i] + cz[j]), l = sqrt(mx * mx + mz * mz);
        /* seen from outside, corner i is left of corner j: i bottom, j bottom, j top, i top is CCW */
        const double q[4][3] = {{cx[i], -1, cz[i]}, {cx[j], -1, cz[j]}, {cx[j], 1, cz[j]}, {cx[i], 1, cz[i]}};
        for (k = 0; k < 4; k++) {
            pos[3 * (v + k)] = (float)q[k][0];
            pos[3 * (v + k) + 1] = (float)q[k][1];
            pos[3 * (v + k) + 2] = (float)q[k][2];
            nrm[3 * (v + k)] = (float)(mx / l);
            nrm[3 * (v + k) + 2] = (float)(mz / l);
        }
        idx[t++] = v; idx[t++] = v + 1; idx[t++] = v + 2;
        idx[t++] = v; idx[t++] = v + 2; idx[t++] = v + 3;
        v += 4;
    }
    for (k = 0; k < 2; k++) { /* caps: top (+Y) counter-clockwise seen from above, bottom reversed */
        float y = k == 0 ? 1.0f : -1.0f;
        for (i = 0; i < 3; i++) {
            int c = k == 0 ? i : 2 - i;
            pos[3 * (v + i)] = (float)cx[c];
            pos[3 * (v + i) + 1] = y;
            pos[3 * (v + i) + 2] = (float)cz[c];
            nrm[3 * (v + i) + 1] = y;
        }
        idx[t++] = v; idx[t++] = v + 1; idx[t++] = v + 2;
        v += 3;
    }
    return snell__mesh_adopt(ctx, al, pos, nrm, idx, 18, 8, out);
}

/* --- goblet ---------------------------------------------------------------
 * Profile (r, y), from the bottom pole of the foot to the pole at the bottom of
 * the bowl's inside. It is tangent-continuous everywhere (lines joined by
 * arcs), so smooth per-vertex normals are exact: no crease needs split
 * vertices and the lathe stays a closed 2-manifold. Pieces:
 *   foot underside, rounded foot edge, foot top, concave fillet, stem,
 *   concave fillet, outer bowl (sphere), rounded rim, inner bowl (sphere).
 * The bowl wall is the thickening of a spherical arc (centre (0, yc), radius
 * BOWL_R, from the bottom up to BOWL_PHI above the equator, a tulip that
 * narrows at the rim) by +-BOWL_H; the rim is a half circle of radius BOWL_H.
 * Units: object space, y from -1 (foot) to +1 (rim top). */
#define FOOT_R 0.50  /* foot radius */
#define FOOT_T 0.05  /* foot thickness */
#define FOOT_FILLET 0.12
#define STEM_R 0.055
#define STEM_FILLET 0.12
#define BOWL_R 0.55
#define BOWL_H 0.025 /* half the wall thickness */
#define BOWL_PHI (15.0 * SHAPE_PI / 180.0)

typedef struct arc_piece {
    int is_arc;
    double x0, y0, x1, y1;           /* line: from (x0,y0) to (x1,y1) */
    double cx, cy, rad, a0, a1, sgn; /* arc: centre, radius, angles; sgn +1 convex, -1 concave */
    double nr, ny;                   /* line normal */
    double measure;                  /* length + bend weight * |angle| */
} arc_piece;

static void piece_line(arc_piece *p, double x0, double y0, double x1, double y1)
{
    double dx = x1 - x0, dy = y1 - y0, len = sqrt(dx * dx + dy * dy);
    memset(p, 0, sizeof *p);
    p->x0 = x0; p->y0 = y0; p->x1 = x1; p->y1 = y1;
    p->nr = dy / len;  /* right of travel direction (dx, dy) */
    p->ny = -dx / len;
    p->measure = len;
}

static void piece_arc(arc_piece *p, double cx, double cy, double rad, double a0, double a1, double sgn)
{
    memset(p, 0, sizeof *p);
    p->is_arc = 1;
    p->cx = cx; p->cy = cy; p->rad = rad; p->a0 = a0; p->a1 = a1; p->sgn = sgn;
    /* bends are sampled more densely than their length alone would ask */
    p->measure = rad * fabs(a1 - a0) + 0.1 * fabs(a1 - a0);
}

static void piece_eval(const arc_piece *p, double t, profile_pt *o)
{
    if (!p->is_arc) {
        o->r = p->x0 + t * (p->x1 - p->x0);
        o->y = p->y0 + t * (p->y1 - p->y0);
        o->nr = p->nr;
        o->ny = p->ny;
    } else {
        double a = p->a0 + t * (p->a1 - p->a0);
        o->r = p->cx + p->rad * cos(a);
        o->y = p->cy + p->rad * sin(a);
        o->nr = p->sgn * cos(a);
        o->ny = p->sgn * sin(a);
    }
}

static snell_status make_goblet(snell_ctx *ctx, uint32_t seg, uint32_t rings, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    arc_piece pc[9];
    const double yc = 1.0 - BOWL_H - BOWL_R * sin(BOWL_PHI); /* top of rim at y = 1 */
    const double ro = BOWL_R + BOWL_H, ri = BOWL_R - BOWL_H;
    const double ft = -1.0 + FOOT_T;
    /* stem-bowl fillet: centre at distance ro + STEM_FILLET from (0, yc), at r = STEM_R + STEM_FILLET */
    const double fcx = STEM_R + STEM_FILLET;
    const double fcy = yc - sqrt((ro + STEM_FILLET) * (ro + STEM_FILLET) - fcx * fcx);
    const double ad = atan2(yc - fcy, -fcx); /* fillet centre -> bowl centre, in (pi/2, pi) */
    double total = 0.0, acc = 0.0;
    uint32_t np = GOBLET_SAMPLES_PER_RING * rings + 1, k;
    int i = 0;
    profile_pt *prof;
    snell_status st;

    piece_line(&pc[0], 0.0, -1.0, FOOT_R, -1.0);                                        /* underside */
    piece_arc(&pc[1], FOOT_R, -1.0 + 0.5 * FOOT_T, 0.5 * FOOT_T, -0.5 * SHAPE_PI, 0.5 * SHAPE_PI, 1.0);
    piece_line(&pc[2], FOOT_R, ft, STEM_R + FOOT_FILLET, ft);                           /* foot top */
    piece_arc(&pc[3], STEM_R + FOOT_FILLET, ft + FOOT_FILLET, FOOT_FILLET, 1.5 * SHAPE_PI, SHAPE_PI, -1.0);
    piece_line(&pc[4], STEM_R, ft + FOOT_FILLET, STEM_R, fcy);                          /* stem */
    piece_arc(&pc[5], fcx, fcy, STEM_FILLET, SHAPE_PI, ad, -1.0);
    piece_arc(&pc[6], 0.0, yc, ro, ad - SHAPE_PI, BOWL_PHI, 1.0);                      /* outer bowl */
    piece_arc(&pc[7], BOWL_R * cos(BOWL_PHI), yc + BOWL_R * sin(BOWL_PHI), BOWL_H, BOWL_PHI,
              BOWL_PHI + SHAPE_PI, 1.0);                                                /* rim */
    piece_arc(&pc[8], 0.0, yc, ri, BOWL_PHI, -0.5 * SHAPE_PI, -1.0);                   /* inner bowl */
    for (i = 0; i < 9; i++) total += pc[i].measure;

    if ((uint64_t)np * seg > SNELL_MESH_MAX_VERTICES)
        return snell__fail(ctx, SNELL_E_LIMIT, "goblet too finely tessellated (%u x %u)", seg, rings);
    prof = (profile_pt *)snell__calloc(al, np, sizeof *prof);
    if (!prof) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for a goblet");
    /* resample uniformly in the combined length/bend measure */
    i = 0;
    for (k = 0; k < np; k++) {
        double s = total * k / (np - 1);
        while (i < 8 && s > acc + pc[i].measure) acc += pc[i++].measure;
        {
            double t = (s - acc) / pc[i].measure;
            piece_eval(&pc[i], t < 0 ? 0 : t > 1 ? 1 : t, &prof[k]);
        }
    }
    /* exact poles */
    prof[0].r = 0.0; prof[0].nr = 0.0; prof[0].ny = -1.0;
    prof[np - 1].r = 0.0; prof[np - 1].nr = 0.0; prof[np - 1].ny = 1.0;
    st = lathe(ctx, prof, np, 0, seg, out);
    snell__free(al, prof);
    return st;
}

snell_status snell_mesh_create_shape(snell_ctx *ctx, const snell_shape_desc *desc, snell_mesh **out)
{
    int seg, rings;
    if (out) *out = NULL;
    if (!desc || !out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_create_shape: desc and out are required");
    seg = desc->segments ? desc->segments : 64;
    rings = desc->rings ? desc->rings : 32;
    if (seg < 0 || rings < 0)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "shape segments %d / rings %d must not be negative",
                           desc->segments, desc->rings);
    if (seg > SHAPE_MAX_SUBDIV || rings > SHAPE_MAX_SUBDIV)
        return snell__fail(ctx, SNELL_E_LIMIT, "shape segments %d / rings %d exceed %d", seg, rings,
                           SHAPE_MAX_SUBDIV);
    if (seg < 3 || rings < 2)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "shape needs at least 3 segments and 2 rings (got %d, %d)",
                           seg, rings);
    switch (desc->shape) {
    case SNELL_SHAPE_SPHERE: return make_sphere(ctx, (uint32_t)seg, (uint32_t)rings, out);
    case SNELL_SHAPE_CUBE: return make_cube(ctx, out); /* segments/rings do not apply */
    case SNELL_SHAPE_TORUS:
        if (rings < 3) return snell__fail(ctx, SNELL_E_INVALID_ARG, "torus needs at least 3 rings");
        return make_torus(ctx, (uint32_t)seg, (uint32_t)rings, out);
    case SNELL_SHAPE_GOBLET: return make_goblet(ctx, (uint32_t)seg, (uint32_t)rings, out);
    case SNELL_SHAPE_PRISM: return make_prism(ctx, out); /* segments/rings do not apply */
    }
    return snell__fail(ctx, SNELL_E_INVALID_ARG, "unknown shape %d", (int)desc->shape);
}
