/* fuzz_obj.c — libFuzzer target for the OBJ loader (snell_mesh_load_obj_mem).
 * Built with -DSNELL_LIBFUZZER for libFuzzer; otherwise a replay program. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    snell_mesh *m = NULL;
    /* the loader takes (pointer, size) and must not read past size: no copy with a NUL */
    snell_status st = snell_mesh_load_obj_mem(NULL, (const char *)data, size, &m);
    fuzz_check_result(st, m);
    return 0;
}
