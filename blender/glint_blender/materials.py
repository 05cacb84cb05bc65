"""Blender materials as glTF materials, which Glint reads with all their extensions.

Shader nodes are read from the active Material Output: the Principled BSDF (every input glTF
has a place for), the Diffuse, Glossy, Glass, Emission and Transparent BSDFs, and Mix and Add
shaders over them. Image Texture nodes become glTF textures, through a Mapping node (Point) as
KHR_texture_transform and a Normal Map node as the normal texture. Whatever has no place is
approximated by the closest material and named in a warning, never dropped silently.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Callable, Optional

import bpy

# Blender's default Principled BSDF "Specular" is 0.5: F0 = 0.08 * specular = 0.04, glTF's.
_F0_PER_SPECULAR = 0.08


@dataclass
class Texture:
    """An Image Texture node feeding an input: the image, its UV map and mapping."""

    image: "bpy.types.Image"
    uv_map: str = ""
    transform: Optional[dict] = None  # KHR_texture_transform
    channel: str = "Color"  # the output used: Color or Alpha
    clamp: bool = False


@dataclass
class Lobe:
    """What one shader node tree amounts to, in glTF's terms."""

    base: tuple = (0.8, 0.8, 0.8)
    base_texture: Optional[Texture] = None
    metallic: float = 0.0
    roughness: float = 0.5
    specular: float = 0.5  # Blender's, F0 = 0.08 x specular
    ior: float = 1.45
    transmission: float = 0.0
    emission: tuple = (0.0, 0.0, 0.0)
    emission_texture: Optional[Texture] = None
    alpha: float = 1.0
    alpha_texture: bool = False  # the base texture's alpha
    normal_texture: Optional[Texture] = None
    normal_scale: float = 1.0
    clearcoat: float = 0.0
    clearcoat_roughness: float = 0.03
    sheen: float = 0.0
    sheen_tint: float = 0.5
    anisotropy: float = 0.0
    anisotropy_rotation: float = 0.0
    subsurface: float = 0.0
    subsurface_radius: tuple = (1.0, 0.2, 0.1)
    subsurface_color: tuple = (0.8, 0.8, 0.8)
    warnings: list = field(default_factory=list)


def _rgb(value) -> tuple:
    return tuple(float(v) for v in value[:3])


def _mix(a: tuple, b: tuple, t: float) -> tuple:
    return tuple((1 - t) * x + t * y for x, y in zip(a, b))


