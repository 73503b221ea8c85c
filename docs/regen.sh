#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# docs/regen.sh — renders the docs' images that come from a snell-render
# command (the command is each image's caption in README.md or docs/*.md, or
# the images are linked from docs/integrating.md), into docs/.
# The other images come from tests (their captions name the test; the test
# writes them under its build folder's test output) and the default image,
# docs/snell.png, is checked byte for byte by the test suite (readme and
# cli tests). Usage: docs/regen.sh [BUILD_DIR] (default build); OUT=dir to
# write somewhere else (to compare before replacing). About 40 s on 2 CPUs.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
render="$build/ports/cli/snell-render"
out=${OUT:-docs}
[ -x "$render" ] || { echo "docs/regen.sh: no $render (build first: bash scripts/quickstart.sh)" >&2; exit 1; }
mkdir -p "$out"
run() { # NAME ARGS...: one image
    local name=$1
    shift
    "$render" "$@" -o "$out/$name" >/dev/null
    echo "docs/regen.sh: $out/$name"
}
run snell.png
run caustics.png --light dir:0.45,-1,0.3 --floor -1,4 --floor-map 512 --photons 512 --mesh sphere --place -0.5,0,0,1 \
    --mesh sphere --place 1.4,-0.45,0.7,0.55 --attenuation 0.9,0.35,0.15,0.6 --opaque cube --place -2.6,-0.7,-0.9,0.3 \
    --color 0.8,0.3,0.3 --camera 15,38,7.5 --size 640x480
run water_ripple.png --water --camera 30,60,3.2 --drop 0.2,0.1,0.12,-0.05 --drop -0.5,-0.4,0.1,-0.04 --frames 40
run water_grazing.png --water --camera 20,14,2.6 --drop 0.2,0.1,0.12,-0.05 --frames 30
run water_objects.png --water --camera 25,28,3.0 --object sphere:0.3,-0.05,0.2,0.3 --object cube:-0.45,-0.35,-0.3,0.35 \
    --object torus:-0.35,-0.3,0.5,0.35 --drop 0.6,-0.6,0.1,-0.04 --frames 40
run water_glass.png --water --grid 256 --camera 25,28,3.0 --glass sphere:0.25,-0.15,0.15,0.35 \
    --glass torus:-0.45,-0.45,-0.3,0.3 --object cube:-0.45,-0.6,0.45,0.2 --drop 0.6,-0.6,0.1,-0.04 \
    --drop -0.2,0.6,0.08,-0.03 --frames 40
run water_caustics.png --water --drop 0.3,0.2,0.15,-0.05 --drop -0.4,-0.3,0.1,-0.04 --frames 40 \
    --light dir:0.3,-1,0.2,1.2 --glass sphere:-0.45,-0.1,0.45,0.22
run panels.png --panels examples/panels.txt --size 640x360 --reference # and panels_reference.png beside it
run dispersion.png --dispersion 1 --mesh prism --place -0.9,0,0 --mesh sphere --place 1.1,0,0,0.8 --camera -20,8,4.5 \
    --size 512x320
