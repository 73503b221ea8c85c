/* SPDX-License-Identifier: MIT */
/* premultiplied.c — premultiplied alpha output (snell_renderer_desc.
 * premultiplied_alpha): a stage that draws nothing and adds a kernel hook,
 * whose variant runs each glass kernel twice a pixel, with the environment
 * 0 and 1, and writes what the glass shows of the rest premultiplied, alpha
 * 1 - the environment's weight (common/output.glsl). */
#include "render/stages.h"
#include "core/ctx.h"
#include "frame/glass_program.h"

typedef struct premultiplied_state {
    int on;                         /* snell_renderer_desc.premultiplied_alpha */
} premultiplied_state;

static snell_status validate_renderer(snell__services *sv, const snell_renderer_desc *d)
{
    if (d->premultiplied_alpha && (d->premultiplied_alpha != 1 || d->output != SNELL_OUTPUT_COLOR))
        return snell__fail(sv->ctx, SNELL_E_INVALID_ARG, "premultiplied_alpha %d: 0 or 1, with colour output",
                           d->premultiplied_alpha);
    return SNELL_OK;
}

static snell_status create(snell__services *sv, const snell_renderer_desc *d, void *state)
{
    (void)sv;
    ((premultiplied_state *)state)->on = d->premultiplied_alpha;
    return SNELL_OK;
}

static int wanted(const snell__frame *f, const void *state)
{
    (void)f, (void)state;
    return 0; /* nothing to draw: the hook alone */
}

static unsigned variant(const snell__frame *f, const void *state, const snell__object *o)
{
    (void)f, (void)o;
    return ((const premultiplied_state *)state)->on ? 1u : 0u;
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
    .state_size = sizeof(premultiplied_state),
    .validate_renderer = validate_renderer,
    .create = create,
    .wanted = wanted,
    .kernel_variant = variant,
    .kernel = &g_hook,
};
