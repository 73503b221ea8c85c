#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# device_shaders.sh: every program variant the suite builds through the real compilers of the GPUs
# snell is for -- V3D 4.2 (v3d), Adreno 630 (freedreno), Mali-G52 (panfrost): Mesa 22.3.6's drivers
# over drm-shim (../shared/devices, docs/devices.md), which compile, link and report statistics but
# draw nothing. Writes OUT/DEVICE.csv, OUT/DEVICE.md and OUT/SHADERS.md (bench/device_shaders.py).
#
#   bash bench/device_shaders.sh [options]
#     --dump DIR     programs as tests dump them (SNELL_TEST_GLSL_DUMP: DIR/<hash>.vert + .frag); may be
#                    given again, the union is compiled. Default: dumped here under each device's own
#                    profile (rpi-v3d, adreno-6xx, mali-bifrost) by the GL label, plus test_units' own
#                    dump (the glsl_validate set): a ctest run each, about 3 min each on 2 idle cores
#     --ci           for CI: --strict, needs --dump, skips (exit 77) without the prebuilt drivers
#     --strict       fail on any spill and on a V3D program at 1 thread too
#     --out DIR      default build/device-shaders
#     --build DIR    the build holding tests/snell-shaderdb and the tests; default build
#     --devices L    default "v3d adreno mali"; also adreno-618 and adreno-660 (FD_GPU_ID 618, 660)
#     --page FILE    also copy OUT/SHADERS.md there (bench/devices/SHADERS.md)
#     --jobs N       programs compiled at once (default: the cores)
#     --cpu-limit S  CPU seconds one program may take to compile and link here (default 60); past it,
#                    it counts as refused: the device's own CPU would stall its first draw for minutes
#     --mem-limit MB memory one compile may take (default 4096): V3D's register allocator grows by
#                    gigabytes on the largest kernels; past it, it counts as refused
#     --profiles     instead: src/core/profile.c's device profiles against their drivers' limits and
#                    extensions (V3D 4.2; Adreno 618, 630, 660; Mali-G52, G31); fails where a profile
#                    promises more (ctest device_profiles)
#     --tables       only write the tables again from OUT/logs of an earlier run of the same --dump
#                    (after a change of bench/device_shaders.py)
#     --drivers      only print the folder of the unpacked drivers (unpacking them if needed)
#
# Exit: 0 ok; 1 a device's compiler refused a program (or, with --strict, a spill or a V3D program at
# 1 thread), each offender printed; 2 bad usage or no build; 77 skipped, the reason printed.
# The drivers: $SNELL_DEVICES_DIR (a folder holding inst/) if set; else unpacked once from
# ../shared/devices/mesa-22.3.6-devices.tar.xz into ${XDG_CACHE_HOME:-~/.cache}/snell/ (again when
# the tarball changes); without the tarball, built there by ../shared/devices/build.sh (25-45 min,
# root and network), except under --ci, --profiles and --drivers, which skip instead.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SNELL_DEVICES_SHARED:-$root/../shared/devices}
tarball=$shared/mesa-22.3.6-devices.tar.xz
cache=${SNELL_DEVICES_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/snell/mesa-22.3.6-devices}

dumps=() out=$root/build/device-shaders build=$root/build devices="v3d adreno mali" strict="" ci="" page=""
jobs=$(nproc) cpu_limit=60 mem_limit=4096 only_drivers="" profiles="" tables=""
usage() { sed -n '8,32p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
while [ $# -gt 0 ]; do
    case $1 in
        --dump) dumps+=("$(cd "${2:?--dump needs a folder}" && pwd)") || exit 2; shift ;;
        --ci) ci=1 strict=--strict ;;
        --strict) strict=--strict ;;
        --out) out=${2:?--out needs a folder}; shift ;;
        --build) build=${2:?--build needs a folder}; shift ;;
        --devices) devices=${2:?--devices needs a list}; shift ;;
        --page) page=${2:?--page needs a file}; shift ;;
        --jobs) jobs=${2:?--jobs needs a number}; shift ;;
        --cpu-limit) cpu_limit=${2:?--cpu-limit needs seconds}; shift ;;
        --mem-limit) mem_limit=${2:?--mem-limit needs megabytes}; shift ;;
        --profiles) profiles=1 ;;
        --tables) tables=1 ;;
        --drivers) only_drivers=1 ;;
        -h|--help) usage ;;
        *) echo "device_shaders.sh: unknown option '$1'" >&2; usage ;;
    esac
    shift
