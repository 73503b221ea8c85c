# SPDX-License-Identifier: MIT
# The Android port (ports/android): its lifecycle rules and its scene (CPU
# data kept, GL objects made again after a context loss) run on the host; the
# NDK glue itself is syntax-checked for aarch64-linux-android24 against
# Debian's Android headers (ports/android/syntax_check.sh; skipped with the
# reason when clang or the headers are missing).
set(SNELL_ANDROID_DIR ${PROJECT_SOURCE_DIR}/ports/android)
snell_add_test(test_android_lifecycle SOURCES test_android_lifecycle.c ${SNELL_ANDROID_DIR}/lifecycle.c
               LABELS "unit;android")
target_include_directories(test_android_lifecycle PRIVATE ${SNELL_ANDROID_DIR})
snell_add_test(test_android_scene SOURCES test_android_scene.c ${SNELL_ANDROID_DIR}/glass_scene.c
               LABELS "render;gl;android")
target_include_directories(test_android_scene PRIVATE ${SNELL_ANDROID_DIR})
target_link_libraries(test_android_scene PRIVATE snell_dep::egl snell_dep::gles)
target_compile_definitions(test_android_scene PRIVATE $<$<BOOL:${SNELL_WITH_GLTF}>:SNELL_WITH_GLTF=1>)
# ctest does not install packages: without them the check reports itself skipped
# (.ci/run runs the script directly, which installs them as root).
add_test(NAME android_syntax COMMAND bash ${SNELL_ANDROID_DIR}/syntax_check.sh)
set_tests_properties(android_syntax PROPERTIES LABELS "android" SKIP_RETURN_CODE 77 TIMEOUT 120
                     ENVIRONMENT "SNELL_NO_INSTALL=1")
