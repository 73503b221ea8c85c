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

# snell-render --scene: a glTF scene's objects and camera; it excludes --mesh.
if(TARGET snell-render)
  add_test(NAME cli_scene_gltf COMMAND $<TARGET_FILE:snell-render> --scene ${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/glass_row.gltf
           --size 64x64 --stats -o ${CMAKE_CURRENT_BINARY_DIR}/cli_scene_gltf.png)
  set_tests_properties(cli_scene_gltf PROPERTIES LABELS "cli"
    PASS_REGULAR_EXPRESSION "glass 1 \\(scene glass, ior 1.33\\): method cubemap.*glass 2 \\(scene glass, ior 1.7\\): method single.*thin wall")
  set(expect ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  add_test(NAME cli_scene_gltf_with_mesh COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>"
           "-DARGS=--scene|${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/glass_row.gltf|--mesh|sphere" -DCODE=2
           "-DERR=does not combine with --mesh or --opaque" -P ${expect})
  set_tests_properties(cli_scene_gltf_with_mesh PROPERTIES LABELS "cli")
  add_test(NAME cli_scene_gltf_required COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>"
           "-DARGS=--scene|${CMAKE_CURRENT_SOURCE_DIR}/data/scenes/bad_required.gltf|-o|${CMAKE_CURRENT_BINARY_DIR}/cli_scene_gltf_bad.png"
           -DCODE=1 "-DERR=requires material extensions that are not supported: KHR_materials_clearcoat" -P ${expect})
  set_tests_properties(cli_scene_gltf_required PROPERTIES LABELS "cli")
endif()
