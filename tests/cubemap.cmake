# SPDX-License-Identifier: MIT
# Cubemap method (Unger 4.1, src/methods/cubemap.c, methods/ndcube.c, mesh/mesh_analyze.c):
# packing twin, bake vs CPU ray casts, sphere/cube/TIR vs the reference,
# analysis (star-shapedness), CLI flags.
snell_add_test(test_analyze SOURCES test_analyze.c LABELS "unit")
target_link_libraries(test_analyze PRIVATE m)

snell_add_test(test_cubemap SOURCES test_cubemap.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_cubemap PRIVATE m)
snell_add_test(test_cubemap_ref SOURCES test_cubemap_ref.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_cubemap_ref PRIVATE m)

# CLI: the cubemap flags, and clear failures (exit 2) for bad values.
if(TARGET snell-render)
  set(cli $<TARGET_FILE:snell-render>)
  add_test(NAME cli_cubemap COMMAND ${cli} --mesh shape:sphere --method cubemap --iterations 6 --linear_steps 4
           --max_interfaces 3 --face_size 64 --encoding plain --size 64x64 --frames 3 --stats
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_cubemap.png)
  set_tests_properties(cli_cubemap PROPERTIES LABELS "cli"
    PASS_REGULAR_EXPRESSION "stats: glass 0 \\(sphere, ior 1.5\\): method cubemap, warning 0, passes [0-9]+, prepared 0.*hidden_fraction 0.0000")
  add_test(NAME cli_auto_goblet COMMAND ${cli} --mesh shape:goblet --method auto --size 32x32 --stats
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_auto.png)
  set_tests_properties(cli_auto_goblet PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "stats: glass 0 \\(goblet[^)]*\\): method peel")
  add_test(NAME cli_auto_sphere COMMAND ${cli} --mesh shape:sphere --method auto --size 32x32 --stats
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_auto.png)
  set_tests_properties(cli_auto_sphere PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "stats: glass 0 \\(sphere[^)]*\\): method layered")
  foreach(bad "--iterations;0" "--iterations;33" "--iterations;x" "--max_interfaces;9" "--max_interfaces;0"
              "--face_size;8" "--face_size;4096" "--encoding;rgb" "--linear_steps;-1" "--method;cube")
    string(MAKE_C_IDENTIFIER "cli_bad_cubemap_${bad}" name)
    string(REPLACE ";" "|" bad_args "${bad}")
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=${bad_args}" -DCODE=2 "-DERR=snell-render: "
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
endif()
snell_add_test(test_cubemap_env SOURCES test_cubemap_env.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_cubemap_env PRIVATE m)
# Inner-surface Fresnel (cubemap and peel param inner): energy in a grey world,
# the gain against FULL (cubemap: the sphere; peel: sphere, torus, goblet),
# AUTO on convex meshes only for the cubemap, on every mesh for peel. ~7 s.
snell_add_test(test_inner_fresnel SOURCES test_inner_fresnel.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_inner_fresnel PRIVATE m)
# CLI antialiasing (snell_renderer_desc.ssaa / msaa): a still each, and clear
# failures for bad values (exit 2) and for msaa with ssaa (the library's message).
if(TARGET snell-render)
  add_test(NAME cli_ssaa COMMAND ${cli} --ssaa 2 --size 48x48 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_ssaa.png)
  add_test(NAME cli_msaa COMMAND ${cli} --msaa 4 --size 48x48 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_msaa.png)
  set_tests_properties(cli_ssaa cli_msaa PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "wrote .*48x48")
  foreach(bad "--ssaa;0" "--ssaa;9" "--msaa;x")
    string(MAKE_C_IDENTIFIER "cli_bad_aa_${bad}" name)
    string(REPLACE ";" "|" bad_args "${bad}")
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=${bad_args}" -DCODE=2 "-DERR=snell-render: "
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
  add_test(NAME cli_msaa_with_ssaa COMMAND ${cli} --msaa 2 --ssaa 2 --size 48x48 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_x.png)
  set_tests_properties(cli_msaa_with_ssaa PROPERTIES LABELS "cli" WILL_FAIL TRUE)
endif()
