"""Renders one of bench/cycles/gltf/'s Glint scenes in Blender Cycles (CPU), through Blender's
own glTF importer, to compare glTF metallic-roughness materials (issue 12, "Against Cycles").

Run headless (Blender 3.4, Debian's `blender` package):

    blender -b --factory-startup --python bench/cycles/gltf/gltf_cycles.py -- \
        --scene OUT/metal.test --out cycles.exr --spp 1024 --threads 2 --seed 0

The Glint scene file is the single source of the set-up: the script reads its `size`,
`camera`, `maxdepth`, `environment` and `mesh` lines (and refuses any other command, so that
nothing Glint renders goes unnoticed here) and builds the same scene:

  - every `mesh` file through bpy.ops.import_scene.gltf with its defaults: glTF's +y up becomes
    Blender's +z up, glTF (x, y, z) = Blender (x, -z, y); the script checks the imported
    vertices' bounds against the file's accessors under that conversion. The importer builds a
    Principled BSDF per material (base colour and its texture, metallic and roughness, the
    normal map through a Normal Map node in tangent space of the UV map, emission and its
    strength); the script changes only the Principled BSDF's distribution to GGX (3.4's default
    is Multiscatter GGX; glTF's BRDF is single-scattering) and prints what the importer made;
  - the `environment` file (and scale, rotation) as the world: an Environment Texture,
    equirectangular, Linear interpolation, into a Background of strength `scale`; Glint's
    rotation r is a Point Mapping of Z rotation -r (docs/scene-format.md);
  - the camera (eye, look-at, up, vertical field of view) converted by the same axis matrix;
  - Cycles on the CPU: --threads, --spp, --seed, max bounces `maxdepth` - 1 for the total and
    every kind (Cycles counts bounces after the first hit), no denoiser, no adaptive sampling,
    no clamping, no glossy filter (blur_glossy 0), caustics on, a box pixel filter 1 pixel
    wide; view transform Standard; output a 32-bit float RGB OpenEXR of linear radiance.

Issue 23 (bench/cycles/layers-media/README.md) adds the subset of Glint's own commands that
its media scenes use: `background r g b` (the world's colour), `quadLight` (a quad emitting from
its front face only), `diffuse` (Lambert), `transmission`/`ior`/`roughness` (a Glass BSDF, GGX
of roughness sqrt(alpha)), `sphere` (a smooth icosphere), `plane` (a square 2 km wide),
`medium`, `interior` and `fog` (Volume Scatter + Volume Absorption on a material's or the
world's Volume output; a density grid as a Volume object reading the same .vdb). Option
--sheen-v1 gives materials with KHR_materials_sheen Principled v1's sheen, which the importer
leaves out. A line `# cycles-args: ARGS` in a scene is read by run.sh, not here.

It prints one line that scripts parse, with the wall-clock and CPU time of
bpy.ops.render.render alone:

    CYCLES_RESULT scene=metal.test width=256 height=256 spp=1024 threads=2 seed=0 bounces=16 \
        render_s=SECONDS cpu_s=CPU_SECONDS
"""

import argparse
import json
import math
import os
import shlex
import struct
import sys
import time

import bpy
from bpy_extras.io_utils import axis_conversion
from mathutils import Matrix, Quaternion, Vector


VDB_SHIFT = 1.0  # --vdb-shift


