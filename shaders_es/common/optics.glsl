// SPDX-License-Identifier: MIT
// optics.glsl - GLSL twin of src/core/optics.h (keep the two in step; the test
// tests/test_optics_twin.c compares them on a grid of inputs).
// i: unit direction of travel, n: unit normal facing the incoming ray,
// eta = n1 / n2.

vec3 snell_reflect(vec3 i, vec3 n)
{
    return i - 2.0 * dot(n, i) * n;
}

// Refracted direction in t; false and the mirror direction on total internal reflection.
bool snell_refract(vec3 i, vec3 n, float eta, out vec3 t)
{
    float c = -dot(n, i);
    float k = 1.0 - eta * eta * (1.0 - c * c);
    if (k < 0.0) {
        t = snell_reflect(i, n);
        return false;
    }
    t = eta * i + (eta * c - sqrt(k)) * n;
    return true;
}

// Per colour channel c: i[c] refracted with eta[c] at the normal n[c] into
// t[c] (its mirror direction where that channel is totally reflected); true
// for each channel that refracted. What the one-path dispersion does at each
// interface (common/dispersion.glsl).
bvec3 snell_refract_rgb(mat3 i, mat3 n, vec3 eta, out mat3 t)
{
    vec3 r, g, b;
    bvec3 through = bvec3(snell_refract(i[0], n[0], eta.r, r), snell_refract(i[1], n[1], eta.g, g),
                          snell_refract(i[2], n[2], eta.b, b));
    t = mat3(r, g, b);
    return through;
}

// Schlick reflectance from n1 into n2; uses the transmitted cosine when n1 > n2, 1 on TIR,
// 0 at matched indices (no interface).
float snell_fresnel_schlick(float cos_i, float n1, float n2)
{
    if (n1 == n2) return 0.0;
    float r0 = (n1 - n2) / (n1 + n2);
    float c = abs(cos_i);
    r0 *= r0;
    if (n1 > n2) {
        float eta = n1 / n2;
        float sin2_t = eta * eta * (1.0 - c * c);
        if (sin2_t >= 1.0) return 1.0;
        c = sqrt(1.0 - sin2_t);
    }
    float m = 1.0 - c;
    return r0 + (1.0 - r0) * m * m * m * m * m;
}

// Exact unpolarised dielectric reflectance from n1 into n2: the mean of the s and p
// Fresnel equations; 1 on TIR, 0 at matched indices (src/core/optics.h).
float snell_fresnel_exact(float cos_i, float n1, float n2)
{
    if (n1 == n2) return 0.0;
    float ci = min(abs(cos_i), 1.0);
    float eta = n1 / n2;
    float sin2_t = eta * eta * (1.0 - ci * ci);
    if (sin2_t >= 1.0) return 1.0;
    float ct = sqrt(1.0 - sin2_t);
    float rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);
    float rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
    return 0.5 * (rs * rs + rp * rp);
}

// The Fresnel model a kernel is built with: SNELL_FRESNEL_EXACT 1 selects the
// exact reflectance (the FULL reference's), else Schlick's (the MATCHED model).
#ifndef SNELL_FRESNEL_EXACT
#define SNELL_FRESNEL_EXACT 0
#endif
float snell_fresnel(float cos_i, float n1, float n2)
{
#if SNELL_FRESNEL_EXACT
    return snell_fresnel_exact(cos_i, n1, n2);
#else
    return snell_fresnel_schlick(cos_i, n1, n2);
#endif
}

// snell_refract and snell_fresnel, selected rather than branched (the same
// operations, so the same bits): a value merged from branches stays live
// through a whole loop on V3D (the kernels' interface loops).
bool snell_refract_sel(vec3 i, vec3 n, float eta, out vec3 t)
{
    float c = -dot(n, i);
    float k = 1.0 - eta * eta * (1.0 - c * c);
    vec3 mirror = snell_reflect(i, n), through = eta * i + (eta * c - sqrt(k)) * n;
    t = k < 0.0 ? mirror : through;
    return !(k < 0.0);
}

float snell_fresnel_schlick_sel(float cos_i, float n1, float n2)
{
    float r0 = (n1 - n2) / (n1 + n2);
    float c = abs(cos_i);
    r0 *= r0;
    float eta = n1 / n2;
    float sin2_t = eta * eta * (1.0 - c * c);
    float ct = sqrt(1.0 - sin2_t);
    c = n1 > n2 ? ct : c;
    float m = 1.0 - c;
    float f = r0 + (1.0 - r0) * m * m * m * m * m;
    return n1 == n2 ? 0.0 : n1 > n2 && sin2_t >= 1.0 ? 1.0 : f;
}

float snell_fresnel_sel(float cos_i, float n1, float n2)
{
#if SNELL_FRESNEL_EXACT
    float ci = min(abs(cos_i), 1.0);
    float eta = n1 / n2;
    float sin2_t = eta * eta * (1.0 - ci * ci);
    float ct = sqrt(1.0 - sin2_t);
    float rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);
    float rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
    float f = 0.5 * (rs * rs + rp * rp);
    return n1 == n2 ? 0.0 : sin2_t >= 1.0 ? 1.0 : f;
#else
    return snell_fresnel_schlick_sel(cos_i, n1, n2);
#endif
}

// Transmittance of a path of length d through a medium with coefficient sigma.
vec3 snell_beer_lambert(vec3 sigma, float d)
{
    return exp(-sigma * d);
}

// A thin wall (slab of the given thickness and index ior, in air) hit at
// incidence cosine cos_i: reflectance rs and transmittance ts of all inner
// bounces summed, Schlick at both faces, Beer-Lambert along the refracted chord
// thickness / cos_t. Light leaves parallel to how it came (src/core/optics.h).
void snell_thin_slab(float cos_i, float ior, vec3 sigma, float thickness, out vec3 rs, out vec3 ts)
{
    float c = abs(cos_i);
    float r = snell_fresnel_schlick(c, 1.0, ior);
    if (r >= 1.0) { // grazing or total reflection: the sum below is 0/0
        rs = vec3(1.0);
        ts = vec3(0.0);
        return;
    }
    float ct = sqrt(1.0 - min((1.0 - c * c) / (ior * ior), 1.0));
    vec3 ti = exp(-sigma * (thickness / max(ct, 1e-6)));
    vec3 d = 1.0 - r * r * ti * ti;
    rs = r + (1.0 - r) * (1.0 - r) * r * ti * ti / d;
    ts = (1.0 - r) * (1.0 - r) * ti / d;
}

