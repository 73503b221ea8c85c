# SPDX-License-Identifier: MIT
# Slow inputs (issue 26 item 3): every loader and stage within a per-byte,
# per-corner or per-pixel bound on inputs made to be slow (repeated indices,
# coincident faces, all vertices equal, a vertex of valence 100,000, deep and
# shared glTF node trees, 2D scene files and contour images), with
# deterministic checks of the GPU copy's work estimate. CPU only.
snell_add_test(test_slow_inputs SOURCES test_slow_inputs.c LABELS "unit")
target_link_libraries(test_slow_inputs PRIVATE m)
if(SNELL_WITH_MESHOPT)
  target_compile_definitions(test_slow_inputs PRIVATE SNELL_WITH_MESHOPT_TEST=1)
endif()
# The file of issue 26 item 1 (one OBJ face of 120,000 corners) through snell-render.
if(TARGET snell-render)
  add_test(NAME cli_slow_face COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:snell-render> -DOUT=${CMAKE_CURRENT_BINARY_DIR}
           -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/cli_slow_face.cmake)
  set_tests_properties(cli_slow_face PROPERTIES LABELS "cli;gl" TIMEOUT 300)
endif()
