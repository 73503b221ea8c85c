/* SPDX-License-Identifier: MIT */
/* cli_scene.c — meshes, environments and placements by name for the CLIs. */
#include "cli_scene.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const cli_shape_names = "sphere|cube|torus|goblet|prism, @N for N segments";

static const char *const g_shapes[] = {"sphere", "cube", "torus", "goblet", "prism"}; /* snell_shape order */

int cli_is_shape_spec(const char *name) { return strncmp(name, "shape:", 6) == 0; }

/* "sphere" or "sphere@N": N segments around the axis (rings N/2). */
static int shape_segments(const char *name)
{
    const char *at = strchr(name, '@');
    char *end;
    long n;
    if (!at) return 0;
    n = strtol(at + 1, &end, 10);
    /* a count out of range is the library's to refuse with its limits
     * (refused here, the name would be tried as a file) */
    if (*end || end == at + 1 || n < 0) return -1;
    return n > 1000000000L ? 1000000000 : (int)n;
}

int cli_shape_from_name(const char *name, snell_shape *out)
{
    int k;
    if (cli_is_shape_spec(name)) name += 6;
    if (shape_segments(name) < 0) return 0;
    for (k = 0; k < (int)(sizeof g_shapes / sizeof *g_shapes); k++)
        if (!strncmp(name, g_shapes[k], strlen(g_shapes[k])) &&
            (name[strlen(g_shapes[k])] == '\0' || name[strlen(g_shapes[k])] == '@')) {
            *out = (snell_shape)k;
            return 1;
        }
    return 0;
}

snell_status cli_mesh_open(snell_ctx *ctx, const char *name, int normalize, snell_mesh **out)
{
    snell_shape shape;
    snell_status st;
    *out = NULL;
    if (cli_shape_from_name(name, &shape)) {
        snell_shape_desc sd;
        memset(&sd, 0, sizeof sd);
        sd.shape = shape;
        sd.segments = shape_segments(name);
        sd.rings = sd.segments / 2;
        st = snell_mesh_create_shape(ctx, &sd, out);
    } else {
        st = snell_mesh_load(ctx, name, out);
    }
    if (st == SNELL_OK && normalize) st = snell_mesh_normalize(*out, 1.0f);
    if (st != SNELL_OK) {
        snell_mesh_destroy(*out);
        *out = NULL;
    }
    return st;
}

/* Expands an --env value into out: "%s" -> face ("" for no face), "%%" ->
 * "%". 1 on success; 0 for any other '%' or a result that does not fit. The
 * value is the user's file name, never a printf format. */
static int expand_env_spec(const char *spec, const char *face, char *out, size_t n, int *faces, char *why,
                           size_t why_n)
{
    size_t len = 0;
    const char *p;
    *faces = 0;
    for (p = spec; *p; p++) {
        const char *piece = p;
        size_t k = 1;
        if (*p == '%') {
            if (p[1] == 's') {
                piece = face;
                k = strlen(face);
                ++*faces;
            } else if (p[1] == '%') {
                piece = "%";
            } else {
                if (p[1]) snprintf(why, why_n, "'%%%c' at offset %d", p[1], (int)(p - spec));
                else snprintf(why, why_n, "a trailing '%%'");
                return 0;
            }
            p++;
        }
        if (len + k >= n) {
            snprintf(why, why_n, "longer than %d bytes once expanded", (int)n - 1);
            return 0;
        }
        memcpy(out + len, piece, k);
        len += k;
    }
    out[len] = '\0';
    return 1;
}

int cli_env_spec_check(const char *spec, char *why, size_t why_size)
{
    char path[1024];
    int faces;
    if (!spec || !strcmp(spec, "procedural")) return 1;
    return expand_env_spec(spec, "px", path, sizeof path, &faces, why, why_size);
}

snell_status cli_env_open(snell_ctx *ctx, const char *spec, snell_env **out)
{
    static const char *const faces[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    char paths[6][1024], why[160];
    snell_env_desc d;
    int k, n = 0;
    memset(&d, 0, sizeof d);
    *out = NULL;
    if (spec && strcmp(spec, "procedural") != 0) {
        for (k = 0; k < 6; k++) {
            if (!expand_env_spec(spec, faces[k], paths[k], sizeof paths[k], &n, why, sizeof why))
                return SNELL_E_INVALID_ARG; /* cli_env_spec_check says why */
            d.face_paths[k] = paths[k];
        }
        if (n > 0) {
            d.source = SNELL_ENV_FACES;
        } else {
            d.source = SNELL_ENV_EQUIRECT;
            d.equirect_path = paths[0]; /* "%%" unescaped */
            memset(d.face_paths, 0, sizeof d.face_paths);
        }
    }
    return snell_env_create(ctx, &d, out);
}

void cli_place_matrix(const float place[4], float m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = place[3];
    m[12] = place[0];
    m[13] = place[1];
    m[14] = place[2];
    m[15] = 1.0f;
}
