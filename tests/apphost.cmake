# SPDX-License-Identifier: MIT
# Apps as people write them (issue 48): SDL2's default GLES context (GLX on
# X11) under Xvfb, the host's GL state and every framebuffer an app binds.
# Without SDL2 or xvfb-run the SDL2 test is registered as a skip that says
# which is missing (.ci/run installs libsdl2-dev, xvfb and xauth).
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(SDL2 QUIET IMPORTED_TARGET sdl2)
endif()
find_program(SNELL_XVFB_RUN xvfb-run)
set(SNELL_TEST_RAW_OK TRUE) # in every preset: the device one takes a GLX context as any current one
if(TARGET PkgConfig::SDL2 AND SNELL_XVFB_RUN AND NOT CMAKE_CROSSCOMPILING)
  add_executable(test_sdl2_app test_sdl2_app.c)
  target_link_libraries(test_sdl2_app PRIVATE snell_static PkgConfig::SDL2)
  target_compile_options(test_sdl2_app PRIVATE ${SNELL_WARNINGS})
  add_test(NAME test_sdl2_app COMMAND ${SNELL_XVFB_RUN} -a $<TARGET_FILE:test_sdl2_app>)
else()
  set(why "")
  if(NOT TARGET PkgConfig::SDL2)
    string(APPEND why " SDL2 (libsdl2-dev)")
  endif()
  if(NOT SNELL_XVFB_RUN)
    string(APPEND why " xvfb-run (xvfb, xauth)")
  endif()
  if(CMAKE_CROSSCOMPILING)
    string(APPEND why " a native build")
  endif()
  add_test(NAME test_sdl2_app COMMAND sh -c "echo 'SKIP: test_sdl2_app needs${why}'; exit 77")
endif()
set(SNELL_TEST_RAW_OK FALSE)
set_tests_properties(test_sdl2_app PROPERTIES LABELS "render;gl" SKIP_RETURN_CODE 77 TIMEOUT 120)

# The host's GL untouched (pending errors of each kind, transform feedback,
# the KHR_debug callback, NO_WRITE on every depth format), framebuffers
# snell cannot draw into refused by name, MRT, sRGB and the host's viewport.
snell_add_test(test_host_gl SOURCES test_host_gl.c LABELS "render;gl")
target_link_libraries(test_host_gl PRIVATE snell_dep::egl snell_dep::gles m)
target_compile_definitions(test_host_gl PRIVATE $<$<BOOL:${SNELL_WITH_HOST_FRAMEBUFFERS}>:SNELL_WITH_HOST_FRAMEBUFFERS=1>)

# A reversed-Z host depth buffer tested against (mapped in and back), every
# method against the same scene through the standard projection.
snell_add_test(test_reversed_z_host SOURCES test_reversed_z_host.c LABELS "render;gl")
target_link_libraries(test_reversed_z_host PRIVATE snell_dep::gles m)
target_compile_definitions(test_reversed_z_host PRIVATE
  $<$<BOOL:${SNELL_WITH_HOST_FRAMEBUFFERS}>:SNELL_WITH_HOST_FRAMEBUFFERS=1>)

# The recipes of docs/integrating.md (examples/recipes): each built (compiled
# and linked against snell) by its test where its toolkit is installed, else
# the test skips saying what is missing. Android's has no NDK in Debian: it
# is compiled for aarch64-linux-android24, syntax and types only, as
# ports/android/syntax_check.sh compiles the port.
set(recipes ${PROJECT_SOURCE_DIR}/examples/recipes)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(GLFW3 QUIET IMPORTED_TARGET glfw3)
  pkg_check_modules(GBM QUIET IMPORTED_TARGET gbm)
  pkg_check_modules(QT5WIDGETS QUIET IMPORTED_TARGET Qt5Widgets)
endif()
foreach(r sdl2:SDL2:libsdl2-dev glfw:GLFW3:libglfw3-dev kms_gbm:GBM:libgbm-dev qt_widget:QT5WIDGETS:qtbase5-dev)
  string(REPLACE ":" ";" r "${r}")
  list(GET r 0 name)
  list(GET r 1 dep)
  list(GET r 2 package)
  set(src ${recipes}/${name}.c)
  if(name STREQUAL "qt_widget")
    set(src ${recipes}/${name}.cpp)
    if(NOT CMAKE_CXX_COMPILER_LOADED)
      set(dep "none") # a C-only build (the device preset) has no C++ compiler
      set(package "a C++ compiler (a build with glTF or meshoptimizer)")
    endif()
  endif()
  if(TARGET PkgConfig::${dep} AND NOT CMAKE_CROSSCOMPILING)
    add_executable(recipe_${name} EXCLUDE_FROM_ALL ${src})
    target_link_libraries(recipe_${name} PRIVATE snell_static PkgConfig::${dep})
    target_compile_options(recipe_${name} PRIVATE ${SNELL_WARNINGS})
    if(name STREQUAL "qt_widget")
      target_compile_options(recipe_${name} PRIVATE -fPIC) # Qt's headers refuse -fPIE
    endif()
    add_test(NAME recipe_${name} COMMAND ${CMAKE_COMMAND} --build ${PROJECT_BINARY_DIR} --target recipe_${name})
  else()
    add_test(NAME recipe_${name} COMMAND sh -c "echo 'SKIP: recipe ${name} needs ${package}'; exit 77")
  endif()
  # one build of the tree at a time (each test builds its target in it)
  set_tests_properties(recipe_${name} PROPERTIES LABELS "install" SKIP_RETURN_CODE 77 TIMEOUT 300
                       RESOURCE_LOCK snell_build_tree)
endforeach()
find_program(SNELL_CLANG clang)
if(SNELL_CLANG AND EXISTS /usr/include/android/nativehelper/jni.h)
  set(android ${PROJECT_SOURCE_DIR}/ports/android)
  add_test(NAME recipe_android_glsurfaceview COMMAND ${SNELL_CLANG} --target=aarch64-linux-android24 -std=c99
           -fsyntax-only -Wall -Wextra -Wpedantic -Werror -include ${android}/syntax_stub/bionic_cdefs.h
           -D_LARGEFILE64_SOURCE -isystem ${android}/syntax_stub -isystem /usr/include/android
           -isystem /usr/include/android/nativehelper -isystem /usr/aarch64-linux-gnu/include
           -I ${PROJECT_SOURCE_DIR}/include ${recipes}/android_glsurfaceview.c)
else()
  add_test(NAME recipe_android_glsurfaceview COMMAND sh -c
           "echo 'SKIP: recipe android_glsurfaceview needs clang and android-libnativehelper-dev'; exit 77")
endif()
set_tests_properties(recipe_android_glsurfaceview PROPERTIES LABELS "install" SKIP_RETURN_CODE 77)
