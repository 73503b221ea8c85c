/* SPDX-License-Identifier: MIT */
/* panel_model.c — snell_panels.h's defaults and checks (one place for the
 * stage and the reference). */
#include "frame/panel_model.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Coordinates and lengths beyond this many pixels lose float precision in
 * the shader's field; no target is that large. */
#define PANEL_MAX_PIXELS 1.0e6f

static int fail(char *msg, size_t n, int i, const char *field, const char *why)
{
    snprintf(msg, n, "panels[%d].%s %s", i, field, why);
    return 1;
}

static int all_zero(const float *v, int n)
{
    int k;
    for (k = 0; k < n; k++)
        if (v[k] != 0.0f) return 0;
    return 1;
}

static int finite_all(const float *v, int n)
{
    int k;
    for (k = 0; k < n; k++)
        if (!isfinite(v[k])) return 0;
    return 1;
}

static int resolve_one(const snell_panel *in, int i, snell__panel *p, char *msg, size_t n)
{
    float shorter, lim;
    int k;

    memset(p, 0, sizeof *p);
    if (!finite_all(in->center, 2) || fabsf(in->center[0]) > PANEL_MAX_PIXELS ||
        fabsf(in->center[1]) > PANEL_MAX_PIXELS)
        return fail(msg, n, i, "center", "is not finite or beyond 1e6 pixels");
    if (!finite_all(in->size, 2) || !(in->size[0] > 0.0f) || !(in->size[1] > 0.0f) ||
        in->size[0] > PANEL_MAX_PIXELS || in->size[1] > PANEL_MAX_PIXELS)
        return fail(msg, n, i, "size", "must be finite, > 0 and <= 1e6 pixels");
    p->center[0] = in->center[0];
    p->center[1] = in->center[1];
    p->half[0] = 0.5f * in->size[0];
    p->half[1] = 0.5f * in->size[1];
    lim = p->half[0] < p->half[1] ? p->half[0] : p->half[1];
    shorter = 2.0f * lim;

    if (!finite_all(in->radius, 4)) return fail(msg, n, i, "radius", "is not finite");
    for (k = 0; k < 4; k++) {
        float r = all_zero(in->radius, 4) ? 0.25f * shorter : in->radius[k];
        p->radius[k] = r < 0.0f ? 0.0f : r > lim ? lim : r;
    }
    if (!isfinite(in->exponent) || (in->exponent != 0.0f && (in->exponent < 2.0f || in->exponent > 16.0f)))
        return fail(msg, n, i, "exponent", "must be 2..16 (0 = 2)");
    p->exponent = in->exponent == 0.0f ? 2.0f : in->exponent;

    if (!isfinite(in->bevel) || in->bevel > PANEL_MAX_PIXELS)
        return fail(msg, n, i, "bevel", "is not finite or beyond 1e6 pixels");
    p->bevel = in->bevel == 0.0f ? (lim < 24.0f ? lim : 24.0f) : in->bevel < 0.0f ? 0.0f : in->bevel;
    if (p->bevel > lim) p->bevel = lim;
    if (!isfinite(in->thickness) || in->thickness < 0.0f || in->thickness > PANEL_MAX_PIXELS)
        return fail(msg, n, i, "thickness", "must be 0..1e6 pixels (0 = the bevel)");
    p->thickness = in->thickness == 0.0f ? p->bevel : in->thickness;
    if ((unsigned)in->bevel_profile > SNELL_PANEL_BEVEL_SQUIRCLE)
        return fail(msg, n, i, "bevel_profile", "is not a snell_panel_bevel");
    p->profile = in->bevel_profile;

    if (!isfinite(in->ior) || (in->ior != 0.0f && (in->ior < 1.0f || in->ior > 3.0f)))
        return fail(msg, n, i, "ior", "must be 1..3 (0 = 1.5)");
    p->ior = in->ior == 0.0f ? 1.5f : in->ior;
    if (!isfinite(in->dispersion) || in->dispersion < 0.0f || in->dispersion > 20.0f)
        return fail(msg, n, i, "dispersion", "must be 0..20");
    p->dispersion = in->dispersion;
    if (!isfinite(in->frost) || in->frost < 0.0f || in->frost > 64.0f)
        return fail(msg, n, i, "frost", "must be 0..64 pixels");
    p->frost = in->frost;
    for (k = 0; k < 4; k++)
        if (!(in->tint[k] >= 0.0f && in->tint[k] <= 1.0f)) return fail(msg, n, i, "tint", "must be 0..1");
    memcpy(p->tint, in->tint, sizeof p->tint);

    if (!isfinite(in->rim) || in->rim > 16.0f) return fail(msg, n, i, "rim", "must be <= 16 (0 = 1, < 0 = none)");
    p->rim = in->rim == 0.0f ? 1.0f : in->rim < 0.0f ? 0.0f : in->rim;
    if (!finite_all(in->light, 3)) return fail(msg, n, i, "light", "is not finite");
    {
        static const float top_left[3] = {-0.5f, 0.5f, 0.70710678f};
        const float *l = all_zero(in->light, 3) ? top_left : in->light;
        double len = sqrt((double)l[0] * l[0] + (double)l[1] * l[1] + (double)l[2] * l[2]);
        if (!(len > 1e-20)) return fail(msg, n, i, "light", "has no direction");
        for (k = 0; k < 3; k++) p->light[k] = (float)(l[k] / len);
    }

    if (!finite_all(in->shadow, 4)) return fail(msg, n, i, "shadow", "is not finite");
    if (all_zero(in->shadow, 4)) {
        p->shadow[0] = 16.0f;
        p->shadow[1] = 0.2f;
        p->shadow[2] = 0.0f;
        p->shadow[3] = -4.0f;
    } else if (in->shadow[0] >= 0.0f) {
        if (in->shadow[0] > 1.0e4f || in->shadow[1] < 0.0f || in->shadow[1] > 1.0f ||
            fabsf(in->shadow[2]) > 1.0e4f || fabsf(in->shadow[3]) > 1.0e4f)
            return fail(msg, n, i, "shadow", "needs radius <= 1e4, opacity 0..1, |offset| <= 1e4 pixels");
        memcpy(p->shadow, in->shadow, sizeof p->shadow);
    }

    if (in->group < 0) return fail(msg, n, i, "group", "must be >= 0");
    p->group = in->group;
    if (!isfinite(in->merge) || in->merge > 1.0e4f) return fail(msg, n, i, "merge", "must be <= 1e4 pixels");
    p->merge = in->merge == 0.0f ? 16.0f : in->merge < 0.0f ? 0.0f : in->merge;
    return 0;
}

