#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""mesh_edges.py MESH.obj [...] — edge counts of an OBJ on position-welded vertices.

An independent cross-check of snell_mesh_analyze's topology counts
(src/mesh/mesh_analyze.c), written separately from it: Python 3 standard
library only, a different grid (cells as wide as the tolerance, neighbours
+-1) and union-find over vertices (not cells). Same definitions:
  - positions are float32 (as the library stores them); the tolerance is
    1e-5 of the diagonal of the bounding box of the vertices the faces use;
  - vertices weld when a chain of vertices, each within the tolerance of the
    next, joins them;
  - polygons are split into a fan from their first corner (as the loader does);
  - triangles with two welded corners equal are left out;
  - an edge with 1 triangle is a boundary edge, with 3 or more non-manifold,
    with 2 running it the same way flipped.
Prints one line per file:
  NAME welded W boundary B nonmanifold N flipped F degenerate D closed C euler X
(euler = W - E + T over the triangles kept, with E the distinct edges), and
with --why some facts behind the counts (duplicate triangles, the nearest
other vertex of boundary vertices in tolerances).
"""
import math
import struct
import sys

REL_TOL = 1e-5


def f32(x):
    return struct.unpack("<f", struct.pack("<f", float(x)))[0]


def load_obj(path):
    verts, tris = [], []
    with open(path, "r", encoding="latin-1") as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append(tuple(f32(c) for c in parts[1:4]))
            elif parts[0] == "f":
                idx = []
                for c in parts[1:]:
                    i = int(c.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                for k in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[k], idx[k + 1]))
    return verts, tris


class UnionFind:
    def __init__(self, n):
        self.p = list(range(n))

    def find(self, a):
        while self.p[a] != a:
            self.p[a] = self.p[self.p[a]]
            a = self.p[a]
        return a

    def union(self, a, b):
        a, b = self.find(a), self.find(b)
        if a != b:
            self.p[max(a, b)] = min(a, b)


def weld(verts, used):
    lo = [min(verts[i][k] for i in used) for k in range(3)]
    hi = [max(verts[i][k] for i in used) for k in range(3)]
    tol = REL_TOL * math.sqrt(sum((hi[k] - lo[k]) ** 2 for k in range(3)))
    uf = UnionFind(len(verts))
    if tol == 0.0:
        for i in used:
            uf.union(used[0], i)
        return uf, tol
    grid = {}
    for i in used:
        key = tuple(int(math.floor((verts[i][k] - lo[k]) / tol)) for k in range(3))
        grid.setdefault(key, []).append(i)
    for (x, y, z), pts in grid.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    other = grid.get((x + dx, y + dy, z + dz))
                    if not other:
                        continue
                    for i in pts:
                        for j in other:
                            if j > i and sum((verts[i][k] - verts[j][k]) ** 2 for k in range(3)) <= tol * tol:
                                uf.union(i, j)
    return uf, tol


def analyse(path, why):
    verts, tris = load_obj(path)
    used = sorted({i for t in tris for i in t})
    uf, tol = weld(verts, used)
    welded = len({uf.find(i) for i in used})
    edges = {}
    degenerate = 0
    kept = []
    for t in tris:
        w = [uf.find(i) for i in t]
        if w[0] == w[1] or w[1] == w[2] or w[2] == w[0]:
            degenerate += 1
            continue
        kept.append(tuple(w))
        for j in range(3):
            a, b = w[j], w[(j + 1) % 3]
            edges.setdefault((min(a, b), max(a, b)), []).append(a < b)
    boundary = sum(1 for d in edges.values() if len(d) == 1)
    nonmanifold = sum(1 for d in edges.values() if len(d) >= 3)
    flipped = sum(1 for d in edges.values() if len(d) == 2 and d[0] == d[1])
    closed = int(bool(edges) and boundary == 0 and nonmanifold == 0 and flipped == 0)
    euler = welded - len(edges) + len(kept)
    print("%s welded %d boundary %d nonmanifold %d flipped %d degenerate %d closed %d euler %d"
          % (path.rsplit("/", 1)[-1], welded, boundary, nonmanifold, flipped, degenerate, closed, euler))
    if why:
        same = {}
        for w in kept:
            same.setdefault(tuple(sorted(w)), []).append(w)
        dup = [v for v in same.values() if len(v) > 1]
        print("  triangles on the same 3 welded vertices: %d groups (%d triangles)"
              % (len(dup), sum(len(v) for v in dup)))
        uses = {}
        for d in edges.values():
            key = "%d" % len(d) if len(d) != 2 else ("2 same way" if d[0] == d[1] else "2")
            uses[key] = uses.get(key, 0) + 1
        print("  edges by triangles using them: " + ", ".join("%s: %d" % kv for kv in sorted(uses.items())))
        bverts = sorted({v for e, d in edges.items() if len(d) == 1 for v in e})
        if bverts and tol > 0.0:
            near = []
            for v in bverts:
                best = min(math.dist(verts[v], verts[u]) for u in used if uf.find(u) != v)
                near.append(best / tol)
            near.sort()
            print("  boundary vertices %d; nearest other vertex (in tolerances): min %.3g median %.3g"
                  % (len(bverts), near[0], near[len(near) // 2]))
        comp = UnionFind(len(verts))
        for w in kept:
            comp.union(w[0], w[1])
            comp.union(w[1], w[2])
        print("  connected pieces: %d" % len({comp.find(w[0]) for w in kept}))


def main():
    args = [a for a in sys.argv[1:] if a != "--why"]
    if not args:
        sys.stderr.write("usage: mesh_edges.py [--why] MESH.obj [...]\n")
        return 2
    for path in args:
        analyse(path, "--why" in sys.argv[1:])
    return 0


if __name__ == "__main__":
    sys.exit(main())
