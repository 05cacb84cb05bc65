#!/usr/bin/env python3
"""Writes the glTF test assets and environment maps for bench/cycles/gltf/ (issue 12, "Against
Cycles"): small .gltf files with their .bin buffers and PNG textures, and equirectangular
Radiance .hdr skies. Python's standard library only (json, struct, zlib, math).

    bench/cycles/gltf/make_assets.py OUT_DIR [NAME ...]

writes into OUT_DIR (all of them, or the NAMEs: metal, dielectric, normalmap, normaltilt,
emissive, lamps, caustic, room, near, sky, sky_low, sky_low_nosun, night):

  metal.gltf       a UV sphere (64 x 32 segments), metallic 1, roughness 0.3, base colour from
                   a texture of coloured metal stripes (gold, copper, silver, blue, green)
  dielectric.gltf  two spheres, metallic 0: red, roughness 0.5 (left) and blue-white checks,
                   roughness 0.15 (right)
  normalmap.gltf   a 4 x 4 m plane (20 x 20 quads) with a tangent-space normal map of bumps and
                   grooves (at most 31 degrees steep), TANGENT given (+x, w = +1: the frame its UV mapping implies),
                   white-grey, roughness 0.5, metallic 0
  normaltilt.gltf  four patches in a row: flat; a constant normal map tilting it 31 degrees
                   towards the low sun; the same tilted away; a patch really tilted towards it
  emissive.gltf    a sphere emitting a striped texture (KHR_materials_emissive_strength 4) over
                   a diffuse grey floor
  caustic.gltf     a glass ball (transmission 1, index 1.5) and a metal ball on a diffuse floor
  room.gltf        a closed room of separate wall quads sharing their edges, a window in its
                   -x wall, a ball inside
  lamps.gltf       36 small emissive spheres in six colours (strength 200, 9216 emissive
                   triangles) over a diffuse floor, beside a diffuse sphere (many lights)
  sky.hdr          sky gradient, brown ground, a sun 2.5 degrees in radius 40 degrees up,
                   behind the cameras' left shoulder
  sky_low.hdr      the same with the sun 8 degrees above the horizon (grazing light)
  sky_low_nosun.hdr  sky_low without its sun (to measure the sun's share on normaltilt)
  night.hdr        the sky without sun at 2% (so that the emissive sphere lights the floor)

Every glTF file is +y up, metres, counter-clockwise front faces, as glTF defines; textures
are 8-bit PNG (colour textures sRGB, the normal map linear). The output is deterministic.
"""

import json
import math
import os
import struct
import sys
import zlib

# --- Files. ------------------------------------------------------------------------------------


def write_png(path, width, height, pixels):
    """pixels: rows top to bottom of (r, g, b) bytes 0..255."""
    raw = bytearray()
    for row in pixels:
        raw.append(0)  # filter: none
        for r, g, b in row:
            raw += bytes((r, g, b))

    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(bytes(raw), 9))
    png += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def rgbe(r, g, b):
    m = max(r, g, b)
    if m < 1e-32:
        return (0, 0, 0, 0)
    e = math.frexp(m)[1]  # m = f 2^e, 0.5 <= f < 1
    s = 256.0 / 2.0**e
    return (min(255, int(r * s)), min(255, int(g * s)), min(255, int(b * s)), e + 128)


def write_hdr(path, width, height, pixels):
    """Radiance RGBE, new-style run-length scanlines (literal runs only), rows top to bottom."""
    out = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
    out += f"-Y {height} +X {width}\n".encode()
    for row in pixels:
        out += bytes((2, 2, width >> 8, width & 255))
        px = [rgbe(*c) for c in row]
        for k in range(4):
            comp = bytes(p[k] for p in px)
            for i in range(0, width, 128):
                part = comp[i:i + 128]
                out.append(len(part))
                out += part
    with open(path, "wb") as f:
        f.write(out)


