"""The Blender add-on, inside headless Blender (ctest's blender.addon):

    blender -b --factory-startup --python-exit-code 1 --python blender/tests/test_addon.py \
        -- BUILD/blender

Scenes are built with Blender's Python; translations are checked in the glTF the add-on
writes, renders in the Render Result and the image file Blender writes.
"""

import json
import math
import os
import sys
import tempfile
import time
import unittest

import bpy
import numpy as np

sys.path.insert(0, sys.argv[sys.argv.index("--") + 1])
import glint_blender  # noqa: E402
from glint_blender import engine as glint_engine  # noqa: E402
from glint_blender.export import Exporter  # noqa: E402

glint_blender.register()


def empty_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = "GLINT"
    sc.render.resolution_x, sc.render.resolution_y = 64, 48
    sc.render.resolution_percentage = 100
    sc.glint.samples = 4
    sc.glint.use_denoising = False
    return sc


def add_camera(sc, location=(0, -6, 1), rotation=(math.radians(85), 0, 0)):
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.location, cam.rotation_euler = location, rotation
    sc.collection.objects.link(cam)
    sc.camera = cam
    return cam


def add_light(sc, kind, energy, **props):
    data = bpy.data.lights.new(kind.title(), kind)
    data.energy = energy
    for k, v in props.items():
        setattr(data, k, v)
    obj = bpy.data.objects.new(data.name, data)
    obj.location = (0, 0, 4)
    sc.collection.objects.link(obj)
    return obj


def principled(name, **inputs):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes["Principled BSDF"]
    for k, v in inputs.items():
        node.inputs[k].default_value = v
    return mat


def translate():
    """The glTF the add-on writes for the scene, and its warnings."""
    warnings = []
    folder = tempfile.mkdtemp(prefix="glint-blender-test-")
    out = Exporter(bpy.context.evaluated_depsgraph_get(), folder, warnings.append).run()
    with open(out.path) as f:
        return json.load(f), out, warnings


def render_pixels(sc):
    """Renders through bpy.ops.render.render; the Render Result's pixels (rows from the top)."""
    path = os.path.join(tempfile.mkdtemp(prefix="glint-blender-render-"), "out.exr")
    sc.render.image_settings.file_format = "OPEN_EXR"
    sc.render.image_settings.color_depth = "32"
    sc.view_settings.view_transform = "Standard"
    sc.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    w, h = img.size
    px = np.empty(w * h * img.channels, np.float32)
    img.pixels.foreach_get(px)
    bpy.data.images.remove(img)
    return px.reshape(h, w, -1)[::-1]


class Registration(unittest.TestCase):
    def test_the_engine_and_its_settings_are_registered(self):
        self.assertIn("GLINT", [e.bl_idname for e in bpy.types.RenderEngine.__subclasses__()])
        sc = empty_scene()
        self.assertEqual(sc.glint.max_bounces, 12)  # Cycles' defaults
        self.assertEqual(glint_engine.bounce_limits(sc.glint),
                         "total=13,diffuse=5,glossy=5,transmission=13,volume=1")
        # Blender's own panels (format, output) open to Glint, and Glint's sampling panel.
        self.assertIn("GLINT", bpy.types.RENDER_PT_format.COMPAT_ENGINES)
        self.assertTrue(hasattr(bpy.types, "GLINT_PT_sampling"))


