/* SPDX-License-Identifier: MIT */
/* prepared.c — see prepared.h. Keys use the mesh pointer and its
 * process-unique geometry version, so a freed mesh's address reused by a new
 * mesh cannot match a stale entry. */
#include "render/prepared.h"
#include "core/ctx.h"

#include <string.h>

void snell__prepared_frame(snell__prepared_cache *c) { c->frame++; }

static int matches(const snell__prepared_entry *e, const snell__method *m, const snell_mesh *mesh, const int key[4])
{
    return e->method == m && e->mesh == mesh && e->version == mesh->version && !memcmp(e->key, key, sizeof e->key);
}

static void release(snell_ctx *ctx, snell__prepared_entry *e)
{
    if (e->data) {
        if (e->method->release) e->method->release(e->data);
        snell__free(&ctx->alloc, e->data);
    }
    memset(e, 0, sizeof *e);
}

/* An entry for the key: the matching one; else an empty slot; else the
 * least recently used entry of another frame (the same method's data block
 * is kept, so its GL objects can be resized in place). */
static snell__prepared_entry *find_slot(snell__prepared_cache *c, const snell__method *m, const snell__object *o,
                                        const int key[4], int *hit)
{
    snell__prepared_entry *empty = NULL, *lru = NULL, *same_mesh = NULL;
    int i;
    *hit = 0;
    for (i = 0; i < SNELL__PREPARED_SLOTS; i++) {
        snell__prepared_entry *e = &c->e[i];
        if (!e->method) {
            if (!empty) empty = e;
            continue;
        }
        if (matches(e, m, o->mesh, key)) {
            *hit = e->ready;
            return e;
        }
        if (e->frame == c->frame) continue;
        /* A deformed mesh (new version) or new settings: take over its slot. */
        if (e->method == m && e->mesh == o->mesh && !same_mesh) same_mesh = e;
        if (!lru || e->frame < lru->frame) lru = e;
    }
    return same_mesh ? same_mesh : empty ? empty : lru;
}

snell_status snell__prepared_lookup(snell_ctx *ctx, snell__prepared_cache *c, const snell__method *m, void *state,
                                    const snell__object *o, snell_object_stats *stats, void **out)
{
    snell__prepared_entry *e;
    int key[4] = {0, 0, 0, 0}, hit;
    snell_status st;
    *out = NULL;
    if (!m->prepare) return SNELL_OK;
    m->key(o, key);
    e = find_slot(c, m, o, key, &hit);
    if (!e) /* cannot happen: more slots than objects in a frame */
        return snell__fail(ctx, SNELL_E_LIMIT, "prepared-resource cache full");
    e->frame = c->frame;
    if (hit) {
        stats->skipped |= SNELL_SKIP_PREPARE;
        *out = e->data;
        return SNELL_OK;
    }
    if (e->method && e->method != m) release(ctx, e);
    if (!e->data) {
        e->data = snell__calloc(&ctx->alloc, 1, m->prepared_size);
        if (!e->data) {
            memset(e, 0, sizeof *e);
            return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for prepared resources");
        }
    }
    e->method = m;
    e->mesh = o->mesh;
    e->version = o->mesh->version;
    memcpy(e->key, key, sizeof e->key);
    e->ready = 0;
    st = m->prepare(ctx, state, o, e->data, stats);
    if (st != SNELL_OK) {
        release(ctx, e);
        return st;
    }
    e->ready = 1;
    stats->prepared = 1;
    *out = e->data;
    return SNELL_OK;
}

snell_status snell__prepared_get(snell_ctx *ctx, snell__prepared_cache *c, const snell__method *m, void *state,
                                 snell__object *o, snell_object_stats *stats)
{
    return snell__prepared_lookup(ctx, c, m, state, o, stats, &o->prepared);
}

void snell__prepared_destroy(snell_ctx *ctx, snell__prepared_cache *c)
{
    int i;
    for (i = 0; i < SNELL__PREPARED_SLOTS; i++)
        if (c->e[i].method) release(ctx, &c->e[i]);
}
