#!/usr/bin/env bash
# quickstart.sh render|test — the README's two commands.
#   render: install what is missing, build, render the default scene to snell.png
#   test:   install what is missing, build, run the whole ctest suite
# Works as root on a fresh Debian 12 (uses apt-get), or as a user when the
# packages are already there. BUILD_DIR (default build) and extra CMake flags
# in CMAKE_ARGS may be set by the caller (.ci/run uses both).
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(build-essential g++ cmake pkg-config
          libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
          libcglm-dev libstb-dev libtinygltf-dev nlohmann-json3-dev libmeshoptimizer-dev
          glmark2-data valgrind
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
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}"
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
    ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j"$(nproc)" ${CTEST_ARGS:-}
    ;;
*)
    echo "usage: $0 render|test" >&2
    exit 2
    ;;
esac
