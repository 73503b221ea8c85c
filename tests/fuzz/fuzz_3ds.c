/* SPDX-License-Identifier: MIT */
/* fuzz_3ds.c — libFuzzer target for glmark2's model formats: every input goes
 * through the .3ds and the .jobj loader (snell_mesh_load_3ds_mem,
 * snell_mesh_load_jobj_mem) and what they accept through the checks after
 * loading. Built with -DSNELL_LIBFUZZER for libFuzzer; otherwise a replay program. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    snell_mesh *m = NULL;
    snell_status st = snell_mesh_load_3ds_mem(NULL, data, size, &m);
    fuzz_check_result(st, m);
    m = NULL;
    st = snell_mesh_load_jobj_mem(NULL, (const char *)data, size, &m);
    fuzz_check_result(st, m);
    return 0;
}
