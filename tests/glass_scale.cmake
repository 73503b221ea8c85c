# SPDX-License-Identifier: MIT
# A glass object shaded at a resolution scale (issue 25 item 3:
# src/render/glass_scale.c, shaders_es/glass_scale.frag, the material's
# scale): values, scale 1 byte-identical, scale 2 close to 1 with no
# background in its outline, methods that cannot scale, no GL objects per frame.
snell_add_test(test_glass_scale SOURCES test_glass_scale.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_glass_scale PRIVATE m)

if(TARGET snell-render)
  add_test(NAME cli_glass_scale COMMAND $<TARGET_FILE:snell-render> --mesh shape:torus --method peel --param scale=2
           --size 64x64 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_glass_scale.png)
  set_tests_properties(cli_glass_scale PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "stats: glass 0 .*, scale 2,")
  # Clear failures (exit 2) for scales the library refuses.
  foreach(bad "--scale;0.5" "--scale;9" "--scale;-2" "--scale;nan" "--param;scale=inf")
    string(MAKE_C_IDENTIFIER "cli_bad_scale_${bad}" name)
    string(REPLACE ";" "|" bad_args "--mesh|torus|--method|peel|${bad}")
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>" "-DARGS=${bad_args}" -DCODE=2
             "-DERR=snell-render: " -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
endif()
