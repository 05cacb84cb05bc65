#!/usr/bin/env python3
"""Writes the two glTF scenes of the punctual-lights comparison (README.md) into a folder:
rgb.gltf, a white floor and a white ball under three coincident point lights, red, green and
blue, and white.gltf, the same lit by one white light of their sum; spot.gltf and spot-hard.gltf,
a floor, a box and a ball under a spot light and a dim white point light.
Standard library only, deterministic."""
import base64
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                                "tests", "data", "gltf"))
from shapes import cuboid, uv_sphere  # noqa: E402


class Asset:
    def __init__(self):
        self.bin = bytearray()
        self.j = {"asset": {"version": "2.0", "generator": "bench/cycles/lights/make_lights.py"},
                  "materials": [], "meshes": [], "nodes": [], "accessors": [],
                  "bufferViews": []}

    def add(self, key, obj):
        self.j.setdefault(key, []).append(obj)
        return len(self.j[key]) - 1

    def floats(self, rows, kind):
        while len(self.bin) % 4:
            self.bin.append(0)
        data = b"".join(struct.pack("<%df" % len(r), *r) for r in rows)
        view = self.add("bufferViews", {"buffer": 0, "byteOffset": len(self.bin),
                                        "byteLength": len(data)})
        self.bin += data
        extra = {}
        if kind == "VEC3":
            extra = {"min": [min(r[i] for r in rows) for i in range(3)],
                     "max": [max(r[i] for r in rows) for i in range(3)]}
        return self.add("accessors", dict({"bufferView": view, "componentType": 5126,
                                           "count": len(rows), "type": kind}, **extra))

    def indices(self, idx):
        while len(self.bin) % 4:
            self.bin.append(0)
        data = struct.pack("<%dI" % len(idx), *idx)
        view = self.add("bufferViews", {"buffer": 0, "byteOffset": len(self.bin),
                                        "byteLength": len(data)})
        self.bin += data
        return self.add("accessors", {"bufferView": view, "componentType": 5125,
                                      "count": len(idx), "type": "SCALAR"})

    def mesh(self, name, positions, normals, idx, material):
        return self.add("meshes", {"name": name, "primitives": [{
            "attributes": {"POSITION": self.floats(positions, "VEC3"),
                           "NORMAL": self.floats(normals, "VEC3")},
            "indices": self.indices(idx), "material": material}]})

    def write(self, path):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.j["buffers"] = [{"byteLength": len(self.bin), "uri":
                              "data:application/octet-stream;base64," +
                              base64.b64encode(bytes(self.bin)).decode()}]
        with open(path, "w") as f:
            json.dump(self.j, f, indent=1)
            f.write("\n")


def matte(a, name, colour):
    return a.add("materials", {"name": name, "pbrMetallicRoughness": {
        "baseColorFactor": list(colour) + [1], "metallicFactor": 0, "roughnessFactor": 1}})


def floor(a, material, half=4):
    p = [(-half, 0, half), (half, 0, half), (half, 0, -half), (-half, 0, -half)]
    return a.mesh("floor", p, [(0, 1, 0)] * 4, [0, 1, 2, 0, 2, 3], material)


def ball(a, material, r):
    return a.mesh("ball", *uv_sphere(r, 24, 48), material)


def box(a, material, h):
    return a.mesh("box", *cuboid((h, h, h)), material)


def look_at(eye, center, up=(0, 1, 0)):
    def norm(v):
        n = math.sqrt(sum(c * c for c in v))
        return [c / n for c in v]
    z = norm([eye[i] - center[i] for i in range(3)])
    x = norm([up[1] * z[2] - up[2] * z[1], up[2] * z[0] - up[0] * z[2], up[0] * z[1] - up[1] * z[0]])
    y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]]
    return x + [0] + y + [0] + z + [0] + list(eye) + [1]


def lit(lights, placed):
    """A floor and a ball under `lights` (KHR_lights_punctual), each at its node in `placed`."""
    a = Asset()
    white = matte(a, "white", (0.8, 0.8, 0.8))
    a.add("nodes", {"name": "floor", "mesh": floor(a, white)})
    a.add("nodes", {"name": "ball", "mesh": ball(a, white, 0.5), "translation": [0.6, 0.5, 0]})
    a.add("cameras", {"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 4 / 3,
                                                             "znear": 0.05}})
    a.add("nodes", {"name": "camera", "camera": 0, "matrix": look_at((0, 2.2, 4.2), (0, 0.3, 0))})
    a.j["extensionsUsed"] = ["KHR_lights_punctual"]
    a.j["extensions"] = {"KHR_lights_punctual": {"lights": lights}}
    for i, node in enumerate(placed):
        node["extensions"] = {"KHR_lights_punctual": {"light": i}}
        a.add("nodes", node)
    a.add("scenes", {"nodes": list(range(len(a.j["nodes"])))})
    a.j["scene"] = 0
    return a


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    where = [-0.6, 1.6, 0.4]
    rgb = [{"name": n, "type": "point", "color": c, "intensity": 8}
           for n, c in (("red", [1, 0, 0]), ("green", [0, 1, 0]), ("blue", [0, 0, 1]))]
    lit(rgb, [{"name": l["name"], "translation": where} for l in rgb]).write(
        os.path.join(out, "rgb.gltf"))
    white = [{"name": "white", "type": "point", "color": [1, 1, 1], "intensity": 8}]
    lit(white, [{"name": "white", "translation": where}]).write(os.path.join(out, "white.gltf"))
    # A spot light 2.2 above the floor, turned 20 degrees off straight down, and a dim white
    # fill: spot.gltf's cone is glTF's smooth one (inner 15 degrees, outer 30), spot-hard.gltf's
    # nearly hard (29.5 and 30), where glTF's fall-off and Blender's spot blend cannot differ.
    tilt = math.radians(-90 + 20)
    for name, inner in (("spot", 15), ("spot-hard", 29.5)):
        spot = [{"name": "spot", "type": "spot", "color": [1, 0.9, 0.8], "intensity": 20,
                 "spot": {"innerConeAngle": math.radians(inner),
                          "outerConeAngle": math.radians(30)}},
                {"name": "fill", "type": "point", "color": [1, 1, 1], "intensity": 0.5}]
        s = lit(spot, [{"name": "spot", "translation": [-0.2, 2.2, 0],
                        "rotation": [math.sin(tilt / 2) * 0.9578, 0,
                                     math.sin(tilt / 2) * 0.2873, math.cos(tilt / 2)]},
                       {"name": "fill", "translation": [-2, 1.5, 2]}])
        s.add("materials", {"name": "red", "pbrMetallicRoughness": {
            "baseColorFactor": [0.7, 0.15, 0.1, 1], "metallicFactor": 0,
            "roughnessFactor": 0.5}})
        s.add("nodes", {"name": "box", "mesh": box(s, 1, 0.3), "translation": [-0.7, 0.3, -0.4]})
        s.j["scenes"][0]["nodes"].append(len(s.j["nodes"]) - 1)
        s.write(os.path.join(out, name + ".gltf"))


main()
