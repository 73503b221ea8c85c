#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""check_layers_symbols.py OBJDIR: the layer rule of docs/ARCHITECTURE.md
("Layers") on the library's objects, not on #include lines: every symbol an
object of src/<folder> leaves undefined must be defined in its own folder or
one below it (core < mesh < frame < methods, ref, water, lm2d < render; ref
may use water). A call up through a header a lower folder declares passes an
include check and fails here. OBJDIR: the build's CMakeFiles/snell_objects.dir."""
import os
import subprocess
import sys

RANK = {"core": 0, "mesh": 1, "frame": 2, "methods": 3, "ref": 3, "water": 3, "lm2d": 3,
        "render": 4}
SIDEWAYS = {("ref", "water")}


def symbols(path):
    out = subprocess.run(["nm", "-P", path], capture_output=True, text=True, check=True).stdout
    defined, undefined = set(), set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) < 2:
            continue
        name, kind = parts[0], parts[1]
        if kind == "U":
            undefined.add(name)
        elif kind not in "wvN":  # weak references and debug symbols define nothing a caller relies on
            defined.add(name)
    return defined, undefined


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    objs = []
    for root, _, files in os.walk(sys.argv[1]):
        for f in files:
            if f.endswith(".o"):
                path = os.path.join(root, f)
                rel = os.path.relpath(path, sys.argv[1]).split(os.sep)
                folder = rel[1] if rel[0] == "src" else "core"  # generated/: core's embedded shaders
                if folder in RANK:
                    objs.append((folder, os.path.join(*rel)[:-2], path))
    if not objs:
        sys.exit(f"check_layers_symbols: no objects under {sys.argv[1]}")
    owner, needs = {}, []
    for folder, name, path in objs:
        defined, undefined = symbols(path)
        for s in defined:
            owner[s] = (folder, name)
        needs.append((folder, name, undefined))
    bad = []
    for folder, name, undefined in needs:
        for s in sorted(undefined):
            if s not in owner:
                continue  # libc, GL, EGL, the C++ runtime
            to, where = owner[s]
            if to == folder or (folder, to) in SIDEWAYS:
                continue
            if RANK[to] >= RANK[folder]:
                bad.append(f"{name} uses {s} of {where} ({folder} may use only folders below it)")
    if bad:
        print("symbols used up or sideways:\n  " + "\n  ".join(bad))
        return 1
    print(f"layers: every symbol {len(objs)} objects use is their folder's or below")
    return 0


if __name__ == "__main__":
    sys.exit(main())