class Meshes(unittest.TestCase):
    def test_modifiers_are_applied_and_slots_become_primitives(self):
        sc = empty_scene()
        add_camera(sc)
        bpy.ops.mesh.primitive_cube_add()
        cube = bpy.context.active_object
        cube.modifiers.new("sub", "SUBSURF").levels = 1
        cube.data.materials.append(principled("Red", **{"Base Color": (1, 0, 0, 1)}))
        cube.data.materials.append(principled("Blue", **{"Base Color": (0, 0, 1, 1)}))
        for i, p in enumerate(cube.data.polygons):
            p.material_index = i % 2
        doc, out, _ = translate()
        self.assertEqual(out.triangles, 6 * 4 * 2)  # subdivided once: 24 quads
        prims = doc["meshes"][0]["primitives"]
        self.assertEqual(len(prims), 2)
        names = {doc["materials"][p["material"]]["name"] for p in prims}
        self.assertEqual(names, {"Red", "Blue"})
        self.assertIn("TEXCOORD_0", prims[0]["attributes"])
        self.assertIn("NORMAL", prims[0]["attributes"])

    def test_objects_sharing_a_mesh_are_instances_of_one_glTF_mesh(self):
        sc = empty_scene()
        add_camera(sc)
        bpy.ops.mesh.primitive_uv_sphere_add()
        first = bpy.context.active_object
        for x in range(1, 4):
            copy = first.copy()  # linked duplicate: the same mesh data
            copy.location.x = 3 * x
            sc.collection.objects.link(copy)
        doc, out, _ = translate()
        self.assertEqual(len(doc["meshes"]), 1)
        self.assertEqual(out.instances, 4)
        placed = [n for n in doc["nodes"] if "mesh" in n]
        self.assertEqual(len(placed), 4)
        self.assertEqual(sorted(round(n["matrix"][12]) for n in placed), [0, 3, 6, 9])

    def test_geometry_node_instances_stay_instances(self):
        sc = empty_scene()
        add_camera(sc)
        bpy.ops.mesh.primitive_grid_add(x_subdivisions=10, y_subdivisions=10, size=10)
        grid = bpy.context.active_object
        bpy.ops.mesh.primitive_ico_sphere_add(radius=0.2, location=(0, 0, 20))
        ball = bpy.context.active_object
        mod = grid.modifiers.new("scatter", "NODES")
        tree = bpy.data.node_groups.new("scatter", "GeometryNodeTree")
        tree.inputs.new("NodeSocketGeometry", "Geometry")
        tree.outputs.new("NodeSocketGeometry", "Geometry")
        nodes, links = tree.nodes, tree.links
        inp, outp = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
        on_points = nodes.new("GeometryNodeInstanceOnPoints")
        info = nodes.new("GeometryNodeObjectInfo")
        info.inputs["Object"].default_value = ball
        links.new(inp.outputs[0], on_points.inputs["Points"])
        links.new(info.outputs["Geometry"], on_points.inputs["Instance"])
        links.new(on_points.outputs[0], outp.inputs[0])
        mod.node_group = tree
        doc, out, _ = translate()
        # Each grid point an instance of the ball's one mesh; the ball itself too.
        self.assertEqual(out.instances, len(grid.data.vertices) + 1)
        self.assertLessEqual(len(doc["meshes"]), 2)
        self.assertLess(out.triangles, 2 * 20 * 10)


