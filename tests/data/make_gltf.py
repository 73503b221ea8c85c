#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Generates the glTF test assets used by tests/test_mesh_gltf.c:

  nodes.gltf      JSON with the buffer embedded as a base64 data URI
  nodes.glb       the same model as a binary container (JSON + BIN chunks)
  nodes_ext.gltf  the same model with the buffer in the external file nodes.bin
  bad_accessor.gltf, bad_stride.gltf, bad_index.gltf, bad_truncated.glb
                  malformed variants (replayed through the fuzz targets by ctest)

Content (expected values are derived in the test from these definitions):
  mesh 0  triangle (0,0,0) (1,0,0) (0,1,0), NORMAL (0,0,1), uint16 indices
  mesh 1  the same triangle, no normals, uint8 indices
  mesh 2  unit quad as a TRIANGLE_STRIP, non-indexed, no normals
  mesh 3  triangle (0,0,0) (0,1,0) (0,0,1), interleaved POSITION+NORMAL
          (byteStride 24), NORMAL (1,0,0), uint32 indices
  node 0  translation (10,0,0), children [1, 2]
  node 1  mesh 0, rotation 90 deg about +Z, scale 2
  node 2  mesh 1, matrix = translate(0,5,0) * scale(1,1,-1)  (mirror: winding flips)
  node 3  mesh 2, translation (0,0,-3)
  node 4  mesh 3, translation (0,-7,0)
  node 5  mesh 0, only in scene 1 (must not be loaded)
  scenes  0: [0, 3, 4] (default), 1: [5]
Run: python3 make_gltf.py  (in tests/data)
"""
import base64
import json
import math
import struct


def f32(*v):
    return struct.pack("<%df" % len(v), *v)


def pad4(b):
    return b + b"\0" * (-len(b) % 4)


views = []
blob = b""


def add_view(data, stride=None):
    global blob
    blob = pad4(blob)
    v = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
    if stride:
        v["byteStride"] = stride
    views.append(v)
    blob += data
    return len(views) - 1


tri = f32(0, 0, 0, 1, 0, 0, 0, 1, 0)
bv_pos = add_view(tri)
bv_nrm = add_view(f32(0, 0, 1) * 3)
bv_i16 = add_view(struct.pack("<3H", 0, 1, 2))
bv_i8 = add_view(struct.pack("<3B", 0, 1, 2))
bv_strip = add_view(f32(0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0))
inter = b"".join(f32(*p, 1, 0, 0) for p in [(0, 0, 0), (0, 1, 0), (0, 0, 1)])
bv_inter = add_view(inter, stride=24)
bv_i32 = add_view(struct.pack("<3I", 0, 1, 2))
blob = pad4(blob)

F, U8, U16, U32 = 5126, 5121, 5123, 5125
accessors = [
    {"bufferView": bv_pos, "componentType": F, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": bv_nrm, "componentType": F, "count": 3, "type": "VEC3"},
    {"bufferView": bv_i16, "componentType": U16, "count": 3, "type": "SCALAR"},
    {"bufferView": bv_i8, "componentType": U8, "count": 3, "type": "SCALAR"},
    {"bufferView": bv_strip, "componentType": F, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": bv_inter, "componentType": F, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [0, 1, 1]},
    {"bufferView": bv_inter, "byteOffset": 12, "componentType": F, "count": 3, "type": "VEC3"},
    {"bufferView": bv_i32, "componentType": U32, "count": 3, "type": "SCALAR"},
]
s45 = math.sqrt(0.5)
model = {
    "asset": {"version": "2.0", "generator": "snell tests/data/make_gltf.py"},
    "scene": 0,
    "scenes": [{"nodes": [0, 3, 4]}, {"nodes": [5]}],
    "nodes": [
        {"translation": [10, 0, 0], "children": [1, 2]},
        {"mesh": 0, "rotation": [0, 0, s45, s45], "scale": [2, 2, 2]},
        {"mesh": 1, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 5, 0, 1]},
        {"mesh": 2, "translation": [0, 0, -3]},
        {"mesh": 3, "translation": [0, -7, 0]},
        {"mesh": 0},
    ],
    "meshes": [
        {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]},
        {"primitives": [{"attributes": {"POSITION": 0}, "indices": 3}]},
        {"primitives": [{"attributes": {"POSITION": 4}, "mode": 5}]},
        {"primitives": [{"attributes": {"POSITION": 5, "NORMAL": 6}, "indices": 7}]},
    ],
    "accessors": accessors,
    "bufferViews": views,
}


def dump(m):
    return json.dumps(m, separators=(",", ":"))


embedded = dict(model)
embedded["buffers"] = [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]
with open("nodes.gltf", "w") as f:
    f.write(dump(embedded) + "\n")

external = dict(model)
external["buffers"] = [{"byteLength": len(blob), "uri": "nodes.bin"}]
with open("nodes_ext.gltf", "w") as f:
    f.write(dump(external) + "\n")
with open("nodes.bin", "wb") as f:
    f.write(blob)

binary = dict(model)
binary["buffers"] = [{"byteLength": len(blob)}]
js = dump(binary).encode()
js += b" " * (-len(js) % 4)
glb = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(blob), b"BIN\0") + blob
with open("nodes.glb", "wb") as f:
    f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(glb)) + glb)

# --- malformed variants ----------------------------------------------------
bad = json.loads(dump(embedded))
bad["accessors"][0]["count"] = 1000  # runs past its bufferView
with open("bad_accessor.gltf", "w") as f:
    f.write(dump(bad) + "\n")
bad = json.loads(dump(embedded))
bad["bufferViews"][bv_inter]["byteStride"] = 8  # smaller than one VEC3 float element
with open("bad_stride.gltf", "w") as f:
    f.write(dump(bad) + "\n")
bad = json.loads(dump(embedded))
blob_bad = bytearray(blob)
off = views[bv_i16]["byteOffset"]
blob_bad[off + 4:off + 6] = struct.pack("<H", 700)  # index 700 of 3 vertices
bad["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(blob_bad)).decode()
with open("bad_index.gltf", "w") as f:
    f.write(dump(bad) + "\n")
with open("nodes.glb", "rb") as f:
    whole = f.read()
with open("bad_truncated.glb", "wb") as f:
    f.write(whole[: len(whole) * 2 // 3])
