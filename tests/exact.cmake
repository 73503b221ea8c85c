# SPDX-License-Identifier: MIT
# Exact refraction by BVH traversal in the fragment shader (issue 18:
# src/methods/exact.c, shaders_es/exact.frag): exit directions vs the MATCHED
# reference on sphere, torus, goblet, an open real mesh (cat) and the bunny,
# both node formats; colour with absorption; the node budget's fallback and
# its count; AUTO's opt-in; one BVH per mesh version.
snell_add_test(test_exact SOURCES test_exact.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_exact PRIVATE m)
# The FULL model's terms (material.exact.fresnel, inner_fresnel, reentry)
# against the MATCHED reference with the same snell_ref_terms (issue 50 item 1).
snell_add_test(test_exact_terms SOURCES test_exact_terms.c LABELS "render;gl")
target_link_libraries(test_exact_terms PRIVATE m)

if(TARGET snell-render)
  # The open cat with the budget and cap set by name; the stats line says
  # exact drew it and that a colour renderer does not count fallbacks.
  add_test(NAME cli_exact COMMAND $<TARGET_FILE:snell-render> --mesh ${CMAKE_CURRENT_SOURCE_DIR}/data/real/cat.obj
           --method exact --param exact.max_interfaces=4 --param exact.node_budget=2048 --param exact.node_format=q16 --size 48x48
           --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_exact.png)
  set_tests_properties(cli_exact PROPERTIES LABELS "cli"
    PASS_REGULAR_EXPRESSION "stats: glass 0 \\([^)]*cat.obj[^)]*\\): method exact, .*fallback_pixels not counted")
  # AUTO takes exact for the open cat only with the opt-in.
  add_test(NAME cli_auto_exact COMMAND $<TARGET_FILE:snell-render> --mesh ${CMAKE_CURRENT_SOURCE_DIR}/data/real/cat.obj
           --param exact.auto_pick=allow --size 32x32 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_auto_exact.png)
  set_tests_properties(cli_auto_exact PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "stats: glass 0 \\([^)]*cat.obj[^)]*\\): method exact")
  # Clear failures (exit 2, the library's range message) for bad values.
  foreach(bad "exact.max_interfaces=11" "exact.max_interfaces=0" "exact.node_budget=63" "exact.node_budget=65537"
          "exact.node_format=f16" "exact.auto_pick=always" "exact.walk=sideways"
          "exact.reentry=maybe" "exact.inner_fresnel=3" "exact.fresnel=fast")
    string(MAKE_C_IDENTIFIER "cli_bad_exact_${bad}" name)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>"
             "-DARGS=--mesh|sphere|--method|exact|--param|${bad}" -DCODE=2 "-DERR=snell-render: "
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
endif()

# bench_refit: what a deforming mesh costs exact (refit against rebuild);
# a tool for bench/BENCHMARKS.md, smoke-run here on the cat (about 2 s).
add_executable(bench_refit bench_refit.c)
target_link_libraries(bench_refit PRIVATE snell_static)
target_compile_options(bench_refit PRIVATE ${SNELL_WARNINGS})
add_test(NAME bench_refit_runs COMMAND bench_refit ${CMAKE_CURRENT_SOURCE_DIR}/data/real/cat.obj 16 3)
set_tests_properties(bench_refit_runs PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION "exact \\(refit\\)")
