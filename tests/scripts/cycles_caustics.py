# SPDX-License-Identifier: MIT
# cycles_caustics.py - renders the irradiance of a white diffuse plane under a
# glass mesh lit by a sun with Blender Cycles, as an independent check of
# snell's caustics reference (tests/test_caustics_cycles.c writes the scene
# and compares).
#
#   blender -b --factory-startup -noaudio -P cycles_caustics.py -- scene.json
#
# scene.json (world coordinates already in Blender's Z-up frame):
#   mesh:     as cycles_render.py reads it: uint32 vertex count, uint32
#             triangle count, float32 positions (3 a vertex), float32 normals
#             (3 a vertex, not used), uint32 indices (counter-clockwise outward)
#   normals_out: where Blender's vertex normals go (float32, 3 a vertex), for
#             the reference to refract at the same ones
#   ior:      the glass's index of refraction
#   sun:      3 floats, the direction the light travels (need not be unit)
#   plane:    [cx, cy, half side]: the square plane z = 0 about (cx, cy)
#   width:    pixels a side (the camera covers the plane exactly)
#   samples, seed, threads
#   mnee:     1 = the glass casts caustics onto the plane (Manifold Next Event
#             Estimation), 0 = it only casts its shadow (the direct light alone)
#   out:      raw output: int32 width, int32 height, then float32 irradiance
#             (one a pixel: pi x the green channel's radiance), top row first
#
# What is measured: an orthographic camera looks straight down at the plane
# (its view exactly the plane's square, pixel centres at the light map's texel
# centres); the plane is a white Lambertian BSDF (Diffuse, roughness 0, colour
# 1), so the radiance it sends up is irradiance / pi; the camera does not see
# the glass (visible_camera off). The sun of strength 1 and angle 0 is
# snell's SNELL_LIGHT_DIRECTIONAL of colour 1: Cycles' sun strength is the
# irradiance on a surface facing it (W/m^2), snell's colour is the same.
#
# A delta light seen through glass cannot be found by a path tracer's
# bounces; Cycles finds it by MNEE ("shadow caustics", Blender 3.2+): at a
# shading point on a caustics receiver, the shadow ray towards a caustics
# light that meets a caustics caster seeds a Newton walk on the specular
# manifold to the refracted path (both interfaces of the sphere) that links
# the point to the light; that path's contribution carries the glass
# closure's Fresnel transmission at each interface and the generalized
# geometry term (how much the glass concentrates the light). Two limits of
# Cycles 3.4's MNEE that the scene has to respect (intern/cycles/kernel/
# integrator/mnee.h): the geometry term is clamped at 2 ("it has a tendency
# to be unstable"), so the plane must sit where the glass concentrates the
# light by less than 2 (a first try near the ball lens's focus, where exact
# rays concentrate it about 40 times, peaked at 2 times the light); and only points whose straight line to the sun meets
# the caster get a caustic (the seed ray), i.e. the caustic inside the
# glass's shadow; light that the glass bends outside its shadow is not seen.
#
# Settings, and why:
#   is_caustics_caster (glass), is_caustics_receiver (plane),
#     is_caustics_light (sun): turn MNEE on for this triple.
#   sun angle 0: a point on the sky, as snell's directional light.
#   diffuse_bounces 2: MNEE refuses a shading point unless diffuse_bounce + 1
#     < max_diffuse_bounces (it counts the manifold path as a diffuse bounce).
#     The plane is black to every ray but camera rays (Light Path "Is Camera
#     Ray" mixing two Diffuse BSDFs), so no light bounces plane -> glass ->
#     plane: the irradiance is the direct light plus the caustic alone, as
#     snell's reference computes it.
#   transmission_bounces, max_bounces 8: MNEE needs transmission_bounce +
#     vertices - 1 < max and bounce + vertices < max (2 vertices here).
#   world black: nothing but the sun lights the plane.
#   pixel filter Gaussian 0.01 pixels: each sample at the pixel centre (point
#     samples of the irradiance, as test_groundtruth finds Cycles' box filter
#     always covers the whole pixel).
#   sharp Glass BSDF: smooth dielectric with Cycles' exact Fresnel (snell's
#     reference takes Schlick's; the test states the difference).
#   no adaptive sampling, no denoising, no clamping (sample_clamp 0),
#     blur_glossy (filter glossy) 0, caustics_refractive/reflective on
#     (off, Cycles drops paths that meet glass after a diffuse bounce),
#     view transform Raw (linear values in the EXR).
import array
import json
import math
import os
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_common import load_mesh, raw_view, render_exr, write_normals  # noqa: E402