int snell__panels_resolve(const snell_panel *panels, int count, snell__panel *out, char *msg, size_t msg_size)
{
    int i, j;
    if (count < 0 || count > SNELL_MAX_PANELS) {
        snprintf(msg, msg_size, "panel_count %d outside 0..%d", count, SNELL_MAX_PANELS);
        return 1;
    }
    if (count > 0 && !panels) {
        snprintf(msg, msg_size, "panel_count %d with no panels", count);
        return 1;
    }
    for (i = 0; i < count; i++)
        if (resolve_one(&panels[i], i, &out[i], msg, msg_size)) return 1;
    /* A group's size: its members are counted where the group first appears. */
    for (i = 0; i < count; i++) {
        int members = 0, first = 1;
        if (out[i].group == 0) continue;
        for (j = 0; j < i && first; j++)
            if (out[j].group == out[i].group) first = 0;
        if (!first) continue;
        for (j = i; j < count; j++)
            if (out[j].group == out[i].group) members++;
        if (members > SNELL_PANEL_GROUP_MAX) {
            snprintf(msg, msg_size, "panels group %d has %d members, at most %d", out[i].group, members,
                     SNELL_PANEL_GROUP_MAX);
            return 1;
        }
    }
    return 0;
}

void snell__panel_bounds(const snell__panel *p, float box[4])
{
    /* smin lowers the field by at most k/4, so a group's shape reaches that
     * far past its members' union; one pixel more for the edge's coverage. */
    float grow = (p->group ? 0.25f * p->merge : 0.0f) + 1.0f;
    float sx = p->shadow[1] > 0.0f ? p->shadow[2] : 0.0f, sy = p->shadow[1] > 0.0f ? p->shadow[3] : 0.0f;
    float sr = p->shadow[1] > 0.0f ? p->shadow[0] : 0.0f;
    float x0 = p->center[0] - p->half[0] - grow, x1 = p->center[0] + p->half[0] + grow;
    float y0 = p->center[1] - p->half[1] - grow, y1 = p->center[1] + p->half[1] + grow;
    box[0] = x0 < x0 + sx - sr ? x0 : x0 + sx - sr;
    box[1] = y0 < y0 + sy - sr ? y0 : y0 + sy - sr;
    box[2] = x1 > x1 + sx + sr ? x1 : x1 + sx + sr;
    box[3] = y1 > y1 + sy + sr ? y1 : y1 + sy + sr;
}
