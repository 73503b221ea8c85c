/* SPDX-License-Identifier: MIT */
/* optics.h — the optics kernel shared by every method and the references:
 * Snell refraction with TIR, mirror reflection, Schlick and exact Fresnel,
 * Beer-Lambert (Unger 2.1), per-channel IOR and refraction for dispersion. GLSL
 * twin: shaders_es/common/optics.glsl (tests/test_optics_twin.c). snell_opt_*
 * floats mirror the GPU, snell_optd_* doubles serve the references.
 * Conventions: i the unit direction of travel, n the unit normal on the side
 * the ray comes from (dot(i, n) <= 0), eta = n1 / n2. */
#ifndef SNELL_OPTICS_H
#define SNELL_OPTICS_H

#include <math.h>

#define SNELL_OPTICS_DEFINE(T, SUF, SQRT, EXP)                                               \
    static inline T snell_opt##SUF##_dot(const T a[3], const T b[3])                               \
    {                                                                                              \
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];                                            \
    }                                                                                              \
    /* r = i - 2 (n.i) n */                                                                        \
    static inline void snell_opt##SUF##_reflect(const T i[3], const T n[3], T r[3])                \
    {                                                                                              \
        T d = (T)2 * snell_opt##SUF##_dot(n, i);                                                   \
        r[0] = i[0] - d * n[0];                                                                    \
        r[1] = i[1] - d * n[1];                                                                    \
        r[2] = i[2] - d * n[2];                                                                    \
    }                                                                                              \
    /* Refracted direction into t; returns 0 and the reflection on TIR. */                        \
    static inline int snell_opt##SUF##_refract(const T i[3], const T n[3], T eta, T t[3])          \
    {                                                                                              \
        T c = -snell_opt##SUF##_dot(n, i);                                                         \
        T k = (T)1 - eta * eta * ((T)1 - c * c);                                                   \
        T f;                                                                                       \
        if (k < (T)0) {                                                                            \
            snell_opt##SUF##_reflect(i, n, t);                                                     \
            return 0;                                                                              \
        }                                                                                          \
        f = eta * c - SQRT(k);                                                                     \
        t[0] = eta * i[0] + f * n[0];                                                              \
        t[1] = eta * i[1] + f * n[1];                                                              \
        t[2] = eta * i[2] + f * n[2];                                                              \
        return 1;                                                                                  \
    }                                                                                              \
    /* Schlick's reflectance for light going from n1 into n2 at incidence cosine                   \
     * cos_i. Going into a thinner medium the transmitted angle's cosine is used                   \
     * (Schlick is symmetric in the larger angle), and TIR gives 1. Matched                        \
     * indices are no interface: 0 (Schlick's formula would leave a rim of                         \
     * (1 - cos_i)^5 there). */                                                                    \
    static inline T snell_opt##SUF##_fresnel_schlick(T cos_i, T n1, T n2)                          \
    {                                                                                              \
        T r0 = (n1 - n2) / (n1 + n2), c = cos_i < (T)0 ? -cos_i : cos_i, m;                        \
        if (n1 == n2) return (T)0;                                                                 \
        r0 *= r0;                                                                                  \
        if (n1 > n2) {                                                                             \
            T eta = n1 / n2, sin2_t = eta * eta * ((T)1 - c * c);                                  \
            if (sin2_t >= (T)1) return (T)1;                                                       \
            c = SQRT((T)1 - sin2_t);                                                               \
        }                                                                                          \
        m = (T)1 - c;                                                                              \
        return r0 + ((T)1 - r0) * m * m * m * m * m;                                               \
    }                                                                                              \
    /* The exact reflectance of unpolarised light at a smooth dielectric                           \
     * interface, n1 into n2 at incidence cosine cos_i: the mean of the s and p                    \
     * Fresnel equations (Born & Wolf 1.5.2; Pharr et al., PBRT 8.2.1),                            \
     * rs = (n1 ci - n2 ct) / (n1 ci + n2 ct), rp = (n2 ci - n1 ct) / (n2 ci + n1 ct),             \
     * R = (rs^2 + rp^2) / 2; 1 on TIR, 0 at matched indices. What FULL and                        \
     * Cycles' Glass BSDF use. */                                                                  \
    static inline T snell_opt##SUF##_fresnel_exact(T cos_i, T n1, T n2)                            \
    {                                                                                              \
        T ci = cos_i < (T)0 ? -cos_i : cos_i, eta = n1 / n2, sin2_t, ct, rs, rp;                   \
        if (n1 == n2) return (T)0;                                                                 \
        if (ci > (T)1) ci = (T)1;                                                                  \
        sin2_t = eta * eta * ((T)1 - ci * ci);                                                     \
        if (sin2_t >= (T)1) return (T)1;                                                           \
        ct = SQRT((T)1 - sin2_t);                                                                  \
        rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);                                            \
        rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);                                            \
        return (T)0.5 * (rs * rs + rp * rp);                                                       \
    }                                                                                              \
    /* Transmittance exp(-sigma * d) of a path of length d (sigma per unit length). */             \
    static inline void snell_opt##SUF##_beer_lambert(const T sigma[3], T d, T out[3])              \
    {                                                                                              \
        out[0] = EXP(-sigma[0] * d);                                                               \
        out[1] = EXP(-sigma[1] * d);                                                               \
        out[2] = EXP(-sigma[2] * d);                                                               \
    }                                                                                              \
    /* A thin wall (slab of the given thickness, index ior, in air) hit at                         \
     * incidence cosine cos_i: reflectance rs and transmittance ts (rgb) of all                    \
     * inner bounces summed (incoherently, with the unpolarised reflectance r of                   \
     * one face, as the Whitted tree treats a solid slab), Beer-Lambert along the                  \
     * refracted chord thickness / cos_t. Light leaves parallel to how it came.                    \
     * exact: r is snell_opt_fresnel_exact (FULL), else Schlick (the kernels). */                  \
    static inline void snell_opt##SUF##_thin_slab_model(T cos_i, T ior, const T sigma[3], T thickness, \
                                                        int exact, T rs[3], T ts[3])               \
    {                                                                                              \
        T c = cos_i < (T)0 ? -cos_i : cos_i;                                                       \
        T r = exact ? snell_opt##SUF##_fresnel_exact(c, (T)1, ior) : snell_opt##SUF##_fresnel_schlick(c, (T)1, ior); \
        T s2 = ((T)1 - c * c) / (ior * ior), ct = SQRT((T)1 - (s2 < (T)1 ? s2 : (T)1));             \
        int k;                                                                                     \
        for (k = 0; k < 3; k++) {                                                                  \
            if (r >= (T)1) { /* grazing or total reflection: the sum below is 0/0 */               \
                rs[k] = (T)1;                                                                      \
                ts[k] = (T)0;                                                                      \
                continue;                                                                          \
            }                                                                                      \
            T ti = EXP(-sigma[k] * thickness / (ct > (T)1e-6 ? ct : (T)1e-6)), d = (T)1 - r * r * ti * ti; \
            rs[k] = r + ((T)1 - r) * ((T)1 - r) * r * ti * ti / d;                                 \
            ts[k] = ((T)1 - r) * ((T)1 - r) * ti / d;                                              \
        }                                                                                          \
    }                                                                                              \
    /* Dispersion (KHR_materials_dispersion): the IOR at wavelength lambda_nm of a                 \
     * material with IOR ior at 587.6 nm and dispersion = 20 / V_d (V_d the Abbe                   \
     * number), by the spec's two-term Cauchy fit n = A + B / lambda^2 through n_d                 \
     * with n_F - n_C = (n_d - 1) / V_d: n_d + (n_d - 1) / V_d (523655 / lambda^2                  \
     * - 1.5168), at least 1. */                                                                   \
    static inline T snell_opt##SUF##_dispersion_ior(T ior, T dispersion, T lambda_nm)               \
    {                                                                                              \
        T n = ior + (ior - (T)1) * dispersion / (T)20 * ((T)523655 / (lambda_nm * lambda_nm) - (T)1.5168); \
        return n > (T)1 ? n : (T)1;                                                                \
    }                                                                                              \
    /* The IOR of each colour channel: red at the C line (656.3 nm), green at d                    \
     * (587.6 nm: ior itself, as the spec's implementation note has it; the fit                    \
     * gives it within 1.5e-4 (ior - 1) / V_d), blue at F (486.1 nm): the lines V_d                \
     * is defined by. Without dispersion every channel is ior exactly. */                          \
    static inline void snell_opt##SUF##_ior_rgb(T ior, T dispersion, T out[3])                    \
    {                                                                                              \
        int disperses = dispersion > (T)0;                                                         \
        out[0] = disperses ? snell_opt##SUF##_dispersion_ior(ior, dispersion, (T)656.3) : ior;     \
        out[1] = ior;                                                                              \
        out[2] = disperses ? snell_opt##SUF##_dispersion_ior(ior, dispersion, (T)486.1) : ior;     \
    }                                                                                              \
    /* Per colour channel c, the direction i[c] refracted with eta[c] at the                       \
     * normal n[c] into t[c] (its mirror direction where that channel is totally                   \
     * reflected); returns a bit per channel that refracted (1 red, 2 green, 4                     \
     * blue). What the kernels' one-path dispersion does at each interface. */                     \
    static inline int snell_opt##SUF##_refract_rgb(const T i[3][3], const T n[3][3], const T eta[3], T t[3][3]) \
    {                                                                                              \
        int c, through = 0;                                                                        \
        for (c = 0; c < 3; c++)                                                                    \
            if (snell_opt##SUF##_refract(i[c], n[c], eta[c], t[c])) through |= 1 << c;             \
        return through;                                                                            \
    }                                                                                              \
    /* The kernels' thin wall: Schlick at both faces. */                                           \
    static inline void snell_opt##SUF##_thin_slab(T cos_i, T ior, const T sigma[3], T thickness,   \
                                                  T rs[3], T ts[3])                                \
    {                                                                                              \
        snell_opt##SUF##_thin_slab_model(cos_i, ior, sigma, thickness, 0, rs, ts);                 \
    }

SNELL_OPTICS_DEFINE(float, , sqrtf, expf)
SNELL_OPTICS_DEFINE(double, d, sqrt, exp)

#undef SNELL_OPTICS_DEFINE

#endif