def fail(message):
    print(f"gltf_cycles.py: error: {message}", file=sys.stderr)
    sys.exit(1)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="gltf_cycles.py", description=__doc__.split("\n")[0])
    p.add_argument("--scene", required=True, help="the Glint scene file (bench/cycles/gltf/*.test)")
    p.add_argument("--out", required=True, help="the 32-bit float EXR to write")
    p.add_argument("--spp", type=int, default=1024, help="samples per pixel")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--multiscatter", action="store_true",
                   help="keep Blender's Multiscatter GGX instead of GGX (for comparison)")
    p.add_argument("--lambert", action="store_true",
                   help="diagnostic: replace every Principled BSDF of metallic 0, no "
                        "transmission and no texture by a Diffuse BSDF (Lambert) of its base "
                        "colour, to tell the Principled BSDF's Burley diffuse from the rest")
    p.add_argument("--sheen-v1", action="store_true",
                   help="Blender 3.4's importer leaves KHR_materials_sheen out: give each "
                        "material that has it the Principled BSDF's own (v1) sheen instead, "
                        "Sheen = the largest channel of sheenColorFactor, Sheen Tint 1 (towards "
                        "the base colour's hue: v1's sheen has no colour of its own)")
    p.add_argument("--vdb-shift", type=float, default=1.0,
                   help="move a density grid by this many half voxels down each index axis, to "
                        "undo Blender 3.4's half-voxel offset (default 1; 0: Blender's placement)")
    p.add_argument("--volume-step-rate", type=float, default=0.25,
                   help="Cycles' volume step rate for density grids (its ray marching steps, "
                        "in voxels; default 0.25, Blender's 1)")
    a = p.parse_args(argv)
    if a.spp < 1 or a.threads < 1:
        p.error("--spp and --threads must be at least 1")
    return a


def read_scene(path):
    """The Glint scene's settings; the commands this script does not reproduce are errors.

    Beside glTF meshes under an environment map, the subset of Glint's own commands that the
    media scenes use (bench/cycles/layers-media): `background r g b`, `quadLight`, `diffuse`,
    `transmission`, `ior`, `roughness`, `plane`, `sphere`, `medium`, `interior`, `fog`. Shapes
    take the material (and interior) current at their line, as in Glint."""
    s = {"size": (640, 480), "camera": None, "maxdepth": 5, "environment": None, "meshes": [],
         "background": None, "quads": [], "shapes": [], "media": {}, "fog": None}
    material = {"diffuse": (0.0, 0.0, 0.0), "transmission": (0.0, 0.0, 0.0), "ior": 1.0,
                "roughness": 0.0, "interior": None, "interface": False}
    base = os.path.dirname(os.path.abspath(path))
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            t = shlex.split(line.split("#")[0])
            if not t:
                continue
            where = f"{path}:{number}"
            cmd, args = t[0], t[1:]
            nums = lambda n: [float(x) for x in args[:n]]  # noqa: E731
            if cmd == "size":
                s["size"] = (int(args[0]), int(args[1]))
            elif cmd == "camera":
                v = [float(x) for x in args]
                if len(v) != 10:
                    fail(f"{where}: camera takes 10 numbers")
                s["camera"] = (Vector(v[0:3]), Vector(v[3:6]), Vector(v[6:9]), v[9])
            elif cmd == "maxdepth":
                s["maxdepth"] = int(args[0])
            elif cmd == "integrator":
                if args != ["path"]:
                    fail(f"{where}: only 'integrator path' has a Cycles counterpart")
            elif cmd == "spp":
                pass  # --spp decides
            elif cmd == "environment":
                scale = float(args[1]) if len(args) > 1 else 1.0
                rotation = float(args[2]) if len(args) > 2 else 0.0
                s["environment"] = (os.path.join(base, args[0]), scale, rotation)
            elif cmd == "mesh":
                s["meshes"].append(os.path.join(base, args[0]))
            elif cmd == "background":
                if len(args) != 3:
                    fail(f"{where}: only a constant background (3 numbers) is reproduced")
                s["background"] = tuple(nums(3))
            elif cmd == "quadLight":
                v = nums(12)
                s["quads"].append((Vector(v[0:3]), Vector(v[3:6]), Vector(v[6:9]), tuple(v[9:12])))
            elif cmd in ("diffuse", "transmission"):
                material[cmd] = tuple(min(max(x, 0.0), 1.0) for x in nums(3))
            elif cmd in ("ior", "roughness"):
                material[cmd] = float(args[0])
            elif cmd in ("specular", "emission"):
                if any(float(x) for x in args):
                    fail(f"{where}: only '{cmd} 0 0 0' is reproduced")
            elif cmd == "plane":
                v = nums(6)
                s["shapes"].append(("plane", Vector(v[0:3]), Vector(v[3:6]), dict(material)))
            elif cmd == "sphere":
                v = nums(4)
                s["shapes"].append(("sphere", Vector(v[0:3]), v[3], dict(material)))
            elif cmd == "medium":
                s["media"][args[0]] = read_medium(where, args[1:], base)
            elif cmd in ("interior", "fog"):
                name = None if args[0] == "none" else args[0]
                if name is not None and name not in s["media"]:
                    fail(f"{where}: no medium '{name}'")
                if cmd == "fog":
                    s["fog"] = name
                else:
                    material["interior"] = name
                    material["interface"] = args[1:] == ["interface"]
            else:
                fail(f"{where}: '{cmd}' is not reproduced in Cycles by this script")
    if s["camera"] is None:
        fail(f"{path}: needs a camera")
    if not s["meshes"] and not s["shapes"] and not s["quads"]:
        fail(f"{path}: nothing to render")
    if s["maxdepth"] < 1:
        fail(f"{path}: maxdepth must be at least 1")
    return s


