/* SPDX-License-Identifier: MIT */
/* lighting.c — see lighting.h. */
#include "frame/lighting.h"

#include <string.h>

void snell__light_defaults(const snell_light *in, snell_light *out)
{
    snell_light l;
    int k;
    memset(&l, 0, sizeof l);
    if (in) l = *in;
    if (l.color[0] == 0.0f && l.color[1] == 0.0f && l.color[2] == 0.0f)
        for (k = 0; k < 3; k++) l.color[k] = 1.0f;
    if (l.spot_angle == 0.0f) l.spot_angle = SNELL_DEFAULT_SPOT_ANGLE;
    if (l.photons == 0) l.photons = SNELL_DEFAULT_PHOTONS;
    *out = l;
}

void snell__receiver_defaults(const snell_receiver *in, snell_receiver *out)
{
    snell_receiver rc;
    int k;
    memset(&rc, 0, sizeof rc);
    if (in) rc = *in;
    if (rc.albedo[0] == 0.0f && rc.albedo[1] == 0.0f && rc.albedo[2] == 0.0f)
        for (k = 0; k < 3; k++) rc.albedo[k] = SNELL_DEFAULT_RECEIVER_ALBEDO;
    if (rc.map_size == 0) rc.map_size = SNELL_DEFAULT_RECEIVER_MAP;
    *out = rc;
}

void snell__opaque_defaults(const snell_opaque *in, snell_opaque *out)
{
    snell_opaque o = *in;
    int k;
    if (o.color[0] == 0.0f && o.color[1] == 0.0f && o.color[2] == 0.0f)
        for (k = 0; k < 3; k++) o.color[k] = SNELL_DEFAULT_OPAQUE_ALBEDO;
    *out = o;
}
