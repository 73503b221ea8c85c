/* SPDX-License-Identifier: MIT */
/* ref_plane.c — the receiver plane in the reference's view
 * (snell_ref_set_receiver): its square, seen from above by the rays in air,
 * albedo times its irradiance map as the view and the glass kernels show
 * it (caustics_receiver.frag, common/receiver.glsl). The map is the
 * reference's own, traced once by snell_ref_receiver_render at the stage's
 * direct-light points (2 x 2 a texel, caustics_direct.frag), and read
 * bilinearly as receiver_irradiance() reads the GPU's. */
#include "ref/ref_scene.h"
#include "core/ctx.h"

struct ref_plane {
    double h, cx, cz, ext, albedo[3];
    int size;
    float map[]; /* 3 floats a texel, snell_ref_receiver_render's layout */
};

void snell__ref_plane_free(snell_ref *r)
{
    snell__free(&r->alloc, r->plane);
    r->plane = NULL;
}

snell_status snell_ref_set_receiver(snell_ref *r, const snell_light *light, const snell_receiver *rc, int photons)
{
    struct ref_plane *P;
    snell_status st;
    int k, n, grey;
    if (!r) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_ref_set_receiver: NULL reference");
    snell__ref_plane_free(r);
    if (!light || light->type == SNELL_LIGHT_NONE || !rc || rc->extent == 0.0f) return SNELL_OK;
    st = isfinite((double)rc->height + rc->center[0] + rc->center[1]) && rc->map_size >= 0 && rc->map_size <= 4096
             ? SNELL_OK
             : SNELL_E_INVALID_ARG;
    for (k = 0; k < 3; k++)
        if (!(rc->albedo[k] >= 0.0f && rc->albedo[k] <= 1.0f)) st = SNELL_E_INVALID_ARG;
    if (st != SNELL_OK)
        return snell__fail(r->ctx, st,
                           "snell_ref_set_receiver: receiver height and center finite, albedo 0..1, "
                           "map_size 0..4096");
    n = rc->map_size ? rc->map_size : SNELL_DEFAULT_RECEIVER_MAP;
    P = (struct ref_plane *)snell__calloc(&r->alloc, 1, sizeof *P + (size_t)n * (size_t)n * 3 * sizeof(float));
    if (!P) return snell__fail(r->ctx, SNELL_E_NOMEM, "snell_ref_set_receiver: out of memory");
    P->size = n;
    P->h = rc->height, P->cx = rc->center[0], P->cz = rc->center[1], P->ext = rc->extent;
    grey = rc->albedo[0] == 0.0f && rc->albedo[1] == 0.0f && rc->albedo[2] == 0.0f;
    for (k = 0; k < 3; k++) P->albedo[k] = grey ? 0.8 : rc->albedo[k]; /* as the stage draws it */
    /* the stage's map: its direct light at 2 x 2 points a texel (caustics_direct.frag) */
    st = snell_ref_receiver_render(r, light, rc, photons, 2, P->map, NULL);
    if (st == SNELL_OK)
        r->plane = P; /* set last: the map's own rays (shadows, photons) do not meet it */
    else
        snell__free(&r->alloc, P);
    return st;
}

/* A ray meeting the square: albedo times the map read as
 * receiver_irradiance() reads it, bilinearly between texel centres, the
 * edge texels held beyond them. */
int snell__ref_plane_hit(const snell_ref *r, const double o[3], const double d[3], double tmax, double rgb[3])
{
    const struct ref_plane *P = r->plane;
    double t, tx, tz;
    int q, k;
    /* none, or met from below (it has no underside): the backdrop, if any, after it */
    if (!P || !(d[1] < 0.0) || !(o[1] > P->h)) return snell__ref_backdrop_hit(r, o, d, tmax, rgb);
    t = (P->h - o[1]) / d[1];
    tx = (o[0] + t * d[0] - P->cx) / P->ext, tz = (o[2] + t * d[2] - P->cz) / P->ext;
    if (!(t < tmax && fabs(tx) <= 1.0 && fabs(tz) <= 1.0)) return snell__ref_backdrop_hit(r, o, d, tmax, rgb);
    if (!rgb) return 1;
    tx = (0.5 * tx + 0.5) * P->size - 0.5, tz = (0.5 * tz + 0.5) * P->size - 0.5; /* texel centres at integers */
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    for (q = 0; q < 4; q++) {
        int x = (int)floor(tx) + (q & 1), z = (int)floor(tz) + (q >> 1);
        double w = fabs(tx - floor(tx) - !(q & 1)) * fabs(tz - floor(tz) - !(q >> 1));
        x = x < 0 ? 0 : x >= P->size ? P->size - 1 : x;
        z = z < 0 ? 0 : z >= P->size ? P->size - 1 : z;
        for (k = 0; k < 3; k++) rgb[k] += w * P->albedo[k] * P->map[3 * ((size_t)z * (size_t)P->size + (size_t)x) + k];
    }
    return 1;
}
