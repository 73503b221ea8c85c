/* fuzz_gltf.c — libFuzzer target for the glTF loader (snell_mesh_load_gltf_mem,
 * JSON and GLB) and the stages after it (snell_mesh_normalize,
 * snell_mesh_analyze: fuzz_check_result). Built with -DSNELL_LIBFUZZER for libFuzzer; otherwise a replay
 * program. Without SNELL_WITH_GLTF every input gives SNELL_E_UNSUPPORTED. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    snell_mesh *m = NULL;
    snell_status st = snell_mesh_load_gltf_mem(NULL, data, size, &m);
    fuzz_check_result(st, m);
    return 0;
}
