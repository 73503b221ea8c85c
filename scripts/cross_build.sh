#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# cross_build.sh arm64|armhf [test] — a Raspberry Pi (Debian arm64/armhf) build
# on an x86-64 Debian 12 host: the sysroot (scripts/make_sysroot.sh, cached in
# build-sysroot/ARCH), then build-ARCH with cmake/toolchains/, and with `test`
# the emulated subset under qemu-user on the sysroot's Mesa llvmpipe:
#   every unit test without GL (ctest -L unit -LE gl), and the GL tests of the
#   context and precision policy, shader assembly, the C/GLSL optics twin, the
#   exit-direction output with its RGBA8 fallback forced and with
#   GL_EXT_color_buffer_float hidden, and the 2D rasteriser's fixed-point
#   (RGB10A2/RGBA8) fallbacks.
# Installs crossbuild-essential-ARCH and qemu-user-static when run as root.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/apt.sh

arch=${1:-}
case "$arch" in
arm64) toolchain=cmake/toolchains/aarch64-linux-gnu.cmake ;;
armhf) toolchain=cmake/toolchains/arm-linux-gnueabihf.cmake ;;
*)
    echo "usage: $0 arm64|armhf [test]" >&2
    exit 2
    ;;
esac
GL_SUBSET='^(test_ctx|test_shader|test_optics_twin|test_exit_dir|test_exit_dir_no_float|test_lm2d_raster)$'

packages=(crossbuild-essential-"$arch" qemu-user-static)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" -ne 0 ]; then
        echo "cross_build: missing packages: ${missing[*]} (run as root to install them)" >&2
        exit 1
    fi
    snell_apt_install "${missing[@]}"
fi

bash scripts/make_sysroot.sh "$arch"
cmake -S . -B "build-$arch" -DCMAKE_TOOLCHAIN_FILE="$toolchain" -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-RelWithDebInfo} >/dev/null
cmake --build "build-$arch" -j"$(nproc)" >/dev/null
echo "cross_build: build-$arch built"
if [ "${2:-}" = test ]; then
    ctest --test-dir "build-$arch" --output-on-failure -j"$(nproc)" -L unit -LE gl
    ctest --test-dir "build-$arch" --output-on-failure -j"$(nproc)" -R "$GL_SUBSET"
fi
