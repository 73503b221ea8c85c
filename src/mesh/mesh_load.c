/* SPDX-License-Identifier: MIT */
/* mesh_load.c — snell_mesh_load: picks the loader by file extension. */
#include "mesh/mesh.h"

#include <stdio.h>
#include <string.h>

/* ASCII case-insensitive "does path end in ext" (ext lower-case, with the dot);
 * deliberately not strcasecmp, which is POSIX and locale-dependent. */
static int has_ext(const char *path, const char *ext)
{
    size_t lp = strlen(path), le = strlen(ext), i;
    if (lp < le) return 0;
    for (i = 0; i < le; i++) {
        char c = path[lp - le + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != ext[i]) return 0;
    }
    return 1;
}

/* The mesh loaders by file extension: format, function, component. A
 * component left out keeps its rows without a function, so its files are
 * refused naming the option; its public functions are generated stubs
 * (cmake/components.cmake, off_stubs.cmake). */
#if SNELL_WITH_GLTF
#define LOAD_GLTF snell_mesh_load_gltf
#else
#define LOAD_GLTF NULL
#endif
#if SNELL_WITH_3DS
#define LOAD_3DS snell__mesh_load_3ds
#define LOAD_JOBJ snell__mesh_load_jobj
#else
#define LOAD_3DS NULL
#define LOAD_JOBJ NULL
#endif
static const struct {
    const char *ext;
    snell_status (*load)(snell_ctx *ctx, const char *path, snell_mesh **out);
    const char *option;
} g_loaders[] = {
    {".obj", snell_mesh_load_obj, NULL},
    {".gltf", LOAD_GLTF, "SNELL_WITH_GLTF"},
    {".glb", LOAD_GLTF, "SNELL_WITH_GLTF"},
    {".3ds", LOAD_3DS, "SNELL_WITH_3DS"},
    {".jobj", LOAD_JOBJ, "SNELL_WITH_3DS"},
};
#define LOADER_COUNT (sizeof g_loaders / sizeof *g_loaders)

snell_status snell_mesh_load(snell_ctx *ctx, const char *path, snell_mesh **out)
{
    char known[64] = "";
    size_t i, n = 0;
    if (out) *out = NULL;
    if (!path || !out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load: path and out are required");
    for (i = 0; i < LOADER_COUNT; i++) {
        if (!has_ext(path, g_loaders[i].ext)) continue;
        if (!g_loaders[i].load)
            return snell__fail(ctx, SNELL_E_UNSUPPORTED, "cannot load '%s': built without %s (configure with -D%s=ON)",
                               path, g_loaders[i].option, g_loaders[i].option);
        return g_loaders[i].load(ctx, path, out);
    }
    for (i = 0; i < LOADER_COUNT && n < sizeof known; i++)
        n += (size_t)snprintf(known + n, sizeof known - n, "%s%s", i ? ", " : "", g_loaders[i].ext);
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "'%s': unknown mesh file extension (supported: %s)", path, known);
}
