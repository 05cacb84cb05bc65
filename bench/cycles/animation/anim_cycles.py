"""Renders one frame of an animated glTF in Blender Cycles (CPU) with a transparent film, for
issue 24's silhouette comparison (bench/cycles/animation/README.md).

    blender -b --factory-startup --python bench/cycles/animation/anim_cycles.py -- \
        --gltf CesiumMan.gltf --frame 30 --orbit 30,63.43,3.1,-0.05,0.75,-0.02 --fovy 40 \
        --size 480 270 --spp 64 --threads 2 --out cycles.exr

- The scene's frame rate is set to --fps (24) before the import: Blender's glTF importer
  (3.4) keys glTF time t at Blender frame t x fps, so Blender's frame N is glTF time N / fps,
  Glint's `--frame N --fps 24`. The script checks it: every key time of the file's first
  animation (read from its accessors) must be a keyframe of the imported actions at t x fps,
  and it prints how many it checked.
- The camera is Glint's `--camera orbit:THETA,PHI,RADIUS,TX,TY,TZ` with `--fov FOVY`: eye at
  target + RADIUS (sin PHI sin THETA, cos PHI, sin PHI cos THETA) in glTF space (+y up),
  looking at the target, up +y; converted to Blender by the importer's own axis conversion
  (glTF (x, y, z) = Blender (x, -z, y)). Vertical field of view, sensor fit vertical.
- Lights: Glint's key and fill for a model with `--environment none` (scene/model_framing.cpp:
  directional lights towards (-1, 1.6, 1.2) at 0.75 and (1.2, 0.6, 0.8) at 0.3) as sun lamps of
  that strength (irradiance: Glint's path tracer weighs a directional light's colour by the
  BSDF, albedo / pi for a diffuse surface, as Cycles its sun's strength) and angle 0; the world
  black. Only the silhouettes are compared; the lights make the pictures alike.
- Cycles: --spp samples, --seed, no denoiser, no adaptive sampling, no clamping, a box pixel
  filter 1 pixel wide (so alpha is the pixel's covered fraction), max bounces 7 (Glint's
  model default maxdepth 8), transparent film; output a 32-bit float RGBA OpenEXR (ZIP), RGB
  premultiplied by alpha.

It prints one line that scripts parse:

    CYCLES_RESULT gltf=CesiumMan.gltf frame=30 time=1.25 width=480 height=270 spp=64 \
        keys_checked=N render_s=SECONDS
"""

import argparse
import json
import math
import os
import struct
import sys
import time

import bpy
from bpy_extras.io_utils import axis_conversion

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "gltf"))
from gltf_cycles import add_camera  # noqa: E402 - after the path to it
from mathutils import Vector


def fail(message):
    print(f"anim_cycles.py: error: {message}", file=sys.stderr, flush=True)
    os._exit(1)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="anim_cycles.py")
    p.add_argument("--gltf", required=True, help="a .gltf file (JSON with its .bin)")
    p.add_argument("--frame", type=int, required=True)
    p.add_argument("--fps", type=int, default=24)
    p.add_argument("--orbit", required=True, help="THETA,PHI,RADIUS,TX,TY,TZ as Glint's")
    p.add_argument("--fovy", type=float, default=40.0)
    p.add_argument("--size", type=int, nargs=2, default=(480, 270), metavar=("W", "H"))
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--out", required=True, help="an .exr file")
    return p.parse_args(argv)


def key_times(path):
    """Every key time of the file's first animation, from its accessors (floats)."""
    with open(path, encoding="utf-8") as f:
        g = json.load(f)
    base = os.path.dirname(path)
    buffers = {}
    times = set()
    if not g.get("animations"):
        fail(f"{path} has no animations")
    for sampler in g["animations"][0]["samplers"]:
        acc = g["accessors"][sampler["input"]]
        view = g["bufferViews"][acc["bufferView"]]
        if acc["componentType"] != 5126 or acc["type"] != "SCALAR":
            fail(f"{path}: key times that are not floats")
        b = view["buffer"]
        if b not in buffers:
            with open(os.path.join(base, g["buffers"][b]["uri"]), "rb") as f:
                buffers[b] = f.read()
        offset = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        times.update(struct.unpack_from(f"<{acc['count']}f", buffers[b], offset))
    return sorted(times)


def check_frame_mapping(path, fps):
    """Every glTF key time t must be a keyframe at t x fps: returns how many were checked."""
    frames = sorted({k.co[0] for a in bpy.data.actions for fc in a.fcurves
                     for k in fc.keyframe_points})
    if not frames:
        fail("the importer made no keyframes")
    for t in key_times(path):
        want = t * fps
        nearest = min(frames, key=lambda x: abs(x - want))
        if abs(nearest - want) > 1e-3:
            fail(f"glTF key time {t:g} s is not keyed at frame {want:g} (nearest keyframe "
                 f"{nearest:g}): the importer's frame mapping is not t x fps")
    return len(key_times(path))


