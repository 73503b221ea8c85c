#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Generates the small hostile inputs of tests/test_hostile_files.c (issue 14).
Bigger ones (a 40 MB data: URI, a 40,000-corner OBJ face, files outside a
model's folder) are made by the test at run time, not committed.

  gltf1.gltf              a glTF 1.0 file (object-shaped sections): "glTF 1.0 is not supported"
  draco.gltf              requires KHR_draco_mesh_compression (accessors have no bufferView)
  required_unknown.gltf   requires EXT_snell_unknown: an error naming it
  required_materials.gltf requires KHR_materials_ior (no effect on geometry): loads
  huge_dims.hdr           Radiance header declaring 20000 x 8 pixels (over 16384 per side)
  truncated_rle.hdr       8x8 run-length HDR cut inside scanline 4 (stb loops forever on it)
  truncated_flat.hdr      4x4 flat HDR with 5 of 16 pixels (stb fills the rest with black)
  rle_8x8.hdr             the complete 8x8 run-length HDR (decodes)
  huge_coords.obj         a tetrahedron at +-1e38 (normalises: bounds in double)
  too_big_coords.obj      a tetrahedron spanning -3e38..3e38 (extent beyond float: SNELL_E_LIMIT)
  tiny_coords.obj         a tetrahedron of size 1e-30 (float squared distances underflow)
  png_bomb.png            a 1x1 RGBA PNG whose IDAT inflates to 32 MiB of zeros (issue 40 item 6)
Run: python3 make_hostile.py  (in tests/data/hostile)
"""
import base64
import json
import struct
import zlib

tri = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"
uri = "data:application/octet-stream;base64," + base64.b64encode(tri).decode()


def dump(name, obj):
    with open(name, "w") as f:
        f.write(json.dumps(obj, indent=1) + "\n")


dump("gltf1.gltf", {
    "asset": {"version": "1.0"}, "scene": "defaultScene",
    "scenes": {"defaultScene": {"nodes": ["node0"]}}, "nodes": {"node0": {"meshes": ["mesh0"]}},
    "meshes": {"mesh0": {"primitives": [{"attributes": {"POSITION": "acc0"}, "indices": "acc1", "mode": 4}]}},
    "accessors": {"acc0": {"bufferView": "bv0", "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                  "acc1": {"bufferView": "bv1", "byteOffset": 0, "componentType": 5123, "count": 3, "type": "SCALAR"}},
    "bufferViews": {"bv0": {"buffer": "b0", "byteOffset": 0, "byteLength": 36, "target": 34962},
                    "bv1": {"buffer": "b0", "byteOffset": 36, "byteLength": 6, "target": 34963}},
    "buffers": {"b0": {"uri": uri, "byteLength": 44}}})


def model2(extra, prim_ext=None, draco=False):
    prim = {"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}
    if prim_ext:
        prim["extensions"] = prim_ext
    acc = [{"componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
           {"componentType": 5123, "count": 3, "type": "SCALAR"}]
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 44}]
    if not draco:
        views = [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}]
        acc[0]["bufferView"] = 0
        acc[1]["bufferView"] = 1
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
         "meshes": [{"primitives": [prim]}], "accessors": acc, "bufferViews": views,
         "buffers": [{"uri": uri, "byteLength": 44}]}
    g.update(extra)
    return g


dump("draco.gltf", model2({"extensionsUsed": ["KHR_draco_mesh_compression"],
                           "extensionsRequired": ["KHR_draco_mesh_compression"]},
                          {"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}, True))
dump("required_unknown.gltf", model2({"extensionsUsed": ["EXT_snell_unknown"],
                                      "extensionsRequired": ["EXT_snell_unknown"]}))
dump("required_materials.gltf", model2({"extensionsUsed": ["KHR_materials_ior"],
                                        "extensionsRequired": ["KHR_materials_ior"],
                                        "materials": [{"extensions": {"KHR_materials_ior": {"ior": 1.4}}}]}))

HDR = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n"
with open("huge_dims.hdr", "wb") as f:
    f.write(HDR + b"-Y 8 +X 20000\n" + bytes([128, 128, 128, 129]) * 4)
line = bytes([2, 2, 0, 8]) + bytes([136, 128]) * 4  # per channel one run of 8
with open("rle_8x8.hdr", "wb") as f:
    f.write(HDR + b"-Y 8 +X 8\n" + line * 8)
with open("truncated_rle.hdr", "wb") as f:
    f.write(HDR + b"-Y 8 +X 8\n" + line * 3 + line[:5])
with open("truncated_flat.hdr", "wb") as f:
    f.write(HDR + b"-Y 4 +X 4\n" + bytes([128, 128, 128, 129]) * 5)


def tetra(name, verts):
    with open(name, "w") as f:
        for v in verts:
            f.write("v %r %r %r\n" % v)
        f.write("f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")


tetra("huge_coords.obj", [(1e38, 1e38, 1e38), (-1e38, -1e38, 1e38), (-1e38, 1e38, -1e38), (1e38, -1e38, -1e38)])
tetra("too_big_coords.obj", [(3e38, 0.0, 0.0), (-3e38, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)])
tetra("tiny_coords.obj", [(1e-30, 1e-30, 1e-30), (-1e-30, -1e-30, 1e-30), (-1e-30, 1e-30, -1e-30),
                          (1e-30, -1e-30, -1e-30)])


def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)


with open("png_bomb.png", "wb") as f:
    f.write(b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 6, 0, 0, 0)) +
            png_chunk(b"IDAT", zlib.compress(bytes(32 << 20), 9)) + png_chunk(b"IEND", b""))
