# SPDX-License-Identifier: MIT
# Multi-layer refraction from depth-peeled layers (issue 12: src/methods/peel.c,
# shaders_es/peel.frag, peel_layer.frag; depth complexity in mesh/mesh_analyze.c):
# layer counts, two layers = two surfaces, the sphere against the cubemap, torus
# and goblet against the FULL reference, more surfaces than layers.
snell_add_test(test_peel SOURCES test_peel.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_peel PRIVATE m)

if(TARGET snell-render)
  add_test(NAME cli_peel COMMAND $<TARGET_FILE:snell-render> --mesh shape:torus --method peel --layers 6 --linear_steps 24
           --binary_steps 4 --max_interfaces 6 --param peel.fixes=merge --param peel.inner_fresnel=on --param peel.fresnel=exact --size 64x64 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_peel.png)
  set_tests_properties(cli_peel PROPERTIES LABELS "cli"
    PASS_REGULAR_EXPRESSION "stats: glass 0 \\(torus, ior 1.5\\): method peel, .*layers_peeled 4, layers_found not counted")
endif()
# Clear failures (exit 2, the library's range message) for bad peel values.
if(TARGET snell-render)
  foreach(bad "--layers;1" "--layers;9" "--binary_steps;0" "--binary_steps;17" "--linear_steps;129" "--max_interfaces;11" "--fixes;all"
          "--param;peel.inner_fresnel=maybe" "--param;peel.fresnel=fast")
    string(MAKE_C_IDENTIFIER "cli_bad_peel_${bad}" name)
    string(REPLACE ";" "|" bad_args "--mesh|torus|--method|peel|${bad}")
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>" "-DARGS=${bad_args}" -DCODE=2
             "-DERR=snell-render: " -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
endif()
# Layer 0 from the G-buffer (issue 25 item 2): the layer against the peeled
# one, the images, and when the route is taken (screen space only).
snell_add_test(test_peel_layer0 SOURCES test_peel_layer0.c LABELS "render;gl")
target_link_libraries(test_peel_layer0 PRIVATE m)
