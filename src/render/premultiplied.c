/* SPDX-License-Identifier: MIT */
/* premultiplied.c — premultiplied alpha output (snell_renderer_desc.
 * premultiplied_alpha): a stage that draws nothing and adds a kernel hook,
 * whose variant runs each glass kernel twice a pixel, with the environment
 * 0 and 1, and writes what the glass shows of the rest premultiplied, alpha
 * 1 - the environment's weight (common/output.glsl). */
#include "render/stages.h"
#include "frame/glass_program.h"

static int wanted(const snell__frame *f, const void *state)
{
    (void)f, (void)state;
    return 0; /* nothing to draw: the hook alone */
}

static unsigned variant(const snell__frame *f, const void *state, const snell__object *o)
{
    (void)state, (void)o;
    return f->r->premultiplied ? 1u : 0u;
}

static const char *hook_defines(unsigned bits)
{
    (void)bits;
    return "#define SNELL_PREMULTIPLIED 1\n";
}

static void hook_uniforms(const snell__glass_program *g, const int *locs, const void *state, const snell__view *v,
                          const snell__object *o)
{
    (void)g, (void)locs, (void)state, (void)v, (void)o;
}

static const snell__kernel_hook g_hook = {
    .variant_bits = 1,
    .defines = hook_defines,
    .uniforms = hook_uniforms,
};

const snell__stage snell__stage_premultiplied = {
    .name = "premultiplied",
    .wanted = wanted,
    .kernel_variant = variant,
    .kernel = &g_hook,
};
