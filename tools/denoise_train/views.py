#!/usr/bin/python3
"""The training scenes and their views, for make_data.sh: one line per view,

    ID <TAB> SCENE <TAB> GLINT_ARGUMENTS (space-separated, none with a space in it)

    views.py GLINT SHARED_DIR REPO_DIR GENERATED_DIR [VIEWS [WxH [NAME_FILTER...]]]

Scenes (the held-out benchmark scenes are left out, by name, whatever the folders hold):
  model-*   glTF models of SHARED/real-world/gltf and gltf-ext, meshes of obj/ (spot too) and
            misc/, in Glint's model mode (studio environment), seen from VIEWS orbit cameras
            around the framing Glint chooses (`--camera none --check` prints it): view 0 that
            framing, the others at a random azimuth, elevation and distance, on a shadow or a
            grey floor;
  course-*, cse-*, repo-*  the course-format scenes of SHARED/real-world/course-scenes,
            SHARED/scenes/cse167x and the repository's scenes/ (the Cornell box among them),
            path traced: view 0 the file's camera, the others orbits a little around it (where
            its up is near +y);
  gen-*     the scenes in GENERATED_DIR (gen_scenes.py and glint_bench_scenes), one view each.
Views are random but reproducible: each scene's generator is seeded by its ID's name.
NAME_FILTER keeps the IDs that contain one of the words.
"""

import glob
import math
import os
import random
import re
import subprocess
import sys
import zlib

# The denoising benchmark's scenes (bench/denoise/make_data.sh): never trained on.
HELD_OUT = {"DamagedHelmet", "WaterBottle", "GlassVaseFlowers", "ToyCar", "SheenChair",
            "SheenCloth", "IridescenceLamp"}
HELD_OUT_FILES = {"bench/denoise/glass.test", "bench/denoise/room.test", "bench/denoise/lamps.test"}


def model_file(folder):
    """The one file of a glTF sample folder to load: glTF, else binary, else Draco."""
    for pattern in ("glTF/*.gltf", "glTF-Binary/*.glb", "glTF-Draco/*.gltf", "*.gltf", "*.glb",
                    "*/*.gltf", "*/*.glb"):
        found = sorted(glob.glob(os.path.join(folder, pattern)))
        if found:
            return found[0]
    return None


def scenes(shared, repo, generated):
    """(id, path, kind) of every training scene."""
    out = []
    real = os.path.join(shared, "real-world")
    for group in ("gltf", "gltf-ext"):
        for entry in sorted(glob.glob(os.path.join(real, group, "*"))):
            name = os.path.basename(entry)
            if name in HELD_OUT:
                continue
            path = entry if entry.endswith(".glb") else (
                model_file(entry) if os.path.isdir(entry) else None)
            if path:
                out.append(("model-" + os.path.splitext(name)[0], path, "model"))
    for pattern in ("obj/*.obj", "obj/*.ply", "obj/spot/spot/spot_triangulated.obj", "misc/*.ply"):
        for path in sorted(glob.glob(os.path.join(real, pattern))):
            out.append(("model-" + os.path.splitext(os.path.basename(path))[0], path, "model"))
    for pattern in (os.path.join(real, "course-scenes", "*.test"),
                    os.path.join(shared, "scenes", "cse167x", "*.test"),
                    os.path.join(repo, "scenes", "*.test")):
        for path in sorted(glob.glob(pattern)):
            stem = os.path.splitext(os.path.basename(path))[0]
            prefix = "course-" if "course-scenes" in path else (
                "cse-" if "cse167x" in path else "repo-")
            out.append((prefix + stem, path, "scene"))
    for path in sorted(glob.glob(os.path.join(generated, "*.test"))):
        out.append(("gen-" + os.path.splitext(os.path.basename(path))[0], path, "generated"))
    return [s for s in out if os.path.relpath(s[1], repo) not in HELD_OUT_FILES]


