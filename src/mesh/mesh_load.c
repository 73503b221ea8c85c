/* SPDX-License-Identifier: MIT */
/* mesh_load.c — snell_mesh_load: picks the OBJ or glTF loader by file extension.
 * Also the glTF stubs for builds without SNELL_WITH_GLTF (mesh_gltf.cpp is then absent). */
#include "mesh/mesh.h"

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

snell_status snell_mesh_load(snell_ctx *ctx, const char *path, snell_mesh **out)
{
    if (out) *out = NULL;
    if (!path || !out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load: path and out are required");
    if (has_ext(path, ".obj")) return snell_mesh_load_obj(ctx, path, out);
    if (has_ext(path, ".gltf") || has_ext(path, ".glb")) return snell_mesh_load_gltf(ctx, path, out);
    if (has_ext(path, ".3ds")) return snell__mesh_load_3ds(ctx, path, out);
    if (has_ext(path, ".jobj")) return snell__mesh_load_jobj(ctx, path, out);
    return snell__fail(ctx, SNELL_E_UNSUPPORTED,
                       "'%s': unknown mesh file extension (supported: .obj, .gltf, .glb, .3ds, .jobj)", path);
}

#if !SNELL_WITH_GLTF
snell_status snell_mesh_load_gltf(snell_ctx *ctx, const char *path, snell_mesh **out)
{
    if (out) *out = NULL;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "cannot load '%s': snell was built without glTF support "
                       "(SNELL_WITH_GLTF=OFF)", path ? path : "(null)");
}

snell_status snell_mesh_load_gltf_ex(snell_ctx *ctx, const char *path, unsigned flags, snell_mesh **out)
{
    (void)flags;
    return snell_mesh_load_gltf(ctx, path, out);
}

snell_status snell_mesh_load_gltf_mem(snell_ctx *ctx, const void *data, size_t size, snell_mesh **out)
{
    (void)data;
    (void)size;
    if (out) *out = NULL;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "snell was built without glTF support (SNELL_WITH_GLTF=OFF)");
}

snell_status snell_scene_load_gltf(snell_ctx *ctx, const char *path, unsigned flags, snell_scene_file **out)
{
    (void)flags;
    if (out) *out = NULL;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "cannot load '%s': snell was built without glTF support "
                       "(SNELL_WITH_GLTF=OFF)", path ? path : "(null)");
}

snell_status snell_scene_load_gltf_mem(snell_ctx *ctx, const void *data, size_t size, snell_scene_file **out)
{
    (void)data;
    (void)size;
    if (out) *out = NULL;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "snell was built without glTF support (SNELL_WITH_GLTF=OFF)");
}

/* Nothing can be loaded, so there is nothing to destroy or read. */
void snell_scene_file_destroy(snell_scene_file *s) { (void)s; }
const snell_glass *snell_scene_file_glass(const snell_scene_file *s, int *count)
{
    (void)s;
    if (count) *count = 0;
    return NULL;
}
const snell_opaque *snell_scene_file_opaque(const snell_scene_file *s, int *count)
{
    (void)s;
    if (count) *count = 0;
    return NULL;
}
int snell_scene_file_camera(const snell_scene_file *s, snell_camera *camera)
{
    (void)s;
    (void)camera;
    return 0;
}
snell_status snell_scene_file_frame(const snell_scene_file *s, float aspect, snell_camera *camera)
{
    (void)s;
    (void)aspect;
    (void)camera;
    return snell__fail(NULL, SNELL_E_UNSUPPORTED, "snell was built without glTF support (SNELL_WITH_GLTF=OFF)");
}
const char *snell_scene_file_glass_name(const snell_scene_file *s, int i)
{
    (void)s;
    (void)i;
    return NULL;
}
const char *snell_scene_file_opaque_name(const snell_scene_file *s, int i)
{
    (void)s;
    (void)i;
    return NULL;
}
#endif
