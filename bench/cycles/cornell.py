"""Renders the Cornell box OBJ in Blender Cycles (CPU), set up to compare with Glint's path tracer.

Run headless (Blender 3.4, Debian's `blender` package):

    blender -b --factory-startup --python bench/cycles/cornell.py -- \
        --obj ../shared/scenes/cornell/cornell.obj --out cycles.exr \
        --width 256 --height 256 --spp 256 --threads 2 --seed 0

What it sets up (see bench/cycles/README.md for why):
  - the OBJ through Blender's own importer (bpy.ops.wm.obj_import) with the axis options that
    turn its +y-up coordinates into Blender's +z-up ones (forward -Z, up Y: OBJ (x, y, z) is
    Blender (x, -z, y)); the camera is converted with the same matrix. The script checks that
    every imported vertex is where that conversion puts the file's vertex;
  - quads split into triangles exactly as Glint's OBJ loader splits them (the shorter diagonal:
    the box's left wall is not planar, so the choice moves it by up to a centimetre);
  - every material replaced: a pure Diffuse BSDF (Lambert, roughness 0) of the MTL's Kd, and
    for a material with a non-zero Ke an Emission shader of colour Ke and strength 1 (radiance
    Ke) that emits from the front face only (the side the face's winding points to: down, for
    the Cornell box's light), black and non-reflecting behind (--light front, the default;
    like Glint's quadLight). --light both emits from both faces (Cycles' own default);
    --light mtl adds the Lambert Kd to the two-sided emission (the MTL read literally);
  - camera eye (0, 1, 3.9), look-at (0, 1, 0), up +y in OBJ space, 38 degrees vertical field of
    view (--eye, --look-at, --up, --fovy);
  - Cycles on the CPU: --threads fixed threads, --spp samples, --seed, --bounces (default 64)
    for the total and for every kind, no denoiser, no adaptive sampling, no clamping, caustics
    on, a box pixel filter 1 pixel wide (the pixel's area), default light sampling settings;
  - film opaque, world black, view transform Standard (exposure 0, gamma 1, no look), output a
    32-bit float RGB OpenEXR (ZIP, lossless): linear scene radiance.

It prints one line that scripts parse, with the time of bpy.ops.render.render alone (scene
synchronisation, BVH build and path tracing; not Blender's start-up, the import or the write):
wall-clock seconds, paths (samples) per second from them, and the CPU seconds of the process
over the same span (all threads; on a busy machine, CPU seconds / threads is what the render
would have taken alone):

    CYCLES_RESULT width=256 height=256 spp=256 threads=2 seed=0 bounces=64 light=front \
        render_s=SECONDS paths=16777216 paths_per_s=PATHS/SECONDS cpu_s=CPU_SECONDS
"""

import argparse
import math
import os
import sys
import time

import bmesh
import bpy
from bpy_extras.io_utils import axis_conversion
from mathutils import Matrix, Vector


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cornell.py", description=__doc__.split("\n")[0])
    p.add_argument("--obj", required=True, help="the Cornell box OBJ (its mtllib beside it)")
    p.add_argument("--out", required=True, help="the 32-bit float EXR to write")
    p.add_argument("--width", type=int, default=256)
    p.add_argument("--height", type=int, default=256)
    p.add_argument("--spp", type=int, default=256, help="samples per pixel")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--bounces", type=int, default=64,
                   help="Cycles' max bounces, total and each kind (0: direct light only)")
    p.add_argument("--light", choices=("front", "both", "mtl"), default="front",
                   help="emitters: front face only (default), both faces, or both faces "
                        "plus the MTL's Kd as a Lambert reflection")
    p.add_argument("--eye", type=float, nargs=3, default=(0.0, 1.0, 3.9))
    p.add_argument("--look-at", type=float, nargs=3, default=(0.0, 1.0, 0.0))
    p.add_argument("--up", type=float, nargs=3, default=(0.0, 1.0, 0.0))
    p.add_argument("--fovy", type=float, default=38.0, help="vertical field of view, degrees")
    a = p.parse_args(argv)
    for name in ("width", "height", "spp", "threads"):
        if getattr(a, name) < 1:
            p.error(f"--{name} must be at least 1")
    if a.bounces < 0:
        p.error("--bounces must not be negative")
    return a


def fail(message):
    print(f"cornell.py: error: {message}", file=sys.stderr)
    sys.exit(1)


def read_obj(path):
    """The file's positions (OBJ space), faces (0-based position indices), mtllib names."""
    positions, faces, libs = [], [], []
    with open(path, encoding="utf-8") as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                positions.append(Vector(tuple(float(x) for x in t[1:4])))
            elif t[0] == "f":
                idx = []
                for c in t[1:]:
                    i = int(c.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(positions) + i)
                faces.append(idx)
            elif t[0] == "mtllib":
                libs.append(" ".join(t[1:]))
    return positions, faces, libs


