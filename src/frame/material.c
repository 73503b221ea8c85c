/* SPDX-License-Identifier: MIT */
/* material.c — the resolve step of a glass material (sokol's _sg_def): zero
 * fields become their documented defaults, the per-unit absorption is
 * derived from glTF's attenuation form, and the channels' IORs from the
 * dispersion (core/optics.h). The methods' parameters are the registry's
 * (methods/registry.c, snell__glass_resolve_all). */
#include "frame/material.h"
#include "core/optics.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define DEFAULT_IOR 1.5f
/* An attenuation colour channel of 0 would mean infinite absorption. */
#define MIN_ATTENUATION_COLOR 1e-6f
#define MAX_DISPERSION 20.0f

static int finite_nonneg(float v) { return isfinite(v) && v >= 0.0f; }

snell_status snell__glass_resolve(const snell_glass_material *in, int object, snell_glass_resolved *out)
{
    snell_glass_material m;
    int k;
    memset(&m, 0, sizeof m);
    if (in) m = *in;
    memset(out, 0, sizeof *out);
    /* The defaults first, then the resolved copy validated (sokol_gfx's
     * order): a message names the value the kernels would see. */
    if (m.ior == 0.0f) m.ior = DEFAULT_IOR;
    if (m.scale == 0.0f) m.scale = 1.0f;
    if (m.tint[0] == 0.0f && m.tint[1] == 0.0f && m.tint[2] == 0.0f) m.tint[0] = m.tint[1] = m.tint[2] = 1.0f;
    if (m.attenuation_color[0] == 0.0f && m.attenuation_color[1] == 0.0f && m.attenuation_color[2] == 0.0f)
        m.attenuation_color[0] = m.attenuation_color[1] = m.attenuation_color[2] = 1.0f;
    /* one path: nearly as accurate as three traces on every kernel, for a
     * cheaper frame where the kernel searches (BENCHMARKS.md, "Dispersion") */
    if (m.dispersion_model == SNELL_DISPERSION_AUTO) m.dispersion_model = SNELL_DISPERSION_ONE_PATH;
    if (!(m.ior >= 0.05f && m.ior <= 100.0f))
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "glass %d: ior %g outside 0.05..100", object, m.ior);
    if (!finite_nonneg(m.attenuation_distance) || !finite_nonneg(m.thickness))
        return snell__fail(NULL, SNELL_E_INVALID_ARG,
                           "glass %d: attenuation_distance and thickness must be finite and >= 0", object);
    for (k = 0; k < 3; k++)
        if (!finite_nonneg(m.attenuation_color[k]) || m.attenuation_color[k] > 1.0f || !finite_nonneg(m.tint[k]))
            return snell__fail(NULL, SNELL_E_INVALID_ARG,
                               "glass %d: attenuation_color must lie in 0..1 and tint be finite and >= 0", object);
    /* 20 is V_d = 1, where n_F - n_C reaches n_d - 1: no glass is near it. */
    if (!finite_nonneg(m.dispersion) || m.dispersion > MAX_DISPERSION)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "glass %d: dispersion %g outside 0..%g", object, m.dispersion,
                           MAX_DISPERSION);
    if ((int)m.dispersion_model < 0 || (int)m.dispersion_model > (int)SNELL_DISPERSION_ONE_PATH)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "glass %d: unknown dispersion_model %d", object,
                           (int)m.dispersion_model);
    /* A scale below 1 would supersample the glass alone: the frame's ssaa does that. */
    if (!(m.scale >= 1.0f && m.scale <= SNELL_MAX_GLASS_SCALE))
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "glass %d: scale %g outside 1..%d", object, m.scale,
                           SNELL_MAX_GLASS_SCALE);
    /* Derived: no attenuation distance is an infinite one. */
    if (m.attenuation_distance == 0.0f) m.attenuation_distance = HUGE_VALF;
    for (k = 0; k < 3; k++) {
        float c = m.attenuation_color[k] > MIN_ATTENUATION_COLOR ? m.attenuation_color[k] : MIN_ATTENUATION_COLOR;
        /* -ln(1) is 0 exactly; an infinite distance gives 0 too. */
        out->absorption[k] = c >= 1.0f ? 0.0f : -logf(c) / m.attenuation_distance;
        if (out->absorption[k] > 0.0f) out->absorbs = 1;
    }
    /* A thin wall sends light on parallel to how it came: no angular spread to show. */
    out->disperses = m.dispersion > 0.0f && m.thickness == 0.0f;
    snell_opt_ior_rgb(m.ior, out->disperses ? m.dispersion : 0.0f, out->ior_rgb);
    out->material = m;
    return SNELL_OK;
}

void snell_glass_set_absorption(snell_glass_material *m, const float sigma[3])
{
    float smax = 0.0f;
    int k;
    if (!m || !sigma) return;
    for (k = 0; k < 3; k++)
        if (sigma[k] > smax) smax = sigma[k];
    memset(m->attenuation_color, 0, sizeof m->attenuation_color);
    m->attenuation_distance = 0.0f;
    if (!(smax > 0.0f) || !isfinite(smax)) return; /* none: the zero (white) default */
    /* Distance 1/smax keeps every colour in [1/e, 1]: no under- or overflow
     * for tiny or huge coefficients, and -ln(c)/d gives sigma back. */
    m->attenuation_distance = 1.0f / smax;
    for (k = 0; k < 3; k++) m->attenuation_color[k] = sigma[k] > 0.0f ? expf(-sigma[k] / smax) : 1.0f;
}

snell_status snell_glass_set_abbe(snell_glass_material *m, float abbe)
{
    if (!m) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_glass_set_abbe: m is NULL");
    if (!isfinite(abbe) || abbe <= 20.0f / MAX_DISPERSION)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_glass_set_abbe: Abbe number %g must be finite and > %g",
                           abbe, 20.0f / MAX_DISPERSION);
    m->dispersion = 20.0f / abbe;
    return SNELL_OK;
}
