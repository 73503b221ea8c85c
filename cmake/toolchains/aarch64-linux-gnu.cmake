# SPDX-License-Identifier: MIT
# 64-bit Raspberry Pi OS / Debian arm64 (Pi 3, 4, 5): crossbuild-essential-arm64,
# a sysroot from scripts/make_sysroot.sh arm64, tests under qemu-aarch64-static.
#   cmake -S . -B build-arm64 -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/aarch64-linux-gnu.cmake
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(SNELL_CROSS_TRIPLE aarch64-linux-gnu)
set(SNELL_CROSS_DEBIAN_ARCH arm64)
set(SNELL_CROSS_QEMU qemu-aarch64-static)
include(${CMAKE_CURRENT_LIST_DIR}/debian-cross.cmake)
