/* SPDX-License-Identifier: MIT */
/* lm2d_scene.h — the 2D scene: polygon objects with BSDF parameters, lights,
 * the flattened edge array with edge and point normals (Brückner 6.2), and the
 * change tracking that lets the lightmap re-trace only what changed. */
#ifndef SNELL_LM2D_SCENE_H
#define SNELL_LM2D_SCENE_H

#include "core/core.h"
#include "lm2d/lm2d_bvh.h"
#include "snell/snell_2d.h"

/* One polygon edge p1 -> p2 (world units, offset applied). ng is the outward
 * unit edge normal; n1/n2 the point normals at p1/p2 used for shading (equal to
 * ng at hard vertices, the normalised sum of both edge normals at smooth ones). */
typedef struct lm2d_edge {
    float p1[2], p2[2];
    float n1[2], n2[2];
    float ng[2];
    int obj;
} lm2d_edge;

typedef struct lm2d_object {
    float *pts;                 /* 2 * n, without the offset, duplicates removed */
    int n;
    snell_material2d mat;       /* defaults resolved (ior >= 1 set, colour set) */
    float offset[2];
    float bmin[2], bmax[2];     /* bounds with offset */
} lm2d_object;

typedef struct lm2d_light {
    snell_light2d_desc d;       /* defaults resolved */
    unsigned version;           /* bumped on every change */
} lm2d_light;

struct snell_scene2d {
    snell_ctx *ctx;
    const snell_alloc *al;
    lm2d_object *objs;
    int n_objs, cap_objs;
    lm2d_light *lights;
    int n_lights, cap_lights;
    /* geometry derived from the objects, rebuilt by lm2d_scene_prepare */
    lm2d_edge *edges;
    int n_edges, cap_edges;
    lm2d_bvh bvh;
    int leaf_size;              /* BVH leaf size used by prepare; 0 = LM2D_BVH_DEFAULT_LEAF */
    int geom_dirty;
    unsigned geom_version;      /* bumped on every object change */
    /* region touched by object changes since version changed_base (union of old
     * and new bounds); a consumer that traced at changed_base may re-trace only
     * the lights whose paths cross it */
    unsigned changed_base;
    float changed_min[2], changed_max[2];
    int changed_any;
};

/* Rebuilds edges and BVH if objects changed. */
snell_status lm2d_scene_prepare(snell_scene2d *scene);
/* Resolved material defaults of an object desc. */
snell_material2d lm2d_material_resolve(const snell_material2d *m);
/* Parses CSV text (one "x,y" per line) into a new array (scene allocator). */
snell_status lm2d_parse_csv(const snell_ctx *ctx, const snell_alloc *al, const char *text, size_t size,
                            const char *name, float **pts, int *n);
/* Reads a whole file (NUL-terminated, size limit 64 MiB). */
snell_status lm2d_read_file(const snell_ctx *ctx, const snell_alloc *al, const char *path, char **text,
                            size_t *size);
/* Parses a scene from text; base_dir prefixes CSV paths (may be ""). */
snell_status lm2d_scene_parse(snell_scene2d *scene, const char *text, const char *name, const char *base_dir,
                              float view[4], int size[2]);

#endif