done
[ -z "$ci$tables" ] || [ ${#dumps[@]} -gt 0 ] || { echo "device_shaders.sh: --ci and --tables need --dump DIR" >&2; exit 2; }
for d in $devices; do
    case $d in v3d|adreno|adreno-618|adreno-660|mali) ;; *) echo "device_shaders.sh: unknown device '$d'" >&2; exit 2 ;; esac
done
skip() { echo "SKIP: device_shaders.sh: $*" >&2; exit 77; }

# The unpacked drivers (a folder holding inst/): given, cached, unpacked or built.
drivers() {
    if [ -n "${SNELL_DEVICES_DIR:-}" ]; then
        [ -d "$SNELL_DEVICES_DIR/inst" ] || skip "SNELL_DEVICES_DIR=$SNELL_DEVICES_DIR holds no inst/"
        echo "$SNELL_DEVICES_DIR"
        return
    fi
    if [ ! -f "$tarball" ] && [ -d "$cache/inst" ]; then
        echo "$cache" # unpacked before the tarball went
        return
    fi
    if [ ! -f "$tarball" ]; then
        [ -z "$ci$only_drivers$profiles" ] || skip "no $tarball (shared/devices/README.md; $shared/build.sh makes it in 25-45 min)"
        [ -f "$shared/build.sh" ] || skip "neither $tarball nor $shared/build.sh to build it"
        echo "device_shaders.sh: no $tarball: building Mesa's drivers with $shared/build.sh into" \
            "$cache.build; this takes 25-45 min on 2 cores and needs root and network" >&2
        bash "$shared/build.sh" "$cache.build" >&2
        tarball=$cache.build/mesa-22.3.6-devices.tar.xz
    fi
    local stamp tmp
    stamp=$(stat -c '%s %Y' "$tarball")
    if [ ! -d "$cache/inst" ] || [ "$(cat "$cache/.stamp" 2>/dev/null)" != "$stamp" ]; then
        echo "device_shaders.sh: unpacking $tarball into $cache" >&2
        mkdir -p "$(dirname "$cache")"
        tmp=$(mktemp -d "$cache.XXXXXX") # moved in whole: a concurrent run never sees half of it
        tar -C "$tmp" -xJf "$tarball"
        echo "$stamp" >"$tmp/.stamp"
        rm -rf "$cache"
        mv "$tmp" "$cache" 2>/dev/null || rm -rf "$tmp" # another run moved its copy in first
    fi
    echo "$cache"
}
dir=$(drivers)
[ -z "$only_drivers" ] || { echo "$dir"; exit 0; }
[ -f "$shared/env.sh" ] || skip "no $shared/env.sh (the drivers' environment, shared/devices/README.md)"
tool=$build/tests/snell-shaderdb
[ -x "$tool" ] || { echo "device_shaders.sh: no $tool: cmake --build $build --target snell-shaderdb" >&2; exit 2; }
profile_of() { case $1 in v3d) echo rpi-v3d ;; adreno*) echo adreno-6xx ;; mali) echo mali-bifrost ;; esac; }

