#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
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
three_glass_two_opaque.gltf  issue 13's "Done means" scene: three glass objects overlapping on screen at
  different depths, an opaque box between two of them and an opaque wall behind (geometry set 2:
  sphere 32 x 16, cube, torus R 0.7 r 0.3 32 x 16; all glass solid, ior 1.5, no absorption):
  node 0  sphere, glass, T(-0.55,0.05,0.9) S(0.6)                     nearest, front left
  node 1  torus, glass, T(0.3,0.1,-0.3) R(60 deg about +X) S(0.75)     middle, partly behind the sphere
  node 2  cube, glass, T(0.95,-0.05,-1.7) R(30 deg about +Y) S(0.45)   farthest, partly behind the torus
  node 3  cube, opaque orange (0.9,0.5,0.15), T(-0.25,-0.1,-0.75) S(0.22): between the sphere and the
          glass cube in depth, seen through the sphere
  node 4  cube, opaque blue (0.2,0.35,0.8), T(0.4,0.2,-3.4) S(1.3,0.9,0.1): a wall behind all three
  node 5  camera (yfov 0.75) at (0,0.6,4.2) looking at (0.15,0,-0.6)
overlap_N.gltf (N = 1, 2, 4, 8)  N glass spheres (geometry set 2, solid, ior 1.5, radius 0.5) in a row
  receding in depth, each overlapping the next on screen: sphere k (0-based) at T(-1.0+0.45k, 0, 1.0-1.1k);
  the same camera for every N (yfov 0.7) at (1.6,0.9,5.0) looking at (0.3,0,-2.0), so the N spheres
  are the first N of overlap_8 and frame times compare.
framed_large.gltf, framed_small.gltf  no camera (issue 28 item 3: snell_scene_file_frame frames the bounds):
  large: node "far_sphere", sphere, opaque orange (0.9,0.6,0.3), T(250,-120,-400) S(60)
  small: node "tiny_glass", sphere, glass ior 1.5 solid, tint (0.3,1,0.3), T(-3,7,-12) S(0.01)
many_opaque.gltf  100 opaque cubes and a glass sphere (issue 28 item 4: more than SNELL_MAX_OPAQUE):
  meshes 0..99  the cube, each its own mesh entry (100 distinct primitives), material 1 + i % 3
  materials     0 glass ior 1.5 solid; 1 "red" (0.9,0.1,0.1); 2 "green" (0.1,0.9,0.1); 3 "blue" (0.1,0.1,0.9)
  node i < 100  "cube_RC" (R = i // 10, C = i % 10), mesh i, T(-2.25+0.5C, -2.25+0.5R, 0) S(0.15)
  node 100      "lens", sphere, glass, T(3.5,0,0) S(0.5)
  node 101      camera (yfov 0.8) at (0.8,0,9) looking at (0.8,0,0)
glass_33.gltf  33 glass spheres (one more than SNELL_MAX_GLASS: must be refused), nodes "g00".."g32"
  at T(-8+0.5k, 0, 0) S(0.2), no camera
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


def torus(major=0.7, minor=0.3, seg=32, rings=16):
    """Torus around the Y axis (major radius to the tube's centre), with smooth normals."""
    pos, nrm, idx = [], [], []
    for r in range(rings + 1):
        th = 2 * math.pi * r / rings
        for s in range(seg + 1):
            ph = 2 * math.pi * s / seg
            n = (math.cos(th) * math.cos(ph), math.sin(th), math.cos(th) * math.sin(ph))
            c = (major * math.cos(ph), 0.0, major * math.sin(ph))
            pos.append(tuple(c[k] + minor * n[k] for k in range(3)))
            nrm.append(n)
    for r in range(rings):
        for s in range(seg):
            a = r * (seg + 1) + s
            b = a + seg + 1
            # counter-clockwise seen from outside (the normal side)
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return pos, nrm, idx


class Geometry:
    """Meshes in one buffer, embedded as a base64 data URI."""

    def __init__(self):
        self.blob = b""
        self.views, self.accessors = [], []

    def add(self, data, target):
        self.blob = pad4(self.blob)
        self.views.append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data), "target": target})
        self.blob += data
        return len(self.views) - 1

    def add_mesh(self, pos, nrm, idx):
        lo = [min(p[k] for p in pos) for k in range(3)]
        hi = [max(p[k] for p in pos) for k in range(3)]
        vp = self.add(b"".join(struct.pack("<3f", *p) for p in pos), 34962)
        vn = self.add(b"".join(struct.pack("<3f", *n) for n in nrm), 34962)
        vi = self.add(struct.pack("<%dH" % len(idx), *idx), 34963)
        a = len(self.accessors)
        self.accessors.extend([
            {"bufferView": vp, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": vn, "componentType": 5126, "count": len(nrm), "type": "VEC3"},
            {"bufferView": vi, "componentType": 5123, "count": len(idx), "type": "SCALAR"},
        ])
        return a

    def uri(self):
        return "data:application/octet-stream;base64," + base64.b64encode(self.blob).decode()


# the first scenes' geometry (glass_row, nested, glass_box, bad_required)
GEO = Geometry()
sph = GEO.add_mesh(*sphere())
cub = GEO.add_mesh(*cube())


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


def write(name, materials, meshes, nodes, roots, cameras=None, used=(), required=(), geo=GEO):
    g = {"asset": {"version": "2.0", "generator": "snell tests/data/scenes/make_scenes.py"},
         "scene": 0, "scenes": [{"nodes": roots}], "nodes": nodes, "meshes": meshes, "materials": materials,
         "accessors": geo.accessors, "bufferViews": geo.views,
         "buffers": [{"byteLength": len(geo.blob), "uri": geo.uri()}],
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


def quat_axis(axis, angle):
    s = math.sin(angle / 2)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2)]


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz]


