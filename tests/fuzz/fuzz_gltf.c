/* SPDX-License-Identifier: MIT */
/* fuzz_gltf.c — libFuzzer target for the glTF loader (snell_mesh_load_gltf_mem,
 * JSON and GLB) and the stages after it (snell_mesh_normalize,
 * snell_mesh_analyze: fuzz_check_result), and the scene loader
 * (snell_scene_load_gltf_mem: object lists within the limits, every object's
 * mesh and model matrix usable). Built with -DSNELL_LIBFUZZER for libFuzzer; otherwise a replay
 * program. Without SNELL_WITH_GLTF every input gives SNELL_E_UNSUPPORTED.
 * The loaders read the input from the end of a mapping (fuzz_at_end_of_mapping):
 * a GLB chunk running past the buffer faults here. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    snell_mesh *m = NULL;
    snell_status st;
    snell_scene_file *scene = NULL;
    const snell_glass *g;
    const snell_opaque *o;
    int ng = 0, no = 0, i, k;
    data = fuzz_at_end_of_mapping(data, size);
    st = snell_mesh_load_gltf_mem(NULL, data, size, &m);
    fuzz_check_result(st, m);
    st = snell_scene_load_gltf_mem(NULL, data, size, &scene);
    if (st != SNELL_OK) {
        if (scene || !snell_last_error(NULL)[0]) abort();
        return 0;
    }
    g = snell_scene_file_glass(scene, &ng);
    o = snell_scene_file_opaque(scene, &no);
    if (ng < 0 || ng > SNELL_MAX_GLASS || no < 0 || no > SNELL_MAX_OPAQUE || ng + no == 0) abort();
    for (i = 0; i < ng + no; i++) {
        const snell_mesh *mesh = i < ng ? g[i].mesh : o[i - ng].mesh;
        const float *model = i < ng ? g[i].model : o[i - ng].model;
        if (!mesh || !snell_mesh_vertex_count(mesh) || !snell_mesh_triangle_count(mesh) || !model) abort();
        for (k = 0; k < 16; k++)
            if (!isfinite(model[k])) abort();
        if (i < ng && !(g[i].material.ior >= 0.05f && g[i].material.ior <= 100.0f)) abort();
    }
    snell_scene_file_destroy(scene);
    return 0;
}
