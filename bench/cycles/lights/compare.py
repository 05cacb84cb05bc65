#!/usr/bin/env python3
"""compare.py REF.pfm IMAGE.pfm...: for each image against the reference (linear PFMs of one
size): the ratio of the image means, relMSE (squared error over the reference's squared value
plus 0.01, averaged), and the colour noise: over the pixels the reference shows brighter than
2% of its mean, the mean of (largest - smallest channel) / mean channel. Three coincident red,
green and blue lights should light a white surface white: the colour noise is the rainbow the
choice among them leaves. NumPy (/usr/bin/python3)."""
import sys

import numpy as np


def read(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3 if kind == b"PF" else 1)[::-1].astype(np.float64)


ref = read(sys.argv[1])
lum = ref.mean(axis=2)
lit = lum > 0.02 * lum.mean()
for path in sys.argv[2:]:
    a = read(path)
    rel = ((a - ref) ** 2 / (ref ** 2 + 1e-2)).mean()
    m = a.mean(axis=2)
    chroma = ((a.max(axis=2) - a.min(axis=2)) / np.maximum(m, 1e-6))[lit].mean()
    print(f"{path}: mean ratio {a.mean() / ref.mean():.4f}, relMSE {rel:.5f}, "
          f"colour noise {chroma:.4f}")
