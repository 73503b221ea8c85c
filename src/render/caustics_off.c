/* SPDX-License-Identifier: MIT */
/* caustics_off.c — the caustics stage in a build without SNELL_WITH_CAUSTICS
 * (cmake/components.cmake; the device preset): a frame that asks for a light
 * on a receiver is refused with the option named, one without them is drawn
 * as in any build, and the stage never runs. */
#include "render/caustics.h"
#include "core/core.h"

snell_status snell__caustics_validate(snell_ctx *ctx, const snell_frame_desc *fd)
{
    if (fd->light.type != SNELL_LIGHT_NONE || fd->receiver.extent != 0.0f)
        return snell__fail(ctx, SNELL_E_UNSUPPORTED, "frame has a light or a receiver: built without "
                           "SNELL_WITH_CAUSTICS");
    return SNELL_OK;
}

int snell__caustics_wanted(const snell_frame_desc *fd, char *why, size_t n)
{
    (void)fd;
    snell__why(why, n, "built without SNELL_WITH_CAUSTICS");
    return 0;
}

snell_status snell__caustics_run(snell_ctx *ctx, snell__caustics *c,
                                 const snell_frame_desc *fd, const snell__scene *sc, snell_frame_stats *s)
{
    (void)c, (void)fd, (void)sc, (void)s;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "caustics: built without SNELL_WITH_CAUSTICS");
}

snell_status snell__caustics_read(snell_ctx *ctx, snell__caustics *c, float *rgba, int *size)
{
    (void)c, (void)rgba, (void)size;
    return snell__fail(ctx, SNELL_E_UNSUPPORTED, "caustics: built without SNELL_WITH_CAUSTICS");
}

void snell__receiver_view(snell__view *v, snell__caustics *c, const snell_receiver *rc)
{
    (void)v, (void)c, (void)rc;
}

const snell__kernel_hook snell__receiver_hook = {0, NULL, NULL, 0, NULL}; /* no bits: never in a variant */

/* Never called: without the stage nothing lights the opaque objects (snell__frame.lit_opaque stays NULL). */
void snell__lit_opaque_uniforms(unsigned prog, const snell__caustics *c, int unit) { (void)prog, (void)c, (void)unit; }

void snell__caustics_destroy(snell__caustics *c) { (void)c; }
