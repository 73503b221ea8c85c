/* stages.c — the frame as a table of stages in frame order (frame/stage.h):
 * AUTO by budget's plan -> opaque objects -> caustics (the light's maps, which
 * the glass set-up's dynamic environments light the opaque objects with) ->
 * glass set-up (method, mesh, prepared resources, dynamic environment,
 * shading) -> scene layers -> water -> back faces -> G-buffer -> kernels ->
 * background -> resolves. snell_render (renderer.c) runs the entries a frame
 * wants. Adding a stage: its module and one line here. */
#include "render/stages.h"

#include <stddef.h>

const snell__stage *const snell__stages[] = {
    &snell__stage_budget,
    &snell__stage_opaque,
    &snell__stage_caustics,
    &snell__stage_glass,
    &snell__stage_layers,
    &snell__stage_water,
    &snell__stage_back_faces,
    &snell__stage_gbuffer,
    &snell__stage_kernels,
    &snell__stage_background,
    &snell__stage_ssaa,
    &snell__stage_msaa,
};
const int snell__stage_count = (int)(sizeof snell__stages / sizeof *snell__stages);

typedef char snell__stages_fit[sizeof snell__stages / sizeof *snell__stages <= SNELL__STAGES_MAX ? 1 : -1];

void *snell__renderer_stage_state(const snell_renderer *r, const snell__stage *stage)
{
    int i;
    for (i = 0; i < snell__stage_count; i++)
        if (snell__stages[i] == stage) return r->stage_state[i];
    return NULL;
}

struct snell__caustics *snell__renderer_caustics(const snell_renderer *r)
{
    return (struct snell__caustics *)snell__renderer_stage_state(r, &snell__stage_caustics);
}