def read_mtl(path):
    """{name: {"Kd": (r, g, b), "Ke": (r, g, b)}} with MTL's defaults (black) where absent."""
    materials, current = {}, None
    with open(path, encoding="utf-8") as f:
        for line in f:
            t = line.split("#")[0].split()
            if not t:
                continue
            if t[0] == "newmtl":
                current = materials.setdefault(" ".join(t[1:]), {"Kd": (0, 0, 0), "Ke": (0, 0, 0)})
            elif t[0] in ("Kd", "Ke") and current is not None:
                current[t[0]] = tuple(float(x) for x in t[1:4])
    return materials


def glint_split(q):
    """The diagonal Glint's OBJ loader splits quad q (4 points) along: (0, 2) or (1, 3).

    The same rule as src/glint/io/obj/obj_loader.cpp: the diagonal whose two triangles face the
    same way, the shorter one when both do (0-2 on a tie)."""
    n0, n1 = (q[1] - q[0]).cross(q[2] - q[0]), (q[2] - q[0]).cross(q[3] - q[0])
    m0, m1 = (q[1] - q[0]).cross(q[3] - q[0]), (q[2] - q[1]).cross(q[3] - q[1])
    along02, along13 = n0.dot(n1) > 0, m0.dot(m1) > 0
    if along02 and along13:
        along02 = (q[2] - q[0]).length_squared <= (q[3] - q[1]).length_squared
    return (0, 2) if along02 or not along13 else (1, 3)


def clear_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for block in (bpy.data.meshes, bpy.data.materials, bpy.data.cameras, bpy.data.lights):
        for item in list(block):
            block.remove(item)


def import_obj(path, conv):
    """Imports the OBJ, checks its vertices against the file, splits quads as Glint does."""
    bpy.ops.wm.obj_import(filepath=path, forward_axis="NEGATIVE_Z", up_axis="Y")
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    if not meshes:
        fail(f"the importer read no mesh from {path}")
    positions, faces, _ = read_obj(path)
    # Sorted by coordinates rounded well below the file's 2 decimals, so that round-off in the
    # conversion (cos 90 degrees is not exactly 0 in float) cannot reorder equal points.
    def key(p):
        return tuple(round(c, 4) for c in p)

    expected = sorted((tuple(conv @ positions[i]) for f in faces for i in f), key=key)
    got = []
    for o in meshes:
        if o.matrix_world != Matrix.Identity(4):
            # The importer puts the axis conversion into the vertices; make that so, whatever.
            o.data.transform(o.matrix_world)
            o.matrix_world = Matrix.Identity(4)
        for poly in o.data.polygons:
            got.extend(tuple(o.data.vertices[v].co) for v in poly.vertices)
    got.sort(key=key)
    if len(got) != len(expected) or any((Vector(g) - Vector(e)).length > 1e-5
                                        for g, e in zip(got, expected)):
        fail("the imported vertices are not the file's vertices under the axis conversion")
    triangles = 0
    for o in meshes:
        bm = bmesh.new()
        bm.from_mesh(o.data)
        for face in list(bm.faces):
            vs = list(face.verts)
            if len(vs) == 4:
                a, b = glint_split([v.co for v in vs])
                bmesh.utils.face_split(face, vs[a], vs[b])
            elif len(vs) > 4:
                fail("faces of more than 4 vertices are not split here as Glint splits them")
        for face in bm.faces:
            face.smooth = False  # the file has no normals: flat shading, as in Glint
        bm.to_mesh(o.data)
        bm.free()
        triangles += len(o.data.polygons)
    return meshes, triangles


