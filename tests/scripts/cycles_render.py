# SPDX-License-Identifier: MIT
# cycles_render.py - renders one glass mesh in an equirectangular environment
# with Blender Cycles, as an independent check of snell's FULL reference
# (tests/test_groundtruth.c writes the scene and compares).
#
#   blender -b --factory-startup -noaudio -P cycles_render.py -- scene.json
#
# scene.json (world coordinates already converted to Blender's Z-up frame):
#   mesh:     file (this machine's byte order) of uint32 vertex count, uint32 triangle count, then float32
#             positions (3 per vertex), float32 normals (3 per vertex, not
#             used: Cycles shades with Blender's own), uint32 indices
#   normals_out: where Blender's vertex normals go (float32, 3 per vertex),
#             for the reference to shade with the same ones
#   camera:   16 floats, camera-to-world, row-major (Blender camera frame:
#             looks down -Z, +Y up, as snell's view frame)
#   fov_y:    vertical field of view, radians
#   width, height, samples, seed, ior, threads
#   filter:   "point" (the pixel centre) or "box" (uniform over the pixel)
#   env:      equirectangular PNG, loaded as non-colour data (bytes / 255)
#   out:      raw output: int32 width, int32 height, then float32 RGB, top row
#             first, linear (no view transform, no clamp)
#
# Settings are those that make Cycles' estimator converge to the same
# quantity as the Whitted tree: sharp Glass BSDF (exact dielectric Fresnel,
# one branch sampled per interface), white colour, no light source but the
# world, no denoising, no adaptive sampling, no clamping, no Russian roulette
# (min bounces = max bounces), 64 bounces, Raw view transform.
import array
import json
import os
import sys

import bpy
from mathutils import Matrix

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_common import load_mesh, raw_view, render_exr, write_normals  # noqa: E402


def main():
    args = sys.argv[sys.argv.index("--") + 1 :]
    with open(args[0]) as f:
        sc = json.load(f)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene

    me = load_mesh(sc["mesh"])
    write_normals(me, sc["normals_out"])
    obj = bpy.data.objects.new("glass", me)
    scene.collection.objects.link(obj)
    mat = bpy.data.materials.new("glass")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    glass = nt.nodes.new("ShaderNodeBsdfGlass")
    glass.distribution = "SHARP"
    glass.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    glass.inputs["IOR"].default_value = sc["ior"]
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(glass.outputs["BSDF"], out.inputs["Surface"])
    obj.data.materials.append(mat)

    world = bpy.data.worlds.new("env")
    scene.world = world
    world.use_nodes = True
    wt = world.node_tree
    wt.nodes.clear()
    tex = wt.nodes.new("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(sc["env"])
    tex.image.colorspace_settings.name = "Non-Color"
    tex.image.alpha_mode = "NONE"
    tex.interpolation = "Linear"
    tex.projection = "EQUIRECTANGULAR"
    bg = wt.nodes.new("ShaderNodeBackground")
    bg.inputs["Strength"].default_value = 1.0
    wout = wt.nodes.new("ShaderNodeOutputWorld")
    wt.links.new(tex.outputs["Color"], bg.inputs["Color"])
    wt.links.new(bg.outputs["Background"], wout.inputs["Surface"])
    world.cycles.sampling_method = "NONE"  # no light sampling: nothing diffuse to light

    cam_data = bpy.data.cameras.new("cam")
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = sc["fov_y"]
    cam_data.clip_start = 1e-3
    cam_data.clip_end = 1e4
    cam = bpy.data.objects.new("cam", cam_data)
    m = sc["camera"]
    cam.matrix_world = Matrix([m[0:4], m[4:8], m[8:12], m[12:16]])
    scene.collection.objects.link(cam)
    scene.camera = cam

    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x = sc["width"]
    r.resolution_y = sc["height"]
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.film_transparent = False
    r.threads_mode = "FIXED"
    r.threads = sc["threads"]
    r.use_persistent_data = False
    c = scene.cycles
    c.device = "CPU"
    c.samples = sc["samples"]
    c.seed = sc["seed"]
    c.use_animated_seed = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    # "point": a Gaussian 0.01 pixels wide, the pixel centre (Cycles' box
    # filter ignores its width and is always one pixel: measured here on a
    # checker environment, 64 samples matched a 1-pixel box to 0.003 rms);
    # "box": the pixel's area, what the reference's samples = S averages.
    if sc["filter"] == "point":
        c.pixel_filter_type = "GAUSSIAN"
        c.filter_width = 0.01
    else:
        c.pixel_filter_type = "BOX"
    c.max_bounces = c.transmission_bounces = c.glossy_bounces = c.transparent_max_bounces = 64
    c.diffuse_bounces = c.volume_bounces = 0
    c.min_light_bounces = c.min_transparent_bounces = 64  # no Russian roulette
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = c.caustics_refractive = True
    raw_view(scene)
    scene.display_settings.display_device = "sRGB"

    # Linear float EXR, read back as data and written raw (top row first).
    w, h, px = render_exr(scene, sc["out"])
    rgb = array.array("f", [0.0]) * (3 * w * h)
    for y in range(h):
        src = 4 * w * (h - 1 - y)  # Blender's row 0 is the bottom
        dst = 3 * w * y
        rgb[dst : dst + 3 * w : 3] = px[src : src + 4 * w : 4]
        rgb[dst + 1 : dst + 3 * w : 3] = px[src + 1 : src + 4 * w : 4]
        rgb[dst + 2 : dst + 3 * w : 3] = px[src + 2 : src + 4 * w : 4]
    with open(sc["out"], "wb") as f:
        array.array("i", [w, h]).tofile(f)
        rgb.tofile(f)


main()
