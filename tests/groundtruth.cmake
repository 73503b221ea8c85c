# SPDX-License-Identifier: MIT
# FULL reference against Blender Cycles (test_groundtruth.c,
# tests/scripts/cycles_render.py): a sphere and a torus at 96x96, 64 samples
# per pixel (about 30 s on 2 cores, most of it Cycles). Skipped where Blender
# is missing (.ci/run installs it). The full-size figures (512x512, 1024
# samples) are in bench/BENCHMARKS.md: test_groundtruth BLENDER SCRIPT 512 1024.
find_program(BLENDER_EXECUTABLE blender)
if(NOT BLENDER_EXECUTABLE)
  set(BLENDER_EXECUTABLE blender)
endif()
snell_add_test(test_groundtruth SOURCES test_groundtruth.c LABELS "groundtruth" TIMEOUT 900
  ARGS ${BLENDER_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/cycles_render.py 96 64)
target_link_libraries(test_groundtruth PRIVATE m)

# The caustics reference and GPU stage against Blender Cycles' MNEE
# (test_caustics_cycles.c, tests/scripts/cycles_caustics.py): a glass sphere
# over a white plane under a directional light, 64x64 texels, 16 samples per
# pixel, three Cycles renders (caustic with seeds 1 and 2, direct light
# alone): 25 s measured alone on 2 cores at load 5-7 (each render about 5 s
# with Blender's start, the reference 2 s), 51-56 s inside the whole suite
# (ctest -j2, load 8-10). Skipped where Blender is missing. The
# full size (figures in docs/accuracy.md "Caustics", 50 s):
# test_caustics_cycles BLENDER SCRIPT 256 64.
snell_add_test(test_caustics_cycles SOURCES test_caustics_cycles.c LABELS "groundtruth" TIMEOUT 900
  ARGS ${BLENDER_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/cycles_caustics.py 64 16)
target_link_libraries(test_caustics_cycles PRIVATE m)