def framing(glint, path, size):
    """Eye and look-at point of the camera Glint frames a model with, or None."""
    run = subprocess.run([glint, path, "--camera", "none", "--check", "--size", size],
                         capture_output=True, text=True)
    number = r"(-?[\d.e+-]+)"
    triple = rf"\({number}, {number}, {number}\)"
    m = re.search(rf"a camera at {triple} looking at {triple}", run.stdout + run.stderr)
    return [float(x) for x in m.groups()] if m else None


def scene_camera(path):
    """(eye, target, up, fovy) of a scene file's last camera line, or None."""
    camera = None
    with open(path, errors="replace") as f:
        for line in f:
            words = line.split()
            if len(words) >= 11 and words[0] == "camera":
                try:
                    camera = [float(w) for w in words[1:11]]
                except ValueError:
                    pass
    return camera


def orbit(eye, target):
    """theta, phi (degrees) and radius of `eye` around `target`, as glint's orbit measures
    them: theta about +y from +z, phi down from +y."""
    d = [e - t for e, t in zip(eye, target)]
    r = math.sqrt(sum(x * x for x in d))
    theta = math.degrees(math.atan2(d[0], d[2]))
    phi = math.degrees(math.acos(max(-1.0, min(1.0, d[1] / r))))
    return theta, phi, r


def orbit_argument(theta, phi, radius, target):
    phi = min(max(phi, 1.0), 179.0)
    numbers = [theta % 360, phi, radius] + list(target)
    return "--camera orbit:" + ",".join(f"{x:.6g}" for x in numbers)


def views(glint, scene_id, path, kind, count, size):
    """[(view id, arguments)] of one scene."""
    rng = random.Random(zlib.crc32(scene_id.encode()))
    out = []
    if kind == "model":
        f = framing(glint, path, size)
        if f is None:
            print(f"views: no framing for {path}; skipped", file=sys.stderr)
            return []
        eye, target = f[:3], f[3:]
        theta0, phi0, r0 = orbit(eye, target)
        for v in range(count):
            if v == 0:
                theta, phi, r = theta0, phi0, r0
            else:
                theta, phi, r = rng.uniform(0, 360), rng.uniform(40, 88), r0 * rng.uniform(0.7, 1.1)
            ground = "floor" if v > 0 and rng.random() < 0.4 else "shadow"
            out.append((f"{scene_id}_v{v}",
                        f"{orbit_argument(theta, phi, r, target)} --fov 40 --ground {ground}"))
        return out
    base = "--integrator path --lenient"
    if kind == "generated":
        return [(f"{scene_id}_v0", base)]
    camera = scene_camera(path)
    out.append((f"{scene_id}_v0", base))
    if camera is None:
        return out
    eye, target, up, fovy = camera[0:3], camera[3:6], camera[6:9], camera[9]
    up_length = math.sqrt(sum(x * x for x in up)) or 1
    if up[1] / up_length < 0.6:  # the orbit keeps +y up: only for scenes that do too
        return out
    theta0, phi0, r0 = orbit(eye, target)
    for v in range(1, count):
        theta = theta0 + rng.uniform(-25, 25)
        phi = phi0 + rng.uniform(-12, 12)
        r = r0 * rng.uniform(0.85, 1.1)
        out.append((f"{scene_id}_v{v}",
                    f"{base} {orbit_argument(theta, phi, r, target)} --fov {fovy:g}"))
    return out


def main(argv):
    glint, shared, repo, generated = argv[:4]
    count = int(argv[4]) if len(argv) > 4 else 3
    size = argv[5] if len(argv) > 5 else "256x192"
    words = argv[6:]
    for scene_id, path, kind in scenes(shared, repo, generated):
        if words and not any(w in scene_id for w in words):
            continue
        for view_id, arguments in views(glint, scene_id, path, kind, count, size):
            print(f"{view_id}\t{path}\t{arguments}")


if __name__ == "__main__":
    main(sys.argv[1:])
