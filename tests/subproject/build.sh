#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# build.sh WORK_DIR [arm64 [PROJECT]] — builds tests/subproject (or PROJECT,
# e.g. ports/android/app/src/main/cpp: configured and built, not run) (snell by add_subdirectory
# in a project that asks for CMake 3.22) as an NDK app's build would meet it:
# no pkg-config on the PATH (and find_package(PkgConfig) disabled, since CMake
# also looks in /usr/bin), and stb, cglm and tinygltf given as folders copied
# out of the system into WORK_DIR/vendor, with the system's TinyGLTF package
# disabled. Host: builds and runs the app (renders a frame, loads a .glb).
# arm64: the same with cmake/toolchains/aarch64-linux-gnu.cmake and its sysroot
# (scripts/make_sysroot.sh arm64), run under qemu-aarch64 when it is there.
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
work=$(realpath -m "${1:?usage: build.sh WORK_DIR [arm64]}")
arch=${2:-host}
project=$(realpath "${3:-$src/tests/subproject}")
rm -rf "$work"
mkdir -p "$work/bin" "$work/vendor/stb" "$work/vendor/cglm" "$work/vendor/tinygltf"

# A PATH of links to every program on the current one but pkg-config.
IFS=: read -ra dirs <<<"$PATH"
for d in "${dirs[@]}"; do
    [ -d "$d" ] || continue
    for f in "$d"/*; do
        n=${f##*/}
        case "$n" in pkg-config | pkgconf | *-pkg-config | *-pkgconf) continue ;; esac
        [ -x "$f" ] && [ ! -e "$work/bin/$n" ] && ln -s "$f" "$work/bin/$n"
    done
done
if PATH=$work/bin command -v pkg-config >/dev/null; then
    echo "build.sh: pkg-config is still on the PATH" >&2
    exit 1
fi

# Header-only dependencies as source folders (an NDK app vendors them so).
root=
[ "$arch" = arm64 ] && root=$src/build-sysroot/arm64
cp "$root"/usr/include/stb/stb_image.h "$root"/usr/include/stb/stb_image_write.h "$work/vendor/stb/"
cp -r "$root"/usr/include/cglm "$work/vendor/cglm/"
cp "$root"/usr/include/tiny_gltf.h "$work/vendor/tinygltf/"

args=(-DSNELL_SOURCE_DIR="$src" -DCMAKE_DISABLE_FIND_PACKAGE_PkgConfig=ON
      -DCMAKE_DISABLE_FIND_PACKAGE_TinyGLTF=ON
      -DSTB_INCLUDE_DIR="$work/vendor/stb" -DCGLM_INCLUDE_DIR="$work/vendor/cglm"
      -DSNELL_TINYGLTF_DIR="$work/vendor/tinygltf")
run=()
if [ "$arch" = arm64 ]; then
    args+=(-DCMAKE_TOOLCHAIN_FILE="$src/cmake/toolchains/aarch64-linux-gnu.cmake")
    if command -v qemu-aarch64-static >/dev/null; then
        run=(qemu-aarch64-static -L "$root")
    else
        run=(true)
    fi
fi
PATH=$work/bin cmake --no-warn-unused-cli -S "$project" -B "$work/build" "${args[@]}" >"$work/configure.log" ||
    { cat "$work/configure.log"; exit 1; }
grep -q "snell: EGL and GLES by library search" "$work/configure.log" ||
    { echo "build.sh: snell did not find EGL/GLES by its library search" >&2; exit 1; }
PATH=$work/bin cmake --build "$work/build" -j"${JOBS:-2}" >"$work/build.log" || { tail -40 "$work/build.log"; exit 1; }
if [ "$project" != "$src/tests/subproject" ]; then
    echo "build.sh: $project configured and built in $work/build"
    exit 0
fi
file "$work/build/subproject_app"
"${run[@]}" "$work/build/subproject_app" "$src/tests/data/nodes.glb"
"${run[@]}" "$work/build/subproject_gl"