def read_medium(where, args, base):
    """Glint's `medium` parameters (docs/scene-format.md, "Media") as sigma_a, sigma_s, g and
    the density grid: sigma_t = 1 / meanfreepath, sigma_s = albedo sigma_t with `albedo`."""
    m = {"sigma_a": [0.0] * 3, "sigma_s": [0.0] * 3, "g": 0.0, "grid": None}
    albedo, mfp, scale, i = None, None, 1.0, 0
    while i < len(args):
        key = args[i]
        if key in ("absorption", "scattering", "albedo"):
            v = [float(x) for x in args[i + 1:i + 4]]
            i += 4
            if key == "albedo":
                albedo = v
            else:
                m["sigma_a" if key == "absorption" else "sigma_s"] = v
        elif key in ("meanfreepath", "g", "scale"):
            v = float(args[i + 1])
            i += 2
            if key == "meanfreepath":
                mfp = v
            elif key == "g":
                m["g"] = v
            else:
                scale = v
        elif key == "density":
            m["grid"] = os.path.join(base, args[i + 1])
            i += 2
            if i < len(args) and args[i] not in ("absorption", "scattering", "albedo",
                                                 "meanfreepath", "g", "scale", "density"):
                fail(f"{where}: this script reads only the grid named 'density'")
        else:
            fail(f"{where}: medium parameter '{key}' is not reproduced")
    if albedo is not None:
        sigma_t = 1.0 / mfp
        m["sigma_s"] = [a * sigma_t for a in albedo]
        m["sigma_a"] = [(1 - a) * sigma_t for a in albedo]
    m["sigma_a"] = [x * scale for x in m["sigma_a"]]
    m["sigma_s"] = [x * scale for x in m["sigma_s"]]
    return m


def gltf_bounds(path, conv):
    """Blender-space bounds of the default scene's meshes, from the accessors' min and max
    under each node's world matrix (TRS or matrix, through the hierarchy), and whether they
    are exact: the box of a transformed box is the transformed points' box when every node
    only permutes and scales the axes (rotations by multiples of 90 degrees), else larger."""
    with open(path, encoding="utf-8") as f:
        j = json.load(f)
    lo, hi = Vector((math.inf,) * 3), Vector((-math.inf,) * 3)
    exact = True

    def local(node):
        if "matrix" in node:
            return Matrix([node["matrix"][c::4] for c in range(4)])  # column-major
        x, y, z, w = node.get("rotation", (0, 0, 0, 1))
        r = Quaternion((w, x, y, z)).to_matrix().to_4x4()
        sx, sy, sz = node.get("scale", (1, 1, 1))
        return (Matrix.Translation(Vector(node.get("translation", (0, 0, 0)))) @ r @
                Matrix.Diagonal((sx, sy, sz, 1.0)))

    def visit(index, parent):
        nonlocal lo, hi, exact
        node = j["nodes"][index]
        world = parent @ local(node)
        if "mesh" in node:
            m3 = world.to_3x3()
            if any(sum(1 for c in range(3) if abs(m3[r][c]) > 1e-6) != 1 for r in range(3)):
                exact = False
            for prim in j["meshes"][node["mesh"]]["primitives"]:
                acc = j["accessors"][prim["attributes"]["POSITION"]]
                for corner in ((x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)):
                    p = Vector([(acc["min"], acc["max"])[c][i] for i, c in enumerate(corner)])
                    q = conv @ (world @ p)
                    lo = Vector(map(min, lo, q))
                    hi = Vector(map(max, hi, q))
        for child in node.get("children", ()):
            visit(child, world)

    roots = j["scenes"][j.get("scene", 0)]["nodes"] if "scenes" in j else range(len(j["nodes"]))
    for index in roots:
        visit(index, Matrix.Identity(4))
    return lo, hi, exact


