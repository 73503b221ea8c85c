/* SPDX-License-Identifier: MIT */
/* ref_scene.h — the reference tracer's scene (ref_scene.c): glass objects
 * with resolved materials and opaque objects, one BVH over all their
 * triangles (or exact spheres), closest-hit queries that see only what a ray
 * in a given medium may see, and the opaque objects' shading. The optics that
 * walk this scene are in ref_trace.c. */
#ifndef SNELL_REF_SCENE_H
#define SNELL_REF_SCENE_H

#include <math.h>

#include "core/core.h"
#include "mesh/bvh.h"
#include "snell/snell_ref.h"

/* A glass object: its material as snell_glass_defaults resolves it, in double. */
typedef struct ref_glass {
    snell_glass_resolved res; /* what snell_ref_set_material / snell_ref_create resolved */
    double ior;
    double ior_rgb[3];        /* per colour channel (snell_optd_ior_rgb); all ior without dispersion */
    double sigma[3];          /* Beer-Lambert absorption per world unit (res.absorption) */
    double tint[3];
    double thickness;         /* thin wall (> 0) of this thickness, world units; 0 = solid */
    int has_sigma, thin;
    double bs_c[3], bs_r;     /* world bounding sphere (snell_ref_bounding_sphere) */
} ref_glass;

typedef struct ref_sphere {
    double c[3], r;
} ref_sphere;

/* Objects are numbered as BVH parts: glass i is part i, opaque j is part
 * glass_count + j. */
struct snell_ref {
    snell_ctx *ctx;
    snell_alloc alloc;
    int glass_count, opaque_count;
    ref_glass glass[SNELL_MAX_GLASS];
    double opaque_color[SNELL_MAX_OPAQUE][3]; /* resolved albedo */
    double opaque_bs[SNELL_MAX_OPAQUE][4];    /* bounding sphere as the renderer's (snell__bounding_sphere) */
    struct ref_lit *lit;      /* snell_ref_set_light's light on the opaque objects (ref_caustics.c);
                               * NULL: opaque.frag's sky light */
    struct ref_plane *plane;  /* snell_ref_set_receiver's plane in the view (ref_plane.c); NULL: none */
    struct ref_backdrop *backdrop; /* snell_ref_set_backdrop's (ref_backdrop.c); NULL: none */
    snell__bvh *bvh;          /* all triangles; NULL for analytic spheres */
    double *normals;          /* 3 per vertex of every object in part order: inverse-transpose(model)
                               * * n, not renormalised (object.vert) */
    uint32_t *indices;        /* 3 per triangle id: vertex numbers into normals */
    int analytic;             /* 1: glass object i is the exact sphere sph[i]; no opaque objects */
    ref_sphere sph[SNELL_MAX_GLASS];
    double eps;               /* tmin of every ray cast, world units */
};

#define REF_SEE_ALL (-1) /* ref_view.glass: every glass object (but excl) */
#define REF_SEE_NONE (-2) /* ref_view.glass: no glass object */

/* What a ray sees. Opaque objects are always seen. A ray inside a solid
 * glass object (medium >= 0) sees only that object's surfaces: objects are
 * taken to be disjoint, and the surfaces of any other glass object that
 * overlaps it are passed through unseen. */
typedef struct ref_view {
    int medium; /* solid glass object the ray travels in, -1 = air */
    int glass;  /* in air: REF_SEE_ALL, REF_SEE_NONE or the one glass object seen */
    int excl;   /* in air: a glass object not seen, -1 = none */
} ref_view;

typedef struct ref_surf {
    double t, p[3];
    double n[3];   /* unit smooth world normal (interpolated, then normalised), not flipped */
    double ng[3];  /* unit geometric normal (the triangle's plane; spheres: n), on the side its vertex
                    * normals point to (outward for a closed mesh with outward normals), not flipped */
    uint32_t prim; /* triangle id, to skip when a ray leaves this point; spheres: SNELL__BVH_NONE */
    int object;    /* glass i -> i, opaque j -> -2 - j (as snell_ref_output.object) */
} ref_surf;

/* Closest surface along o + t d (t > eps) that v admits; skip: the triangle
 * the ray starts on. */
int snell__ref_hit(const snell_ref *r, const double o[3], const double d[3], uint32_t skip, const ref_view *v,
                   ref_surf *s);

/* Radiance of opaque object j at s, lit as shaders_es/opaque.frag lights it:
 * colour * (0.25 + 0.75 * (0.5 + 0.5 * dot(n, normalize(0.3, 1, 0.2)))); with
 * snell_ref_set_light's light, as caustics_opaque.frag: colour * irradiance
 * (snell__ref_lit_irradiance). */
void snell__ref_shade_opaque(const snell_ref *r, int j, const ref_surf *s, double rgb[3]);
/* ref_caustics.c: the irradiance of r->lit at an opaque surface; its release. */
void snell__ref_lit_irradiance(const snell_ref *r, const ref_surf *s, double e[3]);
void snell__ref_lit_free(snell_ref *r);
/* The light frame's caustic map of snell_ref_set_light (3 doubles a texel,
 * flux per texel area facing the light), its size and texel area; NULL if none. */
const double *snell__ref_lit_map(const snell_ref *r, int *size, double *area);
/* ref_plane.c: snell_ref_set_receiver's plane; its release. A ray in air
 * o + t d (unit d) meets it before tmax (from above, inside the square): 1,
 * and rgb (NULL: not wanted) the colour it shows there; 0 without a plane. */
void snell__ref_plane_free(snell_ref *r);
int snell__ref_plane_hit(const snell_ref *r, const double o[3], const double d[3], double tmax, double rgb[3]);
/* ref_backdrop.c: snell_ref_set_backdrop's field; its release. Its hit as
 * snell__ref_plane_hit's (which asks it after the plane). */
void snell__ref_backdrop_free(snell_ref *r);
int snell__ref_backdrop_hit(const snell_ref *r, const double o[3], const double d[3], double tmax, double rgb[3]);

/* Vector helpers of the tracer (double precision). */
static inline double snell__ref_dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Normalises v in place; 0 (v unchanged) if it has no finite length. */
static inline int snell__ref_normalize3(double v[3])
{
    double l = sqrt(snell__ref_dot3(v, v));
    if (!(l > 0.0) || !isfinite(l)) return 0;
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
    return 1;
}

#endif