# Every limit and extension of a profile against its driver, on each GPU the profile stands for
# (the drm-shim of Mesa 22.3.6 knows no Adreno 650: 660 stands in for the newest).
if [ -n "$profiles" ]; then
    rc=0
    for gpu in v3d adreno:618 adreno:630 adreno:660 mali:0x7212 mali:0x7093; do
        dev=${gpu%%:*} id=${gpu#*:} r=0
        result=$(
            case $gpu in adreno:*) export FD_GPU_ID=$id ;; mali:*) export PAN_GPU_ID=$id ;; esac
            . "$shared/env.sh" "$dir" "$dev"
            unset V3D_DEBUG IR3_SHADER_DEBUG BIFROST_MESA_DEBUG # no statistics wanted here
            "$tool" limits "$(profile_of "$dev")" 2>&1
        ) || r=$?
        # the drivers print other lines too: only the tool's
        echo "$result" | grep -E '^(renderer|limit|extension) |: [0-9]+ promise' || true
        case $r in
            0) ;;
            1) rc=1 ;;
            *) echo "device_shaders.sh: snell-shaderdb limits on $gpu failed (exit $r):" >&2
               echo "$result" | tail -n 5 >&2
               rc=1 ;;
        esac
    done
    [ $rc -eq 0 ] || echo "device_shaders.sh: a profile promises more than its driver (OVER above): lower it in src/core/profile.c" >&2
    exit $rc
fi

