/* SPDX-License-Identifier: MIT */
/* pack.h — the C twin of shaders_es/common/pack.glsl: unit directions in
 * octahedral form (Cigolle et al. 2014) and values in [0,1] split across
 * 8-bit channels, so tests know exactly what a packed RGBA8 texel holds. */
#ifndef SNELL_PACK_H
#define SNELL_PACK_H

#include <math.h>
#include <stdint.h>

static inline float snell_pack_sign(float v) { return v >= 0.0f ? 1.0f : -1.0f; }

/* Unit vector -> octahedral coordinates in [-1,1]^2. */
static inline void snell_oct_encode(const float n[3], float e[2])
{
    float l1 = fabsf(n[0]) + fabsf(n[1]) + fabsf(n[2]);
    float x = n[0] / l1, y = n[1] / l1;
    if (n[2] < 0.0f) {
        float ox = (1.0f - fabsf(y)) * snell_pack_sign(x), oy = (1.0f - fabsf(x)) * snell_pack_sign(y);
        x = ox;
        y = oy;
    }
    e[0] = x;
    e[1] = y;
}

/* Octahedral coordinates -> unit vector. */
static inline void snell_oct_decode(const float e[2], float n[3])
{
    float x = e[0], y = e[1], z = 1.0f - fabsf(x) - fabsf(y), len;
    if (z < 0.0f) {
        float ox = (1.0f - fabsf(y)) * snell_pack_sign(x), oy = (1.0f - fabsf(x)) * snell_pack_sign(y);
        x = ox;
        y = oy;
    }
    len = sqrtf(x * x + y * y + z * z);
    n[0] = x / len;
    n[1] = y / len;
    n[2] = z / len;
}

/* v in [0,1] -> 16-bit fixed point as two bytes (high, low), as the GLSL
 * twin writes them into two RGBA8 channels; and back. */
static inline void snell_pack_unorm16(float v, uint8_t *hi, uint8_t *lo)
{
    uint32_t q = (uint32_t)(fminf(fmaxf(v, 0.0f), 1.0f) * 65535.0f + 0.5f);
    *hi = (uint8_t)(q >> 8);
    *lo = (uint8_t)(q & 255u);
}

static inline float snell_unpack_unorm16(uint8_t hi, uint8_t lo) { return (float)((hi << 8) | lo) / 65535.0f; }

/* A unit direction as RGBA8: octahedral x and y, 16 bits each. */
static inline void snell_pack_dir_rgba8(const float n[3], uint8_t px[4])
{
    float e[2];
    snell_oct_encode(n, e);
    snell_pack_unorm16(e[0] * 0.5f + 0.5f, &px[0], &px[1]);
    snell_pack_unorm16(e[1] * 0.5f + 0.5f, &px[2], &px[3]);
}

static inline void snell_unpack_dir_rgba8(const uint8_t px[4], float n[3])
{
    float e[2];
    e[0] = snell_unpack_unorm16(px[0], px[1]) * 2.0f - 1.0f;
    e[1] = snell_unpack_unorm16(px[2], px[3]) * 2.0f - 1.0f;
    snell_oct_decode(e, n);
}

/* An exit direction as RGBA8 with a coverage bit: octahedral x in 16 bits, y
 * in 15, and the low bit of y's word set where the light path went through
 * glass. A direction alone cannot say so: a path that leaves unbent (a slab,
 * IOR 1) has the view ray's direction, which is what the background holds. */
static inline void snell_pack_exit_rgba8(const float n[3], int glass, uint8_t px[4])
{
    float e[2];
    uint32_t q;
    snell_oct_encode(n, e);
    snell_pack_unorm16(e[0] * 0.5f + 0.5f, &px[0], &px[1]);
    q = (uint32_t)(fminf(fmaxf(e[1] * 0.5f + 0.5f, 0.0f), 1.0f) * 32767.0f + 0.5f) * 2u + (glass ? 1u : 0u);
    px[2] = (uint8_t)(q >> 8);
    px[3] = (uint8_t)(q & 255u);
}

/* Returns the coverage bit. */
static inline int snell_unpack_exit_rgba8(const uint8_t px[4], float n[3])
{
    float e[2];
    e[0] = snell_unpack_unorm16(px[0], px[1]) * 2.0f - 1.0f;
    e[1] = (float)(((px[2] << 8) | px[3]) >> 1) / 32767.0f * 2.0f - 1.0f;
    snell_oct_decode(e, n);
    return px[3] & 1;
}

/* ---- normal + distance texels of the cubemap method (Unger 4.1; ndcube.c) ----
 * d is the distance from the cubemap centre divided by the mesh radius about
 * that centre, in [0,1]; n a unit object-space normal. GL converts a float
 * output to UNORM8 as round(clamp(v,0,1) * 255) (GLES 3.0 2.1.6.1). */
static inline uint8_t snell_pack_unorm8(float v) { return (uint8_t)(fminf(fmaxf(v, 0.0f), 1.0f) * 255.0f + 0.5f); }

/* PLAIN (the seed's): rgb = n * 0.5 + 0.5 (Unger eq. 11), a = d; 8 bits each. */
static inline void snell_pack_ndist_plain(const float n[3], float d, uint8_t px[4])
{
    int k;
    for (k = 0; k < 3; k++) px[k] = snell_pack_unorm8(n[k] * 0.5f + 0.5f);
    px[3] = snell_pack_unorm8(d);
}

/* Decoded as the shader does with GL_NEAREST (normal renormalised). */
static inline void snell_unpack_ndist_plain(const uint8_t px[4], float n[3], float *d)
{
    float x = px[0] / 255.0f * 2.0f - 1.0f, y = px[1] / 255.0f * 2.0f - 1.0f, z = px[2] / 255.0f * 2.0f - 1.0f;
    float len = sqrtf(x * x + y * y + z * z);
    if (len > 0.0f) { x /= len; y /= len; z /= len; }
    n[0] = x; n[1] = y; n[2] = z;
    *d = px[3] / 255.0f;
}

/* OCT: rg = octahedral n * 0.5 + 0.5 (8 bits each), ba = d in 16 bits (hi, lo). */
static inline void snell_pack_ndist_oct(const float n[3], float d, uint8_t px[4])
{
    float e[2];
    snell_oct_encode(n, e);
    px[0] = snell_pack_unorm8(e[0] * 0.5f + 0.5f);
    px[1] = snell_pack_unorm8(e[1] * 0.5f + 0.5f);
    snell_pack_unorm16(d, &px[2], &px[3]);
}

static inline void snell_unpack_ndist_oct(const uint8_t px[4], float n[3], float *d)
{
    float e[2];
    e[0] = px[0] / 255.0f * 2.0f - 1.0f;
    e[1] = px[1] / 255.0f * 2.0f - 1.0f;
    snell_oct_decode(e, n);
    *d = snell_unpack_unorm16(px[2], px[3]);
}

#endif
