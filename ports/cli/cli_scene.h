/* SPDX-License-Identifier: MIT */
/* cli_scene.h — scene pieces by name for the CLI ports: meshes (built-in
 * shapes or OBJ/glTF files), environments (procedural, equirectangular, six
 * faces) and placement matrices. Public API only. */
#ifndef SNELL_CLI_SCENE_H
#define SNELL_CLI_SCENE_H

#include "snell/snell.h"

/* "sphere|cube|torus|goblet", for help texts. */
extern const char *const cli_shape_names;

/* 1 and *out set if name is a built-in shape, bare ("torus") or prefixed
 * ("shape:torus"); 0 otherwise. */
int cli_shape_from_name(const char *name, snell_shape *out);
/* 1 if name starts with "shape:" (so it must be a shape, not a file). */
int cli_is_shape_spec(const char *name);

/* A shape by name (see cli_shape_from_name) or a mesh file (OBJ, glTF), then
 * with normalize != 0 fitted into the unit sphere (snell_mesh_normalize). */
snell_status cli_mesh_open(snell_ctx *ctx, const char *name, int normalize, snell_mesh **out);

/* spec NULL or "procedural": the built-in sky; a path containing "%s": six
 * faces (px nx py ny pz nz substituted for each %s); any other path: an
 * equirectangular image. "%%" stands for "%"; any other '%' is refused
 * (SNELL_E_INVALID_ARG: check with cli_env_spec_check first for the reason). */
snell_status cli_env_open(snell_ctx *ctx, const char *spec, snell_env **out);
/* 1 if cli_env_open accepts spec's pattern, else 0 with the reason in why. */
int cli_env_spec_check(const char *spec, char *why, size_t why_size);

/* Column-major model matrix: uniform scale place[3], then translate place[0..2]. */
void cli_place_matrix(const float place[4], float m[16]);

#endif
