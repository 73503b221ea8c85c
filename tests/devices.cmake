# SPDX-License-Identifier: MIT
# Mesa's real GPU drivers over drm-shim (shared/devices, docs/devices.md): the
# device profiles against what each driver reports, and snell-shaderdb, the
# tool bench/device_shaders.sh compiles every program variant with.
add_executable(snell-shaderdb snell_shaderdb.c)
target_link_libraries(snell-shaderdb PRIVATE snell_static PkgConfig::GLES)
target_include_directories(snell-shaderdb PRIVATE ${PROJECT_SOURCE_DIR}/src)
target_compile_options(snell-shaderdb PRIVATE ${SNELL_WARNINGS})
# What a tool's frames link, dumped for snell-shaderdb (bench/device_shaders.sh --defaults):
# LD_PRELOAD=libsnell_glsl_dump.so, GL calls wrapped, nothing of snell's changed.
add_library(snell_glsl_dump MODULE glsl_dump_preload.c)
target_link_libraries(snell_glsl_dump PRIVATE ${CMAKE_DL_LIBS})
target_compile_options(snell_glsl_dump PRIVATE ${SNELL_WARNINGS})
# Each profile of src/core/profile.c with an open driver (rpi-v3d, adreno-6xx, mali-bifrost)
# against what that driver reports on every GPU it stands for: a limit above the driver's or an
# extension the driver lacks fails. Skipped (77), saying why, without the drivers' tarball. A
# few seconds: no llvmpipe, no program compiled (label device, not gl).
if(NOT CMAKE_CROSSCOMPILING)
  add_test(NAME device_profiles COMMAND bash ${PROJECT_SOURCE_DIR}/bench/device_shaders.sh
           --build ${PROJECT_BINARY_DIR} --profiles)
  set_tests_properties(device_profiles PROPERTIES LABELS "device" SKIP_RETURN_CODE 77 TIMEOUT 120)
endif()
# CI's device leg (device_shaders.sh --ci) fails where it should: bench/device_shaders.py on
# made-up compiler logs, a spill, a refusal and a V3D shader below its promised threads.
if(SNELL_PYTHON3)
  add_test(NAME device_shaders_verdicts COMMAND ${SNELL_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/test_device_shaders.py
           ${PROJECT_SOURCE_DIR}/bench/device_shaders.py)
  set_tests_properties(device_shaders_verdicts PROPERTIES LABELS "unit" TIMEOUT 60)
endif()
# bench/device_cost.py (bench/devices/COSTS.md) prices each device loop by its own source loop's trip
# count, or stops: a made-up V3D log in exact's shape, and every loop of the kernels it prices.
if(SNELL_PYTHON3)
  add_test(NAME device_cost_loops COMMAND ${SNELL_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/test_device_cost_loops.py
           ${PROJECT_SOURCE_DIR}/bench/device_cost.py ${PROJECT_SOURCE_DIR}/shaders_es)
  set_tests_properties(device_cost_loops PROPERTIES LABELS "unit" TIMEOUT 60)
endif()
