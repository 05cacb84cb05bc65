#!/usr/bin/python3
"""docs/python.md's walkthrough as one script; it writes the pictures the page shows.

    PYTHONPATH=build/python python3 python/examples/walkthrough.py [OUT_DIR]

OUT_DIR (default: the current folder) gets:
- strip.png: the course's scene6 from three places;
- turntable.png: Blender's Suzanne (tests/data/gltf) from four sides of twelve;
- terrain.png: a scene made in code, with a mesh of arrays placed twice;
- box.exr: the path-traced Cornell box with albedo, normal and depth layers.
"""

import os
import sys
import time

import numpy as np

import glint

# Every file it reads is in the repository: it runs in a clone.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OUT = sys.argv[1] if len(sys.argv) > 1 else "."

# Load a course scene and look at it.
scene = glint.load(os.path.join(ROOT, "tests/data/cse167x/scene6.test"), size=(320, 240))
print(scene.info["triangles"], scene.info["lights"], scene.camera)
image = scene.render()
print(image.shape, image.dtype, f"{image.info['seconds']:.3f} s")

# Move the camera in a loop: the scene is neither loaded nor built again.
frames = []
for x in np.linspace(-0.4, 0.4, 9):
    scene.camera = dict(eye=(x, 0.1, 1.0))
    frames.append(scene.render())
glint.write(os.path.join(OUT, "strip.png"), np.concatenate(frames[::4], axis=1))

# A turntable of a glTF model, framed and denoised as the glint command does it.
start = time.perf_counter()
monkey = glint.load(os.path.join(ROOT, "tests/data/gltf/blender-monkey.gltf"), size=(240, 240))
print(f"loaded the model in {time.perf_counter() - start:.2f} s")
c = monkey.camera
target = np.array(c["target"])
offset = np.array(c["eye"]) - target
turntable = []
for degrees in range(0, 360, 30):
    a = np.radians(degrees)
    turn = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    monkey.camera = dict(eye=tuple(target + turn @ offset))
    turntable.append(monkey.render(spp=16))
print("seconds per frame:", [round(img.info["seconds"], 2) for img in turntable])
# Four of the twelve side by side, shown as the model is (its display: PBR Neutral, sRGB).
glint.write(os.path.join(OUT, "turntable.png"), np.concatenate(turntable[::3], axis=1),
            **turntable[0].display)

# A scene made in code, with a height field of arrays placed twice (stored once).
scene = glint.Scene(size=(320, 240))
scene.camera = dict(eye=(0, 1.5, 5), target=(0, 0.4, 0), fov=40)
scene.point_light((3, 5, 4), (0.9, 0.9, 0.8))
scene.material(diffuse=(0.8, 0.8, 0.8))
scene.plane((0, 0, 0), (0, 1, 0))
n = 64
u, v = np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n))
positions = np.stack([u, 0.3 + 0.2 * np.sin(4 * u) * np.cos(4 * v), v], -1).reshape(-1, 3)
i = np.arange(n * n).reshape(n, n)[:-1, :-1].ravel()
indices = np.concatenate([np.stack([i, i + n, i + 1], -1),
                          np.stack([i + 1, i + n, i + n + 1], -1)])
terrain = glint.Mesh(positions.astype(np.float32), indices)
scene.material(diffuse=(0.3, 0.6, 0.3), specular=(0.1, 0.1, 0.1), shininess=20)
for x in (-1.1, 1.1):
    with scene.transform():
        scene.translate((x, 0, 0))
        scene.mesh(terrain)
scene.material(diffuse=(0.1, 0.1, 0.1), specular=(0.9, 0.9, 0.9))
scene.sphere((0, 0.9, 0.6), 0.3)
glint.write(os.path.join(OUT, "terrain.png"), scene.render(spp=4))
print(scene.text)

# Passes and progress.
box = glint.load(os.path.join(ROOT, "scenes/cornell.test"), integrator="path", size=(256, 256))
image = box.render(spp=64, aov=["albedo", "normal", "depth"],
                   progress=lambda fraction, seconds: print(f"{fraction:4.0%}", end="\r"))
print(image.passes["albedo"].shape, image.passes["depth"].shape)
glint.write(os.path.join(OUT, "box.exr"), image)
