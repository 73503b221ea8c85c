# SPDX-License-Identifier: MIT
# Water (snell_water_*, src/water/, ref/ref_water.c; issue 17).
# test_water_sim: the CPU simulation, no GL (100,000 steps of 64^2, and a run past the stability
# limit that overflows early; ~3-5 s).
snell_add_test(test_water_sim SOURCES test_water_sim.c LABELS "unit")
target_link_libraries(test_water_sim PRIVATE m)
# test_water_gl: GPU simulation against the CPU one, its settle check, and the
# still and rippled water frames against snell_ref_water_render, objects in the water, Fresnel against
# Schlick, tiles bending, the twins settling together (~3-5 s here).
snell_add_test(test_water_gl SOURCES test_water_gl.c LABELS "render;gl")
target_link_libraries(test_water_gl PRIVATE m)
# snell-render --water: a frame sequence with drops from flags (one at frame 3),
# the settled surface skipping its simulation, a bad drop refused (exit 2), glass in the water.
if(TARGET snell-render)
  set(cli $<TARGET_FILE:snell-render>)
  add_test(NAME cli_water_frames COMMAND ${cli} --water --sim gpu --grid 64 --size 48x48 --frames 5 --save-every 2
           --drop 0,0,0.1,-0.03 --drop 0.5,0.5,0.1,0.02,3 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_water.png)
  set_tests_properties(cli_water_frames PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "frame 0: simulated, 2 steps.*frame 4: simulated, 2 steps")
  add_test(NAME cli_water_settled COMMAND ${cli} --water --sim cpu --grid 64 --size 32x32 --frames 2 --stats
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_water_still.png)
  set_tests_properties(cli_water_settled PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "frame 0: simulation skipped \\(settled, undisturbed\\), 0 steps.*heights uploaded.*frame 1: simulation skipped.*heights not uploaded")
  add_test(NAME cli_water_bad_drop COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--water|--drop|5,0|--size|16x16"
           -DCODE=2 "-DERR=outside the container" -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  set_tests_properties(cli_water_bad_drop PROPERTIES LABELS "cli;gl")
  # a glass object through the surface: the water sees it through the scene layers
  add_test(NAME cli_water_glass COMMAND ${cli} --water --grid 64 --size 48x48 --frames 2 --drop 0.3,0.3
           --glass sphere:0,-0.2,0,0.3 --object cube:0.5,-0.6,0.5,0.15 --stats
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_water_glass.png)
  set_tests_properties(cli_water_glass PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "frame 1: simulated.*objects seen under the surface through the scene layers")
  # --light: the floor's caustics made every frame the surface moves, kept while it is still; a bad light refused
  if(SNELL_WITH_CAUSTICS)
    add_test(NAME cli_water_caustics COMMAND ${cli} --water --grid 64 --size 48x48 --frames 2 --drop 0.3,0.3
             --light dir:0.3,-1,0.2 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_water_caustics.png)
    set_tests_properties(cli_water_caustics PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
      "frame 0: simulated.*caustics: water floor: made.*frame 1: simulated.*caustics: water floor: made")
    add_test(NAME cli_water_caustics_still COMMAND ${cli} --water --grid 64 --size 32x32 --frames 2
             --light spot:0,2,0,0,-1,0,0.6,3 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_water_caustics_still.png)
    set_tests_properties(cli_water_caustics_still PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
      "frame 0: simulation skipped.*caustics: water floor: made.*frame 1: simulation skipped.*caustics: water floor: reused")
    add_test(NAME cli_water_bad_light COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--water|--light|dir:0,0,0"
             -DCODE=2 "-DERR=dir:X,Y,Z" -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(cli_water_bad_light PROPERTIES LABELS "cli;gl")
  endif()
endif()
# test_water_glass: glass objects in the water (one through the surface, one under it) and an opaque
# one, the frame against snell_ref_water_render with every medium traced, over the pixels the glass changes.
snell_add_test(test_water_glass SOURCES test_water_glass.c LABELS "render;gl")
target_link_libraries(test_water_glass PRIVATE m)
# test_water_caustics: the floor's light map under the moving surface (issue 27 item 4) against the
# reference's light tracing through the same height field, at two times and under a spot light.
snell_add_test(test_water_caustics SOURCES test_water_caustics.c LABELS "render;gl")
target_link_libraries(test_water_caustics PRIVATE m)
# bench_water_caustics: the frame cost with the floor's caustics against without, the water moving,
# rounds taking turns (a tool, not a test: uses internals; numbers in bench/notes/readme-1f9ff36.md).
if(SNELL_WITH_CAUSTICS AND SNELL_WITH_WATER)
  add_executable(bench_water_caustics bench_water_caustics.c ${PROJECT_SOURCE_DIR}/ports/cli/cli_time.c)
  target_link_libraries(bench_water_caustics PRIVATE snell_static)
  target_include_directories(bench_water_caustics PRIVATE ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR}/ports/cli ${CGLM_INCLUDE_DIR})
  target_compile_options(bench_water_caustics PRIVATE ${SNELL_WARNINGS})
  add_test(NAME bench_water_caustics_runs COMMAND bench_water_caustics 64 2 64 32)
  set_tests_properties(bench_water_caustics_runs PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION "lit/dark median ratio")
endif()
