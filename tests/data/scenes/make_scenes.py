#!/usr/bin/env python3
"""Generates the glTF scene files used by tests/test_scene_gltf.c (issue 13).

Shared geometry (one buffer, embedded as a base64 data URI):
  mesh 0  UV sphere, radius 1, 24 segments x 12 rings, POSITION + NORMAL, uint16 indices
  mesh 1  cube [-1,1]^3, flat faces (24 vertices), POSITION + NORMAL

glass_row.gltf   three glass spheres in a row overlapping on screen, an opaque box behind:
  node 0  sphere, material 0 (glass, ior 1.5, solid: volume thickness 1), T(-1.1,0,0) S(0.6)
  node 1  sphere, material 1 (glass, ior 1.33, solid, attenuation colour (0.8,0.9,1) at 2.0), T(0,0,-0.8) S(0.6)
  node 2  sphere, material 2 (glass, ior 1.7, thin-walled: no volume, tint (0.9,1,0.9)), T(1.1,0,0) S(0.6)
  node 3  cube, material 3 (opaque red (0.8,0.1,0.1)), T(0,0,-3) S(1.5,1,0.2)
  node 4  camera 0 (perspective yfov 0.8, znear 0.1, zfar 50) at (0,0.5,5), looking at -Z, pitched -0.1 rad
nested.gltf      a glass sphere inside a larger one (parent/child transforms):
  node 0  sphere, material 0, S(1.0), children [1]
  node 1  sphere, material 1, S(0.4) (world radius 0.4)
glass_box.gltf   a glass sphere in front of an opaque box (opaque default material):
  node 0  sphere, material 0, T(0,0,1)
  node 1  cube, no material (glTF default: opaque white), T(0,0,-1.5) S(1.2)
bad_required.gltf  glass_row requiring KHR_materials_clearcoat (must be refused)
dispersion.gltf  two glass spheres with KHR_materials_dispersion (required: it is read):
  node 0  sphere, material 0 (ior 1.5, solid, dispersion 0.36: 20 / V_d for diamond's V_d 55), T(-1.1,0,0) S(0.6)
  node 1  sphere, material 1 (ior 1.5, thin-walled, dispersion 1: a thin wall has none), T(1.1,0,0) S(0.6)
bad_dispersion.gltf  dispersion.gltf with dispersion -1 on material 0 (must be refused)
Run: python3 make_scenes.py  (in tests/data/scenes)
"""
import base64
import json
import math
import struct


def pad4(b):
    return b + b"\0" * (-len(b) % 4)


def sphere(seg=24, rings=12):
    pos, idx = [], []
    for r in range(rings + 1):
        th = math.pi * r / rings
        for s in range(seg + 1):
            ph = 2 * math.pi * s / seg
            pos.append((math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)))
    for r in range(rings):
        for s in range(seg):
            a = r * (seg + 1) + s
            b = a + seg + 1
            # counter-clockwise seen from outside
            idx += [a, a + 1, b, a + 1, b + 1, b]
    return pos, pos, idx


def cube():
    pos, nrm, idx = [], [], []
    for axis in range(3):
        for sign in (-1, 1):
            n = [0, 0, 0]
            n[axis] = sign
            u = [0, 0, 0]
            v = [0, 0, 0]
            u[(axis + 1) % 3] = 1
            v[(axis + 2) % 3] = 1
            if sign < 0:
                u, v = v, u
            base = len(pos)
            for du, dv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                pos.append(tuple(n[k] + du * u[k] + dv * v[k] for k in range(3)))
                nrm.append(tuple(n))
            idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, idx


blob = b""
views, accessors = [], []


def add(data, target):
    global blob
    blob = pad4(blob)
    views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
    blob += data
    return len(views) - 1


