"""Translation cost of the add-on (issue 38): a 1M-triangle mesh and 10,000 instances.

    blender -b --factory-startup --python bench/blender/translate.py -- [BUILD_DIR/blender]

For each scene: the add-on's translation (depsgraph to glTF), Glint's load of it, and a
64-sample render at 320x240 on Blender's threads, timed inside Blender; and the translation's
share of the render. Goal: under 10%.
"""

import os
import sys
import tempfile
import time

import bpy

sys.path.insert(0, (sys.argv[sys.argv.index("--") + 1:] or ["build/blender"])[0])
import glint_blender  # noqa: E402
from glint_blender import glint_module  # noqa: E402
from glint_blender.export import Exporter  # noqa: E402

glint_blender.register()
glint = glint_module()


def scene_base():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = "GLINT"
    sc.render.resolution_x, sc.render.resolution_y, sc.render.resolution_percentage = 320, 240, 100
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.location, cam.rotation_euler = (0, -30, 20), (1.0, 0, 0)
    sc.collection.objects.link(cam)
    sc.camera = cam
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3
    sc.collection.objects.link(sun)
    return sc


def million_triangles():
    scene_base()
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=708, y_subdivisions=708, size=20)
    return "one mesh of 1M triangles"


def ten_thousand_instances():
    scene_base()
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=100, y_subdivisions=100, size=40)
    grid = bpy.context.active_object
    bpy.ops.mesh.primitive_monkey_add(location=(0, 0, -100))
    monkey = bpy.context.active_object
    mod = grid.modifiers.new("scatter", "NODES")
    tree = bpy.data.node_groups.new("scatter", "GeometryNodeTree")
    tree.inputs.new("NodeSocketGeometry", "Geometry")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    inp, out = tree.nodes.new("NodeGroupInput"), tree.nodes.new("NodeGroupOutput")
    on_points = tree.nodes.new("GeometryNodeInstanceOnPoints")
    on_points.inputs["Scale"].default_value = (0.15, 0.15, 0.15)
    info = tree.nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = monkey
    tree.links.new(inp.outputs[0], on_points.inputs["Points"])
    tree.links.new(info.outputs["Geometry"], on_points.inputs["Instance"])
    tree.links.new(on_points.outputs[0], out.inputs[0])
    mod.node_group = tree
    return "10,000 instances of a 968-triangle monkey"


for build in (million_triangles, ten_thousand_instances):
    what = build()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    with tempfile.TemporaryDirectory() as folder:
        t0 = time.perf_counter()
        exported = Exporter(depsgraph, folder, lambda text: None).run()
        t1 = time.perf_counter()
        scene = glint.load(exported.path, integrator="path", environment="none", ground="none",
                           camera="Camera", size=exported.size)
        t2 = time.perf_counter()
        scene.render(spp=64, denoise=False)
        t3 = time.perf_counter()
    print(f"{what}: {exported.triangles} triangles translated, {exported.instances} placements; "
          f"translation {t1 - t0:.2f} s, Glint's load {t2 - t1:.2f} s, 64 spp at 320x240 "
          f"{t3 - t2:.2f} s: translation {100 * (t1 - t0) / (t3 - t2):.0f}% of the render")
