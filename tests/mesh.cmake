# SPDX-License-Identifier: MIT
# Mesh loaders (OBJ, glTF) and procedural shapes; fuzz targets replayed on the
# assets in tests/data (valid and malformed) and on tests/fuzz/regressions.
snell_add_test(test_mesh_obj SOURCES test_mesh_obj.c LABELS "unit")
target_link_libraries(test_mesh_obj PRIVATE m)
snell_add_test(test_mesh_shapes SOURCES test_mesh_shapes.c LABELS "unit")
target_link_libraries(test_mesh_shapes PRIVATE m)
if(SNELL_WITH_GLTF)
  target_compile_definitions(test_mesh_obj PRIVATE SNELL_TEST_HAVE_GLTF=1)
  snell_add_test(test_mesh_gltf SOURCES test_mesh_gltf.c LABELS "unit")
  target_link_libraries(test_mesh_gltf PRIVATE m)
endif()

# Fuzz targets as plain replay programs (no -DSNELL_LIBFUZZER): every input file
# goes through both loaders, and every mesh they accept through snell_mesh_normalize
# and snell_mesh_analyze; a crash, sanitizer report or broken invariant fails.
# tests/fuzz/run_libfuzzer.sh runs the same targets under libFuzzer (.ci/run: 5 s each).
file(GLOB SNELL_MESH_FUZZ_INPUTS CONFIGURE_DEPENDS
     ${CMAKE_CURRENT_SOURCE_DIR}/data/*.obj ${CMAKE_CURRENT_SOURCE_DIR}/data/*.gltf
     ${CMAKE_CURRENT_SOURCE_DIR}/data/*.glb ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/regressions/*
     ${CMAKE_CURRENT_SOURCE_DIR}/data/hostile/*.obj ${CMAKE_CURRENT_SOURCE_DIR}/data/hostile/*.gltf
     ${CMAKE_CURRENT_SOURCE_DIR}/data/*.3ds ${CMAKE_CURRENT_SOURCE_DIR}/data/*.jobj)
foreach(target fuzz_obj fuzz_gltf fuzz_3ds)
  snell_add_test(${target} SOURCES fuzz/${target}.c LABELS "unit;fuzz" ARGS ${SNELL_MESH_FUZZ_INPUTS})
  target_link_libraries(${target} PRIVATE m)
endforeach()
# glmark2's .3ds and .jobj (src/mesh/mesh_3ds.c): built and hostile inputs, and
# every model of glmark2-data (Debian's package, in the quick start's list)
# against tests/scripts/3ds_to_obj.py's conversion (not under an emulator,
# where the test program cannot start the host's python3).
set(glmark2_args "")
if(NOT CMAKE_CROSSCOMPILING)
  set(glmark2_args /usr/share/glmark2/models ${CMAKE_CURRENT_SOURCE_DIR}/scripts/3ds_to_obj.py ${CMAKE_CURRENT_BINARY_DIR})
endif()
snell_add_test(test_mesh_3ds SOURCES test_mesh_3ds.c LABELS "unit" ARGS ${glmark2_args})
# The GPU copy of a mesh (src/mesh/mesh_gpu.c): same triangles and winding, better vertex cache.
snell_add_test(test_mesh_gpu SOURCES test_mesh_gpu.c LABELS "unit")
if(SNELL_WITH_MESHOPT)
  target_compile_definitions(test_mesh_gpu PRIVATE SNELL_WITH_MESHOPT_TEST=1)
endif()
# Level of detail (src/mesh/mesh_lod.c): counts, closed stays closed, locked border, hostile descs.
snell_add_test(test_mesh_lod SOURCES test_mesh_lod.c LABELS "unit")
target_link_libraries(test_mesh_lod PRIVATE m)
if(SNELL_WITH_MESHOPT)
  target_compile_definitions(test_mesh_lod PRIVATE SNELL_WITH_MESHOPT_TEST=1)
endif()
