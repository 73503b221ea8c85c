/* SPDX-License-Identifier: MIT */
/* material.h — resolving a glass material (material.c): defaults, validation
 * and the derived absorption, for the renderer and the reference tracer. */
#ifndef SNELL_MATERIAL_H
#define SNELL_MATERIAL_H

#include "core/core.h"

/* snell_glass_defaults but for the methods' parameters, with the object's
 * index in messages ("glass 3: ..."): what the reference tracer uses. */
snell_status snell__glass_resolve(const snell_glass_material *in, int object, snell_glass_resolved *out);

#endif
