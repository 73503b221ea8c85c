# SPDX-License-Identifier: MIT
# snell_gl.cmake — the targets snell_dep::egl and snell_dep::gles, for the
# build and (installed beside snellConfig.cmake) for its users.
# pkg-config where it is found and knows the package (desktop Linux, Debian
# sysroots); otherwise a plain library and header search, which is what an
# Android NDK build gets: its sysroot has libEGL.so and libGLESv3.so and no
# .pc files. On Android pkg-config is never asked, since a host pkg-config
# would answer with the build machine's libraries.
# Given as paths: -DSNELL_EGL_LIBRARY=... -DSNELL_EGL_INCLUDE_DIR=...
# -DSNELL_GLES_LIBRARY=... -DSNELL_GLES_INCLUDE_DIR=... (these skip pkg-config).
if(NOT TARGET snell_dep::egl)
  if(NOT ANDROID AND NOT SNELL_EGL_LIBRARY AND NOT SNELL_GLES_LIBRARY)
    find_package(PkgConfig QUIET)
  endif()
  if(PKG_CONFIG_FOUND)
    pkg_check_modules(EGL QUIET IMPORTED_TARGET egl)
    pkg_check_modules(GLES QUIET IMPORTED_TARGET glesv2)
  endif()
  set(snell_gl_how "pkg-config")
  foreach(dep egl gles)
    string(TOUPPER ${dep} up)
    add_library(snell_dep::${dep} INTERFACE IMPORTED)
    if(TARGET PkgConfig::${up})
      set_target_properties(snell_dep::${dep} PROPERTIES INTERFACE_LINK_LIBRARIES PkgConfig::${up})
      continue()
    endif()
    set(snell_gl_how "library search")
    if(dep STREQUAL "egl")
      find_library(SNELL_EGL_LIBRARY EGL)
      find_path(SNELL_EGL_INCLUDE_DIR EGL/egl.h)
    else()
      # GLESv2 is Mesa's and most drivers' library for ES 3; the NDK has both.
      find_library(SNELL_GLES_LIBRARY NAMES GLESv2 GLESv3)
      find_path(SNELL_GLES_INCLUDE_DIR GLES3/gl3.h)
    endif()
    if(NOT SNELL_${up}_LIBRARY OR NOT SNELL_${up}_INCLUDE_DIR)
      message(FATAL_ERROR "snell: ${dep} not found by pkg-config nor by a library search "
                          "(give -DSNELL_${up}_LIBRARY=... -DSNELL_${up}_INCLUDE_DIR=...)")
    endif()
    set_target_properties(snell_dep::${dep} PROPERTIES
      INTERFACE_LINK_LIBRARIES "${SNELL_${up}_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${SNELL_${up}_INCLUDE_DIR}")
  endforeach()
  message(STATUS "snell: EGL and GLES by ${snell_gl_how}")
endif()
