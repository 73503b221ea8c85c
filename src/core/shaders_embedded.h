/* shaders_embedded.h — the table of GLSL sources under shaders_es/, generated
 * into the build tree at build time by cmake/embed_shaders.cmake. */
#ifndef SNELL_SHADERS_EMBEDDED_H
#define SNELL_SHADERS_EMBEDDED_H

typedef struct snell_shader_file {
    const char *path;    /* relative to shaders_es/, e.g. "common/optics.glsl" */
    const char *source;
} snell_shader_file;

extern const snell_shader_file snell_shader_files[]; /* terminated by {NULL, NULL} */

#endif
