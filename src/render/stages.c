/* SPDX-License-Identifier: MIT */
/* stages.c — the frame as a table of stages in frame order (frame/stage.h):
 * AUTO by budget's plan -> opaque objects -> caustics (the light's maps, which
 * the glass set-up's dynamic environments light the opaque objects with) ->
 * glass set-up (method, mesh, prepared resources, dynamic environment,
 * shading) -> scene layers -> water -> back faces -> G-buffer -> kernels ->
 * background -> resolves -> refine -> glass panels. snell_render
 * (renderer.c) runs the entries a frame wants. Adding a stage: its module
 * and one line of SNELL__STAGE_TABLE. */
#include "render/renderer.h"

#include <stddef.h>

/* The table: one line S(name) per stage, in frame order; each line declares
 * snell__stage_<name> (defined in its module) and takes it into the table. */
#define SNELL__STAGE_TABLE(S) \
    S(budget)                 \
    S(backdrop)               \
    S(opaque)                 \
    S(caustics)               \
    S(glass)                  \
    S(layers)                 \
    S(water)                  \
    S(back_faces)             \
    S(gbuffer)                \
    S(kernels)                \
    S(background)             \
    S(ssaa)                   \
    S(msaa)                   \
    S(premultiplied)          \
    SNELL__STAGE_REFINE(S)    \
    SNELL__STAGE_PANELS(S)

/* The refine stage is a component (SNELL_WITH_REFINE; not in the device preset). */
#if SNELL_WITH_REFINE
#define SNELL__STAGE_REFINE(S) S(refine)
#else
#define SNELL__STAGE_REFINE(S)
#endif
/* The glass panels over the frame, drawn last (SNELL_WITH_PANELS; not in the device preset). */
#if SNELL_WITH_PANELS
#define SNELL__STAGE_PANELS(S) S(panels)
#else
#define SNELL__STAGE_PANELS(S)
#endif

#define DECLARE(name) extern const snell__stage snell__stage_##name;
SNELL__STAGE_TABLE(DECLARE)
#undef DECLARE

#define ENTRY(name) &snell__stage_##name,
const snell__stage *const snell__stages[] = {SNELL__STAGE_TABLE(ENTRY)};
#undef ENTRY
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
