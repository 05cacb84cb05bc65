#!/usr/bin/env python3
"""Writes the glTF test files of this directory with the standard library only.

Run from this directory; the files are committed, this script documents how they were made
(and remakes them after a deliberate change). Every file is small and made for one purpose; see
PROVENANCE.md.
"""
import base64
import json
import math
import struct
import zlib

from shapes import cuboid, uv_sphere  # noqa: E402  (beside this script)

FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125


def png(width, height, pixel):
    """PNG bytes (8-bit RGB); pixel(x, y) -> (r, g, b), row 0 at the top."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    rows = b"".join(
        b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" +
            chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


# quadrants.png: 2 x 2 texels, red and green on top, blue and white below.
QUADRANTS = [[(255, 0, 0), (0, 255, 0)], [(0, 0, 255), (255, 255, 255)]]


def quadrants():
    return png(2, 2, lambda x, y: QUADRANTS[y][x])


def grid():
    """16 x 16: a checker of 4 x 4 texel squares, orange and dark blue, in a white border."""
    def pixel(x, y):
        if x in (0, 15) or y in (0, 15):
            return (255, 255, 255)
        return (240, 140, 20) if ((x // 4) + (y // 4)) % 2 == 0 else (20, 40, 120)
    return png(16, 16, pixel)


class Asset:
    """A glTF asset being built: JSON objects and one binary buffer."""

    def __init__(self):
        self.bin = bytearray()
        self.j = {"asset": {"version": "2.0", "generator": "tests/data/gltf/make_gltf.py"}}

    def add(self, key, obj):
        self.j.setdefault(key, []).append(obj)
        return len(self.j[key]) - 1

    def view(self, data, stride=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            v["byteStride"] = stride
        self.bin += data
        return self.add("bufferViews", v)

    def accessor(self, view, ctype, count, kind, **extra):
        a = {"bufferView": view, "componentType": ctype, "count": count, "type": kind}
        a.update(extra)
        return self.add("accessors", a)

    def vec(self, rows, kind):
        """A float accessor of VEC2/VEC3 rows, with min and max for positions."""
        data = b"".join(struct.pack("<%df" % len(r), *r) for r in rows)
        n = len(rows[0])
        extra = {}
        if kind == "VEC3":
            extra = {"min": [min(r[i] for r in rows) for i in range(n)],
                     "max": [max(r[i] for r in rows) for i in range(n)]}
        return self.accessor(self.view(data), FLOAT, len(rows), kind, **extra)

    def indices(self, idx, ctype=USHORT):
        fmt = {UBYTE: "B", USHORT: "H", UINT: "I"}[ctype]
        return self.accessor(self.view(struct.pack("<%d%s" % (len(idx), fmt), *idx)), ctype,
                             len(idx), "SCALAR")

    def image(self, data):
        return self.add("images", {"bufferView": self.view(data), "mimeType": "image/png"})

    def finish(self):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.j["buffers"] = [{"byteLength": len(self.bin)}]

    def write_gltf(self, path, bin_name=None):
        """As JSON with the buffer in `bin_name`, or embedded as a data: URI."""
        self.finish()
        if bin_name:
            self.j["buffers"][0]["uri"] = bin_name
            with open(bin_name, "wb") as f:
                f.write(self.bin)
        else:
            self.j["buffers"][0]["uri"] = ("data:application/octet-stream;base64," +
                                           base64.b64encode(bytes(self.bin)).decode())
        with open(path, "w") as f:
            json.dump(self.j, f, indent=1)
            f.write("\n")

    def glb(self):
        self.finish()
        text = json.dumps(self.j, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        body = (struct.pack("<II", len(text), 0x4E4F534A) + text +
                struct.pack("<II", len(self.bin), 0x004E4942) + bytes(self.bin))
        return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body

    def write_glb(self, path):
        with open(path, "wb") as f:
            f.write(self.glb())


def quad(a, uv=True, normals=True, material=None):
    """A unit square in the xy plane facing +z, corners (0,0) to (1,1), indexed."""
    attrs = {"POSITION": a.vec([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], "VEC3")}
    if normals:
        attrs["NORMAL"] = a.vec([(0, 0, 1)] * 4, "VEC3")
    if uv:  # glTF's v runs down the image: the top-left corner of the image is (0, 0)
        attrs["TEXCOORD_0"] = a.vec([(0, 1), (1, 1), (1, 0), (0, 0)], "VEC2")
    prim = {"attributes": attrs, "indices": a.indices([0, 1, 2, 0, 2, 3])}
    if material is not None:
        prim["material"] = material
    return a.add("meshes", {"name": "quad", "primitives": [prim]})


def triangle(a):
    """One triangle, (0,0,0) (1,0,0) (0,1,0), not indexed, without normals."""
    pos = a.vec([(0, 0, 0), (1, 0, 0), (0, 1, 0)], "VEC3")
    return a.add("meshes", {"name": "triangle", "primitives": [{"attributes": {"POSITION": pos}}]})


def smooth_mesh(a, name, P, N, I, material):
    """A mesh of one primitive from positions, normals and indices."""
    return a.add("meshes", {"name": name, "primitives": [{"attributes": {
        "POSITION": a.vec(P, "VEC3"), "NORMAL": a.vec(N, "VEC3")}, "indices": a.indices(I),
        "material": material}]})


def quaternion(axis, degrees):
    s = math.sin(math.radians(degrees) / 2)
    n = math.sqrt(sum(c * c for c in axis))
    return [axis[0] / n * s, axis[1] / n * s, axis[2] / n * s, math.cos(math.radians(degrees) / 2)]


def look_at(eye, center, up):
    """The column-major matrix of a camera node at `eye` looking at `center` (down its -z)."""
    def sub(p, q): return [p[i] - q[i] for i in range(3)]
    def norm(v):
        n = math.sqrt(sum(c * c for c in v))
        return [c / n for c in v]
    def cross(p, q): return [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2],
                             p[0] * q[1] - p[1] * q[0]]
    z = norm(sub(eye, center))
    x = norm(cross(up, z))
    y = cross(z, x)
    return x + [0] + y + [0] + z + [0] + list(eye) + [1]


# quad.gltf + quad.bin + quadrants.png: an indexed square with normals and texture coordinates,
# its base colour texture an external PNG, its buffer an external file.
a = Asset()
a.add("images", {"uri": "quadrants.png"})
a.add("samplers", {"wrapS": 33071, "wrapT": 33071})
a.add("textures", {"source": 0, "sampler": 0})
a.add("materials", {"name": "painted", "pbrMetallicRoughness": {
    "baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 1}})
quad(a, material=0)
a.add("nodes", {"mesh": 0})
a.add("scenes", {"nodes": [0]})
a.j["scene"] = 0
a.write_gltf("quad.gltf", "quad.bin")
with open("quadrants.png", "wb") as f:
    f.write(quadrants())

# quad.glb: the same square, binary, the PNG embedded in a bufferView.
a = Asset()
a.image(quadrants())
a.add("samplers", {"wrapS": 33071, "wrapT": 33071})
a.add("textures", {"source": 0, "sampler": 0})
a.add("materials", {"name": "painted", "pbrMetallicRoughness": {
    "baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 1}})
quad(a, material=0)
a.add("nodes", {"mesh": 0})
a.add("scenes", {"nodes": [0]})
a.write_glb("quad.glb")
glb = a.glb()

# truncated.glb: quad.glb cut in the middle of its binary chunk.
with open("truncated.glb", "wb") as f:
    f.write(glb[:len(glb) - 40])

# nodes.gltf (buffer as a data: URI): one triangle mesh placed by two nodes of a tree, one by
# translation, rotation and scale under a translated parent, one by a matrix. Scene 1 is the
# default; scene 0 places nothing.
a = Asset()
triangle(a)
a.add("nodes", {"name": "parent", "translation": [1, 2, 3], "children": [1, 2]})
a.add("nodes", {"name": "trs", "mesh": 0, "rotation": quaternion((0, 0, 1), 90),
                "scale": [2, 2, 2]})
a.add("nodes", {"name": "matrix", "mesh": 0,
                "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1]})
a.add("nodes", {"name": "elsewhere", "mesh": 0})
a.add("scenes", {"nodes": [3]})
a.add("scenes", {"nodes": [0]})
a.j["scene"] = 1
a.write_gltf("nodes.gltf")

# modes.gltf: the same four vertices as a triangle strip (2 triangles), a fan (2), points
# (skipped with a warning) and non-indexed triangles without normals; the strip and fan are
# indexed with unsigned bytes, the fan's texture coordinates are normalised unsigned bytes.
a = Asset()
pos = a.vec([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)], "VEC3")
uv8 = a.accessor(a.view(bytes([0, 255, 255, 255, 0, 0, 255, 0])), UBYTE, 4, "VEC2",
                 normalized=True)
a.add("meshes", {"name": "modes", "primitives": [
    {"attributes": {"POSITION": pos}, "indices": a.indices([0, 1, 2, 3], UBYTE), "mode": 5},
    {"attributes": {"POSITION": pos, "TEXCOORD_0": uv8},
     "indices": a.indices([0, 1, 3, 2], UBYTE), "mode": 6},
    {"attributes": {"POSITION": pos}, "mode": 0},
    {"attributes": {"POSITION": a.vec([(0, 0, 1), (1, 0, 1), (0, 1, 1)], "VEC3")}}]})
a.add("nodes", {"mesh": 0})
a.write_gltf("modes.gltf")

# smooth.gltf: a triangle with vertex normals leaning apart (shaded smooth).
a = Asset()
s = 1 / math.sqrt(2)
a.add("meshes", {"name": "smooth", "primitives": [{"attributes": {
    "POSITION": a.vec([(0, 0, 0), (1, 0, 0), (0, 1, 0)], "VEC3"),
    "NORMAL": a.vec([(-s, 0, s), (s, 0, s), (0, 0, 1)], "VEC3")}}]})
a.add("nodes", {"mesh": 0})
a.write_gltf("smooth.gltf")

# materials.gltf: one quad per material, for the mapping to Glint's model.
a = Asset()
materials = [
    {"name": "plastic", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.2, 0.1, 1], "metallicFactor": 0, "roughnessFactor": 0.5}},
    {"name": "gold", "pbrMetallicRoughness": {
        "baseColorFactor": [1, 0.8, 0.3, 1], "metallicFactor": 1, "roughnessFactor": 0}},
    {"name": "default"},
    {"name": "lamp", "emissiveFactor": [1, 0.5, 0.25],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}},
    {"name": "veil", "alphaMode": "BLEND", "pbrMetallicRoughness": {
        "baseColorFactor": [0.2, 0.4, 0.6, 0.25], "metallicFactor": 0}},
    {"name": "glass", "pbrMetallicRoughness": {
        "baseColorFactor": [0.9, 1, 0.9, 1], "metallicFactor": 0, "roughnessFactor": 0},
     "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                    "KHR_materials_ior": {"ior": 1.33}}},
    {"name": "cutout", "alphaMode": "MASK", "alphaCutoff": 0.5,
     "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.4]}},
]
for i, m in enumerate(materials):
    a.add("materials", m)
    quad(a, material=i)
    a.add("nodes", {"mesh": i, "translation": [2 * i, 0, 0]})
a.j["extensionsUsed"] = ["KHR_materials_emissive_strength", "KHR_materials_transmission",
                         "KHR_materials_ior"]
a.write_gltf("materials.gltf")

# sparse.gltf: a triangle whose positions are zeros (no bufferView) with two of them replaced
# by a sparse accessor.
a = Asset()
ind = a.view(struct.pack("<2H", 1, 2))
val = a.view(struct.pack("<6f", 1, 0, 0, 0, 1, 0))
pos = a.add("accessors", {"componentType": FLOAT, "count": 3, "type": "VEC3", "sparse": {
    "count": 2, "indices": {"bufferView": ind, "componentType": USHORT},
    "values": {"bufferView": val}}})
a.add("meshes", {"primitives": [{"attributes": {"POSITION": pos}}]})
a.add("nodes", {"mesh": 0})
a.write_gltf("sparse.gltf")

# scene.glb: the golden scene. A textured box placed twice (one mesh, two nodes), a grey
# ground, a camera (a node matrix), a point light and a directional light (KHR_lights_punctual).
a = Asset()
a.image(grid())
a.add("samplers", {"wrapS": 10497, "wrapT": 10497})
a.add("textures", {"source": 0, "sampler": 0})
a.add("materials", {"name": "crate", "pbrMetallicRoughness": {
    "baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 0}})
a.add("materials", {"name": "ground", "pbrMetallicRoughness": {
    "baseColorFactor": [0.5, 0.55, 0.6, 1], "metallicFactor": 0, "roughnessFactor": 0}})
a.add("materials", {"name": "brass", "pbrMetallicRoughness": {
    "baseColorFactor": [0.9, 0.7, 0.3, 1], "metallicFactor": 1, "roughnessFactor": 0}})
# The box: 6 faces of 4 vertices each (own normals and texture coordinates), side 1, centred.
faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
         ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
         ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
P, N, T, I = [], [], [], []
for n, u, v in faces:
    base = len(P)
    for su, sv, tu, tv in ((-1, -1, 0, 1), (1, -1, 1, 1), (1, 1, 1, 0), (-1, 1, 0, 0)):
        P.append(tuple(0.5 * (n[i] + su * u[i] + sv * v[i]) for i in range(3)))
        N.append(n)
        T.append((tu, tv))
    I += [base, base + 1, base + 2, base, base + 2, base + 3]
a.add("meshes", {"name": "box", "primitives": [{"attributes": {
    "POSITION": a.vec(P, "VEC3"), "NORMAL": a.vec(N, "VEC3"), "TEXCOORD_0": a.vec(T, "VEC2")},
    "indices": a.indices(I), "material": 0}]})
g = 3
a.add("meshes", {"name": "ground", "primitives": [{"attributes": {
    "POSITION": a.vec([(-g, 0, g), (g, 0, g), (g, 0, -g), (-g, 0, -g)], "VEC3"),
    "NORMAL": a.vec([(0, 1, 0)] * 4, "VEC3")}, "indices": a.indices([0, 1, 2, 0, 2, 3]),
    "material": 1}]})
# A brass ball: a UV sphere of radius 0.35, smooth.
smooth_mesh(a, "ball", *uv_sphere(0.35, 12, 24), 2)
a.add("cameras", {"name": "view", "type": "perspective", "perspective": {
    "yfov": 0.7, "aspectRatio": 16 / 9, "znear": 0.1}})
a.j["extensionsUsed"] = ["KHR_lights_punctual"]
a.j["extensions"] = {"KHR_lights_punctual": {"lights": [
    {"name": "bulb", "type": "point", "color": [1, 0.9, 0.8], "intensity": 30},
    {"name": "sun", "type": "directional", "intensity": 1.2}]}}
nodes = [
    {"name": "crate A", "mesh": 0, "translation": [-0.9, 0.5, 0],
     "rotation": quaternion((0, 1, 0), 30)},
    {"name": "crate B", "mesh": 0, "translation": [0.8, 0.3, 0.4],
     "rotation": quaternion((0, 1, 0), -20), "scale": [0.6, 0.6, 0.6]},
    {"name": "ground", "mesh": 1},
    {"name": "camera", "camera": 0, "matrix": look_at((0.3, 1.8, 4.2), (0, 0.4, 0), (0, 1, 0))},
    {"name": "bulb", "translation": [2, 3, 2.5],
     "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "sun", "rotation": quaternion((1, 0.6, 0), -50),
     "extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"name": "ball", "mesh": 2, "translation": [0.05, 0.35, 1.1]},
]
for n in nodes:
    a.add("nodes", n)
a.add("scenes", {"nodes": list(range(len(nodes)))})
a.write_glb("scene.glb")

# animated.gltf (buffer as a data: URI): animation 0 'Turn', 99 frames at 24 fps (0 to 4.125 s):
# a red box turning a full turn about y (LINEAR rotation keys a quarter turn apart) as it rises
# and falls (LINEAR translation), and a small blue box beside it stepping between three places
# (STEP). No camera: Glint frames it for the whole animation. Every frame of 0 to 99 differs from
# the next; the farm tests render 100 of them (tests/slurm/frames_test.sh, tests/mpi/).
a = Asset()
P, N, I = [], [], []
for n, u, v in faces:  # the golden scene's box, without texture coordinates
    base = len(P)
    for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
        P.append(tuple(0.5 * (n[i] + su * u[i] + sv * v[i]) for i in range(3)))
        N.append(n)
    I += [base, base + 1, base + 2, base, base + 2, base + 3]
box = {"POSITION": a.vec(P, "VEC3"), "NORMAL": a.vec(N, "VEC3")}
box_indices = a.indices(I)
for name, colour in (("red", [0.8, 0.15, 0.1, 1]), ("blue", [0.1, 0.25, 0.8, 1])):
    material = a.add("materials", {"name": name, "pbrMetallicRoughness": {
        "baseColorFactor": colour, "metallicFactor": 0, "roughnessFactor": 0.6}})
    a.add("meshes", {"name": name + " box", "primitives": [{
        "attributes": box, "indices": box_indices, "material": material}]})
a.add("nodes", {"name": "turning", "mesh": 0, "translation": [0, 0.5, 0]})
a.add("nodes", {"name": "stepping", "mesh": 1, "translation": [1.2, 0.2, 0],
                "scale": [0.4, 0.4, 0.4]})
a.add("scenes", {"nodes": [0, 1]})
end = 99 / 24


def keys(values):
    """A float accessor of key values (rows) or key times (numbers)."""
    if isinstance(values[0], (int, float)):
        data = struct.pack("<%df" % len(values), *values)
        return a.accessor(a.view(data), FLOAT, len(values), "SCALAR",
                          min=[min(values)], max=[max(values)])
    data = b"".join(struct.pack("<%df" % len(r), *r) for r in values)
    return a.accessor(a.view(data), FLOAT, len(values), {3: "VEC3", 4: "VEC4"}[len(values[0])])


turn_times = keys([end * k / 4 for k in range(5)])
rise_times = keys([0, end / 2, end])
step_times = keys([0, end / 3, 2 * end / 3])
a.add("animations", {"name": "Turn", "samplers": [
    {"input": turn_times, "output": keys([quaternion((0, 1, 0), 90 * k) for k in range(5)])},
    {"input": rise_times, "output": keys([(0, 0.5, 0), (0, 1.1, 0), (0, 0.5, 0)])},
    {"input": step_times, "interpolation": "STEP",
     "output": keys([(1.2, 0.2, 0), (0, 0.2, 1.2), (-1.2, 0.2, 0)])}],
    "channels": [{"sampler": 0, "target": {"node": 0, "path": "rotation"}},
                 {"sampler": 1, "target": {"node": 0, "path": "translation"}},
                 {"sampler": 2, "target": {"node": 1, "path": "translation"}}]})
a.write_gltf("animated.gltf")


# The error cases: each file is broken in one way.
def broken(path, change):
    a = Asset()
    quad(a, material=None)
    a.add("nodes", {"mesh": 0})
    change(a)
    a.write_gltf(path)


broken("bad-accessor.gltf",
       lambda a: a.j["meshes"][0]["primitives"][0]["attributes"].update({"NORMAL": 9}))
broken("bad-accessor-range.gltf", lambda a: a.j["accessors"][0].update({"count": 40}))
broken("bad-bufferview.gltf", lambda a: a.j["bufferViews"][1].update({"byteLength": 4000}))

# bad-index.gltf: the square's last index is 7, but it has 4 vertices.
a = Asset()
pos = a.vec([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], "VEC3")
a.add("meshes", {"primitives": [{"attributes": {"POSITION": pos},
                                 "indices": a.indices([0, 1, 2, 0, 2, 7])}]})
a.add("nodes", {"mesh": 0})
a.write_gltf("bad-index.gltf")

# missing-bin.gltf: its buffer names a file that is not there.
a = Asset()
quad(a)
a.add("nodes", {"mesh": 0})
a.finish()
a.j["buffers"][0]["uri"] = "nowhere.bin"
with open("missing-bin.gltf", "w") as f:
    json.dump(a.j, f, indent=1)
    f.write("\n")

# missing-texture.gltf: a material whose texture file is not there (a warning, not an error).
a = Asset()
a.add("images", {"uri": "nowhere.png"})
a.add("textures", {"source": 0})
a.add("materials", {"name": "painted", "pbrMetallicRoughness": {
    "baseColorFactor": [0.2, 0.6, 0.2, 1], "baseColorTexture": {"index": 0}}})
quad(a, material=0)
a.add("nodes", {"mesh": 0})
a.write_gltf("missing-texture.gltf")

# closed-room.gltf: a closed box, its faces turned inwards, around the file's own camera, and
# no lights: the studio's environment cannot reach the inside, so the image is black (glint
# warns of it and says what to try).
a = Asset()
corners = [(x, y, z) for x in (-2, 2) for y in (-1, 3) for z in (-2, 2)]
faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
idx = []
for f in faces:
    idx += [f[0], f[2], f[1], f[0], f[3], f[2]]  # wound to face inwards
pos = a.vec(corners, "VEC3")
a.add("materials", {"name": "wall", "pbrMetallicRoughness": {"metallicFactor": 0}})
a.add("meshes", {"name": "room", "primitives": [{"attributes": {"POSITION": pos},
                                                  "indices": a.indices(idx), "material": 0}]})
a.add("cameras", {"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.05}})
a.add("nodes", {"mesh": 0})
a.add("nodes", {"camera": 0, "matrix": look_at((0, 1, 1.5), (0, 0.5, -1), (0, 1, 0))})
a.add("scenes", {"nodes": [0, 1]})
a.j["scene"] = 0
a.write_gltf("closed-room.gltf")

# glass-slabs.gltf: five slabs of clear glass one behind another before a chequered board, so
# that a ray through all of them refracts ten times: black where the path tracer's transmission
# limit is shorter (the model mode's was 8 bounces in all), the board where it is not.
a = Asset()
a.add("materials", {"name": "glass", "pbrMetallicRoughness": {"metallicFactor": 0,
                                                               "roughnessFactor": 0},
                    "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                                   "KHR_materials_volume": {"thicknessFactor": 0.12}}})
a.j["extensionsUsed"] = ["KHR_materials_transmission", "KHR_materials_volume"]
smooth_mesh(a, "slab", *cuboid((0.8, 0.8, 0.06)), 0)
a.add("samplers", {"magFilter": 9728, "minFilter": 9728})
a.add("textures", {"source": a.image(grid()), "sampler": 0})
a.add("materials", {"name": "board", "pbrMetallicRoughness": {
    "baseColorTexture": {"index": 0}, "metallicFactor": 0}})
quad(a, material=1)
for i in range(5):
    a.add("nodes", {"mesh": 0, "translation": [0, 0, 0.3 * i]})
a.add("nodes", {"mesh": 1, "translation": [-1.5, -1.5, -0.6], "scale": [3, 3, 1]})
a.add("cameras", {"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.05}})
a.add("nodes", {"camera": 0, "matrix": look_at((0.5, 0.4, 6), (0, 0, 0), (0, 1, 0))})
a.add("scenes", {"nodes": list(range(7))})
a.j["scene"] = 0
a.write_gltf("glass-slabs.gltf")

# unlit.gltf: an unlit sign (KHR_materials_unlit, the chequered texture) standing on a lit grey
# floor, a directional light low behind it: the camera sees the sign's colours as they are, and
# the sign casts no shadow (Blender's importer makes it visible to camera rays alone).
a = Asset()
a.add("samplers", {"magFilter": 9728, "minFilter": 9728})
a.add("textures", {"source": a.image(grid()), "sampler": 0})
a.add("materials", {"name": "sign", "pbrMetallicRoughness": {
    "baseColorTexture": {"index": 0}, "metallicFactor": 0},
    "extensions": {"KHR_materials_unlit": {}}})
a.add("materials", {"name": "floor", "pbrMetallicRoughness": {
    "baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0, "roughnessFactor": 1}})
quad(a, material=0)
floor_pos = a.vec([(-3, 0, 3), (3, 0, 3), (3, 0, -3), (-3, 0, -3)], "VEC3")
floor_nrm = a.vec([(0, 1, 0)] * 4, "VEC3")
a.add("meshes", {"name": "floor", "primitives": [{
    "attributes": {"POSITION": floor_pos, "NORMAL": floor_nrm},
    "indices": a.indices([0, 1, 2, 0, 2, 3]), "material": 1}]})
a.add("cameras", {"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 4 / 3,
                                                         "znear": 0.05}})
a.j["extensionsUsed"] = ["KHR_materials_unlit", "KHR_lights_punctual"]
a.j["extensions"] = {"KHR_lights_punctual": {"lights": [
    {"name": "sun", "type": "directional", "intensity": 3}]}}
a.add("nodes", {"name": "sign", "mesh": 0, "translation": [-0.5, 0.2, 0]})
a.add("nodes", {"name": "floor", "mesh": 1})
a.add("nodes", {"name": "camera", "camera": 0,
                "matrix": look_at((0.6, 1.2, 3.2), (0, 0.5, 0), (0, 1, 0))})
a.add("nodes", {"name": "sun", "rotation": quaternion((1, 0, 0), -150),
                "extensions": {"KHR_lights_punctual": {"light": 0}}})
a.add("scenes", {"nodes": [0, 1, 2, 3]})
a.j["scene"] = 0
a.write_gltf("unlit.gltf")

# lamp-in-lux.gltf: lit in physical units, as glTF means its lights: a 1500 cd point light inside
# its glowing bulb (emissive strength 1500) above a white cube, and a 512 lux sun. At exposure 0
# it is white; glint chooses an exposure for it. No ground of its own: the model mode's shadow
# catcher takes the cube's shadow, and none from the bulb around the light.
a = Asset()
a.add("materials", {"name": "white", "pbrMetallicRoughness": {"metallicFactor": 0,
                                                               "roughnessFactor": 0.6}})
a.add("materials", {"name": "bulb", "emissiveFactor": [1, 0.85, 0.6],
                    "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1],
                                             "metallicFactor": 0},
                    "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1500}}})
smooth_mesh(a, "cube", *cuboid((0.3, 0.3, 0.3), (0, 0.3, 0)), 0)
smooth_mesh(a, "bulb", *uv_sphere(0.08, 8, 16), 1)
a.j["extensionsUsed"] = ["KHR_lights_punctual", "KHR_materials_emissive_strength"]
a.j["extensions"] = {"KHR_lights_punctual": {"lights": [
    {"name": "filament", "type": "point", "color": [1, 0.85, 0.6], "intensity": 1500},
    {"name": "sun", "type": "directional", "intensity": 512}]}}
a.add("nodes", {"name": "cube", "mesh": 0})
a.add("nodes", {"name": "bulb", "mesh": 1, "translation": [0.6, 1.1, 0.2]})
a.add("nodes", {"name": "filament", "translation": [0.6, 1.1, 0.2],
                "extensions": {"KHR_lights_punctual": {"light": 0}}})
a.add("nodes", {"name": "sun", "rotation": quaternion((1, 0.3, 0), -60),
                "extensions": {"KHR_lights_punctual": {"light": 1}}})
a.add("scenes", {"nodes": [0, 1, 2, 3]})
a.j["scene"] = 0
a.write_gltf("lamp-in-lux.gltf")

# variants.gltf: a quad, red as the file has it, blue and green in its two material variants
# (KHR_materials_variants), before the file's own camera: the web page's variant picker.
a = Asset()
for name, colour in (("red", [0.8, 0.1, 0.1, 1]), ("blue", [0.1, 0.2, 0.8, 1]),
                     ("green", [0.1, 0.7, 0.2, 1])):
    a.add("materials", {"name": name, "pbrMetallicRoughness": {"baseColorFactor": colour,
                                                                "metallicFactor": 0}})
quad(a, material=0)
a.j["meshes"][0]["primitives"][0]["extensions"] = {"KHR_materials_variants": {"mappings": [
    {"material": 1, "variants": [0]}, {"material": 2, "variants": [1]}]}}
a.j["extensionsUsed"] = ["KHR_materials_variants"]
a.j["extensions"] = {"KHR_materials_variants": {"variants": [{"name": "Blue"},
                                                             {"name": "Green"}]}}
a.add("cameras", {"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 4 / 3,
                                                         "znear": 0.05}})
a.add("nodes", {"name": "quad", "mesh": 0, "translation": [-0.5, -0.5, 0]})
a.add("nodes", {"name": "camera", "camera": 0, "translation": [0, 0, 2]})
a.add("scenes", {"nodes": [0, 1]})
a.j["scene"] = 0
a.write_gltf("variants.gltf")
