# The library in a careless or hostile host's hands (issue 14): contexts,
# host GL state (EXTERNAL), pixel buffers, destroy order, NULL/NaN lookups,
# camera and model values; the CLI's --env pattern; and the long run (flat
# RSS and GL object counts over 2,000 varied frames and 500 create/destroy
# cycles), labelled "longrun" only so that the sanitizer legs skip it.
snell_add_test(test_host SOURCES test_host.c LABELS "unit;gl")
target_link_libraries(test_host PRIVATE snell_dep::egl snell_dep::gles m)

snell_add_test(test_longrun SOURCES test_longrun.c LABELS "longrun" TIMEOUT 600)
target_link_libraries(test_longrun PRIVATE snell_dep::gles m)

if(TARGET snell-render)
  # --env is a file name, never a printf format: %s is the face, %% a percent
  # sign, anything else after a % a usage error (exit 2), not a write through %n.
  foreach(bad "%s_%n" "%n" "sky%d.png" "a%" "%s%s%x")
    string(MAKE_C_IDENTIFIER "cli_env_format_${bad}" name)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>" "-DARGS=--env|${bad}|--size|8x8"
             -DCODE=2 "-DERR=snell-render: --env '.*': .*only %s" -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
  add_test(NAME cli_env_format_bench COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-bench>"
           "-DARGS=--env|%s_%n|-b|single" -DCODE=2 "-DERR=snell-bench: --env '%s_%n': " -P
           ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  set_tests_properties(cli_env_format_bench PROPERTIES LABELS "cli")
  # Each %s is a face name, %% one '%', as the message's file name shows.
  add_test(NAME cli_env_format_expand COMMAND $<TARGET_FILE:snell-render> --env /nonexistent/%s_%%_%s.png --size 8x8
           -o ${CMAKE_CURRENT_BINARY_DIR}/x.png)
  set_tests_properties(cli_env_format_expand PROPERTIES LABELS "cli"
                       PASS_REGULAR_EXPRESSION "cannot open image \"/nonexistent/px_%_px.png\"")
endif()
