/* SPDX-License-Identifier: MIT */
/* snell_panels.h — glass panels over the frame (snell_frame_desc.panels):
 * thin slabs with a bevelled edge lying on what the frame shows, refracted
 * by Snell's law with an index of refraction, drawn last. Included by
 * snell.h. The model, which the GPU stage and the reference
 * (snell_ref_panels) share, is below and in docs/panels.md. */
#ifndef SNELL_SNELL_PANELS_H
#define SNELL_SNELL_PANELS_H

#ifdef __cplusplus
extern "C" {
#endif

/* The model. Coordinates are the frame's pixels, origin at its bottom-left
 * corner (GL's window coordinates relative to the frame's rectangle); a
 * pixel's centre is at (i + 0.5, j + 0.5).
 * - Field: each shape has a signed distance d(p) in pixels (< 0 inside).
 *   Every shape is a rectangle of half size b = size / 2 with corner radius
 *   r (the radius of p's quadrant) and exponent n: with q = |p - centre| -
 *   (b - r), d = ||max(q, 0)||_n + min(max(q.x, q.y), 0) - r, where
 *   ||v||_n = (|v.x|^n + |v.y|^n)^(1/n). n = 2 gives circular corners;
 *   n > 2 superelliptic ones (continuous curvature as the corner turns).
 *   Panels of one group merge: d = smin(d1, d2) with k = merge, applied in
 *   order, smin(a, b) = min(a, b) - max(k - |a - b|, 0)^2 / (4 k).
 * - Height: the glass fills 0 <= z <= h(s) over the plane of what lies
 *   beneath (z = 0), s = -d the distance inside: h = thickness for
 *   s >= bevel, thickness * P(s / bevel) below, P(u) = sqrt(1 - (1 - u)^2)
 *   (CIRCULAR) or (1 - (1 - u)^4)^(1/4) (SQUIRCLE); 0 outside.
 * - Light: the viewer looks straight down (0, 0, -1) at every pixel. The
 *   ray meets the top at (p, h) with normal n = normalize(h'(s) grad d, 1),
 *   refracts into the glass (1 / ior) and reaches z = 0 at p + h t.xy / -t.z;
 *   what lies beneath is read there (bilinear; frost: its Gaussian blur of
 *   sigma frost pixels). Colour = (1 - F) mix(beneath, tint.rgb, tint.a) +
 *   F rim max(0, dot(reflect, light))^4, F the unpolarised Fresnel
 *   reflectance at the top. With dispersion the red, green and blue rays
 *   each refract at their own index (snell_glass_material's rule for the
 *   Abbe number). The light inside the slab is not followed further (the
 *   slab rests on what lies beneath).
 * - Values: what lies beneath as the target's colour buffer stores them
 *   (any normalized or float format, multisampled or not; an integer one
 *   is refused). On an sRGB buffer the panels work in its encoded values,
 *   as the rest of the frame does (written unencoded: render/host_target.h).
 * - Edge: a pixel is the mean over its area, so the rim is antialiased.
 * - Shadow: outside the shape, what lies beneath is darkened by
 *   opacity * (1 - clamp(d(p - offset) / radius, 0, 1))^2. */

typedef enum snell_panel_bevel {
    SNELL_PANEL_BEVEL_CIRCULAR = 0, /* a quarter circle when thickness = bevel: the strongest rim */
    SNELL_PANEL_BEVEL_SQUIRCLE      /* flatter near the top, steeper at the rim */
} snell_panel_bevel;

/* One panel. Zero means a default that looks like the system design for
 * every field; where zero is also a value (sharp corners, no shadow, no
 * rim), a negative number asks for it. */
typedef struct snell_panel {
    float center[2];                /* pixels from the frame's bottom-left corner; any finite value (a panel
                                     * off the frame is culled) */
    float size[2];                  /* full width and height, pixels, > 0 and finite */
    float radius[4];                /* corner radii, pixels, counter-clockwise from the bottom-left:
                                     * bottom-left, bottom-right, top-right, top-left; clamped to half the
                                     * shorter side; all 0 = 0.25 of the shorter side; < 0 = sharp.
                                     * A capsule or a circle: a radius of half the shorter side */
    float exponent;                 /* of the corners, 2..16: 2 circular; 0 = 2; a superellipse: its
                                     * exponent with the radius of half the shorter side */
    float thickness;                /* of the slab, pixels; 0 = bevel */
    float bevel;                    /* width of the bevelled edge, pixels; 0 = min(24, half the shorter side);
                                     * clamped to half the shorter side; < 0 = none (a flat pane) */
    snell_panel_bevel bevel_profile;
    float ior;                      /* 1..3; 0 = 1.5 */
    float dispersion;               /* KHR_materials_dispersion: 20 / Abbe number, 0..20; 0 = none */
    float frost;                    /* Gaussian blur of what lies beneath, sigma in pixels, 0..64; 0 = clear */
    float tint[4];                  /* rgb 0..1 laid over what lies beneath with opacity a; all 0 = none */
    float rim;                      /* strength of the reflected light, 0..16; 0 = 1; < 0 = none */
    float light[3];                 /* direction towards the light (normalised by snell); all 0 =
                                     * (-0.5, 0.5, 0.707): from the top-left */
    float shadow[4];                /* radius (pixels; 0 a hard edge), opacity 0..1, offset x, offset y;
                                     * all 0 = (16, 0.2, 0, -4); radius < 0 = none */
    int group;                      /* 0: alone; panels with the same group > 0 merge into one shape (the
                                     * first of them gives the material, its shadow and its place in the
                                     * order), at most SNELL_PANEL_GROUP_MAX */
    float merge;                    /* the group's smoothing distance k, pixels; 0 = 16; < 0 = a plain union */
} snell_panel;

#define SNELL_MAX_PANELS 4096
#define SNELL_PANEL_GROUP_MAX 8

/* What lies beneath the panels (snell_frame_desc.panels_under). */
typedef enum snell_panels_under_source {
    SNELL_PANELS_UNDER_TARGET = 0,  /* what the frame's rectangle holds when the panels are drawn (the host's
                                     * frame and snell's objects), copied once a frame */
    SNELL_PANELS_UNDER_TEXTURE,     /* an app's GL_TEXTURE_2D, over the frame's rectangle */
    SNELL_PANELS_UNDER_EXTERNAL     /* an app's GL_TEXTURE_EXTERNAL_OES (camera preview, video), where the
                                     * context has OES_EGL_image_external_essl3; without it the frame falls
                                     * back to TARGET and the stats say so */
} snell_panels_under_source;

typedef struct snell_panels_under {
    snell_panels_under_source source;
    unsigned texture;               /* TEXTURE, EXTERNAL: the texture name, required */
    float uv_transform[16];         /* column-major, applied to (u, v, 0, 1) across the frame's rectangle
                                     * (Android's SurfaceTexture.getTransformMatrix); all 0 = identity;
                                     * outside 0..1 the texture's edge texels (clamped) */
    int draw;                       /* TEXTURE, EXTERNAL: 1 = draw the texture over the frame's rectangle first
                                     * (the picture under the panels); 0 = it is there already */
} snell_panels_under;

/* What the panels stage dropped to hold the frame's budget
 * (snell_frame_stats.panels_dropped): with budget_ms, when its estimate of
 * the panels' cost (their boxes' pixels and taps at a Raspberry Pi 4's
 * rate) is over it, frost goes first, then dispersion. */
typedef enum snell_panels_dropped {
    SNELL_PANELS_DROPPED_FROST = 1 << 0,
    SNELL_PANELS_DROPPED_DISPERSION = 1 << 1
} snell_panels_dropped;

#ifdef __cplusplus
}
#endif
#endif
