# SPDX-License-Identifier: MIT
# The scene and the method seam (issue 9: src/render/scene.c, renderer.c,
# prepared.c, env_dynamic.c, composite.c, methods/registry.c): registry and
# material resolve, AUTO's per-object choice, order, skips, 8 glass + 4
# opaque objects against the reference tracer.
snell_add_test(test_scene SOURCES test_scene.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_scene PRIVATE m)

# glTF scene files (issue 13 item 4): tests/data/scenes (make_scenes.py),
# loading, refusals, and a rendered scene against the reference tracer.
snell_add_test(test_scene_gltf SOURCES test_scene_gltf.c LABELS "render;gl")
target_link_libraries(test_scene_gltf PRIVATE m)
# Issue 28 items 3 and 4: camera-less scenes framed from their bounds
# (snell_scene_file_frame); more opaque objects than SNELL_MAX_OPAQUE merged
# per colour, more glass than SNELL_MAX_GLASS refused; node names.
snell_add_test(test_scene_gltf_frame SOURCES test_scene_gltf_frame.c LABELS "render;gl")
target_link_libraries(test_scene_gltf_frame PRIVATE m)
snell_add_test(test_scene_gltf_limits SOURCES test_scene_gltf_limits.c LABELS "render;gl")
target_link_libraries(test_scene_gltf_limits PRIVATE m)

# snell-render --scene: a glTF scene's objects and camera; it excludes --mesh.
if(TARGET snell-render)
  add_test(NAME cli_scene_gltf COMMAND $<TARGET_FILE:snell-render> --scene ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/glass_row.gltf
           --size 64x64 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_scene_gltf.png)
  set_tests_properties(cli_scene_gltf PROPERTIES LABELS "cli"
    PASS_REGULAR_EXPRESSION "camera: the file's.*glass 1 \\(node 1, ior 1.33\\): method layered.*glass 2 \\(node 2, ior 1.7\\): method single.*thin wall")
  # A file without a camera is framed (--stats says so); node names beside the
  # glass; 100 opaque objects merged into 3; 33 glass objects refused.
  set(scenes ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes)
  add_test(NAME cli_scene_gltf_framed COMMAND $<TARGET_FILE:snell-render> --scene ${scenes}/framed_small.gltf
           --size 48x32 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_scene_gltf_framed.png)
  set_tests_properties(cli_scene_gltf_framed PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION
    "camera: framed the scene's bounds \\(the file has none\\): target \\(-3, 7, -12\\).*glass 0 \\(tiny_glass, ior 1.5\\)")
  add_test(NAME cli_scene_gltf_many_opaque COMMAND $<TARGET_FILE:snell-render> --scene ${scenes}/many_opaque.gltf
           --size 48x48 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_scene_gltf_many_opaque.png)
  set_tests_properties(cli_scene_gltf_many_opaque PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION
    "glass 1, opaque drawn 3,.*camera: the file's.*glass 0 \\(lens, ior 1.5\\)")
  set(expect ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  add_test(NAME cli_scene_gltf_with_mesh COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>"
           "-DARGS=--scene|${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/glass_row.gltf|--mesh|sphere" -DCODE=2
           "-DERR=does not combine with --mesh or --opaque" -P ${expect})
  set_tests_properties(cli_scene_gltf_with_mesh PROPERTIES LABELS "cli")
  add_test(NAME cli_scene_gltf_required COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>"
           "-DARGS=--scene|${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/bad_required.gltf|-o|${CMAKE_CURRENT_BINARY_DIR}/cli_scene_gltf_bad.png"
           -DCODE=1 "-DERR=requires material extensions that are not supported: KHR_materials_clearcoat" -P ${expect})
  set_tests_properties(cli_scene_gltf_required PROPERTIES LABELS "cli")
  add_test(NAME cli_scene_gltf_33_glass COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>"
           "-DARGS=--scene|${scenes}/glass_33.gltf|-o|${CMAKE_CURRENT_BINARY_DIR}/cli_scene_gltf_33.png"
           -DCODE=1 "-DERR=33 glass objects: more than the limit of 32" -P ${expect})
  set_tests_properties(cli_scene_gltf_33_glass PROPERTIES LABELS "cli")
endif()

# A mirroring model matrix is the same object as its vertices mirrored and
# re-wound, for every method in the registry, on both shading paths.
snell_add_test(test_mirror SOURCES test_mirror.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_mirror PRIVATE m)