def camera_node(eye, target):
    """A glTF camera node at eye looking at target (glTF cameras look down their local -Z, +Y up)."""
    f = [target[k] - eye[k] for k in range(3)]
    n = math.sqrt(sum(x * x for x in f))
    f = [x / n for x in f]
    yaw, pitch = math.atan2(-f[0], -f[2]), math.asin(f[1])
    q = quat_mul(quat_axis((0, 1, 0), yaw), quat_axis((1, 0, 0), pitch))
    return {"camera": 0, "translation": list(eye), "rotation": q}


def perspective(yfov):
    return [{"type": "perspective", "perspective": {"yfov": yfov, "znear": 0.1, "zfar": 50.0, "aspectRatio": 1.0}}]


# geometry set 2 (issue 13's measured scenes): finer sphere, cube, torus
GEO2 = Geometry()
sph2 = GEO2.add_mesh(*sphere(32, 16))
cub2 = GEO2.add_mesh(*cube())
tor2 = GEO2.add_mesh(*torus())
solid = glass(1.5, {"thicknessFactor": 1.0})

write("three_glass_two_opaque.gltf",
      [solid, {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.5, 0.15, 1.0]}},
       {"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.35, 0.8, 1.0]}}],
      [mesh(sph2, 0), mesh(tor2, 0), mesh(cub2, 0), mesh(cub2, 1), mesh(cub2, 2)],
      [{"mesh": 0, "translation": [-0.55, 0.05, 0.9], "scale": [0.6, 0.6, 0.6]},
       {"mesh": 1, "translation": [0.3, 0.1, -0.3], "rotation": quat_axis((1, 0, 0), math.radians(60)),
        "scale": [0.75, 0.75, 0.75]},
       {"mesh": 2, "translation": [1.2, -0.05, -1.7], "rotation": quat_axis((0, 1, 0), math.radians(30)),
        "scale": [0.5, 0.5, 0.5]},
       {"mesh": 3, "translation": [-0.25, -0.1, -0.75], "scale": [0.22, 0.22, 0.22]},
       {"mesh": 4, "translation": [0.4, 0.2, -3.4], "scale": [1.3, 0.9, 0.1]},
       camera_node((0, 0.6, 4.2), (0.15, 0, -0.6))],
      [0, 1, 2, 3, 4, 5], perspective(0.75), EXT, geo=GEO2)

for count in (1, 2, 4, 8):
    nodes = [{"mesh": 0, "translation": [-0.9 + 0.25 * k, 0, 1.0 - 1.1 * k], "scale": [0.5, 0.5, 0.5]}
             for k in range(count)]
    nodes.append(camera_node((2.2, 0.9, 5.5), (-0.3, -0.1, -2.0)))
    write("overlap_%d.gltf" % count, [solid], [mesh(sph2, 0)], nodes, list(range(count + 1)), perspective(0.7),
          EXT, geo=GEO2)

# issue 28: camera-less scenes far off the origin, many opaque objects, too many glass objects
write("framed_large.gltf", [{"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.3, 1.0]}}], [mesh(sph, 0)],
      [{"name": "far_sphere", "mesh": 0, "translation": [250, -120, -400], "scale": [60, 60, 60]}], [0], None, EXT)
write("framed_small.gltf", [glass(1.5, {"thicknessFactor": 1.0}, (0.3, 1.0, 0.3))], [mesh(sph, 0)],
      [{"name": "tiny_glass", "mesh": 0, "translation": [-3, 7, -12], "scale": [0.01, 0.01, 0.01]}], [0], None, EXT)
many_materials = [glass(1.5, {"thicknessFactor": 1.0})] + [
    {"name": n, "pbrMetallicRoughness": {"baseColorFactor": c + [1.0]}}
    for n, c in (("red", [0.9, 0.1, 0.1]), ("green", [0.1, 0.9, 0.1]), ("blue", [0.1, 0.1, 0.9]))]
many_nodes = [{"name": "cube_%d%d" % (i // 10, i % 10), "mesh": i,
               "translation": [-2.25 + 0.5 * (i % 10), -2.25 + 0.5 * (i // 10), 0], "scale": [0.15, 0.15, 0.15]}
              for i in range(100)]
many_nodes.append({"name": "lens", "mesh": 100, "translation": [3.5, 0, 0], "scale": [0.5, 0.5, 0.5]})
many_nodes.append(camera_node((0.8, 0, 9), (0.8, 0, 0)))
write("many_opaque.gltf", many_materials, [mesh(cub, 1 + i % 3) for i in range(100)] + [mesh(sph, 0)], many_nodes,
      list(range(102)), perspective(0.8), EXT)
write("glass_33.gltf", [glass(1.5, {"thicknessFactor": 1.0})], [mesh(sph, 0)],
      [{"name": "g%02d" % k, "mesh": 0, "translation": [-8 + 0.5 * k, 0, 0], "scale": [0.2, 0.2, 0.2]}
       for k in range(33)], list(range(33)), None, EXT)