start=$(date +%s)
mkdir -p "$out"
# Each device's programs: the given folders, else a dump under its own profile (its limits and
# extensions choose the variants snell builds there), once per profile.
declare -A dumped
sources_of() { # DEVICE: its dump folders, one a line
    if [ ${#dumps[@]} -gt 0 ]; then printf '%s\n' "${dumps[@]}"; else
        printf '%s\n' "$out/dump/$(profile_of "$1")" "$out/dump/$(profile_of "$1")-units"; fi
}
for d in $devices; do
    p=$(profile_of "$d") t0=$(date +%s)
    if [ ${#dumps[@]} -gt 0 ] || [ -n "${dumped[$p]:-}" ]; then continue; fi
    dumped[$p]=1
    echo "== the GL label under the profile $p, dumping every program (about 3 min)" >&2
    rm -rf "$out/dump/$p" "$out/dump/$p-units" && mkdir -p "$out/dump/$p" "$out/dump/$p-units"
    SNELL_TEST_GLSL_DUMP=$out/dump/$p SNELL_DEVICE_PROFILE=$p \
        ctest --test-dir "$build" -L gl -j"$jobs" >"$out/dump/$p.log" 2>&1 ||
        echo "device_shaders.sh: GL tests failed under $p ($out/dump/$p.log); the programs they built stay in" >&2
    # test_units dumps into its own folder whatever SNELL_TEST_GLSL_DUMP says (glsl_validate's set)
    cp "$build"/tests/glsl/*.vert "$build"/tests/glsl/*.frag "$out/dump/$p-units/" 2>/dev/null ||
        echo "device_shaders.sh: no test_units dump in $build/tests/glsl" >&2
    echo "   $(( $(date +%s) - t0 )) s, $(cat "$out/dump/$p"*/*.frag 2>/dev/null | grep -c '^#version') programs" >&2
done

# One process per program and device, all in one queue: a crash or a runaway compile costs that
# program only, and a device's long compiles overlap the others' short ones.
# shellcheck disable=SC2317 # run by xargs
compile_one() { # "DEVICE DUMP/HASH"
    local device=${1%% *} path=${1#* } hash rc=0 TIMEFORMAT='@shaderdb cpu %U %S'
    local dev=${device%%-*} log
    hash=$(basename "$path")
    log=$out/logs/$device/$hash.log
    { time (
        [ "$device" = "$dev" ] || export FD_GPU_ID=${device#adreno-}
        . "$shared/env.sh" "$dir" "$dev"
        # freedreno's shaderdb line comes through KHR_debug (its disassembly would print every NIR
        # pass); no threaded context, whose own thread would compile out of the program's window
        unset IR3_SHADER_DEBUG
        export FD_MESA_DEBUG=shaderdb GALLIUM_THREAD=0
        ulimit -S -t "$cpu_limit" && ulimit -H -t $((cpu_limit + 10)) # SIGXCPU first: 152, a timeout
        ulimit -v $((mem_limit * 1024))
        "$tool" compile "$(dirname "$path")" "$hash"
    ) >"$log" 2>&1 || rc=$?; } 2>>"$log"
    case $rc in
        0|1) ;;
        152) echo "@shaderdb timeout $hash: over $cpu_limit CPU seconds" >>"$log" ;;
        *) echo "@shaderdb crash $hash: exit status $rc (past $mem_limit MB?)" >>"$log" ;;
    esac
}
export -f compile_one
export shared dir tool cpu_limit mem_limit out
report=() folders=() queue=()
for d in $devices; do
    mapfile -t from < <(sources_of "$d")
    folders+=("${from[@]}")
    mapfile -t list < <(find "${from[@]}" -maxdepth 1 -name '*.frag' | sed 's/\.frag$//' | awk -F/ '!seen[$NF]++')
    [ ${#list[@]} -gt 0 ] || { echo "device_shaders.sh: no <hash>.frag in ${from[*]}" >&2; exit 2; }
    echo "== $d: ${#list[@]} programs" >&2
    [ -n "$tables" ] || rm -rf "$out/logs/$d" && mkdir -p "$out/logs/$d"
    queue+=("${list[@]/#/$d }")
    report+=(--device "$d" "$out/logs/$d")
done
mapfile -t folders < <(printf '%s\n' "${folders[@]}" | sort -u)
t0=$(date +%s)
# shellcheck disable=SC2016 # $1 is the inner bash's
[ -n "$tables" ] || printf '%s\n' "${queue[@]}" | awk -F/ '{ print $NF "\t" $0 }' | sort | cut -f2- | xargs -d '\n' -P "$jobs" -I{} bash -c 'compile_one "$1"' _ {}
[ -n "$tables" ] || echo "   compiled in $(( $(date +%s) - t0 )) s" >&2
# What a device's compiler refused, again on the suite's own driver (llvmpipe here): a test's
# deliberate error, refused there too, is no failure.
mapfile -t refused < <(grep -l '^@shaderdb error' "$out"/logs/*/*.log 2>/dev/null | xargs -r -n1 basename |
    sed 's/\.log$//' | sort -u)
rm -rf "$out/logs/reference" && mkdir -p "$out/logs/reference"
for h in "${refused[@]}"; do
    for s in "${folders[@]}"; do
        [ -f "$s/$h.frag" ] || continue
        "$tool" compile "$s" "$h" >"$out/logs/reference/$h.log" 2>&1 || true
        break
    done
done

# Programs are named by their kernel: the build's own stripped copy of it, shaders_es/ now, or
# the C file of src/ or tests/ that holds it inline.
command="bash bench/device_shaders.sh"
for s in "${dumps[@]}"; do command+=" --dump ${s#"$root"/}"; done
[ "$devices" = "v3d adreno mali" ] || command+=" --devices '$devices'"
args=(--shaders "$root/shaders_es" --c-sources "$root/src" --c-sources "$root/tests" --out "$out" --command "$command")
[ ! -d "$build/generated/shaders_embedded.c.stripped" ] || args+=(--shaders "$build/generated/shaders_embedded.c.stripped")
[ -z "$strict" ] || args+=(--strict)
[ ${#refused[@]} -eq 0 ] || args+=(--reference "$out/logs/reference")
for s in "${folders[@]}"; do args+=(--dump "$s"); done
rc=0
python3 "$root/bench/device_shaders.py" "${args[@]}" "${report[@]}" || rc=$?
[ -z "$page" ] || cp "$out/SHADERS.md" "$page"
echo "device_shaders.sh: $(( $(date +%s) - start )) s; tables in $out" >&2
exit $rc
