#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""glsl_check.py DIR [PROFILES]: every program's final sources that a test dumped into
DIR (tests/test_util.c, SNELL_TEST_GLSL_DUMP; test_units always does), as
pairs <hash>.vert + <hash>.frag, validated and linked as GLSL ES 3.00 by
glslangValidator (Khronos' reference front end, stricter than Mesa's), then
counted against every device profile of DIR/profiles.txt or PROFILES (test_units
writes it from src/core/profile.c):
varying vectors, fragment outputs (draw buffers), vertex uniform vectors and
samplers per stage, read from the preprocessed text (glslangValidator -E).
Declarations are counted, not only what is used, and without packing: a
program that fits here fits the device. Exit 77 (ctest: skipped) without
glslangValidator (Debian: glslang-tools)."""
import glob
import os
import re
import shutil
import subprocess
import sys

ROWS = {"mat2": 2, "mat3": 3, "mat4": 4, "mat2x2": 2, "mat2x3": 2, "mat2x4": 2, "mat3x2": 3, "mat3x3": 3,
        "mat3x4": 3, "mat4x2": 4, "mat4x3": 4, "mat4x4": 4}
LIMITS = ["texture_size", "cube_size", "array_layers", "renderbuffer_size", "samples", "fragment_units",
          "fragment_vectors", "vertex_vectors", "varyings", "draw_buffers"]


def top_level(text):
    """The declarations outside every block ({...} of functions and structs)."""
    out, depth, cur = [], 0, ""
    text = "\n".join(l for l in text.splitlines() if not l.lstrip().startswith("#"))
    for ch in text:
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
            cur = ""
            continue
        if depth:
            continue
        if ch == ";":
            out.append(" ".join(cur.split()))
            cur = ""
        else:
            cur += ch
    return out


QUALIFIERS = {"flat", "smooth", "centroid", "invariant", "highp", "mediump", "lowp", "const"}


def declared(decls, storage):
    """(vectors, samplers) of the top-level declarations with that storage."""
    vectors = samplers = 0
    for d in decls:
        words = re.sub(r"layout\s*\([^)]*\)", "", d).replace(",", " , ").split()
        if storage not in words:
            continue
        words = [w for w in words if w not in QUALIFIERS and w != storage]
        typ, names = words[0], " ".join(words[1:]).split(",")
        for n in names:
            if not n.strip():
                continue
            arr = re.search(r"\[\s*(\d+)\s*\]", n + typ)
            count = int(arr.group(1)) if arr else 1
            if "sampler" in typ:
                samplers += count
            else:
                vectors += ROWS.get(typ.split("[")[0], 1) * count
    return vectors, samplers


def preprocess(tool, path):
    r = subprocess.run([tool, "-E", path], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{path}: glslangValidator -E failed:\n{r.stdout}{r.stderr}")
    return r.stdout


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: glsl_check.py DIR [PROFILES.txt]")
    folder = sys.argv[1]
    profiles_txt = sys.argv[2] if len(sys.argv) == 3 else os.path.join(folder, "profiles.txt")
    tool = shutil.which("glslangValidator")
    if not tool:
        print("skipped: glslangValidator not found (Debian package glslang-tools)")
        sys.exit(77)
    pairs = sorted(p[:-5] for p in glob.glob(os.path.join(folder, "*.vert")) if os.path.exists(p[:-5] + ".frag"))
    if not pairs:
        sys.exit(f"no dumped programs in {folder}: run test_units (or a suite with SNELL_TEST_GLSL_DUMP) first")
    profiles = {}
    with open(profiles_txt) as f:
        for line in f:
            w = line.split()
            profiles[w[0]] = dict(zip(LIMITS, map(int, w[1:])))
    failed, most = 0, {}
    for base in pairs:
        name = os.path.basename(base)
        r = subprocess.run([tool, "-l", base + ".vert", base + ".frag"], capture_output=True, text=True)
        if r.returncode != 0:
            failed += 1
            print(f"FAIL {name}: glslangValidator rejects it as GLSL ES 3.00:\n{r.stdout}{r.stderr}")
            continue
        vs, fs = top_level(preprocess(tool, base + ".vert")), top_level(preprocess(tool, base + ".frag"))
        count = {"varyings": declared(vs, "out")[0], "draw_buffers": declared(fs, "out")[0],
                 "vertex_vectors": declared(vs, "uniform")[0], "fragment_units": declared(fs, "uniform")[1]}
        for k, v in count.items():
            if v > most.get(k, (-1, ""))[0]:
                most[k] = (v, name)
        for pname, lim in profiles.items():
            for k, v in count.items():
                if v > lim[k]:
                    failed += 1
                    print(f"FAIL {name}: {k} {v} over {pname}'s {lim[k]}")
    print(f"{len(pairs)} programs valid GLSL ES 3.00 (glslangValidator -l): {len(pairs) - failed} fit every profile")
    for k, (v, name) in sorted(most.items()):
        least = min(p[k] for p in profiles.values())
        print(f"  most {k}: {v} ({name}); the lowest profile has {least}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