class Gltf:
    """A .gltf (JSON) with one external .bin buffer, assembled as meshes are added."""

    def __init__(self, name):
        self.name = name
        self.bin = bytearray()
        self.j = {"asset": {"version": "2.0", "generator": "glint bench/cycles/gltf/make_assets.py"},
                  "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                  "materials": [], "textures": [], "images": [], "samplers": [],
                  "accessors": [], "bufferViews": [], "buffers": []}

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.j["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin),
                                      "byteLength": len(data), "target": target})
        self.bin += data
        return len(self.j["bufferViews"]) - 1

    def _accessor(self, values, kind, ncomp):
        flat = [x for v in values for x in v] if ncomp > 1 else list(values)
        if kind == "index":
            view = self._view(struct.pack(f"<{len(flat)}I", *flat), 34963)
            self.j["accessors"].append({"bufferView": view, "componentType": 5125,
                                        "count": len(flat), "type": "SCALAR"})
        else:
            view = self._view(struct.pack(f"<{len(flat)}f", *flat), 34962)
            acc = {"bufferView": view, "componentType": 5126, "count": len(values),
                   "type": {2: "VEC2", 3: "VEC3", 4: "VEC4"}[ncomp]}
            if kind == "position":
                acc["min"] = [min(v[i] for v in values) for i in range(3)]
                acc["max"] = [max(v[i] for v in values) for i in range(3)]
            self.j["accessors"].append(acc)
        return len(self.j["accessors"]) - 1

    def texture(self, png_name):
        if not self.j["samplers"]:
            # Bilinear, no mipmaps (both renderers' default lookup), repeating.
            self.j["samplers"].append({"magFilter": 9729, "minFilter": 9729,
                                       "wrapS": 10497, "wrapT": 10497})
        self.j["images"].append({"uri": png_name})
        self.j["textures"].append({"sampler": 0, "source": len(self.j["images"]) - 1})
        return len(self.j["textures"]) - 1

    def material(self, m):
        self.j["materials"].append(m)
        return len(self.j["materials"]) - 1

    def mesh(self, name, geom, material, translation=(0, 0, 0)):
        pos, nrm, uv, tan, idx = geom
        attrs = {"POSITION": self._accessor(pos, "position", 3),
                 "NORMAL": self._accessor(nrm, "normal", 3),
                 "TEXCOORD_0": self._accessor(uv, "uv", 2),
                 "TANGENT": self._accessor(tan, "tangent", 4)}
        prim = {"attributes": attrs, "indices": self._accessor(idx, "index", 1),
                "material": material}
        self.j["meshes"].append({"name": name, "primitives": [prim]})
        node = {"name": name, "mesh": len(self.j["meshes"]) - 1}
        if any(translation):
            node["translation"] = list(translation)
        self.j["nodes"].append(node)
        self.j["scenes"][0]["nodes"].append(len(self.j["nodes"]) - 1)

    def write(self, out_dir):
        bin_name = self.name + ".bin"
        self.j["buffers"].append({"uri": bin_name, "byteLength": len(self.bin)})
        for key in ("textures", "images", "samplers"):
            if not self.j[key]:
                del self.j[key]
        used = sorted({e for m in self.j["materials"] for e in m.get("extensions", {})})
        if used:
            self.j["extensionsUsed"] = used
        with open(os.path.join(out_dir, bin_name), "wb") as f:
            f.write(self.bin)
        with open(os.path.join(out_dir, self.name + ".gltf"), "w", encoding="utf-8") as f:
            json.dump(self.j, f, indent=1)
            f.write("\n")


# --- Geometry. ---------------------------------------------------------------------------------


def uv_sphere(radius, nu=64, nv=32):
    """Positions, normals, uvs (glTF's: v down the image, 0 at the north pole), tangents and
    indices of a UV sphere. u runs eastwards (seen from outside, +y up: to the right), so the
    mapping is not mirrored: tangent dp/du, bitangent N x T (w = +1) points up the image."""
    pos, nrm, uv, tan, idx = [], [], [], [], []
    for j in range(nv + 1):
        theta = math.pi * j / nv
        for i in range(nu + 1):
            phi = 2 * math.pi * i / nu
            n = (math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi))
            pos.append(tuple(radius * c for c in n))
            nrm.append(n)
            uv.append((i / nu, j / nv))
            tan.append((math.cos(phi), 0.0, -math.sin(phi), 1.0))
    row = nu + 1
    for j in range(nv):
        for i in range(nu):
            a, b = j * row + i, j * row + i + 1
            d, c = a + row, b + row
            if j != nv - 1:
                idx += [a, d, c]
            if j != 0:
                idx += [a, c, b]
    return pos, nrm, uv, tan, idx


