#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""3ds_to_obj.py IN.3ds OUT.obj — the triangle meshes of an Autodesk 3DS file as OBJ.

Reads the chunk tree (each chunk: uint16 id, uint32 length including its
6-byte header, little-endian):
  0x4D4D main > 0x3D3D editor > 0x4000 object (NUL-terminated name, then
  chunks) > 0x4100 triangle mesh > 0x4110 vertices (uint16 n, n x 3 float32)
                                 > 0x4120 faces (uint16 n, n x (3 uint16 + uint16 flags))
Every other chunk is skipped by its length. Each object becomes an OBJ group
("o name"); its vertices are written as stored (3DS object files hold them in
world coordinates, Z up; the 0x4160 local frame is not applied), with the
shortest decimal that reads back as the same float32, so the OBJ has exactly
the 3DS geometry. Vertices are not welded and faces not reoriented: what the
analysis sees is what the file holds. Python 3 standard library only.
"""
import struct
import sys


def f32_str(x):
    """Shortest %g form that parses back to the same float32 value."""
    want = struct.pack("<f", x)
    for digits in range(6, 10):
        s = "%.*g" % (digits, x)
        if struct.pack("<f", float(s)) == want:
            return s
    return repr(x)


def chunks(data, start, end):
    """Yields (id, body_start, chunk_end) for the chunks in data[start:end]."""
    p = start
    while p + 6 <= end:
        cid, length = struct.unpack_from("<HI", data, p)
        if length < 6 or p + length > end:
            raise ValueError("chunk 0x%04x at %d: bad length %d" % (cid, p, length))
        yield cid, p + 6, p + length
        p += length


def read_mesh(data, start, end):
    verts, faces = [], []
    for cid, body, cend in chunks(data, start, end):
        if cid == 0x4110:
            (n,) = struct.unpack_from("<H", data, body)
            verts = [struct.unpack_from("<3f", data, body + 2 + 12 * i) for i in range(n)]
        elif cid == 0x4120:
            (n,) = struct.unpack_from("<H", data, body)
            faces = [struct.unpack_from("<3H", data, body + 2 + 8 * i) for i in range(n)]
    return verts, faces


def read_objects(data):
    objects = []
    for cid, body, cend in chunks(data, 0, len(data)):
        if cid != 0x4D4D:
            continue
        for cid2, body2, cend2 in chunks(data, body, cend):
            if cid2 != 0x3D3D:
                continue
            for cid3, body3, cend3 in chunks(data, body2, cend2):
                if cid3 != 0x4000:
                    continue
                nul = data.index(b"\0", body3, cend3)
                name = data[body3:nul].decode("latin-1") or "object%d" % len(objects)
                for cid4, body4, cend4 in chunks(data, nul + 1, cend3):
                    if cid4 == 0x4100:
                        verts, faces = read_mesh(data, body4, cend4)
                        for f in faces:
                            if max(f) >= len(verts):
                                raise ValueError("%s: face %s references vertex >= %d" % (name, f, len(verts)))
                        objects.append((name, verts, faces))
    return objects


def main():
    if len(sys.argv) != 3:
        sys.stderr.write("usage: 3ds_to_obj.py IN.3ds OUT.obj\n")
        return 2
    with open(sys.argv[1], "rb") as f:
        data = f.read()
    objects = read_objects(data)
    if not objects:
        sys.stderr.write("3ds_to_obj: no triangle mesh in %s\n" % sys.argv[1])
        return 1
    nv = sum(len(o[1]) for o in objects)
    nf = sum(len(o[2]) for o in objects)
    base = 1
    with open(sys.argv[2], "w", newline="\n") as out:
        out.write("# converted from %s by tests/scripts/3ds_to_obj.py: %d objects, %d vertices, %d triangles\n"
                  % (sys.argv[1].rsplit("/", 1)[-1], len(objects), nv, nf))
        for name, verts, faces in objects:
            out.write("o %s\n" % name.replace(" ", "_"))
            for v in verts:
                out.write("v %s %s %s\n" % tuple(f32_str(c) for c in v))
            for a, b, c in faces:
                out.write("f %d %d %d\n" % (a + base, b + base, c + base))
            base += len(verts)
    return 0


if __name__ == "__main__":
    sys.exit(main())