def import_gltf(path, conv):
    # Debian 12's Blender 3.4 importer uses numpy.bool, which the packaged NumPy 1.24 removed
    # ("module 'numpy' has no attribute 'bool'"): restore the alias, which meant bool.
    import numpy
    if not hasattr(numpy, "bool"):
        numpy.bool = bool
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=path)
    objs = [o for o in bpy.data.objects if o not in before and o.type == "MESH"]
    if not objs:
        fail(f"the importer read no mesh from {path}")
    bpy.context.view_layer.update()
    lo, hi = Vector((math.inf,) * 3), Vector((-math.inf,) * 3)
    for o in objs:
        for v in o.data.vertices:
            q = o.matrix_world @ v.co
            lo = Vector(map(min, lo, q))
            hi = Vector(map(max, hi, q))
    elo, ehi, exact = gltf_bounds(path, conv)
    tol = 1e-4 * max(1.0, (ehi - elo).length)
    if (exact and ((lo - elo).length > tol or (hi - ehi).length > tol)) or \
            any(lo[i] < elo[i] - tol or hi[i] > ehi[i] + tol for i in range(3)):
        fail(f"{path}: imported bounds {tuple(lo)}..{tuple(hi)} are not the file's "
             f"{tuple(elo)}..{tuple(ehi)} under the axis conversion")
    return objs


