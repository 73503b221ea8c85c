#!/bin/sh
# SPDX-License-Identifier: MIT
# bench/device_cost.sh — regenerates bench/devices/COSTS.md, the per-device cost model (issue 46 item 2).
#
#   bench/device_cost.sh [BUILD_DIR] [DEVICES_DIR]     (defaults: build-h4, /tmp/dev)
#
# BUILD_DIR: a configured and built tree (snell-render's objects and libsnell.a); DEVICES_DIR: the unpacked
# ../shared/devices/mesa-22.3.6-devices.tar.xz (it is unpacked there when missing). It
#  1. links bench/device_cost_trace.c into a copy of snell-render (BUILD_DIR/snell-render-trace, -Wl,--wrap):
#     a GL trace of every link and draw, nothing in the library changed;
#  2. per device (v3d, freedreno 630, panfrost G52), scene (sphere, bunny, torus) and method (the seven and
#     auto): a frame on the device's driver over drm-shim keeping its disassembly (compiles only), and the
#     same frame on llvmpipe at 1280x720 and 1920x1080 taking that device's decisions (its profile,
#     SNELL_DEVICE_PROFILE, and its GL_RENDERER, SNELL_COST_RENDERER) counting each draw's shaded
#     fragments, and at 720p each source loop's body executions (SNELL_COST_COUNT=1; 2 at 1080p);
#  3. the glmark2 anchor: glmark2's light-refract shaders compiled on each driver as glmark2 does;
#  4. runs bench/device_cost.py on those logs, which writes bench/devices/COSTS.md.
# Logs stay in BUILD_DIR/device_cost/ (KEEP=1 reuses those there; SKIP="exact-mali bunny-peel-v3d ..." leaves
# configurations out; DEVS, SCENES and METHODS narrow the lists, e.g. METHODS="peel exact auto"). About 20
# minutes on a shared 2-core box, most of it llvmpipe counting the loops of exact and peel at 720p.
set -eu
cd "$(dirname "$0")/.."
B=${1:-build-h4}
DEV=${2:-/tmp/dev}
OUT=$B/device_cost
SHARED=../shared/devices
[ -d "$SHARED" ] || SHARED=/work/shared/devices
if [ ! -d "$DEV/inst" ]; then
    mkdir -p "$DEV" && tar -C "$DEV" -xJf "$SHARED/mesa-22.3.6-devices.tar.xz"
fi
cmake --build "$B" --target snell-render -j2 >/dev/null
W="-Wl,--wrap=glShaderSource,--wrap=glAttachShader,--wrap=glLinkProgram,--wrap=glDrawArrays"
W="$W,--wrap=glDrawElements,--wrap=glGetString,--wrap=snell_render,--wrap=glBindFramebuffer"
W="$W,--wrap=glFramebufferTexture2D,--wrap=glFramebufferTextureLayer,--wrap=glFramebufferRenderbuffer"
W="$W,--wrap=glDrawBuffers,--wrap=glClear,--wrap=glClearBufferfv,--wrap=glBlitFramebuffer"
cc -O2 -std=c99 -Wall -Wextra -c bench/device_cost_trace.c -o "$B/device_cost_trace.o"
c++ -O2 "$B"/ports/cli/CMakeFiles/snell-render.dir/*.o "$B/device_cost_trace.o" $W -o "$B/snell-render-trace" \
    "$B/ports/cli/libsnell_cli_common.a" "$B/libsnell.a" -lEGL -lGLESv2 -ltinygltf -lmeshoptimizer -lstdc++ -lm
cc -O2 -std=c99 -Wall -Wextra bench/device_cost_glmark2.c -o "$B/device_cost_glmark2" -lEGL -lGLESv2 -lm
R=$(pwd)/$B/snell-render-trace
mkdir -p "$OUT"
{ "$R" --version 2>&1 | head -1; git rev-parse --short HEAD 2>/dev/null || echo "${SNELL_COST_COMMIT:-}"; } |
    tr '\n' ' ' >"$OUT/version.txt"
BUNNY=/usr/share/glmark2/models/bunny.obj
for dev in ${DEVS:-v3d adreno mali}; do
    case $dev in
        v3d) profile=rpi-v3d renderer="V3D 4.2" ;;
        adreno) profile=adreno-6xx renderer="FD630" ;;
        mali) profile=mali-bifrost renderer="Mali-G52 (Panfrost)" ;;
    esac
    for scene in ${SCENES:-sphere bunny torus}; do
        case $scene in sphere) mesh="" ;; bunny) mesh="--mesh $BUNNY" ;; *) mesh="--mesh $scene" ;; esac
        for method in ${METHODS:-single layered cubemap wyman oliveira peel exact auto}; do
            tag=$scene-$method-$dev
            case " ${SKIP:-} " in *" $tag "*|*" $method-$dev "*) continue ;; esac
            if [ "${KEEP:-0}" != 1 ] || [ ! -s "$OUT/$tag.log" ]; then
                # shellcheck disable=SC1090,SC2086
                ( set -- "$DEV" $dev; . "$SHARED/env.sh"
                  case $dev in v3d) export V3D_DEBUG=shaderdb,qpu ;; mali) export BIFROST_MESA_DEBUG=shaderdb,shaders ;; esac
                  "$R" $mesh --method $method --size 1280x720 --frames 1 -o "$OUT/x.png" ) >"$OUT/$tag.log" 2>&1 || true
            fi
            for size in 1280x720 1920x1080; do
                [ "${KEEP:-0}" = 1 ] && [ -s "$OUT/$tag-$size.llvmpipe.log" ] && continue
                rm -rf "$OUT/$tag-$size.src" && mkdir -p "$OUT/$tag-$size.src"
                # shellcheck disable=SC2086
                # loop bodies counted at 720p on every device (its programs may be other variants: Mali's
                # exact walks without a stack); at 1080p the fragments alone, trips taken from 720p's
                count=2
                [ "$size" = 1280x720 ] && count=1
                SNELL_DEVICE_PROFILE=$profile SNELL_COST_RENDERER=$renderer SNELL_COST_COUNT=$count \
                    SNELL_COST_DUMP="$OUT/$tag-$size.src" "$R" $mesh --method $method --size $size \
                    --frames 2 --stats -o "$OUT/$tag-$size.png" >"$OUT/$tag-$size.llvmpipe.log" 2>&1 || true
            done
        done
    done
    # shellcheck disable=SC1090
    ( set -- "$DEV" $dev; . "$SHARED/env.sh"
      case $dev in v3d) export V3D_DEBUG=shaderdb,qpu ;; mali) export BIFROST_MESA_DEBUG=shaderdb,shaders ;; esac
      "$B/device_cost_glmark2" ) >"$OUT/glmark2-$dev.log" 2>&1 || true
done
rm -f "$OUT/x.png"
python3 bench/device_cost.py "$OUT" bench/devices/COSTS.md
