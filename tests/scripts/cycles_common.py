# SPDX-License-Identifier: MIT
# cycles_common.py - what tests/scripts/cycles_render.py and cycles_caustics.py
# share: the mesh file snell's tests write (test_util.c test_write_blender_mesh),
# the normals Cycles shades with, a raw linear view, and a render read back
# from a linear float EXR. Imported from the scripts' own folder.
import array

import bpy


def load_mesh(path):
    with open(path, "rb") as f:
        head = array.array("I")
        head.fromfile(f, 2)
        nv, nt = head[0], head[1]
        pos = array.array("f")
        pos.fromfile(f, 3 * nv)
        nrm = array.array("f")
        nrm.fromfile(f, 3 * nv)
        idx = array.array("I")
        idx.fromfile(f, 3 * nt)
    me = bpy.data.meshes.new("glass")
    me.vertices.add(nv)
    me.vertices.foreach_set("co", pos)
    me.loops.add(3 * nt)
    me.loops.foreach_set("vertex_index", idx)
    me.polygons.add(nt)
    me.polygons.foreach_set("loop_start", array.array("i", range(0, 3 * nt, 3)))
    me.polygons.foreach_set("loop_total", array.array("i", [3]) * nt)
    me.polygons.foreach_set("use_smooth", array.array("b", [1]) * nt)  # smooth normals (MNEE needs them)
    me.update(calc_edges=True)
    return me


def write_normals(me, path):
    """The vertex normals Cycles shades with (smooth faces, no custom normals:
    Blender's own, float32), for the reference to use the very same ones.
    Custom split normals were tried first: their 16-bit encoding moved the
    refracted checker edges by ~1e-4 rad, 2.5/255 of bias on the sphere."""
    n = array.array("f", [0.0]) * (3 * len(me.vertices))
    me.vertices.foreach_get("normal", n)
    with open(path, "wb") as f:
        n.tofile(f)


def raw_view(scene):
    """No view transform, look, exposure or gamma: the render is the scene's linear values."""
    scene.view_settings.view_transform = "Raw"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.sequencer_colorspace_settings.name = "Non-Color"


def render_exr(scene, out):
    """Renders to out + ".exr" (32-bit float, uncompressed), reads it back as data:
    (width, height, RGBA floats, Blender's row 0 at the bottom)."""
    r = scene.render
    exr = out + ".exr"
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.exr_codec = "NONE"
    r.filepath = exr
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(exr)
    img.colorspace_settings.name = "Non-Color"
    w, h = img.size
    px = array.array("f", [0.0]) * (4 * w * h)
    img.pixels.foreach_get(px)
    return w, h, px
