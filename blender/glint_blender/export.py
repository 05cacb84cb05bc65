"""The evaluated depsgraph as what Glint renders: a glTF file, an environment and a camera lens.

Blender is z-up, glTF (and Glint) y-up: one root node turns the scene (Blender (x, y, z) is
Glint's (x, z, -y), as Glint's environment map mapping expects). Every object keeps its
Blender matrix below it. Units, as Cycles reads Blender's (docs/blender.md):
  point and spot lights of P watts: P / (4 pi) W/sr (glTF's intensity, which Glint takes as
  radiant intensity); suns of S W/m^2: S; area lights of P watts and area A: emitting
  surfaces of radiance P / (4 A) (measured in Cycles 3.4: pi / 4 of a Lambertian emitter of P
  watts), one-sided (single-sided glTF emitters emit from their front
  only), along the light's -z, hidden from the camera as Cycles hides them.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Callable, Optional

import bpy
import numpy as np
from mathutils import Matrix, Vector

from .gltf_writer import GltfWriter
from .materials import Lobe, MaterialReader, Texture, gltf_material, image_path

# Blender (x, y, z) -> glTF (x, z, -y), column-major.
_Z_UP_TO_Y_UP = [1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1]
_DISK_SEGMENTS = 64


def _columns(m: Matrix) -> list:
    return [float(m[r][c]) for c in range(4) for r in range(4)]


def _unscaled(m: Matrix) -> Matrix:
    loc, rot, _ = m.decompose()
    return Matrix.Translation(loc) @ rot.to_matrix().to_4x4()


@dataclass
class Environment:
    pixels: np.ndarray  # rows x columns x 3, row 0 at the top, linear
    strength: float = 1.0
    rotation: float = 0.0  # degrees about Glint's +y


@dataclass
class Lens:
    aperture: float = 0.0  # radius, metres
    focus: float = 0.0


@dataclass
class Exported:
    path: str
    camera: Optional[str]
    environment: Optional[Environment]
    lens: Optional[Lens]
    size: tuple
    triangles: int = 0
    instances: int = 0
    meshes: int = 0
    warnings: list = field(default_factory=list)


def render_size(scene) -> tuple:
    r = scene.render
    return (max(1, r.resolution_x * r.resolution_percentage // 100),
            max(1, r.resolution_y * r.resolution_percentage // 100))


class Exporter:
    """One translation of a depsgraph into `folder`."""

    def __init__(self, depsgraph, folder: str, warn: Callable[[str], None]) -> None:
        self.depsgraph = depsgraph
        self.scene = depsgraph.scene
        self.folder = folder
        self.warnings: list[str] = []
        self._warned: set[str] = set()
        self._warn_out = warn
        self.gltf = GltfWriter()
        self.root = self.gltf.add_node({"name": "Blender z-up", "matrix": _Z_UP_TO_Y_UP,
                                        "children": []}, root=True)
        self.materials = MaterialReader(self.warn)
        self._material_index: dict = {}
        self._mesh_index: dict = {}
        self._images: dict = {}
        self._default_material: Optional[int] = None
        self.triangles = 0
        self.instances = 0
        self._lens: Optional[Lens] = None  # the camera's depth of field, if it has one

    def warn(self, text: str) -> None:
        if text not in self._warned:
            self._warned.add(text)
            self.warnings.append(text)
            self._warn_out(text)

    def _child(self, node: dict) -> int:
        index = self.gltf.add_node(node)
        self.gltf.doc["nodes"][self.root]["children"].append(index)
        return index

    # ---- the whole scene ------------------------------------------------------------------

    def run(self) -> Exported:
        size = render_size(self.scene)
        camera = self._camera(size)
        for inst in self.depsgraph.object_instances:
            obj = inst.object
            if not inst.is_instance and not inst.show_self:
                continue
            matrix = inst.matrix_world.copy()
            if obj.type in ("MESH", "CURVE", "SURFACE", "META", "FONT", "CURVES"):
                self._place_mesh(obj, matrix)
            elif obj.type == "LIGHT":
                self._light(obj, matrix)
            elif obj.type == "VOLUME":
                self.warn(f"volume object '{obj.name}': OpenVDB volume objects are not read yet")
        environment = self._world()
        path = self.gltf.write(self.folder)
        return Exported(path=path, camera=camera, environment=environment,
                        lens=self._lens, size=size, triangles=self.triangles,
                        instances=self.instances, meshes=len(self._mesh_index),
                        warnings=self.warnings)

    # ---- meshes and materials -------------------------------------------------------------

    def _place_mesh(self, obj, matrix: Matrix) -> None:
        slots = tuple(s.material.name if s.material else "" for s in obj.material_slots)
        data = obj.data
        key = (data.as_pointer() if data is not None else obj.as_pointer(), slots,
               obj.as_pointer() if obj.type != "MESH" else 0)
        index = self._mesh_index.get(key)
        if index is None:
            index = self._mesh(obj)
            self._mesh_index[key] = index
        if index < 0:
            return
        self._child({"name": obj.name, "mesh": index, "matrix": _columns(matrix)})
        self.instances += 1

    def _mesh(self, obj) -> int:
        try:
            me = obj.to_mesh()
        except RuntimeError:
            me = None
        if me is None:
            return -1
        try:
            return self._mesh_of(obj, me)
        finally:
            obj.to_mesh_clear()

    def _mesh_of(self, obj, me) -> int:
        me.calc_loop_triangles()
        nt = len(me.loop_triangles)
        if nt == 0:
            return -1
        if hasattr(me, "calc_normals_split"):
            me.calc_normals_split()
        nv, nl = len(me.vertices), len(me.loops)
        co = np.empty(nv * 3, np.float32)
        me.vertices.foreach_get("co", co)
        loop_vertex = np.empty(nl, np.int32)
        me.loops.foreach_get("vertex_index", loop_vertex)
        normals = np.empty(nl * 3, np.float32)
        me.loops.foreach_get("normal", normals)
        tri = np.empty(nt * 3, np.uint32)
        me.loop_triangles.foreach_get("loops", tri)
        material = np.empty(nt, np.int32)
        me.loop_triangles.foreach_get("material_index", material)
        positions = co.reshape(-1, 3)[loop_vertex]
        attributes = {
            "POSITION": self.gltf.accessor(positions, target=34962, bounds=True),
            "NORMAL": self.gltf.accessor(normals.reshape(-1, 3), target=34962),
        }
        uv_names = []
        render_uv = next((u for u in me.uv_layers if u.active_render), None)
        layers = ([render_uv] if render_uv else []) + [u for u in me.uv_layers
                                                      if u is not render_uv][:1]
        for i, layer in enumerate(layers):
            uv = np.empty(nl * 2, np.float32)
            layer.data.foreach_get("uv", uv)
            uv = uv.reshape(-1, 2)
            uv[:, 1] = 1.0 - uv[:, 1]  # glTF's v runs down the image
            attributes[f"TEXCOORD_{i}"] = self.gltf.accessor(uv, target=34962)
            uv_names.append(layer.name)
        primitives = []
        tri = tri.reshape(-1, 3)
        slots = obj.material_slots
        for m in np.unique(material):
            faces = tri[material == m]
            prim = {"attributes": attributes,
                    "indices": self.gltf.accessor(faces.reshape(-1), target=34963)}
            mat = slots[m].material if 0 <= m < len(slots) else None
            prim["material"] = self._material(mat, uv_names)
            primitives.append(prim)
        self.triangles += nt
        return self.gltf.add("meshes", {"name": obj.data.name if obj.data else obj.name,
                                        "primitives": primitives})

    def _material(self, mat, uv_names: list) -> int:
        key = (mat.name if mat else "", tuple(uv_names))
        index = self._material_index.get(key)
        if index is not None:
            return index
        if mat is None:
            lobe = Lobe()
            two_sided, blend, cutoff, name = True, "OPAQUE", 0.5, "default"
        else:
            name = mat.name
            if mat.use_nodes and mat.node_tree:
                out = _active_output(mat.node_tree, "OUTPUT_MATERIAL")
                lobe = self.materials.shader(out.inputs["Surface"] if out else None)
                if out is not None and out.inputs["Volume"].is_linked:
                    self.warn(f"material '{mat.name}': volume shaders are not read yet")
            else:
                lobe = Lobe(base=tuple(mat.diffuse_color[:3]), metallic=mat.metallic,
                            roughness=mat.roughness)
            two_sided = True  # Cycles shades both faces of a mesh alike
            blend = mat.blend_method
            cutoff = mat.alpha_threshold
        for w in lobe.warnings:
            self.warn(f"material '{name}': {w}")

        def texture_info(tex: Texture, role: str) -> Optional[dict]:
            return self._texture(tex, role, uv_names)

        index = self.gltf.add("materials", gltf_material(lobe, name, texture_info, two_sided,
                                                         blend, cutoff, self.gltf))
        self._material_index[key] = index
        return index

    def _texture(self, tex: Texture, role: str, uv_names: list) -> Optional[dict]:
        image = tex.image
        colour = image.colorspace_settings.name
        linear_role = role == "normal"
        if linear_role and colour not in ("Non-Color", "Linear", "Raw"):
            self.warn(f"image '{image.name}' is a normal map in colour space '{colour}': "
                      "read as Non-Color")
        if not linear_role and colour in ("Non-Color", "Raw"):
            self.warn(f"image '{image.name}' is a colour in colour space '{colour}': read as "
                      "sRGB, as glTF's colour textures are")
        key = (image.name, tex.clamp)
        texture = self._images.get(key)
        if texture is None:
            path = image_path(image, self.folder, self.warn)
            if path is None:
                return None
            link = os.path.join(self.folder, f"t{len(self._images)}{os.path.splitext(path)[1]}")
            if os.path.abspath(path) != os.path.abspath(link):
                os.symlink(os.path.abspath(path), link)
            source = self.gltf.add("images", {"uri": os.path.basename(link)})
            wrap = 33071 if tex.clamp else 10497
            sampler = self.gltf.add("samplers", {"wrapS": wrap, "wrapT": wrap})
            texture = self.gltf.add("textures", {"source": source, "sampler": sampler})
            self._images[key] = texture
        info: dict = {"index": texture}
        if tex.uv_map and tex.uv_map in uv_names:
            info["texCoord"] = uv_names.index(tex.uv_map)
        elif tex.uv_map:
            self.warn(f"UV map '{tex.uv_map}' is not the mesh's render or second UV map: the "
                      "render UV map is used")
        if tex.transform:
            info["extensions"] = {"KHR_texture_transform": dict(tex.transform)}
            self.gltf.use_extension("KHR_texture_transform")
        return info

    # ---- lights ---------------------------------------------------------------------------

    def _light(self, obj, matrix: Matrix) -> None:
        light = obj.data
        colour = [float(c) for c in light.color]
        if light.type == "AREA":
            self._area_light(obj, light, matrix, colour)
            return
        entry: dict = {"name": obj.name, "color": colour}
        if light.type == "SUN":
            entry["type"] = "directional"
            entry["intensity"] = float(light.energy)
            if light.angle > 0.0175:  # a degree (Blender's default is 0.53)
                self.warn(f"sun '{obj.name}': its angle ({math.degrees(light.angle):.3g} "
                          "degrees) is not read: a sharp shadow")
        else:
            entry["type"] = "point" if light.type == "POINT" else "spot"
            entry["intensity"] = float(light.energy) / (4 * math.pi)
            if light.type == "SPOT":
                outer = min(float(light.spot_size) / 2, math.pi / 2)
                cos_outer = math.cos(outer)
                cos_inner = cos_outer + (1 - cos_outer) * float(light.spot_blend)
                entry["spot"] = {"innerConeAngle": math.acos(min(cos_inner, 1.0)) * 0.999,
                                 "outerConeAngle": outer}
        index = self.gltf.add_light(entry)
        self._child({"name": obj.name, "matrix": _columns(_unscaled(matrix)),
                     "extensions": {"KHR_lights_punctual": {"light": index}}})

    def _area_light(self, obj, light, matrix: Matrix, colour: list) -> None:
        sx = float(light.size)
        sy = float(light.size_y) if light.shape in ("RECTANGLE", "ELLIPSE") else sx
        if light.shape in ("SQUARE", "RECTANGLE"):
            a, b = sx / 2, sy / 2
            ring = np.array([[-a, -b, 0], [a, -b, 0], [a, b, 0], [-a, b, 0]], np.float32)
            local_area = sx * sy
        else:
            t = np.linspace(0, 2 * math.pi, _DISK_SEGMENTS, endpoint=False)
            ring = np.stack([sx / 2 * np.cos(t), sy / 2 * np.sin(t), 0 * t], -1).astype(
                np.float32)
            # The polygon's area, so that the power is Blender's.
            local_area = 0.5 * _DISK_SEGMENTS * (sx / 2) * (sy / 2) * math.sin(
                2 * math.pi / _DISK_SEGMENTS)
        scale = matrix.to_scale()
        area = local_area * abs(scale[0] * scale[1])
        if area <= 0:
            return
        radiance = float(light.energy) / (4 * area)  # Cycles' (measured: docs/blender.md)
        positions = np.concatenate([np.zeros((1, 3), np.float32), ring])
        n = len(ring)
        # A fan around the centre, front faces towards the light's -z.
        faces = np.array([[0, 1 + (i + 1) % n, 1 + i] for i in range(n)], np.uint32)
        normals = np.tile(np.array([[0, 0, -1]], np.float32), (n + 1, 1))
        emission = [c * radiance for c in colour]
        peak = max(emission)
        mat = {"name": f"{obj.name} (area light)", "doubleSided": False,
               "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0,
                                        "roughnessFactor": 1},
               "emissiveFactor": [e / peak for e in emission] if peak > 0 else [0, 0, 0],
               "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": peak},
                              "KHR_materials_specular": {"specularFactor": 0}},
               # Cycles does not show area lights to the camera (reflections see them).
               "extras": {"glint": {"camera": False}}}
        self.gltf.use_extension("KHR_materials_emissive_strength")
        self.gltf.use_extension("KHR_materials_specular")
        material = self.gltf.add("materials", mat)
        mesh = self.gltf.add("meshes", {"name": obj.name, "primitives": [{
            "attributes": {"POSITION": self.gltf.accessor(positions, bounds=True),
                           "NORMAL": self.gltf.accessor(normals)},
            "indices": self.gltf.accessor(faces.reshape(-1)),
            "material": material}]})
        self._child({"name": obj.name, "mesh": mesh, "matrix": _columns(matrix)})
        if float(getattr(light, "spread", math.pi)) < math.pi - 1e-3:
            self.warn(f"area light '{obj.name}': its spread is not read (180 degrees)")

    # ---- camera ---------------------------------------------------------------------------

    def _camera(self, size: tuple) -> Optional[str]:
        cam_obj = self.scene.camera
        if cam_obj is None:
            self.warn("the scene has no camera: Glint frames it")
            return None
        cam_obj = cam_obj.evaluated_get(self.depsgraph)
        cam = cam_obj.data
        r = self.scene.render
        aspect = (size[0] * r.pixel_aspect_x) / (size[1] * r.pixel_aspect_y)
        entry: dict = {"name": cam_obj.name}
        if cam.type == "ORTHO":
            half = cam.ortho_scale / 2
            fit = _fit(cam.sensor_fit, aspect)
            xmag, ymag = (half, half / aspect) if fit == "HORIZONTAL" else (half * aspect, half)
            entry["type"] = "orthographic"
            entry["orthographic"] = {"xmag": xmag, "ymag": ymag, "znear": max(cam.clip_start, 0),
                                     "zfar": max(cam.clip_end, cam.clip_start + 1e-3)}
        else:
            if cam.type == "PANO":
                self.warn(f"camera '{cam_obj.name}' is panoramic: rendered as a perspective "
                          "camera")
            fit = _fit(cam.sensor_fit, aspect)
            sensor = cam.sensor_height if cam.sensor_fit == "VERTICAL" else cam.sensor_width
            half = sensor / (2 * cam.lens)
            tan_y = half / aspect if fit == "HORIZONTAL" else half
            entry["type"] = "perspective"
            entry["perspective"] = {"yfov": 2 * math.atan(tan_y), "aspectRatio": aspect,
                                    "znear": max(cam.clip_start, 1e-6), "zfar": cam.clip_end}
        if abs(cam.shift_x) > 1e-6 or abs(cam.shift_y) > 1e-6:
            self.warn(f"camera '{cam_obj.name}': its shift is not read")
        if cam.dof.use_dof and cam.type != "ORTHO":
            if cam.dof.focus_object is not None:
                target = cam.dof.focus_object.evaluated_get(self.depsgraph).matrix_world
                view = cam_obj.matrix_world.to_3x3() @ Vector((0, 0, -1))
                focus = (target.translation - cam_obj.matrix_world.translation).dot(
                    view.normalized())
            else:
                focus = cam.dof.focus_distance
            self._lens = Lens(aperture=(cam.lens / 1000) / (2 * cam.dof.aperture_fstop),
                              focus=max(focus, 1e-4))
            if cam.dof.aperture_blades > 0:
                self.warn(f"camera '{cam_obj.name}': a round aperture, not "
                          f"{cam.dof.aperture_blades} blades")
        index = self.gltf.add("cameras", entry)
        self._child({"name": cam_obj.name, "camera": index,
                     "matrix": _columns(_unscaled(cam_obj.matrix_world))})
        return cam_obj.name

    # ---- world ----------------------------------------------------------------------------

    def _world(self) -> Optional[Environment]:
        world = self.scene.world
        if world is None:
            return None
        if not world.use_nodes or world.node_tree is None:
            return _constant(world.color, 1.0)
        out = _active_output(world.node_tree, "OUTPUT_WORLD")
        if out is None or not out.inputs["Surface"].is_linked:
            return None
        node = out.inputs["Surface"].links[0].from_node
        if node.type != "BACKGROUND":
            self.warn(f"world: a {node.bl_label} node, not a Background: the world is black")
            return None
        strength = float(node.inputs["Strength"].default_value)
        colour = node.inputs["Color"]
        if not colour.is_linked:
            return _constant(colour.default_value, strength)
        src = colour.links[0].from_node
        if src.type != "TEX_ENVIRONMENT" or src.image is None:
            self.warn(f"world: its colour comes from a {src.bl_label} node, which Glint does "
                      "not evaluate: the Background's own colour is used")
            return _constant(colour.default_value, strength)
        if src.projection != "EQUIRECTANGULAR":
            self.warn("world: a mirror-ball environment is read as equirectangular")
        rotation = 0.0
        vector = src.inputs.get("Vector")
        if vector is not None and vector.is_linked:
            mapping = vector.links[0].from_node
            if mapping.type == "MAPPING":
                z = math.degrees(mapping.inputs["Rotation"].default_value[2])
                rotation = -z if mapping.vector_type == "POINT" else z
            else:
                self.warn(f"world: the environment's vector comes from a {mapping.bl_label} "
                          "node: not rotated")
        pixels = _image_pixels(src.image)
        if pixels is None:
            self.warn(f"world: image '{src.image.name}' cannot be read: the world is black")
            return None
        return Environment(pixels=pixels, strength=strength, rotation=rotation)


def _fit(sensor_fit: str, aspect: float) -> str:
    if sensor_fit == "AUTO":
        return "HORIZONTAL" if aspect >= 1 else "VERTICAL"
    return sensor_fit


def _active_output(tree, kind: str):
    outputs = [n for n in tree.nodes if n.type == kind]
    for n in outputs:
        if n.is_active_output and n.target in ("ALL", "CYCLES"):
            return n
    return next((n for n in outputs if n.target in ("ALL", "CYCLES")), None)


def _constant(colour, strength: float) -> Optional[Environment]:
    rgb = np.array([max(float(c), 0.0) for c in colour[:3]], np.float32)
    if strength <= 0 or not rgb.any():
        return None
    return Environment(pixels=np.tile(rgb, (1, 2, 1)), strength=strength)


def _image_pixels(image) -> Optional[np.ndarray]:
    w, h = image.size
    if w == 0 or h == 0:
        return None
    px = np.empty(w * h * image.channels, np.float32)
    image.pixels.foreach_get(px)
    px = px.reshape(h, w, image.channels)[::-1, :, :3]
    if not image.is_float and image.colorspace_settings.name == "sRGB":
        px = np.where(px <= 0.04045, px / 12.92, ((px + 0.055) / 1.055) ** 2.4)
    return np.ascontiguousarray(np.maximum(px, 0), dtype=np.float32)