def orbit_camera(scene, conv, orbit, fovy, width, height):
    """Glint's --camera orbit:THETA,PHI,RADIUS,TX,TY,TZ as a Blender camera (through
    gltf_cycles.py's add_camera); returns its eye and target in glTF's axes."""
    theta, phi, radius, tx, ty, tz = orbit
    th, ph = math.radians(theta), math.radians(phi)
    target = Vector((tx, ty, tz))
    eye = target + radius * Vector((math.sin(ph) * math.sin(th), math.cos(ph),
                                    math.sin(ph) * math.cos(th)))
    add_camera(scene, conv, (eye, target, Vector((0.0, 1.0, 0.0)), fovy), width, height)
    return conv @ eye, conv @ target


def sun(scene, conv, name, towards, value):
    """A sun lamp shining from `towards` (glTF space, the direction to the light)."""
    light = bpy.data.lights.new(name, "SUN")
    light.energy = value
    light.angle = 0.0
    obj = bpy.data.objects.new(name, light)
    scene.collection.objects.link(obj)
    z = (conv @ Vector(towards)).normalized()  # a sun lamp shines along its local -z
    obj.matrix_world = z.to_track_quat("Z", "Y").to_matrix().to_4x4()


def configure(scene, a):
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = a.spp
    c.seed = a.seed
    c.use_animated_seed = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.max_bounces = 7
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    scene.render.film_transparent = True
    scene.render.threads_mode = "FIXED"
    scene.render.threads = a.threads
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    s = scene.render.image_settings
    s.file_format = "OPEN_EXR"
    s.color_mode = "RGBA"
    s.color_depth = "32"
    s.exr_codec = "ZIP"
    scene.render.use_compositing = False
    scene.render.use_sequencer = False


def main():
    a = parse_args()
    out = os.path.abspath(a.out)
    orbit = [float(x) for x in a.orbit.split(",")]
    if len(orbit) != 6:
        fail("--orbit is THETA,PHI,RADIUS,TX,TY,TZ")
    # Debian 12's Blender 3.4 importer uses numpy.bool, which NumPy 1.24 removed.
    import numpy
    if not hasattr(numpy, "bool"):
        numpy.bool = bool
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = a.fps, 1.0
    bpy.ops.import_scene.gltf(filepath=os.path.abspath(a.gltf))
    checked = check_frame_mapping(a.gltf, a.fps)
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    nt.nodes.clear()
    background = nt.nodes.new("ShaderNodeBackground")
    background.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    background.inputs["Strength"].default_value = 0.0
    nt.links.new(background.outputs["Background"],
                 nt.nodes.new("ShaderNodeOutputWorld").inputs["Surface"])
    conv = axis_conversion(from_forward="-Z", from_up="Y", to_forward="Y", to_up="Z").to_4x4()
    eye, target = orbit_camera(scene, conv, orbit, a.fovy, *a.size)
    sun(scene, conv, "key", (-1.0, 1.6, 1.2), 0.75)
    sun(scene, conv, "fill", (1.2, 0.6, 0.8), 0.3)
    configure(scene, a)
    scene.frame_set(a.frame)

    # The posed meshes' bounds in glTF space, for the log.
    inverse = conv.inverted()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    lo, hi = Vector((math.inf,) * 3), Vector((-math.inf,) * 3)
    for obj in scene.objects:
        if obj.type != "MESH":
            continue
        ev = obj.evaluated_get(depsgraph)
        mesh = ev.to_mesh()
        for v in mesh.vertices:
            q = inverse @ (ev.matrix_world @ v.co)
            lo = Vector(map(min, lo, q))
            hi = Vector(map(max, hi, q))
        ev.to_mesh_clear()
    print(f"anim_cycles.py: frame {a.frame} = {a.frame / a.fps:g} s; posed bounds (glTF space) "
          f"{tuple(round(x, 4) for x in lo)} to {tuple(round(x, 4) for x in hi)}; camera eye "
          f"{tuple(round(x, 4) for x in inverse @ eye)}", flush=True)

    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    seconds = time.perf_counter() - t0
    tmp = out + ".tmp.exr"
    bpy.data.images["Render Result"].save_render(filepath=tmp, scene=scene)
    os.replace(tmp, out)
    print(f"CYCLES_RESULT gltf={os.path.basename(a.gltf)} frame={a.frame} "
          f"time={a.frame / a.fps:g} width={a.size[0]} height={a.size[1]} spp={a.spp} "
          f"keys_checked={checked} render_s={seconds:.3f}", flush=True)


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