def node_material(name, kd, ke, light):
    """A pure Lambert material of colour kd; with ke non-zero, an emitter of radiance ke."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*kd, 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0  # Lambert (non-zero is Oren-Nayar)
    if not any(ke):
        nt.links.new(diffuse.outputs["BSDF"], out.inputs["Surface"])
        return m
    emission = nt.nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*ke, 1.0)
    emission.inputs["Strength"].default_value = 1.0
    if light == "front":
        # Emission in front, nothing (black, no reflection) behind: Cycles' Emission shader
        # emits from both faces, and Blender 3.4 has no per-material setting for one side.
        geometry = nt.nodes.new("ShaderNodeNewGeometry")
        mix = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
        nt.links.new(emission.outputs["Emission"], mix.inputs[1])  # Fac 0: the front
        # mix.inputs[2] stays unlinked: no closure behind, so black and non-reflecting.
        nt.links.new(mix.outputs["Shader"], out.inputs["Surface"])
    elif light == "both":
        nt.links.new(emission.outputs["Emission"], out.inputs["Surface"])
    else:
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(emission.outputs["Emission"], add.inputs[0])
        nt.links.new(diffuse.outputs["BSDF"], add.inputs[1])
        nt.links.new(add.outputs["Shader"], out.inputs["Surface"])
    return m


def replace_materials(meshes, obj_path, light):
    _, _, libs = read_obj(obj_path)
    mtl = {}
    for lib in libs:
        mtl.update(read_mtl(os.path.join(os.path.dirname(obj_path), lib)))
    made, emitters = {}, []
    for o in meshes:
        for slot in o.material_slots:
            name = slot.material.name if slot.material else None
            if name not in mtl:
                fail(f"{o.name}: material {name!r} is not in the OBJ's material library")
            if name not in made:
                made[name] = node_material("cycles_" + name, mtl[name]["Kd"], mtl[name]["Ke"],
                                           light)
                if any(mtl[name]["Ke"]):
                    emitters.append(name)
            slot.material = made[name]
    if not emitters:
        fail("no material has a non-zero Ke: the box would be dark")
    return mtl, emitters


def add_camera(scene, conv, eye, look_at, up, fovy, width, height):
    eye, look_at, up = (conv @ Vector(v) for v in (eye, look_at, up))
    cam = bpy.data.cameras.new("Camera")
    cam.type = "PERSP"
    cam.sensor_fit = "VERTICAL"
    cam.angle_y = math.radians(fovy)
    cam.shift_x = cam.shift_y = 0.0
    cam.clip_start, cam.clip_end = 1e-3, 1e3
    obj = bpy.data.objects.new("Camera", cam)
    scene.collection.objects.link(obj)
    # Blender's camera looks down its local -Z with +Y up.
    forward = (look_at - eye).normalized()
    right = forward.cross(up).normalized()
    true_up = right.cross(forward)
    rot = Matrix((right, true_up, -forward)).transposed()
    obj.matrix_world = Matrix.Translation(eye) @ rot.to_4x4()
    scene.camera = obj
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
    scene.render.use_border = False


def configure_cycles(scene, a):
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
    for kind in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces",
                 "volume_bounces", "transparent_max_bounces"):
        setattr(c, kind, a.bounces)
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.film_exposure = 1.0
    scene.render.film_transparent = False
    scene.render.threads_mode = "FIXED"
    scene.render.threads = a.threads
    scene.render.use_persistent_data = False
    for layer in scene.view_layers:
        layer.cycles.denoising_store_passes = False
        layer.samples = 0  # 0: the scene's sample count
    # A black world: no light from the background, and black where rays leave the box.
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes.clear()
    bg = world.node_tree.nodes.new("ShaderNodeBackground")
    bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bg.inputs["Strength"].default_value = 0.0
    wout = world.node_tree.nodes.new("ShaderNodeOutputWorld")
    world.node_tree.links.new(bg.outputs["Background"], wout.inputs["Surface"])
    # Linear radiance out: Standard view, no look, exposure 0, gamma 1 (float EXR is written
    # linear anyway; this keeps previews and any 8-bit save honest too).
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
    s.use_preview = False
    scene.render.use_compositing = False
    scene.render.use_sequencer = False


def main():
    a = parse_args()
    obj_path = os.path.abspath(a.obj)
    if not os.path.isfile(obj_path):
        fail(f"cannot read {a.obj}")
    out = os.path.abspath(a.out)
    if not out.lower().endswith(".exr"):
        fail("--out must name an .exr file")
    # OBJ space (+y up, -z forward) to Blender space (+z up, +y forward).
    conv = axis_conversion(from_forward="-Z", from_up="Y", to_forward="Y", to_up="Z")
    clear_scene()
    scene = bpy.context.scene
    meshes, triangles = import_obj(obj_path, conv)
    mtl, emitters = replace_materials(meshes, obj_path, a.light)
    add_camera(scene, conv, a.eye, a.look_at, a.up, a.fovy, a.width, a.height)
    configure_cycles(scene, a)
    print(f"cornell.py: Blender {bpy.app.version_string}, Cycles CPU, {triangles} triangles, "
          f"{len(mtl)} materials, emitters {emitters} ({a.light}), "
          f"sampling pattern {scene.cycles.sampling_pattern}, "
          f"light sampling threshold {scene.cycles.light_sampling_threshold:g}", flush=True)

    t0, c0 = time.perf_counter(), time.process_time()
    bpy.ops.render.render(write_still=False)
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0

    result = bpy.data.images["Render Result"]
    tmp = out + ".tmp.exr"
    result.save_render(filepath=tmp, scene=scene)
    os.replace(tmp, out)
    paths = a.width * a.height * a.spp
    print(f"CYCLES_RESULT width={a.width} height={a.height} spp={a.spp} threads={a.threads} "
          f"seed={a.seed} bounces={a.bounces} light={a.light} render_s={seconds:.3f} "
          f"paths={paths} paths_per_s={paths / seconds:.0f} cpu_s={cpu:.3f}", flush=True)


if __name__ == "__main__":
    try:
        main()
    except SystemExit as e:
        # Blender keeps running after a Python error unless told otherwise: exit with its code.
        os._exit(e.code if isinstance(e.code, int) else 1)
    except Exception as e:  # noqa: BLE001 - report and exit non-zero instead of Blender's 0
        import traceback
        traceback.print_exc()
        os._exit(1)
    sys.stdout.flush()
    os._exit(0)
