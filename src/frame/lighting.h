/* SPDX-License-Identifier: MIT */
/* lighting.h — the light's and the receiver's defaults, resolved once for
 * the renderer (snell_frame_defaults) and the reference tracer alike: a
 * light's colour (all zero = 1), spot angle and photons; a receiver's albedo
 * (all zero = 0.8 grey) and light-map size; an opaque object's albedo (all
 * zero = 0.8 grey). Nothing is validated. */
#ifndef SNELL_LIGHTING_H
#define SNELL_LIGHTING_H

#include "core/core.h"

void snell__light_defaults(const snell_light *in, snell_light *out);
void snell__receiver_defaults(const snell_receiver *in, snell_receiver *out);
void snell__opaque_defaults(const snell_opaque *in, snell_opaque *out);

#endif
