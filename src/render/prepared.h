/* SPDX-License-Identifier: MIT */
/* prepared.h — the "prepare" stage's cache: per (mesh version, method,
 * settings key) the resources a method builds for a mesh (baked cubemaps,
 * per-vertex data), owned by the renderer. It holds twice as many entries as
 * a frame can have glass objects (each object's method's, and the exact
 * method's BVH that the caustics' photons borrow), and only evicts (least recently used)
 * entries that the current frame has not used, so a scene never re-prepares
 * within or across frames while it and its settings stay the same. */
#ifndef SNELL_PREPARED_H
#define SNELL_PREPARED_H

#include "frame/method.h"

#define SNELL__PREPARED_SLOTS (2 * SNELL_MAX_GLASS)

typedef struct snell__prepared_entry {
    const snell__method *method;    /* NULL: empty */
    const snell_mesh *mesh;
    unsigned version;
    int key[4];
    int ready;                      /* prepare() succeeded for this key */
    unsigned long frame;            /* last frame that used it */
    void *data;                     /* method->prepared_size bytes */
} snell__prepared_entry;

typedef struct snell__prepared_cache {
    snell__prepared_entry e[SNELL__PREPARED_SLOTS];
    unsigned long frame;
} snell__prepared_cache;

/* Starts a frame (entries used from now on are pinned for this frame). */
void snell__prepared_frame(snell__prepared_cache *c);
/* The object's prepared resources, built (stats->prepared = 1) if missing
 * or reused (SNELL_SKIP_PREPARE). Sets o->prepared. */
snell_status snell__prepared_get(snell_ctx *ctx, snell__prepared_cache *c, const snell__method *m, void *state,
                                 snell__object *o, snell_object_stats *stats);
/* The same for any method m and object o, into *out (o->prepared is left
 * alone): a stage borrowing a method's resources for the object's mesh (the
 * caustics' photons walk exact's BVH), shared with that method's objects. */
snell_status snell__prepared_lookup(snell_ctx *ctx, snell__prepared_cache *c, const snell__method *m, void *state,
                                    const snell__object *o, snell_object_stats *stats, void **out);
void snell__prepared_destroy(snell_ctx *ctx, snell__prepared_cache *c);

#endif
