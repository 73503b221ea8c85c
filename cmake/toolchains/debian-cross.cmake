# SPDX-License-Identifier: MIT
# Shared part of the Debian cross toolchains (aarch64-linux-gnu.cmake,
# arm-linux-gnueabihf.cmake): Debian's crossbuild-essential-<arch> compilers
# against a sysroot made by scripts/make_sysroot.sh from Debian's own packages
# of that architecture, and qemu-user-static as the emulator that ctest runs
# the test programs through. The includer sets SNELL_CROSS_TRIPLE,
# SNELL_CROSS_DEBIAN_ARCH, SNELL_CROSS_QEMU and CMAKE_SYSTEM_PROCESSOR.
set(CMAKE_SYSTEM_NAME Linux)

# The sysroot: -DSNELL_SYSROOT=DIR, else build-sysroot/<arch> next to the source.
if(NOT SNELL_SYSROOT)
  get_filename_component(SNELL_SYSROOT "${CMAKE_CURRENT_LIST_DIR}/../../build-sysroot/${SNELL_CROSS_DEBIAN_ARCH}"
                         ABSOLUTE)
endif()
set(SNELL_SYSROOT "${SNELL_SYSROOT}" CACHE PATH "sysroot from scripts/make_sysroot.sh ${SNELL_CROSS_DEBIAN_ARCH}")
if(NOT EXISTS "${SNELL_SYSROOT}/usr/include/${SNELL_CROSS_TRIPLE}")
  message(FATAL_ERROR "no ${SNELL_CROSS_DEBIAN_ARCH} sysroot at ${SNELL_SYSROOT}: "
                      "run scripts/make_sysroot.sh ${SNELL_CROSS_DEBIAN_ARCH} (or pass -DSNELL_SYSROOT=DIR)")
endif()
# try_compile projects get the variables they need to find the same sysroot.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES SNELL_SYSROOT)

set(CMAKE_SYSROOT "${SNELL_SYSROOT}")
set(CMAKE_C_COMPILER ${SNELL_CROSS_TRIPLE}-gcc)
set(CMAKE_CXX_COMPILER ${SNELL_CROSS_TRIPLE}-g++)
set(CMAKE_FIND_ROOT_PATH "${SNELL_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# A sysroot unpacked with dpkg-deb has no ld.so.cache: the linker finds the
# libraries' own dependencies (libEGL -> libGLdispatch, ...) by rpath-link.
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-Wl,-rpath-link,${SNELL_SYSROOT}/usr/lib/${SNELL_CROSS_TRIPLE}:${SNELL_SYSROOT}/lib/${SNELL_CROSS_TRIPLE}")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "${CMAKE_EXE_LINKER_FLAGS_INIT}")

# pkg-config reads the sysroot's .pc files only, and prefixes their paths.
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${SNELL_SYSROOT}")
set(ENV{PKG_CONFIG_LIBDIR}
    "${SNELL_SYSROOT}/usr/lib/${SNELL_CROSS_TRIPLE}/pkgconfig:${SNELL_SYSROOT}/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_PATH} "")

# ctest (and add_custom_command on a target) run target programs through
# qemu-user with the sysroot as the root for the loader, libraries and
# Mesa's drivers; -L applies to every path the program opens.
find_program(SNELL_QEMU ${SNELL_CROSS_QEMU})
if(SNELL_QEMU)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${SNELL_QEMU};-L;${SNELL_SYSROOT}")
endif()
