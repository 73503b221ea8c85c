# SPDX-License-Identifier: MIT
# Hostile files (issue 14): glTF URIs leaving the model's folder, coordinates at
# the float range, coincident triangles, the memory budget and the messages of
# refused files. Inputs under tests/data/hostile (make_hostile.py), bigger ones
# made at run time. The budget cases need a context (memory_budget): label gl.
snell_add_test(test_hostile_files SOURCES test_hostile_files.c LABELS "unit")
target_link_libraries(test_hostile_files PRIVATE m)
snell_add_test(test_hostile_files_ctx SOURCES test_hostile_files.c LABELS "unit;gl" ARGS ctx)
target_link_libraries(test_hostile_files_ctx PRIVATE m)
# Hostile input, fourth round (issue 40): one function per item of the issue.
snell_add_test(test_hostile_inputs4 SOURCES test_hostile_inputs4.c LABELS "unit")
target_link_libraries(test_hostile_inputs4 PRIVATE m)
snell_add_test(test_hostile_inputs4_ctx SOURCES test_hostile_inputs4.c LABELS "unit;gl" ARGS ctx)
target_link_libraries(test_hostile_inputs4_ctx PRIVATE m)
