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