def describe_material(m):
    """One line per linked input of the Principled BSDF: what the importer made of the glTF."""
    nt = m.node_tree
    bsdf = next((n for n in nt.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        return f"  {m.name}: no Principled BSDF ({[n.type for n in nt.nodes]})"
    lines = [f"  {m.name}: distribution {bsdf.distribution}"]
    for inp in bsdf.inputs:
        if inp.is_linked:
            chain, node = [], inp.links[0].from_node
            for _ in range(6):
                label = node.type
                if node.type == "TEX_IMAGE" and node.image:
                    label += f"({node.image.name}, {node.image.colorspace_settings.name}, " \
                             f"{node.interpolation})"
                elif node.type == "NORMAL_MAP":
                    label += f"({node.space}, uv '{node.uv_map}', strength " \
                             f"{node.inputs['Strength'].default_value:g})"
                elif node.type == "MATH":
                    label += f"({node.operation}, " + ", ".join(
                        f"{i.default_value:g}" for i in node.inputs[:2] if not i.is_linked) + ")"
                chain.append(label)
                linked = [i for i in node.inputs if i.is_linked]
                if not linked:
                    break
                node = linked[0].links[0].from_node
            lines.append(f"    {inp.name} <- {' <- '.join(chain)}")
        elif inp.name in ("Base Color", "Metallic", "Roughness", "Specular", "Emission",
                          "Emission Strength", "IOR", "Transmission", "Alpha", "Specular Tint",
                          "Sheen", "Sheen Tint", "Clearcoat", "Clearcoat Roughness"):
            v = inp.default_value
            v = tuple(round(x, 4) for x in v) if hasattr(v, "__len__") else round(v, 4)
            lines.append(f"    {inp.name} = {v}")
    return "\n".join(lines)


def plain_dielectric(n):
    """A Principled BSDF of metallic 0, no transmission, no emission and no linked inputs but
    its output: what --lambert replaces."""
    inputs = n.inputs
    linked = [i.name for i in inputs if i.is_linked]
    return (not linked and inputs["Metallic"].default_value == 0 and
            inputs["Transmission"].default_value == 0 and
            max(inputs["Emission"].default_value[:3]) == 0)


def lambert(tree, n):
    """Replaces Principled BSDF `n` by a Diffuse BSDF (roughness 0: Lambert) of its base colour."""
    d = tree.nodes.new("ShaderNodeBsdfDiffuse")
    d.inputs["Color"].default_value = n.inputs["Base Color"].default_value
    d.inputs["Roughness"].default_value = 0.0
    for link in list(n.outputs["BSDF"].links):
        tree.links.new(d.outputs["BSDF"], link.to_socket)
    tree.nodes.remove(n)


def shader_material(name, shape_material, media):
    """A Glint course material as Cycles nodes (docs/scene-format.md, "Path tracing": the
    path tracer's BSDF of it): `transmission` T > 0 a Glass BSDF of colour T, index `ior`,
    GGX of roughness sqrt(alpha) (Cycles squares its roughness; Glint's `roughness` is alpha)
    or Sharp at 0; else a Lambertian Diffuse BSDF (roughness 0) of colour `diffuse`. An
    interior medium goes to the Volume output; with `interface` the surface is left out
    (Cycles: no surface shader, the boundary is only the volume's)."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    interior = shape_material["interior"]
    if not (interior and shape_material["interface"]):
        if max(shape_material["transmission"]) > 0:
            bsdf = nt.nodes.new("ShaderNodeBsdfGlass")
            bsdf.inputs["Color"].default_value = (*shape_material["transmission"], 1.0)
            bsdf.inputs["IOR"].default_value = shape_material["ior"]
            alpha = shape_material["roughness"]
            bsdf.distribution = "GGX" if alpha >= 1e-4 else "SHARP"
            bsdf.inputs["Roughness"].default_value = math.sqrt(alpha) if alpha >= 1e-4 else 0.0
        else:
            bsdf = nt.nodes.new("ShaderNodeBsdfDiffuse")
            bsdf.inputs["Color"].default_value = (*shape_material["diffuse"], 1.0)
            bsdf.inputs["Roughness"].default_value = 0.0  # Lambert
        nt.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    if interior:
        volume_nodes(nt, media[interior], out.inputs["Volume"])
        m.cycles.homogeneous_volume = media[interior]["grid"] is None
    return m


def volume_nodes(nt, medium, socket, density=None):
    """sigma_s and sigma_a of `medium` (times the `density` output socket, if given) into
    `socket`: a Volume Scatter (Henyey-Greenstein of anisotropy g) plus a Volume Absorption.
    Cycles' Volume Scatter has sigma_s = Color x Density, its Volume Absorption
    sigma_a = (1 - Color) x Density (intern/cycles/kernel/svm/closure.h, svm_node_closure_volume):
    so Density = the largest channel, and the colours are sigma_s / Density and
    1 - sigma_a / Density, all within [0, 1]."""
    add = nt.nodes.new("ShaderNodeAddShader")
    for i, (kind, sigma) in enumerate((("ShaderNodeVolumeScatter", medium["sigma_s"]),
                                       ("ShaderNodeVolumeAbsorption", medium["sigma_a"]))):
        node = nt.nodes.new(kind)
        peak = max(sigma)
        if peak > 0:
            colour = [x / peak for x in sigma]
            if kind == "ShaderNodeVolumeAbsorption":
                colour = [1 - c for c in colour]
            node.inputs["Color"].default_value = (*colour, 1.0)
        node.inputs["Density"].default_value = peak
        if kind == "ShaderNodeVolumeScatter":
            node.inputs["Anisotropy"].default_value = medium["g"]
        if density is not None and peak > 0:
            mul = nt.nodes.new("ShaderNodeMath")
            mul.operation = "MULTIPLY"
            nt.links.new(density, mul.inputs[0])
            mul.inputs[1].default_value = peak
            nt.links.new(mul.outputs["Value"], node.inputs["Density"])
        nt.links.new(node.outputs["Volume"], add.inputs[i])
    nt.links.new(add.outputs["Shader"], socket)


def mesh_object(name, verts, faces, material, smooth=False):
    me = bpy.data.meshes.new(name)
    me.from_pydata([tuple(v) for v in verts], [], faces)
    me.update()
    if smooth:
        me.polygons.foreach_set("use_smooth", [True] * len(me.polygons))
    me.materials.append(material)
    obj = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_shapes(s, conv):
    """Glint's shapes, quad lights and media, in Blender's axes (conv @ Glint's point)."""
    objs, materials = [], {}
    for i, (c, e1, e2, radiance) in enumerate(s["quads"]):
        # The quad light: radiance L from the front face (cross(e1, e2)), black and
        # non-reflecting behind (Glint's quadLight, and cornell.py's --light front).
        m = bpy.data.materials.new(f"quadLight{i}")
        m.use_nodes = True
        nt = m.node_tree
        nt.nodes.clear()
        out = nt.nodes.new("ShaderNodeOutputMaterial")
        emission = nt.nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = (*radiance, 1.0)
        emission.inputs["Strength"].default_value = 1.0
        geometry = nt.nodes.new("ShaderNodeNewGeometry")
        mix = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
        nt.links.new(emission.outputs["Emission"], mix.inputs[1])
        nt.links.new(mix.outputs["Shader"], out.inputs["Surface"])
        verts = [conv @ v for v in (c, c + e1, c + e1 + e2, c + e2)]
        objs.append(mesh_object(f"quadLight{i}", verts, [(0, 1, 2, 3)], m))
    for i, shape in enumerate(s["shapes"]):
        kind, material = shape[0], shape[3]
        key = repr(sorted(material.items()))
        if key not in materials:
            materials[key] = shader_material(f"glint{len(materials)}", material, s["media"])
        m = materials[key]
        if kind == "plane":
            # Glint's plane is infinite: a square 2 km wide about the point, facing the normal.
            p, n = shape[1], shape[2].normalized()
            u = n.orthogonal().normalized()
            v = n.cross(u)
            h = 1000.0
            verts = [conv @ (p + a * u * h + b * v * h) for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
            objs.append(mesh_object(f"plane{i}", verts, [(0, 1, 2, 3)], m))
        else:
            # A sphere: an icosphere of 6 subdivisions (20480 faces), smooth-shaded, its
            # vertices on the sphere (the faces' mid-points at most 0.01% of r inside).
            import bmesh
            bm = bmesh.new()
            bmesh.ops.create_icosphere(bm, subdivisions=6, radius=shape[2])
            me = bpy.data.meshes.new(f"sphere{i}")
            bm.to_mesh(me)
            bm.free()
            me.polygons.foreach_set("use_smooth", [True] * len(me.polygons))
            me.materials.append(m)
            obj = bpy.data.objects.new(f"sphere{i}", me)
            obj.location = conv @ shape[1]
            bpy.context.scene.collection.objects.link(obj)
            objs.append(obj)
    return objs


def add_fog(scene, s, conv):
    """`fog NAME`: homogeneous, the world's Volume (the camera and everything outside the
    objects' volumes are in it); with a density grid, a Volume object reading the same .vdb,
    placed by the same axis conversion and moved by half a voxel (below)."""
    medium = s["media"][s["fog"]]
    if medium["grid"] is None:
        nt = scene.world.node_tree
        out = next(n for n in nt.nodes if n.type == "OUTPUT_WORLD")
        volume_nodes(nt, medium, out.inputs["Volume"])
        scene.world.cycles.homogeneous_volume = True
        return None
    vol = bpy.data.volumes.new("fog")
    vol.filepath = medium["grid"]
    vol.render.precision = "FULL"   # not half floats
    vol.render.clipping = 0.0       # no voxel is taken for empty
    vol.render.space = "OBJECT"
    vol.render.step_size = 0.0      # automatic: the voxel size, times the scene's step rate
    m = bpy.data.materials.new("fog")
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    attr = nt.nodes.new("ShaderNodeAttribute")
    attr.attribute_type = "GEOMETRY"
    attr.attribute_name = "density"
    volume_nodes(nt, medium, out.inputs["Volume"], density=attr.outputs["Fac"])
    m.cycles.volume_interpolation = "LINEAR"
    vol.materials.append(m)
    obj = bpy.data.objects.new("fog", vol)
    scene.collection.objects.link(obj)
    vol.grids.load()
    names = [g.name for g in vol.grids]
    if "density" not in names:
        fail(f"{medium['grid']}: no grid named 'density' ({names})")
    # OpenVDB puts voxel (i, j, k)'s value at the grid's image of the integer point (i, j, k),
    # and so does Glint (io/vdb/vdb_reader.cpp). Blender 3.4's Cycles, built without NanoVDB
    # as Debian's is, copies the grid into a dense 3D texture whose texel centres
    # ((n + 0.5) / dim) it maps to index min + n + 0.5 (intern/cycles/scene/image_vdb.cpp,
    # texture_to_index = translate(min) x scale(dim)): every value half a voxel up each index
    # axis (later Cycles shift it back: "Shift by half a voxel to sample at voxel centers").
    # Measured here: the smoke plume's centroid 0.7 pixel right and 0.5 up in Cycles, half a
    # voxel at that distance. --vdb-shift 0 keeps Blender's placement.
    grid = next(g for g in vol.grids if g.name == "density")
    half = grid.matrix_object.to_3x3() @ Vector((0.5, 0.5, 0.5))
    obj.matrix_world = conv.to_4x4() @ Matrix.Translation(-VDB_SHIFT * half)
    return obj


def empty_world(scene):
    """The scene's world (made if it has none) with an empty node tree: (world, tree)."""
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes.clear()
    return world, world.node_tree


def set_background(scene, colour):
    """Glint's `background r g b` in the path tracer: a constant environment light, seen by
    camera rays too; black without one."""
    world, nt = empty_world(scene)
    bg = nt.nodes.new("ShaderNodeBackground")
    bg.inputs["Color"].default_value = (*(colour or (0.0, 0.0, 0.0)), 1.0)
    bg.inputs["Strength"].default_value = 1.0
    out = nt.nodes.new("ShaderNodeOutputWorld")
    nt.links.new(bg.outputs["Background"], out.inputs["Surface"])
    world.cycles.sampling_method = "AUTOMATIC"



def set_world(scene, hdr, scale, rotation):
    world, nt = empty_world(scene)
    tex = nt.nodes.new("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(hdr)
    tex.image.colorspace_settings.name = "Linear"
    tex.interpolation = "Linear"
    tex.projection = "EQUIRECTANGULAR"
    if rotation:
        coord = nt.nodes.new("ShaderNodeTexCoord")
        mapping = nt.nodes.new("ShaderNodeMapping")
        mapping.vector_type = "POINT"
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(-rotation))
        nt.links.new(coord.outputs["Generated"], mapping.inputs["Vector"])
        nt.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    bg = nt.nodes.new("ShaderNodeBackground")
    bg.inputs["Strength"].default_value = scale
    out = nt.nodes.new("ShaderNodeOutputWorld")
    nt.links.new(tex.outputs["Color"], bg.inputs["Color"])
    nt.links.new(bg.outputs["Background"], out.inputs["Surface"])
    world.cycles.sampling_method = "AUTOMATIC"  # importance-sampled, as Glint's map


def add_camera(scene, conv, camera, width, height):
    eye, look_at, up, fovy = camera
    eye, look_at, up = (conv @ v for v in (eye, look_at, up))
    cam = bpy.data.cameras.new("Camera")
    cam.type = "PERSP"
    cam.sensor_fit = "VERTICAL"
    cam.angle_y = math.radians(fovy)
    cam.clip_start, cam.clip_end = 1e-3, 1e4
    obj = bpy.data.objects.new("Camera", cam)
    scene.collection.objects.link(obj)
    forward = (look_at - eye).normalized()
    right = forward.cross(up).normalized()
    true_up = right.cross(forward)
    obj.matrix_world = Matrix.Translation(eye) @ Matrix((right, true_up, -forward)).transposed().to_4x4()
    scene.camera = obj
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0


def configure_cycles(scene, a, bounces):
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = a.spp
    c.seed = a.seed
    c.use_animated_seed = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.use_preview_denoising = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    for kind in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces",
                 "volume_bounces", "transparent_max_bounces"):
        setattr(c, kind, bounces)
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.film_exposure = 1.0
    scene.render.film_transparent = False
    scene.render.threads_mode = "FIXED"
    scene.render.threads = a.threads
    for layer in scene.view_layers:
        layer.cycles.denoising_store_passes = False
        layer.samples = 0
    scene.display_settings.display_device = "sRGB"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.view_settings.use_curve_mapping = False
    s = scene.render.image_settings
    s.file_format = "OPEN_EXR"
    s.color_mode = "RGB"
    s.color_depth = "32"
    s.exr_codec = "ZIP"
    scene.render.use_compositing = False
    scene.render.use_sequencer = False


def main():
    a = parse_args()
    out = os.path.abspath(a.out)
    if not out.lower().endswith(".exr"):
        fail("--out must name an .exr file")
    s = read_scene(a.scene)
    global VDB_SHIFT
    VDB_SHIFT = a.vdb_shift
    conv = axis_conversion(from_forward="-Z", from_up="Y", to_forward="Y", to_up="Z")
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    scene = bpy.context.scene
    objs = []
    for path in s["meshes"]:
        objs += import_gltf(path, conv)
    materials = sorted({slot.material for o in objs for slot in o.material_slots
                        if slot.material}, key=lambda m: m.name)
    sheen = {}
    if a.sheen_v1:
        for path in s["meshes"]:
            with open(path, encoding="utf-8") as f:
                for gm in json.load(f).get("materials", ()):
                    ext = gm.get("extensions", {}).get("KHR_materials_sheen")
                    if ext is not None:
                        sheen[gm.get("name", "")] = max(ext.get("sheenColorFactor", (0, 0, 0)))
    for m in materials:
        for n in list(m.node_tree.nodes):
            if n.type == "BSDF_PRINCIPLED" and m.name.split(".")[0] in sheen:
                n.inputs["Sheen"].default_value = sheen[m.name.split(".")[0]]
                n.inputs["Sheen Tint"].default_value = 1.0
                print(f"gltf_cycles.py: --sheen-v1: {m.name}: Sheen "
                      f"{sheen[m.name.split('.')[0]]:g}, Sheen Tint 1", flush=True)
            if n.type == "BSDF_PRINCIPLED" and not a.multiscatter:
                n.distribution = "GGX"
            if a.lambert and n.type == "BSDF_PRINCIPLED" and plain_dielectric(n):
                lambert(m.node_tree, n)
    objs += add_shapes(s, conv)
    if s["environment"]:
        set_world(scene, *s["environment"])
    else:
        set_background(scene, s["background"])
    fog = add_fog(scene, s, conv) if s["fog"] else None
    add_camera(scene, conv, s["camera"], *s["size"])
    bounces = s["maxdepth"] - 1
    configure_cycles(scene, a, bounces)
    scene.cycles.volume_step_rate = a.volume_step_rate
    scene.cycles.volume_max_steps = 4096
    triangles = sum(len(o.data.polygons) for o in objs)
    for name, m in s["media"].items():
        print(f"gltf_cycles.py: medium {name}: sigma_a {tuple(round(x, 5) for x in m['sigma_a'])}"
              f", sigma_s {tuple(round(x, 5) for x in m['sigma_s'])}, g {m['g']}"
              f"{', density ' + m['grid'] if m['grid'] else ''}"
              f"{' (the fog)' if name == s['fog'] else ''}", flush=True)
    if fog is not None:
        grid = next(g for g in fog.data.grids if g.name == "density")
        print(f"gltf_cycles.py: fog grid 'density' {grid.data_type}, "
              f"matrix_object {[list(map(lambda x: round(x, 6), r)) for r in grid.matrix_object]}",
              flush=True)
    print(f"gltf_cycles.py: Blender {bpy.app.version_string}, Cycles CPU, {len(objs)} objects, "
          f"{triangles} faces, materials:", flush=True)
    for m in materials:
        print(describe_material(m), flush=True)

    t0, c0 = time.perf_counter(), time.process_time()
    bpy.ops.render.render(write_still=False)
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0

    tmp = out + ".tmp.exr"
    bpy.data.images["Render Result"].save_render(filepath=tmp, scene=scene)
    os.replace(tmp, out)
    w, h = s["size"]
    print(f"CYCLES_RESULT scene={os.path.basename(a.scene)} width={w} height={h} spp={a.spp} "
          f"threads={a.threads} seed={a.seed} bounces={bounces} render_s={seconds:.3f} "
          f"cpu_s={cpu:.3f}", flush=True)


if __name__ == "__main__":
    try:
        main()
    except SystemExit as e:
        os._exit(e.code if isinstance(e.code, int) else 1)
    except Exception:  # noqa: BLE001 - report and exit non-zero instead of Blender's 0
        import traceback
        traceback.print_exc()
        os._exit(1)
    sys.stdout.flush()
    os._exit(0)
