// SPDX-License-Identifier: MIT
// panel_copy.frag - an app's texture drawn over the frame's rectangle through
// its uv transform (render/panels_stage.c): what lies beneath the panels.
// PANEL_EXTERNAL: a GL_TEXTURE_EXTERNAL_OES (OES_EGL_image_external_essl3).
#ifndef PANEL_EXTERNAL
#define PANEL_EXTERNAL 0
#endif
#if PANEL_EXTERNAL
#extension GL_OES_EGL_image_external_essl3 : require
#endif
precision highp float;

#if PANEL_EXTERNAL
uniform highp samplerExternalOES u_image;
#else
uniform highp sampler2D u_image;
#endif
uniform mat4 u_uv;   // column-major, applied to (u, v, 0, 1)
uniform vec2 u_size; // the frame's

out vec4 o_color;

void main()
{
    vec2 uv = (u_uv * vec4(gl_FragCoord.xy / u_size, 0.0, 1.0)).xy;
    o_color = texture(u_image, uv);
}
