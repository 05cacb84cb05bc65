"""The validation scenes of docs/blender.md, built with Blender's Python (issue 38).

    blender -b --factory-startup --python bench/blender/scenes.py -- NAME OUT.blend [--diffuse]

NAME is one of SCENES. Each scene is saved as a .blend file that Cycles and Glint both render
(bench/blender/render.py); emitters are Blender lights, materials Principled BSDFs.
"""

import math
import sys

import bpy


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.resolution_x, sc.render.resolution_y = 192, 144
    sc.render.resolution_percentage = 100
    return sc


def camera(sc, location, target, lens=35.0):
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.location = location
    sc.collection.objects.link(cam)
    from mathutils import Vector
    d = Vector(target) - Vector(location)
    cam.rotation_euler = d.to_track_quat("-Z", "Y").to_euler()
    cam.data.lens = lens
    sc.camera = cam


# With --diffuse every material is a Diffuse BSDF of its base colour: Lambert in both engines,
# where the Principled BSDF (Cycles' v1, Disney's) and glTF's layers are different models.
DIFFUSE = False


def material(name, colour=(0.8, 0.8, 0.8), **inputs):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    if DIFFUSE and not inputs.get("Transmission") and not inputs.get("Metallic"):
        nodes = mat.node_tree.nodes
        nodes.remove(nodes["Principled BSDF"])
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = (*colour, 1)
        mat.node_tree.links.new(diffuse.outputs[0], nodes["Material Output"].inputs["Surface"])
        return mat
    node = mat.node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (*colour, 1)
    for k, v in inputs.items():
        node.inputs[k].default_value = v
    return mat


def plane(sc, name, location, rotation, size, mat):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(mat)
    return obj


def light(sc, kind, energy, location, rotation=(0, 0, 0), **props):
    data = bpy.data.lights.new(kind.lower(), kind)
    data.energy = energy
    for k, v in props.items():
        setattr(data, k, v)
    obj = bpy.data.objects.new(kind.lower(), data)
    obj.location, obj.rotation_euler = location, rotation
    sc.collection.objects.link(obj)
    return obj


def black_world(sc):
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    sc.world = world


def cornell():
    """A box 2 m wide, open to the camera, with a square area light under its ceiling."""
    sc = reset()
    black_world(sc)
    white = material("white", (0.73, 0.73, 0.73), Specular=0.0, Roughness=1.0)
    red = material("red", (0.65, 0.05, 0.05), Specular=0.0, Roughness=1.0)
    green = material("green", (0.12, 0.45, 0.15), Specular=0.0, Roughness=1.0)
    plane(sc, "floor", (0, 0, 0), (0, 0, 0), 2, white)
    plane(sc, "ceiling", (0, 0, 2), (math.pi, 0, 0), 2, white)
    plane(sc, "back", (0, 1, 1), (math.pi / 2, 0, 0), 2, white)
    plane(sc, "left", (-1, 0, 1), (0, math.pi / 2, 0), 2, red)
    plane(sc, "right", (1, 0, 1), (0, -math.pi / 2, 0), 2, green)
    bpy.ops.mesh.primitive_cube_add(size=0.6, location=(0.35, 0.2, 0.3),
                                    rotation=(0, 0, math.radians(-18)))
    bpy.context.active_object.data.materials.append(white)
    bpy.ops.mesh.primitive_cube_add(size=0.6, location=(-0.35, 0.35, 0.6),
                                    rotation=(0, 0, math.radians(20)))
    bpy.context.active_object.scale.z = 2
    bpy.context.active_object.data.materials.append(white)
    light(sc, "AREA", 60.0, (0, 0, 1.98), size=0.5)
    camera(sc, (0, -3.9, 1), (0, 0, 1), lens=38)


def materials():
    """Principled BSDFs in a row on a grey floor, lit by a sun and a blue-grey world."""
    sc = reset()
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0.5, 0.6, 0.8, 1)
    bg.inputs["Strength"].default_value = 0.6
    sc.world = world
    plane(sc, "floor", (0, 0, 0), (0, 0, 0), 20, material("floor", (0.4, 0.4, 0.4)))
    specs = [
        ("rough plastic", (0.8, 0.2, 0.1), {"Roughness": 0.6}),
        ("gold", (1.0, 0.77, 0.34), {"Metallic": 1.0, "Roughness": 0.25}),
        ("clearcoat", (0.05, 0.2, 0.6), {"Roughness": 0.5, "Clearcoat": 1.0,
                                          "Clearcoat Roughness": 0.05}),
        ("sheen", (0.3, 0.5, 0.2), {"Roughness": 0.8, "Sheen": 1.0}),
        ("glass", (1.0, 1.0, 1.0), {"Transmission": 1.0, "Roughness": 0.0, "IOR": 1.45}),
    ]
    for i, (name, colour, inputs) in enumerate(specs):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.45, location=(-2 + i, 0, 0.45),
                                             segments=64, ring_count=32)
        bpy.ops.object.shade_smooth()
        bpy.context.active_object.data.materials.append(material(name, colour, **inputs))
    light(sc, "SUN", 3.0, (0, 0, 5), (math.radians(40), 0, math.radians(30)))
    camera(sc, (0, -5.5, 2.2), (0, 0, 0.4), lens=40)


def lights():
    """A monkey on a floor under a spot, a point and a disk light, and a wall behind."""
    sc = reset()
    black_world(sc)
    grey = material("grey", (0.6, 0.6, 0.6), Roughness=0.7)
    plane(sc, "floor", (0, 0, 0), (0, 0, 0), 10, grey)
    plane(sc, "wall", (0, 2, 2.5), (math.pi / 2, 0, 0), 10, grey)
    bpy.ops.mesh.primitive_monkey_add(location=(0, 0, 0.9), rotation=(math.radians(-20), 0, 0))
    bpy.ops.object.modifier_add(type="SUBSURF")
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(material("skin", (0.8, 0.5, 0.3),
                                                             Roughness=0.5))
    light(sc, "SPOT", 800.0, (2, -2, 4), (math.radians(40), 0, math.radians(45)),
          spot_size=math.radians(50), spot_blend=0.3, shadow_soft_size=0.0, color=(1, 0.9, 0.8))
    light(sc, "POINT", 150.0, (-2, -1, 2.5), shadow_soft_size=0.0, color=(0.6, 0.7, 1.0))
    light(sc, "AREA", 100.0, (0, -2, 3), (math.radians(40), 0, 0), shape="DISK", size=1.0)
    camera(sc, (0, -5, 2), (0, 0, 0.9), lens=40)


SCENES = {"cornell": cornell, "materials": materials, "lights": lights}

if __name__ == "__main__":
    args = sys.argv[sys.argv.index("--") + 1:]
    DIFFUSE = "--diffuse" in args
    name, out = [a for a in args if a != "--diffuse"][:2]
    SCENES[name]()
    bpy.ops.wm.save_as_mainfile(filepath=out)