def add_mesh(pos, nrm, idx):
    lo = [min(p[k] for p in pos) for k in range(3)]
    hi = [max(p[k] for p in pos) for k in range(3)]
    vp = add(b"".join(struct.pack("<3f", *p) for p in pos), 34962)
    vn = add(b"".join(struct.pack("<3f", *n) for n in nrm), 34962)
    vi = add(struct.pack("<%dH" % len(idx), *idx), 34963)
    a = len(accessors)
    accessors.extend([
        {"bufferView": vp, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": lo, "max": hi},
        {"bufferView": vn, "componentType": 5126, "count": len(nrm), "type": "VEC3"},
        {"bufferView": vi, "componentType": 5123, "count": len(idx), "type": "SCALAR"},
    ])
    return a


sph = add_mesh(*sphere())
cub = add_mesh(*cube())
uri = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()


def mesh(acc, material):
    p = {"attributes": {"POSITION": acc, "NORMAL": acc + 1}, "indices": acc + 2}
    if material is not None:
        p["material"] = material
    return {"primitives": [p]}


def glass(ior, volume=None, tint=(1, 1, 1), dispersion=None):
    ext = {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": ior}}
    if volume:
        ext["KHR_materials_volume"] = volume
    if dispersion is not None:
        ext["KHR_materials_dispersion"] = {"dispersion": dispersion}
    return {"pbrMetallicRoughness": {"baseColorFactor": list(tint) + [1.0], "roughnessFactor": 0.0},
            "extensions": ext}


def write(name, materials, meshes, nodes, roots, cameras=None, used=(), required=()):
    g = {"asset": {"version": "2.0", "generator": "snell tests/data/scenes/make_scenes.py"},
         "scene": 0, "scenes": [{"nodes": roots}], "nodes": nodes, "meshes": meshes, "materials": materials,
         "accessors": accessors, "bufferViews": views, "buffers": [{"byteLength": len(blob), "uri": uri}],
         "extensionsUsed": sorted(set(used) | set(required))}
    if required:
        g["extensionsRequired"] = list(required)
    if cameras:
        g["cameras"] = cameras
    with open(name, "w") as f:
        json.dump(g, f, indent=1)


EXT = ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"]
row_materials = [
    glass(1.5, {"thicknessFactor": 1.0}),
    glass(1.33, {"thicknessFactor": 1.0, "attenuationColor": [0.8, 0.9, 1.0], "attenuationDistance": 2.0}),
    glass(1.7, None, (0.9, 1.0, 0.9)),
    {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1.0]}},
]
row_meshes = [mesh(sph, 0), mesh(sph, 1), mesh(sph, 2), mesh(cub, 3)]
pitch = -0.1
row_nodes = [
    {"mesh": 0, "translation": [-1.1, 0, 0], "scale": [0.6, 0.6, 0.6]},
    {"mesh": 1, "translation": [0, 0, -0.8], "scale": [0.6, 0.6, 0.6]},
    {"mesh": 2, "translation": [1.1, 0, 0], "scale": [0.6, 0.6, 0.6]},
    {"mesh": 3, "translation": [0, 0, -3], "scale": [1.5, 1.0, 0.2]},
    {"camera": 0, "translation": [0, 0.5, 5], "rotation": [math.sin(pitch / 2), 0, 0, math.cos(pitch / 2)]},
]
cams = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 50.0, "aspectRatio": 1.0}}]
write("glass_row.gltf", row_materials, row_meshes, row_nodes, [0, 1, 2, 3, 4], cams, EXT)
write("bad_required.gltf", row_materials, row_meshes, row_nodes, [0, 1, 2, 3, 4], cams, EXT,
      ["KHR_materials_clearcoat"])
write("nested.gltf", [glass(1.5, {"thicknessFactor": 2.0}), glass(1.33, {"thicknessFactor": 0.8})],
      [mesh(sph, 0), mesh(sph, 1)],
      [{"mesh": 0, "children": [1]}, {"mesh": 1, "scale": [0.4, 0.4, 0.4]}], [0], None, EXT)
write("glass_box.gltf", [glass(1.5, {"thicknessFactor": 2.0})], [mesh(sph, 0), mesh(cub, None)],
      [{"mesh": 0, "translation": [0, 0, 1]}, {"mesh": 1, "translation": [0, 0, -1.5], "scale": [1.2, 1.2, 1.2]}],
      [0, 1], None, EXT)
DISP_EXT = EXT + ["KHR_materials_dispersion"]
disp_nodes = [{"mesh": 0, "translation": [-1.1, 0, 0], "scale": [0.6, 0.6, 0.6]},
              {"mesh": 1, "translation": [1.1, 0, 0], "scale": [0.6, 0.6, 0.6]}]
write("dispersion.gltf", [glass(1.5, {"thicknessFactor": 1.0}, dispersion=0.36), glass(1.5, None, dispersion=1.0)],
      [mesh(sph, 0), mesh(sph, 1)], disp_nodes, [0, 1], None, DISP_EXT, ["KHR_materials_dispersion"])
write("bad_dispersion.gltf", [glass(1.5, {"thicknessFactor": 1.0}, dispersion=-1.0), glass(1.5, None)],
      [mesh(sph, 0), mesh(sph, 1)], disp_nodes, [0, 1], None, DISP_EXT)