class Materials(unittest.TestCase):
    def setUp(self):
        add_camera(empty_scene())

    def material_of(self, mat):
        """The glTF material of `mat` on a plane (the only mesh), and the warnings."""
        for obj in [o for o in bpy.data.objects if o.type == "MESH"]:
            bpy.data.objects.remove(obj)
        bpy.ops.mesh.primitive_plane_add()
        bpy.context.active_object.data.materials.append(mat)
        doc, _, warnings = translate()
        return next(m for m in doc["materials"] if m["name"] == mat.name), warnings

    def test_principled_inputs_land_in_gltf_and_its_extensions(self):
        m, warnings = self.material_of(principled(
            "P", **{"Base Color": (0.2, 0.4, 0.6, 1), "Metallic": 0.3, "Roughness": 0.7,
                    "Clearcoat": 0.5, "Sheen": 0.4, "Anisotropic": 0.6,
                    "Emission": (1, 0.5, 0, 1), "Emission Strength": 4.0, "Alpha": 0.5}))
        pbr = m["pbrMetallicRoughness"]
        self.assertAlmostEqual(pbr["baseColorFactor"][1], 0.4, places=5)
        self.assertAlmostEqual(pbr["baseColorFactor"][3], 0.5, places=5)
        self.assertAlmostEqual(pbr["metallicFactor"], 0.3, places=5)
        self.assertAlmostEqual(pbr["roughnessFactor"], 0.7, places=5)
        ext = m["extensions"]
        self.assertAlmostEqual(ext["KHR_materials_emissive_strength"]["emissiveStrength"], 4.0)
        self.assertEqual(m["emissiveFactor"], [1.0, 0.5, 0.0])
        self.assertAlmostEqual(ext["KHR_materials_clearcoat"]["clearcoatFactor"], 0.5)
        self.assertIn("KHR_materials_sheen", ext)
        self.assertAlmostEqual(ext["KHR_materials_anisotropy"]["anisotropyStrength"], 0.6,
                               places=5)
        self.assertAlmostEqual(ext["KHR_materials_ior"]["ior"], 1.5, places=5)  # Specular 0.5
        self.assertEqual(m["alphaMode"], "BLEND")
        self.assertEqual(warnings, [])

    def test_transmission_is_a_refracting_volume_with_blenders_ior(self):
        m, _ = self.material_of(principled("Glass", **{"Transmission": 1.0, "IOR": 1.33,
                                                       "Roughness": 0.0}))
        ext = m["extensions"]
        self.assertEqual(ext["KHR_materials_transmission"]["transmissionFactor"], 1.0)
        self.assertAlmostEqual(ext["KHR_materials_ior"]["ior"], 1.33, places=5)
        self.assertIn("KHR_materials_volume", ext)

    def test_shader_nodes_other_than_principled(self):
        def tree(kind, **inputs):
            mat = bpy.data.materials.new(kind)
            mat.use_nodes = True
            nodes = mat.node_tree.nodes
            nodes.remove(nodes["Principled BSDF"])
            node = nodes.new(kind)
            for k, v in inputs.items():
                node.inputs[k].default_value = v
            mat.node_tree.links.new(node.outputs[0], nodes["Material Output"].inputs["Surface"])
            return mat, node

        m, _ = self.material_of(tree("ShaderNodeBsdfDiffuse", Color=(0.5, 0.25, 0.125, 1))[0])
        self.assertEqual(m["pbrMetallicRoughness"]["roughnessFactor"], 1.0)
        self.assertEqual(m["extensions"]["KHR_materials_specular"]["specularFactor"], 0.0)
        m, _ = self.material_of(tree("ShaderNodeBsdfGlossy", Roughness=0.2)[0])
        self.assertEqual(m["pbrMetallicRoughness"]["metallicFactor"], 1.0)
        m, _ = self.material_of(tree("ShaderNodeBsdfGlass", IOR=1.6)[0])
        self.assertAlmostEqual(m["extensions"]["KHR_materials_ior"]["ior"], 1.6, places=5)
        m, _ = self.material_of(tree("ShaderNodeEmission", Color=(1, 1, 1, 1), Strength=7.0)[0])
        self.assertAlmostEqual(m["extensions"]["KHR_materials_emissive_strength"]
                               ["emissiveStrength"], 7.0)
        # A node with no Glint lobe: its colour as a diffuse surface, and a warning naming it.
        m, warnings = self.material_of(tree("ShaderNodeBsdfToon", Color=(0, 1, 0, 1))[0])
        self.assertEqual(m["pbrMetallicRoughness"]["baseColorFactor"][:3], [0.0, 1.0, 0.0])
        self.assertTrue(any("Toon" in w for w in warnings), warnings)

    def test_mix_of_emission_and_transparency(self):
        mat = principled("Mix", **{"Base Color": (1, 1, 1, 1)})
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        mix = nodes.new("ShaderNodeMixShader")
        mix.inputs[0].default_value = 0.25
        transparent = nodes.new("ShaderNodeBsdfTransparent")
        links.new(nodes["Principled BSDF"].outputs[0], mix.inputs[1])
        links.new(transparent.outputs[0], mix.inputs[2])
        links.new(mix.outputs[0], nodes["Material Output"].inputs["Surface"])
        m, _ = self.material_of(mat)
        self.assertAlmostEqual(m["pbrMetallicRoughness"]["baseColorFactor"][3], 0.75)
        self.assertEqual(m["alphaMode"], "BLEND")

    def test_image_textures_normal_maps_and_mapping(self):
        folder = tempfile.mkdtemp(prefix="glint-blender-tex-")
        img = bpy.data.images.new("checks", 8, 8)
        img.filepath_raw = os.path.join(folder, "checks.png")
        img.file_format = "PNG"
        img.save()
        mat = principled("Textured")
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        tex = nodes.new("ShaderNodeTexImage")
        tex.image = img
        mapping = nodes.new("ShaderNodeMapping")
        mapping.inputs["Scale"].default_value = (2, 3, 1)
        mapping.inputs["Location"].default_value = (0.5, 0.25, 0)
        links.new(mapping.outputs[0], tex.inputs["Vector"])
        links.new(tex.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
        ntex = nodes.new("ShaderNodeTexImage")
        ntex.image = img
        nmap = nodes.new("ShaderNodeNormalMap")
        nmap.inputs["Strength"].default_value = 0.5
        links.new(ntex.outputs["Color"], nmap.inputs["Color"])
        links.new(nmap.outputs[0], nodes["Principled BSDF"].inputs["Normal"])
        m, warnings = self.material_of(mat)
        info = m["pbrMetallicRoughness"]["baseColorTexture"]
        t = info["extensions"]["KHR_texture_transform"]
        self.assertEqual(t["scale"], [2.0, 3.0])
        # Blender's v up, glTF's down: offset (lu, 1 - lv - sv) with no rotation.
        self.assertAlmostEqual(t["offset"][0], 0.5)
        self.assertAlmostEqual(t["offset"][1], 1 - 0.25 - 3)
        self.assertAlmostEqual(m["normalTexture"]["scale"], 0.5)
        self.assertTrue(any("normal map in colour space" in w for w in warnings), warnings)

    def test_a_missing_texture_is_a_warning_and_the_render_goes_on(self):
        sc = bpy.context.scene
        add_light(sc, "SUN", 3.0)
        bpy.ops.mesh.primitive_plane_add(size=20)
        mat = principled("Lost", **{"Base Color": (0.5, 0.5, 0.5, 1)})
        tex = mat.node_tree.nodes.new("ShaderNodeTexImage")
        tex.image = bpy.data.images.new("lost", 4, 4)
        tex.image.source = "FILE"
        tex.image.filepath = "/nonexistent/lost.png"
        mat.node_tree.links.new(tex.outputs["Color"],
                                mat.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
        bpy.context.active_object.data.materials.append(mat)
        _, _, warnings = translate()
        self.assertTrue(any("lost.png" in w for w in warnings), warnings)
        px = render_pixels(sc)
        self.assertGreater(float(px[..., :3].mean()), 0.05)  # the plane, lit, in grey


class Lights(unittest.TestCase):
    def test_units_as_cycles_reads_blenders(self):
        sc = empty_scene()
        add_camera(sc)
        add_light(sc, "POINT", 100.0)
        add_light(sc, "SPOT", 50.0, spot_size=math.radians(60), spot_blend=0.5)
        add_light(sc, "SUN", 3.0)
        area = add_light(sc, "AREA", 20.0, shape="RECTANGLE", size=2.0, size_y=0.5)
        area.scale = (2, 1, 1)
        add_light(sc, "AREA", 10.0, shape="DISK", size=1.0)
        doc, _, _ = translate()
        lights = {l["type"]: l for l in doc["extensions"]["KHR_lights_punctual"]["lights"]}
        self.assertAlmostEqual(lights["point"]["intensity"], 100 / (4 * math.pi), places=5)
        self.assertAlmostEqual(lights["spot"]["intensity"], 50 / (4 * math.pi), places=5)
        self.assertAlmostEqual(lights["spot"]["spot"]["outerConeAngle"], math.radians(30))
        cos_inner = math.cos(math.radians(30)) + (1 - math.cos(math.radians(30))) * 0.5
        self.assertAlmostEqual(lights["spot"]["spot"]["innerConeAngle"],
                               math.acos(cos_inner) * 0.999, places=5)
        self.assertAlmostEqual(lights["directional"]["intensity"], 3.0)
        # Area lights: emitting surfaces of radiance P / (4 A) (Cycles'), A with the scale.
        emitters = [m for m in doc["materials"] if m["name"].endswith("(area light)")]
        strengths = sorted(m["extensions"]["KHR_materials_emissive_strength"]
                           ["emissiveStrength"] for m in emitters)
        disk_area = 0.5 * 64 * 0.25 * math.sin(2 * math.pi / 64)
        for m in emitters:  # one-sided, and hidden from the camera as Cycles hides them
            self.assertFalse(m["doubleSided"])
            self.assertEqual(m["extras"], {"glint": {"camera": False}})
        self.assertAlmostEqual(strengths[0], 20 / (4 * 2.0 * 0.5 * 2), places=4)
        self.assertAlmostEqual(strengths[1], 10 / (4 * disk_area), places=4)


class World(unittest.TestCase):
    def test_colour_and_environment_texture_with_rotation(self):
        sc = empty_scene()
        add_camera(sc)
        world = bpy.data.worlds.new("W")
        world.use_nodes = True
        sc.world = world
        bg = world.node_tree.nodes["Background"]
        bg.inputs["Color"].default_value = (0.1, 0.2, 0.3, 1)
        bg.inputs["Strength"].default_value = 2.0
        _, out, _ = translate()
        self.assertEqual(out.environment.strength, 2.0)
        np.testing.assert_allclose(out.environment.pixels[0, 0], [0.1, 0.2, 0.3], rtol=1e-6)
        img = bpy.data.images.new("sky", 16, 8, float_buffer=True)
        px = np.zeros((8, 16, 4), np.float32)
        px[-1, :, 0] = 5.0  # Blender's top row (its last)
        img.pixels.foreach_set(px.reshape(-1))
        env = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
        env.image = img
        mapping = world.node_tree.nodes.new("ShaderNodeMapping")
        mapping.inputs["Rotation"].default_value = (0, 0, math.radians(30))
        world.node_tree.links.new(mapping.outputs[0], env.inputs["Vector"])
        world.node_tree.links.new(env.outputs[0], bg.inputs["Color"])
        _, out, _ = translate()
        self.assertEqual(out.environment.pixels.shape, (8, 16, 3))
        self.assertEqual(float(out.environment.pixels[0, 3, 0]), 5.0)  # Glint's row 0 on top
        self.assertAlmostEqual(out.environment.rotation, -30.0, places=4)


class Camera(unittest.TestCase):
    def test_sensor_fit_orthographic_and_depth_of_field(self):
        sc = empty_scene()
        sc.render.resolution_x, sc.render.resolution_y = 200, 100
        cam = add_camera(sc)
        cam.data.lens, cam.data.sensor_width = 50, 36
        doc, _, _ = translate()
        p = doc["cameras"][0]["perspective"]
        self.assertAlmostEqual(p["aspectRatio"], 2.0)
        self.assertAlmostEqual(math.tan(p["yfov"] / 2), 18 / 50 / 2, places=6)
        cam.data.sensor_fit = "VERTICAL"
        cam.data.sensor_height = 24
        doc, _, _ = translate()
        self.assertAlmostEqual(math.tan(doc["cameras"][0]["perspective"]["yfov"] / 2), 12 / 50,
                               places=6)
        cam.data.dof.use_dof = True
        cam.data.dof.aperture_fstop = 2.0
        cam.data.dof.focus_distance = 3.0
        _, out, _ = translate()
        self.assertAlmostEqual(out.lens.aperture, 0.05 / 4)
        self.assertAlmostEqual(out.lens.focus, 3.0)
        cam.data.sensor_fit = "AUTO"
        cam.data.type = "ORTHO"
        cam.data.ortho_scale = 4
        doc, _, _ = translate()
        o = doc["cameras"][0]["orthographic"]
        self.assertAlmostEqual(o["xmag"], 2.0)
        self.assertAlmostEqual(o["ymag"], 1.0)


class Rendering(unittest.TestCase):
    def lit_scene(self):
        sc = empty_scene()
        add_camera(sc, location=(0, -5, 2), rotation=(math.radians(70), 0, 0))
        add_light(sc, "AREA", 400.0, size=2.0)
        bpy.ops.mesh.primitive_plane_add(size=10)
        bpy.ops.mesh.primitive_monkey_add(location=(0, 0, 1))
        return sc

    def test_a_render_fills_the_result_and_its_passes(self):
        sc = self.lit_scene()
        bpy.context.view_layer.use_pass_z = True
        sc.glint.denoising_passes = True
        sc.glint.use_denoising = True
        written = {}
        original = glint_engine.GlintRenderEngine._write

        def spy(engine_self, scene, result, image, passes):
            original(engine_self, scene, result, image, passes)
            for p in result.layers[0].passes:
                written[p.name] = np.array(p.rect[:]).reshape(-1, p.channels)

        glint_engine.GlintRenderEngine._write = spy
        try:
            px = render_pixels(sc)
        finally:
            glint_engine.GlintRenderEngine._write = original
        self.assertEqual(px.shape, (48, 64, 4))
        self.assertGreater(float(px[..., :3].mean()), 0.01)
        self.assertTrue(np.isfinite(px).all())
        self.assertLessEqual({"Combined", "Depth", "Denoising Normal", "Denoising Albedo"},
                             set(written))
        depth = written["Depth"][:, 0]
        self.assertTrue(((depth > 1) & (depth < 20)).any())  # the plane, metres away
        normal = written["Denoising Normal"]
        # The plane faces Blender's +z: normals back in Blender's axes.
        self.assertGreater(float(np.median(normal[:, 2])), 0.9)

    def test_escape_stops_a_long_render_keeping_the_rounds_done(self):
        sc = self.lit_scene()
        sc.render.resolution_x, sc.render.resolution_y = 160, 120
        sc.glint.samples = 65536
        start = [None]
        stop_after = 1.5
        original = glint_engine.GlintRenderEngine.should_stop

        def test_break(engine_self):
            if start[0] is None:
                start[0] = time.perf_counter()
            return time.perf_counter() - start[0] > stop_after

        glint_engine.GlintRenderEngine.should_stop = test_break
        try:
            t0 = time.perf_counter()
            px = render_pixels(sc)
            seconds = time.perf_counter() - t0
        finally:
            glint_engine.GlintRenderEngine.should_stop = original
        # Stopped soon after Esc (a wide margin for a loaded machine), with the rounds' image.
        self.assertLess(seconds, stop_after + 10.0)
        self.assertGreater(float(px[..., :3].mean()), 0.01)


if __name__ == "__main__":
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
