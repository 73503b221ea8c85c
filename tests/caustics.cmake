# SPDX-License-Identifier: MIT
# Caustics and shadows of glass on a receiver plane (render/caustics.c,
# ref/ref_caustics.c; issue 27).
# test_caustics: a glass sphere over a plane under a directional light: the caustic's peak at the ball lens's
# paraxial focus, flux and PSNR against the reference's light tracing, reuse, skips, bad input.
snell_add_test(test_caustics SOURCES test_caustics.c LABELS "render;gl")
target_link_libraries(test_caustics PRIVATE m)
# gcc 12's aarch64 cross compiler (Debian's crossbuild-essential-arm64) stops with an internal
# compiler error in its loop vectoriser on this file's main at -O2 (vect_transform_reduction,
# tree-vect-loop.cc:7457; CI's arm64 leg); a test loses nothing without it.
if(TARGET test_caustics AND CMAKE_C_COMPILER_ID STREQUAL "GNU")
  target_compile_options(test_caustics PRIVATE -fno-tree-vectorize)
endif()
if(TARGET snell-render)
  # snell-render --light/--floor: the stage runs (its stats line), and a bad --light is refused (exit 2)
  add_test(NAME cli_caustics COMMAND $<TARGET_FILE:snell-render> --light dir:0.5,-1,0.2 --floor -1,3 --size 64x64
           --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_caustics.png)
  set_tests_properties(cli_caustics PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "stages run: opaque caustics glass.*caustics: made: 1 glass casting.*65536 photons")
  add_test(NAME cli_caustics_bad_light COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>"
           "-DARGS=--light|dir:0,0,0|--floor|0" -DCODE=2 "-DERR=wants dir:X,Y,Z" -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  set_tests_properties(cli_caustics_bad_light PROPERTIES LABELS "cli;gl")
endif()
# bench_caustics: the frame cost off / light map reused / made every frame, rounds taking turns
# (a tool, not a test: uses internals; numbers in the issue's note).
add_executable(bench_caustics bench_caustics.c ${PROJECT_SOURCE_DIR}/ports/cli/cli_time.c)
target_link_libraries(bench_caustics PRIVATE snell_static)
target_include_directories(bench_caustics PRIVATE ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR}/ports/cli ${CGLM_INCLUDE_DIR})
target_compile_options(bench_caustics PRIVATE ${SNELL_WARNINGS})
add_test(NAME bench_caustics_runs COMMAND bench_caustics 64 2 32 32)
set_tests_properties(bench_caustics_runs PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION "made/off median ratio")
# test_caustics_opaque: opaque objects as receivers: a glass sphere over an opaque box (its top at the ball
# lens's focus), a small cube and the floor; the lit view against the reference's (snell_ref_set_light) over the
# opaque pixels, the caustic maps' flux and peak, photons stopped by the box, its shadow edge; a spot light.
# TIMEOUT: under ASan + UBSan at -O0 (.ci/run) its CPU references take minutes.
snell_add_test(test_caustics_opaque SOURCES test_caustics_opaque.c LABELS "render;gl" TIMEOUT 900)
target_link_libraries(test_caustics_opaque PRIVATE m)
add_test(NAME bench_caustics_opaque_runs COMMAND bench_caustics 64 2 32 32 1)
set_tests_properties(bench_caustics_opaque_runs PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION "opaque box.*made/off median ratio")
if(TARGET snell-render AND SNELL_WITH_GLTF)
  # snell-render --scene with opaque objects and a light: they are lit (the stage's stats line)
  add_test(NAME cli_caustics_opaque COMMAND $<TARGET_FILE:snell-render> --scene
           ${PROJECT_SOURCE_DIR}/tests/data/scenes/three_glass_two_opaque.gltf --light dir:-0.4,-1,-0.3 --floor -1,4
           --size 64x64 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_caustics_opaque.png)
  set_tests_properties(cli_caustics_opaque PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "caustics: made: 3 glass casting; [0-9]+x[0-9]+ RGBA(32|16)F light map; 2 opaque lit")
endif()
# The glass sees the lit receiver plane along its exit and reflected rays
# (common/receiver.glsl): every method, both shading paths.
snell_add_test(test_caustics_seen SOURCES test_caustics_seen.c LABELS "render;gl" SHADINGS forward screen)
# test_caustics_seen_ref: the same against the reference, which sees the plane after snell_ref_set_receiver
# (ref_plane.c): a sphere and a standing torus over the lit plane, its caustic and shadow seen through them; the
# GPU frame by each method against the reference over the glass pixels that see the plane and the plane's own.
snell_add_test(test_caustics_seen_ref SOURCES test_caustics_seen_ref.c LABELS "render;gl")
target_link_libraries(test_caustics_seen_ref PRIVATE m)
# test_caustics_env: the glass sees the opaque objects lit through its dynamic environment (scene layers off):
# every method, the cube map, dual-paraboloid maps made from it or rendered straight; the environment
# re-rendered when the light moves or its maps are remade, reused while it is still.
snell_add_test(test_caustics_env SOURCES test_caustics_env.c LABELS "render;gl" SHADINGS forward screen)
# test_caustics_concave: a standing torus (concave): photons by the BVH through entries, TIR, exits and
# re-entries; the lit receiver against the reference and against its one-crossing model, flux, energy; TIR in a
# cube of the exact method.
snell_add_test(test_caustics_concave SOURCES test_caustics_concave.c LABELS "render;gl")
target_link_libraries(test_caustics_concave PRIVATE m)
# bench_caustics on a torus (not convex): its photons by the BVH ("made") against the depth maps alone ("maps").
add_test(NAME bench_caustics_torus_runs COMMAND bench_caustics 64 2 32 32 0 torus)
set_tests_properties(bench_caustics_torus_runs PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION "torus.*made/maps median ratio")
# test_caustics_thin: a thin-walled sphere (thickness 0.02, tinted, absorbing): photons straight on through both
# walls, a slab each; the shadow's colour against the slab model in closed form, the receiver against the
# reference, the BVH's path, a spot light, a thin torus (four walls on a line), an opaque box under it, a clear
# thin wall passes.
snell_add_test(test_caustics_thin SOURCES test_caustics_thin.c LABELS "render;gl")
target_link_libraries(test_caustics_thin PRIVATE m)
# test_caustics_chain: a glass sphere above a tinted one, their beams overlapping: photons through both in
# sequence (the chain path) against the reference's chain, directional and spot; each caster alone (the path
# before) clearly off; side by side under a light from above: no chain.
# TIMEOUT: under ASan + UBSan at -O0 (.ci/run) its CPU references take minutes.
snell_add_test(test_caustics_chain SOURCES test_caustics_chain.c LABELS "render;gl" TIMEOUT 900)
target_link_libraries(test_caustics_chain PRIVATE m)