class MaterialReader:
    """Reads the node trees of one render; warns once per material and problem."""

    def __init__(self, warn: Callable[[str], None]) -> None:
        self.warn = warn

    # ---- inputs ---------------------------------------------------------------------------

    def _value(self, node, name: str, lobe: Lobe, default=None):
        """An input's value: its own, or a constant node's; a texture is read by _texture."""
        socket = node.inputs.get(name)
        if socket is None:
            return default
        if socket.is_linked:
            link = socket.links[0]
            src = link.from_node
            if src.type == "RGB":
                return _rgb(src.outputs[0].default_value) if socket.type == "RGBA" else float(
                    sum(_rgb(src.outputs[0].default_value)) / 3)
            if src.type == "VALUE":
                v = float(src.outputs[0].default_value)
                return (v, v, v) if socket.type == "RGBA" else v
            if src.type != "TEX_IMAGE" and src.type != "NORMAL_MAP":
                lobe.warnings.append(
                    f"input '{name}' of '{node.name}' comes from a {src.bl_label} node, which "
                    "Glint does not evaluate: its own value is used")
        value = socket.default_value
        if socket.type in ("RGBA", "VECTOR"):
            return _rgb(value)
        return float(value)

    def _texture(self, node, name: str, lobe: Lobe) -> Optional[Texture]:
        """The Image Texture node linked (directly) into an input, if any."""
        socket = node.inputs.get(name)
        if socket is None or not socket.is_linked:
            return None
        link = socket.links[0]
        src = link.from_node
        if src.type != "TEX_IMAGE":
            return None
        if src.image is None:
            lobe.warnings.append(f"'{src.name}' has no image: '{name}' keeps its value")
            return None
        tex = Texture(image=src.image, channel=link.from_socket.name,
                      clamp=src.extension in ("EXTEND", "CLIP"))
        if src.projection != "FLAT":
            lobe.warnings.append(f"'{src.name}' uses {src.projection.lower()} projection: "
                                 "read as flat (UV)")
        vector = src.inputs.get("Vector")
        if vector is not None and vector.is_linked:
            self._vector(vector.links[0].from_node, vector.links[0].from_socket.name, tex, lobe)
        return tex

    def _vector(self, src, output: str, tex: Texture, lobe: Lobe) -> None:
        if src.type == "UVMAP":
            tex.uv_map = src.uv_map
        elif src.type == "TEX_COORD" and output == "UV":
            pass
        elif src.type == "MAPPING":
            if src.vector_type not in ("POINT", "TEXTURE"):
                lobe.warnings.append(f"'{src.name}' is a {src.vector_type.lower()} mapping: "
                                     "ignored")
            else:
                loc = _rgb(src.inputs["Location"].default_value)
                rot = _rgb(src.inputs["Rotation"].default_value)
                scale = _rgb(src.inputs["Scale"].default_value)
                if src.vector_type == "TEXTURE":  # the inverse of a point mapping
                    lobe.warnings.append(f"'{src.name}' is a texture mapping: read as point")
                tex.transform = _texture_transform(loc[0], loc[1], rot[2], scale[0], scale[1])
            inner = src.inputs.get("Vector")
            if inner is not None and inner.is_linked:
                self._vector(inner.links[0].from_node, inner.links[0].from_socket.name, tex,
                             lobe)
        else:
            lobe.warnings.append(f"texture coordinates from a {src.bl_label} node: read as UV")

    # ---- shader nodes ---------------------------------------------------------------------

    def shader(self, socket) -> Lobe:
        if socket is None or not socket.is_linked:
            return Lobe(base=(0.0, 0.0, 0.0), roughness=1.0, specular=0.0)
        node = socket.links[0].from_node
        t = node.type
        if t == "BSDF_PRINCIPLED":
            return self._principled(node)
        lobe = Lobe()
        if t == "BSDF_DIFFUSE":
            lobe.base = self._value(node, "Color", lobe)
            lobe.base_texture = self._texture(node, "Color", lobe)
            lobe.roughness, lobe.specular = 1.0, 0.0
        elif t in ("BSDF_GLOSSY", "BSDF_ANISOTROPIC"):
            lobe.base = self._value(node, "Color", lobe)
            lobe.base_texture = self._texture(node, "Color", lobe)
            lobe.metallic = 1.0
            lobe.roughness = self._value(node, "Roughness", lobe, 0.5)
        elif t in ("BSDF_GLASS", "BSDF_REFRACTION"):
            lobe.base = self._value(node, "Color", lobe)
            lobe.roughness = self._value(node, "Roughness", lobe, 0.0)
            lobe.ior = self._value(node, "IOR", lobe, 1.45)
            lobe.transmission = 1.0
            if t == "BSDF_REFRACTION":
                lobe.warnings.append("a Refraction BSDF is read as glass (it also reflects)")
        elif t == "EMISSION":
            colour = self._value(node, "Color", lobe)
            strength = self._value(node, "Strength", lobe, 1.0)
            lobe.base, lobe.roughness, lobe.specular = (0.0, 0.0, 0.0), 1.0, 0.0
            lobe.emission = tuple(c * strength for c in colour)
            lobe.emission_texture = self._texture(node, "Color", lobe)
        elif t == "BSDF_TRANSPARENT":
            lobe.alpha = 0.0
        elif t in ("MIX_SHADER", "ADD_SHADER"):
            return self._combine(node)
        else:
            colour = node.inputs.get("Color")
            if colour is not None and colour.type == "RGBA":
                lobe.base = self._value(node, "Color", lobe)
            lobe.roughness, lobe.specular = 1.0, 0.0
            lobe.warnings.append(f"'{node.name}' ({node.bl_label}) has no Glint lobe: rendered "
                                 "as a diffuse surface of its colour")
        return lobe

    def _principled(self, node) -> Lobe:
        lobe = Lobe()
        v = lambda name, d=None: self._value(node, name, lobe, d)  # noqa: E731
        lobe.base = v("Base Color")
        lobe.base_texture = self._texture(node, "Base Color", lobe)
        lobe.metallic = v("Metallic", 0.0)
        lobe.roughness = v("Roughness", 0.5)
        lobe.specular = v("Specular", 0.5)
        lobe.ior = v("IOR", 1.45)
        lobe.transmission = v("Transmission", 0.0)
        strength = v("Emission Strength", 1.0)
        lobe.emission = tuple(c * strength for c in v("Emission", (0, 0, 0)))
        lobe.emission_texture = self._texture(node, "Emission", lobe)
        lobe.alpha = v("Alpha", 1.0)
        alpha_tex = self._texture(node, "Alpha", lobe)
        if alpha_tex is not None:
            if lobe.base_texture is not None and alpha_tex.image == lobe.base_texture.image:
                lobe.alpha_texture, lobe.alpha = True, 1.0
            else:
                lobe.warnings.append("the alpha comes from another image than the base colour: "
                                     "its value is used")
        lobe.clearcoat = v("Clearcoat", 0.0)
        lobe.clearcoat_roughness = v("Clearcoat Roughness", 0.03)
        lobe.sheen = v("Sheen", 0.0)
        lobe.sheen_tint = v("Sheen Tint", 0.5)
        lobe.anisotropy = v("Anisotropic", 0.0)
        lobe.anisotropy_rotation = v("Anisotropic Rotation", 0.0)
        lobe.subsurface = v("Subsurface", 0.0)
        lobe.subsurface_radius = v("Subsurface Radius", (1.0, 0.2, 0.1))
        lobe.subsurface_color = v("Subsurface Color", (0.8, 0.8, 0.8))
        normal = node.inputs.get("Normal")
        if normal is not None and normal.is_linked:
            src = normal.links[0].from_node
            if src.type == "NORMAL_MAP":
                lobe.normal_texture = self._texture(src, "Color", lobe)
                lobe.normal_scale = float(src.inputs["Strength"].default_value)
                if src.space != "TANGENT":
                    lobe.warnings.append(f"'{src.name}' is in {src.space.lower()} space: read as "
                                         "a tangent-space normal map")
                if src.uv_map and lobe.normal_texture is not None:
                    lobe.normal_texture.uv_map = src.uv_map
            else:
                lobe.warnings.append(f"the normal comes from a {src.bl_label} node, which Glint "
                                     "does not read (bump mapping): the surface's own normal is "
                                     "used")
        return lobe

    def _combine(self, node) -> Lobe:
        """Mix and Add shaders: emission added, transparency as alpha, BSDFs blended."""
        add = node.type == "ADD_SHADER"
        fac = 0.5 if add else float(node.inputs[0].default_value)
        if not add and node.inputs[0].is_linked:
            mixing = node.inputs[0].links[0].from_node
            if mixing.type == "LIGHT_PATH" or mixing.type == "NEW_GEOMETRY":
                lobe = self.shader(node.inputs[1])
                lobe.warnings.append(f"'{node.name}' mixes by a {mixing.bl_label} node: its "
                                     "first shader is used")
                return lobe
        a = self.shader(node.inputs[1 if not add else 0])
        b = self.shader(node.inputs[2 if not add else 1])
        wa, wb = (1.0, 1.0) if add else (1.0 - fac, fac)
        warnings = a.warnings + b.warnings
        emit_a = a.emission != (0, 0, 0) and a.base == (0.0, 0.0, 0.0)
        emit_b = b.emission != (0, 0, 0) and b.base == (0.0, 0.0, 0.0)
        if a.alpha == 0.0 or b.alpha == 0.0:  # a transparent BSDF: coverage
            solid, weight = (b, wb) if a.alpha == 0.0 else (a, wa)
            solid.alpha = solid.alpha * weight
            solid.warnings = warnings
            return solid
        if emit_a or emit_b:  # emission over a BSDF (or two emissions)
            light, lw, surface, sw = (a, wa, b, wb) if emit_a else (b, wb, a, wa)
            surface.emission = tuple(sw * s + lw * e for s, e in zip(surface.emission,
                                                                      light.emission))
            surface.emission_texture = surface.emission_texture or light.emission_texture
            if not (emit_a and emit_b):
                surface.base = tuple(sw * c for c in surface.base)
            surface.warnings = warnings
            return surface
        # Two BSDFs: glTF has one layered material; blend their parameters.
        out = Lobe()
        for name in ("metallic", "roughness", "specular", "ior", "transmission", "clearcoat",
                     "sheen", "subsurface", "anisotropy"):
            setattr(out, name, wa * getattr(a, name) + wb * getattr(b, name))
        out.base = tuple(wa * x + wb * y for x, y in zip(a.base, b.base))
        out.emission = tuple(wa * x + wb * y for x, y in zip(a.emission, b.emission))
        out.base_texture = a.base_texture or b.base_texture
        out.normal_texture = a.normal_texture or b.normal_texture
        out.warnings = warnings + [f"'{node.name}' mixes two BSDFs: Glint blends their "
                                   "parameters into one material"]
        return out