def plane(size, n=20, y=0.0):
    """A size x size square in y = y facing +y, n x n quads. u along +x, glTF's v along +z (so
    N x T = -z is up the image: not mirrored, w = +1)."""
    pos, nrm, uv, tan, idx = [], [], [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            u, v = i / n, j / n
            pos.append(((u - 0.5) * size, y, (v - 0.5) * size))
            nrm.append((0.0, 1.0, 0.0))
            uv.append((u, v))
            tan.append((1.0, 0.0, 0.0, 1.0))
    row = n + 1
    for j in range(n):
        for i in range(n):
            a, b = j * row + i, j * row + i + 1
            d, c = a + row, b + row
            # Seen from +y with +x right, +z is towards the viewer: a b / d c is counter-
            # clockwise as a, d, c and a, c, b.
            idx += [a, d, c, a, c, b]
    return pos, nrm, uv, tan, idx


def quad(corner, e1, e2):
    """The parallelogram corner + u e1 + v e2 (u, v in [0, 1]), facing cross(e1, e2): its
    triangles are counter-clockwise seen from there."""
    cx = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
          e1[0] * e2[1] - e1[1] * e2[0]]
    n = math.sqrt(sum(v * v for v in cx))
    normal = tuple(v / n for v in cx)
    l1 = math.sqrt(sum(v * v for v in e1))
    tangent = tuple(v / l1 for v in e1) + (1.0,)
    pos = [tuple(c + u * a + v * b for c, a, b in zip(corner, e1, e2))
           for u, v in ((0, 0), (1, 0), (1, 1), (0, 1))]
    uv = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    return pos, [normal] * 4, uv, [tangent] * 4, [0, 1, 2, 0, 2, 3]


# --- Textures. ---------------------------------------------------------------------------------


def srgb8(x):
    x = min(max(x, 0.0), 1.0)
    s = 12.92 * x if x <= 0.0031308 else 1.055 * x ** (1 / 2.4) - 0.055
    return int(round(s * 255))


