"""Checks, in Cycles itself, the conventions bench/cycles/cornell.py relies on.

    blender -b --factory-startup --python bench/cycles/check_units.py [-- --threads 2]

The camera sits inside a closed box (a cube) whose every face emits radiance E and reflects
diffusely with albedo rho. Whatever the enclosure's shape, the radiance is then the same
everywhere and in every direction, L = E + rho L, so the camera sees L = E / (1 - rho) in every
pixel; with at most B bounces the sum stops after B + 1 reflections, if Cycles' "bounces" count
reflections after the first hit (pbrt's maxdepth B + 1). Rendered, with means over all pixels:

  1. rho 0:               E                 an Emission shader of colour c, strength 1 emits
                                            radiance c (as seen by camera rays);
  2. rho 0.5, 64 bounces: E / (1 - rho)     the same radiance reaches a Lambert surface through
                                            Cycles' light sampling and its BSDF rays (MIS);
  3. rho 0.5, 0 bounces:  E (1 + rho)       "0 bounces" is direct lighting only (pbrt's
     rho 0.5, 1 bounce:   E (1 + rho + rho^2) maxdepth 1), and each bounce adds one reflection;
  4. one-sided emission (Backfacing mix, as cornell.py's --light front) with the faces'
     normals pointing in: E / (1 - rho); pointing out: 0 (the back emits nothing, also to
     light sampling).

Prints one line per case and "ALL PASSED" or exits 1.
"""

import argparse
import os
import sys

import bmesh
import bpy


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="check_units.py")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--size", type=int, default=32)
    return p.parse_args(argv)


def material(e, rho, one_sided):
    m = bpy.data.materials.new("box")
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    emission = nt.nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (e, e, e, 1)
    emission.inputs["Strength"].default_value = 1.0
    shader = emission.outputs["Emission"]
    if one_sided:
        geometry = nt.nodes.new("ShaderNodeNewGeometry")
        mix = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
        nt.links.new(shader, mix.inputs[1])
        shader = mix.outputs["Shader"]
    if rho > 0:
        diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = (rho, rho, rho, 1)
        diffuse.inputs["Roughness"].default_value = 0.0
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(shader, add.inputs[0])
        nt.links.new(diffuse.outputs["BSDF"], add.inputs[1])
        shader = add.outputs["Shader"]
    nt.links.new(shader, out.inputs["Surface"])
    return m


def render_mean(a, e, rho, bounces, one_sided=False, normals_in=True):
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for m in list(bpy.data.materials):
        bpy.data.materials.remove(m)
    mesh = bpy.data.meshes.new("box")
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=2.0)  # normals point out
    if normals_in:
        bmesh.ops.reverse_faces(bm, faces=bm.faces)
    bm.to_mesh(mesh)
    bm.free()
    box = bpy.data.objects.new("box", mesh)
    box.data.materials.append(material(e, rho, one_sided))
    scene = bpy.context.scene
    scene.collection.objects.link(box)
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    cam.location = (0.1, -0.2, 0.05)
    cam.rotation_euler = (1.3, 0.2, 0.4)
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = a.spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    for kind in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces"):
        setattr(c, kind, bounces)
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    scene.render.resolution_x = scene.render.resolution_y = a.size
    scene.render.resolution_percentage = 100
    scene.render.threads_mode = "FIXED"
    scene.render.threads = a.threads
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    world = scene.world
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0, 0, 0, 1)
    bg.inputs["Strength"].default_value = 0.0
    s = scene.render.image_settings
    s.file_format, s.color_mode, s.color_depth = "OPEN_EXR", "RGB", "32"
    bpy.ops.render.render()
    # Read the float result back through an EXR file (the Render Result has no pixels in
    # background mode).
    path = os.path.join(bpy.app.tempdir, "check_units.exr")
    bpy.data.images["Render Result"].save_render(filepath=path, scene=scene)
    img = bpy.data.images.load(path)
    px = img.pixels[:]
    n = len(px) // 4
    mean = sum(px[i * 4 + 1] for i in range(n)) / n  # green; the box is grey
    bpy.data.images.remove(img)
    return mean


def main():
    a = parse_args()
    e = 0.8
    cases = [
        ("emission seen by the camera: rho 0", e, dict(rho=0.0, bounces=64)),
        ("closed box, rho 0.5, 64 bounces", e / 0.5, dict(rho=0.5, bounces=64)),
        ("closed box, rho 0.5, 0 bounces", e * 1.5, dict(rho=0.5, bounces=0)),
        ("closed box, rho 0.5, 1 bounce", e * 1.75, dict(rho=0.5, bounces=1)),
        ("one-sided, normals in, rho 0.5", e / 0.5, dict(rho=0.5, bounces=64, one_sided=True)),
        ("one-sided, normals out, rho 0.5", 0.0,
         dict(rho=0.5, bounces=64, one_sided=True, normals_in=False)),
    ]
    ok = True
    for name, want, kw in cases:
        got = render_mean(a, e, **kw)
        # 1% of the expected value: far below a factor of pi or a missing bounce.
        good = abs(got - want) <= 0.01 * max(want, 1e-3)
        ok &= good
        print(f"CHECK {'ok  ' if good else 'FAIL'} {name}: mean {got:.5f}, expected {want:.5f}",
              flush=True)
    print("ALL PASSED" if ok else "SOME FAILED", flush=True)
    os._exit(0 if ok else 1)


if __name__ == "__main__":
    try:
        main()
    except Exception:  # noqa: BLE001
        import traceback
        traceback.print_exc()
        os._exit(1)