def _texture_transform(lu: float, lv: float, theta: float, su: float, sv: float) -> dict:
    """A Blender point mapping of UVs (u, v) -> R(theta) S (u, v) + l, in glTF's UVs (v down):
    KHR_texture_transform's offset, rotation and scale."""
    s, c = math.sin(theta), math.cos(theta)
    return {"offset": [lu - sv * s, 1.0 - lv - sv * c], "rotation": theta, "scale": [su, sv]}


def _ior_for_specular(specular: float) -> float:
    """The index whose F0 is Blender's 0.08 x specular (1.5 for the default 0.5)."""
    f0 = min(max(_F0_PER_SPECULAR * specular, 0.0), 0.999)
    r = math.sqrt(f0)
    return (1 + r) / (1 - r) if f0 > 0 else 1.0


def gltf_material(lobe: Lobe, name: str, texture_index: Callable[[Texture, str], Optional[dict]],
                  two_sided: bool, blend: str, alpha_cutoff: float, writer) -> dict:
    """The glTF material of `lobe`; `texture_index(tex, role)` gives a textureInfo."""
    ext: dict = {}
    pbr = {
        "baseColorFactor": [*[min(max(c, 0.0), 1.0) for c in lobe.base], float(lobe.alpha)],
        "metallicFactor": min(max(lobe.metallic, 0.0), 1.0),
        "roughnessFactor": min(max(lobe.roughness, 0.0), 1.0),
    }
    if lobe.base_texture is not None:
        info = texture_index(lobe.base_texture, "base")
        if info:
            pbr["baseColorTexture"] = info
    mat: dict = {"name": name, "pbrMetallicRoughness": pbr, "doubleSided": bool(two_sided)}
    if lobe.alpha < 1.0 or lobe.alpha_texture:
        mat["alphaMode"] = "MASK" if blend == "CLIP" else "BLEND"
        if blend == "CLIP":
            mat["alphaCutoff"] = float(alpha_cutoff)
    peak = max(lobe.emission)
    if peak > 0:
        mat["emissiveFactor"] = [c / peak for c in lobe.emission] if peak > 1 else list(
            lobe.emission)
        if peak > 1:
            ext["KHR_materials_emissive_strength"] = {"emissiveStrength": peak}
        if lobe.emission_texture is not None:
            info = texture_index(lobe.emission_texture, "emission")
            if info:
                mat["emissiveTexture"] = info
    if lobe.normal_texture is not None:
        info = texture_index(lobe.normal_texture, "normal")
        if info:
            info["scale"] = lobe.normal_scale
            mat["normalTexture"] = info
    if lobe.transmission > 0:
        ext["KHR_materials_transmission"] = {"transmissionFactor": min(lobe.transmission, 1.0)}
        # Blender's transmission refracts into a solid: a volume, not a thin wall.
        ext["KHR_materials_volume"] = {"thicknessFactor": 1.0}
        ext["KHR_materials_ior"] = {"ior": max(lobe.ior, 1.0) if lobe.ior >= 1 else 1.0}
        if lobe.ior < 1:
            lobe.warnings.append(f"IOR {lobe.ior:g} below 1: read as 1")
    else:
        # Opaque dielectrics: Blender's F0 comes from Specular, glTF's from the index.
        ext["KHR_materials_ior"] = {"ior": _ior_for_specular(lobe.specular)}
    if lobe.specular <= 0 and lobe.transmission == 0:
        ext["KHR_materials_specular"] = {"specularFactor": 0.0}
    if lobe.clearcoat > 0:
        ext["KHR_materials_clearcoat"] = {"clearcoatFactor": min(lobe.clearcoat, 1.0),
                                          "clearcoatRoughnessFactor": lobe.clearcoat_roughness}
    if lobe.sheen > 0:
        tint = _mix((1.0, 1.0, 1.0), _tint(lobe.base), lobe.sheen_tint)
        ext["KHR_materials_sheen"] = {"sheenColorFactor": [min(lobe.sheen * t, 1.0) for t in tint],
                                      "sheenRoughnessFactor": 0.5}
    if lobe.anisotropy > 0:
        ext["KHR_materials_anisotropy"] = {"anisotropyStrength": min(lobe.anisotropy, 1.0),
                                           "anisotropyRotation": 2 * math.pi *
                                           lobe.anisotropy_rotation}
    if lobe.subsurface > 0 and lobe.transmission == 0:
        # Random-walk subsurface scattering inside the mesh: KHR_materials_volume_scatter.
        radius = [max(r * lobe.subsurface, 1e-4) for r in lobe.subsurface_radius]
        ext["KHR_materials_transmission"] = {"transmissionFactor": 1.0}
        ext["KHR_materials_volume"] = {
            "thicknessFactor": 1.0, "attenuationDistance": sum(radius) / 3,
            "attenuationColor": [min(max(c, 0.0), 1.0) for c in lobe.subsurface_color]}
        ext["KHR_materials_volume_scatter"] = {
            "multiscatterColor": [min(max(c, 0.0), 0.999) for c in lobe.subsurface_color]}
        lobe.warnings.append("subsurface scattering is approximated by a scattering volume "
                             "(KHR_materials_volume_scatter) of the mean radius")
    if ext:
        mat["extensions"] = ext
        for e in ext:
            writer.use_extension(e)
    return mat


