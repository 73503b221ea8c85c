# SPDX-License-Identifier: MIT
# Foundation tests: context, shaders, optics twin, single-surface render, CLI, install.
snell_add_test(test_why SOURCES test_why.c LABELS "unit")
snell_add_test(test_ctx SOURCES test_ctx.c LABELS "unit;gl")
target_link_libraries(test_ctx PRIVATE snell_dep::egl snell_dep::gles)
snell_add_test(test_shader SOURCES test_shader.c LABELS "unit;gl")
target_link_libraries(test_shader PRIVATE snell_dep::gles)
snell_add_test(test_optics_twin SOURCES test_optics_twin.c LABELS "unit;gl")
target_link_libraries(test_optics_twin PRIVATE snell_dep::gles m)
snell_add_test(test_render_single SOURCES test_render_single.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_render_single PRIVATE m)

# Installed package, moved after installing: find_package(snell) from a separate
# C-only project (shared and static, the static one loading a .glb), and cc with
# the pkg-config flags (shared and --static).
set(consumer_glb "")
if(SNELL_WITH_GLTF)
  set(consumer_glb ${CMAKE_CURRENT_SOURCE_DIR}/data/nodes.glb)
endif()
# In every preset: the consumer needs nothing but the floor (CI's device leg).
set(SNELL_TEST_RAW_OK TRUE)
add_test(NAME install_consumer
  COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
          -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/consumer -DCC=${CMAKE_C_COMPILER}
          -DGLB=${consumer_glb} -P ${CMAKE_CURRENT_SOURCE_DIR}/consumer/run.cmake)
set(SNELL_TEST_RAW_OK FALSE)
set_tests_properties(install_consumer PROPERTIES LABELS "install" TIMEOUT 300)
# snell built from source by add_subdirectory in a project that asks for CMake
# 3.22, with no pkg-config and the header-only dependencies given as folders
# (tests/subproject/build.sh; .ci/run does the same with the arm64 toolchain).
if(SNELL_WITH_GLTF AND NOT CMAKE_CROSSCOMPILING)
  set(SNELL_TEST_RAW_OK TRUE)
  add_test(NAME subproject_consumer
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/subproject/build.sh ${CMAKE_CURRENT_BINARY_DIR}/subproject)
  set(SNELL_TEST_RAW_OK FALSE)
  set_tests_properties(subproject_consumer PROPERTIES LABELS "install" TIMEOUT 600)
endif()

# The CLI: default run, flags, and clear failures with a non-zero exit.
if(TARGET snell-render)
  set(cli $<TARGET_FILE:snell-render>)
  add_test(NAME cli_default COMMAND ${cli} --size 96x64 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_default.png)
  set_tests_properties(cli_default PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "wrote .*cli_default.png \\(96x64\\)")
  add_test(NAME cli_flags COMMAND ${cli} --mesh shape:torus --ior 1.33 --absorption 0.2,0.1,0
           --camera 45,30,4 --fov 50 --method single --size 64x64 --frames 3 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_flags.png)
  set_tests_properties(cli_flags PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "median .* ms/frame")
  add_test(NAME cli_help COMMAND ${cli} --help)
  set_tests_properties(cli_help PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "usage: snell-render")
  foreach(bad "--ior;abc" "--size;0x5" "--camera;1,2" "--bogus" "--method;nosuch" "--mesh;shape:blob" "--ior")
    string(MAKE_C_IDENTIFIER "cli_bad_${bad}" name)
    string(REPLACE ";" "|" bad_args "${bad}")
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=${bad_args}" -DCODE=2 "-DERR=snell-render: "
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
  add_test(NAME cli_missing_mesh COMMAND ${cli} --mesh /nonexistent/x.obj -o ${CMAKE_CURRENT_BINARY_DIR}/x.png)
  set_tests_properties(cli_missing_mesh PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "snell-render: mesh: .*x.obj")
  add_test(NAME cli_missing_env COMMAND ${cli} --env /nonexistent/sky.png --size 8x8 -o ${CMAKE_CURRENT_BINARY_DIR}/x.png)
  set_tests_properties(cli_missing_env PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "environment: cannot open image")
  add_test(NAME cli_unwritable COMMAND ${cli} --size 8x8 -o /nonexistent/dir/x.png)
  set_tests_properties(cli_unwritable PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "cannot write PNG")
