#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks profile_tests.py's choice on traces made up for it: a test runs under a setting only
when its questions get answers there that no earlier run gave it."""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
PROFILES = """gles30-min 2048 2048 256 2048 4 16 224 256 15 4
rpi-v3d 4096 4096 2048 4096 4 16 224 256 16 4 GL_KHR_debug
mali-bifrost 8192 8192 2048 8192 4 16 224 256 32 8 GL_KHR_debug GL_OES_texture_float_linear
adreno-6xx 16384 16384 256 16384 4 16 224 256 15 4 GL_EXT_disjoint_timer_query GL_KHR_debug
"""
# A: extensions only; B: an array-layer check of 300 (fails at 256); C: asks nothing.
TRACES = {"A": "ext 1 GL_KHR_debug\next 1 GL_EXT_color_buffer_float\next 0 \n", "B": "check 2 300 2048\n"}


def choose(root, ran, want, removed=""):
    args = [sys.executable, os.path.join(HERE, "profile_tests.py"), root, os.path.join(root, "profiles.txt"),
            "--want", want, "--list", "--removed", removed] + [x for s in ran for x in ("--ran", s)]
    return set(subprocess.run(args, check=True, capture_output=True, text=True).stdout.split())


def main():
    with tempfile.TemporaryDirectory() as root:
        with open(os.path.join(root, "profiles.txt"), "w") as f:
            f.write(PROFILES)
        for setting in ("none", "gles30-min", "rpi-v3d"):
            os.makedirs(os.path.join(root, setting))
            for test, text in TRACES.items():
                with open(os.path.join(root, setting, test), "w") as f:
                    f.write(text)
        cases = [
            # debug on, float targets off: neither the driver's own answers nor gles30-min's
            ((["none", "gles30-min"], "rpi-v3d"), {"A"}),
            # the same answers as rpi-v3d's for A; B fits 2048 layers as rpi-v3d's did
            ((["none", "gles30-min", "rpi-v3d"], "mali-bifrost"), set()),
            # B fails at 256 as under gles30-min, but the message names another profile
            ((["none", "gles30-min", "rpi-v3d"], "adreno-6xx"), {"B"}),
            # Mesa hides KHR_debug: debug off, float targets on is new; B fits the driver's limit
            ((["none", "gles30-min"], "mesa-overrides", "GL_KHR_debug"), {"A"}),
            ((["none"], "none"), set()),
        ]
        failed = 0
        for args, expected in cases:
            got = choose(root, *args)
            if got != expected:
                print(f"FAIL {args}: chose {sorted(got)}, expected {sorted(expected)}")
                failed += 1
        if failed:
            sys.exit(1)
        print(f"ok: {len(cases)} choices")


if __name__ == "__main__":
    main()
