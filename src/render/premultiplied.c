/* premultiplied.c — premultiplied alpha output (snell_renderer_desc.
 * premultiplied_alpha): a kernel hook with no stage work, whose variant runs
 * each glass kernel twice a pixel, with the environment 0 and 1, and writes
 * what the glass shows of the rest premultiplied, alpha 1 - the environment's
 * weight (common/output.glsl). */
#include "render/premultiplied.h"
#include "render/stages.h"
#include "frame/glass_program.h"

/* Nothing to draw: the hook alone (its variant is asked of every stage each frame). */
int snell__premultiplied_wanted(const snell__frame *f)
{
    (void)f;
    return 0;
}

unsigned snell__premultiplied_variant(const snell__frame *f, const snell__object *o)
{
    (void)o;
    return f->r->premultiplied ? SNELL__GLASS_PREMULTIPLIED : 0;
}

static const char *premultiplied_defines(unsigned bits)
{
    (void)bits;
    return "#define SNELL_PREMULTIPLIED 1\n";
}

static void premultiplied_uniforms(const snell__glass_program *g, const int *locs, const snell__view *v,
                                   const snell__object *o)
{
    (void)g, (void)locs, (void)v, (void)o;
}

const snell__kernel_hook snell__premultiplied_hook = {
    .variant_mask = SNELL__GLASS_PREMULTIPLIED,
    .defines = premultiplied_defines,
    .uniform_names = NULL,
    .uniform_count = 0,
    .uniforms = premultiplied_uniforms,
};
