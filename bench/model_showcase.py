#!/usr/bin/env python3
"""Writes the glTF models whose model-mode renders the README and docs show (issue 12: "textured
metal, a normal-mapped surface and a double-sided plane"): small .gltf files with their .bin
buffers and PNG textures, built with bench/cycles/gltf/make_assets.py's writer.

    bench/model_showcase.py OUT_DIR

writes into OUT_DIR:

  showcase.gltf      three things in a row on the ground: a sphere of textured metal (stripes of
                     gold, copper, silver, blue, green and red metal, roughness 0.3), a sphere
                     of white-grey plastic with a normal map of bumps and grooves (roughness
                     0.4), and a curled sheet (240 degrees of a cylinder) with a checked
                     texture whose material is double-sided, its gap turned so that the camera
                     sees its inside (the front faces) through it and its outside (the back
                     faces) beside it;
  sheet_one_sided.gltf  the sheet alone, single-sided: its back faces are not drawn;
  sheet_two_sided.gltf  the sheet alone, double-sided.

Every file is +y up, metres, counter-clockwise front faces; the output is deterministic.
Render with `glint OUT_DIR/showcase.gltf` (the model mode's defaults).
"""

import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "cycles", "gltf"))
from make_assets import (Gltf, bump_normals, checks, metal_stripes, uv_sphere,  # noqa: E402
                         write_png)


def sheet(radius=0.7, height=1.5, arc_deg=240.0, n_around=64, n_up=4, turn_deg=40.0):
    """A sheet curled `arc_deg` around the y axis at `radius`, from y = 0 to `height`, its gap
    towards +z before it is turned `turn_deg` about y. Front faces (counter-clockwise seen from
    there) on the inside, the concave side; u around, v down the texture."""
    pos, nrm, uv, tan, idx = [], [], [], [], []
    turn = math.radians(turn_deg)
    c, s = math.cos(turn), math.sin(turn)

    def rot(x, z):
        return (c * x + s * z, -s * x + c * z)

    for j in range(n_up + 1):
        y = height * j / n_up
        for i in range(n_around + 1):
            # From the gap's right edge round through -z (the back) to its left edge.
            a = math.radians(90 - arc_deg / 2 + arc_deg * i / n_around)
            x, z = radius * math.cos(a), -radius * math.sin(a)
            px, pz = rot(x, z)
            nx, nz = rot(-math.cos(a), math.sin(a))  # inwards: the front faces' normal
            tx, tz = rot(-math.sin(a), -math.cos(a))  # d position / d a
            pos.append((px, y, pz))
            nrm.append((nx, 0.0, nz))
            uv.append((1 - i / n_around, 1 - j / n_up))
            # u grows with -a: the tangent is -d position / d a; seen from inside with +y up,
            # u runs to the right and v-up is +y: not mirrored, w = +1.
            tan.append((-tx, 0.0, -tz, 1.0))
    row = n_around + 1
    for j in range(n_up):
        for i in range(n_around):
            a, b = j * row + i, j * row + i + 1
            d, e = a + row, b + row
            # Seen from inside (the axis) the points a, b, e, d run counter-clockwise.
            idx += [a, e, b, a, d, e]
    return pos, nrm, uv, tan, idx


def translated(geom, offset):
    pos, nrm, uv, tan, idx = geom
    return [tuple(p[k] + offset[k] for k in range(3)) for p in pos], nrm, uv, tan, idx


def sheet_material(g, texture, double_sided):
    return g.material({"name": "sheet", "doubleSided": double_sided, "pbrMetallicRoughness": {
        "baseColorTexture": {"index": texture}, "metallicFactor": 0.0, "roughnessFactor": 0.6}})


def showcase(out):
    g = Gltf("showcase")
    write_png(os.path.join(out, "showcase_metal.png"), *metal_stripes())
    write_png(os.path.join(out, "showcase_normal.png"), *bump_normals(slope=0.9))
    write_png(os.path.join(out, "showcase_checks.png"), *checks(n=(8, 4)))
    metal = g.material({"name": "striped_metal", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": g.texture("showcase_metal.png")}, "metallicFactor": 1.0,
        "roughnessFactor": 0.3}})
    bumpy = g.material({"name": "bumpy_plastic", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.8, 0.78, 1.0], "metallicFactor": 0.0,
        "roughnessFactor": 0.4}, "normalTexture": {"index": g.texture("showcase_normal.png")}})
    checked = g.texture("showcase_checks.png")
    g.mesh("metal", uv_sphere(0.7), metal, (-1.9, 0.7, 0.0))
    g.mesh("bumpy", uv_sphere(0.7), bumpy, (0.0, 0.7, 0.0))
    g.mesh("sheet", translated(sheet(), (1.9, 0.0, 0.0)), sheet_material(g, checked, True))
    g.write(out)
    for name, double_sided in (("sheet_one_sided", False), ("sheet_two_sided", True)):
        g = Gltf(name)
        g.mesh("sheet", sheet(), sheet_material(g, g.texture("showcase_checks.png"),
                                                double_sided))
        g.write(out)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    os.makedirs(sys.argv[1], exist_ok=True)
    showcase(sys.argv[1])


if __name__ == "__main__":
    main()
