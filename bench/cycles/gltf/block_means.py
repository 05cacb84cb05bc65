"""Mean luminance of the central half of each N x N block of two float images (EXR), and their
ratio: for scenes laid out as a row of patches (bench/cycles/gltf/normaltilt.test). Runs in
Blender's Python, which reads OpenEXR and has NumPy:

    blender -b --factory-startup --python bench/cycles/gltf/block_means.py -- \
        glint.exr cycles.exr 32

prints one line per block, left to right, top to bottom:

    BLOCK 0 x=0 y=0 a=0.4189 b=0.4378 a/b=0.957
"""

import os
import sys

import bpy
import numpy as np


def load(path):
    im = bpy.data.images.load(os.path.abspath(path))
    w, h = im.size
    px = np.array(im.pixels[:], dtype=np.float64).reshape(h, w, 4)[::-1]  # row 0 at the top
    return px[:, :, 0] * 0.2126 + px[:, :, 1] * 0.7152 + px[:, :, 2] * 0.0722


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 3:
        print("usage: block_means.py A.exr B.exr N", file=sys.stderr)
        return 2
    a, b, n = load(argv[0]), load(argv[1]), int(argv[2])
    if a.shape != b.shape or n < 2:
        print("block_means.py: error: the images differ in size, or N < 2", file=sys.stderr)
        return 2
    q = n // 4
    k = 0
    for y in range(0, a.shape[0] - n + 1, n):
        for x in range(0, a.shape[1] - n + 1, n):
            ma = a[y + q:y + n - q, x + q:x + n - q].mean()
            mb = b[y + q:y + n - q, x + q:x + n - q].mean()
            print(f"BLOCK {k} x={x} y={y} a={ma:.4f} b={mb:.4f} a/b={ma / mb:.3f}", flush=True)
            k += 1
    return 0


if __name__ == "__main__":
    code = 1
    try:
        code = main()
    finally:
        sys.stdout.flush()
        os._exit(code)