endif()
snell_add_test(test_env SOURCES test_env.c LABELS "unit")
target_link_libraries(test_env PRIVATE m)
snell_add_test(test_alloc SOURCES test_alloc.c LABELS "unit;gl")
snell_add_test(test_exit_dir SOURCES test_exit_dir.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_exit_dir PRIVATE snell_dep::gles m)
# Again as on a driver without GL_EXT_color_buffer_float (a Pi's v3d must be
# probed for it): Mesa hides it, and EXIT_DIRECTION must fall back to RGBA8.
add_test(NAME test_exit_dir_no_float COMMAND test_exit_dir WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(test_exit_dir_no_float PROPERTIES LABELS "render;gl" SKIP_RETURN_CODE 77 TIMEOUT 300
  ENVIRONMENT "SNELL_TEST_DATA=${CMAKE_CURRENT_SOURCE_DIR}/data;SNELL_TEST_OUT=${CMAKE_CURRENT_BINARY_DIR};MESA_EXTENSION_OVERRIDE=-GL_EXT_color_buffer_float;SNELL_TEST_HIDDEN_EXTENSION=GL_EXT_color_buffer_float")

# valgrind on the CLI: no definite leaks, no invalid accesses (driver-internal
# records are suppressed in tests/valgrind.supp with the evidence).
find_program(VALGRIND valgrind)
if(VALGRIND AND TARGET snell-render AND NOT SNELL_SANITIZE)
  add_test(NAME valgrind_snell_render
    COMMAND ${VALGRIND} --error-exitcode=9 --leak-check=full --errors-for-leak-kinds=definite,indirect
            --keep-debuginfo=yes --suppressions=${CMAKE_CURRENT_SOURCE_DIR}/valgrind.supp
            $<TARGET_FILE:snell-render> --size 48x48 -o ${CMAKE_CURRENT_BINARY_DIR}/valgrind.png)
  set_tests_properties(valgrind_snell_render PROPERTIES LABELS "valgrind" TIMEOUT 900)
endif()

# Image input (environment maps) as a fuzz target replayed on valid and broken files.
file(GLOB SNELL_IMAGE_FUZZ_INPUTS CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/data/images/* ${CMAKE_CURRENT_SOURCE_DIR}/data/hostile/*.png)
snell_add_test(fuzz_image SOURCES fuzz/fuzz_image.c LABELS "unit;fuzz" ARGS ${SNELL_IMAGE_FUZZ_INPUTS})
target_link_libraries(fuzz_image PRIVATE m)

# 2D scene and CSV text as a fuzz target, replayed on the valid and malformed
# files under tests/data/lm2d.
file(GLOB SNELL_SCENE2D_FUZZ_INPUTS CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/data/lm2d/*.csv
     ${CMAKE_CURRENT_SOURCE_DIR}/data/lm2d/*.txt)
snell_add_test(fuzz_scene2d SOURCES fuzz/fuzz_scene2d.c LABELS "unit;fuzz" ARGS ${SNELL_SCENE2D_FUZZ_INPUTS})
target_link_libraries(fuzz_scene2d PRIVATE m)
# Dual-paraboloid environment maps: the parameterisation's twin, the GPU
# look-up against exact radiance (random and rim directions), and frames
# through the paraboloid path against the cube path for every kernel (~10 s a run on
# llvmpipe, three runs: AUTO, forward, screen shading).
snell_add_test(test_env_paraboloid SOURCES test_env_paraboloid.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_env_paraboloid PRIVATE m)

# Stored shaders (issue 24): stripped and as written render the same bytes.
# The readable table is generated beside the embedded one for these tests only.
snell_add_test(test_shader_strip SOURCES test_shader_strip.c LABELS "render;gl")
snell_add_test(test_shader_strip_water SOURCES test_shader_strip_water.c LABELS "render;gl")
foreach(t test_shader_strip test_shader_strip_water)
  if(TARGET ${t})
    target_link_libraries(${t} PRIVATE snell_shaders_readable)
  endif()
endforeach()

# Component options (issue 24): what a preset leaves out answers SNELL_E_UNSUPPORTED.
snell_add_test(test_components SOURCES test_components.c LABELS "unit;gl")

# The folders' import rule (docs/ARCHITECTURE.md "Layers"): nothing imports back up.
add_test(NAME source_layers COMMAND ${CMAKE_COMMAND} -DSRC=${PROJECT_SOURCE_DIR}/src -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_layers.cmake)
set_tests_properties(source_layers PROPERTIES LABELS "unit")
# A method parameter's name is the name of the field it sets (snell_param_info).
add_test(NAME source_param_names COMMAND ${CMAKE_COMMAND} -DSRC=${PROJECT_SOURCE_DIR}/src
         -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_param_names.cmake)
set_tests_properties(source_param_names PROPERTIES LABELS "unit")

# The shared library exports snell_* only (cmake/snell.map).
if(CMAKE_NM)
  add_test(NAME library_exports COMMAND ${CMAKE_COMMAND} -DNM=${CMAKE_NM} -DLIB=$<TARGET_FILE:snell_shared>
           -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_exports.cmake)
  set_tests_properties(library_exports PROPERTIES LABELS "unit")
endif()
# Texture units and uniforms bound per program (frame/textures.h): every
# method in both shadings with every kernel hook on, against GLES 3.0's
# minimum limits read back from the programs; too many samplers refused.
snell_add_test(test_units SOURCES test_units.c LABELS "unit;gl" TIMEOUT 1500)
target_link_libraries(test_units PRIVATE PkgConfig::GLES)
# Every program those frames build, its final source (defines and chunks
# pasted; dumped by test_units into glsl/), validated and linked as GLSL ES
# 3.00 by glslangValidator and counted against every device profile's
# varyings, draw buffers, vertex uniform vectors and samplers
# (tests/scripts/glsl_check.py); skipped, saying so, without glslangValidator.
find_program(SNELL_PYTHON3 python3)
if(SNELL_PYTHON3 AND TARGET test_units AND NOT CMAKE_CROSSCOMPILING)
  add_test(NAME glsl_validate COMMAND ${SNELL_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/glsl_check.py
           ${CMAKE_CURRENT_BINARY_DIR}/glsl)
  set_tests_properties(glsl_validate PROPERTIES LABELS "unit;gl" SKIP_RETURN_CODE 77 FIXTURES_REQUIRED glsl_dump
                       TIMEOUT 600)
  set_tests_properties(test_units PROPERTIES FIXTURES_SETUP glsl_dump)
endif()
# The same rule on the symbols the library's objects use: a call up through a
# header a lower folder declares passes the include check and fails this one.
if(SNELL_PYTHON3)
  add_test(NAME source_layers_symbols COMMAND ${SNELL_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_layers_symbols.py
           ${PROJECT_BINARY_DIR}/CMakeFiles/snell_objects.dir)
  set_tests_properties(source_layers_symbols PROPERTIES LABELS "unit")
  # Which tests .ci/run's profile legs run: those whose profile-bound answers differ.
  add_test(NAME profile_tests_choice COMMAND ${SNELL_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/test_profile_tests.py)
  set_tests_properties(profile_tests_choice PROPERTIES LABELS "unit")
endif()
# test_stage_seam: the stages' kernel hooks take their variant bits in the table's order (frame/stage.h).
snell_add_test(test_stage_seam SOURCES test_stage_seam.c LABELS "unit")
