# Mesh loaders (OBJ, glTF) and procedural shapes; fuzz targets replayed on tests/data.
snell_add_test(test_mesh_obj SOURCES test_mesh_obj.c LABELS "unit")
target_link_libraries(test_mesh_obj PRIVATE m)
if(SNELL_WITH_GLTF)
  target_compile_definitions(test_mesh_obj PRIVATE SNELL_TEST_HAVE_GLTF=1)
endif()
snell_add_test(test_mesh_shapes SOURCES test_mesh_shapes.c LABELS "unit")
target_link_libraries(test_mesh_shapes PRIVATE m)
