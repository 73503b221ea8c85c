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
#     --defaults     instead: the programs the tools' default frames build on each device, made
#                    there: snell-render's default scene and snell-bench's every method and auto at
#                    its defaults on the bunny and the sphere, run on the device's own driver with
#                    tests' glsl_dump_preload (build/tests/libsnell_glsl_dump.so); about 40 programs
#     --ci           for CI: --defaults (unless --dump), --strict, V3D fragment shaders held to the
#                    threads docs/devices.md promises; skips (exit 77) without the prebuilt drivers
#     --strict       fail on any spill and on a V3D program at 1 thread too
#     --out DIR      default build/device-shaders
#     --build DIR    the build holding tests/snell-shaderdb and the tests; default build
#     --devices L    default "v3d adreno mali"; also adreno-618 and adreno-660 (FD_GPU_ID 618, 660)
#     --page FILE    also copy OUT/SHADERS.md there (bench/devices/SHADERS.md)
#     --about TEXT   what the --dump folders hold, for the page
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
# 1 thread, or under --ci below its promised threads), each offender printed; 2 bad usage or no
# build; 77 skipped, the reason printed.
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
jobs=$(nproc) cpu_limit=60 mem_limit=4096 only_drivers="" profiles="" tables="" defaults="" about=""
usage() { sed -n '8,37p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
while [ $# -gt 0 ]; do
    case $1 in
        --dump) dumps+=("$(cd "${2:?--dump needs a folder}" && pwd)") || exit 2; shift ;;
        --ci) ci=1 strict=--strict ;;
        --defaults) defaults=1 ;;
        --strict) strict=--strict ;;
        --out) out=${2:?--out needs a folder}; shift ;;
        --build) build=${2:?--build needs a folder}; shift ;;
        --devices) devices=${2:?--devices needs a list}; shift ;;
        --page) page=${2:?--page needs a file}; shift ;;
        --about) about=${2:?--about needs a text}; shift ;;
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
[ -z "$tables" ] || [ ${#dumps[@]} -gt 0 ] || [ -n "$defaults" ] ||
    { echo "device_shaders.sh: --tables needs the --dump or --defaults of the earlier run" >&2; exit 2; }
[ -z "$ci" ] || [ ${#dumps[@]} -gt 0 ] || defaults=1
[ -z "$defaults" ] || [ ${#dumps[@]} -eq 0 ] || { echo "device_shaders.sh: --defaults or --dump, not both" >&2; exit 2; }
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
[ -d "$shared" ] || [ -z "$ci$profiles" ] || skip "no $shared: the GPUs' drivers over drm-shim (docs/devices.md)"
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
# Each device's programs: the given folders; with --defaults what the default frames built on
# its driver; else a dump under its own profile (its limits and extensions choose the variants
# snell builds there), once per profile.
declare -A dumped
sources_of() { # DEVICE: its dump folders, one a line
    if [ ${#dumps[@]} -gt 0 ]; then printf '%s\n' "${dumps[@]}";
    elif [ -n "$defaults" ]; then echo "$out/dump/defaults-$1"; else
        printf '%s\n' "$out/dump/$(profile_of "$1")" "$out/dump/$(profile_of "$1")-units"; fi
}
# The default frames, every program they link dumped (tests/glsl_dump_preload.c), twice: on the
# device's own driver over drm-shim (its limits, extensions and GL_RENDERER choose the variants,
# as on the device; it compiles them there too, cheaply, and draws nothing), and on the suite's
# driver under the device's profile and GL_RENDERER, where read-backs are real (the variants that
# the data choose: layered's layers, from its bake; over drm-shim they read garbage).
frames() { # FOLDER: snell-render's default scene, snell-bench's every method on the bunny and sphere
    # (and exact's FULL terms and its dispersion on the bunny)
    local specs=() m
    for m in single layered cubemap wyman oliveira peel exact auto; do specs+=(-b "$m:scene=bunny,sphere:size=64x64"); done
    # exact with the FULL model's terms (inner Fresnel alone and all three): candidates for its
    # default (issue 50); and with dispersion (three traces): held to no spills too
    specs+=(-b exact:scene=bunny:size=64x64:inner_fresnel=on
        -b exact:scene=bunny:size=64x64:fresnel=exact:inner_fresnel=on:reentry=on
        -b exact:scene=bunny:size=64x64:dispersion=0.31)
    export LD_PRELOAD="${LD_PRELOAD:+$LD_PRELOAD }$build/tests/libsnell_glsl_dump.so" SNELL_GLSL_DUMP=$1
    timeout 300 "$build/ports/cli/snell-render" -o "$1/render.png" || return $?
    timeout 300 "$build/ports/cli/snell-bench" -q --cache "$out/dump/reference-cache" "${specs[@]}" \
        --frames 1 --warmup 0 -o "$1/bench"
}
on_device() { # DEVICE COMMAND...: the command under the device's driver, without statistics
    local device=$1 dev=${1%%-*}
    shift
    (
        [ "$device" = "$dev" ] || export FD_GPU_ID=${device#adreno-}
        . "$shared/env.sh" "$dir" "$dev"
        unset V3D_DEBUG IR3_SHADER_DEBUG BIFROST_MESA_DEBUG SNELL_DEVICE_PROFILE # the driver's own answers
        "$@"
    )
}
dump_defaults() { # DEVICE FOLDER
    local device=$1 folder=$2 rc=0 renderer profile
    local bunny=/usr/share/glmark2/models/bunny.obj
    profile=$(profile_of "$device")
    [ -f "$build/tests/libsnell_glsl_dump.so" ] ||
        { echo "device_shaders.sh: no $build/tests/libsnell_glsl_dump.so: cmake --build $build" >&2; return 2; }
    [ -f "$bunny" ] || { echo "device_shaders.sh: no $bunny (Debian's glmark2-data): the bunny scene" >&2; return 2; }
    renderer=$(on_device "$device" "$tool" limits 2>/dev/null | sed -n 's/^renderer //p')
    [ -n "$renderer" ] || { echo "device_shaders.sh: $device: its driver gives no GL_RENDERER" >&2; return 2; }
    rm -rf "$folder" && mkdir -p "$folder" "$out/dump/reference-cache"
    {
        echo "== on the device's driver, $renderer" && on_device "$device" frames "$folder" &&
            echo "== on the suite's driver as $renderer, under the profile $profile" &&
            (SNELL_GLSL_DUMP_RENDERER=$renderer SNELL_DEVICE_PROFILE=$profile frames "$folder")
    } >"$folder.log" 2>&1 || rc=$?
    rm -f "$folder"/render.png "$folder"/bench.*
    if [ $rc -ne 0 ]; then
        echo "device_shaders.sh: $device: the default frames failed (exit $rc$([ $rc -ne 124 ] || echo ', past 300 s')); $folder.log:" >&2
        tail -n 5 "$folder.log" >&2
    fi
    return $rc
}
for d in $devices; do
    p=$(profile_of "$d") t0=$(date +%s)
    if [ -n "$defaults" ] && [ -z "$tables" ]; then
        echo "== $d: the default frames on its driver, dumping their programs" >&2
        dump_defaults "$d" "$out/dump/defaults-$d" || exit 1
        echo "   $(( $(date +%s) - t0 )) s, $(ls "$out/dump/defaults-$d" | grep -c '\.frag$') programs" >&2
        continue
    fi
    if [ ${#dumps[@]} -gt 0 ] || [ -n "$defaults" ] || [ -n "${dumped[$p]:-}" ]; then continue; fi
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
[ -z "$defaults" ] || command+=" --defaults"
[ "$devices" = "v3d adreno mali" ] || command+=" --devices '$devices'"
args=(--shaders "$root/shaders_es" --c-sources "$root/src" --c-sources "$root/tests" --out "$out" --command "$command")
[ ! -d "$build/generated/shaders_embedded.c.stripped" ] || args+=(--shaders "$build/generated/shaders_embedded.c.stripped")
[ -z "$strict" ] || args+=(--strict)
[ -z "$ci" ] || args+=(--promises "$root/docs/devices.md")
if [ -n "$defaults" ]; then
    args+=(--what "the programs the default frames build on each device: snell-render's default scene and \
snell-bench's every method and auto at its defaults on the bunny and the sphere, on the device's driver and on \
llvmpipe under its profile")
elif [ -n "$about" ]; then
    args+=(--what "$about")
elif [ ${#dumps[@]} -eq 0 ]; then
    args+=(--what "every program the GL tests and test_units build under each device's profile")
fi
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null) && args+=(--commit "$commit")
[ ${#refused[@]} -eq 0 ] || args+=(--reference "$out/logs/reference")
for s in "${folders[@]}"; do args+=(--dump "$s"); done
rc=0
python3 "$root/bench/device_shaders.py" "${args[@]}" "${report[@]}" || rc=$?
[ -z "$page" ] || cp "$out/SHADERS.md" "$page"
echo "device_shaders.sh: $(( $(date +%s) - start )) s; tables in $out" >&2
exit $rc
