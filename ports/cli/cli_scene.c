/* cli_scene.c — meshes, environments and placements by name for the CLIs. */
#include "cli_scene.h"

#include <stdio.h>
#include <string.h>

const char *const cli_shape_names = "sphere|cube|torus|goblet";

static const char *const g_shapes[] = {"sphere", "cube", "torus", "goblet"}; /* snell_shape order */

int cli_is_shape_spec(const char *name) { return strncmp(name, "shape:", 6) == 0; }

int cli_shape_from_name(const char *name, snell_shape *out)
{
    int k;
    if (cli_is_shape_spec(name)) name += 6;
    for (k = 0; k < (int)(sizeof g_shapes / sizeof *g_shapes); k++)
        if (!strcmp(name, g_shapes[k])) {
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

snell_status cli_env_open(snell_ctx *ctx, const char *spec, snell_env **out)
{
    static const char *const faces[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    char paths[6][1024];
    snell_env_desc d;
    int k;
    memset(&d, 0, sizeof d);
    if (spec && strcmp(spec, "procedural") != 0) {
        if (strstr(spec, "%s")) {
            d.source = SNELL_ENV_FACES;
            for (k = 0; k < 6; k++) {
                /* the pattern is the user's own file name, with one %s */
                const char *at = strstr(spec, "%s");
                snprintf(paths[k], sizeof paths[k], "%.*s%s%s", (int)(at - spec), spec, faces[k], at + 2);
                d.face_paths[k] = paths[k];
            }
        } else {
            d.source = SNELL_ENV_EQUIRECT;
            d.equirect_path = spec;
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