def _tint(colour: tuple) -> tuple:
    lum = 0.3 * colour[0] + 0.6 * colour[1] + 0.1 * colour[2]
    return tuple(c / lum for c in colour) if lum > 0 else (1.0, 1.0, 1.0)


def image_path(image: "bpy.types.Image", folder: str, warn: Callable[[str], None]) -> Optional[str]:
    """A file Glint can read for `image`: its own file, or a copy saved into `folder` (packed,
    generated or in a format Glint does not read)."""
    path = bpy.path.abspath(image.filepath, library=image.library) if image.filepath else ""
    ok = path and os.path.isfile(path) and not image.packed_file and os.path.splitext(
        path)[1].lower() in (".png", ".jpg", ".jpeg", ".bmp", ".tga", ".hdr", ".webp", ".gif")
    if ok:
        return path
    if image.size[0] == 0 or image.size[1] == 0:
        warn(f"image '{image.name}' cannot be read ({path or 'no file'}): its texture is left "
             "out")
        return None
    out = os.path.join(folder, f"image{abs(hash(image.name)) % 10**8}.png")
    copy = image.copy()
    try:
        copy.filepath_raw = out
        copy.file_format = "PNG"
        copy.save()
    except RuntimeError as e:
        warn(f"image '{image.name}' cannot be saved for Glint ({e}): its texture is left out")
        return None
    finally:
        bpy.data.images.remove(copy)
    return out
