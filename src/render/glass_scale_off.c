/* SPDX-License-Identifier: MIT */
/* glass_scale_off.c — the resolution scale in a build without the methods
 * it serves (peel, exact; cmake/components.cmake, the device preset): every
 * object is drawn at scale 1, as snell_object_stats.scale says, and AUTO by
 * budget puts no rung of a larger scale on a ladder. */
#include "render/glass_scale.h"

int snell__glass_scale_max(const snell__method *m)
{
    (void)m;
    return 1;
}

float snell__glass_scale_of(const snell__method *m, snell__output_kind out, const snell__object *o)
{
    (void)m, (void)out, (void)o;
    return 1.0f;
}

snell_status snell__glass_scale_draw(snell_ctx *ctx, snell__glass_scale *gs,
                                     const snell__view *v, const snell__object *o, snell_object_stats *stats,
                                     snell__glass_draw_fn draw, void *user)
{
    (void)gs, (void)v, (void)o, (void)stats, (void)draw, (void)user;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "resolution scale: built without peel and exact");
}

void snell__glass_scale_destroy(snell__glass_scale *gs) { (void)gs; }
