#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# syntax_check.sh — compiles the Android port for aarch64-linux-android24
# with clang -fsyntax-only -Wall -Wextra -Werror: no NDK exists in Debian, so
# this is a syntax and type check, not an NDK build (nothing is linked).
# Headers: Debian's Android headers (android-platform-frameworks-native-headers:
# native_activity.h, input.h, looper.h, asset_manager.h; android-libnativehelper-dev:
# jni.h; android-liblog-dev: log.h), aarch64 glibc's C headers standing in for
# bionic's (libc6-dev-arm64-cross), Khronos EGL/GLES headers (libegl-dev,
# libgles-dev), snell's public headers, and the labelled stubs in syntax_stub/
# for what Debian's Android packages lack (<android/native_window.h>, two
# bionic <sys/cdefs.h> macros).
# Exit 0: it compiles; 1: it does not; 77 (ctest's skip code): a tool or
# header package is missing and cannot be installed (not root).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)

packages=(clang android-platform-frameworks-native-headers android-libnativehelper-dev android-liblog-dev
          libc6-dev-arm64-cross libegl-dev libgles-dev)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" -ne 0 ] || [ "${SNELL_NO_INSTALL:-0}" = 1 ]; then
        echo "SKIP: Android syntax check needs ${missing[*]} (apt-get install them as root)"
        exit 77
    fi
    . "$root/scripts/apt.sh"
    snell_apt_install "${missing[@]}"
fi

sources=("$here"/snell_activity.c "$here"/glass_scene.c "$here"/lifecycle.c "$here"/video_under.c)
clang --target=aarch64-linux-android24 -std=c99 -fsyntax-only -Wall -Wextra -Wpedantic -Werror \
    -include "$here/syntax_stub/bionic_cdefs.h" -D_LARGEFILE64_SOURCE \
    -isystem "$here/syntax_stub" \
    -isystem /usr/include/android -isystem /usr/include/android/nativehelper \
    -isystem /usr/aarch64-linux-gnu/include \
    -I "$root/include" -I "$here" \
    "${sources[@]}"
echo "android syntax check: ${#sources[@]} files compile for aarch64-linux-android24 (syntax only, no NDK)"
