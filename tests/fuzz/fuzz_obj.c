/* SPDX-License-Identifier: MIT */
/* fuzz_obj.c — libFuzzer target for the OBJ loader (snell_mesh_load_obj_mem)
 * and the stages after it (snell_mesh_normalize, snell_mesh_analyze). Built with -DSNELL_LIBFUZZER for libFuzzer; otherwise a replay program. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    snell_mesh *m = NULL;
    snell_status st;
    /* the loader takes (pointer, size) and must not read past size: no copy with a NUL;
     * an accepted mesh then goes through snell_mesh_normalize and snell_mesh_analyze */
    data = fuzz_at_end_of_mapping(data, size);
    st = snell_mesh_load_obj_mem(NULL, (const char *)data, size, &m);
    fuzz_check_result(st, m);
    return 0;
}
