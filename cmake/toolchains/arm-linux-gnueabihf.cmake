# SPDX-License-Identifier: MIT
# 32-bit Raspberry Pi OS / Debian armhf (ARMv7 + VFPv3-D16, Pi 2 and later):
# crossbuild-essential-armhf, a sysroot from scripts/make_sysroot.sh armhf,
# tests (if run) under qemu-arm-static.
#   cmake -S . -B build-armhf -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/arm-linux-gnueabihf.cmake
set(CMAKE_SYSTEM_PROCESSOR armv7l)
set(SNELL_CROSS_TRIPLE arm-linux-gnueabihf)
set(SNELL_CROSS_DEBIAN_ARCH armhf)
set(SNELL_CROSS_QEMU qemu-arm-static)
include(${CMAKE_CURRENT_LIST_DIR}/debian-cross.cmake)
