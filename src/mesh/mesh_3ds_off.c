/* SPDX-License-Identifier: MIT */
/* mesh_3ds_off.c — glmark2's formats in a build without SNELL_WITH_3DS
 * (the device preset: OBJ only): every entry says so. */
#include "mesh/mesh.h"

static snell_status off(snell_ctx *ctx, snell_mesh **out, const char *what)
{
    if (out) *out = NULL;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "%s: snell was built without .3ds/.jobj support (SNELL_WITH_3DS=OFF)",
                       what);
}

snell_status snell_mesh_load_3ds_mem(snell_ctx *ctx, const void *data, size_t size, snell_mesh **out)
{
    (void)data, (void)size;
    return off(ctx, out, "snell_mesh_load_3ds_mem");
}

snell_status snell_mesh_load_jobj_mem(snell_ctx *ctx, const char *data, size_t size, snell_mesh **out)
{
    (void)data, (void)size;
    return off(ctx, out, "snell_mesh_load_jobj_mem");
}

snell_status snell__mesh_load_3ds(snell_ctx *ctx, const char *path, snell_mesh **out)
{
    (void)path;
    return off(ctx, out, "snell_mesh_load (.3ds)");
}

snell_status snell__mesh_load_jobj(snell_ctx *ctx, const char *path, snell_mesh **out)
{
    (void)path;
    return off(ctx, out, "snell_mesh_load (.jobj)");
}
