/* SPDX-License-Identifier: MIT */
/* water_off.c — the water's frame hooks in a build without SNELL_WITH_WATER
 * (the public API's stubs are generated from snell_water.h): no water can
 * be made, so a frame never has one, and these are never reached with one. */
#include "water/water_draw.h"

snell_status snell__water_copy_scene(snell_ctx *ctx, snell__water_programs *p, unsigned read_fbo, int width, int height)
{
    (void)p, (void)read_fbo, (void)width, (void)height;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "water: built without SNELL_WITH_WATER");
}

snell_status snell__water_draw(snell_ctx *ctx, snell__water_programs *p, snell__output_kind out, snell_water *w,
                               const snell__view *v, unsigned env_texture, int env_paraboloid,
                               const snell_opaque *objects, int object_count, int layers, snell_frame_stats *stats)
{
    (void)p, (void)out, (void)w, (void)v, (void)env_texture, (void)env_paraboloid, (void)objects;
    (void)object_count, (void)layers, (void)stats;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "water: built without SNELL_WITH_WATER");
}

const char *const snell__water_uniform_names[SNELL__WATER_UNIFORMS] = {"", "", "", "", "", "", "", "", ""};
void snell__water_set_uniforms(const int *locs, const snell_water *w) { (void)locs, (void)w; }
void snell__water_publish(const snell_water *w, snell__textures *ts) { (void)w, (void)ts; }
void snell__water_uniforms(unsigned prog, const snell__samplers *samplers, const snell_water *w)
{
    (void)prog, (void)samplers, (void)w;
}

void snell__water_programs_destroy(snell__water_programs *p) { (void)p; }
