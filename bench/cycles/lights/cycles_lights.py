"""Blender script (README.md): renders a glTF file lit by its own KHR_lights_punctual lights in
Cycles, through the file's camera, with a black world, and writes a PFM of linear radiance.

    blender -b --factory-startup --python cycles_lights.py -- FILE.gltf OUT.pfm SPP SEED
        WIDTH HEIGHT BOUNCES THREADS [diffuse]

The importer's 'COMPAT' lighting mode turns a point or spot light of I candela into 4 pi I
watts (a radiant intensity of I watts per steradian) and a sun of E lux into E watts per square
metre, without the photometric 683 lm/W, as glTF viewers light their images. Prints the render's
own seconds (bpy.ops.render.render). With `diffuse`, every material becomes a Diffuse BSDF of
its base colour: how much of a difference is the Principled BSDF's (v1) own."""
import struct
import sys
import time

import bpy

a = sys.argv[sys.argv.index("--") + 1:]
path, out = a[0], a[1]
spp, seed, width, height, bounces, threads = (int(x) for x in a[2:8])

bpy.ops.wm.read_factory_settings(use_empty=True)
import numpy  # noqa: E402  Debian's importer uses numpy.bool, which NumPy 1.24 removed
if not hasattr(numpy, "bool"):
    numpy.bool = bool
bpy.ops.import_scene.gltf(filepath=path, convert_lighting_mode="COMPAT")
scene = bpy.context.scene
if len(a) > 8 and a[8] == "diffuse":
    for m in bpy.data.materials:
        if not m.use_nodes:
            continue
        nt = m.node_tree
        p = next((n for n in nt.nodes if n.type == "BSDF_PRINCIPLED"), None)
        sink = next((n for n in nt.nodes if n.type == "OUTPUT_MATERIAL"), None)
        if p is None or sink is None:
            continue
        d = nt.nodes.new("ShaderNodeBsdfDiffuse")
        d.inputs["Color"].default_value = p.inputs["Base Color"].default_value
        nt.links.new(d.outputs[0], sink.inputs["Surface"])
cameras = [o for o in scene.objects if o.type == "CAMERA"]
scene.camera = cameras[0]
world = bpy.data.worlds.new("black")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
scene.world = world
scene.render.engine = "CYCLES"
c = scene.cycles
c.device = "CPU"
c.samples = spp
c.seed = seed
c.use_adaptive_sampling = False
c.use_denoising = False
c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
for kind in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces",
             "volume_bounces", "transparent_max_bounces"):
    setattr(c, kind, bounces)
c.pixel_filter_type = "BOX"
c.filter_width = 1.0
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100
scene.render.threads_mode = "FIXED"
scene.render.threads = threads
scene.view_settings.view_transform = "Standard"
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.filepath = out + ".exr"
start = time.perf_counter()
bpy.ops.render.render(write_still=True)
print(f"cycles: rendered {spp} spp in {time.perf_counter() - start:.3f} s")
img = bpy.data.images.load(out + ".exr")
px = numpy.array(img.pixels[:], dtype=numpy.float32).reshape(height, width, 4)[:, :, :3]
with open(out, "wb") as f:  # PFM: bottom row first, as Blender's pixels are
    f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
    f.write(numpy.ascontiguousarray(px).astype("<f4").tobytes())
