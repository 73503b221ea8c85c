# SPDX-License-Identifier: MIT
# Dispersion (material.dispersion, core/optics.h, common/dispersion.glsl, ref/ref_trace.c):
# the channels' IORs, the reference's per-channel traces, and every kernel in both
# variants on a prism and a sphere against the per-channel reference. 5 s a run at
# load 9, 18 s at load 14 (three runs: AUTO, forward, screen).
snell_add_test(test_dispersion SOURCES test_dispersion.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_dispersion PRIVATE m)

# CLI: dispersion on the prism shape in both variants, by number and by Abbe
# number; clear failures (exit 2) for values out of range.
if(TARGET snell-render)
  set(cli $<TARGET_FILE:snell-render>)
  add_test(NAME cli_dispersion COMMAND ${cli} --mesh prism --method cubemap --dispersion 1 --dispersion-model per-channel
           --mesh sphere --place 2,0,0 --abbe 55 --dispersion-model one-path --size 64x64 --stats
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_dispersion.png)
  set_tests_properties(cli_dispersion PROPERTIES LABELS "cli"
    PASS_REGULAR_EXPRESSION "stats: glass 0 \\(prism, ior 1.5\\): method cubemap, warning 0.*stats: glass 1 \\(sphere")
  foreach(bad "--dispersion|-1" "--dispersion|21" "--dispersion|x" "--abbe|1" "--abbe|-3" "--dispersion-model|spectral")
    string(MAKE_C_IDENTIFIER "cli_bad_dispersion_${bad}" name)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=${bad}" -DCODE=2 "-DERR=snell-render: "
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
endif()
