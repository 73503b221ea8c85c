/* SPDX-License-Identifier: MIT */
/* shaders_embedded.h — the table of GLSL sources under shaders_es/, generated
 * into the build tree at build time by cmake/embed_shaders.cmake. */
#ifndef SNELL_SHADERS_EMBEDDED_H
#define SNELL_SHADERS_EMBEDDED_H

#include <stddef.h>

typedef struct snell_shader_file {
    const char *path;    /* relative to shaders_es/, e.g. "common/optics.glsl" */
    const char *source;
} snell_shader_file;

/* A table's sources packed in one stream (LZ77 + range coder, tools/shader_pack.c), unpacked
 * into unpacked[0..size) once before the table is read; packed NULL: the
 * sources are stored as they are (a build without the pack tool, the readable table). */
typedef struct snell_shader_pack {
    const unsigned char *packed;
    size_t packed_size;
    char *unpacked;
    size_t size;
} snell_shader_pack;

extern const snell_shader_file snell_shader_files[]; /* terminated by {NULL, NULL} */
extern const snell_shader_pack snell_shader_files_pack;
/* The sources as written (comments kept), generated only for test_shader_strip. */
extern const snell_shader_file snell_shader_files_readable[];
extern const snell_shader_pack snell_shader_files_readable_pack;
/* Test hook: build later programs from table (NULL: the embedded one again). */
void snell__shader_table_set(const snell_shader_file *table);

#endif
