#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# quickstart.sh render|test|test-all — the README's commands.
#   render:   install what is missing, build, render the default scene to snell.png
#   test:     install what is missing, build, run the whole ctest suite, then
#             say which tests skipped themselves and why (ctest counts a skip
#             as passed: without blender, qemu and the Android headers
#             test_groundtruth, test_caustics_cycles, kms_vm and android_syntax skip,
#             without SDL2, GLFW, Qt 5 and Xvfb test_sdl2_app and recipe_*,
#             and device_profiles without ../shared/devices, docs/devices.md)
#   test-all: also install what those three need (as root), then as test
# Works as root on a fresh Debian 12 (uses apt-get), or as a user when the
# packages are already there. BUILD_DIR (default build) and extra CMake flags
# in CMAKE_ARGS may be set by the caller (.ci/run uses both).
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/apt.sh

PACKAGES=(build-essential g++ cmake pkg-config
          libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
          libcglm-dev libstb-dev libtinygltf-dev nlohmann-json3-dev libmeshoptimizer-dev
          glmark2-data valgrind glslang-tools
          libdrm-dev libgbm-dev)

install_missing() {
    local missing=()
    for p in "${PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    if [ "$(id -u)" -ne 0 ]; then
        echo "quickstart: missing packages: ${missing[*]} (run as root to install them)" >&2
        exit 1
    fi
    echo "quickstart: installing ${missing[*]}"
    snell_apt_install "${missing[@]}"
}

# What the tests that skip without it need (test-all): Blender for
# test_groundtruth and test_caustics_cycles, qemu and a kernel with the bochs DRM module for kms_vm,
# SDL2, GLFW, Qt 5 and Xvfb for test_sdl2_app and the recipe_* tests (the
# same lists as .ci/run's); ports/android/syntax_check.sh installs its own
# packages as root (it compiles nothing else of the build).
EXTRA_PACKAGES=(blender qemu-system-x86 busybox-static kmod linux-image-amd64
                libsdl2-dev libglfw3-dev qtbase5-dev xvfb xauth)

install_extra() {
    local missing=()
    if [ "$(id -u)" -ne 0 ]; then
        echo "quickstart: test-all installs packages with apt-get: run it as root" >&2
        exit 1
    fi
    for p in "${EXTRA_PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    if [ ${#missing[@]} -gt 0 ]; then
        echo "quickstart: installing ${missing[*]}"
        snell_apt_install "${missing[@]}"
    fi
    bash ports/android/syntax_check.sh
}

# The tests ctest reports "(Skipped)" (exit 77, SKIP_RETURN_CODE), each with
# the SKIP line it printed (from Testing/Temporary/LastTest.log), and the one
# command that runs them. Nothing when ctest ran no test (CTEST_ARGS=-N).
report_skipped() {
    local dir=$1 out=$2 log=$1/Testing/Temporary/LastTest.log total skipped t reason n
    total=$(sed -n 's/.*tests passed, .* out of \([0-9][0-9]*\)$/\1/p' "$out" | tail -n 1)
    [ -n "$total" ] || return 0
    skipped=$(sed -n 's/^[[:space:]]*[0-9][0-9]* - \(.*\) (Skipped)$/\1/p' "$out")
    echo
    if [ -z "$skipped" ]; then
        echo "quickstart: all $total tests ran; none was skipped"
        return 0
    fi
    n=$(printf '%s\n' "$skipped" | wc -l)
    echo "quickstart: $n of the $total tests were SKIPPED (ctest counts them as passed), so they tested nothing:"
    for t in $skipped; do
        reason=$(awk -v t="$t" '/^[0-9]+\/[0-9]+ Testing: / { on = ($NF == t); next }
                                on && /^<end of output>/ { on = 0 }
                                on && /SKIP/ { print; exit }' "$log" 2>/dev/null || true)
        printf '  %-22s %s\n' "$t" "${reason:-(it printed no reason)}"
    done
    echo "quickstart: to install what they need (Blender, qemu and a kernel, the Android headers; as root, a few"
    echo "            minutes more) and run every test: bash scripts/quickstart.sh test-all"
}

run_tests() {
    local dir=${BUILD_DIR:-build} out rc=0
    out=$(mktemp)
    # shellcheck disable=SC2086
    ctest --test-dir "$dir" --output-on-failure -j"$(nproc)" ${CTEST_ARGS:-} | tee "$out" || rc=$?
    report_skipped "$dir" "$out"
    rm -f "$out"
    return $rc
}

build() {
    local dir=${BUILD_DIR:-build}
    # shellcheck disable=SC2086
    cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-RelWithDebInfo} ${CMAKE_ARGS:-}
    cmake --build "$dir" -j"$(nproc)"
}

case "${1:-}" in
render)
    install_missing
    build
    "${BUILD_DIR:-build}/ports/cli/snell-render" -o snell.png
    ;;
test)
    install_missing
    build
    run_tests
    ;;
test-all)
    install_missing
    install_extra
    build
    run_tests
    ;;
*)
    echo "usage: $0 render|test|test-all" >&2
    exit 2
    ;;
esac
