#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# run_libfuzzer.sh [SECONDS] — builds the fuzz targets (fuzz_obj, fuzz_gltf, fuzz_3ds,
# fuzz_image, fuzz_scene2d) with clang's libFuzzer, ASan and UBSan, and runs
# each for SECONDS (default 5) on a corpus seeded from the test assets. A
# crash, sanitizer report, broken invariant (fuzz_common.h) or an input slower
# than 10 s fails the script; the input is left in $FUZZ_DIR/crash-*.
# Without clang or its libFuzzer runtime (Debian: libclang-rt-14-dev) it says
# so and exits 0. .ci/run calls it after the ctest replay of the corpora.
# The library is compiled from src/ straight into the targets (instrumented),
# and tinygltf from its header (tests/fuzz/tinygltf_impl.cpp), so both are
# covered; README.md here has the commands for one target by hand.
set -euo pipefail
cd "$(dirname "$0")/../.."

SECS=${1:-5}
OUT=${FUZZ_DIR:-build-libfuzzer}
JOBS=$(nproc)

if ! command -v clang >/dev/null 2>&1 || ! command -v clang++ >/dev/null 2>&1; then
    echo "run_libfuzzer: clang not found: skipped"
    exit 0
fi
mkdir -p "$OUT/obj"
OUT=$(cd "$OUT" && pwd)
printf 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { (void)d; (void)n; return 0; }\n' \
    >"$OUT/probe.c"
if ! clang -fsanitize=fuzzer "$OUT/probe.c" -o "$OUT/probe" 2>/dev/null; then
    echo "run_libfuzzer: clang has no libFuzzer runtime (Debian: libclang-rt-14-dev): skipped"
    exit 0
fi

STB=$(dirname "$(find /usr/include /usr/local/include -name stb_image.h 2>/dev/null | head -1)")
F="-g -O1 -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -DSNELL_LIBFUZZER"
F="$F -DSNELL_WITH_GLTF=1 -DTINYGLTF_NO_STB_IMAGE -DTINYGLTF_NO_STB_IMAGE_WRITE -Iinclude -Isrc -I$STB -Itests/fuzz"
# snell_mesh_simplify (the level of detail) when meshoptimizer is installed (Debian:
# libmeshoptimizer-dev), as the CMake default builds it; its own code is not instrumented.
LIBS=""
if [ -f /usr/include/meshoptimizer.h ]; then
    F="$F -DSNELL_WITH_MESHOPT=1"
    LIBS="-lmeshoptimizer"
fi
export F OUT

echo "run_libfuzzer: building into $OUT"
cmake -DSHADER_DIR="$PWD/shaders_es" -DOUTPUT="$OUT/shaders_embedded.c" -P cmake/embed_shaders.cmake
# Every component built in (cmake/components.cmake's header for the full build;
# the *_off.c stubs of components left out are not compiled). The components
# are read from its option(SNELL_WITH_<X> ... ${snell_default}) lines and the
# methods from the registry, so a new one cannot be missing here (a hand-kept
# list once left out CAUSTICS and the targets did not link).
{
    echo "#ifndef SNELL_COMPONENTS_H"; echo "#define SNELL_COMPONENTS_H"
    comps=$(sed -n 's/^option(SNELL_WITH_\([A-Z0-9_]*\) .*${snell_default})$/\1/p' cmake/components.cmake)
    [ -n "$comps" ] || { echo "run_libfuzzer: no component options in cmake/components.cmake" >&2; exit 1; }
    for c in $comps; do echo "#define SNELL_WITH_$c 1"; done
    methods=$(sed -n 's/^ *M(\([a-z0-9_]*\), [A-Z0-9_]*).*/\1/p' src/methods/registry.c)
    for m in $methods; do echo "#define SNELL__BUILT_$m 1"; done
    echo "#define SNELL__COMPONENTS \"$(echo $comps | tr 'A-Z' 'a-z') $(echo $methods)\""; echo "#endif"
} > "$OUT/snell_components.h"
F="$F -I$OUT"
# One object per library source (warnings are the gcc build's business: -w).
compile() {
    local src=$1 obj
    obj="$OUT/obj/$(echo "$src" | tr '/' '_').o"
    case "$src" in
    *.cpp) clang++ -std=c++11 $F -w -c "$src" -o "$obj" ;;
    # stb_image (third party, inside image.c): see the SNELL_SANITIZE note in CMakeLists.txt
    src/core/image.c) clang -std=c99 $F -fno-sanitize=pointer-overflow,nonnull-attribute -w -c "$src" -o "$obj" ;;
    *) clang -std=c99 $F -w -c "$src" -o "$obj" ;;
    esac
}
export -f compile
{ find src -name '*.c' ! -name '*_off.c'; echo src/mesh/mesh_gltf.cpp; echo tests/fuzz/tinygltf_impl.cpp; echo "$OUT/shaders_embedded.c"; } |
    xargs -P "$JOBS" -I{} bash -c 'compile {}'

run() {
    local t=$1 max_len=$2
    shift 2
    clang -std=c99 $F -w -c "tests/fuzz/$t.c" -o "$OUT/$t.o"
    clang++ $F -fsanitize=fuzzer "$OUT/$t.o" "$OUT"/obj/*.o $LIBS -lEGL -lGLESv2 -lpthread -lm -o "$OUT/$t"
    rm -rf "$OUT/corpus_$t"
    mkdir -p "$OUT/corpus_$t"
    cp "$@" "$OUT/corpus_$t/" 2>/dev/null || true
    echo "== $t: $SECS s"
    local rc=0
    "$OUT/$t" -max_total_time="$SECS" -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
        -artifact_prefix="$OUT/crash-$t-" "$OUT/corpus_$t" >"$OUT/$t.log" 2>&1 || rc=$?
    grep -E "^#[0-9]+ +DONE|stat::number_of_executed_units|ERROR|SUMMARY|Test unit written" "$OUT/$t.log" || true
    # (The status used to be read from PIPESTATUS after "|| true", which is
    # true's own: a finding passed CI. The fuzzer's exit status decides now.)
    if [ "$rc" -ne 0 ]; then
        echo "run_libfuzzer: $t failed (exit $rc); the input: $(ls "$OUT"/crash-"$t"-* 2>/dev/null | head -1)" >&2
        exit 1
    fi
}
# (tests/fuzz/regressions/coincident_face.obj stays out of the seeds: it runs into
# the analysis's work bound, ~3 s a run when instrumented; ctest replays it.)
run fuzz_obj 4096 tests/data/*.obj tests/data/hostile/*.obj
run fuzz_gltf 8192 tests/data/*.gltf tests/data/*.glb tests/data/hostile/*.gltf
run fuzz_3ds 4096 tests/data/*.3ds tests/data/*.jobj
run fuzz_image 4096 tests/data/images/*
run fuzz_scene2d 4096 tests/data/lm2d/*
echo "run_libfuzzer: 5 targets, $SECS s each: no findings"
