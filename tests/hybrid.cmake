# SPDX-License-Identifier: MIT
# The hybrid (issue 50 item 2: src/methods/hybrid.c, shaders_es/hybrid.frag):
# the cubemap's doubt mask against exact on a sphere and a torus, and the
# hybrid's image exact's on the marked pixels and the cubemap's elsewhere,
# forward and in screen space.
snell_add_test(test_hybrid SOURCES test_hybrid.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_hybrid PRIVATE m)

if(TARGET snell-render)
  # By name from the CLI, its parameters with it; the stats line says the hybrid drew it.
  add_test(NAME cli_hybrid COMMAND $<TARGET_FILE:snell-render> --mesh torus --method hybrid
           --param hybrid.doubt=50 --param hybrid.max_interfaces=6 --size 48x48 --stats
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_hybrid.png)
  set_tests_properties(cli_hybrid PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "stats: glass 0 \\([^)]*\\): method hybrid")
  # Clear failures (exit 2, the library's range message) for bad values.
  foreach(bad "hybrid.doubt=0" "hybrid.doubt=1001" "hybrid.max_interfaces=9" "hybrid.doubted=maybe")
    string(MAKE_C_IDENTIFIER "cli_bad_hybrid_${bad}" name)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>"
             "-DARGS=--mesh|sphere|--method|hybrid|--param|${bad}" -DCODE=2 "-DERR=snell-render: "
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
endif()
