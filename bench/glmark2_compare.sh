#!/bin/sh
# SPDX-License-Identifier: MIT
# glmark2_compare.sh — frame time of snell's single-surface glass vs glmark2-es2's
# "refract" scene on the same bunny (/usr/share/glmark2/models/bunny.obj) at the
# same sizes, runs alternated (glmark2, snell, glmark2, snell, ...) so that load
# from other processes hits both alike. Prints a table and the ratio
# snell / glmark2 of the median frame times.
#
# Needs: glmark2-es2-x11 glmark2-data xvfb (Debian), a built snell-bench.
# usage: bench/glmark2_compare.sh [SNELL_BENCH] [REPEATS]
#   SNELL_BENCH  path of snell-bench (default build/ports/cli/snell-bench)
#   REPEATS      alternations per size (default 3)
# Environment: SIZES (default "256x256 512x512 800x600"), DURATION (glmark2
# seconds per run, default 5), FRAMES (snell frames per run, default 30),
# METHOD (snell-bench method spec, default single; e.g. cubemap).
#
# Caveats, stated in the output too: glmark2's refract is a different
# algorithm (two passes: back-face depth/normal texture, then the front
# faces; its IOR handling and view vector are wrong, see BENCHMARKS.md) and
# it rotates the bunny; glmark2 --off-screen renders to an FBO and reports
# FrameTime = 1000/FPS over the run; snell-bench reports the median of
# frames each ended by glFinish. Both are llvmpipe here, so the ratio is a
# CPU-rasteriser ratio, not a GPU one.
set -eu

SNELL_BENCH=${1:-build/ports/cli/snell-bench}
REPEATS=${2:-3}
SIZES=${SIZES:-"256x256 512x512 800x600"}
DURATION=${DURATION:-5}
FRAMES=${FRAMES:-30}
METHOD=${METHOD:-single}
BUNNY=/usr/share/glmark2/models/bunny.obj

for tool in glmark2-es2 xvfb-run; do
    command -v "$tool" >/dev/null 2>&1 || { echo "missing $tool: apt-get install glmark2-es2-x11 glmark2-data xvfb" >&2; exit 2; }
done
[ -r "$BUNNY" ] || { echo "missing $BUNNY: apt-get install glmark2-data" >&2; exit 2; }
[ -x "$SNELL_BENCH" ] || { echo "snell-bench not found at $SNELL_BENCH (build it, or pass its path)" >&2; exit 2; }

TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT INT TERM

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) print "nan"; else if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "load before: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) CPU(s)"
printf '%-9s %-4s %12s %12s\n' size run glmark2_ms snell_ms
for size in $SIZES; do
    w=${size%x*}
    h=${size#*x}
    : >"$TMP/g_$size"
    : >"$TMP/s_$size"
    i=1
    while [ "$i" -le "$REPEATS" ]; do
        # glmark2: "[refract] <default>: FPS: 21 FrameTime: 47.619 ms"
        g=$(xvfb-run -a -s "-screen 0 1024x768x24" glmark2-es2 --off-screen -s "${w}x${h}" \
                -b "refract:duration=$DURATION" 2>&1 | sed -n 's/.*FrameTime: *\([0-9.]*\) ms.*/\1/p' | head -n 1)
        [ -n "$g" ] || { echo "glmark2-es2 gave no FrameTime (run it by hand to see why)" >&2; exit 1; }
        # snell: same bunny, METHOD, median of FRAMES frames
        "$SNELL_BENCH" -q -b "$METHOD:scene=$BUNNY:size=${w}x${h}" --frames "$FRAMES" --warmup 3 \
            --cache "$TMP/cache" -o "$TMP/snell_$size" >/dev/null
        s=$(awk -F, 'NR == 2 { print $8 }' "$TMP/snell_$size.csv")
        [ -n "$s" ] || { echo "snell-bench gave no time" >&2; exit 1; }
        echo "$g" >>"$TMP/g_$size"
        echo "$s" >>"$TMP/s_$size"
        printf '%-9s %-4s %12.3f %12.3f\n' "$size" "$i" "$g" "$s"
        i=$((i + 1))
    done
done
echo
printf '%-9s %14s %14s %16s\n' size glmark2_median snell_median ratio_snell/glmark2
for size in $SIZES; do
    g=$(median <"$TMP/g_$size")
    s=$(median <"$TMP/s_$size")
    printf '%-9s %14.3f %14.3f %16.3f\n' "$size" "$g" "$s" "$(echo "$s $g" | awk '{ print $1 / $2 }')"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "GL: $(xvfb-run -a glmark2-es2 --off-screen -s 64x64 -b refract:duration=0.1 2>&1 | sed -n 's/.*GL_RENDERER: *//p' | head -n 1)"
