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
from mathutils import Matrix, Vector


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
    a = p.parse_args(argv)
    if a.spp < 1 or a.threads < 1:
        p.error("--spp and --threads must be at least 1")
    return a


def read_scene(path):
    """The Glint scene's settings; the commands this script does not reproduce are errors."""
    s = {"size": (640, 480), "camera": None, "maxdepth": 5, "environment": None, "meshes": []}
    base = os.path.dirname(os.path.abspath(path))
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            t = shlex.split(line.split("#")[0])
            if not t:
                continue
            where = f"{path}:{number}"
            cmd, args = t[0], t[1:]
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
            elif cmd == "environment":
                scale = float(args[1]) if len(args) > 1 else 1.0
                rotation = float(args[2]) if len(args) > 2 else 0.0
                s["environment"] = (os.path.join(base, args[0]), scale, rotation)
            elif cmd == "mesh":
                s["meshes"].append(os.path.join(base, args[0]))
            else:
                fail(f"{where}: '{cmd}' is not reproduced in Cycles by this script")
    if s["camera"] is None or not s["meshes"] or s["environment"] is None:
        fail(f"{path}: needs a camera, an environment and at least one mesh")
    if s["maxdepth"] < 1:
        fail(f"{path}: maxdepth must be at least 1")
    return s


def gltf_bounds(path, conv):
    """Blender-space bounds of every node's mesh, from the accessors' min and max (translation-
    only nodes, as make_assets.py writes them)."""
    with open(path, encoding="utf-8") as f:
        j = json.load(f)
    lo, hi = Vector((math.inf,) * 3), Vector((-math.inf,) * 3)
    for node in j["nodes"]:
        if "mesh" not in node:
            continue
        tr = Vector(node.get("translation", (0, 0, 0)))
        for prim in j["meshes"][node["mesh"]]["primitives"]:
            acc = j["accessors"][prim["attributes"]["POSITION"]]
            for corner in ((x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)):
                p = Vector([(acc["min"], acc["max"])[c][i] for i, c in enumerate(corner)]) + tr
                q = conv @ p
                lo = Vector(map(min, lo, q))
                hi = Vector(map(max, hi, q))
    return lo, hi


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
    elo, ehi = gltf_bounds(path, conv)
    if (lo - elo).length > 1e-4 or (hi - ehi).length > 1e-4:
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
                chain.append(label)
                linked = [i for i in node.inputs if i.is_linked]
                if not linked:
                    break
                node = linked[0].links[0].from_node
            lines.append(f"    {inp.name} <- {' <- '.join(chain)}")
        elif inp.name in ("Base Color", "Metallic", "Roughness", "Specular", "Emission",
                          "Emission Strength", "IOR", "Transmission", "Alpha"):
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


def set_world(scene, hdr, scale, rotation):
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    nt.nodes.clear()
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
    conv = axis_conversion(from_forward="-Z", from_up="Y", to_forward="Y", to_up="Z")
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    scene = bpy.context.scene
    objs = []
    for path in s["meshes"]:
        objs += import_gltf(path, conv)
    materials = sorted({slot.material for o in objs for slot in o.material_slots
                        if slot.material}, key=lambda m: m.name)
    for m in materials:
        for n in list(m.node_tree.nodes):
            if n.type == "BSDF_PRINCIPLED" and not a.multiscatter:
                n.distribution = "GGX"
            if a.lambert and n.type == "BSDF_PRINCIPLED" and plain_dielectric(n):
                lambert(m.node_tree, n)
    set_world(scene, *s["environment"])
    add_camera(scene, conv, s["camera"], *s["size"])
    bounces = s["maxdepth"] - 1
    configure_cycles(scene, a, bounces)
    triangles = sum(len(o.data.polygons) for o in objs)
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
