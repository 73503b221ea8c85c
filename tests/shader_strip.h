/* SPDX-License-Identifier: MIT */
/* shader_strip.h — for test_shader_strip*.c: a scene renders the same bytes
 * from the stripped shader table the library embeds and from the sources as
 * written (generated/shaders_readable.c, linked into these tests only), each
 * time in a fresh context so that every program is built from that table. */
#ifndef SNELL_TEST_SHADER_STRIP_H
#define SNELL_TEST_SHADER_STRIP_H

#include "test_util.h"
#include "core/program.h"
#include "core/shaders_embedded.h"

#include <stdlib.h>
#include <string.h>

/* Renders one scene into px (w * h * 4 bytes) on ctx; returns SNELL_OK. */
typedef snell_status (*strip_scene_fn)(snell_ctx *ctx, int variant, int w, int h, uint8_t *px);

/* Bytes of a table's sources (NUL excluded). */
static inline size_t strip_table_bytes(const snell_shader_file *t)
{
    size_t n = 0;
    for (; t->path; t++) n += strlen(t->source);
    return n;
}

/* Renders scene variant from both tables; CHECKs the status and the bytes. */
static inline void strip_compare(const char *name, strip_scene_fn scene, int variant, int w, int h)
{
    uint8_t *a = (uint8_t *)calloc((size_t)w * h * 4, 1), *b = (uint8_t *)calloc((size_t)w * h * 4, 1);
    const snell_shader_file *tables[2] = {snell_shader_files, snell_shader_files_readable};
    uint8_t *out[2] = {a, b};
    int t;
    for (t = 0; t < 2; t++) {
        snell_ctx *ctx = NULL;
        snell_status st;
        snell__shader_table_set(tables[t]);
        /* The table in use is the one asked for: the readable one has comments. */
        CHECK((strstr(snell__shader_source("object.vert"), "//") != NULL) == (t == 1), "%s: table %d not in use", name, t);
        st = snell_ctx_create(NULL, &ctx);
        if (st == SNELL_OK) st = scene(ctx, variant, w, h, out[t]);
        CHECK(st == SNELL_OK, "%s (%s sources): %s: %s", name, t ? "readable" : "stripped", snell_status_str(st),
              snell_last_error(ctx));
        snell_ctx_destroy(ctx);
    }
    snell__shader_table_set(NULL);
    {
        long diff = 0, i;
        for (i = 0; i < (long)w * h * 4; i++) diff += a[i] != b[i];
        CHECK(diff == 0, "%s: %ld bytes differ between the stripped and the readable shaders", name, diff);
        printf("%-34s %s\n", name, diff == 0 ? "byte-identical" : "DIFFERS");
    }
    free(a);
    free(b);
}

#endif
