/* SPDX-License-Identifier: MIT */
/* defaults.c — the renderer's and the frame's descriptions with every
 * default applied, once: snell_renderer_create and snell_render resolve
 * what they are given here, then validate the resolved copy (sokol_gfx's
 * order), and the stages see only resolved values. */
#include "frame/camera.h"
#include "frame/lighting.h"
#include "render/renderer.h"
#include "frame/env.h"

#include <string.h>

void snell_renderer_defaults(const snell_renderer_desc *in, snell_renderer_desc *out)
{
    snell_renderer_desc d;
    memset(&d, 0, sizeof d);
    if (in) d = *in;
    if (!d.width) d.width = SNELL_DEFAULT_RENDER_SIZE;
    if (!d.height) d.height = SNELL_DEFAULT_RENDER_SIZE;
    if (d.ssaa == 0) d.ssaa = 1;
    if (d.msaa == 1) d.msaa = 0;
    *out = d;
}

void snell_frame_defaults(const snell_frame_desc *in, snell_frame_desc *out)
{
    snell_frame_desc f;
    memset(&f, 0, sizeof f);
    if (in) f = *in;
    snell__camera_defaults(&f.camera, &f.camera);
    if (f.light.type != SNELL_LIGHT_NONE) snell__light_defaults(&f.light, &f.light);
    if (f.receiver.extent > 0.0f || f.light.type != SNELL_LIGHT_NONE) snell__receiver_defaults(&f.receiver, &f.receiver);
    if (f.scene_layers == SNELL_SCENE_LAYERS_AUTO) f.scene_layers = SNELL_DEFAULT_SCENE_LAYERS;
    if (!f.dynamic_env_size && f.env && f.env->size > 0) {
        /* Unger 4.1: lower resolution than the static map; half of it, capped. */
        f.dynamic_env_size = f.env->size / 2;
        if (f.dynamic_env_size > 256) f.dynamic_env_size = 256;
        if (f.dynamic_env_size < 16) f.dynamic_env_size = 16;
    }
    *out = f;
}