def metal_stripes(w=256, h=128):
    """Vertical stripes of metal colours (linear F0 values), with a darker band around v = 0.5
    (the equator)."""
    # gold, copper, silver, blue, green, red, twice: 12 stripes, 4 or 5 in view, no symmetry
    # (a mirrored u would show).
    metals = [(1.00, 0.77, 0.34), (0.96, 0.64, 0.54), (0.91, 0.92, 0.92), (0.25, 0.45, 0.95),
              (0.35, 0.85, 0.40), (0.95, 0.35, 0.30)] * 2
    rows = []
    for y in range(h):
        band = abs((y + 0.5) / h - 0.5) < 0.06
        row = []
        for x in range(w):
            c = metals[x * len(metals) // w]
            if band:
                c = tuple(0.3 * v for v in c)
            row.append(tuple(srgb8(v) for v in c))
        rows.append(row)
    return w, h, rows


def checks(w=256, h=128, n=(16, 8), a=(0.9, 0.9, 0.85), b=(0.15, 0.3, 0.8)):
    rows = []
    for y in range(h):
        row = []
        for x in range(w):
            odd = (x * n[0] // w + y * n[1] // h) % 2
            row.append(tuple(srgb8(v) for v in (b if odd else a)))
        rows.append(row)
    return w, h, rows


def bump_normals(w=512, h=512, cells=8, slope=0.6):
    """A tangent-space normal map (glTF's convention: +x right, +y up the image, +z out) of a
    height field: round bumps (a raised cosine, radius 0.35 of a cell) in a cells x cells grid
    over the lower (v > 0.5) half of the image, and V-grooves running along u over its upper
    half, both at most `slope` steep (0.6: 31 degrees), so that no shading normal turns far
    from the surface's. From the height field's gradient in (u, t), t = 1 - v up the image,
    in units of the plane's side; stored linear."""
    radius = 0.35 / cells

    def height(u, t):
        if t < 0.5:  # lower half of the image: bumps
            fu, ft = ((u * cells) % 1.0 - 0.5) / cells, ((t * cells) % 1.0 - 0.5) / cells
            r = math.hypot(fu, ft)
            amplitude = slope * 2 * radius / math.pi
            return amplitude * 0.5 * (1 + math.cos(math.pi * r / radius)) if r < radius else 0.0
        # upper half: V-grooves along u, two per cell
        period = 1.0 / (cells * 2)
        ft = (t % period) / period
        return slope * period * abs(ft - 0.5)

    eps = 0.25 / w
    rows = []
    for y in range(h):
        t = 1 - (y + 0.5) / h
        row = []
        for x in range(w):
            u = (x + 0.5) / w
            dhu = (height(u + eps, t) - height(u - eps, t)) / (2 * eps)
            dht = (height(u, t + eps) - height(u, t - eps)) / (2 * eps)
            n = (-dhu, -dht, 1.0)
            ln = math.sqrt(sum(c * c for c in n))
            row.append(tuple(int(round((c / ln * 0.5 + 0.5) * 255)) for c in n))
        rows.append(row)
    return w, h, rows


def emissive_stripes(w=256, h=128):
    """Horizontal stripes (along u) of warm and cool light, with dark gaps."""
    cols = [(0.25, 0.14, 0.04), (0.005, 0.005, 0.005), (0.05, 0.18, 0.25), (0.005, 0.005, 0.005)]
    rows = []
    for y in range(h):
        c = cols[(y * 8 // h) % 4]
        rows.append([tuple(srgb8(v) for v in c)] * w)
    return w, h, rows


# --- Environment maps. -------------------------------------------------------------------------


def direction(s, t):
    """Glint's (and Cycles', after the axis conversion) equirectangular mapping, y up:
    docs/scene-format.md, "Environment maps"."""
    theta, phi = math.pi * t, 2 * math.pi * s - math.pi
    return (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))


def sky(sun_elevation_deg, sun_azimuth_deg, sun=True, scale=1.0, w=1024, h=512):
    """Rows of linear RGB radiance. The sun's azimuth is measured from +x towards -z
    (counter-clockwise seen from above); a disc of 2.5 degrees radius, soft over its last half
    degree, of radiance 400 x (1, 0.93, 0.82)."""
    el, az = math.radians(sun_elevation_deg), math.radians(sun_azimuth_deg)
    sd = (math.cos(el) * math.cos(az), math.sin(el), -math.cos(el) * math.sin(az))
    radius, soft = math.radians(2.5), math.radians(0.5)

    def radiance(d, sun_weight):
        x, y, z = d
        if y >= 0:
            k = math.sqrt(y)
            c = [(1 - k) * hz + k * zn for hz, zn in zip((1.0, 0.95, 0.9), (0.25, 0.45, 1.0))]
            glow = max(0.0, x * sd[0] + y * sd[1] + z * sd[2]) ** 16
            c = [v + 1.5 * glow * g for v, g in zip(c, (1.0, 0.8, 0.55))]
            # a little azimuthal structure: a faint pink band towards -z
            c = [v * (1 + 0.25 * max(0.0, -z) ** 4 * (1 - k)) for v in c]
        else:
            c = [0.28, 0.23, 0.18]
            c = [v * (0.6 + 0.4 * math.exp(8 * y)) for v in c]  # darker towards the nadir
        if sun_weight:
            cosang = max(-1.0, min(1.0, x * sd[0] + y * sd[1] + z * sd[2]))
            ang = math.acos(cosang)
            wgt = 1.0 if ang < radius - soft else max(0.0, (radius - ang) / soft)
            c = [v + sun_weight * wgt * 400 * s for v, s in zip(c, (1.0, 0.93, 0.82))]
        return [scale * v for v in c]

    rows = []
    near = radius + math.radians(1.0)
    for j in range(h):
        row = []
        for i in range(w):
            d = direction((i + 0.5) / w, (j + 0.5) / h)
            close = sun and math.acos(max(-1.0, min(1.0, sum(a * b for a, b in zip(d, sd))))) < near
            if not close:
                row.append(radiance(d, 0.0))
                continue
            # Near the sun: the texel's mean over a 6 x 6 grid (the disc's edge is soft anyway).
            acc = [0.0, 0.0, 0.0]
            for a in range(6):
                for b in range(6):
                    v = radiance(direction((i + (a + 0.5) / 6) / w, (j + (b + 0.5) / 6) / h), 1.0)
                    acc = [p + q for p, q in zip(acc, v)]
            row.append([v / 36 for v in acc])
        rows.append(row)
    return w, h, rows


# --- Assets. -----------------------------------------------------------------------------------


def metal(out):
    """(1) Textured metal."""
    g = Gltf("metal")
    write_png(os.path.join(out, "metal_base.png"), *metal_stripes())
    t = g.texture("metal_base.png")
    m = g.material({"name": "striped_metal", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": t}, "metallicFactor": 1.0, "roughnessFactor": 0.3}})
    g.mesh("sphere", uv_sphere(1.0), m)
    g.write(out)


def dielectric(out):
    """(2) Dielectrics: rough red, and smoother textured checks."""
    g = Gltf("dielectric")
    write_png(os.path.join(out, "dielectric_checks.png"), *checks())
    t = g.texture("dielectric_checks.png")
    rough = g.material({"name": "rough_red", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.12, 0.08, 1.0], "metallicFactor": 0.0,
        "roughnessFactor": 0.5}})
    smooth = g.material({"name": "smooth_checks", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": t}, "metallicFactor": 0.0, "roughnessFactor": 0.15}})
    g.mesh("rough", uv_sphere(0.9), rough, (-1.0, 0.0, 0.0))
    g.mesh("smooth", uv_sphere(0.9), smooth, (1.0, 0.0, 0.0))
    g.write(out)


def normalmap(out):
    """(3) A normal map on a plane."""
    g = Gltf("normalmap")
    write_png(os.path.join(out, "normalmap_normal.png"), *bump_normals())
    t = g.texture("normalmap_normal.png")
    m = g.material({"name": "bumpy", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5},
        "normalTexture": {"index": t, "scale": 1.0}})
    g.mesh("plane", plane(4.0), m)
    g.write(out)


def emissive(out):
    """(4) An emissive textured sphere over a diffuse floor."""
    g = Gltf("emissive")
    write_png(os.path.join(out, "emissive_stripes.png"), *emissive_stripes())
    t = g.texture("emissive_stripes.png")
    lamp = g.material({"name": "lamp", "pbrMetallicRoughness": {
        "baseColorFactor": [0.05, 0.05, 0.05, 1.0], "metallicFactor": 0.0,
        "roughnessFactor": 0.6}, "emissiveFactor": [1.0, 1.0, 1.0],
        "emissiveTexture": {"index": t},
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4.0}}})
    floor = g.material({"name": "floor", "pbrMetallicRoughness": {
        "baseColorFactor": [0.6, 0.6, 0.6, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    g.mesh("lamp", uv_sphere(0.5), lamp, (0.0, 0.6, 0.0))
    g.mesh("floor", plane(8.0, 8), floor)
    g.write(out)


def lamps(out):
    """(6) Many lights: 36 small emissive spheres of six colours (16 x 8 segments each, 256
    triangles: 9216 emissive triangles in all) in a 6 x 6 grid over a diffuse floor, around a
    diffuse sphere, under a dim sky (issue 22)."""
    g = Gltf("lamps")
    floor = g.material({"name": "floor", "pbrMetallicRoughness": {
        "baseColorFactor": [0.6, 0.6, 0.6, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    ball = g.material({"name": "ball", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    colours = [(1.0, 0.3, 0.3), (1.0, 0.6, 0.2), (0.9, 0.9, 0.3),
               (0.3, 1.0, 0.4), (0.3, 0.6, 1.0), (0.8, 0.4, 1.0)]
    lamp_materials = [g.material({"name": f"lamp{k}", "pbrMetallicRoughness": {
        "baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
        "emissiveFactor": list(c),
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 200.0}}})
        for k, c in enumerate(colours)]
    g.mesh("floor", plane(12.0, 12), floor)
    g.mesh("ball", uv_sphere(0.6), ball, (-1.0, 0.6, 0.0))
    for i in range(6):
        for j in range(6):
            x, z = -3.0 + 1.2 * i, -3.0 + 1.2 * j
            y = 1.8 + 0.3 * ((i + 2 * j) % 3)
            g.mesh(f"lamp{i}_{j}", uv_sphere(0.06, 16, 8), lamp_materials[(i + j) % 6], (x, y, z))
    g.write(out)


def caustic(out):
    """(7) Caustics: a solid glass ball (KHR_materials_transmission and _volume, index 1.5) and a metal one on a
    diffuse floor under sky.hdr's sun, which the glass focuses onto the floor (issue 22)."""
    g = Gltf("caustic")
    floor = g.material({"name": "floor", "pbrMetallicRoughness": {
        "baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    glass = g.material({"name": "glass", "pbrMetallicRoughness": {
        "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                       "KHR_materials_ior": {"ior": 1.5},
                       # A solid ball: without a volume glTF's transmission is thin-walled
                       # (no refraction), which Blender's importer does not follow.
                       "KHR_materials_volume": {"thicknessFactor": 1.0}}})
    metal = g.material({"name": "metal", "pbrMetallicRoughness": {
        "baseColorFactor": [0.95, 0.8, 0.55, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.2}})
    g.mesh("floor", plane(10.0, 10), floor)
    g.mesh("glass", uv_sphere(0.5), glass, (0.0, 0.5, 0.0))
    g.mesh("metal", uv_sphere(0.4), metal, (1.2, 0.4, -0.6))
    g.write(out)


def room(out):
    """(8) An interior: a closed room of separate wall quads that share their edges (6 x 5 x
    2.5 m), lit only through a window in its -x wall by sky.hdr's sun and sky (issue 22:
    nearly all of its light is indirect; corners show any leak)."""
    g = Gltf("room")
    wall = g.material({"name": "wall", "pbrMetallicRoughness": {
        "baseColorFactor": [0.75, 0.72, 0.68, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    x0, x1, y0, y1, z0, z1 = -3.0, 3.0, 0.0, 2.5, -2.5, 2.5
    # Inward faces: floor, ceiling, +x wall, both z walls.
    g.mesh("floor", quad((x0, y0, z0), (0, 0, z1 - z0), (x1 - x0, 0, 0)), wall)
    g.mesh("ceiling", quad((x0, y1, z0), (x1 - x0, 0, 0), (0, 0, z1 - z0)), wall)
    g.mesh("east", quad((x1, y0, z0), (0, 0, z1 - z0), (0, y1 - y0, 0)), wall)
    g.mesh("north", quad((x0, y0, z0), (x1 - x0, 0, 0), (0, y1 - y0, 0)), wall)
    g.mesh("south", quad((x0, y0, z1), (0, y1 - y0, 0), (x1 - x0, 0, 0)), wall)
    # The -x wall, facing +x, around a window from y 1.0 to 2.0 and z -0.8 to 0.8.
    wy0, wy1, wz0, wz1 = 1.0, 2.0, -0.8, 0.8
    parts = [((y0, z0), (wy0 - y0, z1 - z0)), ((wy1, z0), (y1 - wy1, z1 - z0)),
             ((wy0, z0), (wy1 - wy0, wz0 - z0)), ((wy0, wz1), (wy1 - wy0, z1 - wz1))]
    for k, ((py, pz), (hy, hz)) in enumerate(parts):
        g.mesh(f"west{k}", quad((x0, py, pz), (0, hy, 0), (0, 0, hz)), wall)
    furniture = g.material({"name": "table", "pbrMetallicRoughness": {
        "baseColorFactor": [0.55, 0.3, 0.15, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6}})
    g.mesh("ball", uv_sphere(0.4), furniture, (0.5, 0.4, -0.8))
    g.write(out)


def normaltilt(out):
    """(3b) Four 1 x 1 m patches in a row along x, grey 0.8, roughness 0.5, to take the normal
    map apart: flat; flat with a constant normal map tilted 31 degrees towards -x (towards
    sky_low's sun, whose direction is (-0.866, 0.139, -0.5)); the same tilted towards +x (away
    from it); and a patch really tilted 31 degrees towards -x (turned about its z axis), without
    a map: what the mapped patch imitates."""
    g = Gltf("normaltilt")
    a = math.radians(31)
    c, s = math.cos(a), math.sin(a)
    for k, (name, n) in enumerate((("flat", None), ("mapped_left", (-s, 0.0, c)),
                                    ("mapped_right", (s, 0.0, c)), ("tilted_left", None))):
        mat = {"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0,
            "roughnessFactor": 0.5}}
        if n:
            png = f"normaltilt_{name}.png"
            texel = tuple(int(round((v * 0.5 + 0.5) * 255)) for v in n)
            write_png(os.path.join(out, png), 4, 4, [[texel] * 4] * 4)
            mat["normalTexture"] = {"index": g.texture(png)}
        geom = plane(1.0, 1)
        if name == "tilted_left":
            def rot(v):  # about z: +y turns towards -x
                return (v[0] * c - v[1] * s, v[0] * s + v[1] * c, v[2])
            pos, nrm, uv, tan, idx = geom
            geom = ([rot(p) for p in pos], [rot(v) for v in nrm], uv,
                    [rot(t[:3]) + (t[3],) for t in tan], idx)
        g.mesh(name, geom, g.material(mat), (k - 1.5, 0.0, 0.0))
    g.write(out)


def near(out):
    """(9) Near area lights: a corner of two walls and a floor, a white panel light 2 x 1 m
    lying 0.3 m above the floor close to the back wall (facing down), a second one upright 0.25
    m from the left wall (facing it), and a diffuse box under the first: points close to large
    emitters, which area sampling serves badly (issue 22). Under night.hdr (the scene file)."""
    g = Gltf("near")
    grey = g.material({"name": "grey", "pbrMetallicRoughness": {
        "baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    box = g.material({"name": "box", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.5, 0.3, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    # Double-sided: Cycles' mesh lights emit from both faces whatever the file says
    # (../shared/platform-notes.md), so both renderers see both faces emit.
    panel = g.material({"name": "panel", "doubleSided": True, "pbrMetallicRoughness": {
        "baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
        "emissiveFactor": [1.0, 0.95, 0.85],
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1.5}}})
    g.mesh("floor", quad((-2.0, 0.0, -2.0), (0, 0, 4.0), (4.0, 0, 0)), grey)
    g.mesh("back", quad((-2.0, 0.0, -2.0), (4.0, 0, 0), (0, 2.5, 0)), grey)
    g.mesh("left", quad((-2.0, 0.0, -2.0), (0, 2.5, 0), (0, 0, 4.0)), grey)
    # Facing down (-y), 0.3 m up; facing the left wall (-x), 0.25 m from it.
    g.mesh("panel_low", quad((-1.0, 0.3, -1.8), (2.0, 0, 0), (0, 0, 1.0)), panel)
    g.mesh("panel_side", quad((-1.75, 0.2, 0.0), (0, 0, 1.0), (0, 1.0, 0)), panel)
    b0, b1 = (-0.2, 0.0, -1.4), (0.3, 0.15, -1.0)
    g.mesh("box_top", quad((b0[0], b1[1], b0[2]), (0, 0, b1[2] - b0[2]), (b1[0] - b0[0], 0, 0)), box)
    g.mesh("box_front", quad((b0[0], b0[1], b1[2]), (b1[0] - b0[0], 0, 0), (0, b1[1] - b0[1], 0)), box)
    g.mesh("box_right", quad((b1[0], b0[1], b0[2]), (0, b1[1] - b0[1], 0), (0, 0, b1[2] - b0[2])), box)
    g.write(out)


# The cameras look along -z: sky's sun (azimuth 230 degrees) is behind the camera, to the left;
# sky_low's (150 degrees) skims the plane from the back left.
WRITERS = {
    "metal": metal, "dielectric": dielectric, "normalmap": normalmap,
    "normaltilt": normaltilt, "emissive": emissive, "lamps": lamps, "caustic": caustic,
    "room": room, "near": near,
    "sky": lambda out: write_hdr(os.path.join(out, "sky.hdr"), *sky(40, 230)),
    "sky_low": lambda out: write_hdr(os.path.join(out, "sky_low.hdr"), *sky(8, 150)),
    "sky_low_nosun": lambda out: write_hdr(os.path.join(out, "sky_low_nosun.hdr"),
                                           *sky(8, 150, sun=False)),
    "night": lambda out: write_hdr(os.path.join(out, "night.hdr"),
                                   *sky(0, 0, sun=False, scale=0.02)),
}


def main():
    if len(sys.argv) < 2 or any(n not in WRITERS for n in sys.argv[2:]):
        print(f"usage: make_assets.py OUT_DIR [{' | '.join(WRITERS)} ...]", file=sys.stderr)
        sys.exit(2)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name in sys.argv[2:] or WRITERS:
        WRITERS[name](out)


if __name__ == "__main__":
    main()