def main():
    args = sys.argv[sys.argv.index("--") + 1 :]
    with open(args[0]) as f:
        sc = json.load(f)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    mnee = bool(sc["mnee"])

    me = load_mesh(sc["mesh"])
    write_normals(me, sc["normals_out"])
    glass = bpy.data.objects.new("glass", me)
    scene.collection.objects.link(glass)
    mat = bpy.data.materials.new("glass")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    bsdf = nt.nodes.new("ShaderNodeBsdfGlass")
    bsdf.distribution = "SHARP"
    bsdf.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bsdf.inputs["IOR"].default_value = sc["ior"]
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    me.materials.append(mat)
    glass.visible_camera = False
    glass.cycles.is_caustics_caster = mnee

    cx, cy, half = sc["plane"]
    pm = bpy.data.meshes.new("plane")
    pm.from_pydata([(cx - half, cy - half, 0.0), (cx + half, cy - half, 0.0), (cx + half, cy + half, 0.0),
                    (cx - half, cy + half, 0.0)], [], [(0, 1, 2, 3)])
    pm.update()
    plane = bpy.data.objects.new("plane", pm)
    scene.collection.objects.link(plane)
    pmat = bpy.data.materials.new("plane")
    pmat.use_nodes = True
    nt = pmat.node_tree
    nt.nodes.clear()
    white = nt.nodes.new("ShaderNodeBsdfDiffuse")
    white.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    white.inputs["Roughness"].default_value = 0.0  # Lambert
    black = nt.nodes.new("ShaderNodeBsdfDiffuse")
    black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    path = nt.nodes.new("ShaderNodeLightPath")
    mix = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
    nt.links.new(black.outputs["BSDF"], mix.inputs[1])
    nt.links.new(white.outputs["BSDF"], mix.inputs[2])
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(mix.outputs["Shader"], out.inputs["Surface"])
    pm.materials.append(pmat)
    plane.cycles.is_caustics_receiver = mnee

    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = 1.0
    sun.angle = 0.0
    sun.cycles.is_caustics_light = mnee
    sun_obj = bpy.data.objects.new("sun", sun)
    sun_obj.rotation_mode = "QUATERNION"
    sun_obj.rotation_quaternion = Vector(sc["sun"]).normalized().to_track_quat("-Z", "Y")  # a sun shines along -Z
    scene.collection.objects.link(sun_obj)

    world = bpy.data.worlds.new("black")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0

    cam_data = bpy.data.cameras.new("cam")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = 2.0 * half
    cam_data.sensor_fit = "AUTO"
    cam_data.clip_start = 1e-2
    cam_data.clip_end = 1e3
    cam = bpy.data.objects.new("cam", cam_data)
    cam.location = (cx, cy, 50.0)  # looking down -Z, +Y up: the image's top row at y = cy + half
    scene.collection.objects.link(cam)
    scene.camera = cam

    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x = r.resolution_y = sc["width"]
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.threads_mode = "FIXED"
    r.threads = sc["threads"]
    c = scene.cycles
    c.device = "CPU"
    c.samples = sc["samples"]
    c.seed = sc["seed"]
    c.use_animated_seed = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.pixel_filter_type = "GAUSSIAN"
    c.filter_width = 0.01
    c.max_bounces = c.transmission_bounces = c.glossy_bounces = c.transparent_max_bounces = 8
    c.diffuse_bounces = 2
    c.volume_bounces = 0
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = c.caustics_refractive = True
    raw_view(scene)

    w, h, px = render_exr(scene, sc["out"])
    e = array.array("f", [0.0]) * (w * h)
    for y in range(h):
        src = 4 * w * (h - 1 - y)  # Blender's row 0 is the bottom
        for x in range(w):
            e[w * y + x] = math.pi * px[src + 4 * x + 1]
    with open(sc["out"], "wb") as f:
        array.array("i", [w, h]).tofile(f)
        e.tofile(f)


main()
